!> METIS 5 through iso_c_binding: nested-dissection fill-reducing ordering
!> (METIS_NodeND). Debian's METIS uses 32-bit idx_t (IDXTYPEWIDTH 32).
module metis_binding
  use, intrinsic :: iso_c_binding
  implicit none
  private
  public :: metis_nodend, metis_setdefaultoptions, metis_noptions, metis_ok, metis_option_numbering

  integer, parameter :: metis_noptions = 40
  integer(c_int), parameter :: metis_ok = 1
  integer, parameter :: metis_option_numbering = 18   ! METIS_OPTION_NUMBERING + 1

  interface
    integer(c_int) function metis_setdefaultoptions(options) bind(C, name='METIS_SetDefaultOptions')
      import :: c_int
      integer(c_int), intent(out) :: options(*)
    end function metis_setdefaultoptions

    integer(c_int) function metis_nodend(nvtxs, xadj, adjncy, vwgt, options, perm, iperm) &
        bind(C, name='METIS_NodeND')
      import :: c_int, c_ptr
      integer(c_int), intent(in) :: nvtxs
      integer(c_int), intent(in) :: xadj(*), adjncy(*)
      type(c_ptr), value :: vwgt
      integer(c_int), intent(in) :: options(*)
      integer(c_int), intent(out) :: perm(*), iperm(*)
    end function metis_nodend
  end interface
end module metis_binding
