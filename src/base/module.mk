# Layer: base. Modules and the objects of the modules each one uses.
MODULES += growable kinds messages solver_codes strings
$(OBJDIR)/growable.o: $(OBJDIR)/kinds.o
$(OBJDIR)/kinds.o:
$(OBJDIR)/messages.o:
$(OBJDIR)/solver_codes.o:
$(OBJDIR)/strings.o: $(OBJDIR)/kinds.o
