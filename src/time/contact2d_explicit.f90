!> Central-difference time integration with mass-proportional damping and the forward-increment
!> contact step (SPEC sections 4, 5, 6).
!>
!> One step, from u^n and v^(n-1/2):
!>   1. f_int = K u^n, f_ext(t_n)
!>   2. predictor  v* = ((1 - a dt/2) v + dt M^-1 (f_ext - f_int)) / (1 + a dt/2),  u~ = u^n + dt v*
!>      prescribed dofs take their value at t_(n+1)
!>   3. contact forces F_c chosen so that u^(n+1) = u~ + c M^-1 F_c meets the constraints
!>   4. v^(n+1/2) = (u^(n+1) - u^n)/dt, energies of SPEC section 6.
!> The step does no I/O and no allocation.
module contact2d_explicit
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use contact2d_kinds, only: wp, i8
   use contact2d_stiffness, only: stiffness_t, omp_min_nodes
   use contact2d_loading, only: loading_t
   use contact2d_contact, only: contact_t
   implicit none
   private
   public :: explicit_t, damping_none, damping_given, damping_auto

   integer, parameter :: damping_none = 0, damping_given = 1, damping_auto = 2

   !> Kinetic energy above this multiple of the absolute work put in means the run blew up.
   real(wp), parameter :: blowup_ratio = 1.0e3_wp
   !> Nodes per block of the node loops (fixed, so sums do not depend on the thread count).
   integer, parameter :: block_size = 1024

   !> State and settings of the explicit integrator.
   type :: explicit_t
      integer :: nnode = 0
      real(wp) :: dt = 0                   !< time step [s]
      real(wp) :: alpha = 0                !< current mass-proportional damping [1/s]
      real(wp) :: alpha_next = 0           !< damping from the next step on (automatic damping)
      integer :: damping = damping_none    !< damping mode
      integer :: damping_interval = 20     !< steps between omega_1 estimates (auto)
      integer(i8) :: step = 0              !< steps done
      real(wp) :: time = 0                 !< t_n [s]
      real(wp), allocatable :: u(:, :)     !< u^n [mm]
      real(wp), allocatable :: v(:, :)     !< v^(n-1/2) [mm/s]
      real(wp), allocatable :: unew(:, :)  !< u~, then u^(n+1) [mm]
      real(wp), allocatable :: fint(:, :)  !< K u^n of the last step [N]
      real(wp), allocatable :: fext(:, :)  !< f_ext(t_n) of the last step [N]
      real(wp), allocatable :: fc(:, :)    !< contact force on the body of the last step [N]
      real(wp), allocatable :: mass(:)     !< lumped mass [t]
      real(wp), allocatable :: minv(:)     !< 1 / lumped mass [1/t]
      real(wp), allocatable :: mdof(:)     !< lumped mass per dof, (2 nnode) [t]
      integer :: nblock = 0                !< blocks of block_size nodes
      real(wp), allocatable :: partial(:, :)  !< per-block sums (3, nblock)
      real(wp), allocatable :: cval(:)     !< curve values at t_n
      real(wp), allocatable :: cnext(:)    !< curve values at t_(n+1)
      ! automatic damping: u and K u at the last estimate
      real(wp), allocatable :: u_mark(:, :), f_mark(:, :), work(:, :)
      integer, allocatable :: pres_elements(:)   !< elements touching a prescribed dof
      ! energies (SPEC section 6) [mJ = N mm]
      real(wp) :: kinetic = 0              !< 1/2 v^(n+1/2) M v^(n+1/2)
      real(wp) :: strain = 0               !< 1/2 u^(n+1) K u^n
      real(wp) :: external_work = 0        !< loads and Dirichlet reactions
      real(wp) :: work_in = 0              !< sum of |external work increments|
      real(wp) :: damping_dissipation = 0
      real(wp) :: initial_kinetic = 0      !< 1/2 v^(-1/2) M v^(-1/2), energy put in at t = 0 (issue 12)
      logical :: blown_up = .false.
   contains
      procedure :: init => explicit_init
      procedure :: advance => explicit_advance
      procedure :: update_damping => explicit_update_damping
      procedure :: residual => explicit_residual
      procedure :: balance_error => explicit_balance_error
   end type explicit_t

