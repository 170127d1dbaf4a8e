!> The primal-dual active-set (semismooth Newton) iteration of the static engine on the
!> condensed contact problem (docs/static.md "Algorithm" 3; Hintermueller, Ito & Kunisch, SIAM J.
!> Optim. 13 (2002) 865): dense algebra on the condensed operator A, nothing of the mesh.
module contact2d_pdas
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_cholmod, only: dense_potrf, dense_potrs
   implicit none
   private
   public :: pdas_solve, classify, max_pdas

   !> Iteration limit of one active-set solve.
   integer, parameter :: max_pdas = 200

contains

   !> Primal-dual active set on the condensed problem A (y - y0) + lambda = 0 (cvec = A y0), on
   !> plain arrays (the engine's pass and the unit tests call it): a(m, m) SPD, the first nc unknowns
   !> normal, the others tangential with limits lim(m - nc). Unknown r is in state
   !> 1 (normal active: y = 0), 0 (normal inactive: lambda = 0), 3 (stick: y = 0),
   !> +2 / -2 (slip: lambda = +-lim), 4 (no friction: lambda = 0). The sets follow
   !> lambda_n = max(0, lambda_n + A_rr y_n), lambda_t = proj(lambda_t + ct A_rr y_t).
   !> state on entry: the starting sets (-99 in state(1): everything in contact and stuck); on exit
   !> the last sets, lambda the multipliers and y the contact unknowns of the last solve.
   !> ok = .false. if a set repeats an earlier one (a cycle) or max_iter is reached: lambda is then
   !> the last iterate, not a solution. stat /= 0 only on a LAPACK failure.
   subroutine pdas_solve(a, nc, cvec, lim, ct, max_iter, state, lambda, y, nit, ok, stat, errmsg)
      real(wp), intent(in) :: a(:, :), cvec(:), lim(:)
      integer, intent(in) :: nc
      real(wp), intent(in) :: ct   !< tangential complementarity constant, a fraction of A_rr
      integer, intent(in) :: max_iter
      integer, intent(inout) :: state(:)
      real(wp), intent(inout) :: lambda(:)
      real(wp), intent(out) :: y(:)
      integer, intent(out) :: nit
      logical, intent(out) :: ok
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer, allocatable :: hist(:, :), free_set(:), new_state(:)
      real(wp), allocatable :: akk(:, :), rhs(:)
      integer :: it, r, nk, info, j, m

      stat = 0
      errmsg = ''
      ok = .false.
      m = size(cvec)
      allocate (hist(m, max(max_iter, 1)), new_state(m))
      y = 0
      nit = 0
      if (m == 0) then
         ok = .true.
         return
      end if
      ! start: the previous sets (warm start), else everything in contact and stuck
      if (state(1) == -99) then
         state(1:nc) = 1
         state(nc + 1:) = 3
      end if
      do r = nc + 1, m
         if (lim(r - nc) <= 0) state(r) = 4
         if (lim(r - nc) > 0 .and. state(r) == 4) state(r) = 3
      end do
      do it = 1, max_iter
         nit = it
         hist(:, it) = state
         ! known lambda on K (inactive, slip, no friction), y = 0 on J (active, stick)
         free_set = pack([(r, r=1, m)], state == 0 .or. abs(state) == 2 .or. state == 4)
         do r = 1, m
            select case (state(r))
            case (0, 4); lambda(r) = 0
            case (2); lambda(r) = lim(r - nc)
            case (-2); lambda(r) = -lim(r - nc)
            end select
         end do
         nk = size(free_set)
         ! A_KK (y_K - y0_K) - A_KJ y0_J = -lambda_K  =>  A_KK y_K = cvec_K - lambda_K
         y = 0
         if (nk > 0) then
            akk = a(free_set, free_set)
            rhs = cvec(free_set) - lambda(free_set)
            call dense_potrf('L', nk, akk, nk, info)
            if (info /= 0) then
               stat = 2
               errmsg = 'LAPACK dpotrf failed on the condensed contact matrix (info = '//str(info)//')'
               return
            end if
            call dense_potrs('L', nk, 1, akk, nk, rhs, nk, info)
            y(free_set) = rhs
         end if
         ! lambda_J = cvec_J - A_JK y_K
         do r = 1, m
            if (any(state(r) == [1, 3])) then
               lambda(r) = cvec(r) - dot_product(a(r, free_set), y(free_set))
            end if
         end do
         call classify(a, nc, lambda, y, lim, ct, new_state)
         if (all(new_state == state)) then
            ok = .true.
            return
         end if
         do j = 1, it - 1
            if (all(new_state == hist(:, j))) then
               state = new_state
               return   ! cycling
            end if
         end do
         state = new_state
      end do
   end subroutine pdas_solve

   !> The sets from (lambda, y): see pdas_solve.
   pure subroutine classify(a, nc, lambda, y, lim, ct, state)
      real(wp), intent(in) :: a(:, :)
      integer, intent(in) :: nc
      real(wp), intent(in) :: lambda(:), y(:), lim(:), ct
      integer, intent(out) :: state(:)
      integer :: r
      real(wp) :: v
      do r = 1, nc
         state(r) = merge(1, 0, lambda(r) + a(r, r)*y(r) > 0)
      end do
      do r = nc + 1, size(lambda)
         if (lim(r - nc) <= 0) then
            state(r) = 4
         else
            v = lambda(r) + ct*a(r, r)*y(r)
            if (abs(v) <= lim(r - nc)) then
               state(r) = 3
            else
               state(r) = merge(2, -2, v > 0)
            end if
         end if
      end do
   end subroutine classify
end module contact2d_pdas
