!> Where an array element sits in its 64-byte cache line (docs/performance.md
!> "Aligned blocks"). A vector load of eight reals that starts on a line reads one line, one
!> that starts elsewhere two; the integrator keeps its per-node arrays on lines, and the sweep
!> starts its blocks where a row of them starts a line and places its row-sized arrays alike.
!> Where the arrays are only changes speed: no result depends on it (the sweep chooses its
!> blocks from the mesh, not from addresses).
module contact2d_align
   use, intrinsic :: iso_c_binding, only: c_loc, c_intptr_t
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: line_reals, line_slot, line_skip

   !> reals in a 64-byte line
   integer, parameter :: line_reals = 8

contains

   !> Which real of its line x is (0 .. 7; x is at least 8-byte aligned, as every real is).
   integer function line_slot(x)
      real(wp), intent(in), target :: x
      line_slot = int(modulo(transfer(c_loc(x), 0_c_intptr_t), 64_c_intptr_t)/8)
   end function line_slot

   !> How many reals after x the next line starts (0 .. 7): x(1 + line_skip(x(1))) starts a line.
   integer function line_skip(x)
      real(wp), intent(in), target :: x
      line_skip = modulo(-line_slot(x), line_reals)
   end function line_skip
end module contact2d_align
