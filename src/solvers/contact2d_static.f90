!> The static engine (docs/static.md): an exact solve of the paper's saddle-point
!> problem (13) on the model's mesh, multipliers and friction law, with the contact condensed
!> onto Gamma_c.
!>
!> 1. K is assembled once (sparse, from the element matrices) on the free dofs, the free dofs of
!>    the contact nodes numbered last; CHOLMOD factorises it with those dofs eliminated last, so
!>    the trailing block L22 of the factor gives the Schur complement S = L22 L22^T on them.
!> 2. In the contact unknowns y = (T (u.n - g), u.t - psi_ref) (T = I for P1, D for P0, SPEC
!>    section 3) the condensed problem is A (y - y0) + lambda = 0, A = P^T B S B^T P SPD dense,
!>    y0 the contact response of the body without contact, lambda = (P1: Lambda_n, P0: mu_n;
!>    nodal F_t), with y_n <= 0, lambda_n >= 0, y_n lambda_n = 0 and nodal Tresca
!>    |lambda_t| <= s_i w_i, lambda_t = s_i w_i sign(y_t) where y_t /= 0.
!> 3. A primal-dual active-set (semismooth Newton) iteration solves it exactly: until the active,
!>    stick and slip sets repeat (converged) or an earlier set repeats (cycling: not converged).
!> 4. u = K^-1 (f + contact forces) and the KKT residuals are checked on it.
!> With tresca_scope = 'contact' the thresholds depend on the contact state: an outer fixed point
!> on them, reported as not converged if it cycles. A law whose limits are linear in F_n
!> (Coulomb) also gets the fixed-set solves of the submodule contact2d_static_friction.
module contact2d_static
   use contact2d_kinds, only: wp, i8
   use contact2d_strings, only: str
   use contact2d_model, only: model_t
   use contact2d_contact, only: contact_t
   use contact2d_cholmod, only: cholmod_t, dense_lauum, dense_gesv
   use contact2d_pdas, only: pdas_solve, classify, max_pdas
   use contact2d_kkt, only: kkt_names, kkt_values, absmax
   implicit none
   private
   public :: static_t, static_saved_t, singular_pivot_ratio, prox_eps

   !> A pivot L_jj^2 / K_jj below this marks a singular stiffness (a free rigid-body mode).
   real(wp), parameter :: singular_pivot_ratio = 1.0e-11_wp
   !> Local node and component of each of the 8 element dofs (u1x, u1y, u2x, ...).
   integer, parameter :: node_of(8) = [1, 1, 2, 2, 3, 3, 4, 4], comp_of(8) = [1, 2, 1, 2, 1, 2, 1, 2]
   !> Fixed-point iteration limit.
   integer, parameter :: max_outer = 50
   !> The friction limits of two passes of the fixed point agree to this (relative to the largest).
   real(wp), parameter :: fp_tol = 1.0e-12_wp
   logical, parameter :: debug = .false.
   !> Tangential complementarity constants tried in turn (fractions of A_rr): with 1, the slip
   !> signs of the paper scene flip-flop from level 4 on; 0.1 settles in 9-14 iterations (levels 0-6).
   real(wp), parameter :: ct_tries(3) = [0.1_wp, 0.01_wp, 1.0_wp]
   !> Proximal weight of a body held by contact alone (docs/static.md "Bodies held by contact"):
   !> K + prox_eps diag(K) is factorised. Each pass contracts the error of the elastic modes by
   !> about prox_eps / (prox_eps + lambda), lambda / diag(K) ~ (h / L)^2 for the lowest one, while
   !> round-off along the regularised rigid motions grows like 1 / prox_eps. Measured on
   !> block_on_flat_p1: 1e-6 leaves a penetration of 1e-12 max|u| at level 1 (round-off), 1e-4
   !> takes 23 passes at level 5; 1e-5 takes 4 passes at level 1, 10 at level 5, and leaves
   !> KKT residuals of 4e-13 or less.
   real(wp), parameter :: prox_eps = 1.0e-5_wp
   !> Proximal passes: stop when the proximal force prox_eps diag(K) (u_k+1 - u_k) is below
   !> prox_tol of the force scale (it is then the only equilibrium residual), or after max_prox.
   real(wp), parameter :: prox_tol = 1.0e-14_wp
   integer, parameter :: max_prox = 200

   !> The state of an increment's start, kept so that an increment that does not settle can be
   !> taken again from there in smaller steps (static_t%save, static_t%restore).
   type :: static_saved_t
      real(wp), allocatable :: u(:, :), fext(:, :), fint(:, :), fc(:, :), lambda(:), fn(:), ft(:), mu(:)
      integer, allocatable :: state(:)
      real(wp) :: kkt(4) = 0
   end type static_saved_t

   !> The factorised, condensed problem and the state of the last increment.
   type :: static_t
      integer :: nnode = 0
      integer :: nfree = 0                 !< free dofs (order of K_ff)
      integer :: ncdof = 0                 !< free dofs of the contact nodes (numbered last)
      !> the contact operator of the model's one pair (inactive without contact); the engine
      !> condenses onto one chain of contact unknowns, so the deck refuses several pairs with
      !> solver:method = 'static' (contact2d_deck)
      type(contact_t) :: ct
      integer :: nc = 0                    !< contact nodes (normal unknowns)
      integer :: nt = 0                    !< tangential unknowns
      integer :: m = 0                     !< nc + nt
      logical :: p0 = .false.
      !> the law's limits are slope_i F_n,i (law%linear_in_fn: Coulomb): fixed-set solves and
      !> the semismooth Newton step on the friction problem itself
      logical :: linear = .false.
      logical :: law_fp = .false.          !< limits depend on the forces: fixed point (not law%fixed)
      real(wp), allocatable :: mu_coef(:)  !< slope_i = d limit_i / d F_n,i per contact node (0 unless linear)
      integer, allocatable :: dof(:, :)    !< free-dof index of (component, node), 0 if prescribed
      integer, allocatable :: cnode(:)     !< contact index of each unknown (m)
      real(wp), allocatable :: bdir(:, :)  !< unknown direction (n or t) (2, m)
      real(wp), allocatable :: a(:, :)     !< condensed operator A (m, m) [N/mm]
      !> the law's limits with every node in contact at zero normal force, per tangential unknown
      !> (nt) [N]: a fixed law's limits (Tresca s_i w_i), the start of the fixed point otherwise
      real(wp), allocatable :: limit(:)
      !> proximal weights prox_eps diag(K_ff) per free dof (nfree) when a rigid motion of the body
      !> is not fixed by its supports (model%unsupported), else not allocated [N/mm]
      real(wp), allocatable :: dreg(:)
      integer :: prox_iterations = 0       !< proximal passes, all increments
      type(cholmod_t) :: chol
      ! state
      real(wp), allocatable :: u(:, :)     !< displacement (2, nnode) [mm]
      real(wp), allocatable :: fext(:, :)  !< tractions (2, nnode) [N]
      real(wp), allocatable :: fint(:, :)  !< K u (2, nnode) [N]
      real(wp), allocatable :: fc(:, :)    !< contact force on the body (2, nnode) [N]
      real(wp), allocatable :: lambda(:)   !< (mu_n or Lambda_n; F_t) (m)
      integer, allocatable :: state(:)     !< set of each unknown (m): see pdas
      real(wp), allocatable :: fn(:), ft(:), mu(:)   !< nodal F_n, F_t and P0 mu per contact node
      real(wp) :: kkt(4) = 0               !< KKT residuals of the last increment (kkt_names)
      integer :: iterations = 0            !< PDAS iterations, all increments
      !> active-set iterations one solve may take before the increment counts as not settled
      integer :: max_iter = max_pdas
      integer :: outer_iterations = 0      !< threshold fixed-point iterations, all increments
      real(wp) :: time_factor = 0          !< assembly and factorisation [s]
      real(wp) :: time_condense = 0        !< Schur complement and A [s]
      real(wp) :: time_pdas = 0            !< increments: solves and PDAS [s]
   contains
      procedure :: setup => static_setup
      procedure :: increment => static_increment
      procedure :: save => static_save
      procedure :: restore => static_restore
      procedure :: free => static_free
   end type static_t

   interface
      !> Semismooth Newton iteration on the friction problem with limits linear in F_n, from the
      !> current sets (contact2d_static_friction). ok: every condition holds, lambda and the nodal
      !> forces set; not ok: cycling or max_iter reached, lambda unchanged.
      module subroutine linear_newton(this, model, cvec, nit, ok, stat, errmsg)
         type(static_t), intent(inout) :: this
         type(model_t), intent(in) :: model
         real(wp), intent(in) :: cvec(:)
         integer, intent(out) :: nit
         logical, intent(out) :: ok
         integer, intent(out) :: stat
         character(len=:), allocatable, intent(out) :: errmsg
      end subroutine linear_newton

      !> The exact solution for the current sets with limits linear in F_n, kept (ok) only if the
      !> sets it implies are the same (contact2d_static_friction).
      module subroutine linear_exact(this, model, cvec, ok, stat, errmsg)
         type(static_t), intent(inout) :: this
         type(model_t), intent(in) :: model
         real(wp), intent(in) :: cvec(:)
         logical, intent(out) :: ok
         integer, intent(out) :: stat
         character(len=:), allocatable, intent(out) :: errmsg
      end subroutine linear_exact

      !> y = D x for the contact chain (D symmetric tridiagonal, SPEC section 3).
      module subroutine d_apply(this, x, y)
         class(static_t), intent(in) :: this
         real(wp), intent(in) :: x(:)
         real(wp), intent(out) :: y(:)
      end subroutine d_apply

      !> The friction law's limits of the tangential unknowns for the nodal normal forces fn and
      !> the P0 cell multipliers mu (contact2d_static_friction).
      module subroutine law_limits(this, model, fn, mu, limk)
         type(static_t), intent(in) :: this
         type(model_t), intent(in) :: model
         real(wp), intent(in) :: fn(:), mu(:)
         real(wp), intent(out) :: limk(:)
      end subroutine law_limits

      !> Nodal forces from lambda: F_n = T lambda_n (mu for P0), F_t per node.
      module subroutine nodal_forces(this, model)
         type(static_t), intent(inout) :: this
         type(model_t), intent(in) :: model
      end subroutine nodal_forces
   end interface

