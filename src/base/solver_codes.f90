!> Names of the linear solvers and orderings a deck can choose, shared by
!> the model (what was asked for) and the solver layer (what it does).
module solver_codes
  implicit none
  private
  public :: solver_skyline, solver_cholmod, solver_umfpack, &
            order_natural, order_rcm, order_amd, order_metis, solver_name, ordering_name

  integer, parameter :: solver_skyline = 1, solver_cholmod = 2, solver_umfpack = 3
  integer, parameter :: order_natural = 0, order_rcm = 1, order_amd = 2, order_metis = 3

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
end module solver_codes
