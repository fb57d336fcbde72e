!> The generic `grow` of module growable extended to the derived types of
!> the model, for the deck reader that fills them one card at a time.
!> One specific routine per type because Fortran 2008 has no generic way
!> to reallocate an array of any type: an allocatable dummy argument must
!> have the declared type of its actual argument (class(*) does not accept
!> a type(t), allocatable), and there are no templates. Each routine is
!> the same few lines; the capacity rule is growable's new_capacity.
!> (These would sit in the model layer; they are here because only the
!> reader grows the model's arrays.)
module model_growth
  use growable, only: new_capacity
  use model, only: node_set_t, elem_set_t, surface_t, material_t, section_t, amplitude_t, &
                   step_t, contact_pair_t, bc_t, cload_t, request_t, src_t, &
                   equation_t
  implicit none
  private
  public :: grow

  !> grow(a, n): capacity of a at least n, contents kept (a may be unallocated).
  interface grow
    module procedure grow_nsets, grow_elsets, grow_surfaces, grow_materials, grow_sections, grow_amplitudes, &
                     grow_steps, grow_pairs, grow_bcs, grow_cloads, grow_requests, grow_srcs, &
                     grow_equations
  end interface grow

contains

  pure subroutine grow_nsets(a, n)
    type(node_set_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(node_set_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_nsets

  pure subroutine grow_elsets(a, n)
    type(elem_set_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(elem_set_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_elsets

  pure subroutine grow_surfaces(a, n)
    type(surface_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(surface_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_surfaces

  pure subroutine grow_materials(a, n)
    type(material_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(material_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_materials

  pure subroutine grow_sections(a, n)
    type(section_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(section_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_sections

  pure subroutine grow_amplitudes(a, n)
    type(amplitude_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(amplitude_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_amplitudes

  pure subroutine grow_steps(a, n)
    type(step_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(step_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_steps

  pure subroutine grow_pairs(a, n)
    type(contact_pair_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(contact_pair_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_pairs

  pure subroutine grow_bcs(a, n)
    type(bc_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(bc_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_bcs

  pure subroutine grow_cloads(a, n)
    type(cload_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(cload_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_cloads

  pure subroutine grow_requests(a, n)
    type(request_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(request_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_requests

  pure subroutine grow_srcs(a, n)
    type(src_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(src_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_srcs

  pure subroutine grow_equations(a, n)
    type(equation_t), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    type(equation_t), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_equations
end module model_growth
