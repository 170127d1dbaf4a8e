!> Linear complementarity problems with a symmetric positive definite band matrix (SPEC 4, P0):
!>     find mu >= 0 with w = A mu - b >= 0 and mu^T w = 0.
!>
!> Primal-dual active set (semismooth Newton) iterations, warm-started from the previous active
!> set; each iteration solves A_SS mu_S = b_S with a banded Cholesky (LAPACK dpbtrf/dpbtrs) of the
!> active submatrix, whose factor is kept while the set does not change. If the block iteration
!> cycles (A is not an M-matrix), Murty's least-index principal pivoting takes over; it ends in
!> finitely many pivots for any P-matrix, so for SPD A. The result satisfies mu >= 0 exactly,
!> w_S = 0 to round-off and w >= -tol on the inactive set, tol = 1e-14 max|b|.
module contact2d_lcp
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_band, only: band_cholesky_solve
   implicit none
   private
   public :: lcp_t

   integer, parameter :: max_block_iterations = 50
   real(wp), parameter :: rel_tol = 1.0e-14_wp

   !> An LCP matrix in LAPACK upper band storage with its last factorization.
   type :: lcp_t
      integer :: n = 0                      !< size
      integer :: kd = 0                     !< number of super-diagonals
      real(wp), allocatable :: ab(:, :)     !< A in band storage: ab(kd+1+i-j, j) = A(i, j), i <= j
      real(wp), allocatable :: arow(:, :)   !< A by rows: arow(j-i, i) = A(i, j), |i-j| <= kd (-kd:kd, n)
      logical, allocatable :: active(:)     !< active set of the last solve (warm start)
      ! factorization cache
      logical, allocatable :: fact_set(:)   !< the set the factor belongs to
      logical :: have_factor = .false.
      logical :: set_moved = .true.         !< active may differ from fact_set (changed since compared)
      integer :: na = 0                     !< size of the factored set
      integer, allocatable :: idx(:)        !< its indices, increasing
      real(wp), allocatable :: fab(:, :)    !< its band Cholesky factor
      real(wp), allocatable :: rhs(:), w(:)
      ! statistics
      integer :: iterations = 0             !< iterations of the last solve
      integer :: factorizations = 0         !< factorizations so far
      integer :: pivoting_solves = 0        !< solves that needed Murty's method
   contains
      procedure :: init => lcp_init
      procedure :: solve => lcp_solve
      procedure :: matvec => lcp_matvec
      procedure :: entry => lcp_entry
   end type lcp_t

