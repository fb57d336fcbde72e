# Layer: base. Modules and the objects of the modules each one uses.
# make_dirs is a C shim (mkdir), see make_dirs.c; build_features.c says what the build found (MUMPS).
MODULES += build_features directories growable kinds make_dirs messages small_matrices solver_codes strings
$(OBJDIR)/build_features.o:
$(OBJDIR)/directories.o:
$(OBJDIR)/growable.o: $(OBJDIR)/kinds.o
$(OBJDIR)/kinds.o:
$(OBJDIR)/make_dirs.o:
$(OBJDIR)/messages.o:
$(OBJDIR)/small_matrices.o: $(OBJDIR)/kinds.o
$(OBJDIR)/solver_codes.o:
$(OBJDIR)/strings.o: $(OBJDIR)/kinds.o
