!> Working precision and shared numeric constants.
module contact2d_kinds
   use, intrinsic :: iso_fortran_env, only: real64, int64
   implicit none
   private
   public :: wp, i8, pi

   !> Working real kind (IEEE double).
   integer, parameter :: wp = real64
   !> 64-bit integer kind (step counters, operation counts).
   integer, parameter :: i8 = int64
   !> pi to working precision.
   real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp
end module contact2d_kinds
