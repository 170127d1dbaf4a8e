!> What a run prints on stdout and the warnings it gives on stderr: the header (the run's
!> line, the effective deck, the model's warnings, the mesh), the time-step lines, the progress
!> line and the summaries (docs/quickstart.md "What a run prints"). Nothing here stops the run.
module contact2d_report
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   use contact2d_kinds, only: wp, i8
   use contact2d_version, only: program_name, program_version
   use contact2d_strings, only: str, fixed, sci, printable
   use contact2d_deck, only: deck_t, edge_load_cfg_t
   use contact2d_model, only: model_t
   use contact2d_state, only: state_t
   use contact2d_contact, only: contact_t
   use contact2d_threads, only: thread_tuner_t
   use contact2d_static, only: static_t, prox_eps
   use contact2d_kkt, only: kkt_names
   implicit none
   private
   public :: report_header, report_time_step, ramp_warning, progress_line, report_summary, summary_contact_status
   public :: report_threads, report_static_summary

   !> A load ramp covered by fewer steps than this is warned about (ramp_warning).
   real(wp), parameter :: ramp_steps_min = 10

contains

   !> The run's first lines: program, deck and output; the effective deck (unless quiet); the
   !> model's warnings on stderr; the mesh line.
   subroutine report_header(deck_path, output, quiet, deck, model)
      character(len=*), intent(in) :: deck_path, output
      logical, intent(in) :: quiet
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      character(len=:), allocatable :: extent
      integer :: i
      write (output_unit, '(a)') program_name//' '//program_version//': '//printable(deck_path//' -> '//output)
      if (.not. quiet) then
         write (output_unit, '(a)') '--- effective deck ---'
         write (output_unit, '(a)', advance='no') deck%effective
         write (output_unit, '(a)') '----------------------'
      end if
      do i = 1, model%warnings%n
         write (error_unit, '(a)') program_name//': warning: '//printable(trim(model%warnings%items(i)))
      end do
      if (model%mesh%nx > 0) then
         extent = str(model%mesh%nx)//' x '//str(model%mesh%ny)//' ='
      else
         extent = 'from '//trim(deck%mesh%file)//':'
      end if
      write (output_unit, '(a)') 'mesh '//extent//' '// &
         str(model%mesh%nel)//' Q1 elements, '//str(model%mesh%nnode)//' nodes, '// &
         str(model%stiff%nshape)//' distinct element matrix(es)'
      ! the bodies of a deck with &body groups (one body, the whole mesh, otherwise: the deck's
      ! &material, echoed above)
      if (size(deck%body) > 0) then
         do i = 1, size(model%bodies)
            associate (b => model%bodies(i), c => deck%body(i))
               write (output_unit, '(a)') 'body '//str(i)//" '"//printable(b%name)//"': "// &
                  str(size(b%elements))//' elements, E = '//str(c%young)//' MPa, nu = '//str(c%poisson)// &
                  ', rho = '//str(c%density)//' t/mm^3'
            end associate
         end do
      end if
   end subroutine report_header

   !> A warning when the first stage that moves a load (a &dirichlet or &traction curve: its first
   !> stage whose end value differs from the value before it) lasts fewer than ramp_steps_min
   !> steps of dt, the shortest such stage named; '' otherwise. Typical of units that do not go
   !> together (SI material values with lengths in mm make dt 1000 x too long): the load is then
   !> applied in a few steps, and the run may end before anything happens. Curves that only hold
   !> a value (the rollers of the impact decks) are not ramps.
   function ramp_warning(deck, dt) result(msg)
      type(deck_t), intent(in) :: deck
      real(wp), intent(in) :: dt
      character(len=:), allocatable :: msg, name
      real(wp) :: shortest
      integer :: i
      msg = ''
      name = ''
      shortest = huge(1.0_wp)
      do i = 1, size(deck%dirichlet)
         call first_ramp(deck%dirichlet(i), 'dirichlet#'//str(i))
      end do
      do i = 1, size(deck%traction)
         call first_ramp(deck%traction(i), 'traction#'//str(i))
      end do
      if (len(name) == 0 .or. .not. shortest < ramp_steps_min*dt) return
      msg = 'the load ramp of '//name//' lasts '//sci(shortest)//' s, only '//fixed(shortest/dt, 1)// &
            ' step(s) of dt = '//sci(dt)//' s (fewer than '//str(nint(ramp_steps_min))//'): the load is '// &
            'applied almost at once; check the units (the shipped decks use mm, N, MPa, t/mm^3 and s: '// &
            'material:young in Pa and density in kg/m^3 with lengths in mm make dt 1000 x too long)'
   contains
      subroutine first_ramp(cfg, label)
         type(edge_load_cfg_t), intent(in) :: cfg
         character(len=*), intent(in) :: label
         real(wp) :: t0, v0
         integer :: k
         t0 = 0
         v0 = 0
         do k = 1, cfg%nstage
            if (cfg%values(k) /= v0) then
               if (cfg%times(k) - t0 < shortest) then
                  shortest = cfg%times(k) - t0
                  name = label//' (stage '//str(k)//')'
               end if
               return
            end if
            t0 = cfg%times(k)
            v0 = cfg%values(k)
         end do
      end subroutine first_ramp
   end function ramp_warning

   !> The time-step lines (contact2d_timestep): dt against dt_critical and its bound, the
   !> power-iteration estimate, the mass added by mass scaling.
   subroutine report_time_step(model, iterations, mass_scaling)
      type(model_t), intent(in) :: model
      integer, intent(in) :: iterations     !< solver:power_iterations
      real(wp), intent(in) :: mass_scaling  !< solver:mass_scaling [s]
      character(len=:), allocatable :: bound
      bound = 'element bound 2/omega_max'
      if (model%scaled_nodes > 0) bound = 'bound with mass scaling'
      if (any(model%contacts%penalty)) bound = bound//trim(merge(' and ', ' with', model%scaled_nodes > 0))//' the penalty springs'
      write (output_unit, '(a)') 'dt = '//sci(model%dt)//' s = '//fixed(model%dt/model%dt_critical, 3)// &
         ' dt_critical ('//bound//' = '//sci(model%dt_critical)//' s)'
      if (model%omega2_power > 0) then
         write (output_unit, '(a)') 'power iteration ('//str(iterations)//' its): omega_max >= '// &
            sci(sqrt(model%omega2_power))//' 1/s, true stable limit <= '//sci(2/sqrt(model%omega2_power))//' s = '// &
            fixed(2/sqrt(model%omega2_power)/model%dt_critical, 3)//' dt_critical (the element bound is conservative)'
      end if
      if (model%added_mass > 0) then
         write (output_unit, '(a)') 'mass scaling: '//sci(model%added_mass)//' t added at '//str(model%scaled_nodes)// &
            ' node(s) ('//sci(model%added_mass/model%body_mass)//' of the body mass) for a stable step of '// &
            sci(mass_scaling)//' s'
      end if
   end subroutine report_time_step

   !> The progress line (a terminal only), rewritten in place: step, time, residual, ETA.
   subroutine progress_line(state, deck, residual, elapsed)
      type(state_t), intent(in) :: state
      type(deck_t), intent(in) :: deck
      real(wp), intent(in) :: residual, elapsed
      real(wp) :: frac, eta
      character(len=:), allocatable :: line
      frac = max(state%time/deck%solver%t_end, real(state%step, wp)/deck%solver%max_steps)
      eta = elapsed*(1 - frac)/max(frac, 1.0e-12_wp)
      line = 'step '//str(state%step)//'  t = '//sci(state%time)//' s  residual '// &
             sci(residual)//'  ETA <= '//fixed(eta, 1)//' s   '
      write (output_unit, '(a)', advance='no') achar(13)//line
      flush (output_unit)
   end subroutine progress_line

   !> Contact lines of the summary of one pair: status counts, extent, pressure sign,
   !> penetration. label: 'contact', or 'contact <name>' with several pairs.
   subroutine contact_summary(state, c, label)
      type(state_t), intent(in) :: state
      type(contact_t), intent(in) :: c
      character(len=*), intent(in) :: label
      integer :: status(c%nc), info, nneg
      real(wp) :: pressure(c%nc), shear(c%nc)
      block
         call c%status(status)
         call c%fields(pressure, shear, info)
         call summary_contact_status(c, status, label)
         nneg = count(pressure < 0)
         write (output_unit, '(a)', advance='no') ' contact pressure    max '//sci(maxval(pressure))//' MPa'
         if (nneg > 0) then
            write (output_unit, '(a)') '; negative at '//str(nneg)//' node(s), min '//sci(minval(pressure))// &
               ' MPa (recovered multiplier, reported as is)'
         else
            write (output_unit, '(a)') '; nowhere negative'
         end if
         write (output_unit, '(a)') ' penetration         '//sci(c%penetration(state%u))//' mm (max'// &
            trim(merge(' per dual cell)', ' per node)     ', c%multiplier_name() == 'P0'))
         ! two bodies: the search's interval and clock, the LCP's largest violation (of this pair)
         if (c%body) then
            associate (mb => c%master)
               write (output_unit, '(a)') ' contact search      '//str(int(mb%searches))//' bucket search(es) in '// &
                  str(int(mb%steps))//' steps (one every '//fixed(real(mb%steps, wp)/max(real(mb%searches, wp), 1.0_wp), 1)// &
                  ' steps: at 1/4 of the shortest master edge of relative motion); '// &
                  fixed(real(mb%search_ticks, wp)/max(real(c%clock_ticks, wp), 1.0_wp)*100, 1)//' % of the contact time'
               write (output_unit, '(a)') ' contact LCP         '//str(int(mb%lcp_iterations))// &
                  ' active-set iterations; largest violation max(-w)/max|b| '//sci(mb%residual_max)
            end associate
         end if
      end block
   end subroutine contact_summary

   !> The summary's label of pair k: 'contact' for one pair, 'contact <name>' for several.
   function pair_label(model, k) result(label)
      type(model_t), intent(in) :: model
      integer, intent(in) :: k
      character(len=:), allocatable :: label
      label = 'contact'
      if (size(model%pairs) > 1) label = 'contact '//model%pairs(k)%name
   end function pair_label

   !> The summary of an explicit run (docs/quickstart.md "What a run prints").
   subroutine report_summary(model, deck, state, path, residual, wall, timings, dt_initial, fallback_step, snap_missed)
      type(model_t), intent(in) :: model
      type(deck_t), intent(in) :: deck
      type(state_t), intent(in) :: state
      character(len=*), intent(in) :: path
      real(wp), intent(in) :: residual, wall, timings(4), dt_initial
      integer(i8), intent(in) :: fallback_step
      real(wp), intent(in) :: snap_missed(:)   !< output:snapshot_times after the end [s]
      character(len=:), allocatable :: conv, times
      real(wp) :: rate
      integer :: k
      associate (converged => state%converged, status => state%status)
         if (converged) then
            conv = 'yes (relative residual '//sci(residual)//' < '//sci(deck%solver%tol_residual)//')'
         else if (.not. deck%convergence_test) then
            conv = 'not tested (solver:convergence_test = '''//trim(deck%solver%convergence_test)// &
                   '''); status: '//status
         else
            conv = 'NO: '//status
            ! why the steps ended (a blow-up, a contact failure or a signal say so in the status)
            if (status == 'not converged') then
               if (state%step >= deck%solver%max_steps) then
                  conv = conv//', solver:max_steps = '//str(deck%solver%max_steps)//' reached'
               else
                  conv = conv//', solver:t_end = '//sci(deck%solver%t_end)//' s reached'
               end if
            end if
            conv = conv//' (relative residual '//sci(residual)//', tolerance '//sci(deck%solver%tol_residual)//')'
         end if
         rate = real(state%step, wp)*model%mesh%nel/max(timings(2), 1.0e-9_wp)
         write (output_unit, '(a)') repeat('-', 72)
         write (output_unit, '(a)') ' steps               '//str(state%step)//'   (t = '//sci(state%time)//' s)'
         write (output_unit, '(a)') ' dt / dt_critical    '//fixed(state%dt/model%dt_critical, 4)//'   (dt_limit = '// &
            trim(deck%solver%dt_limit)//')'
         if (fallback_step >= 0) write (output_unit, '(a)') ' growing mode        at step '//str(fallback_step)// &
            ': dt '//sci(dt_initial)//' s -> '//sci(state%dt)//' s (element bound)'
         if (model%added_mass > 0) write (output_unit, '(a)') ' added mass          '//sci(model%added_mass)// &
            ' t at '//str(model%scaled_nodes)//' node(s) = '//sci(model%added_mass/model%body_mass)//' x body mass'
         if (deck%dynamic) write (output_unit, '(a)') ' run                 dynamic: initial velocity ('// &
            sci(deck%initial%velocity(1))//', '//sci(deck%initial%velocity(2))//') mm/s, no damping, '// &
            trim(merge('stops when converged or at t_end =', 'ends at t_end =                   ', deck%convergence_test))//' '// &
            sci(deck%solver%t_end)//' s; initial kinetic energy '//sci(state%initial_kinetic)//' mJ'
         write (output_unit, '(a)') ' converged           '//conv
         if (size(snap_missed) > 0) then
            times = str(snap_missed(1))
            do k = 2, size(snap_missed)
               times = times//', '//str(snap_missed(k))
            end do
            write (output_unit, '(a)') ' snapshots           not reached: output:snapshot_times '//times// &
               ' s (the run ended at t = '//sci(state%time)//' s); '// &
               str(deck%output%nsnapshot - size(snap_missed))//' of '//str(deck%output%nsnapshot)//' written'
         end if
         write (output_unit, '(a)') ' energy balance      '//sci(state%balance_error())// &
            ' (relative error; W_ext = '//sci(state%external_work)//' mJ)'
         ! several pairs: each pair's terms of the balance (it takes their sums, contact2d_state)
         if (size(state%contacts) > 1) then
            do k = 1, size(state%contacts)
               write (output_unit, '(a)') '                     pair '//model%pairs(k)%name//': D_friction = '// &
                  sci(state%contacts(k)%friction_dissipation)//' mJ, W_normal = '// &
                  sci(state%contacts(k)%normal_work)//' mJ, W_obstacle = '//sci(state%contacts(k)%obstacle_work)//' mJ'
            end do
         end if
         ! one set of contact lines per pair
         do k = 1, size(state%contacts)
            if (state%contacts(k)%active) call contact_summary(state, state%contacts(k), pair_label(model, k))
         end do
         write (output_unit, '(a)') ' wall time           '//fixed(wall, 3)//' s (set-up '//fixed(timings(1), 3)// &
            ', steps '//fixed(timings(2), 3)//', contact '//fixed(timings(3), 3)//', output '//fixed(timings(4), 3)//')'
         write (output_unit, '(a)') ' element-steps / s   '//sci(rate)
         write (output_unit, '(a)') ' output              '//printable(path)
         write (output_unit, '(a)') repeat('-', 72)
      end associate
   end subroutine report_summary
   !> The thread tuner's line of the summary (contact2d_threads).
   subroutine report_threads(tuner)
      type(thread_tuner_t), intent(in) :: tuner
      if (tuner%active) write (output_unit, '(a)') ' threads             auto: '//str(tuner%nmax)//' on '// &
         fixed(100*real(tuner%steps(2), wp)/max(1.0_wp, real(sum(tuner%steps), wp)), 1)//' % of the steps, 1 on the rest ('// &
         'started on '//str(tuner%started)//', '//str(tuner%switches)//' switches; set OMP_NUM_THREADS to fix the count)'
      if (allocated(tuner%forced)) write (output_unit, '(a)') ' threads             forced: '//str(tuner%nmax)// &
         ' on '//str(tuner%steps(2))//' steps, 1 on '//str(tuner%steps(1))//' ('//str(tuner%switches)// &
         ' switches, CONTACT2D_THREAD_SWITCHES)'
   end subroutine report_threads

   !> The summary of a static run (docs/static.md): increments, halvings, convergence, the
   !> largest KKT residuals, the contact lines, the engine's times, the output.
   subroutine report_static_summary(st, state, nk, splits, kkt_max, wall, final)
      type(static_t), intent(in) :: st
      type(state_t), intent(in) :: state
      integer, intent(in) :: nk, splits   !< increments asked for, halvings made
      real(wp), intent(in) :: kkt_max(4)  !< largest relative KKT residuals
      real(wp), intent(in) :: wall        !< wall time [s]
      character(len=*), intent(in) :: final   !< where the file is
      integer :: i
      integer, allocatable :: status_c(:)
      character(len=:), allocatable :: asked
      write (output_unit, '(a)') repeat('-', 72)
      write (output_unit, '(a)') ' method              static (CHOLMOD, contact condensed onto Gamma_c, '// &
         'primal-dual active set)'
      if (splits == 0) then
         asked = ' of '//str(nk)
      else
         asked = ' for '//str(nk)
      end if
      write (output_unit, '(a)') ' increments          '//str(state%step)//asked//' ('//str(st%iterations)// &
         ' active-set iterations, '//str(st%outer_iterations)//' threshold passes)'
      ! a body held by contact alone (docs/static.md "Bodies held by contact")
      if (st%prox_iterations > 0) write (output_unit, '(a)') '                     '//str(st%prox_iterations)// &
         ' proximal passes (rigid motions held by contact alone, K + '//str(prox_eps)//' diag(K))'
      if (splits > 0) write (output_unit, '(a)') '                     '//str(splits)//' halving(s): '// &
         'an increment that did not settle was taken again in halves (solver:static_splits)'
      write (output_unit, '(a)') ' converged           '//trim(merge('yes', 'NO ', state%converged))// &
         trim(merge(' '//state%status, repeat(' ', len(state%status) + 1), .not. state%converged))
      do i = 1, 4
         write (output_unit, '(a)') ' KKT '//kkt_names(i)(1:21)//sci(kkt_max(i))//' (relative)'
      end do
      ! (the static engine solves one pair: contact2d_deck)
      if (size(state%contacts) > 0) then
         associate (c => state%contacts(1))
            allocate (status_c(c%nc))
            call c%status(status_c)
            call summary_contact_status(c, status_c, 'contact')
         end associate
      end if
      write (output_unit, '(a)') ' static solve        '//fixed(st%time_factor + st%time_condense + st%time_pdas, 3)// &
         ' s (assembly + factorisation '//fixed(st%time_factor, 3)//', condensation '// &
         fixed(st%time_condense, 3)//', increments '//fixed(st%time_pdas, 3)//')'
      write (output_unit, '(a)') ' wall time           '//fixed(wall, 3)//' s'
      write (output_unit, '(a)') ' output              '//final
      write (output_unit, '(a)') repeat('-', 72)
   end subroutine report_static_summary

   !> The summary's contact lines shared by explicit and static runs: status counts, totals and
   !> the extent of the contact zone (docs/quickstart.md "What a run prints").
   subroutine summary_contact_status(c, status, label)
      type(contact_t), intent(in) :: c
      integer, intent(in) :: status(:)
      character(len=*), intent(in) :: label   !< 'contact', or 'contact <name>' (several pairs)
      character(len=20) :: head
      head = label
      write (output_unit, '(a)') ' '//head//c%multiplier_name()//', '//str(c%nc)//' nodes: '// &
         str(count(status == 1))//' stick, '//str(count(status == 2))//' slip, '// &
         str(count(status == 0))//' separated; total F_n = '//sci(c%normal_total)//' N/mm, F_t = '// &
         sci(c%tangential_total)//' N/mm'
      if (any(status > 0)) then
         write (output_unit, '(a)') '                     in contact from abscissa '// &
            sci(minval(c%abscissa, mask=status > 0))//' to '//sci(maxval(c%abscissa, mask=status > 0))//' mm'
      end if
   end subroutine summary_contact_status
end module contact2d_report
