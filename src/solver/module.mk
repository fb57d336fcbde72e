# Layer: solver. Modules and the objects of the modules each one uses.
MODULES += blas_info cholmod_binding linear_solver metis_binding ordering skyline sparse_matrix umfpack_binding
$(OBJDIR)/blas_info.o:
$(OBJDIR)/cholmod_binding.o:
$(OBJDIR)/linear_solver.o: $(OBJDIR)/cholmod_binding.o $(OBJDIR)/kinds.o $(OBJDIR)/messages.o $(OBJDIR)/metis_binding.o $(OBJDIR)/skyline.o $(OBJDIR)/solver_codes.o $(OBJDIR)/sparse_matrix.o $(OBJDIR)/strings.o $(OBJDIR)/umfpack_binding.o
$(OBJDIR)/metis_binding.o:
$(OBJDIR)/ordering.o: $(OBJDIR)/messages.o $(OBJDIR)/metis_binding.o $(OBJDIR)/strings.o
$(OBJDIR)/skyline.o: $(OBJDIR)/kinds.o
$(OBJDIR)/sparse_matrix.o: $(OBJDIR)/kinds.o
$(OBJDIR)/umfpack_binding.o:
