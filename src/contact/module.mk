# Layer: contact. Modules and the objects of the modules each one uses.
MODULES += contact contact_results
$(OBJDIR)/contact.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/element_interface.o $(OBJDIR)/element_library.o $(OBJDIR)/kinds.o $(OBJDIR)/mesh_topology.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/contact_results.o: $(OBJDIR)/contact.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o
