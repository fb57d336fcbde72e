# Layer: input. Modules and the objects of the modules each one uses.
# file_kind is a C shim (stat), see file_kind.c.
MODULES += file_kind deck_input deck_parser
$(OBJDIR)/file_kind.o:
$(OBJDIR)/deck_input.o: $(OBJDIR)/growable.o $(OBJDIR)/messages.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_parser.o: $(OBJDIR)/deck_input.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/mesh_topology.o $(OBJDIR)/model.o $(OBJDIR)/solver_codes.o $(OBJDIR)/strings.o
