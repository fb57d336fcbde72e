!> MUMPS and its MPI session through the C shim mumps_shim.c: an
!> instance is a small integer handle; the matrix (coordinates, 1-based),
!> right-hand sides and Schur block are passed at every job and live on
!> rank 0 only. In a build without MUMPS (the Makefile finds no MUMPS or
!> MPI) the same entry points exist and cfe_mumps_available() is 0.
module mumps_binding
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_long_long
  implicit none
  private
  public :: cfe_mumps_available, cfe_mpi_start, cfe_mpi_rank, cfe_mpi_worker_loop, cfe_mumps_new, &
            cfe_mumps_free, cfe_mumps_get_control, cfe_mumps_set_control, cfe_mumps_job, &
            cfe_mumps_null_pivots, mumps_job_analyse, mumps_job_factor, mumps_job_solve

  !> MUMPS' JOB values.
  integer(c_int), parameter :: mumps_job_analyse = 1, mumps_job_factor = 2, mumps_job_solve = 3

  interface
    !> 1 when this build has MUMPS and MPI, 0 otherwise.
    integer(c_int) function cfe_mumps_available() bind(C, name='cfe_mumps_available')
      import :: c_int
    end function cfe_mumps_available

    !> Starts MPI when an MPI launcher started the program, or always with
    !> force /= 0; returns the number of ranks (1 without MPI, -1 when
    !> MPI_Init failed).
    integer(c_int) function cfe_mpi_start(force) bind(C, name='cfe_mpi_start')
      import :: c_int
      integer(c_int), value :: force
    end function cfe_mpi_start

    integer(c_int) function cfe_mpi_rank() bind(C, name='cfe_mpi_rank')
      import :: c_int
    end function cfe_mpi_rank

    !> A rank other than 0: joins rank 0's MUMPS jobs until it quits.
    subroutine cfe_mpi_worker_loop() bind(C, name='cfe_mpi_worker_loop')
    end subroutine cfe_mpi_worker_loop

    !> A new instance (sym 0: unsymmetric, 2: symmetric), or -1.
    integer(c_int) function cfe_mumps_new(sym) bind(C, name='cfe_mumps_new')
      import :: c_int
      integer(c_int), value :: sym
    end function cfe_mumps_new

    subroutine cfe_mumps_free(h) bind(C, name='cfe_mumps_free')
      import :: c_int
      integer(c_int), value :: h
    end subroutine cfe_mumps_free

    !> ICNTL(1:60) and CNTL(1:15) of an instance.
    subroutine cfe_mumps_get_control(h, icntl, cntl) bind(C, name='cfe_mumps_get_control')
      import :: c_int, c_double
      integer(c_int), value :: h
      integer(c_int), intent(out) :: icntl(60)
      real(c_double), intent(out) :: cntl(15)
    end subroutine cfe_mumps_get_control

    subroutine cfe_mumps_set_control(h, icntl, cntl) bind(C, name='cfe_mumps_set_control')
      import :: c_int, c_double
      integer(c_int), value :: h
      integer(c_int), intent(in) :: icntl(60)
      real(c_double), intent(in) :: cntl(15)
    end subroutine cfe_mumps_set_control

    !> One MUMPS job on every rank; returns INFOG(1). nschur > 0: the
    !> equations schur_list form a Schur block returned into schur
    !> (nschur x nschur, rank 0); rhs(n, nrhs) becomes the solutions.
    integer(c_int) function cfe_mumps_job(h, job, n, nnz, irn, jcn, a, nschur, schur_list, schur, nrhs, rhs, &
                                          infog, info, rinfog) bind(C, name='cfe_mumps_job')
      import :: c_int, c_double, c_long_long
      integer(c_int), value :: h, job, n
      integer(c_long_long), value :: nnz
      integer(c_int), intent(in) :: irn(*), jcn(*)
      real(c_double), intent(in) :: a(*)
      integer(c_int), value :: nschur
      integer(c_int), intent(in) :: schur_list(*)
      real(c_double), intent(inout) :: schur(*)
      integer(c_int), value :: nrhs
      real(c_double), intent(inout) :: rhs(*)
      integer(c_int), intent(out) :: infog(80), info(80)
      real(c_double), intent(out) :: rinfog(40)
    end function cfe_mumps_job

    !> Equations of the null pivots of the last factorisation (at most
    !> max); returns their number (INFOG(28)).
    integer(c_int) function cfe_mumps_null_pivots(h, list, max) bind(C, name='cfe_mumps_null_pivots')
      import :: c_int
      integer(c_int), value :: h, max
      integer(c_int), intent(out) :: list(*)
    end function cfe_mumps_null_pivots
  end interface
end module mumps_binding
