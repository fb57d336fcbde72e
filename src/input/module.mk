# Layer: input. Modules and the objects of the modules each one uses.
MODULES += deck_input deck_parser
$(OBJDIR)/deck_input.o: $(OBJDIR)/messages.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_parser.o: $(OBJDIR)/deck_input.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/mesh_topology.o $(OBJDIR)/model.o $(OBJDIR)/solver_codes.o $(OBJDIR)/strings.o
