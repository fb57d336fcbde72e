# Layer: base. Modules and the objects of the modules each one uses.
MODULES += kinds messages solver_codes strings
$(OBJDIR)/kinds.o:
$(OBJDIR)/messages.o:
$(OBJDIR)/solver_codes.o:
$(OBJDIR)/strings.o: $(OBJDIR)/kinds.o