contains

   !> Number the dofs, assemble and factorise K, condense onto the contact unknowns.
   !> stat 1: a singular stiffness or a model the engine cannot honour (one-line errmsg).
   subroutine static_setup(this, model, stat, errmsg)
      class(static_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp), allocatable :: l22(:, :)
      integer, allocatable :: order(:)
      integer(i8) :: t0, t1, rate

      call system_clock(t0, rate)
      stat = 1
      errmsg = ''
      if (size(model%contacts) > 0) this%ct = model%contacts(1)
      if (this%ct%active .and. this%ct%penalty) then
         errmsg = "the static engine solves the multiplier problem (13); contact:method = 'penalty' "// &
                  "is not supported with solver:method = 'static'"
         return
      end if
      call setup_numbering(this, model, stat, errmsg)
      if (stat /= 0) return
      call setup_factor(this, model, stat, errmsg)
      if (stat /= 0) return
      call system_clock(t1)
      this%time_factor = real(t1 - t0, wp)/rate
      t0 = t1

      ! A = P^T B S B^T P from S = L22 L22^T
      if (this%m > 0) then
         allocate (l22(this%ncdof, this%ncdof))
         allocate (order(this%ncdof))
         call this%chol%trailing(l22, order)
         call condense(this, model, l22, order, stat, errmsg)
         if (stat /= 0) return
      end if
      allocate (this%u(2, this%nnode), this%fext(2, this%nnode), this%fint(2, this%nnode), &
                this%fc(2, this%nnode), this%lambda(this%m), this%state(this%m), &
                this%fn(this%nc), this%ft(this%nc), this%mu(this%nc))
      this%u = 0
      this%fext = 0
      this%fint = 0
      this%fc = 0
      this%lambda = 0
      this%state = -99       ! no state yet: the first increment starts from lambda = 0
      this%fn = 0
      this%ft = 0
      this%mu = 0
      call system_clock(t1)
      this%time_condense = real(t1 - t0, wp)/rate
      stat = 0
   end subroutine static_setup

   !> The numbering: free dofs of the interior first, then those of the contact nodes along
   !> Gamma_c (so that CHOLMOD eliminates them last and L22 gives their Schur complement), and
   !> the contact unknowns (the normal of every contact node, then the tangent where both of its
   !> dofs are free) with their directions and Tresca limits. stat 1: a contact node with a
   !> prescribed dof that is neither its normal nor its tangent.
   subroutine setup_numbering(this, model, stat, errmsg)
      class(static_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer :: k, c, i, n, nint, ncd
      logical, allocatable :: is_contact(:)
      real(wp), allocatable :: zero(:), closed(:), limnode(:)

      stat = 1
      errmsg = ''
      this%nnode = model%mesh%nnode
      associate (free => model%load%free, ct => this%ct)
         allocate (this%dof(2, this%nnode), is_contact(this%nnode))
         is_contact = .false.
         if (ct%active) is_contact(ct%node) = .true.
         this%dof = 0
         ! interior free dofs first, then the contact dofs node by node along Gamma_c
         nint = 0
         do n = 1, this%nnode
            if (is_contact(n)) cycle
            do c = 1, 2
               if (free(c, n) > 0) then
                  nint = nint + 1
                  this%dof(c, n) = nint
               end if
            end do
         end do
         ncd = 0
         this%nc = 0
         this%nt = 0
         if (ct%active) then
            this%nc = ct%nc
            this%p0 = ct%multiplier_name() == 'P0'
            if (ct%friction) then
               this%linear = ct%law%linear_in_fn()
               this%law_fp = .not. ct%law%fixed
            end if
            do i = 1, ct%nc
               n = ct%node(i)
               do c = 1, 2
                  if (free(c, n) > 0) then
                     ncd = ncd + 1
                     this%dof(c, n) = nint + ncd
                  end if
               end do
               if (all(free(:, n) > 0)) this%nt = this%nt + 1
            end do
         end if
         allocate (this%mu_coef(this%nc))
         this%mu_coef = 0
         if (this%linear) call ct%law%fn_slopes(this%mu_coef)
         this%ncdof = ncd
         this%nfree = nint + ncd
         this%m = this%nc + this%nt
         ! the unknowns: normal of every contact node, then tangential where both dofs are free
         allocate (this%cnode(this%m), this%bdir(2, this%m), this%limit(this%nt))
         ! the law's own limits (friction_law_t%limits, docs/friction.md section 2) with every
         ! node closed and no normal force: what a fixed law gives at every step
         allocate (zero(this%nc), closed(this%nc), limnode(this%nc))
         zero = 0
         closed = 1
         limnode = 0
         if (ct%active .and. ct%friction) call ct%law%limits(zero, closed, limnode)
         k = this%nc
         do i = 1, this%nc
            this%cnode(i) = i
            this%bdir(:, i) = ct%normal(:, i)
            if (all(free(:, ct%node(i)) > 0)) then
               k = k + 1
               this%cnode(k) = i
               this%bdir(:, k) = ct%tangent(:, i)
               this%limit(k - this%nc) = limnode(i)
            end if
         end do
         if (this%m /= this%ncdof) then
            errmsg = 'static engine: a contact node has a prescribed dof that is neither its normal nor its '// &
                     'tangential direction'
            return
         end if
      end associate
      stat = 0
   end subroutine setup_numbering

   !> The factorisation: K_ff assembled from the element matrices (lower triangle, as triplets)
   !> and factorised by CHOLMOD with the contact dofs last, each dof grouped with its node and
   !> placed at its coordinates for the ordering. stat 1: nothing to solve or a singular K_ff
   !> (a free rigid-body mode).
   subroutine setup_factor(this, model, stat, errmsg)
      class(static_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer :: k, c, n, nnz, e, a, b, ia, ib
      integer, allocatable :: ti(:), tj(:), group(:)
      real(wp), allocatable :: tx(:), xy(:, :)
      logical :: prox

      stat = 1
      errmsg = ''
      ! a body held by contact alone: K_ff + prox_eps diag(K_ff), the proximal operator
      prox = model%unsupported%nfree > 0
      if (prox) then
         allocate (this%dreg(this%nfree))
         this%dreg = 0
      end if
      ! K_ff from the element matrices, lower triangle (row >= column)
      nnz = 0
      do e = 1, model%mesh%nel
         do a = 1, 8
            ia = this%dof(comp_of(a), model%mesh%conn(node_of(a), e))
            if (ia == 0) cycle
            do b = 1, 8
               ib = this%dof(comp_of(b), model%mesh%conn(node_of(b), e))
               if (ib > 0 .and. ib <= ia) nnz = nnz + 1
            end do
         end do
      end do
      allocate (ti(nnz), tj(nnz), tx(nnz))
      k = 0
      do e = 1, model%mesh%nel
         associate (ke => model%stiff%ke(:, :, model%stiff%shape_of(e)))
            do a = 1, 8
               ia = this%dof(comp_of(a), model%mesh%conn(node_of(a), e))
               if (ia == 0) cycle
               do b = 1, 8
                  ib = this%dof(comp_of(b), model%mesh%conn(node_of(b), e))
                  if (ib > 0 .and. ib <= ia) then
                     k = k + 1
                     ti(k) = ia
                     tj(k) = ib
                     tx(k) = ke(a, b)
                     if (prox .and. ia == ib) then
                        tx(k) = tx(k) + prox_eps*ke(a, b)
                        this%dreg(ia) = this%dreg(ia) + prox_eps*ke(a, b)
                     end if
                  end if
               end do
            end do
         end associate
      end do
      if (this%nfree == 0) then
         errmsg = 'static engine: every dof is prescribed; nothing to solve'
         return
      end if
      allocate (group(this%nfree))
      do n = 1, this%nnode
         do c = 1, 2
            if (this%dof(c, n) > 0) group(this%dof(c, n)) = n
         end do
      end do
      allocate (xy(2, this%nfree))
      do k = 1, this%nfree
         xy(:, k) = model%mesh%x(:, group(k))
      end do
      call this%chol%factor(this%nfree, ti, tj, tx, this%ncdof, group, stat, errmsg, xy=xy)
      deallocate (ti, tj, tx)
      if (stat == 2 .or. (stat == 0 .and. this%chol%pivot_ratio < singular_pivot_ratio)) then
         stat = 1
         errmsg = 'the stiffness matrix with the Dirichlet data is singular (a rigid-body mode is free; '// &
                  'smallest pivot / diagonal = '//str(this%chol%pivot_ratio)// &
                  '): the static engine needs Dirichlet data that hold the body without contact'
         return
      end if
   end subroutine setup_factor

   !> S = L22 L22^T (LAPACK dlauum on the index-reversed factor), then A = P^T B S B^T P:
   !> B rotates each contact node's free dofs to (n, t), P = diag(D^-1, I) for P0 (I for P1).
   subroutine condense(this, model, l22, order, stat, errmsg)
      type(static_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      real(wp), allocatable, intent(inout) :: l22(:, :)
      integer, intent(in) :: order(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp), allocatable :: s(:, :), w(:, :), dd(:), dl(:), tr(:, :)
      integer :: nl, i, j, r, c, n, info
      external :: dpttrf, dpttrs

      nl = this%ncdof
      ! U = J L22 J is upper triangular; U U^T = J L22 L22^T J
      l22 = l22(nl:1:-1, nl:1:-1)
      call dense_lauum('U', nl, l22, nl, info)
      if (info /= 0) then
         stat = 2
         errmsg = 'LAPACK dlauum failed (info = '//str(info)//')'
         return
      end if
      ! back to the trailing dofs' own order: S(order(a), order(b)) = (L22 L22^T)(a, b)
      allocate (s(nl, nl))
      do j = 1, nl
         do i = 1, j
            s(order(nl + 1 - i), order(nl + 1 - j)) = l22(i, j)
            s(order(nl + 1 - j), order(nl + 1 - i)) = l22(i, j)
         end do
      end do
      deallocate (l22)
      ! W = B S (row r of B: bdir(:, r) on the free dofs of its node), then A = W B^T
      allocate (w(this%m, nl), this%a(this%m, this%m))
      w = 0
      do r = 1, this%m
         n = this%ct%node(this%cnode(r))
         do c = 1, 2
            i = this%dof(c, n)
            if (i > 0) w(r, :) = w(r, :) + this%bdir(c, r)*s(i - (this%nfree - nl), :)
         end do
      end do
      this%a = 0
      do r = 1, this%m
         n = this%ct%node(this%cnode(r))
         do c = 1, 2
            i = this%dof(c, n)
            if (i > 0) this%a(:, r) = this%a(:, r) + this%bdir(c, r)*w(:, i - (this%nfree - nl))
         end do
      end do
      deallocate (w, s)
      if (this%p0) then
         ! A_nn = D^-1 Shat_nn D^-1, A_nt = D^-1 Shat_nt (D symmetric positive definite tridiagonal)
         dd = this%ct%dd
         dl = this%ct%dl
         call dpttrf(this%nc, dd, dl, info)
         if (info /= 0) then
            stat = 2
            errmsg = 'LAPACK dpttrf failed on D (info = '//str(info)//')'
            return
         end if
         tr = this%a(1:this%nc, :)
         call dpttrs(this%nc, this%m, dd, dl, tr, this%nc, info)
         this%a(1:this%nc, :) = tr
         tr = transpose(this%a(:, 1:this%nc))
         call dpttrs(this%nc, this%m, dd, dl, tr, this%nc, info)
         this%a(:, 1:this%nc) = transpose(tr)
      end if
      ! exact symmetry
      this%a = 0.5_wp*(this%a + transpose(this%a))
      stat = 0
      errmsg = ''
   end subroutine condense

   !> One load increment: the loads and prescribed values of time t, friction acting on the
   !> tangential displacement since the last increment. converged = .false. when the PDAS or the
   !> threshold fixed point cycles or runs out of iterations (the state is then the last iterate).
   !> stat /= 0 only on a numerical failure.
   subroutine static_increment(this, model, t, converged, message, stat, errmsg)
      class(static_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: t
      logical, intent(out) :: converged
      character(len=:), allocatable, intent(out) :: message
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp), allocatable :: up(:, :), f(:), x(:), cvec(:), uprev(:, :), fn_last(:), mu_last(:)
      integer(i8) :: t0, t1, rate

      call system_clock(t0, rate)
      stat = 0
      errmsg = ''
      message = ''
      converged = .true.
      uprev = this%u
      call increment_loads(this, model, t, up, f, x, stat, errmsg)
      if (stat /= 0) return

      fn_last = this%fn
      mu_last = this%mu
      if (allocated(this%dreg)) then
         call increment_proximal(this, model, f, up, uprev, fn_last, mu_last, converged, message, stat, errmsg)
         if (stat /= 0) return
         call kkt_residuals(this, model, uprev)
         call system_clock(t1)
         this%time_pdas = this%time_pdas + real(t1 - t0, wp)/rate
         return
      end if
      this%fn = 0
      this%ft = 0
      this%mu = 0
      this%fc = 0
      if (this%m > 0) then
         call increment_condensed_rhs(this, model, x, uprev, cvec)
         call increment_sets(this, model, cvec, fn_last, mu_last, converged, message, stat, errmsg)
         if (stat /= 0) return
      end if
      ! one solve: u = K^-1 (f + F_c). The condensed operator and this solve come from the same
      ! factor, so the KKT residuals of u are at round-off level without refinement (docs/static.md
      ! step 5: iterative refinement of u and of the multipliers changed u by at most 2.4e-11
      ! relative at level 6 and did not lower the residuals)
      call displacement(this, model, f, up, stat)
      if (stat /= 0) then
         errmsg = 'CHOLMOD solve failed'
         return
      end if
      call kkt_residuals(this, model, uprev)
      call system_clock(t1)
      this%time_pdas = this%time_pdas + real(t1 - t0, wp)/rate
   end subroutine static_increment

   !> A body held by contact alone (docs/static.md "Bodies held by contact"): the proximal point
   !> iteration (K + E) u_k+1 = f + E u_k + F_c(lambda_k+1), E = prox_eps diag(K_ff), from u_0
   !> and lambda_0 the state of the last increment, each pass the whole contact problem
   !> (increment_sets) on the regularised operator. It is solved in correction form, so that no
   !> vector carries the large rigid response (load / E) of the body without contact:
   !>   r_k = f - K_ff u_k + F_c(lambda_k),  du = (K + E)^-1 (r_k + F_c(lambda_k+1) - F_c(lambda_k)),
   !> whose contact unknowns give A (y - y0) + lambda_k+1 = 0 with A y0 = A y(u_k + (K + E)^-1 r_k)
   !> + lambda_k (A the condensed operator of K + E). At a fixed point E du = 0 and u solves
   !> K u = f + F_c: the proximal term vanishes, and the KKT residuals (with K itself) prove the
   !> end state. Stops when the proximal force E du is below prox_tol of the force scale, or when
   !> it no longer falls (round-off) and is below 1e-12 of it; otherwise not converged.
   subroutine increment_proximal(this, model, f, up, uprev, fn_last, mu_last, converged, message, stat, errmsg)
      class(static_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: f(:), up(:, :), uprev(:, :), fn_last(:), mu_last(:)
      logical, intent(inout) :: converged
      character(len=:), allocatable, intent(inout) :: message
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp), allocatable :: r(:), du(:), xk(:), cvec(:), v(:, :), kv(:, :), fcv(:), fnk(:), muk(:), lambda_k(:)
      real(wp) :: prox, prox_best, scale
      integer :: pass, n, c, i, stale

      allocate (r(this%nfree), du(this%nfree), xk(this%nfree), fcv(this%nfree), v(2, this%nnode), kv(2, this%nnode))
      prox_best = huge(1.0_wp)
      stale = 0
      fnk = fn_last
      muk = mu_last
      do pass = 1, max_prox
         this%prox_iterations = this%prox_iterations + 1
         ! u_k on the free dofs (0 on the prescribed ones) and r_k = f - K_ff u_k + F_c(lambda_k)
         v = 0
         do n = 1, this%nnode
            do c = 1, 2
               if (this%dof(c, n) > 0) v(c, n) = this%u(c, n)
            end do
         end do
         call model%stiff%apply(v, kv)
         call contact_force_vector(this, model, fcv)
         do n = 1, this%nnode
            do c = 1, 2
               i = this%dof(c, n)
               if (i > 0) then
                  xk(i) = v(c, n)
                  r(i) = f(i) - kv(c, n) + fcv(i)
               end if
            end do
         end do
         call this%chol%solve(r, du, stat)
         if (stat /= 0) then
            errmsg = 'CHOLMOD solve failed'
            return
         end if
         if (this%m > 0) then
            ! the contact problem of the pass: y0 from u_k + (K + E)^-1 r_k, shifted by lambda_k
            lambda_k = this%lambda
            call increment_condensed_rhs(this, model, xk + du, uprev, cvec)
            cvec = cvec + lambda_k
            call increment_sets(this, model, cvec, fnk, muk, converged, message, stat, errmsg)
            if (stat /= 0 .or. .not. converged) return
            fnk = this%fn
            muk = this%mu
            ! du += (K + E)^-1 (F_c(lambda_k+1) - F_c(lambda_k))
            r = -fcv
            call contact_force_vector(this, model, fcv)
            r = r + fcv
            call this%chol%solve(r, xk, stat)
            if (stat /= 0) then
               errmsg = 'CHOLMOD solve failed'
               return
            end if
            du = du + xk
         end if
         ! u_k+1 = u_k + du on the free dofs, the prescribed values of this increment elsewhere
         prox = 0
         do n = 1, this%nnode
            do c = 1, 2
               i = this%dof(c, n)
               if (i > 0) then
                  this%u(c, n) = v(c, n) + du(i)
                  prox = max(prox, abs(this%dreg(i)*du(i)))
               else
                  this%u(c, n) = up(c, n)
               end if
            end do
         end do
         call model%stiff%apply(this%u, this%fint)
         ! the proximal force E (u_k+1 - u_k) against the forces acting on the body
         scale = max(maxval(abs(this%fext)), maxval(abs(this%fc)), maxval(abs(this%fint)), tiny(1.0_wp))
         if (debug) print '(a,i4,es12.4)', 'prox', pass, prox/scale
         if (prox <= prox_tol*scale) return
         if (prox < 0.5_wp*prox_best) then
            prox_best = prox
            stale = 0
         else
            stale = stale + 1
            ! round-off: the iterate no longer moves by more than a rounding error
            if (stale >= 3 .and. prox <= 1.0e-12_wp*scale) return
         end if
      end do
      converged = .false.
      message = 'the proximal iteration on the rigid motions of the body (held by contact alone) did not '// &
                'settle in '//str(max_prox)//' passes'
   end subroutine increment_proximal

   !> The contact force on the body of the nodal forces F_n, F_t (this%fn, this%ft): this%fc
   !> (2, nnode) and its free-dof vector fcv (nfree).
   subroutine contact_force_vector(this, model, fcv)
      class(static_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      real(wp), intent(out) :: fcv(:)
      integer :: i, n, c
      this%fc = 0
      fcv = 0
      do i = 1, this%nc
         n = this%ct%node(i)
         do c = 1, 2
            if (this%dof(c, n) > 0) then
               this%fc(c, n) = -this%fn(i)*this%ct%normal(c, i) - this%ft(i)*this%ct%tangent(c, i)
               fcv(this%dof(c, n)) = this%fc(c, n)
            end if
         end do
      end do
   end subroutine contact_force_vector

   !> The loads of time t: up the prescribed values, this%fext the tractions, f = f_ext - K u_p
   !> on the free dofs, and x = K_ff^-1 f, the body's response without contact (docs/static.md
   !> step 2's y0 comes from it). stat /= 0: the CHOLMOD solve failed.
   subroutine increment_loads(this, model, t, up, f, x, stat, errmsg)
      class(static_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: t
      real(wp), allocatable, intent(out) :: up(:, :), f(:), x(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp), allocatable :: ku(:, :)
      real(wp) :: cv(model%load%ncurve)
      integer :: p, n, c

      errmsg = ''
      ! loads and prescribed values at t; f = tractions - K u_p on the free dofs
      call model%load%curve_values(t, cv)
      allocate (up(2, this%nnode), ku(2, this%nnode))
      up = 0
      do p = 1, model%load%npres
         up(model%load%pcomp(p), model%load%pnode(p)) = cv(model%load%pcurve(p))
      end do
      this%fext = 0
      do p = 1, model%load%ntrac
         this%fext(model%load%tcomp(p), model%load%tnode(p)) = this%fext(model%load%tcomp(p), model%load%tnode(p)) + &
                                                               cv(model%load%tcurve(p))*model%load%tweight(p)
      end do
      call model%stiff%apply(up, ku)
      allocate (f(this%nfree), x(this%nfree))
      do n = 1, this%nnode
         do c = 1, 2
            if (this%dof(c, n) > 0) f(this%dof(c, n)) = this%fext(c, n) - ku(c, n)
         end do
      end do
      ! the body's response without contact
      call this%chol%solve(f, x, stat)
      if (stat /= 0) then
         errmsg = 'CHOLMOD solve failed'
         return
      end if
   end subroutine increment_loads

   !> The condensed right-hand side cvec = A y0, y0 = (T (q0_n - g), q0_t - psi_ref) the contact
   !> unknowns of the response x without contact (T = D for P0, I for P1, SPEC §3; psi_ref the
   !> tangential displacement of the last increment uprev, from which friction acts).
   subroutine increment_condensed_rhs(this, model, x, uprev, cvec)
      class(static_t), intent(in) :: this
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: x(:), uprev(:, :)
      real(wp), allocatable, intent(out) :: cvec(:)
      real(wp), allocatable :: y0(:), qn(:), psi_ref(:)
      integer :: r, n, c

      ! y0 = (T (q0_n - g), q0_t - psi_ref)
      allocate (y0(this%m), qn(this%nc), psi_ref(this%nt))
      do r = 1, this%m
         n = this%ct%node(this%cnode(r))
         y0(r) = 0
         do c = 1, 2
            if (this%dof(c, n) > 0) y0(r) = y0(r) + this%bdir(c, r)*x(this%dof(c, n))
         end do
      end do
      do r = this%nc + 1, this%m
         psi_ref(r - this%nc) = dot_product(this%bdir(:, r), uprev(:, this%ct%node(this%cnode(r))))
      end do
      qn = y0(1:this%nc) - this%ct%gap
      if (this%p0) then
         call d_apply(this, qn, y0(1:this%nc))
      else
         y0(1:this%nc) = qn
      end if
      y0(this%nc + 1:) = y0(this%nc + 1:) - psi_ref
      allocate (cvec(this%m))
      cvec = matmul(this%a, y0)
   end subroutine increment_condensed_rhs

   !> The active-set loop: the PDAS solve of the condensed problem (tangential constants tried
   !> in turn, then for Coulomb the semismooth Newton iteration), inside the fixed point on the
   !> friction limits when they depend on the contact forces. Sets lambda, the state and the nodal
   !> forces; converged = .false. with a message when a loop cycles or does not settle.
   subroutine increment_sets(this, model, cvec, fn_last, mu_last, converged, message, stat, errmsg)
      class(static_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: cvec(:), fn_last(:), mu_last(:)
      logical, intent(inout) :: converged
      character(len=:), allocatable, intent(inout) :: message
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp), allocatable :: lim(:), lim_new(:), hist(:, :), ysol(:)
      real(wp) :: scale
      integer, allocatable :: state_prev(:), state_first(:)
      integer :: i, iouter, nit, k, itry
      logical :: done, pdas_ok, ok_exact

      allocate (ysol(this%m))
      ! thresholds: Tresca's s_i w_i; with Coulomb (mu F_n,i) or tresca_scope = 'contact' (none
      ! where the node is out of contact) they depend on the contact forces: a fixed point on
      ! them (docs/static.md "Coulomb friction and tresca_scope = 'contact'")
      allocate (lim(this%nt), lim_new(this%nt), hist(this%nt, max_outer), state_prev(this%m))
      if (this%linear) then
         ! warm start: the limits of the last increment's forces (none at the first)
         call law_limits(this, model, fn_last, mu_last, lim)
      else
         lim = this%limit
      end if
      state_prev = -99
      done = .false.
      do iouter = 1, max_outer
         this%outer_iterations = this%outer_iterations + 1
         ! a cycle restarts the iteration from 'all in contact, all stuck' with a smaller
         ! tangential constant (docs/static.md)
         do itry = 1, size(ct_tries)
            if (itry > 1) this%state = -99
            call pdas_solve(this%a, this%nc, cvec, lim, ct_tries(itry), this%max_iter, this%state, this%lambda, &
                            ysol, nit, pdas_ok, stat, errmsg)
            this%iterations = this%iterations + nit
            if (stat /= 0) return
            if (pdas_ok) exit
            if (itry == 1) state_first = this%state
         end do
         if (.not. pdas_ok .and. this%linear) then
            ! Coulomb: the Tresca subproblem's active-set iteration cycles; a semismooth Newton
            ! iteration on the Coulomb problem itself, from the first try's sets
            this%state = state_first
            call linear_newton(this, model, cvec, nit, pdas_ok, stat, errmsg)
            this%iterations = this%iterations + nit
            if (stat /= 0) return
            if (pdas_ok) then
               done = .true.
               exit
            end if
         end if
         if (.not. pdas_ok) then
            converged = .false.
            message = 'the active-set iteration cycled or did not settle in '//str(this%max_iter)// &
                      ' iterations (solver:static_iterations)'
            exit
         end if
         call nodal_forces(this, model)
         if (.not. this%law_fp) then
            done = .true.
            exit
         end if
         hist(:, iouter) = lim
         call law_limits(this, model, this%fn, this%mu, lim_new)
         if (debug) then
            do k = 1, this%nt
               if (lim_new(k) /= lim(k)) print '(a,i4,i5,4es12.4)', 'fp', iouter, k, lim(k), lim_new(k), &
                  this%mu(this%cnode(this%nc + k)), this%fn(this%cnode(this%nc + k))
            end do
         end if
         scale = max(absmax(lim_new), absmax(lim), tiny(1.0_wp))
         ! Coulomb: once the sets repeat (or the limits have settled), the fixed point of the
         ! limits with these sets is one linear solve; it is the answer if the sets hold
         if (this%linear .and. (all(this%state == state_prev) .or. &
                                 absmax(lim_new - lim) <= fp_tol*scale)) then
            call linear_exact(this, model, cvec, ok_exact, stat, errmsg)
            if (stat /= 0) return
            if (ok_exact) then
               done = .true.
               exit
            end if
         end if
         if (absmax(lim_new - lim) <= fp_tol*scale) then
            done = .true.
            exit
         end if
         do i = 1, iouter - 1
            if (absmax(lim_new - hist(:, i)) <= fp_tol*scale) exit
         end do
         if (i <= iouter - 1) then
            converged = .false.
            message = 'the fixed point on the friction limits ('//trim(this%ct%law%name())// &
                      ') cycles (period '//str(iouter + 1 - i)//')'
            exit
         end if
         state_prev = this%state
         lim = lim_new
      end do
      if (.not. done .and. converged) then
         converged = .false.
         message = 'the fixed point on the friction limits did not settle in '//str(max_outer)//' passes'
      end if
      if (.not. pdas_ok) call nodal_forces(this, model)
   end subroutine increment_sets

   !> u = K^-1 (f0 + contact forces) on the free dofs, up on the prescribed ones; fc and fint
   !> (element by element) follow.
   subroutine displacement(this, model, f0, up, stat)
      type(static_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: f0(:), up(:, :)
      integer, intent(out) :: stat
      real(wp) :: f(this%nfree), x(this%nfree)
      integer :: i, n, c
      this%fc = 0
      do i = 1, this%nc
         n = this%ct%node(i)
         do c = 1, 2
            if (this%dof(c, n) > 0) this%fc(c, n) = -this%fn(i)*this%ct%normal(c, i) - &
                                                     this%ft(i)*this%ct%tangent(c, i)
         end do
      end do
      this%u = up
      f = f0
      do n = 1, this%nnode
         do c = 1, 2
            if (this%dof(c, n) > 0) f(this%dof(c, n)) = f(this%dof(c, n)) + this%fc(c, n)
         end do
      end do
      call this%chol%solve(f, x, stat)
      if (stat /= 0) return
      do n = 1, this%nnode
         do c = 1, 2
            if (this%dof(c, n) > 0) this%u(c, n) = this%u(c, n) + x(this%dof(c, n))
         end do
      end do
      call model%stiff%apply(this%u, this%fint)
   end subroutine displacement

   !> The KKT residuals of the state (kkt_values), from the full displacement u and u_prev, the
   !> displacement at the start of the increment.
   subroutine kkt_residuals(this, model, uprev)
      type(static_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: uprev(:, :)
      real(wp) :: d(this%nc), e(this%nc), lam(this%nc), limk(this%nt), ftk(this%nt), psi(this%nt)
      integer :: i, n, k

      if (this%nc > 0) then
         do i = 1, this%nc
            d(i) = dot_product(this%u(:, this%ct%node(i)), this%ct%normal(:, i)) - this%ct%gap(i)
         end do
         if (this%p0) then
            call d_apply(this, d, e)
            e = e/this%ct%weight
            lam = this%mu
         else
            e = d
            lam = this%fn
         end if
         ! the limits of the final forces (Tresca s_i w_i; Coulomb mu F_n,i; tresca_scope =
         ! 'contact': none out of contact), so a node without a limit must carry no F_t
         call law_limits(this, model, this%fn, this%mu, limk)
         do k = 1, this%nt
            i = this%cnode(this%nc + k)
            n = this%ct%node(i)
            ftk(k) = this%ft(i)
            psi(k) = dot_product(this%u(:, n) - uprev(:, n), this%ct%tangent(:, i))
         end do
      end if
      this%kkt = kkt_values(this%u, e, lam, ftk, limk, psi, this%fext, this%fc, this%fint, this%dof > 0)
   end subroutine kkt_residuals

   !> Keep the state of the last increment (the start of the next one).
   subroutine static_save(this, saved)
      class(static_t), intent(in) :: this
      type(static_saved_t), intent(inout) :: saved
      saved%u = this%u
      saved%fext = this%fext
      saved%fint = this%fint
      saved%fc = this%fc
      saved%lambda = this%lambda
      saved%fn = this%fn
      saved%ft = this%ft
      saved%mu = this%mu
      saved%state = this%state
      saved%kkt = this%kkt
   end subroutine static_save

   !> Go back to a kept state: the next increment starts from it as from the increment that
   !> made it (warm-started sets and multipliers, friction on the displacement since it).
   subroutine static_restore(this, saved)
      class(static_t), intent(inout) :: this
      type(static_saved_t), intent(in) :: saved
      this%u = saved%u
      this%fext = saved%fext
      this%fint = saved%fint
      this%fc = saved%fc
      this%lambda = saved%lambda
      this%fn = saved%fn
      this%ft = saved%ft
      this%mu = saved%mu
      this%state = saved%state
      this%kkt = saved%kkt
   end subroutine static_restore

   subroutine static_free(this)
      class(static_t), intent(inout) :: this
      call this%chol%free()
   end subroutine static_free
end module contact2d_static