contains

   !> Store A (band storage, kd super-diagonals); the warm start begins with all inactive.
   subroutine lcp_init(this, ab, kd)
      class(lcp_t), intent(out) :: this
      real(wp), intent(in) :: ab(:, :)      !< (kd+1, n)
      integer, intent(in) :: kd
      integer :: i, o
      this%n = size(ab, 2)
      this%kd = kd
      this%ab = ab
      allocate (this%active(this%n), this%fact_set(this%n), this%idx(this%n), &
                this%fab(kd + 1, this%n), this%rhs(this%n), this%w(this%n))
      this%active = .false.
      this%fact_set = .false.
      this%set_moved = .true.
      allocate (this%arow(-kd:kd, this%n))
      this%arow = 0
      do i = 1, this%n
         do o = max(-kd, 1 - i), min(kd, this%n - i)
            this%arow(o, i) = this%entry(i, i + o)
         end do
      end do
   end subroutine lcp_init

   !> A(i, j) (zero outside the band).
   pure real(wp) function lcp_entry(this, i, j) result(a)
      class(lcp_t), intent(in) :: this
      integer, intent(in) :: i, j
      if (abs(i - j) > this%kd) then
         a = 0
      else if (i <= j) then
         a = this%ab(this%kd + 1 + i - j, j)
      else
         a = this%ab(this%kd + 1 + j - i, i)
      end if
   end function lcp_entry

   !> y = A x (the rows of A in arow: no branch per entry; the terms in the order of j).
   pure subroutine lcp_matvec(this, x, y)
      class(lcp_t), intent(in) :: this
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      call band_matvec(this%n, this%kd, this%arow, x, y)
   end subroutine lcp_matvec

   pure subroutine band_matvec(n, kd, arow, x, y)
      integer, intent(in) :: n, kd
      real(wp), intent(in) :: arow(-kd:kd, n), x(n)
      real(wp), intent(out) :: y(n)
      integer :: i
      real(wp) :: s
      if (kd == 2 .and. n > 4) then
         ! the P0 LCP's five bands: the interior rows written out (same terms, same order)
         call band_rows(n, kd, arow, x, y, 1, 2)
         do i = 3, n - 2
            s = 0
            s = s + arow(-2, i)*x(i - 2)
            s = s + arow(-1, i)*x(i - 1)
            s = s + arow(0, i)*x(i)
            s = s + arow(1, i)*x(i + 1)
            s = s + arow(2, i)*x(i + 2)
            y(i) = s
         end do
         call band_rows(n, kd, arow, x, y, n - 1, n)
      else
         call band_rows(n, kd, arow, x, y, 1, n)
      end if
   end subroutine band_matvec

   !> Rows i1..i2 of y = A x, the terms in the order of j.
   pure subroutine band_rows(n, kd, arow, x, y, i1, i2)
      integer, intent(in) :: n, kd, i1, i2
      real(wp), intent(in) :: arow(-kd:kd, n), x(n)
      real(wp), intent(inout) :: y(n)
      integer :: i, j
      real(wp) :: s
      do i = i1, i2
         s = 0
         do j = max(1, i - kd), min(n, i + kd)
            s = s + arow(j - i, i)*x(j)
         end do
         y(i) = s
      end do
   end subroutine band_rows

   !> Solve the LCP for b. stat /= 0 (with a message) if LAPACK fails or no method converges.
   subroutine lcp_solve(this, b, mu, stat, errmsg)
      class(lcp_t), intent(inout) :: this
      real(wp), intent(in) :: b(:)
      real(wp), intent(out) :: mu(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: tol
      integer :: it, i, flip, max_pivots
      logical :: changed

      stat = 0
      tol = rel_tol*max(maxval(abs(b)), tiny(1.0_wp))
      this%iterations = 0
      ! primal-dual active set
      do it = 1, max_block_iterations
         this%iterations = it
         call solve_on_set(this, b, mu, stat, errmsg)
         if (stat /= 0) return
         changed = .false.
         do i = 1, this%n
            if (this%active(i)) then
               if (mu(i) <= 0) then
                  this%active(i) = .false.
                  changed = .true.
               end if
            else if (this%w(i) < -tol) then
               this%active(i) = .true.
               changed = .true.
            end if
         end do
         if (.not. changed) return
         this%set_moved = .true.
      end do
      ! cycling: Murty's least-index principal pivoting (finite for P-matrices)
      this%pivoting_solves = this%pivoting_solves + 1
      max_pivots = 20*this%n + 200
      do it = 1, max_pivots
         this%iterations = this%iterations + 1
         call solve_on_set(this, b, mu, stat, errmsg)
         if (stat /= 0) return
         flip = 0
         do i = 1, this%n
            if (this%active(i)) then
               if (mu(i) <= 0) flip = i
            else if (this%w(i) < -tol) then
               flip = i
            end if
            if (flip /= 0) exit
         end do
         if (flip == 0) return
         this%active(flip) = .not. this%active(flip)
         this%set_moved = .true.
      end do
      stat = 1
      errmsg = 'P0 contact LCP: no convergence after '//str(this%iterations)// &
               ' active-set iterations (n = '//str(this%n)//')'
   end subroutine lcp_solve

   !> mu on the current active set (zero elsewhere) and w = A mu - b.
   subroutine solve_on_set(this, b, mu, stat, errmsg)
      type(lcp_t), intent(inout) :: this
      real(wp), intent(in) :: b(:)
      real(wp), intent(out) :: mu(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: p, q, info
      external :: dpbtrf

      stat = 0
      mu = 0
      ! the factor is kept while the set is unchanged (compared only after lcp_solve moved it)
      if (this%set_moved) then
         if (this%have_factor) this%have_factor = all(this%fact_set .eqv. this%active)
         this%set_moved = .false.
      end if
      if (.not. this%have_factor) then
         this%na = 0
         do p = 1, this%n
            if (this%active(p)) then
               this%na = this%na + 1
               this%idx(this%na) = p
            end if
         end do
         ! band of the active submatrix: indices keep their order, so the band width stays kd
         this%fab = 0
         do q = 1, this%na
            do p = max(1, q - this%kd), q
               this%fab(this%kd + 1 + p - q, q) = this%entry(this%idx(p), this%idx(q))
            end do
         end do
         if (this%na > 0) then
            call dpbtrf('U', this%na, this%kd, this%fab, this%kd + 1, info)
            if (info /= 0) then
               stat = 1
               errmsg = 'P0 contact LCP: LAPACK dpbtrf failed (info = '//str(info)//')'
               return
            end if
         end if
         this%fact_set = this%active
         this%have_factor = .true.
         this%factorizations = this%factorizations + 1
      end if
      if (this%na > 0) then
         ! explicit loops: a vector subscript would make a heap temporary in the step loop
         do p = 1, this%na
            this%rhs(p) = b(this%idx(p))
         end do
         ! dpbtrs('U') of reference LAPACK, operation for operation (contact2d_band)
         call band_cholesky_solve(this%na, this%kd, this%fab, this%kd + 1, this%rhs)
         do p = 1, this%na
            mu(this%idx(p)) = this%rhs(p)
         end do
      end if
      call this%matvec(mu, this%w)
      this%w = this%w - b
   end subroutine solve_on_set
end module contact2d_lcp