contains

   !> Zero state; damping mode and value; the elements touching prescribed dofs.
   subroutine explicit_init(this, stiff, load, dt, damping, alpha, damping_interval)
      class(explicit_t), intent(out) :: this
      type(stiffness_t), intent(in) :: stiff
      type(loading_t), intent(in) :: load
      real(wp), intent(in) :: dt, alpha
      integer, intent(in) :: damping, damping_interval
      integer :: nnode, e
      logical, allocatable :: touches(:)

      nnode = size(stiff%mass)
      this%nnode = nnode
      this%dt = dt
      this%damping = damping
      this%alpha = merge(alpha, 0.0_wp, damping == damping_given)
      this%alpha_next = this%alpha
      this%damping_interval = damping_interval
      allocate (this%u(2, nnode), this%v(2, nnode), this%unew(2, nnode), this%fint(2, nnode), &
                this%fext(2, nnode), this%fc(2, nnode), this%work(2, nnode))
      this%u = 0; this%v = 0; this%unew = 0; this%fint = 0; this%fext = 0; this%fc = 0
      this%mass = stiff%mass
      this%minv = 1/stiff%mass
      this%mdof = reshape(spread(stiff%mass, 1, 2), [2*nnode])
      this%nblock = (nnode + block_size - 1)/block_size
      allocate (this%partial(3, this%nblock))
      allocate (this%cval(load%ncurve), this%cnext(load%ncurve))
      call load%curve_values(0.0_wp, this%cnext)
      if (damping == damping_auto) then
         allocate (this%u_mark(2, nnode), this%f_mark(2, nnode))
         this%u_mark = 0
         this%f_mark = 0
         this%work = 0
         allocate (touches(size(stiff%conn, 2)))
         do e = 1, size(touches)
            touches(e) = any(load%free(:, stiff%conn(:, e)) == 0)
         end do
         this%pres_elements = pack([(e, e=1, size(touches))], touches)
      end if
   end subroutine explicit_init

   !> Run up to nsteps steps; stops early (blown_up = .true.) if the energy runs away.
   subroutine explicit_advance(this, stiff, load, contact, nsteps)
      class(explicit_t), intent(inout) :: this
      type(stiffness_t), intent(in) :: stiff
      type(loading_t), intent(in) :: load
      type(contact_t), intent(inout) :: contact
      integer, intent(in) :: nsteps
      integer :: k, p, node, comp
      real(wp) :: dt, a1, a2inv, c, vnew, vbar, work, acc, f
      real(wp), allocatable :: swap(:, :)

      dt = this%dt
      do k = 1, nsteps
         ! 1-2. internal force at u^n and, fused with it, the predictor without the loads:
         !      u~ = u + (dt/(1 + a dt/2)) (a1 v - dt M^-1 f_int)
         this%alpha = this%alpha_next
         a1 = 1 - 0.5_wp*this%alpha*dt
         a2inv = 1/(1 + 0.5_wp*this%alpha*dt)
         c = dt*dt*a2inv
         call stiff%apply_update(this%u, this%fint, this%v, this%minv, dt*a2inv*a1, c, this%unew)
         ! automatic damping: a new alpha from (u^n, K u^n), used from the next step on
         if (this%damping == damping_auto) then
            if (mod(this%step, int(this%damping_interval, i8)) == 0) call this%update_damping(stiff, load)
         end if
         ! loads at t_n (sparse), prescribed values at t_(n+1)
         this%cval = this%cnext
         call load%curve_values(this%time + dt, this%cnext)
         do p = 1, load%ntrac
            this%fext(load%tcomp(p), load%tnode(p)) = 0
         end do
         do p = 1, load%ntrac
            node = load%tnode(p)
            comp = load%tcomp(p)
            f = this%cval(load%tcurve(p))*load%tweight(p)
            this%fext(comp, node) = this%fext(comp, node) + f
            this%unew(comp, node) = this%unew(comp, node) + c*this%minv(node)*f
         end do
         do p = 1, load%npres
            this%unew(load%pcomp(p), load%pnode(p)) = this%cnext(load%pcurve(p))
         end do
         ! 3. contact
         if (contact%active) call contact%enforce(this%u, this%v, this%unew, c, dt, this%fc)
         ! 4a. external work of the reactions (inertial and damping parts included) and loads,
         !     with the centred increment (u^(n+1) - u^(n-1))/2 = dt vbar
         work = 0
         do p = 1, load%npres
            node = load%pnode(p)
            comp = load%pcomp(p)
            vnew = (this%unew(comp, node) - this%u(comp, node))/dt
            vbar = 0.5_wp*(vnew + this%v(comp, node))
            acc = (vnew - this%v(comp, node))/dt
            f = this%mass(node)*(acc + this%alpha*vbar) + this%fint(comp, node)
            work = work + f*dt*vbar
         end do
         do p = 1, load%ntrac
            node = load%tnode(p)
            comp = load%tcomp(p)
            vnew = (this%unew(comp, node) - this%u(comp, node))/dt
            vbar = 0.5_wp*(vnew + this%v(comp, node))
            work = work + this%cval(load%tcurve(p))*load%tweight(p)*dt*vbar
         end do
         this%external_work = this%external_work + work
         this%work_in = this%work_in + abs(work)
         ! 4b. velocities and energies; u^(n+1) becomes u (the arrays are swapped, not copied)
         call corrector(this, dt)
         call move_alloc(this%u, swap)
         call move_alloc(this%unew, this%u)
         call move_alloc(swap, this%unew)
         this%step = this%step + 1
         this%time = real(this%step, wp)*dt
         ! blow-up guard: runaway kinetic energy or non-finite values
         if (.not. ieee_is_finite(this%kinetic) .or. &
             this%kinetic > blowup_ratio*max(this%work_in, tiny(1.0_wp))) then
            this%blown_up = .true.
            return
         end if
      end do
   end subroutine explicit_advance


   !> v^(n+1/2) = (u^(n+1) - u^n)/dt; kinetic, strain and damping energies.
   subroutine corrector(this, dt)
      type(explicit_t), intent(inout) :: this
      real(wp), intent(in) :: dt
      real(wp) :: ekin, edamp, estrain
      integer :: b
      call corrector_blocks(2*this%nnode, this%nblock, dt, this%unew, this%u, this%fint, this%mdof, &
                            this%v, this%partial)
      ekin = 0
      edamp = 0
      estrain = 0
      do b = 1, this%nblock
         ekin = ekin + this%partial(1, b)
         edamp = edamp + this%partial(2, b)
         estrain = estrain + this%partial(3, b)
      end do
      this%kinetic = 0.5_wp*ekin
      this%strain = 0.5_wp*estrain
      this%damping_dissipation = this%damping_dissipation + this%alpha*dt*edamp
   end subroutine corrector

   !> The corrector on the flattened dofs, block by block. Within a block the sums are vector
   !> reductions (OpenMP simd: their order is fixed by the compiled code) and the blocks are
   !> added in order, so the bits do not depend on the number of threads.
   subroutine corrector_blocks(ndof, nblock, dt, unew, u, fint, mdof, v, partial)
      integer, intent(in) :: ndof, nblock
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: unew(ndof), u(ndof), fint(ndof), mdof(ndof)
      real(wp), intent(inout) :: v(ndof)
      real(wp), intent(out) :: partial(3, nblock)
      integer :: b, d
      real(wp) :: rdt, vn, vb, ek, ed, es
      rdt = 1/dt
      !$omp parallel do schedule(static) private(d, vn, vb, ek, ed, es) if(ndof >= 2*omp_min_nodes)
      do b = 1, nblock
         ek = 0
         ed = 0
         es = 0
         !$omp simd private(vn, vb) reduction(+:ek, ed, es)
         do d = 2*(b - 1)*block_size + 1, min(2*b*block_size, ndof)
            vn = (unew(d) - u(d))*rdt
            vb = 0.5_wp*(vn + v(d))
            ek = ek + mdof(d)*vn*vn
            ed = ed + mdof(d)*vb*vb
            es = es + unew(d)*fint(d)
            v(d) = vn
         end do
         partial(:, b) = [ek, ed, es]
      end do
      !$omp end parallel do
   end subroutine corrector_blocks

   !> Automatic damping (dynamic relaxation, SPEC section 5): alpha = 2 omega_1, with omega_1^2
   !> the Rayleigh quotient of the free part du_f of the displacement increment since the last
   !> estimate, du_f^T K du_f / du_f^T M du_f. Called right after f_int = K u^n, so (u, f_int)
   !> and the stored mark are consistent pairs: K du_f = (f_int - f_mark) - K du_p, and K du_p
   !> only involves the elements that touch a prescribed dof.
   subroutine explicit_update_damping(this, stiff, load)
      class(explicit_t), intent(inout) :: this
      type(stiffness_t), intent(in) :: stiff
      type(loading_t), intent(in) :: load
      real(wp) :: num, den
      integer :: p, b
      ! K du = f_int - f_mark; then subtract K du_p, du_p being zero but on the prescribed dofs
      call block_difference(2*this%nnode, this%nblock, this%fint, this%f_mark)
      do p = 1, load%npres
         this%work(load%pcomp(p), load%pnode(p)) = this%u(load%pcomp(p), load%pnode(p)) &
                                                   - this%u_mark(load%pcomp(p), load%pnode(p))
      end do
      call stiff%apply_elements(this%pres_elements, this%work, this%f_mark, subtract=.true.)
      do p = 1, load%npres
         this%work(load%pcomp(p), load%pnode(p)) = 0
      end do
      ! du_f^T K du_f and du_f^T M du_f by blocks; the marks move to (u, f_int)
      call rayleigh_blocks(2*this%nnode, this%nblock, this%u, this%fint, load%free, this%mdof, &
                           this%u_mark, this%f_mark, this%partial)
      num = 0
      den = 0
      do b = 1, this%nblock
         num = num + this%partial(1, b)
         den = den + this%partial(2, b)
      end do
      if (num > 0 .and. den > 0) this%alpha_next = min(2*sqrt(num/den), 2/this%dt)
   end subroutine explicit_update_damping

   !> d = a - d on the flattened dofs.
   subroutine block_difference(ndof, nblock, a, d)
      integer, intent(in) :: ndof, nblock
      real(wp), intent(in) :: a(ndof)
      real(wp), intent(inout) :: d(ndof)
      integer :: b, i
      !$omp parallel do schedule(static) private(i) if(ndof >= 2*omp_min_nodes)
      do b = 1, nblock
         do i = 2*(b - 1)*block_size + 1, min(2*b*block_size, ndof)
            d(i) = a(i) - d(i)
         end do
      end do
      !$omp end parallel do
   end subroutine block_difference

   !> Per block: sum of du_f kdu and of m du_f^2 with du_f = (u - u_mark) free; then u_mark = u,
   !> f_mark = f_int. Block sums are added in order by the caller (thread-independent bits).
   subroutine rayleigh_blocks(ndof, nblock, u, fint, free, mdof, u_mark, f_mark, partial)
      integer, intent(in) :: ndof, nblock
      real(wp), intent(in) :: u(ndof), fint(ndof), free(ndof), mdof(ndof)
      real(wp), intent(inout) :: u_mark(ndof), f_mark(ndof)
      real(wp), intent(inout) :: partial(3, nblock)
      integer :: b, i
      real(wp) :: du, num, den
      !$omp parallel do schedule(static) private(i, du, num, den) if(ndof >= 2*omp_min_nodes)
      do b = 1, nblock
         num = 0
         den = 0
         !$omp simd private(du) reduction(+:num, den)
         do i = 2*(b - 1)*block_size + 1, min(2*b*block_size, ndof)
            du = (u(i) - u_mark(i))*free(i)
            num = num + du*f_mark(i)
            den = den + mdof(i)*du*du
            u_mark(i) = u(i)
            f_mark(i) = fint(i)
         end do
         partial(1, b) = num
         partial(2, b) = den
      end do
      !$omp end parallel do
   end subroutine rayleigh_blocks

   !> Out-of-balance force on the free dofs at t_n (contact forces included), relative to the
   !> largest of the reactions, the loads and the contact forces (SPEC section 5).
   real(wp) function explicit_residual(this, load) result(rel)
      class(explicit_t), intent(in) :: this
      type(loading_t), intent(in) :: load
      real(wp) :: rfree, scale, r
      integer :: i, j
      rfree = 0
      scale = 0
      ! max is exact in any order: the same bits for any number of threads
      !$omp parallel do schedule(static) private(j, r) reduction(max:rfree, scale) if(this%nnode >= omp_min_nodes)
      do i = 1, this%nnode
         do j = 1, 2
            r = this%fext(j, i) - this%fint(j, i) + this%fc(j, i)
            ! free dofs: out of balance; prescribed dofs: the reaction sets the scale
            rfree = max(rfree, abs(r*load%free(j, i)))
            scale = max(scale, abs(r*(1 - load%free(j, i))), abs(this%fext(j, i)), abs(this%fc(j, i)))
         end do
      end do
      !$omp end parallel do
      if (scale > 0) then
         rel = rfree/scale
      else
         rel = 0
      end if
   end function explicit_residual

   !> |E_kin0 + W_ext - (E_kin + E_strain + D_friction + D_damping + W_normal)| / max(terms),
   !> E_kin0 the initial kinetic energy (issue 12).
   real(wp) function explicit_balance_error(this, friction, normal_work) result(err)
      class(explicit_t), intent(in) :: this
      real(wp), intent(in) :: friction, normal_work
      real(wp) :: scale
      scale = max(abs(this%external_work), abs(this%kinetic), abs(this%strain), abs(friction), &
                  abs(this%damping_dissipation), abs(normal_work), this%initial_kinetic)
      if (scale > 0) then
         err = abs(this%initial_kinetic + this%external_work - (this%kinetic + this%strain + friction + &
                                          this%damping_dissipation + normal_work))/scale
      else
         err = 0
      end if
   end function explicit_balance_error
end module contact2d_explicit
