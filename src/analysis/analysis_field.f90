!> A field the driver (analysis) steps through the increments: the
!> unknowns of one physics with their own equations, solve, history and
!> results. Today the one field is the displacements (displacement_field);
!> a temperature field (heat transfer, coupled or alone) is another
!> extension of field_t added to the driver's list, not a second driver
!> (docs/architecture.md, "Adding a field"). The driver owns time: the
!> steps, the increments and their cut-back; a field owns everything of
!> its unknowns, and says whether its step needs automatic increments
!> (nonlinear), why an increment failed and by how much to cut it.
module analysis_field
  use kinds, only: dp
  use model, only: model_t
  use analysis_events, only: observer_ref_t, step_info_t, step_summary_t, run_timing_t
  implicit none
  private
  public :: field_t, field_ref_t

  type, abstract :: field_t
  contains
    !> once per run, before the first step: the field's data of the model
    procedure(field_setup), deferred :: setup
    !> a step begins: its loads, its equations; the field's part of the
    !> step's description (info); whether its step is nonlinear
    procedure(field_begin_step), deferred :: begin_step
    procedure(field_query), deferred :: nonlinear
    !> the field's notes on its step for the listing, after the step's
    !> header (the contact search's: a coarse slave)
    procedure(field_notes), deferred :: step_notes
    !> an increment from step time t0 to t1 begins: the state it starts
    !> from is saved (restore), the prescribed values and loads of t1 set;
    !> search_due: a contact search on the current configuration is due
    !> (UPDATE SEARCH, NLGEOM)
    procedure(field_begin_increment), deferred :: begin_increment
    !> the field's equations of the increment solved; ok false when they
    !> did not converge (why: failure)
    procedure(field_solve), deferred :: solve
    !> a converged increment: its path-dependent state becomes the state
    !> the next one starts from
    procedure(field_plain), deferred :: commit
    !> a failed increment: back to the state saved at its start
    procedure(field_restore), deferred :: restore
    !> why the last solve failed and the factor to cut the increment by
    !> (automatic increments); what is still changing (a linear step's
    !> bisection: the contact nodes still switching)
    procedure(field_failure), deferred :: failure
    !> a converged increment that the field would rather have split in
    !> two (a frictional contact zone that grew too far within it); the
    !> default: never
    procedure :: split_wanted => never_split
    !> a converged increment's results, to the observers
    procedure(field_report), deferred :: report
    !> the step is done: the field's part of its summary (and its notes)
    procedure(field_end_step), deferred :: end_step
    !> the run is done: the field's part of where the time went
    procedure(field_finish), deferred :: finish
  end type field_t

  !> An element of the driver's list of fields.
  type :: field_ref_t
    class(field_t), allocatable :: f
  end type field_ref_t

  abstract interface
    subroutine field_setup(f, m, timing)
      import :: field_t, model_t, run_timing_t
      class(field_t), intent(inout) :: f
      type(model_t), intent(in) :: m
      type(run_timing_t), intent(inout) :: timing
    end subroutine field_setup

    subroutine field_begin_step(f, m, is, total_time, info, timing)
      import :: field_t, model_t, dp, step_info_t, run_timing_t
      class(field_t), intent(inout) :: f
      type(model_t), intent(in) :: m
      integer, intent(in) :: is
      real(dp), intent(in) :: total_time
      type(step_info_t), intent(inout) :: info
      type(run_timing_t), intent(inout) :: timing
    end subroutine field_begin_step

    subroutine field_notes(f, obs)
      import :: field_t, observer_ref_t
      class(field_t), intent(in) :: f
      type(observer_ref_t), intent(in) :: obs(:)
    end subroutine field_notes

    logical function field_query(f)
      import :: field_t
      class(field_t), intent(in) :: f
    end function field_query

    subroutine field_begin_increment(f, m, t0, t1, search_due, timing)
      import :: field_t, model_t, dp, run_timing_t
      class(field_t), intent(inout) :: f
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: t0, t1
      logical, intent(in) :: search_due
      type(run_timing_t), intent(inout) :: timing
    end subroutine field_begin_increment

    subroutine field_solve(f, m, is, inc, obs, ok, iters)
      import :: field_t, model_t, observer_ref_t
      class(field_t), intent(inout) :: f
      type(model_t), intent(in) :: m
      integer, intent(in) :: is, inc
      type(observer_ref_t), intent(in) :: obs(:)
      logical, intent(out) :: ok
      integer, intent(out) :: iters
    end subroutine field_solve

    subroutine field_plain(f)
      import :: field_t
      class(field_t), intent(inout) :: f
    end subroutine field_plain

    subroutine field_restore(f, m)
      import :: field_t, model_t
      class(field_t), intent(inout) :: f
      type(model_t), intent(in) :: m
    end subroutine field_restore

    subroutine field_failure(f, reason, cut, changing)
      import :: field_t, dp
      class(field_t), intent(in) :: f
      character(len=:), allocatable, intent(out) :: reason, changing
      real(dp), intent(out) :: cut
    end subroutine field_failure

    subroutine field_report(f, m, is, inc, t, total_time, iters, dt, obs, timing)
      import :: field_t, model_t, dp, observer_ref_t, run_timing_t
      class(field_t), intent(inout) :: f
      type(model_t), intent(in) :: m
      integer, intent(in) :: is, inc, iters
      real(dp), intent(in) :: t, total_time, dt
      type(observer_ref_t), intent(in) :: obs(:)
      type(run_timing_t), intent(inout) :: timing
    end subroutine field_report

    subroutine field_end_step(f, obs, summary)
      import :: field_t, observer_ref_t, step_summary_t
      class(field_t), intent(inout) :: f
      type(observer_ref_t), intent(in) :: obs(:)
      type(step_summary_t), intent(inout) :: summary
    end subroutine field_end_step

    subroutine field_finish(f, timing)
      import :: field_t, run_timing_t
      class(field_t), intent(in) :: f
      type(run_timing_t), intent(inout) :: timing
    end subroutine field_finish
  end interface

contains

  !> Purpose: the default of split_wanted: a converged increment of a
  !> field is never split (wanted false, reason empty).
  !> Arguments: m the model; is the step.
  subroutine never_split(f, m, is, wanted, reason)
    class(field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    logical, intent(out) :: wanted
    character(len=:), allocatable, intent(out) :: reason
    wanted = .false.
    reason = ''
  end subroutine never_split
end module analysis_field
