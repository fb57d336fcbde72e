!> Working precision and program identity, shared by every other module.
module kinds
  implicit none
  private
  public :: dp, program_version, name_len

  integer, parameter :: dp = selected_real_kind(15, 307)
  character(len=*), parameter :: program_version = '0.1.0'
  !> Length of set, material, surface and amplitude names (Abaqus allows 80).
  integer, parameter :: name_len = 80
end module kinds
