!> The state of the equilibrium iteration of one increment (iteration_t),
!> which the loop (equilibrium_loop) reads and its steps change, and the
!> interface of a linear path (linear_path_t): how the linear system of a
!> contact status is factored and solved and what the forces of its
!> solution are. The loop is the same for every path; a path is the only
!> thing that differs between the full solve (module equilibrium: the
!> whole stiffness factored for every status, and Newton's tangent) and
!> the condensed one (condensed_equilibrium: the contact equations
!> condensed out of one factorisation of the bodies).
module iteration_state
  use kinds, only: dp
  use model, only: model_t
  use contact, only: contact_set_t
  use assembly, only: body_t
  use dof_numbering, only: dofmap_t
  use linear_solver, only: linear_system_t
  use constraints, only: mpc_t
  use equilibrium_common, only: equilibrium_t
  use analysis_events, only: observer_ref_t
  implicit none
  private
  public :: iteration_t, linear_path_t

  !> What a step of the loop says about the iteration: go on to the next
  !> step, begin the next iteration, or give the increment up (the
  !> reason is in eq%newton: newton_give_up).
  integer, parameter, public :: go_on = 0, again = 1, give_up = 2

  !> One increment's equilibrium iteration. The first part is the
  !> problem, associated by solve_increment for the increment (the
  !> objects belong to the caller); the rest is the iteration's own.
  type :: iteration_t
    type(equilibrium_t), pointer :: eq => null()
    type(model_t), pointer :: m => null()
    integer :: is = 0, inc = 0                         ! step, and the increment being solved
    type(body_t), pointer :: body => null()
    type(contact_set_t), pointer :: cs => null()
    type(dofmap_t), pointer :: dm => null()
    type(linear_system_t), pointer :: sys => null()
    real(dp), pointer :: fext(:, :) => null()          ! external forces of the increment (2, nn)
    real(dp), pointer :: u(:, :) => null()             ! the displacements, updated by every solve
    real(dp), pointer :: rf(:, :) => null()            ! T^T (f_int - f_ext) of the last residual
    type(observer_ref_t), pointer :: obs(:) => null()
    !> A nonlinear step: the converged state the increment starts from
    !> (u_from), and whether u differs from it (predict: the first
    !> iteration is linearised about u_from, the bodies' forces are
    !> body_predictor_forces).
    real(dp), pointer :: u_from(:, :) => null()
    logical :: predict = .false.
    !> NLGEOM with contact: the step's prescribed dofs and constraints,
    !> which a renumbering needs; research says that the contact is
    !> searched again after every update (search_again).
    logical, pointer :: presc(:, :) => null()
    type(mpc_t), pointer :: mpc => null()
    logical :: research = .false.
    ! the iteration
    integer :: it = 0                   ! iterations of this increment
    integer :: verdict = 0              ! of the last step: go_on, again or give_up
    logical :: usable = .true.          ! the factor of the status can be used (factor)
    logical :: restabilised = .false.   ! factor stabilised the open contact
    real(dp) :: c_max = 0.0_dp          ! the largest correction of the solve
    integer :: nsearched = 0            ! statuses changed by the search in this iteration
    logical :: searched = .false.       ! this iteration searched the contact again
    real(dp) :: energy = 0.0_dp         ! the potential energy of the status's solution
    real(dp) :: fext_norm = 0.0_dp      ! |f_ext|
    integer :: nchanged = 0             ! statuses changed in this iteration
    real(dp) :: scale = 0.0_dp          ! the force scale of the last residual (relative_residual)
    logical :: converged = .false.      ! the out-of-balance passes the test
    !> the path's residual asks the loop to judge the statuses again on a
    !> solution it has just made better (the loop's rejudge; the path's
    !> rejudged then makes the out-of-balance)
    logical :: rejudge = .false.
    integer :: naug = 0                 ! augmentations of the multipliers (exact enforcement)
    !> Newton on the condensed path: this iteration only searched the
    !> contact status of the linearised problem (its solution is not
    !> whole): no Newton iteration, no Newton test
    logical :: inner = .false.
    integer :: ninner = 0               ! inner iterations of the increment
    real(dp), allocatable :: u_start(:, :)   ! a nonlinear step: u at the increment's start
    real(dp), allocatable :: u_pred(:, :)    ! u after the first iteration's predictor step
    !> The cycle watch of a nonlinear step: the statuses and out-of-balance
    !> of the last two iterations that changed a status.
    logical, allocatable :: closed1(:), closed2(:)
    real(dp) :: res1 = -1.0_dp, res2 = -1.0_dp
  end type iteration_t

  !> A way of solving the linear system of a contact status. Every
  !> binding acts on the iteration state st (its problem and its
  !> iteration).
  type, abstract :: linear_path_t
    !> exact enforcement by augmenting the multipliers (augment_multipliers)
    !> once the status settles; false where the path solves them directly
    logical :: augmented = .true.
    !> Newton: the loop makes the factor invalid before every iteration
    !> (the tangent at the new u); false where the path says itself when
    !> its tangent is made (condensed_equilibrium's Newton path)
    logical :: newton_refactors = .true.
    !> NLGEOM with contact: the path searches the contact again itself
    !> (once its solution is whole), not the loop's search_again step
    logical :: searches_itself = .false.
  contains
    !> before the status search: the start of the increment
    procedure(path_step), deferred :: begin
    !> the matrix of the current status factored unless the factor in
    !> hand is for it; sets st%usable and st%restabilised
    procedure(path_step), deferred :: factor
    !> the status's system solved and u updated; sets st%c_max
    procedure(path_step), deferred :: solve
    !> the forces of the solution and the bodies' part of the potential
    !> energy of the status search (st%energy, without the contact's)
    procedure(path_step), deferred :: solution_energy
    !> after the status switch: the out-of-balance (eq%residual, st%scale)
    procedure(path_step), deferred :: residual
    !> the status changed outside the switch (a pivot taken back, the
    !> open contact stabilised): the forces of the new one
    procedure(path_step), deferred :: status_changed
    !> a new status search (the nominal open penalty, updated
    !> multipliers) from where the path starts it
    procedure(path_step), deferred :: restart
    !> the increment converged: what the path keeps of it
    procedure(path_step), deferred :: converged
    !> after the loop judged the statuses again (st%rejudge): the
    !> out-of-balance; nothing where the path never asks
    procedure :: rejudged => no_rejudge
  end type linear_path_t

  abstract interface
    subroutine path_step(path, st)
      import :: linear_path_t, iteration_t
      class(linear_path_t), intent(inout) :: path
      type(iteration_t), intent(inout) :: st
    end subroutine path_step
  end interface

contains

  !> Purpose: the rejudged step of a path that never sets st%rejudge.
  subroutine no_rejudge(path, st)
    class(linear_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
  end subroutine no_rejudge
end module iteration_state
