# Layer: base. Modules and the objects of the modules each one uses.
# make_dirs is a C shim (mkdir), see make_dirs.c; build_features.c says what the build found (MUMPS);
# memory_policy.c sets the C library's policy for large arrays (a constructor: nothing calls it).
MODULES += build_features directories growable kinds make_dirs memory_policy messages small_matrices solver_codes strings
$(OBJDIR)/build_features.o:
$(OBJDIR)/directories.o:
$(OBJDIR)/growable.o: $(OBJDIR)/kinds.o
$(OBJDIR)/kinds.o:
$(OBJDIR)/make_dirs.o:
$(OBJDIR)/memory_policy.o:
$(OBJDIR)/messages.o:
$(OBJDIR)/small_matrices.o: $(OBJDIR)/kinds.o
$(OBJDIR)/solver_codes.o:
$(OBJDIR)/strings.o: $(OBJDIR)/kinds.o
