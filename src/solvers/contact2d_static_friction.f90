!> The friction side of the static engine: the law's limits of the tangential unknowns
!> (law_limits), nodal forces from the multipliers (nodal_forces, d_apply), and the solves for a
!> friction law whose limits are linear in the normal forces,
!> limit_i = mu_i F_n,i (friction_law_t%linear_in_fn; Coulomb, docs/static.md "Coulomb friction
!> and tresca_scope = 'contact'"): with the active, stick and slip sets fixed the condensed
!> problem is one linear system (linear_sets_solve), which gives a semismooth Newton iteration on
!> the friction problem itself (linear_newton) and the exact end of the fixed point on the limits
!> (linear_exact). A submodule of contact2d_static: it works on static_t's condensed operator and
!> sets.
submodule(contact2d_static) contact2d_static_friction
   implicit none

contains

   !> The friction law's limits (docs/friction.md section 2) of the tangential unknowns for the
   !> nodal normal forces fn and the P0 cell multipliers mu (the contact measure: fn for P1, mu
   !> for P0, as contact2d_contact passes it).
   module procedure law_limits
      real(wp) :: limnode(this%nc)
      integer :: k
      if (.not. this%law_fp) then
         limk = this%limit
         return
      end if
      if (this%p0) then
         call this%ct%law%limits(fn, mu, limnode)
      else
         call this%ct%law%limits(fn, fn, limnode)
      end if
      do k = 1, this%nt
         limk(k) = limnode(this%cnode(this%nc + k))
      end do
   end procedure law_limits

   !> Nodal forces from lambda: F_n = T lambda_n (mu for P0), F_t per node.
   module procedure nodal_forces
      integer :: r
      if (this%p0) then
         this%mu = this%lambda(1:this%nc)
         call d_apply(this, this%mu, this%fn)
      else
         this%fn = this%lambda(1:this%nc)
         this%mu = 0
      end if
      this%ft = 0
      do r = this%nc + 1, this%m
         this%ft(this%cnode(r)) = this%lambda(r)
      end do
   end procedure nodal_forces

   !> y = D x for the contact chain (D symmetric tridiagonal, SPEC section 3).
   module procedure d_apply
      integer :: i, nc
      nc = size(x)
      y = this%ct%dd*x
      do i = 1, nc - 1
         y(i) = y(i) + this%ct%dl(i)*x(i + 1)
         y(i + 1) = y(i + 1) + this%ct%dl(i)*x(i)
      end do
   end procedure d_apply

   !> The friction limits implied by the multipliers lam (normal part first): law_limits on the
   !> nodal normal forces (P0: F_n = D^T mu_n) and the normal multipliers themselves.
   subroutine multiplier_limits(this, model, lam, limk)
      type(static_t), intent(in) :: this
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: lam(:)
      real(wp), intent(out) :: limk(:)
      real(wp) :: fnode(this%nc)
      if (this%p0) then
         call d_apply(this, lam(1:this%nc), fnode)
         call law_limits(this, model, fnode, lam(1:this%nc), limk)
      else
         call law_limits(this, model, lam(1:this%nc), lam(1:this%nc), limk)
      end if
   end subroutine multiplier_limits

   !> A law linear in F_n (Coulomb) with the sets fixed (normal active/inactive, stick, slip +-,
   !> no friction): the limits mu_i F_n,i (mu_i = fn_slopes) are linear in the normal
   !> multipliers, so the condensed problem
   !> A y + lambda = rhs with y_J = 0 (active, stick), lambda = 0 (inactive, no friction) and
   !> lambda_r = +-mu_i (T lambda_n)_i (slip; T = I for P1, D for P0) is one linear system in
   !> (y_K, lambda_J), solved with LAPACK dgesv (it is not symmetric). info /= 0: singular.
   subroutine linear_sets_solve(this, model, rhs, lam, y, info)
      type(static_t), intent(in) :: this
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: rhs(:)
      real(wp), intent(out) :: lam(:), y(:)
      integer, intent(out) :: info
      real(wp), allocatable :: mat(:, :), z(:, :)
      real(wp) :: fnode(this%nc), sg, tij
      integer, allocatable :: ipiv(:)
      integer :: k, r, i, j, m, nc
      m = this%m
      nc = this%nc
      allocate (mat(m, m), z(m, 1), ipiv(m))
      mat = 0
      do k = 1, m
         if (any(this%state(k) == [1, 3])) then
            mat(k, k) = 1
         else
            mat(:, k) = this%a(:, k)
         end if
      end do
      do r = nc + 1, m
         if (abs(this%state(r)) /= 2) cycle
         i = this%cnode(r)
         sg = sign(1.0_wp, real(this%state(r), wp))
         do j = max(i - 1, 1), min(i + 1, nc)
            if (this%state(j) /= 1) cycle
            if (i == j) then
               tij = 1
               if (this%p0) tij = this%ct%dd(i)
            else if (this%p0) then
               tij = this%ct%dl(min(i, j))
            else
               tij = 0
            end if
            mat(r, j) = mat(r, j) + sg*this%mu_coef(i)*tij
         end do
      end do
      z(:, 1) = rhs
      call dense_gesv(m, 1, mat, m, ipiv, z, m, info)
      y = 0
      lam = 0
      if (info /= 0) return
      do k = 1, m
         if (any(this%state(k) == [1, 3])) then
            lam(k) = z(k, 1)
         else
            y(k) = z(k, 1)
         end if
      end do
      if (this%p0) then
         call d_apply(this, lam(1:nc), fnode)
      else
         fnode = lam(1:nc)
      end if
      do r = nc + 1, m
         if (abs(this%state(r)) /= 2) cycle
         lam(r) = sign(1.0_wp, real(this%state(r), wp))*this%mu_coef(this%cnode(r))*fnode(this%cnode(r))
      end do
   end subroutine linear_sets_solve

   !> Semismooth Newton (active-set) iteration on the friction problem itself (limits linear in F_n): with the current
   !> sets, the exact fixed-set solution (linear_sets_solve), then the sets it implies with the
   !> limits mu F_n of its own forces; until the sets repeat (ok: every condition holds) or an
   !> earlier set comes back or max_iter is reached (not ok; lambda unchanged).
   module procedure linear_newton
      real(wp) :: lam(this%m), y(this%m), limk(this%nt)
      integer :: new_state(this%m), info, it, j
      integer, allocatable :: hist(:, :)
      stat = 0
      errmsg = ''
      ok = .false.
      nit = 0
      allocate (hist(this%m, this%max_iter))
      do it = 1, this%max_iter
         nit = it
         hist(:, it) = this%state
         call linear_sets_solve(this, model, cvec, lam, y, info)
         if (info /= 0) return
         call multiplier_limits(this, model, lam, limk)
         call classify(this%a, this%nc, lam, y, limk, ct_tries(1), new_state)
         if (debug) print '(a,i4,a,6i6)', 'ssn ', it, ' active/inactive/stick/slip+/slip-/free', &
            count(new_state == 1), count(new_state == 0), count(new_state == 3), count(new_state == 2), &
            count(new_state == -2), count(new_state == 4)
         if (all(new_state == this%state)) then
            ok = .true.
            this%lambda = lam
            call nodal_forces(this, model)
            return
         end if
         do j = 1, it
            if (all(new_state == hist(:, j))) return   ! cycling
         end do
         this%state = new_state
      end do
   end procedure linear_newton

   !> The exact solution for the current sets with limits linear in F_n (linear_sets_solve on A (y - y0) +
   !> lambda = 0), kept (ok) only if the sets it implies are the same, the limits being
   !> mu F_n of its own forces: then every condition of the condensed problem holds.
   module procedure linear_exact
      real(wp) :: lam(this%m), y(this%m), limk(this%nt)
      integer :: check(this%m), info
      stat = 0
      errmsg = ''
      ok = .false.
      call linear_sets_solve(this, model, cvec, lam, y, info)
      if (info /= 0) return   ! singular with these sets: go on with the fixed point
      call multiplier_limits(this, model, lam, limk)
      call classify(this%a, this%nc, lam, y, limk, ct_tries(1), check)
      ok = all(check == this%state)
      if (ok) then
         this%lambda = lam
         call nodal_forces(this, model)
      end if
   end procedure linear_exact
end submodule contact2d_static_friction
