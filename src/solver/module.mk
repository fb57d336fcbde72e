# Layer: solver. Modules and the objects of the modules each one uses.
# cholmod_shim and thread_shim are C: CHOLMOD's structs stay on the C side, and
# the thread policy looks up OpenMP and OpenBLAS entry points at run time; mumps_shim
# holds MUMPS' C interface and the MPI session (stubs in a build without MUMPS).
MODULES += arpack_binding eigen_solver blas_info cholmod_binding cholmod_backend cholmod_shim dense_cholesky dense_lu linear_solver metis_binding mpi_session \
           mumps_backend mumps_binding mumps_shim ordering skyline \
           skyline_backend solver_backend sparse_matrix thread_shim umfpack_backend umfpack_binding
$(OBJDIR)/blas_info.o:
$(OBJDIR)/cholmod_backend.o: $(OBJDIR)/blas_info.o $(OBJDIR)/cholmod_binding.o $(OBJDIR)/kinds.o $(OBJDIR)/messages.o $(OBJDIR)/ordering.o $(OBJDIR)/solver_backend.o $(OBJDIR)/solver_codes.o $(OBJDIR)/sparse_matrix.o $(OBJDIR)/strings.o
$(OBJDIR)/cholmod_binding.o:
$(OBJDIR)/cholmod_shim.o:
$(OBJDIR)/dense_cholesky.o: $(OBJDIR)/kinds.o
$(OBJDIR)/dense_lu.o: $(OBJDIR)/kinds.o
$(OBJDIR)/linear_solver.o: $(OBJDIR)/cholmod_backend.o $(OBJDIR)/kinds.o $(OBJDIR)/messages.o $(OBJDIR)/mumps_backend.o $(OBJDIR)/skyline_backend.o $(OBJDIR)/solver_backend.o $(OBJDIR)/solver_codes.o $(OBJDIR)/strings.o $(OBJDIR)/umfpack_backend.o
$(OBJDIR)/metis_binding.o:
$(OBJDIR)/mpi_session.o: $(OBJDIR)/blas_info.o $(OBJDIR)/mumps_binding.o
$(OBJDIR)/mumps_backend.o: $(OBJDIR)/blas_info.o $(OBJDIR)/dense_cholesky.o $(OBJDIR)/kinds.o $(OBJDIR)/messages.o $(OBJDIR)/mumps_binding.o $(OBJDIR)/solver_backend.o $(OBJDIR)/solver_codes.o $(OBJDIR)/sparse_matrix.o $(OBJDIR)/strings.o
$(OBJDIR)/mumps_binding.o:
$(OBJDIR)/mumps_shim.o:
$(OBJDIR)/ordering.o: $(OBJDIR)/messages.o $(OBJDIR)/metis_binding.o $(OBJDIR)/strings.o
$(OBJDIR)/skyline.o: $(OBJDIR)/kinds.o
$(OBJDIR)/skyline_backend.o: $(OBJDIR)/kinds.o $(OBJDIR)/skyline.o $(OBJDIR)/solver_backend.o $(OBJDIR)/strings.o
$(OBJDIR)/solver_backend.o: $(OBJDIR)/kinds.o
$(OBJDIR)/sparse_matrix.o: $(OBJDIR)/kinds.o
$(OBJDIR)/thread_shim.o:
$(OBJDIR)/umfpack_backend.o: $(OBJDIR)/blas_info.o $(OBJDIR)/kinds.o $(OBJDIR)/messages.o $(OBJDIR)/solver_backend.o $(OBJDIR)/solver_codes.o $(OBJDIR)/sparse_matrix.o $(OBJDIR)/strings.o $(OBJDIR)/umfpack_binding.o
$(OBJDIR)/umfpack_binding.o:
$(OBJDIR)/arpack_binding.o: $(OBJDIR)/kinds.o
$(OBJDIR)/eigen_solver.o: $(OBJDIR)/arpack_binding.o $(OBJDIR)/kinds.o $(OBJDIR)/linear_solver.o $(OBJDIR)/sparse_matrix.o
