# Layer: model. Modules and the objects of the modules each one uses.
MODULES += element_catalogue mesh_topology model
$(OBJDIR)/element_catalogue.o:
$(OBJDIR)/mesh_topology.o: $(OBJDIR)/element_catalogue.o
$(OBJDIR)/model.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/mesh_topology.o $(OBJDIR)/solver_codes.o
