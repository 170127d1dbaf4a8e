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
!> values or step 3 moved (docs/performance.md).
!> The step does no I/O and no allocation.
module contact2d_explicit
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use, intrinsic :: iso_fortran_env, only: int8
   use contact2d_kinds, only: wp, i8
   use contact2d_align, only: line_reals, line_skip
   use contact2d_stiffness, only: stiffness_t, omp_min_nodes
   use contact2d_loading, only: loading_t
   use contact2d_contact, only: contact_t
   use contact2d_sys, only: sys_signal_pending
   use contact2d_sweep, only: sweep_t
   use contact2d_rows, only: chunk_rows
   use contact2d_layout, only: layout_t
   use contact2d_damping_estimate, only: damping_estimate_t
   use contact2d_growth_guard, only: growth_guard_t
   use contact2d_comm, only: comm_allgatherv, comm_allgatherv_inplace, comm_halo_start, comm_halo_wait, comm_max
   use contact2d_sys, only: sys_signal_raise
   implicit none
   private
   public :: explicit_t, damping_none, damping_given, damping_auto

   integer, parameter :: damping_none = 0, damping_given = 1, damping_auto = 2

   !> Runs of the listed dofs shorter than this go through one loop over their places (s_short).
   integer, parameter :: long_run = 4
   !> Kinetic energy above this multiple of the absolute work put in means the run blew up.
   real(wp), parameter :: blowup_ratio = 1.0e3_wp
   !> Nodes per block of the node loops (fixed, so sums do not depend on the thread count).
   integer, parameter :: block_size = 1024

   !> State and settings of the explicit integrator.
   type :: explicit_t
      integer :: nnode = 0
      !> the nodes this process owns (local 1 .. layout%nowned, contact2d_layout): the energy and
      !> residual reductions run over them only (one process: every node, the same loops)
      type(layout_t) :: layout
      real(wp) :: dt = 0                   !< time step [s]
      real(wp) :: alpha = 0                !< current mass-proportional damping [1/s]
      real(wp) :: alpha_next = 0           !< damping from the next step on (automatic damping)
      integer :: damping = damping_none    !< damping mode
      integer :: damping_interval = 20     !< steps between omega_1 estimates (auto)
      integer(i8) :: step = 0              !< steps done
      real(wp) :: time = 0                 !< t_n [s]
      !> u, v, unew and fint: views of one allocation (the store), each starting on a 64-byte
      !> line, so that the sweep's rows of all four are aligned alike and its blocks start at
      !> the same outputs in every run (contact2d_align, contact2d_sweep); u and unew are swapped
      !> by pointer after each step. So an explicit_t is declared with the target attribute (its
      !> views point into itself) and never copied by assignment (the copy's views would point
      !> into the original).
      real(wp), allocatable :: store(:)
      real(wp), pointer, contiguous :: u(:, :) => null()     !< u^n [mm]
      real(wp), pointer, contiguous :: v(:, :) => null()     !< v^(n-1/2) [mm/s]
      real(wp), pointer, contiguous :: unew(:, :) => null()  !< u~, then u^(n+1) [mm]
      type(sweep_t) :: sweep               !< K u, predictor and energy sums in one pass
      !> dofs whose u~ changes after the sweep (loads, prescribed, contact nodes), as indices of
      !> the flattened (2 nnode) arrays, and their v^(n-1/2), v* and u~ of the current step; set
      !> up by the first advance, in dof order; its runs of at least long_run consecutive dofs as
      !> s_run(:, r) = (first dof, its place in the list, length): the loops over them are vector
      !> copies and sums; the places of the other dofs (short runs, as on the boundaries of Gmsh
      !> meshes) in s_short: one loop over all of them, no vector set-up per run.
      integer, allocatable :: sdof(:), s_run(:, :), s_short(:)
      real(wp), allocatable :: s_pres(:)   !< 1 at the prescribed dofs of the list, else 0
      integer, allocatable :: p_dof(:)     !< the dof of each prescribed value (flattened), load order
      !> per dof (flattened): 0 on the listed dofs, 1 elsewhere (explicit_residual)
      integer(int8), allocatable :: s_other(:)
      real(wp), allocatable :: s_vold(:), s_vstar(:), s_wstar(:)
      real(wp), allocatable :: s_mass(:)   !< the mass of each listed dof [t]
      integer :: s_ncontact = -1           !< contact nodes when sdof was built
      !> a listed dof where the sweep does not always store K u: every sweep is then full
      logical :: s_interior = .false.
      real(wp), pointer, contiguous :: fint(:, :) => null()  !< K u^n of the last step [N]
      real(wp), allocatable :: fext(:, :)  !< f_ext(t_n) of the last step [N]
      real(wp), allocatable :: fc(:, :)    !< contact force on the body of the last step [N]
      real(wp), allocatable :: mass(:)     !< lumped mass [t]
      real(wp), allocatable :: mdof(:)     !< lumped mass per dof (2 nnode), for the Rayleigh sums [t]
      real(wp), allocatable :: minv(:)     !< 1 / lumped mass [1/t]
      integer :: nblock = 0                !< blocks of block_size nodes
      real(wp), allocatable :: partial(:, :)  !< per-block sums (4, nblock)
      real(wp), allocatable :: cval(:)     !< curve values at t_n
      real(wp), allocatable :: cnext(:)    !< curve values at t_(n+1)
      !> automatic damping: the Rayleigh-quotient estimate of omega_1 (contact2d_damping_estimate)
      type(damping_estimate_t) :: damp
      ! energies (SPEC section 6) [mJ = N mm]
      real(wp) :: kinetic = 0              !< 1/2 v^(n+1/2) M v^(n+1/2)
      real(wp) :: strain = 0               !< 1/2 u^(n+1) K u^n (current when advance returns)
      !> The physical energies at the last whole step t_n (docs/output.md): the two above are
      !> staggered in time (SPEC section 6), which makes the discrete balance exact, but differ
      !> from the energy of a state by O(omega dt) per mode. kinetic_step = 1/2 v^n M v^n with
      !> v^n = (v^(n-1/2) + v^(n+1/2))/2 (the average the damping term uses), strain_step =
      !> 1/2 u^n K u^n; before the first step the initial state (u = 0, v^0 = v^(-1/2)).
      real(wp) :: kinetic_step = 0
      real(wp) :: strain_step = 0
      real(wp) :: external_work = 0        !< loads and Dirichlet reactions
      real(wp) :: work_in = 0              !< sum of |external work increments| (a moving obstacle's included)
      real(wp) :: damping_dissipation = 0
      real(wp) :: initial_kinetic = 0      !< 1/2 v^(-1/2) M v^(-1/2), energy put in at t = 0
      !> sum m (v^(n-1/2))^2: twice the kinetic energy of the last step, formed from v by the
      !> next advance when vsum_stale (set it when v is changed between advance calls)
      real(wp) :: vsum = 0
      logical :: vsum_stale = .true.
      logical :: blown_up = .false.
      !> sum m (v^(n+1/2) - v^(n-1/2))^2 / sum m (v^(n+1/2))^2 of the last step: close to 4
      !> for a mode that changes sign every step (the one that grows when dt is too long)
      real(wp) :: alternating = 0
      real(wp) :: alternating_energy = 0   !< 1/2 sum m (v^(n+1/2) - v^(n-1/2))^2 [mJ]
      ! growing-mode guard (docs/deck.md solver:dt_limit)
      logical :: guard = .false.           !< watch for a growing mode
      logical :: growing = .false.         !< a growing mode was detected (advance returned)
      real(wp) :: guard_after = 0          !< the energy test starts at this time (end of loading) [s]
      type(growth_guard_t) :: watch        !< the guard's rises in a row (contact2d_growth_guard)
      real(wp) :: time0 = 0                !< time at step0 (dt changes) [s]
      integer(i8) :: step0 = 0             !< step at the last change of dt
      ! several processes (explicit_distribute, docs/mpi.md):
      ! every array is whole on every rank; rank r sweeps the parts row_lo(r) .. row_hi(r) (grid
      ! rows of the built-in mesh, chunks of block rows of a Gmsh mesh: contact2d_sweep), that is
      ! the nodes n_lo(r) .. n_hi(r), and after each sweep every rank receives the others' part
      ! sums and their values at the listed dofs, so that the rest of the step (loads, prescribed
      ! values, contact, energies, the tests that end the loop) is done alike on every rank from
      ! the same numbers
      logical :: split = .false.           !< the rows are shared among several processes
      integer :: rank = 0                  !< this process (0 .. nproc - 1)
      integer :: nproc = 1
      !> (0:nproc - 1) each rank's parts (counted from 0: partial(:, j + 1) of the sweep)
      integer, allocatable :: row_lo(:), row_hi(:)
      integer, allocatable :: n_lo(:), n_hi(:)       !< (0:nproc - 1) each rank's nodes
      !> this rank's halo, as node ranges: h_lo(k) .. h_hi(k) received from the rank below (k = 1)
      !> and above (k = 2), s_lo(k) .. s_hi(k) of its own sent to them (empty: hi < lo)
      integer :: h_lo(2) = 1, h_hi(2) = 0, s_lo(2) = 1, s_hi(2) = 0
      !> the parts swept before the halo is sent: row_lo .. e_lo (the nodes sent below) and
      !> e_hi .. row_hi (sent above); the others are swept while it travels
      integer :: e_lo = -1, e_hi = 0
      integer, allocatable :: q_lo(:), q_hi(:)       !< (0:nproc - 1) its listed dofs (sdof places)
      !> (0:nproc - 1) the values and offsets of each rank's part of the step's gather (x_) and of
      !> the whole fields' gather (u_), reals
      integer, allocatable :: x_count(:), x_displ(:), u_count(:), u_displ(:)
      real(wp), allocatable :: x_send(:), x_recv(:)
      !> the halo: this rank's nodes of u~ that its neighbours read sent (:, 1) below and (:, 2)
      !> above, the neighbours' nodes that it reads received, in flight from the sweep of one step
      !> to the next (every message h_n reals, the largest halo of the run)
      real(wp), allocatable :: h_send(:, :), h_recv(:, :)
      integer :: h_n = 0
      logical :: halo_pending = .false.
   contains
      procedure :: init => explicit_init
      procedure :: advance => explicit_advance
      procedure :: update_damping => explicit_update_damping
      procedure :: residual => explicit_residual
      procedure :: balance_error => explicit_balance_error
      procedure :: set_dt => explicit_set_dt
      procedure :: distribute => explicit_distribute
   end type explicit_t

contains

   !> Zero state; damping mode and value; the elements touching prescribed dofs.
   subroutine explicit_init(this, stiff, load, dt, damping, alpha, damping_interval)
      class(explicit_t), intent(out), target :: this
      type(stiffness_t), intent(in) :: stiff
      type(loading_t), intent(in) :: load
      real(wp), intent(in) :: dt, alpha
      integer, intent(in) :: damping, damping_interval
      integer :: nnode, len, o

      nnode = size(stiff%mass)
      this%nnode = nnode
      call this%layout%init_single(nnode)
      this%dt = dt
      this%damping = damping
      this%alpha = merge(alpha, 0.0_wp, damping == damping_given)
      this%alpha_next = this%alpha
      this%damping_interval = damping_interval
      ! the four views of the store, each 2 nnode reals rounded up to whole lines
      len = line_reals*((2*nnode + line_reals - 1)/line_reals)
      allocate (this%store(4*len + line_reals - 1))
      o = line_skip(this%store(1))
      this%u(1:2, 1:nnode) => this%store(o + 1:o + 2*nnode)
      this%v(1:2, 1:nnode) => this%store(o + len + 1:o + len + 2*nnode)
      this%unew(1:2, 1:nnode) => this%store(o + 2*len + 1:o + 2*len + 2*nnode)
      this%fint(1:2, 1:nnode) => this%store(o + 3*len + 1:o + 3*len + 2*nnode)
      allocate (this%fext(2, nnode), this%fc(2, nnode), this%damp%work(2, nnode))
      this%u = 0; this%v = 0; this%unew = 0; this%fint = 0; this%fext = 0; this%fc = 0
      call this%sweep%init(stiff)
      this%mass = stiff%mass
      this%minv = 1/stiff%mass
      this%mdof = reshape(spread(stiff%mass, 1, 2), [2*nnode])
      this%nblock = (nnode + block_size - 1)/block_size
      allocate (this%partial(4, this%nblock))
      allocate (this%cval(load%ncurve), this%cnext(load%ncurve))
      call load%curve_values(0.0_wp, this%cnext)
      if (damping == damping_auto) call this%damp%init(stiff, load, nnode)
   end subroutine explicit_init

   !> Run up to nsteps steps; stops early (blown_up = .true.) if the energy runs away, after a
   !> failed contact solve (a pair's stat /= 0) and when SIGINT/SIGTERM arrived (polled once per
   !> step: a read of a flag, no I/O). contacts: the operator of each contact pair (none: no
   !> contact); their node sets are disjoint (contact2d_model), so the pairs, each setting
   !> u^(n+1) and F_c at its own nodes only, are enforced one after the other in pair order.
   subroutine explicit_advance(this, stiff, load, contacts, nsteps)
      class(explicit_t), intent(inout) :: this
      type(stiffness_t), intent(in) :: stiff
      type(loading_t), intent(in) :: load
      type(contact_t), intent(inout) :: contacts(:)
      integer, intent(in) :: nsteps
      integer :: k, p, node, comp, ip, cstat
      real(wp) :: dt, a1, a2inv, c, vnew, vbar, work, workt, f, corr(4), wobst
      logical :: full
      real(wp), pointer, contiguous :: swap(:, :)

      ! set-up, outside the step loop: the dofs that change after the sweep
      if (.not. allocated(this%sdof) .or. this%s_ncontact /= active_nodes(contacts)) &
         call special_dofs(this, load, contacts)
      if (this%vsum_stale) this%vsum = mass_sum(2*this%layout%nowned, this%mdof, this%v)
      this%vsum_stale = .false.
      ! v^(n-1/2) at the listed dofs; special_correct keeps it up to date from here on
      call special_gather(this%s_run, this%s_short, this%sdof, this%v, this%s_vold)
      dt = this%dt
      full = .true.
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
         full = k == nsteps .or. this%s_interior
         if (this%damping == damping_auto) &
            full = full .or. mod(this%step, int(this%damping_interval, i8)) == 0
         if (this%split) then
            call split_sweep(this, stiff, a1*a2inv, dt*a2inv, dt, full)
         else
            call this%sweep%step(stiff, this%u, this%v, this%fint, a1*a2inv, dt*a2inv, dt, this%unew, full)
         end if
         ! the dofs changed below: keep v* and u~, give back v^(n-1/2) (loads, reactions and
         ! the contact step use it)
         call special_keep(this%s_run, this%s_short, this%sdof, this%v, this%unew, this%s_vold, this%s_vstar, this%s_wstar)
         ! automatic damping: a new alpha from (u^n, K u^n), used from the next step on
         if (this%damping == damping_auto) then
            if (mod(this%step, int(this%damping_interval, i8)) == 0) then
               ! (several processes: the estimate reads u^n and K u^n at every node)
               if (this%split) call gather_fields(this, this%u, this%fint)
               call this%update_damping(stiff, load)
            end if
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
         call set_prescribed(load%npres, this%p_dof, load%pcurve, this%cnext, this%unew)
         ! 3. contact
         ! (wobst: the work of a moving obstacle on the body in this step, 0 for a fixed one)
         wobst = 0
         cstat = 0
         do ip = 1, size(contacts)
            wobst = wobst - contacts(ip)%obstacle_work
            if (contacts(ip)%active) call contacts(ip)%enforce(this%u, this%v, this%unew, c, dt, this%fc, this%time)
            wobst = wobst + contacts(ip)%obstacle_work
            if (contacts(ip)%stat /= 0) cstat = contacts(ip)%stat
         end do
         ! 4a. external work of the reactions (inertial and damping parts included) and loads,
         !     with the centred increment (u^(n+1) - u^(n-1))/2 = dt vbar
         !     (the reactions in special_correct below, the loads here, before it changes v)
         workt = 0
         do p = 1, load%ntrac
            node = load%tnode(p)
            comp = load%tcomp(p)
            vnew = (this%unew(comp, node) - this%u(comp, node))/dt
            vbar = 0.5_wp*(vnew + this%v(comp, node))
            workt = workt + this%cval(load%tcurve(p))*load%tweight(p)*dt*vbar
         end do
         ! 4b. velocities and energies: v^(n+1/2) = v* but at the changed dofs, where it is
         !     (u^(n+1) - u^n)/dt and the sums of the sweep are corrected (in a fixed order)
         call special_correct(this%s_run, this%s_short, this%sdof, this%s_pres, this%s_mass, this%u, this%unew, this%fint, &
                              dt, this%alpha, this%s_vold, this%s_vstar, this%s_wstar, this%v, corr, work)
         work = work + workt
         this%external_work = this%external_work + work
         this%work_in = this%work_in + abs(work)
         ! a moving obstacle puts work in too (docs/geometry.md)
         this%work_in = this%work_in + abs(wobst)
         call add_energies(this, this%sweep%partial, corr, this%alpha, dt, full)
         ! u^(n+1) becomes u (the arrays are swapped, not copied)
         swap => this%u
         this%u => this%unew
         this%unew => swap
         this%step = this%step + 1
         this%time = this%time0 + real(this%step - this%step0, wp)*dt
         ! blow-up guard: runaway kinetic energy or non-finite values
         if (.not. ieee_is_finite(this%kinetic) .or. &
             this%kinetic > blowup_ratio*max(this%work_in, tiny(1.0_wp))) then
            this%blown_up = .true.
            exit
         end if
         if (this%guard) then
            this%growing = this%watch%check(this%alternating_energy, this%alternating, this%step, this%time, &
                                            this%guard_after)
            if (this%growing) exit
         end if
         if (this%split) then
            ! the signal every rank saw in this step's gather (the same decision on every rank)
            if (cstat /= 0 .or. nint(this%x_recv(size(this%x_recv))) /= 0) exit
         else
            if (cstat /= 0 .or. sys_signal_pending() /= 0) exit
         end if
      end do
      ! several processes: every field whole on every rank again (the driver, the output and the
      ! next call read them), and a signal that reached any rank raised on all
      if (this%split) call split_end(this)
      ! stopped early after a step that was not full: K u^n and the strain energy of that step
      if (.not. full) then
         call stiff%apply(this%unew, this%fint)
         this%strain = 0.5_wp*sum(this%u(:, 1:this%layout%nowned)*this%fint(:, 1:this%layout%nowned))
      end if
      ! the physical strain energy at t_n, once per call (not per step): after the swap unew
      ! holds u^n and fint = K u^n at every dof (the last step of a call is full); not after a
      ! blow-up (the values may overflow, which traps in Debug builds, and mean nothing)
      if (.not. this%blown_up) &
         this%strain_step = 0.5_wp*sum(this%unew(:, 1:this%layout%nowned)*this%fint(:, 1:this%layout%nowned))
   end subroutine explicit_advance

   !> Share the mesh among nproc processes (this one rank), so that every part's energy sums
   !> are formed by one rank exactly as by one process and added in the same order on every rank
   !> (the same bits for any nproc): the built-in mesh by blocks of whole grid rows, in order; a
   !> Gmsh mesh by contiguous ranges of whole chunks of block rows (contact2d_rows; its nodes
   !> renumbered by contact2d_renumber, so a chunk's rows reach only nearby nodes), each rank's
   !> halo the nodes its chunks reach beyond its own, which must be the neighbours' (docs/mpi.md).
   !> stat /= 0 with a one-line errmsg for a mesh too small for nproc.
   subroutine explicit_distribute(this, nproc, rank, stat, errmsg)
      class(explicit_t), intent(inout) :: this
      integer, intent(in) :: nproc, rank
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer :: r, nparts, npn
      integer, allocatable :: g_lo(:), g_hi(:)
      character(len=12) :: a, b, c
      stat = 1
      write (a, '(i0)') nproc
      allocate (this%row_lo(0:nproc - 1), this%row_hi(0:nproc - 1), this%n_lo(0:nproc - 1), this%n_hi(0:nproc - 1), &
                g_lo(0:nproc - 1), g_hi(0:nproc - 1))
      if (this%sweep%structured) then
         write (b, '(i0)') this%sweep%ny + 1
         if (this%sweep%ny + 1 < 2*nproc) then
            errmsg = 'mpirun -np '//trim(a)//': the mesh has '//trim(b)//' grid rows, at least two per process needed'
            return
         end if
         nparts = this%sweep%ny + 1
         npn = this%sweep%nx + 1   ! nodes per part
      else
         nparts = size(this%sweep%rows%reach, 2)
         npn = chunk_rows
         write (b, '(i0)') this%nnode
         write (c, '(i0)') nparts
         if (nparts < nproc) then
            errmsg = 'mpirun -np '//trim(a)//': the mesh has '//trim(b)//' nodes, '//trim(c)// &
                     ' chunks of block rows, at least one per process needed'
            return
         end if
      end if
      do r = 0, nproc - 1
         this%row_lo(r) = (r*nparts)/nproc
         this%row_hi(r) = ((r + 1)*nparts)/nproc - 1
         this%n_lo(r) = this%row_lo(r)*npn + 1
         this%n_hi(r) = min((this%row_hi(r) + 1)*npn, this%nnode)
         if (this%sweep%structured) then
            ! a grid row reads u on the rows beside it (contact2d_sweep)
            g_lo(r) = max(this%n_lo(r) - npn, 1)
            g_hi(r) = min(this%n_hi(r) + npn, this%nnode)
         else
            g_lo(r) = minval(this%sweep%rows%reach(1, this%row_lo(r) + 1:this%row_hi(r) + 1))
            g_hi(r) = maxval(this%sweep%rows%reach(2, this%row_lo(r) + 1:this%row_hi(r) + 1))
         end if
      end do
      ! each rank's reach within its neighbours' nodes: the halo comes from them alone
      do r = 0, nproc - 1
         if (g_lo(r) < this%n_lo(max(r - 1, 0)) .or. g_hi(r) > this%n_hi(min(r + 1, nproc - 1))) then
            errmsg = 'mpirun -np '//trim(a)//': the mesh has '//trim(b)//' nodes, too few for '//trim(a)// &
                     ' processes (the rows of one reach beyond its neighbours'' nodes)'
            return
         end if
      end do
      stat = 0
      errmsg = ''
      this%split = nproc > 1
      this%nproc = nproc
      this%rank = rank
      allocate (this%u_count(0:nproc - 1), this%u_displ(0:nproc - 1))
      this%u_count = 2*(this%n_hi - this%n_lo + 1)
      this%u_displ = 2*(this%n_lo - 1)
      ! the halo of this rank: what it reads of its neighbours' nodes, what they read of its own
      this%h_n = 0
      do r = 1, nproc - 1
         this%h_n = max(this%h_n, 2*(this%n_lo(r) - g_lo(r)), 2*(g_hi(r - 1) - this%n_hi(r - 1)))
      end do
      this%h_lo = 1
      this%h_hi = 0
      this%s_lo = 1
      this%s_hi = 0
      this%e_lo = this%row_lo(rank) - 1
      this%e_hi = this%row_hi(rank) + 1
      if (rank > 0) then
         this%h_lo(1) = g_lo(rank)
         this%h_hi(1) = this%n_lo(rank) - 1
         this%s_lo(1) = this%n_lo(rank)
         this%s_hi(1) = g_hi(rank - 1)
         this%e_lo = max((this%s_hi(1) - 1)/npn, this%row_lo(rank))
      end if
      if (rank < nproc - 1) then
         this%h_lo(2) = this%n_hi(rank) + 1
         this%h_hi(2) = g_hi(rank)
         this%s_lo(2) = g_lo(rank + 1)
         this%s_hi(2) = this%n_hi(rank)
         this%e_hi = min((this%s_lo(2) - 1)/npn, this%row_hi(rank))
      end if
      allocate (this%h_send(max(this%h_n, 1), 2), this%h_recv(max(this%h_n, 1), 2))
      this%h_send = 0
      this%h_recv = 0
      ! the listed dofs' shares follow when they are known (split_dofs, from the next advance)
      this%s_ncontact = -1
   end subroutine explicit_distribute

   !> Each rank's places of the listed dofs (sdof is in dof order, so a rank's are consecutive)
   !> and the sizes of the step's gather: its parts' four sums, its listed dofs' v*, u~ and K u,
   !> and the signal it has seen.
   subroutine split_dofs(this)
      type(explicit_t), intent(inout) :: this
      integer :: r, q, n
      allocate (this%q_lo(0:this%nproc - 1), this%q_hi(0:this%nproc - 1), this%x_count(0:this%nproc - 1), &
                this%x_displ(0:this%nproc - 1))
      q = 1
      n = 0
      do r = 0, this%nproc - 1
         this%q_lo(r) = q
         do while (q <= size(this%sdof))
            if ((this%sdof(q) - 1)/2 + 1 > this%n_hi(r)) exit
            q = q + 1
         end do
         this%q_hi(r) = q - 1
         this%x_count(r) = 4*(this%row_hi(r) - this%row_lo(r) + 1) + 3*(this%q_hi(r) - this%q_lo(r) + 1) + 1
         this%x_displ(r) = n
         n = n + this%x_count(r)
      end do
      allocate (this%x_send(this%x_count(this%rank)), this%x_recv(n))
   end subroutine split_dofs

   !> The sweep of this rank's parts (several processes). The nodes beside them, sent by the
   !> neighbours during the last step, are put into u first (halo_merge); then the parts that
   !> hold the nodes the neighbours read are swept and sent to them (MPI_Isend/Irecv,
   !> halo_start), and the inside parts swept while they travel; then the step's gather. The
   !> parts read u on their reach only (contact2d_sweep; a grid row's j + 2 value of the last
   !> row only forms what the next row would reuse, and no row after it does: never used).
   subroutine split_sweep(this, stiff, ca, cb, dt, full)
      type(explicit_t), intent(inout) :: this
      type(stiffness_t), intent(in) :: stiff
      real(wp), intent(in) :: ca, cb, dt
      logical, intent(in) :: full
      integer :: lo, hi, rows(2)
      lo = this%row_lo(this%rank)
      hi = this%row_hi(this%rank)
      if (this%halo_pending) call halo_merge(this)
      if (this%e_lo >= this%e_hi - 1) then
         ! the parts sent meet: all swept, then sent
         rows(1) = lo
         rows(2) = hi
         call this%sweep%step(stiff, this%u, this%v, this%fint, ca, cb, dt, this%unew, full, rows)
         call halo_start(this)
      else
         rows(1) = lo
         rows(2) = this%e_lo
         if (rows(2) >= rows(1)) call this%sweep%step(stiff, this%u, this%v, this%fint, ca, cb, dt, this%unew, full, rows)
         rows(1) = this%e_hi
         rows(2) = hi
         if (rows(2) >= rows(1)) call this%sweep%step(stiff, this%u, this%v, this%fint, ca, cb, dt, this%unew, full, rows)
         call halo_start(this)
         rows(1) = this%e_lo + 1
         rows(2) = this%e_hi - 1
         call this%sweep%step(stiff, this%u, this%v, this%fint, ca, cb, dt, this%unew, full, rows)
      end if
      call split_gather(this, this%sweep%partial, this%v, this%unew, this%fint)
   end subroutine split_sweep

   !> After the sweep (several processes): every rank's row sums and v*, u~, K u at its listed
   !> dofs, and the signal it has seen (the largest wins), put in place on every rank.
   subroutine split_gather(this, partial, v, w, f)
      type(explicit_t), intent(inout) :: this
      real(wp), intent(inout) :: partial(4, 0:*), v(*), w(*), f(*)
      integer :: r, k, q, d, j
      ! (loops, not reshape or constructors: the step allocates nothing)
      k = 0
      do j = this%row_lo(this%rank), this%row_hi(this%rank)
         this%x_send(k + 1) = partial(1, j)
         this%x_send(k + 2) = partial(2, j)
         this%x_send(k + 3) = partial(3, j)
         this%x_send(k + 4) = partial(4, j)
         k = k + 4
      end do
      do q = this%q_lo(this%rank), this%q_hi(this%rank)
         d = this%sdof(q)
         this%x_send(k + 1) = v(d)
         this%x_send(k + 2) = w(d)
         this%x_send(k + 3) = f(d)
         k = k + 3
      end do
      this%x_send(k + 1) = real(sys_signal_pending(), wp)
      call comm_allgatherv(this%x_send, this%x_recv, this%x_count, this%x_displ)
      do r = 0, this%nproc - 1
         k = this%x_displ(r)
         if (r /= this%rank) then
            do j = this%row_lo(r), this%row_hi(r)
               partial(1, j) = this%x_recv(k + 1)
               partial(2, j) = this%x_recv(k + 2)
               partial(3, j) = this%x_recv(k + 3)
               partial(4, j) = this%x_recv(k + 4)
               k = k + 4
            end do
            do q = this%q_lo(r), this%q_hi(r)
               d = this%sdof(q)
               v(d) = this%x_recv(k + 1)
               w(d) = this%x_recv(k + 2)
               f(d) = this%x_recv(k + 3)
               k = k + 3
            end do
         end if
         ! the last value of the gather: the largest signal of all ranks
         this%x_recv(size(this%x_recv)) = max(this%x_recv(size(this%x_recv)), this%x_recv(this%x_displ(r) + this%x_count(r)))
      end do
   end subroutine split_gather

   !> Send this rank's nodes of u~ (just swept) that the ranks below and above read, and receive
   !> theirs (non-blocking; halo_merge waits). Sent from copies: the step changes u~ at the
   !> listed dofs before the messages are done.
   subroutine halo_start(this)
      type(explicit_t), intent(inout) :: this
      integer :: below, above, k
      below = merge(this%rank - 1, -1, this%rank > 0)
      above = merge(this%rank + 1, -1, this%rank < this%nproc - 1)
      do k = 1, 2
         if (this%s_hi(k) >= this%s_lo(k)) &
            call flat_copy(2*(this%s_hi(k) - this%s_lo(k) + 1), this%unew, 2*(this%s_lo(k) - 1), this%h_send(:, k))
      end do
      call comm_halo_start(this%h_send, this%h_recv, this%h_n, below, above)
      this%halo_pending = .true.
   end subroutine halo_start

   !> The neighbours' nodes of u~ received (halo_start of the last step) put into u beside this
   !> rank's nodes, but at the listed dofs: those every rank has already changed alike (loads,
   !> prescribed values, contact), so that u there is u^(n+1) of every rank.
   subroutine halo_merge(this)
      type(explicit_t), intent(inout) :: this
      integer :: k
      call comm_halo_wait(this%h_recv)
      this%halo_pending = .false.
      do k = 1, 2
         if (this%h_hi(k) >= this%h_lo(k)) &
            call merge_row(2*(this%h_hi(k) - this%h_lo(k) + 1), this%h_recv(:, k), this%s_other, &
                           2*(this%h_lo(k) - 1), this%u)
      end do
   end subroutine halo_merge

   !> b(1:n) = a(o + 1 : o + n) (flattened a).
   subroutine flat_copy(n, a, o, b)
      integer, intent(in) :: n, o
      real(wp), intent(in) :: a(*)
      real(wp), intent(out) :: b(n)
      b = a(o + 1:o + n)
   end subroutine flat_copy

   !> u(o + p) = row(p) where other(o + p) = 1 (not a listed dof), p = 1 .. n (flattened u).
   subroutine merge_row(n, row, other, o, u)
      integer, intent(in) :: n, o
      real(wp), intent(in) :: row(n)
      integer(int8), intent(in) :: other(*)
      real(wp), intent(inout) :: u(*)
      integer :: p
      do p = 1, n
         if (other(o + p) == 1) u(o + p) = row(p)
      end do
   end subroutine merge_row

   !> Two fields made whole on every rank: each rank's rows to all (in place).
   subroutine gather_fields(this, a, b)
      type(explicit_t), intent(in) :: this
      real(wp), intent(inout) :: a(*), b(*)
      call comm_allgatherv_inplace(a, this%u_count, this%u_displ)
      call comm_allgatherv_inplace(b, this%u_count, this%u_displ)
   end subroutine gather_fields

   !> The end of an advance call with several processes: the halo in flight received, u, u^n
   !> (unew after the swap), v and K u whole on every rank, and a signal any rank has seen
   !> raised on every rank (the driver's tests of it then agree).
   subroutine split_end(this)
      type(explicit_t), intent(inout) :: this
      integer :: sig
      if (this%halo_pending) call halo_merge(this)
      call gather_fields(this, this%u, this%unew)
      call gather_fields(this, this%v, this%fint)
      sig = comm_max(sys_signal_pending())
      if (sig /= 0) call sys_signal_raise(sig)
   end subroutine split_end

   !> The dofs whose u~ is changed after the sweep: loaded, prescribed and contact-node dofs
   !> (with two bodies the master boundary's nodes as well), each once, in dof order.
   subroutine special_dofs(this, load, contacts)
      type(explicit_t), intent(inout) :: this
      type(loading_t), intent(in) :: load
      type(contact_t), intent(in) :: contacts(:)
      logical, allocatable :: mark(:, :), pres(:, :)
      integer, allocatable :: runs(:, :)
      integer :: p, i, j, n, r, comp, node
      allocate (mark(2, this%nnode))
      mark = .false.
      do p = 1, load%ntrac
         mark(load%tcomp(p), load%tnode(p)) = .true.
      end do
      do p = 1, load%npres
         mark(load%pcomp(p), load%pnode(p)) = .true.
      end do
      do j = 1, size(contacts)
         if (.not. contacts(j)%active) cycle
         do i = 1, contacts(j)%nc
            mark(:, contacts(j)%node(i)) = .true.
         end do
         ! two bodies: the contact forces act on every node of the master boundary too
         if (contacts(j)%body) then
            do i = 1, contacts(j)%master%nm
               mark(:, contacts(j)%master%mnode(i)) = .true.
            end do
         end if
      end do
      this%s_ncontact = active_nodes(contacts)
      n = count(mark)
      this%s_interior = .false.
      do node = 1, this%nnode
         if (any(mark(:, node))) this%s_interior = this%s_interior .or. .not. this%sweep%kept(node)
      end do
      if (allocated(this%sdof)) deallocate (this%sdof, this%s_vold, this%s_vstar, this%s_wstar, this%s_mass, &
                                            this%s_pres, this%s_run, this%s_short, this%s_other)
      allocate (this%sdof(n), this%s_vold(n), this%s_vstar(n), this%s_wstar(n), this%s_mass(n), this%s_pres(n))
      allocate (pres(2, this%nnode))
      pres = .false.
      do p = 1, load%npres
         pres(load%pcomp(p), load%pnode(p)) = .true.
      end do
      this%p_dof = 2*(load%pnode(1:load%npres) - 1) + load%pcomp(1:load%npres)
      this%s_other = reshape(merge(0_int8, 1_int8, mark), [2*this%nnode])
      ! the list in dof order, then its runs
      n = 0
      do node = 1, this%nnode
         do comp = 1, 2
            if (.not. mark(comp, node)) cycle
            n = n + 1
            this%sdof(n) = 2*(node - 1) + comp
            this%s_mass(n) = this%mass(node)
            this%s_pres(n) = merge(1, 0, pres(comp, node))
         end do
      end do
      r = 0
      do i = 1, n
         if (i == 1) then
            r = r + 1
         else if (this%sdof(i) /= this%sdof(i - 1) + 1) then
            r = r + 1
         end if
      end do
      allocate (runs(3, r))
      r = 0
      do i = 1, n
         if (i > 1) then
            if (this%sdof(i) == this%sdof(i - 1) + 1) then
               runs(3, r) = runs(3, r) + 1
               cycle
            end if
         end if
         r = r + 1
         runs(:, r) = [this%sdof(i), i, 1]
      end do
      ! long runs kept as runs, the places of the others listed
      this%s_run = runs(:, pack([(i, i=1, r)], runs(3, 1:r) >= long_run))
      allocate (this%s_short(0))
      do i = 1, r
         if (runs(3, i) < long_run) this%s_short = [this%s_short, [(runs(2, i) + j, j=0, runs(3, i) - 1)]]
      end do
      if (this%split) then
         if (allocated(this%q_lo)) deallocate (this%q_lo, this%q_hi, this%x_count, this%x_displ, this%x_send, this%x_recv)
         call split_dofs(this)
      end if
   end subroutine special_dofs

   !> The contact nodes of the active pairs, all pairs together (special_dofs' list is rebuilt
   !> when it changes).
   pure integer function active_nodes(contacts) result(n)
      type(contact_t), intent(in) :: contacts(:)
      integer :: k
      n = 0
      do k = 1, size(contacts)
         if (contacts(k)%active) n = n + contacts(k)%nc
      end do
   end function active_nodes

   !> The prescribed values at t_(n+1): w(dof(p)) = c(curve(p)), in load order (flattened w).
   subroutine set_prescribed(n, dof, curve, c, w)
      integer, intent(in) :: n, dof(n), curve(n)
      real(wp), intent(in) :: c(:)
      real(wp), intent(inout) :: w(*)
      integer :: p
      do p = 1, n
         w(dof(p)) = c(curve(p))
      end do
   end subroutine set_prescribed

   !> vold = v at the listed dofs (flattened arrays).
   subroutine special_gather(run, short, dof, v, vold)
      integer, intent(in) :: run(:, :), short(:), dof(:)
      real(wp), intent(in) :: v(*)
      real(wp), intent(inout) :: vold(*)
      integer :: r, d, q, l, i
      do r = 1, size(run, 2)
         d = run(1, r) - 1
         q = run(2, r) - 1
         l = run(3, r)
         ! (a simd loop, not an array copy: that became a call of memcpy per run)
         !$omp simd
         do i = 1, l
            vold(q + i) = v(d + i)
         end do
      end do
      do i = 1, size(short)
         q = short(i)
         vold(q) = v(dof(q))
      end do
   end subroutine special_gather

   !> At the listed dofs, right after the sweep: keep v* and u~, give v^(n-1/2) back to v.
   subroutine special_keep(run, short, dof, v, w, vold, vstar, wstar)
      integer, intent(in) :: run(:, :), short(:), dof(:)
      real(wp), intent(inout) :: v(*)
      real(wp), intent(in) :: w(*), vold(*)
      real(wp), intent(inout) :: vstar(*), wstar(*)
      integer :: r, d, q, l, i
      do r = 1, size(run, 2)
         d = run(1, r) - 1
         q = run(2, r) - 1
         l = run(3, r)
         if (l == 1) then   ! (the loop below is three calls of memcpy)
            vstar(q + 1) = v(d + 1)
            wstar(q + 1) = w(d + 1)
            v(d + 1) = vold(q + 1)
            cycle
         end if
         !$omp simd
         do i = 1, l
            vstar(q + i) = v(d + i)
            wstar(q + i) = w(d + i)
            v(d + i) = vold(q + i)
         end do
      end do
      do i = 1, size(short)
         q = short(i)
         d = dof(q)
         vstar(q) = v(d)
         wstar(q) = w(d)
         v(d) = vold(q)
      end do
   end subroutine special_keep

   !> At the listed dofs, after the contact step: v^(n+1/2) = (u^(n+1) - u^n)/dt, and the changes
   !> of the sweep's sums (m v^2, -, u . K u, m dv^2) from v* and u~ to these values, run by run
   !> (vector sums in a fixed order; a^2 - b^2 = (a - b)(a + b); the damping sum is not needed:
   !> add_energies). At the prescribed dofs (pres = 1) also the work of the reactions, inertial
   !> and damping parts included, on the centred increment dt vbar = (u^(n+1) - u^(n-1))/2.
   !> vold becomes v^(n+1/2), the next step's v^(n-1/2).
   subroutine special_correct(run, short, dof, pres, mass, u, unew, fint, dt, alpha, vold, vstar, wstar, v, corr, work)
      integer, intent(in) :: run(:, :), short(:), dof(:)
      real(wp), intent(in) :: pres(*), mass(*), u(*), unew(*), fint(*), dt, alpha, vstar(*), wstar(*)
      real(wp), intent(inout) :: v(*), vold(*)
      real(wp), intent(out) :: corr(4), work
      integer :: r, i, q0, d0, k
      real(wp) :: c1, c3, c4, vo, vs, vn, md, vbar, acc, f
      c1 = 0
      c3 = 0
      c4 = 0
      work = 0
      ! (correct_one written out here: called from two loops, gfortran 12 did not inline it, and
      ! its calls kept the long runs from being vector loops: about 4.5 % of the run at k = 5)
      do r = 1, size(run, 2)
         d0 = run(1, r) - 1
         q0 = run(2, r) - 1
         !$omp simd reduction(+:c1, c3, c4, work) private(vo, vs, vn, md, vbar, acc, f)
         do i = 1, run(3, r)
            vo = vold(q0 + i)
            vs = vstar(q0 + i)
            vn = (unew(d0 + i) - u(d0 + i))/dt
            vbar = 0.5_wp*(vn + vo)
            acc = (vn - vo)/dt
            f = mass(q0 + i)*(acc + alpha*vbar) + fint(d0 + i)
            work = work + pres(q0 + i)*(f*dt*vbar)
            md = mass(q0 + i)*(vn - vs)
            c1 = c1 + md*(vn + vs)
            c3 = c3 + (unew(d0 + i) - wstar(q0 + i))*fint(d0 + i)
            c4 = c4 + md*((vn + vs) - 2*vo)
            v(d0 + i) = vn
            vold(q0 + i) = vn
         end do
      end do
      ! the dofs of the short runs, in list order after the long runs (a fixed order)
      !$omp simd reduction(+:c1, c3, c4, work)
      do k = 1, size(short)
         call correct_one(short(k), dof(short(k)), c1, c3, c4, work)
      end do
      corr(1) = c1
      corr(2) = 0
      corr(3) = c3
      corr(4) = c4
   contains
      !> Listed dof q (flattened dof d): v^(n+1/2), the next step's v^(n-1/2), and its terms of
      !> the sums (the reduction's copies passed in; the same as the long runs' loop above).
      subroutine correct_one(q, d, c1, c3, c4, work)
         integer, intent(in) :: q, d
         real(wp), intent(inout) :: c1, c3, c4, work
         real(wp) :: vo, vs, vn, md, vbar, acc, f
         vo = vold(q)
         vs = vstar(q)
         vn = (unew(d) - u(d))/dt
         vbar = 0.5_wp*(vn + vo)
         acc = (vn - vo)/dt
         f = mass(q)*(acc + alpha*vbar) + fint(d)
         work = work + pres(q)*(f*dt*vbar)
         md = mass(q)*(vn - vs)
         c1 = c1 + md*(vn + vs)
         c3 = c3 + (unew(d) - wstar(q))*fint(d)
         c4 = c4 + md*((vn + vs) - 2*vo)
         v(d) = vn
         vold(q) = vn
      end subroutine correct_one
   end subroutine special_correct


   !> A new time step from the next step on (the growing-mode fallback); the guard is reset.
   subroutine explicit_set_dt(this, dt)
      class(explicit_t), intent(inout) :: this
      real(wp), intent(in) :: dt
      this%time0 = this%time
      this%step0 = this%step
      this%dt = dt
      this%alpha_next = min(this%alpha_next, 2/dt)
      this%growing = .false.
      call this%watch%reset()
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
      ! sum m ((v^(n-1/2) + v^(n+1/2))/2)^2 = edamp: the kinetic energy at the whole step t_n
      this%kinetic_step = 0.5_wp*edamp
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

   !> Automatic damping (dynamic relaxation, SPEC section 5): alpha = 2 omega_1 from the next
   !> step on, estimated from (u^n, K u^n) right after the sweep (contact2d_damping_estimate).
   subroutine explicit_update_damping(this, stiff, load)
      class(explicit_t), intent(inout) :: this
      type(stiffness_t), intent(in) :: stiff
      type(loading_t), intent(in) :: load
      ! the Rayleigh sums over the nodes this process owns (contact2d_layout)
      call this%damp%estimate(stiff, load, this%layout%nowned, this%nblock, block_size, this%u, this%fint, &
                              this%mdof, this%partial, this%dt, this%alpha_next)
   end subroutine explicit_update_damping

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
         call residual_others(2*this%layout%nowned, this%nblock, this%fint, this%s_other, rfree)
         call residual_listed(size(this%sdof), this%sdof, this%fext, this%fint, this%fc, load%free, rfree, scale)
      else
         call residual_blocks(2*this%layout%nowned, this%nblock, this%fext, this%fint, this%fc, load%free, rfree, scale)
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
   !> E_kin0 the initial kinetic energy (docs/deck.md &initial).
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
