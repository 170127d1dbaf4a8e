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
   use contact2d_sys, only: sys_signal_pending
   use contact2d_sweep, only: sweep_stencils, sweep_parts, sweep_step
   use contact2d_rows, only: rows_t
   implicit none
   private
   public :: explicit_t, damping_none, damping_given, damping_auto

   integer, parameter :: damping_none = 0, damping_given = 1, damping_auto = 2

   !> Kinetic energy above this multiple of the absolute work put in means the run blew up.
   real(wp), parameter :: blowup_ratio = 1.0e3_wp
   !> Nodes per block of the node loops (fixed, so sums do not depend on the thread count).
   integer, parameter :: block_size = 1024
   !> Growing-mode guard: rise factor per step of the alternating energy, rises in a row and
   !> alternating ratio that mean a fast-growing mode; steps between the checks of the slow
   !> test and its rises in a row under constant loads.
   integer, parameter :: guard_interval = 10
   real(wp), parameter :: guard_factor = 1.05_wp, guard_ratio = 2.0_wp
   integer, parameter :: guard_rises = 12, guard_kin_rises = 30

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
      real(wp), allocatable :: uold(:, :)  !< u^(n-1) while the corrector is pending [mm]
      !> the corrector of the last step is still to be done (it is fused into the next sweep)
      logical :: pending = .false.
      real(wp) :: alpha_prev = 0           !< damping of the last step (pending corrector)
      real(wp) :: stencils(2, 2, -1:1, -1:1, 3, 3) = 0   !< structured-mesh stencils (sweep)
      real(wp), allocatable :: rowsum(:, :)  !< per-row sums of the sweep (3, sweep_parts)
      type(rows_t) :: rows                 !< block rows of a general mesh (contact2d_rows)
      real(wp), allocatable :: fint(:, :)  !< K u^n of the last step [N]
      real(wp), allocatable :: fext(:, :)  !< f_ext(t_n) of the last step [N]
      real(wp), allocatable :: fc(:, :)    !< contact force on the body of the last step [N]
      real(wp), allocatable :: mass(:)     !< lumped mass [t]
      real(wp), allocatable :: minv(:)     !< 1 / lumped mass [1/t]
      real(wp), allocatable :: mdof(:)     !< lumped mass per dof, (2 nnode) [t]
      real(wp), allocatable :: minvdof(:)  !< 1 / lumped mass per dof, (2 nnode) [1/t]
      integer :: nblock = 0                !< blocks of block_size nodes
      real(wp), allocatable :: partial(:, :)  !< per-block sums (4, nblock)
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
      !> sum m (v^(n+1/2) - v^(n-1/2))^2 / sum m (v^(n+1/2))^2 of the last corrector: close to 4
      !> for a mode that changes sign every step (the one that grows when dt is too long)
      real(wp) :: alternating = 0
      real(wp) :: alternating_energy = 0   !< 1/2 sum m (v^(n+1/2) - v^(n-1/2))^2 [mJ]
      ! growing-mode guard (issue 13, docs/deck.md solver:dt_limit)
      logical :: guard = .false.           !< watch for a growing mode
      logical :: growing = .false.         !< a growing mode was detected (advance returned)
      real(wp) :: guard_after = 0          !< the energy test starts at this time (end of loading) [s]
      real(wp) :: guard_alt = 0, guard_kin = 0   !< values at the last guard check
      integer :: guard_rise = 0, guard_kin_rise = 0   !< consecutive rises
      real(wp) :: time0 = 0                !< time at step0 (dt changes) [s]
      integer(i8) :: step0 = 0             !< step at the last change of dt
   contains
      procedure :: init => explicit_init
      procedure :: advance => explicit_advance
      procedure :: update_damping => explicit_update_damping
      procedure :: residual => explicit_residual
      procedure :: balance_error => explicit_balance_error
      procedure :: set_dt => explicit_set_dt
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
                this%fext(2, nnode), this%fc(2, nnode), this%work(2, nnode), this%uold(2, nnode))
      this%u = 0; this%v = 0; this%unew = 0; this%fint = 0; this%fext = 0; this%fc = 0; this%uold = 0
      if (stiff%structured) call sweep_stencils(stiff%ke(:, :, 1), this%stencils)
      if (stiff%structured) then
         allocate (this%rowsum(4, sweep_parts(stiff)))
      else
         ! general meshes: the block rows in the layout of contact2d_rows
         call this%rows%init(stiff)
         allocate (this%rowsum(4, this%rows%parts()))
      end if
      this%mass = stiff%mass
      this%minv = 1/stiff%mass
      this%mdof = reshape(spread(stiff%mass, 1, 2), [2*nnode])
      this%minvdof = 1/this%mdof
      this%nblock = (nnode + block_size - 1)/block_size
      allocate (this%partial(4, this%nblock))
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

   !> Run up to nsteps steps; stops early (blown_up = .true.) if the energy runs away, after a
   !> failed contact solve (contact%stat /= 0) and when SIGINT/SIGTERM arrived (polled once per
   !> step: a read of a flag, no I/O).
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
         ! one sweep: the corrector of the last step (if pending), K u^n and the predictor
         if (stiff%structured) then
            call sweep_step(stiff, this%stencils, this%u, this%uold, this%v, this%fint, this%minv, this%mass, &
                            this%mdof, this%minvdof, dt*a2inv*a1, c, 1/dt, this%pending, this%unew, this%rowsum)
         else
            call this%rows%sweep(this%u, this%uold, this%v, this%fint, this%mdof, this%minvdof, dt*a2inv*a1, c, &
                            1/dt, this%pending, this%unew, this%rowsum)
         end if
         if (this%pending) call add_energies(this, this%rowsum, this%alpha_prev, dt)
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
         ! 4b. velocities and energies: pending, done in the next sweep (or below, on return);
         !     u^(n+1) becomes u, u^n becomes uold (the arrays are rotated, not copied)
         call move_alloc(this%uold, swap)
         call move_alloc(this%u, this%uold)
         call move_alloc(this%unew, this%u)
         call move_alloc(swap, this%unew)
         this%pending = .true.
         this%alpha_prev = this%alpha
         this%step = this%step + 1
         this%time = this%time0 + real(this%step - this%step0, wp)*dt
         ! blow-up guard: runaway kinetic energy or non-finite values (the energies of the
         ! sweep lag one step)
         if (.not. ieee_is_finite(this%kinetic) .or. &
             this%kinetic > blowup_ratio*max(this%work_in, tiny(1.0_wp))) then
            this%blown_up = .true.
            exit
         end if
         if (this%guard) then
            call guard_check(this)
            if (this%growing) exit
         end if
         if (contact%stat /= 0 .or. sys_signal_pending() /= 0) return
      end do
      ! on return the state is complete: v^(n+1/2) and the energies of the last step
      if (this%pending) call corrector(this, dt)
      if (.not. ieee_is_finite(this%kinetic) .or. &
          this%kinetic > blowup_ratio*max(this%work_in, tiny(1.0_wp))) this%blown_up = .true.
   end subroutine explicit_advance


   !> Growing-mode guard, every step: a mode above the stability limit changes sign every step
   !> and grows geometrically, so its alternating energy rises at every step (guard_rises in a
   !> row by guard_factor or more) and soon dominates the kinetic energy (alternating ratio
   !> above guard_ratio; 4 for a pure sign-changing mode, near 0 for smooth motion); once the loads are constant and the damping takes energy out of
   !> every mode, a slowly growing mode shows as alternating energy that rises at every check
   !> of guard_interval steps (guard_kin_rises in a row).
   subroutine guard_check(this)
      type(explicit_t), intent(inout) :: this
      if (this%alternating_energy > guard_factor*this%guard_alt .and. this%guard_alt > 0) then
         this%guard_rise = this%guard_rise + 1
      else
         this%guard_rise = 0
      end if
      this%guard_alt = this%alternating_energy
      if (mod(this%step, int(guard_interval, i8)) == 0) then
         if (this%time > this%guard_after .and. this%alternating_energy > this%guard_kin .and. this%guard_kin > 0) then
            this%guard_kin_rise = this%guard_kin_rise + 1
         else
            this%guard_kin_rise = 0
         end if
         this%guard_kin = this%alternating_energy
      end if
      this%growing = (this%guard_rise >= guard_rises .and. this%alternating > guard_ratio) .or. &
                     this%guard_kin_rise >= guard_kin_rises
   end subroutine guard_check

   !> A new time step from the next step on (the growing-mode fallback); the guard is reset.
   subroutine explicit_set_dt(this, dt)
      class(explicit_t), intent(inout) :: this
      real(wp), intent(in) :: dt
      this%time0 = this%time
      this%step0 = this%step
      this%dt = dt
      this%alpha_next = min(this%alpha_next, 2/dt)
      this%growing = .false.
      this%guard_rise = 0
      this%guard_kin_rise = 0
   end subroutine explicit_set_dt

   !> The pending corrector on its own (u is u^(n+1), uold u^n): v^(n+1/2) = (u^(n+1) - u^n)/dt;
   !> kinetic, strain and damping energies.
   subroutine corrector(this, dt)
      type(explicit_t), intent(inout) :: this
      real(wp), intent(in) :: dt
      call corrector_blocks(2*this%nnode, this%nblock, dt, this%u, this%uold, this%fint, this%mdof, &
                            this%v, this%partial)
      call add_energies(this, this%partial, this%alpha_prev, dt)
   end subroutine corrector

   !> Energies of the corrector from its partial sums (m v^2, m vbar^2, u . K u), added in order.
   subroutine add_energies(this, partial, alpha, dt)
      type(explicit_t), intent(inout) :: this
      real(wp), intent(in) :: partial(:, :), alpha, dt
      real(wp) :: ekin, edamp, estrain, ealt
      integer :: b
      ekin = 0
      edamp = 0
      estrain = 0
      ealt = 0
      do b = 1, size(partial, 2)
         ekin = ekin + partial(1, b)
         edamp = edamp + partial(2, b)
         estrain = estrain + partial(3, b)
         ealt = ealt + partial(4, b)
      end do
      ! (not merge: both of its arguments are evaluated, and 0/0 traps in Debug builds)
      if (ekin > 0) then
         this%alternating = ealt/ekin
      else
         this%alternating = 0
      end if
      this%alternating_energy = 0.5_wp*ealt
      this%kinetic = 0.5_wp*ekin
      this%strain = 0.5_wp*estrain
      this%damping_dissipation = this%damping_dissipation + alpha*dt*edamp
      this%pending = .false.
   end subroutine add_energies

   !> The corrector on the flattened dofs, block by block. Within a block the sums are vector
   !> reductions (OpenMP simd: their order is fixed by the compiled code) and the blocks are
   !> added in order, so the bits do not depend on the number of threads.
   subroutine corrector_blocks(ndof, nblock, dt, unew, u, fint, mdof, v, partial)
      integer, intent(in) :: ndof, nblock
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: unew(ndof), u(ndof), fint(ndof), mdof(ndof)
      real(wp), intent(inout) :: v(ndof)
      real(wp), intent(out) :: partial(4, nblock)
      integer :: b, d
      real(wp) :: rdt, vn, vb, ek, ed, es, ea
      rdt = 1/dt
      !$omp parallel do schedule(static) private(d, vn, vb, ek, ed, es, ea) if(ndof >= 2*omp_min_nodes)
      do b = 1, nblock
         ek = 0
         ed = 0
         es = 0
         ea = 0
         !$omp simd private(vn, vb) reduction(+:ek, ed, es, ea)
         do d = 2*(b - 1)*block_size + 1, min(2*b*block_size, ndof)
            vn = (unew(d) - u(d))*rdt
            vb = 0.5_wp*(vn + v(d))
            ek = ek + mdof(d)*vn*vn
            ed = ed + mdof(d)*vb*vb
            es = es + unew(d)*fint(d)
            ea = ea + mdof(d)*(vn - v(d))**2
            v(d) = vn
         end do
         partial(:, b) = [ek, ed, es, ea]
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
      real(wp), intent(inout) :: partial(4, nblock)
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
   !> largest of the reactions, the loads and the contact forces (SPEC section 5), or to `floor`
   !> when that is larger: the caller passes the largest scale reached during the run, so a
   !> stress-free end state (load removed) still converges (docs/output.md). scale_out: this
   !> step's scale [N].
   real(wp) function explicit_residual(this, load, floor, scale_out) result(rel)
      class(explicit_t), intent(in) :: this
      type(loading_t), intent(in) :: load
      real(wp), intent(in), optional :: floor
      real(wp), intent(out), optional :: scale_out
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
      if (present(scale_out)) scale_out = scale
      if (present(floor)) scale = max(scale, floor)
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
