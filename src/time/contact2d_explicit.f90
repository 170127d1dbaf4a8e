!> Central-difference time integration with mass-proportional damping and the forward-increment
!> contact step (SPEC sections 4, 5, 6).
!>
!> One step, from u^n and v^(n-1/2):
!>   1. f_int = K u^n, f_ext(t_n)
!>   2. predictor  v* = ((1 - a dt/2) v + dt M^-1 (f_ext - f_int)) / (1 + a dt/2),  u~ = u^n + dt v*
!>      prescribed dofs take their value at t_(n+1)
!>   3. contact forces F_c chosen so that u^(n+1) = u~ + c M^-1 F_c meets the constraints
!>   4. v^(n+1/2) = (u^(n+1) - u^n)/dt, energies of SPEC section 6.
!> Steps 1-2 and the energy sums are one sweep over memory (contact2d_sweep), which writes v*
!> as the new velocity; step 4 then only corrects the dofs that step 2's loads, the prescribed
!> values or step 3 moved (docs/performance.md, issue 13). On structured meshes the work local
!> to a grid row (the listed dofs, the prescribed values, the damping estimate, the correction
!> of the dofs that neither the loads nor the contact step change) is done in the sweep's
!> parallel region by the thread that swept the row (contact2d_stepwork).
!> The step does no I/O and no allocation.
module contact2d_explicit
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use, intrinsic :: iso_fortran_env, only: int8
   use contact2d_kinds, only: wp, i8
   use contact2d_stiffness, only: stiffness_t, omp_min_nodes
   use contact2d_loading, only: loading_t
   use contact2d_contact, only: contact_t
   use contact2d_sys, only: sys_signal_pending
   use contact2d_sweep, only: sweep_t
   use contact2d_stepwork, only: stepwork_t
   use omp_lib, only: omp_get_thread_num, omp_get_wtime
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
      type(sweep_t) :: sweep               !< K u, predictor and energy sums in one pass
      !> dofs whose u~ changes after the sweep (loads, prescribed, contact nodes), as indices of
      !> the flattened (2 nnode) arrays, in dof order; set up by the first advance. Their v*, u~
      !> and v^(n-1/2), the prescribed values and the damping estimate's state are in rw.
      integer, allocatable :: sdof(:)
      type(stepwork_t) :: rw               !< the work per grid row (contact2d_stepwork)
      !> per dof (flattened): 0 on the listed dofs, 1 elsewhere (explicit_residual)
      integer(int8), allocatable :: s_other(:)
      integer :: s_ncontact = -1           !< contact nodes when sdof was built
      !> a listed dof where the sweep does not always store K u: every sweep is then full
      logical :: s_interior = .false.
      real(wp), allocatable :: fint(:, :)  !< K u^n of the last step [N]
      real(wp), allocatable :: fext(:, :)  !< f_ext(t_n) of the last step [N]
      real(wp), allocatable :: fc(:, :)    !< contact force on the body of the last step [N]
      real(wp), allocatable :: mass(:)     !< lumped mass [t]
      real(wp), allocatable :: mdof(:)     !< lumped mass per dof (2 nnode), for the Rayleigh sums [t]
      real(wp), allocatable :: minv(:)     !< 1 / lumped mass [1/t]
      integer :: nblock = 0                !< blocks of block_size nodes
      real(wp), allocatable :: cval(:)     !< curve values at t_n
      real(wp), allocatable :: cnext(:)    !< curve values at t_(n+1)
      ! energies (SPEC section 6) [mJ = N mm]
      real(wp) :: kinetic = 0              !< 1/2 v^(n+1/2) M v^(n+1/2)
      real(wp) :: strain = 0               !< 1/2 u^(n+1) K u^n (current when advance returns)
      real(wp) :: external_work = 0        !< loads and Dirichlet reactions
      real(wp) :: work_in = 0              !< sum of |external work increments|
      real(wp) :: damping_dissipation = 0
      real(wp) :: initial_kinetic = 0      !< 1/2 v^(-1/2) M v^(-1/2), energy put in at t = 0 (issue 12)
      !> sum m (v^(n-1/2))^2: twice the kinetic energy of the last step, formed from v by the
      !> next advance when vsum_stale (set it when v is changed between advance calls)
      real(wp) :: vsum = 0
      logical :: vsum_stale = .true.
      logical :: blown_up = .false.
      !> sum m (v^(n+1/2) - v^(n-1/2))^2 / sum m (v^(n+1/2))^2 of the last step: close to 4
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
      integer :: nnode

      nnode = size(stiff%mass)
      this%nnode = nnode
      this%dt = dt
      this%damping = damping
      this%alpha = merge(alpha, 0.0_wp, damping == damping_given)
      this%alpha_next = this%alpha
      this%damping_interval = damping_interval
      allocate (this%u(2, nnode), this%v(2, nnode), this%unew(2, nnode), this%fint(2, nnode), &
                this%fext(2, nnode), this%fc(2, nnode))
      this%u = 0; this%v = 0; this%unew = 0; this%fint = 0; this%fext = 0; this%fc = 0
      call this%sweep%init(stiff)
      this%mass = stiff%mass
      this%minv = 1/stiff%mass
      this%mdof = reshape(spread(stiff%mass, 1, 2), [2*nnode])
      this%nblock = (nnode + block_size - 1)/block_size
      allocate (this%cval(load%ncurve), this%cnext(load%ncurve))
      call load%curve_values(0.0_wp, this%cnext)
      ! segments of the per-row work: the grid rows of a structured mesh, else all dofs
      if (stiff%structured) then
         call this%rw%init(nnode, 2*(stiff%nx + 1), load%ncurve)
      else
         call this%rw%init(nnode, 2*nnode, load%ncurve)
      end if
      if (damping == damping_auto) &
         call this%rw%set_damping(stiff%conn, stiff%shape_of, stiff%ke, load%free, this%mdof)
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
      integer :: k, p, node, comp, nt, jlo, jhi
      real(wp) :: dt, a1, a2inv, c, vnew, vbar, work, workt, f, corr(4), num, den, t0, t1
      logical :: full, damp, inside, cdone, mine
      real(wp), allocatable :: swap(:, :)

      ! set-up, outside the step loop: the dofs that change after the sweep
      if (.not. allocated(this%sdof) .or. this%s_ncontact /= merge(contact%nc, 0, contact%active)) &
         call special_dofs(this, load, contact)
      if (this%vsum_stale) this%vsum = mass_sum(2*this%nnode, this%mdof, this%v)
      this%vsum_stale = .false.
      ! v^(n-1/2) at the listed dofs; the correction keeps it up to date from here on
      call this%rw%gather(this%v)
      dt = this%dt
      full = .true.
      ! the contact step in the sweep's parallel region, by the thread that swept the contact
      ! nodes' rows right after them, while the others sweep theirs (structured meshes, no loads:
      ! the loads come before the contact step and may be anywhere)
      inside = this%sweep%structured .and. contact%active .and. load%ntrac == 0 .and. this%rw%c_lo >= 0
      nt = this%sweep%team(stiff)
      call this%rw%reserve(nt)
      do k = 1, nsteps
         ! 1-2. internal force at u^n and, fused with it, the predictor without the loads:
         !      v* = (a1 v - dt M^-1 f_int)/(1 + a dt/2), u~ = u + dt v*
         this%alpha = this%alpha_next
         a1 = 1 - 0.5_wp*this%alpha*dt
         a2inv = 1/(1 + 0.5_wp*this%alpha*dt)
         c = dt*dt*a2inv
         ! one sweep: K u^n, v* (into v), u~ and the energy sums of v*; K u at every node and
         ! the strain energy only on the steps that read them (the last of this call, for the
         ! driver's residual and output; the damping estimate's)
         damp = .false.
         if (this%damping == damping_auto) damp = mod(this%step, int(this%damping_interval, i8)) == 0
         full = k == nsteps .or. this%s_interior .or. damp
         ! curve values at t_n (the loads) and t_(n+1) (the prescribed values)
         this%cval = this%cnext
         call load%curve_values(this%time + dt, this%cnext)
         ! the work per grid row, done by the sweep (structured meshes) or right after it: keep
         ! v* and u~ at the listed dofs and give v^(n-1/2) back (loads, reactions and the contact
         ! step use it); prescribed values at t_(n+1); automatic damping: the sums of a new
         ! alpha from (u^n, K u^n), used from the next step on; v^(n+1/2) and the correction
         ! sums at the listed dofs that neither the loads nor the contact step change
         call this%rw%prepare(this%cnext, dt, this%alpha, damp, this%u)
         cdone = .false.
         if (inside) then
            call this%sweep%prepare(dt*a2inv, .true.)
            call this%rw%plan(nt)
            !$omp parallel if(nt > 1) num_threads(nt) private(jlo, jhi, mine, t0, t1)
            call this%rw%split(omp_get_thread_num(), jlo, jhi, mine)
            t0 = omp_get_wtime()
            call this%sweep%rows_range(this%u, this%v, this%fint, a1*a2inv, dt, this%unew, full, this%rw, jlo, jhi)
            if (mine) then
               ! the prescribed values on the contact dofs, the contact step, the contact dofs'
               ! velocities and sums (as below)
               t1 = omp_get_wtime()
               call this%rw%set_late_prescribed(this%unew)
               call contact%enforce(this%u, this%v, this%unew, c, dt, this%fc)
               call this%rw%correct_late(this%u, this%unew, this%fint, this%v)
               call this%rw%balance(t1 - t0, jhi - jlo + 1, omp_get_wtime() - t1)
               cdone = .true.
            end if
            call this%rw%after_rows(this%u, this%fint)
            !$omp end parallel
         else if (this%sweep%structured) then
            call this%sweep%step(stiff, this%u, this%v, this%fint, a1*a2inv, dt*a2inv, dt, this%unew, full, this%rw)
         else
            call this%sweep%step(stiff, this%u, this%v, this%fint, a1*a2inv, dt*a2inv, dt, this%unew, full)
            call this%rw%all_rows(this%u, this%v, this%fint, this%unew)
         end if
         if (damp) then
            call this%rw%estimate(num, den)
            if (num > 0 .and. den > 0) this%alpha_next = min(2*sqrt(num/den), 2/this%dt)
         end if
         ! loads at t_n (sparse)
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
         ! 3. the prescribed values on the loaded and contact dofs, contact (if not done above)
         if (.not. cdone) then
            call this%rw%set_late_prescribed(this%unew)
            if (contact%active) call contact%enforce(this%u, this%v, this%unew, c, dt, this%fc)
         end if
         ! 4a. external work of the reactions (inertial and damping parts included) and loads,
         !     with the centred increment (u^(n+1) - u^(n-1))/2 = dt vbar
         !     (the reactions in the correction below, the loads here, before it changes v)
         workt = 0
         do p = 1, load%ntrac
            node = load%tnode(p)
            comp = load%tcomp(p)
            vnew = (this%unew(comp, node) - this%u(comp, node))/dt
            vbar = 0.5_wp*(vnew + this%v(comp, node))
            workt = workt + this%cval(load%tcurve(p))*load%tweight(p)*dt*vbar
         end do
         ! 4b. velocities and energies: v^(n+1/2) = v* but at the changed dofs, where it is
         !     (u^(n+1) - u^n)/dt and the sums of the sweep are corrected (run by run, in a
         !     fixed order); the runs with a loaded or contact dof here, the others were done
         !     with the sweep
         if (.not. cdone) call this%rw%correct_late(this%u, this%unew, this%fint, this%v)
         call this%rw%sums(corr, work)
         work = work + workt
         this%external_work = this%external_work + work
         this%work_in = this%work_in + abs(work)
         call add_energies(this, this%sweep%partial, corr, this%alpha, dt, full)
         ! u^(n+1) becomes u (the arrays are swapped, not copied)
         call move_alloc(this%u, swap)
         call move_alloc(this%unew, this%u)
         call move_alloc(swap, this%unew)
         this%step = this%step + 1
         this%time = this%time0 + real(this%step - this%step0, wp)*dt
         ! blow-up guard: runaway kinetic energy or non-finite values
         if (.not. ieee_is_finite(this%kinetic) .or. &
             this%kinetic > blowup_ratio*max(this%work_in, tiny(1.0_wp))) then
            this%blown_up = .true.
            exit
         end if
         if (this%guard) then
            call guard_check(this)
            if (this%growing) exit
         end if
         if (contact%stat /= 0 .or. sys_signal_pending() /= 0) exit
      end do
      ! stopped early after a step that was not full: K u^n and the strain energy of that step
      if (.not. full) then
         call stiff%apply(this%unew, this%fint)
         this%strain = 0.5_wp*sum(this%u*this%fint)
      end if
   end subroutine explicit_advance

   !> The dofs whose u~ is changed after the sweep: loaded, prescribed and contact-node dofs,
   !> each once, in dof order; the loaded and contact-node ones are changed after the sweep's
   !> parallel region ("late", contact2d_stepwork).
   subroutine special_dofs(this, load, contact)
      type(explicit_t), intent(inout) :: this
      type(loading_t), intent(in) :: load
      type(contact_t), intent(in) :: contact
      logical, allocatable :: mark(:, :), pres(:, :), late(:, :)
      integer :: p, i, n, comp, node
      allocate (mark(2, this%nnode), late(2, this%nnode))
      mark = .false.
      late = .false.
      do p = 1, load%ntrac
         mark(load%tcomp(p), load%tnode(p)) = .true.
         late(load%tcomp(p), load%tnode(p)) = .true.
      end do
      do p = 1, load%npres
         mark(load%pcomp(p), load%pnode(p)) = .true.
      end do
      this%s_ncontact = 0
      if (contact%active) then
         do i = 1, contact%nc
            mark(:, contact%node(i)) = .true.
            late(:, contact%node(i)) = .true.
         end do
         this%s_ncontact = contact%nc
      end if
      n = count(mark)
      this%s_interior = .false.
      do node = 1, this%nnode
         if (any(mark(:, node))) this%s_interior = this%s_interior .or. .not. this%sweep%kept(node)
      end do
      if (allocated(this%sdof)) deallocate (this%sdof, this%s_other)
      allocate (this%sdof(n))
      allocate (pres(2, this%nnode))
      pres = .false.
      do p = 1, load%npres
         pres(load%pcomp(p), load%pnode(p)) = .true.
      end do
      this%s_other = reshape(merge(0_int8, 1_int8, mark), [2*this%nnode])
      n = 0
      do node = 1, this%nnode
         do comp = 1, 2
            if (.not. mark(comp, node)) cycle
            n = n + 1
            this%sdof(n) = 2*(node - 1) + comp
         end do
      end do
      call this%rw%set_list(reshape(mark, [2*this%nnode]), reshape(pres, [2*this%nnode]), &
                            reshape(late, [2*this%nnode]), this%mass, &
                            2*(load%pnode(1:load%npres) - 1) + load%pcomp(1:load%npres), load%pcurve(1:load%npres))
      if (contact%active) then
         call this%rw%set_contact(contact%node(1:contact%nc))
      else
         call this%rw%set_contact([integer ::])
      end if
   end subroutine special_dofs


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

   !> Energies of the step from the sweep's partial sums (m v^2, -, u . K u, m dv^2), added in
   !> order, and the corrections of the changed dofs. The damping sum m vbar^2 = m (v + vold)^2/4
   !> follows from (a + b)^2 = 2 a^2 + 2 b^2 - (a - b)^2 with this%vsum = sum m vold^2: no
   !> cancellation (all three terms are non-negative, the subtracted one the smallest when the
   !> motion is smooth). this%vsum becomes sum m v^2 of this step.
   subroutine add_energies(this, partial, corr, alpha, dt, full)
      type(explicit_t), intent(inout) :: this
      real(wp), intent(in) :: partial(:, :), corr(4), alpha, dt
      logical, intent(in) :: full   !< the strain sum was formed (else this%strain is kept)
      real(wp) :: ekin, edamp, estrain, ealt
      integer :: b
      ekin = 0
      estrain = 0
      ealt = 0
      do b = 1, size(partial, 2)
         ekin = ekin + partial(1, b)
         estrain = estrain + partial(3, b)
         ealt = ealt + partial(4, b)
      end do
      ekin = ekin + corr(1)
      estrain = estrain + corr(3)
      ealt = ealt + corr(4)
      edamp = 0.5_wp*(ekin + this%vsum) - 0.25_wp*ealt
      this%vsum = ekin
      ! (not merge: both of its arguments are evaluated, and 0/0 traps in Debug builds)
      if (ekin > 0) then
         this%alternating = ealt/ekin
      else
         this%alternating = 0
      end if
      this%alternating_energy = 0.5_wp*ealt
      this%kinetic = 0.5_wp*ekin
      if (full) this%strain = 0.5_wp*estrain
      this%damping_dissipation = this%damping_dissipation + alpha*dt*edamp
   end subroutine add_energies

   !> sum m v^2 over the flattened dofs, in a fixed order (thread-independent bits).
   real(wp) function mass_sum(ndof, mdof, v) result(t)
      integer, intent(in) :: ndof
      real(wp), intent(in) :: mdof(ndof), v(ndof)
      integer :: i
      t = 0
      !$omp simd reduction(+:t)
      do i = 1, ndof
         t = t + mdof(i)*v(i)*v(i)
      end do
   end function mass_sum

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
      real(wp) :: rfree, scale
      ! max is exact in any order: the same bits for any number of threads
      if (allocated(this%s_other)) then
         ! the step loop writes f_ext and f_c at the listed dofs only: elsewhere r = -f_int on a
         ! free dof (the prescribed ones are listed), one array read instead of four
         call residual_others(2*this%nnode, this%nblock, this%fint, this%s_other, rfree)
         call residual_listed(size(this%sdof), this%sdof, this%fext, this%fint, this%fc, load%free, rfree, scale)
      else
         call residual_blocks(2*this%nnode, this%nblock, this%fext, this%fint, this%fc, load%free, rfree, scale)
      end if
      if (present(scale_out)) scale_out = scale
      if (present(floor)) scale = max(scale, floor)
      if (scale > 0) then
         rel = rfree/scale
      else
         rel = 0
      end if
   end function explicit_residual

   !> The largest out-of-balance force r = fext - fint + fc on the free dofs (rfree) and the
   !> largest of |r| on the prescribed ones, |fext| and |fc| (scale), over the flattened dofs by
   !> blocks (vector loops).
   subroutine residual_blocks(ndof, nblock, fext, fint, fc, free, rfree, scale)
      integer, intent(in) :: ndof, nblock
      real(wp), intent(in) :: fext(ndof), fint(ndof), fc(ndof), free(ndof)
      real(wp), intent(out) :: rfree, scale
      integer :: b, i
      real(wp) :: r
      rfree = 0
      scale = 0
      !$omp parallel do schedule(static) private(i, r) reduction(max:rfree, scale) if(ndof >= 2*omp_min_nodes)
      do b = 1, nblock
         !$omp simd private(r) reduction(max:rfree, scale)
         do i = 2*(b - 1)*block_size + 1, min(2*b*block_size, ndof)
            r = fext(i) - fint(i) + fc(i)
            ! free dofs: out of balance; prescribed dofs: the reaction sets the scale
            rfree = max(rfree, abs(r*free(i)))
            scale = max(scale, abs(r*(1 - free(i))), abs(fext(i)), abs(fc(i)))
         end do
      end do
      !$omp end parallel do
   end subroutine residual_blocks

   !> The largest |f_int| over the dofs where other = 1, by blocks (vector loops).
   subroutine residual_others(ndof, nblock, fint, other, rfree)
      integer, intent(in) :: ndof, nblock
      real(wp), intent(in) :: fint(ndof)
      integer(int8), intent(in) :: other(ndof)
      real(wp), intent(out) :: rfree
      integer :: b, i
      rfree = 0
      !$omp parallel do schedule(static) private(i) reduction(max:rfree) if(ndof >= 2*omp_min_nodes)
      do b = 1, nblock
         !$omp simd reduction(max:rfree)
         do i = 2*(b - 1)*block_size + 1, min(2*b*block_size, ndof)
            rfree = max(rfree, abs(fint(i))*other(i))
         end do
      end do
      !$omp end parallel do
   end subroutine residual_others

   !> rfree and scale of residual_blocks over the listed dofs, rfree taken further from its
   !> value on entry.
   subroutine residual_listed(n, dof, fext, fint, fc, free, rfree, scale)
      integer, intent(in) :: n, dof(n)
      real(wp), intent(in) :: fext(*), fint(*), fc(*), free(*)
      real(wp), intent(inout) :: rfree
      real(wp), intent(out) :: scale
      integer :: q, i
      real(wp) :: r
      scale = 0
      do q = 1, n
         i = dof(q)
         r = fext(i) - fint(i) + fc(i)
         rfree = max(rfree, abs(r*free(i)))
         scale = max(scale, abs(r*(1 - free(i))), abs(fext(i)), abs(fc(i)))
      end do
   end subroutine residual_listed

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
