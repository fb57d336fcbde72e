!> The MPI session of a run (`mpirun -np N bin/cfe2d deck.inp`): rank 0
!> is the program (reads the deck, runs the analysis, writes the
!> results); every other rank only joins the MUMPS jobs rank 0 starts, in
!> a loop that ends when rank 0 exits (mumps_shim.c). A run that was not
!> started by an MPI launcher does not start MPI here (MUMPS starts it as
!> a single rank if the deck asks for it).
module mpi_session
  use, intrinsic :: iso_c_binding, only: c_int
  use mumps_binding, only: cfe_mpi_start, cfe_mpi_rank, cfe_mpi_worker_loop
  use blas_info, only: set_solver_threads
  implicit none
  private
  public :: session_start, session_serve

contains

  !> Purpose: starts MPI when an MPI launcher started this process.
  !> Arguments: worker returns true on the ranks other than 0, which
  !> then call session_serve instead of running the program; ranks
  !> returns the number of ranks (1 without MPI, 0 if MPI_Init failed).
  subroutine session_start(worker, ranks)
    logical, intent(out) :: worker
    integer, intent(out) :: ranks
    ranks = max(0, int(cfe_mpi_start(0_c_int)))
    worker = ranks > 1 .and. cfe_mpi_rank() /= 0
  end subroutine session_start

  !> Purpose: a worker rank's whole life: join rank 0's MUMPS jobs until
  !> rank 0 ends the session. The thread policy is rank 0's (one BLAS
  !> thread per rank unless the environment asks for more).
  subroutine session_serve()
    call set_solver_threads()
    call cfe_mpi_worker_loop()
  end subroutine session_serve
end module mpi_session
