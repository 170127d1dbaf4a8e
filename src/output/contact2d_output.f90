!> The HDF5 output file of a run (SPEC section 8) and its XDMF sidecar for ParaView.
!>
!> Layout: root attributes; /mesh; /contact (contact runs); /history/<name> extendible series,
!> buffered and flushed every `flush_samples` samples or `flush_seconds` of wall time; /final
!> written at the end, also after a blow-up, so the file always opens.
!> It reads the model (what the deck and the mesh define) and the state (what the engine
!> computed: contact2d_state); it knows neither engine: the root attributes particular to an
!> engine come as plain values (attributes_explicit*, attributes_static*).
module contact2d_output
   use contact2d_kinds, only: wp, i8
   use contact2d_version, only: program_name, program_version, output_format_version
   use contact2d_h5, only: h5file_t, h5series_t
   use contact2d_deck, only: deck_t
   use contact2d_model, only: model_t
   use contact2d_friction, only: parameter_name_len
   use contact2d_state, only: state_t
   use contact2d_contact, only: contact_t
   use contact2d_strings, only: str
   use contact2d_sys, only: sys_write_file, sys_strerror
   use contact2d_outpath, only: sidecar_name
   use contact2d_kkt, only: kkt_names
   use hdf5, only: hid_t
   implicit none
   private
   public :: output_t, history_names, static_figures_t

   !> History series: SPEC section 8 names first, then additions (docs/output.md).
   !> kinetic_energy and strain_energy are the staggered energies of the balance (SPEC section 6);
   !> kinetic_energy_physical and strain_energy_physical those of the state at the last whole
   !> step t_n (state_t kinetic_step, strain_step).
   !> The last four only where the obstacle moves (docs/geometry.md): the work of the contact
   !> forces on the body through the obstacle's motion (the balance's input W_obstacle), the
   !> obstacle's displacement d(t) and angle theta(t) at the sample's time.
   character(len=24), parameter :: history_names(22) = [character(len=24) :: &
      'time', 'kinetic_energy', 'strain_energy', 'external_work', 'friction_dissipation', &
      'damping_dissipation', 'energy_balance_error', 'residual', 'normal_force_total', &
      'tangential_force_total', 'normal_contact_work', 'step', 'damping_alpha', 'stick_increment_max', &
      'status_changes', 'penetration_max', 'kinetic_energy_physical', 'strain_energy_physical', &
      'obstacle_work', 'obstacle_displacement_x', 'obstacle_displacement_y', 'obstacle_angle']
   !> (plane strain: forces are per unit thickness, N/mm)
   character(len=8), parameter :: history_units(22) = [character(len=8) :: &
      's', 'mJ', 'mJ', 'mJ', 'mJ', 'mJ', '1', '1', 'N/mm', 'N/mm', 'mJ', '1', '1/s', 'mm', '1', 'mm', 'mJ', 'mJ', &
      'mJ', 'mm', 'mm', 'rad']
   integer, parameter :: nseries = size(history_names)
   !> the series written for a fixed obstacle
   integer, parameter :: nseries_fixed = 18
   integer, parameter :: flush_samples = 256
   !> With several contact pairs the contact series above are the sums over the pairs (forces,
   !> works, dissipation, status changes) or their largest values (stick increment,
   !> penetration), the obstacle's motion that of the first moving pair; each pair also gets
   !> these, named '<pair name>_<series>' (docs/output.md).
   character(len=24), parameter :: pair_series_names(6) = [character(len=24) :: &
      'friction_dissipation', 'normal_force_total', 'tangential_force_total', 'normal_contact_work', &
      'obstacle_work', 'penetration_max']
   character(len=8), parameter :: pair_series_units(6) = [character(len=8) :: 'mJ', 'N/mm', 'N/mm', 'mJ', 'mJ', 'mm']
   integer, parameter :: npair_series = size(pair_series_names)
   real(wp), parameter :: flush_seconds = 2.0_wp

   !> What the static engine leaves for its closing root attributes (attributes_static_end).
   type :: static_figures_t
      real(wp) :: kkt_max(4) = 0           !< largest relative KKT residuals (kkt_names)
      integer :: increments = 0            !< solver:static_increments
      integer :: steps = 0                 !< settled steps, halves included
      integer :: splits = 0                !< halvings made
      integer :: iterations = 0            !< PDAS iterations, all increments
      integer :: outer_iterations = 0      !< threshold fixed-point iterations, all increments
      real(wp) :: factor_nonzeros = 0      !< nonzeros of the CHOLMOD factor
      real(wp) :: factor_flops = 0         !< its flops
      real(wp) :: time_factor = 0          !< assembly and factorisation [s]
      real(wp) :: time_condense = 0        !< Schur complement and A [s]
      real(wp) :: time_solve = 0           !< increments: solves and PDAS [s]
   end type static_figures_t

   !> An open output file.
   type :: output_t
      type(h5file_t) :: file
      type(h5series_t) :: series(nseries)
      integer :: nactive = nseries_fixed   !< series written (nseries where the obstacle moves)
      !> where the obstacle moves: /history/contact_slip_velocity, the contact nodes' slip
      !> velocities relative to the obstacle, one row of ncontact values per sample (flattened)
      type(h5series_t) :: slip_series
      real(wp), allocatable :: slip_buf(:)   !< flush_samples rows of ncontact values
      integer(hid_t) :: history = -1
      integer(hid_t) :: fields = -1
      real(wp) :: buffer(flush_samples, nseries) = 0   !< one contiguous column per series
      !> several contact pairs: each pair's own series (pair_series_names, '<name>_<series>'),
      !> (npair_series, npairs), and their buffer (flush_samples, npair_series, npairs); with one
      !> pair the series above are that pair's and these are not allocated (docs/output.md)
      type(h5series_t), allocatable :: pair_series(:, :)
      real(wp), allocatable :: pair_buf(:, :, :)
      integer :: nbuf = 0
      integer(i8) :: last_flush_clock = 0
      logical :: xdmf = .true.
      character(len=:), allocatable :: xmf_path   !< where the sidecar is written
      character(len=:), allocatable :: h5_name    !< the HDF5 file name the sidecar refers to
      integer :: nsnap = 0                       !< /fields/<step> groups written so far
      integer(i8), allocatable :: snap_step(:)   !< their steps, in the order written
      real(wp), allocatable :: snap_time(:)      !< their times [s] (the sidecar's time series)
      !> this process writes the file (rank 0 of several, or the only one); on the other ranks of
      !> mpirun every procedure here returns at once, touching no file (docs/mpi.md)
      logical :: writer = .true.
   contains
      procedure :: open => output_open
      procedure :: sample => output_sample
      procedure :: flush_history => output_flush_history
      procedure :: snapshot => output_snapshot
      procedure :: finish => output_finish
      procedure :: attributes_explicit => output_attributes_explicit
      procedure :: attributes_explicit_end => output_attributes_explicit_end
      procedure :: attributes_compare_static => output_attributes_compare_static
      procedure :: attributes_static => output_attributes_static
      procedure :: attributes_static_end => output_attributes_static_end
   end type output_t

contains

   !> Create the file and write what is known before the first step. The sidecar goes to
   !> `sidecar` (default <path stem>.xmf) and refers to the HDF5 file as `target` (default path):
   !> a run writes temporary files and renames them at the end (contact2d_outpath).
   subroutine output_open(this, path, overwrite, deck, model, state, stat, errmsg, sidecar, target)
      class(output_t), intent(inout) :: this
      character(len=*), intent(in) :: path
      logical, intent(in) :: overwrite
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: state   !< the state at t = 0 (its time step)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      character(len=*), intent(in), optional :: sidecar, target
      integer(hid_t) :: root, g, gp
      integer :: k, j
      real(wp), allocatable :: mass(:, :), pvalue(:)
      character(len=parameter_name_len), allocatable :: pname(:)

      if (.not. this%writer) then
         stat = 0
         errmsg = ''
         return
      end if
      this%xdmf = deck%output%xdmf
      this%xmf_path = sidecar_name(path)
      if (present(sidecar)) this%xmf_path = sidecar
      this%h5_name = path
      if (present(target)) this%h5_name = target
      ! at most one snapshot per output:snapshot_times entry (times in one step share one): the
      ! list the sidecar's time series is written from, sized here, not in the step loop
      this%nsnap = 0
      allocate (this%snap_step(deck%output%nsnapshot), this%snap_time(deck%output%nsnapshot))
      call this%file%create(path, overwrite)
      root = this%file%id
      call this%file%attr(root, 'program', program_name)
      call this%file%attr(root, 'program_version', program_version)
      call this%file%attr(root, 'format_version', output_format_version)
      call this%file%attr(root, 'deck', deck%text)
      call this%file%attr(root, 'deck_path', deck%path)
      call this%file%attr(root, 'effective_deck', deck%effective)
      call this%file%attr(root, 'units', 'length mm, force N (nodal forces per unit thickness, N/mm), '// &
                          'stress MPa, mass t, time s, energy mJ')
      ! (several pairs: the first pair's; each pair's group has its own)
      if (size(model%contacts) > 0) then
         call this%file%attr(root, 'multiplier', model%contacts(1)%multiplier_name())
      else
         call this%file%attr(root, 'multiplier', 'none')
      end if
      call this%file%attr(root, 'dt', state%dt)
      call this%file%attr(root, 'dt_critical', model%dt_critical)
      call this%file%attr(root, 'element_count', model%mesh%nel)
      call this%file%attr(root, 'node_count', model%mesh%nnode)
      call this%file%attr(root, 'nx', model%mesh%nx)
      call this%file%attr(root, 'ny', model%mesh%ny)
      call this%file%attr(root, 'converged', 0)
      call this%file%attr(root, 'status', 'running')

      g = this%file%group(root, 'mesh')
      call this%file%dataset(g, 'coordinates', model%mesh%file_order(model%mesh%x), 'mm')
      call this%file%dataset(g, 'connectivity', model%mesh%file_id(model%mesh%conn), '1')
      mass = model%mesh%file_order(reshape(model%stiff%mass, [1, model%mesh%nnode]))
      call this%file%dataset(g, 'mass', mass(1, :), 't')
      ! the bodies (docs/output.md "/mesh"): of each element, of each node (the lowest of a node
      ! shared by bonded bodies), their count and names as attributes of /mesh
      call this%file%dataset(g, 'body', model%body_of, '1')
      call this%file%dataset(g, 'node_body', node_body(model), '1')
      call this%file%attr(g, 'body_count', size(model%bodies))
      do k = 1, size(model%bodies)
         call this%file%attr(g, 'body_name_'//str(k), model%bodies(k)%name)
      end do
      call this%file%close_group(g)

      ! /contact: the one pair's data, or with several pairs /contact/<name> for each
      if (size(model%contacts) == 1) then
         g = this%file%group(root, 'contact')
         call write_pair_setup(g, 1)
         call this%file%close_group(g)
      else if (size(model%contacts) > 1) then
         g = this%file%group(root, 'contact')
         call this%file%attr(g, 'pair_count', size(model%contacts))
         do k = 1, size(model%contacts)
            call this%file%attr(g, 'pair_name_'//str(k), model%pairs(k)%name)
            gp = this%file%group(g, model%pairs(k)%name)
            call this%file%attr(gp, 'multiplier', model%contacts(k)%multiplier_name())
            call write_pair_setup(gp, k)
            call this%file%close_group(gp)
         end do
         call this%file%close_group(g)
      end if
      this%history = this%file%group(root, 'history')
      this%nactive = nseries_fixed
      do k = 1, size(model%contacts)
         if (allocated(model%contacts(k)%obstacle)) then
            if (model%contacts(k)%obstacle%moving) this%nactive = nseries
         end if
      end do
      do k = 1, this%nactive
         call this%series(k)%create(this%file, this%history, trim(history_names(k)), &
                                    trim(history_units(k)), flush_samples)
      end do
      ! the slip velocities: one pair only (several pairs: docs/output.md)
      if (this%nactive == nseries .and. size(model%contacts) == 1) then
         call this%slip_series%create(this%file, this%history, 'contact_slip_velocity', 'mm/s', &
                                      flush_samples*model%contacts(1)%nc)
         call this%file%attr(this%slip_series%id, 'ncontact', model%contacts(1)%nc)
         allocate (this%slip_buf(flush_samples*model%contacts(1)%nc))
      end if
      if (size(model%contacts) > 1) then
         allocate (this%pair_series(npair_series, size(model%contacts)))
         allocate (this%pair_buf(flush_samples, npair_series, size(model%contacts)))
         this%pair_buf = 0
         do k = 1, size(model%contacts)
            do j = 1, npair_series
               call this%pair_series(j, k)%create(this%file, this%history, model%pairs(k)%name//'_'// &
                                                  trim(pair_series_names(j)), trim(pair_series_units(j)), flush_samples)
            end do
         end do
      end if
      call this%file%flush()
      call system_clock(this%last_flush_clock)
      stat = this%file%stat
      errmsg = ''
      if (stat /= 0) errmsg = this%file%errmsg
   contains
      !> A pair's set-up data in group g (/contact, or /contact/<name> with several pairs).
      subroutine write_pair_setup(g, ip)
         integer(hid_t), intent(in) :: g
         integer, intent(in) :: ip
         integer :: k
         associate (c => model%contacts(ip))
            call this%file%dataset(g, 'nodes', model%mesh%file_id(c%node), '1')
            ! the contact nodes' coordinates, the geometry of the sidecar's polyline grids
            call this%file%dataset(g, 'coordinates', model%mesh%x(:, c%node), 'mm')
            call this%file%dataset(g, 'abscissa', c%abscissa, 'mm')
            call this%file%dataset(g, 'weight', c%weight, 'mm')
            call this%file%dataset(g, 'gap', c%gap, 'mm')
            call this%file%dataset(g, 'threshold', c%threshold, 'MPa')
            ! per-node outward normal of the body, fixed at set-up (docs/geometry.md)
            call this%file%dataset(g, 'normal', c%normal, '1')
            ! the body whose boundary Gamma_c is (1-based, as /mesh/body)
            call this%file%attr(g, 'slave_body', model%pairs(ip)%slave_body)
            ! geometry 'current' (docs/geometry.md): the gaps and normals above are those of
            ! the initial configuration; the step refreshes them
            if (c%current) call this%file%attr(g, 'geometry', 'current')
            if (c%friction) then
               call this%file%attr(g, 'friction', c%law%name())
               ! the law's own parameters (Coulomb: friction_coefficient), whatever the law
               call c%law%parameters(pname, pvalue)
               do k = 1, size(pname)
                  call this%file%attr(g, trim(pname(k)), pvalue(k))
               end do
            else
               call this%file%attr(g, 'friction', 'frictionless')
            end if
         end associate
      end subroutine write_pair_setup
   end subroutine output_open

   !> An explicit run's root attributes at the start: the method, the step's bounds, the masses,
   !> the kind of run and the energy put in at t = 0 (docs/output.md).
   subroutine output_attributes_explicit(this, deck, model, initial_kinetic)
      class(output_t), intent(inout) :: this
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: initial_kinetic   !< [mJ]
      if (.not. this%writer) return
      call this%file%attr(this%file%id, 'method', 'explicit')
      call this%file%attr(this%file%id, 'omega_max_element', sqrt(model%stiff%omega2_element))
      call this%file%attr(this%file%id, 'dt_limit', trim(deck%solver%dt_limit))
      call this%file%attr(this%file%id, 'added_mass', model%added_mass)
      call this%file%attr(this%file%id, 'body_mass', model%body_mass)
      if (model%omega2_power > 0) then
         call this%file%attr(this%file%id, 'omega_max_power', sqrt(model%omega2_power))
         call this%file%attr(this%file%id, 'dt_stable_estimate', 2/sqrt(model%omega2_power))
      end if
      call this%file%attr(this%file%id, 'dynamic', merge(1, 0, deck%dynamic))
      call this%file%attr(this%file%id, 'convergence_test', merge(1, 0, deck%convergence_test))
      call this%file%attr(this%file%id, 'initial_kinetic_energy', initial_kinetic)
   end subroutine output_attributes_explicit

   !> An explicit run's closing root attributes: output:snapshot_times after the end of the run
   !> (if any), the step it started with and the step of the growing-mode fallback (-1: none).
   subroutine output_attributes_explicit_end(this, snap_missed, dt_initial, fallback_step)
      class(output_t), intent(inout) :: this
      real(wp), intent(in) :: snap_missed(:)   !< [s]
      real(wp), intent(in) :: dt_initial       !< [s]
      integer, intent(in) :: fallback_step
      if (.not. this%writer) return
      if (size(snap_missed) > 0) call this%file%attr(this%file%id, 'snapshot_times_not_reached', snap_missed)
      call this%file%attr(this%file%id, 'dt_initial', dt_initial)
      call this%file%attr(this%file%id, 'dt_fallback_step', fallback_step)
   end subroutine output_attributes_explicit_end

   !> solver:compare_static: the energy distance of the end state to the static solution and
   !> whether the static engine converged.
   subroutine output_attributes_compare_static(this, dist, converged)
      class(output_t), intent(inout) :: this
      real(wp), intent(in) :: dist
      logical, intent(in) :: converged
      if (.not. this%writer) return
      call this%file%attr(this%file%id, 'static_distance_energy', dist)
      call this%file%attr(this%file%id, 'static_converged', merge(1, 0, converged))
   end subroutine output_attributes_compare_static

   !> A static run's root attributes at the start: those an explicit file has, with their static
   !> values (docs/output.md).
   subroutine output_attributes_static(this, deck, model)
      class(output_t), intent(inout) :: this
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      if (.not. this%writer) return
      call this%file%attr(this%file%id, 'method', 'static')
      call this%file%attr(this%file%id, 'omega_max_element', sqrt(model%stiff%omega2_element))
      call this%file%attr(this%file%id, 'dt_limit', trim(deck%solver%dt_limit))
      call this%file%attr(this%file%id, 'dt_initial', 0.0_wp)
      call this%file%attr(this%file%id, 'dt_fallback_step', -1)
      call this%file%attr(this%file%id, 'added_mass', model%added_mass)
      call this%file%attr(this%file%id, 'body_mass', model%body_mass)
      call this%file%attr(this%file%id, 'dynamic', 0)
      call this%file%attr(this%file%id, 'convergence_test', 1)
      call this%file%attr(this%file%id, 'initial_kinetic_energy', 0.0_wp)
   end subroutine output_attributes_static

   !> A static run's closing root attributes: the largest KKT residuals, the increments, steps
   !> and halvings, the iterations, the factor's size and the engine's times (docs/output.md).
   subroutine output_attributes_static_end(this, fig)
      class(output_t), intent(inout) :: this
      type(static_figures_t), intent(in) :: fig
      integer :: i
      if (.not. this%writer) return
      do i = 1, 4
         call this%file%attr(this%file%id, 'kkt_'//trim(kkt_names(i)), fig%kkt_max(i))
      end do
      call this%file%attr(this%file%id, 'static_increments', fig%increments)
      call this%file%attr(this%file%id, 'static_steps', fig%steps)
      call this%file%attr(this%file%id, 'static_splits', fig%splits)
      call this%file%attr(this%file%id, 'static_iterations', fig%iterations)
      call this%file%attr(this%file%id, 'static_outer_iterations', fig%outer_iterations)
      call this%file%attr(this%file%id, 'factor_nonzeros', fig%factor_nonzeros)
      call this%file%attr(this%file%id, 'factor_flops', fig%factor_flops)
      call this%file%attr(this%file%id, 'time_factor_seconds', fig%time_factor)
      call this%file%attr(this%file%id, 'time_condense_seconds', fig%time_condense)
      call this%file%attr(this%file%id, 'time_solve_seconds', fig%time_solve)
   end subroutine output_attributes_static_end

   !> Record one history sample (buffered).
   !> The contact's maxima and counts since the last sample are reset (they are per sample).
   subroutine output_sample(this, state, residual)
      class(output_t), intent(inout) :: this
      type(state_t), intent(inout) :: state
      real(wp), intent(in) :: residual
      integer(i8) :: now, rate
      integer :: k, ip
      real(wp) :: obstacle_now(3)
      real(wp) :: tot(8)   !< the pairs' contact figures (the order of the series)
      if (.not. this%writer) then   ! (the per-sample maxima end here on every rank alike)
         do ip = 1, size(state%contacts)
            state%contacts(ip)%stick_increment_max = 0
            state%contacts(ip)%status_changes = 0
            state%contacts(ip)%penetration_max = 0
         end do
         return
      end if
      obstacle_now = 0
      if (this%nactive == nseries) then
         ! the obstacle's motion: the first moving pair's
         do ip = 1, size(state%contacts)
            if (.not. allocated(state%contacts(ip)%obstacle)) cycle
            if (.not. state%contacts(ip)%obstacle%moving) cycle
            obstacle_now(1:2) = state%contacts(ip)%obstacle%displacement(state%time)
            obstacle_now(3) = state%contacts(ip)%obstacle%angle(state%time)
            exit
         end do
      end if
      if (allocated(this%slip_buf)) then
         ! slip velocity of the last step relative to the obstacle's surface point, along t_i:
         ! v^(n+1/2).t_i - Delta s_i.t_i / dt (0 where a node sticks)
         associate (c => state%contacts(1), nc => state%contacts(1)%nc)
            do k = 1, nc
               this%slip_buf(this%nbuf*nc + k) = dot_product(state%v(:, c%node(k)), c%tangent(:, k))
               if (state%dt > 0) this%slip_buf(this%nbuf*nc + k) = this%slip_buf(this%nbuf*nc + k) - c%ds(1, k)/state%dt
            end do
         end associate
      end if
      this%nbuf = this%nbuf + 1
      ! the contact figures: the one pair's as they are, several pairs' summed (largest values
      ! for the maxima) in pair order; no pair: zeros
      tot = 0
      do ip = 1, size(state%contacts)
         associate (c => state%contacts(ip))
            if (ip == 1) then
               tot = [c%friction_dissipation, c%normal_total, c%tangential_total, c%normal_work, &
                      c%stick_increment_max, real(c%status_changes, wp), c%penetration_max, c%obstacle_work]
            else
               tot = tot + [c%friction_dissipation, c%normal_total, c%tangential_total, c%normal_work, &
                            0.0_wp, real(c%status_changes, wp), 0.0_wp, c%obstacle_work]
               tot(5) = max(tot(5), c%stick_increment_max)
               tot(7) = max(tot(7), c%penetration_max)
            end if
            if (allocated(this%pair_buf)) this%pair_buf(this%nbuf, :, ip) = &
               [c%friction_dissipation, c%normal_total, c%tangential_total, c%normal_work, c%obstacle_work, &
                c%penetration_max]
         end associate
      end do
      this%buffer(this%nbuf, :) = [state%time, state%kinetic, state%strain, state%external_work, &
                                   tot(1), state%damping_dissipation, &
                                   state%balance_error(), &
                                   residual, tot(2), tot(3), tot(4), &
                                   real(state%step, wp), state%alpha, tot(5), &
                                   tot(6), tot(7), &
                                   state%kinetic_step, state%strain_step, tot(8), obstacle_now]
      do ip = 1, size(state%contacts)
         state%contacts(ip)%stick_increment_max = 0
         state%contacts(ip)%status_changes = 0
         state%contacts(ip)%penetration_max = 0
      end do
      call system_clock(now, rate)
      if (this%nbuf == flush_samples .or. real(now - this%last_flush_clock, wp) > flush_seconds*rate) then
         call this%flush_history()
      end if
   end subroutine output_sample

   !> /fields/<step>: a snapshot of the displacement (and the contact fields) at this step.
   subroutine output_snapshot(this, model, state)
      class(output_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: state
      integer(hid_t) :: fields, g, gc, gp
      integer :: ip
      if (.not. this%writer) return
      if (this%fields < 0) this%fields = this%file%group(this%file%id, 'fields')
      fields = this%fields
      g = this%file%group(fields, str(state%step))
      call this%file%attr(g, 'time', state%time)
      call this%file%attr(g, 'step', int(state%step))
      call this%file%dataset(g, 'displacement', model%mesh%file_order(state%u), 'mm')
      ! the contact fields: the one pair's in the step's group, several pairs' in
      ! contact/<name> below it (docs/output.md)
      if (size(state%contacts) == 1) then
         call snapshot_contact(this, g, state%contacts(1))
      else if (size(state%contacts) > 1) then
         gc = this%file%group(g, 'contact')
         do ip = 1, size(state%contacts)
            gp = this%file%group(gc, model%pairs(ip)%name)
            call snapshot_contact(this, gp, state%contacts(ip))
            call this%file%close_group(gp)
         end do
         call this%file%close_group(gc)
      end if
      call this%file%close_group(g)
      call this%file%flush()
      if (this%nsnap < size(this%snap_step)) then
         this%nsnap = this%nsnap + 1
         this%snap_step(this%nsnap) = state%step
         this%snap_time(this%nsnap) = state%time
      end if
   end subroutine output_snapshot

   !> One pair's contact fields of a snapshot in group g.
   subroutine snapshot_contact(this, g, c)
      type(output_t), intent(inout) :: this
      integer(hid_t), intent(in) :: g
      type(contact_t), intent(in) :: c
      real(wp) :: pressure(c%nc), shear(c%nc)
      integer :: status(c%nc), info
      if (.not. c%active) return
      call this%file%dataset(g, 'contact_normal_force', c%fn, 'N/mm')
      call this%file%dataset(g, 'contact_tangential_force', c%ft, 'N/mm')
      ! the multiplier fields and statuses as /final/contact has them (SPEC section 3)
      call c%fields(pressure, shear, info)
      call c%status(status)
      call this%file%dataset(g, 'contact_pressure', pressure, 'MPa')
      call this%file%dataset(g, 'contact_shear', shear, 'MPa')
      call this%file%dataset(g, 'contact_status', status, '0 separated, 1 stick, 2 slip')
   end subroutine snapshot_contact

   !> Append the buffered samples and flush the file.
   subroutine output_flush_history(this)
      class(output_t), intent(inout) :: this
      integer :: k, ip
      if (.not. this%writer) return
      if (this%nbuf > 0) then
         do k = 1, this%nactive
            call this%series(k)%append(this%file, this%buffer(1:this%nbuf, k))
         end do
         if (allocated(this%slip_buf)) &
            call this%slip_series%append(this%file, this%slip_buf(1:this%nbuf*size(this%slip_buf)/flush_samples))
         if (allocated(this%pair_series)) then
            do ip = 1, size(this%pair_series, 2)
               do k = 1, npair_series
                  call this%pair_series(k, ip)%append(this%file, this%pair_buf(1:this%nbuf, k, ip))
               end do
            end do
         end if
         this%nbuf = 0
      end if
      call this%file%flush()
      call system_clock(this%last_flush_clock)
   end subroutine output_flush_history

   !> Write /final and the closing attributes (the state's status and convergence last), close
   !> the file, write the XDMF sidecar.
   subroutine output_finish(this, model, state, wall_seconds, timings, stat, errmsg)
      class(output_t), intent(inout) :: this
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: state
      real(wp), intent(in) :: wall_seconds
      real(wp), intent(in) :: timings(:)   !< set-up, step loop, contact, output [s]
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer(hid_t) :: root, g, gc, gp
      real(wp), allocatable :: stress(:, :), reaction(:, :)
      real(wp) :: dmat(3, 3)
      integer :: e, k, a, b

      if (.not. this%writer) then
         stat = 0
         errmsg = ''
         return
      end if
      call this%flush_history()
      do k = 1, this%nactive
         call this%series(k)%close(this%file)
      end do
      call this%slip_series%close(this%file)
      if (allocated(this%pair_series)) then
         do b = 1, size(this%pair_series, 2)
            do k = 1, npair_series
               call this%pair_series(k, b)%close(this%file)
            end do
         end do
      end if
      call this%file%close_group(this%history)
      call this%file%close_group(this%fields)
      root = this%file%id
      call this%file%attr(root, 'steps', int(state%step))
      call this%file%attr(root, 'wall_seconds', wall_seconds)
      call this%file%attr(root, 'time_setup_seconds', timings(1))
      call this%file%attr(root, 'time_steps_seconds', timings(2))
      call this%file%attr(root, 'time_contact_seconds', timings(3))
      call this%file%attr(root, 'time_output_seconds', timings(4))
      call this%file%attr(root, 'final_time', state%time)

      allocate (stress(3, model%mesh%nel))
      ! each body's elements with that body's material
      do b = 1, size(model%bodies)
         dmat = model%bodies(b)%material%dmat()
         do k = 1, size(model%bodies(b)%elements)
            e = model%bodies(b)%elements(k)
            stress(:, e) = model%stiff%element%stress_average(model%mesh%element_coordinates(e), dmat, &
                                                              [(state%u(:, model%mesh%conn(a, e)), a=1, 4)])
         end do
      end do
      reaction = (state%fint - state%fext)*(1 - model%load%free)
      g = this%file%group(root, 'final')
      call this%file%dataset(g, 'displacement', model%mesh%file_order(state%u), 'mm')
      call this%file%dataset(g, 'velocity', model%mesh%file_order(state%v), 'mm/s')
      call this%file%dataset(g, 'stress', stress, 'MPa')
      call this%file%dataset(g, 'reaction', model%mesh%file_order(reaction), 'N/mm')
      ! /final/contact: the one pair's, or /final/contact/<name> for each of several
      if (size(state%contacts) == 1) then
         if (state%contacts(1)%active) then
            gc = this%file%group(g, 'contact')
            call write_final_contact(this, gc, state%contacts(1))
            call this%file%close_group(gc)
         end if
      else if (size(state%contacts) > 1) then
         gc = this%file%group(g, 'contact')
         do k = 1, size(state%contacts)
            gp = this%file%group(gc, model%pairs(k)%name)
            call write_final_contact(this, gp, state%contacts(k))
            call this%file%close_group(gp)
         end do
         call this%file%close_group(gc)
      end if
      call this%file%close_group(g)
      ! the status last: a file whose /final failed to be written still says 'running'
      call this%file%attr(root, 'converged', merge(1, 0, state%converged))
      call this%file%attr(root, 'status', state%status)
      call this%file%close()
      stat = this%file%stat
      errmsg = ''
      if (stat /= 0) then
         errmsg = this%file%errmsg
         return
      end if
      if (this%xdmf) call write_xdmf(this%xmf_path, this%h5_name, model, this%snap_step(1:this%nsnap), &
                                     this%snap_time(1:this%nsnap), stat, errmsg)
   end subroutine output_finish

   !> /final/contact (or /final/contact/<name>), group g: a pair's nodal forces, multiplier
   !> fields and status (SPEC section 8).
   subroutine write_final_contact(this, g, contact)
      type(output_t), intent(inout) :: this
      integer(hid_t), intent(in) :: g
      type(contact_t), intent(in) :: contact   !< the state's contact operator of the pair
      real(wp) :: pressure(contact%nc), shear(contact%nc)
      integer :: status(contact%nc), info
      associate (c => contact)
         call c%fields(pressure, shear, info)
         call c%status(status)
         call this%file%dataset(g, 'normal_force', c%fn, 'N/mm')
         call this%file%dataset(g, 'tangential_force', c%ft, 'N/mm')
         call this%file%dataset(g, 'pressure', pressure, 'MPa')
         call this%file%dataset(g, 'shear', shear, 'MPa')
         call this%file%dataset(g, 'status', status, '0 separated, 1 stick, 2 slip')
      end associate
   end subroutine write_final_contact

   !> The body of each node (nnode, in the file's order of the nodes): the lowest body index of
   !> its elements (a node on the curve where bonded bodies meet belongs to both).
   function node_body(model) result(nb)
      type(model_t), intent(in) :: model
      integer, allocatable :: nb(:)
      integer, allocatable :: own(:)
      integer :: e, a, n
      allocate (own(model%mesh%nnode), nb(model%mesh%nnode))
      own = huge(1)
      do e = 1, model%mesh%nel
         do a = 1, 4
            n = model%mesh%conn(a, e)
            own(n) = min(own(n), model%body_of(e))
         end do
      end do
      nb(model%mesh%file_id([(n, n=1, model%mesh%nnode)])) = own
   end function node_body

   !> <output>.xmf next to the HDF5 file (docs/output.md, "XDMF sidecar"), every array a reference
   !> into the HDF5 file: the mesh with the final displacement, velocity and stress; the contact
   !> boundary as a polyline through the contact nodes with the final contact fields; and, with
   !> snapshots, two XDMF temporal collections (one grid per /fields/<step> at its time): the mesh
   !> with the displacement, the polyline with the contact fields.
   subroutine write_xdmf(xmf, h5path, model, snap_step, snap_time, stat, errmsg)
      character(len=*), intent(in) :: xmf, h5path
      type(model_t), intent(in) :: model
      integer(i8), intent(in) :: snap_step(:)   !< the /fields/<step> groups, in time order
      real(wp), intent(in) :: snap_time(:)      !< their times [s]
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      character(len=:), allocatable :: base, nn, ne, nc, nseg, seg, text, ind, field
      !> the pair's paths and grid-name suffix: /contact, /final/contact and '' for one pair,
      !> /contact/<name>, /final/contact/<name> and '_<name>' for each of several
      character(len=:), allocatable :: cpath, fpath, suffix, spath
      logical :: has_line   !< a contact boundary of >= 2 nodes: the polyline grids
      integer :: slash, i, k, ip

      slash = index(h5path, '/', back=.true.)
      base = h5path(slash + 1:)
      nn = str(model%mesh%nnode)
      ne = str(model%mesh%nel)
      text = ''
      ind = ''
      call put('<?xml version="1.0" ?>')
      call put('<Xdmf Version="2.0">')
      call put(' <Domain>')
      ind = '  '
      call put('<Grid Name="final" GridType="Uniform">')
      call mesh()
      call vector('displacement', '/final/displacement')
      call vector('velocity', '/final/velocity')
      call put(' <Attribute Name="stress_xx_yy_xy" AttributeType="Matrix" Center="Cell">')
      call put('  <DataItem Dimensions="'//ne//' 3" NumberType="Float" Precision="8" Format="HDF">'// &
         base//':/final/stress</DataItem>')
      call put(' </Attribute>')
      ! the body of each element and of each node (1-based, /mesh/body and /mesh/node_body)
      call put(' <Attribute Name="body" AttributeType="Scalar" Center="Cell">')
      call put('  <DataItem Dimensions="'//ne//'" NumberType="Int" Format="HDF">'//base//':/mesh/body</DataItem>')
      call put(' </Attribute>')
      call put(' <Attribute Name="node_body" AttributeType="Scalar" Center="Node">')
      call put('  <DataItem Dimensions="'//nn//'" NumberType="Int" Format="HDF">'//base//':/mesh/node_body</DataItem>')
      call put(' </Attribute>')
      call put('</Grid>')
      ! one contact grid per pair
      do ip = 1, size(model%contacts)
         call pair_line(ip)
         if (.not. has_line) cycle
         call put('<Grid Name="contact_final'//suffix//'" GridType="Uniform">')
         call polyline()
         call contact_fields(fpath//'/pressure', fpath//'/shear', fpath//'/status', &
                             fpath//'/normal_force', fpath//'/tangential_force')
         call put('</Grid>')
      end do
      if (size(snap_step) > 0) then
         call put('<Grid Name="snapshots" GridType="Collection" CollectionType="Temporal">')
         do k = 1, size(snap_step)
            field = '/fields/'//str(snap_step(k))
            call put(' <Grid Name="step_'//str(snap_step(k))//'" GridType="Uniform">')
            ind = '    '
            call put('<Time Value="'//str(snap_time(k))//'"/>')
            call mesh()
            call vector('displacement', field//'/displacement')
            ind = '  '
            call put(' </Grid>')
         end do
         call put('</Grid>')
         do ip = 1, size(model%contacts)
            call pair_line(ip)
            if (.not. has_line) cycle
            call put('<Grid Name="contact_snapshots'//suffix//'" GridType="Collection" CollectionType="Temporal">')
            do k = 1, size(snap_step)
               field = '/fields/'//str(snap_step(k))//spath
               call put(' <Grid Name="contact'//suffix//'_step_'//str(snap_step(k))//'" GridType="Uniform">')
               ind = '    '
               call put('<Time Value="'//str(snap_time(k))//'"/>')
               call polyline()
               call contact_fields(field//'/contact_pressure', field//'/contact_shear', field//'/contact_status', &
                                   field//'/contact_normal_force', field//'/contact_tangential_force')
               ind = '  '
               call put(' </Grid>')
            end do
            call put('</Grid>')
         end do
      end if
      ind = ''
      call put(' </Domain>')
      call put('</Xdmf>')
      ! written whole, every write, fsync and close checked (a full disk is an error, not an
      ! empty sidecar)
      stat = sys_write_file(xmf, text)
      errmsg = ''
      if (stat /= 0) errmsg = 'cannot write '//xmf//': '//sys_strerror(stat)
   contains
      !> Pair ip's polyline: segments between consecutive contact nodes (by abscissa), indices
      !> into its coordinates (0-based, as XDMF wants), and its paths.
      subroutine pair_line(ip)
         integer, intent(in) :: ip
         associate (c => model%contacts(ip))
            has_line = c%active .and. c%nc >= 2
            nc = str(c%nc)
            nseg = str(c%nc - 1)
            seg = ''
            if (has_line) then
               do i = 0, c%nc - 2
                  seg = seg//' '//str(i)//' '//str(i + 1)
               end do
               seg = seg(2:)
            end if
         end associate
         if (size(model%contacts) == 1) then
            cpath = '/contact'
            fpath = '/final/contact'
            suffix = ''
            spath = ''
         else
            cpath = '/contact/'//model%pairs(ip)%name
            fpath = '/final/contact/'//model%pairs(ip)%name
            suffix = '_'//model%pairs(ip)%name
            spath = '/contact/'//model%pairs(ip)%name
         end if
      end subroutine pair_line
      subroutine put(line)
         character(len=*), intent(in) :: line
         text = text//ind//line//new_line('a')
      end subroutine put
      !> the quadrilateral mesh: topology and reference geometry
      subroutine mesh()
         call put(' <Topology TopologyType="Quadrilateral" NumberOfElements="'//ne//'">')
         ! connectivity is 1-based in the file; XDMF wants 0-based
         call put('  <DataItem ItemType="Function" Function="$0 - 1" Dimensions="'//ne//' 4">')
         call put('   <DataItem Dimensions="'//ne//' 4" NumberType="Int" Format="HDF">'// &
            base//':/mesh/connectivity</DataItem>')
         call put('  </DataItem>')
         call put(' </Topology>')
         call put(' <Geometry GeometryType="XY">')
         call put('  <DataItem Dimensions="'//nn//' 2" NumberType="Float" Precision="8" Format="HDF">'// &
            base//':/mesh/coordinates</DataItem>')
         call put(' </Geometry>')
      end subroutine mesh
      !> the contact boundary: nc - 1 two-node segments through the contact nodes' coordinates
      subroutine polyline()
         call put(' <Topology TopologyType="Polyline" NodesPerElement="2" NumberOfElements="'//nseg//'">')
         call put('  <DataItem Dimensions="'//nseg//' 2" NumberType="Int" Format="XML">'//seg//'</DataItem>')
         call put(' </Topology>')
         call put(' <Geometry GeometryType="XY">')
         call put('  <DataItem Dimensions="'//nc//' 2" NumberType="Float" Precision="8" Format="HDF">'// &
            base//':'//cpath//'/coordinates</DataItem>')
         call put(' </Geometry>')
      end subroutine polyline
      !> the contact fields on the polyline's nodes, and the initial gap
      subroutine contact_fields(pressure, shear, status, fn, ft)
         character(len=*), intent(in) :: pressure, shear, status, fn, ft
         call scalar('pressure', pressure, 'Float')
         call scalar('shear', shear, 'Float')
         call scalar('status', status, 'Int')
         call scalar('normal_force', fn, 'Float')
         call scalar('tangential_force', ft, 'Float')
         call scalar('gap', cpath//'/gap', 'Float')
      end subroutine contact_fields
      subroutine scalar(name, path, kind)
         character(len=*), intent(in) :: name, path, kind
         call put(' <Attribute Name="'//name//'" AttributeType="Scalar" Center="Node">')
         if (kind == 'Int') then
            call put('  <DataItem Dimensions="'//nc//'" NumberType="Int" Format="HDF">'//base//':'//path//'</DataItem>')
         else
            call put('  <DataItem Dimensions="'//nc//'" NumberType="Float" Precision="8" Format="HDF">'// &
               base//':'//path//'</DataItem>')
         end if
         call put(' </Attribute>')
      end subroutine scalar
      subroutine vector(name, path)
         character(len=*), intent(in) :: name, path
         ! pad (x, y) with a zero z so that ParaView's Warp By Vector works
         call put(' <Attribute Name="'//name//'" AttributeType="Vector" Center="Node">')
         call put('  <DataItem ItemType="Function" Function="JOIN($0, $1, 0*$1)" Dimensions="'//nn//' 3">')
         call put('   <DataItem ItemType="HyperSlab" Dimensions="'//nn//' 1">')
         call put('    <DataItem Dimensions="3 2" Format="XML">0 0 1 1 '//nn//' 1</DataItem>')
         call put('    <DataItem Dimensions="'//nn//' 2" NumberType="Float" Precision="8" Format="HDF">'// &
            base//':'//path//'</DataItem>')
         call put('   </DataItem>')
         call put('   <DataItem ItemType="HyperSlab" Dimensions="'//nn//' 1">')
         call put('    <DataItem Dimensions="3 2" Format="XML">0 1 1 1 '//nn//' 1</DataItem>')
         call put('    <DataItem Dimensions="'//nn//' 2" NumberType="Float" Precision="8" Format="HDF">'// &
            base//':'//path//'</DataItem>')
         call put('   </DataItem>')
         call put('  </DataItem>')
         call put(' </Attribute>')
      end subroutine vector
   end subroutine write_xdmf
end module contact2d_output
