! Compiled (to assembly only) at configure time with the build's flags: does the compiler put a
! loop of eight lanes in one 512-bit register? (CMakeLists.txt, contact2d_build_config)
subroutine contact2d_simd_probe(x, a, y)
   implicit none
   real(kind(1.0d0)), intent(in) :: x(0:7), a(0:7)
   real(kind(1.0d0)), intent(inout) :: y(0:7)
   integer :: l
   !$omp simd
   do l = 0, 7
      y(l) = y(l) + a(l)*x(l)
   end do
end subroutine contact2d_simd_probe
