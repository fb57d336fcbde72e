!> Names of the linear solvers and orderings a deck can choose, shared by
!> the model (what was asked for) and the solver layer (what it does).
module solver_codes
  implicit none
  private
  public :: solver_skyline, solver_cholmod, solver_umfpack, &
            order_natural, order_rcm, order_amd, order_metis, solver_name, ordering_name, &
            contact_solve_auto, contact_solve_condensed, contact_solve_full, contact_solve_name

  integer, parameter :: solver_skyline = 1, solver_cholmod = 2, solver_umfpack = 3
  integer, parameter :: order_natural = 0, order_rcm = 1, order_amd = 2, order_metis = 3
  !> How the contact iterations are solved (*SOLVER, CONTACT SOLVE=): the
  !> status iterations on the contact equations condensed out of one
  !> factorisation of the bodies, the whole system factored for every
  !> status, or the first where it pays (analysis/condensed_contact).
  integer, parameter :: contact_solve_auto = 0, contact_solve_condensed = 1, contact_solve_full = 2

contains

  pure function solver_name(kind) result(s)
    integer, intent(in) :: kind
    character(len=:), allocatable :: s
    select case (kind)
    case (solver_skyline); s = 'skyline LDL^T'
    case (solver_cholmod); s = 'CHOLMOD'
    case default; s = 'UMFPACK'
    end select
  end function solver_name

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
