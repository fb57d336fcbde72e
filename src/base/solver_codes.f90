!> Names of the linear solvers and orderings a deck can choose, shared by
!> the model (what was asked for) and the solver layer (what it does).
module solver_codes
  use, intrinsic :: iso_c_binding, only: c_int
  implicit none
  private
  public :: solver_skyline, solver_cholmod, solver_umfpack, solver_mumps, solver_in_build, solver_code, &
            order_natural, order_rcm, order_amd, order_metis, solver_name, ordering_name, &
            contact_solve_auto, contact_solve_condensed, contact_solve_full, contact_solve_name

  integer, parameter :: solver_skyline = 1, solver_cholmod = 2, solver_umfpack = 3, solver_mumps = 4
  integer, parameter :: order_natural = 0, order_rcm = 1, order_amd = 2, order_metis = 3
  !> How the contact iterations are solved (*SOLVER, CONTACT SOLVE=): the
  !> status iterations on the contact equations condensed out of one
  !> factorisation of the bodies, the whole system factored for every
  !> status, or the first where it pays (analysis/condensed_contact).
  integer, parameter :: contact_solve_auto = 0, contact_solve_condensed = 1, contact_solve_full = 2

  interface
    !> 1 when the build found MUMPS and MPI (build_features.c).
    integer(c_int) function cfe_build_has_mumps() bind(C, name='cfe_build_has_mumps')
      import :: c_int
    end function cfe_build_has_mumps
  end interface

contains

  pure function solver_name(kind) result(s)
    integer, intent(in) :: kind
    character(len=:), allocatable :: s
    select case (kind)
    case (solver_skyline); s = 'skyline LDL^T'
    case (solver_cholmod); s = 'CHOLMOD'
    case (solver_mumps); s = 'MUMPS'
    case default; s = 'UMFPACK'
    end select
  end function solver_name

  !> Purpose: the solver of a name as a deck or the command line gives it
  !> (SKYLINE, CHOLMOD, UMFPACK, MUMPS; upper case), 0 for none of them.
  pure integer function solver_code(name)
    character(len=*), intent(in) :: name
    select case (name)
    case ('SKYLINE'); solver_code = solver_skyline
    case ('CHOLMOD'); solver_code = solver_cholmod
    case ('UMFPACK'); solver_code = solver_umfpack
    case ('MUMPS'); solver_code = solver_mumps
    case default; solver_code = 0
    end select
  end function solver_code

  !> Purpose: can this build run the solver? MUMPS needs MPI and MUMPS
  !> where cfe2d was built (the Makefile looks for them).
  logical function solver_in_build(kind)
    integer, intent(in) :: kind
    solver_in_build = .true.
    if (kind == solver_mumps) solver_in_build = cfe_build_has_mumps() /= 0
  end function solver_in_build

  pure function ordering_name(o) result(s)
    integer, intent(in) :: o
    character(len=:), allocatable :: s
    select case (o)
    case (order_natural); s = 'natural'
    case (order_rcm); s = 'RCM'
    case (order_amd); s = 'AMD'
    case default; s = 'METIS'
    end select
  end function ordering_name

  pure function contact_solve_name(c) result(s)
    integer, intent(in) :: c
    character(len=:), allocatable :: s
    select case (c)
    case (contact_solve_condensed); s = 'condensed'
    case (contact_solve_full); s = 'full'
    case default; s = 'auto'
    end select
  end function contact_solve_name
end module solver_codes
