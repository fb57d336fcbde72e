# Layer: base. Modules and the objects of the modules each one uses.
# make_dirs is a C shim (mkdir), see make_dirs.c.
MODULES += directories growable kinds make_dirs messages solver_codes strings
$(OBJDIR)/directories.o:
$(OBJDIR)/growable.o: $(OBJDIR)/kinds.o
$(OBJDIR)/kinds.o:
$(OBJDIR)/make_dirs.o:
$(OBJDIR)/messages.o:
$(OBJDIR)/solver_codes.o:
$(OBJDIR)/strings.o: $(OBJDIR)/kinds.o
