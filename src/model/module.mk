# Layer: model. Modules and the objects of the modules each one uses.
MODULES += constraints element_catalogue mesh_topology model
$(OBJDIR)/element_catalogue.o:
$(OBJDIR)/mesh_topology.o: $(OBJDIR)/element_catalogue.o
$(OBJDIR)/model.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/mesh_topology.o $(OBJDIR)/solver_codes.o $(OBJDIR)/strings.o
$(OBJDIR)/constraints.o: $(OBJDIR)/growable.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
