!> Solve with a band Cholesky factor: A x = b for A = U^T U, U upper band (LAPACK dpbtrf 'U'
!> storage, kd super-diagonals). The same operations in the same order as reference LAPACK
!> dpbtrs('U') with reference BLAS dtbsv (Upper, Transpose then No transpose, Non-unit), so the
!> result has the same bits as the library call of the reference BLAS; without its call
!> overhead and argument checks, which cost more than the arithmetic on the five-band P0 LCP
!> (src/kernels/contact2d_lcp.f90). This file is compiled with -ffp-contract=off (CMakeLists.txt):
!> the reference BLAS rounds every product before the subtraction, so no fused multiply-add here.
module contact2d_band
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: band_cholesky_solve

contains

   !> x := A^-1 x with A = U^T U; fab(kd+1+i-j, j) = U(i, j), max(1, j-kd) <= i <= j.
   pure subroutine band_cholesky_solve(n, kd, fab, ldab, x)
      integer, intent(in) :: n, kd, ldab
      real(wp), intent(in) :: fab(ldab, *)
      real(wp), intent(inout) :: x(*)
      integer :: i, j, l
      real(wp) :: temp
      if (kd == 2 .and. n > 2) then
         call solve_kd2(n, fab, ldab, x)
         return
      end if
      ! U^T y = b, forward (dtbsv 'U', 'T', 'N', incx = 1)
      do j = 1, n
         temp = x(j)
         l = kd + 1 - j
         do i = max(1, j - kd), j - 1
            temp = temp - fab(l + i, j)*x(i)
         end do
         temp = temp/fab(kd + 1, j)
         x(j) = temp
      end do
      ! U x = y, backward (dtbsv 'U', 'N', 'N', incx = 1)
      do j = n, 1, -1
         if (x(j) /= 0) then
            l = kd + 1 - j
            x(j) = x(j)/fab(kd + 1, j)
            temp = x(j)
            do i = j - 1, max(1, j - kd), -1
               x(i) = x(i) - temp*fab(l + i, j)
            end do
         end if
      end do
   end subroutine band_cholesky_solve

   !> band_cholesky_solve for kd = 2 (the P0 LCP), the inner loops written out in their order.
   pure subroutine solve_kd2(n, fab, ldab, x)
      integer, intent(in) :: n, ldab
      real(wp), intent(in) :: fab(ldab, *)
      real(wp), intent(inout) :: x(*)
      integer :: j
      real(wp) :: temp
      x(1) = x(1)/fab(3, 1)
      x(2) = (x(2) - fab(2, 2)*x(1))/fab(3, 2)
      do j = 3, n
         temp = x(j)
         temp = temp - fab(1, j)*x(j - 2)
         temp = temp - fab(2, j)*x(j - 1)
         x(j) = temp/fab(3, j)
      end do
      do j = n, 3, -1
         if (x(j) /= 0) then
            x(j) = x(j)/fab(3, j)
            temp = x(j)
            x(j - 1) = x(j - 1) - temp*fab(2, j)
            x(j - 2) = x(j - 2) - temp*fab(1, j)
         end if
      end do
      if (x(2) /= 0) then
         x(2) = x(2)/fab(3, 2)
         x(1) = x(1) - x(2)*fab(2, 2)
      end if
      if (x(1) /= 0) x(1) = x(1)/fab(3, 1)
   end subroutine solve_kd2
end module contact2d_band
