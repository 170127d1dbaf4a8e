!> The driver: command line -> deck -> model -> time loop -> HDF5, progress and summary.
!> Only this module stops the program (exit 1: bad input or usage, exit 2: the run failed).
module contact2d_driver
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit, compiler_version
   use contact2d_kinds, only: wp, i8
   use contact2d_version, only: program_name, program_version
   use contact2d_strings, only: str, fixed, sci, printable
   use contact2d_cli, only: cli_t, cli_parse, usage
   use contact2d_deck, only: deck_t, deck_read, deck_blame, edge_load_cfg_t
   use contact2d_model, only: model_t, model_build, beside
   use contact2d_explicit, only: explicit_t
   use contact2d_state, only: state_t
   use contact2d_timestep, only: timestep_fallback
   use contact2d_output, only: output_t
   use contact2d_outpath, only: outpath_t
   use contact2d_sys, only: sys_signals_install, sys_signal_pending, sys_strerror, sys_exit_now
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use contact2d_threads, only: thread_tuner_t
   use contact2d_stiffness, only: omp_min_nodes
   use contact2d_build_config, only: sweep_lanes, build_flags
   use contact2d_static_run, only: static_run, static_distance, summary_contact_status
   use contact2d_initial, only: initial_velocity_apply, initial_velocity_warning
   use contact2d_validity, only: validity_t
   implicit none
   private
   public :: driver_main

   !> Seconds between progress-line updates.
   real(wp), parameter :: progress_seconds = 0.5_wp
   !> A load ramp covered by fewer steps than this is warned about (ramp_warning).
   real(wp), parameter :: ramp_steps_min = 10

   !> This run's output names and lock: fail() releases them (docs/output.md, output safety).
   type(outpath_t), save :: opath
   !> Keep OUT.h5.<pid>.partial when the run fails (it holds what was written so far).
   logical, save :: keep_partial = .false.

contains

   subroutine driver_main()
      type(cli_t) :: cli
      type(deck_t) :: deck
      type(model_t) :: model
      type(explicit_t), target :: solver
      type(state_t), target :: state
      type(output_t) :: out
      character(len=:), allocatable :: errmsg
      integer :: stat, i, nstep, isnap
      integer(i8) :: clock0, clock1, clock_last_progress, rate, t_steps, t_output, tick, snap_step
      real(wp) :: residual, t_load_end, timings(4), wall, kin_ratio
      real(wp) :: scale_peak, strain_peak, scale_now
      logical :: converged, done, interactive, sampled
      real(wp), allocatable :: extra(:, :)
      real(wp), allocatable :: snap_missed(:)
      real(wp) :: dt_initial
      type(thread_tuner_t) :: tuner
      integer(i8) :: fallback_step
      real(wp) :: static_dist
      logical :: static_converged, static_written, static_opened, static_ended, ended
      character(len=:), allocatable :: static_msg, dest, mesh_file
      type(validity_t) :: validity

      call system_clock(clock0, rate)
      call tuner%begin()  ! the set-up window of the thread tuner (contact2d_threads)
      static_dist = huge(1.0_wp)
      call cli_parse(cli, stat, errmsg)
      if (stat /= 0) call fail(1, errmsg//' (usage: contact2d --help)')
      if (cli%help) then
         write (output_unit, '(a)') usage
         write (output_unit, '(a)') 'Runs the deck and writes its HDF5 file (default: <deck stem>.h5 here).'
         write (output_unit, '(a)') '  -o, --output FILE   output file'
         write (output_unit, '(a)') '  --force             overwrite an existing output file'
         write (output_unit, '(a)') '  --set G:V=X         override deck variable V of group G (G#i for the i-th'
         write (output_unit, '(a)') '                      &dirichlet or &traction); repeatable; validated as the deck'
         write (output_unit, '(a)') '  -q, --quiet         do not echo the effective deck'
         write (output_unit, '(a)') '  --static            solve the static problem directly (solver:method = ''static'','
         write (output_unit, '(a)') '                      docs/static.md) instead of the explicit march'
         write (output_unit, '(a)') 'Deck reference: docs/deck.md. Output layout: docs/output.md.'
         stop
      end if
      if (cli%version) then
         write (output_unit, '(a)') program_name//' '//program_version
         ! the build, so that a timing can be told apart from another build's (docs/deck.md)
         write (output_unit, '(a)') 'built with '//compiler_version()//', '//build_flags// &
            '; the sweep''s inside rows use '//str(sweep_lanes)//' lanes'
         stop
      end if

      call deck_read(cli%deck, cli%sets, deck, stat, errmsg)
      if (stat /= 0) call fail(1, errmsg)
      ! output names before any set-up (contact2d_outpath)
      mesh_file = ''   ! an input the output must not be, as the deck
      if (len_trim(deck%mesh%file) > 0) mesh_file = beside(cli%deck, trim(deck%mesh%file))
      call opath%check(cli%output, cli%deck, mesh_file, cli%force, deck%output%xdmf, stat, errmsg)
      if (stat /= 0) call fail(1, errmsg)
      call memory_check(deck, stat, errmsg)
      if (stat /= 0) call fail(1, errmsg//deck_blame(deck, errmsg))
      call model_build(deck, model, stat, errmsg)
      if (stat /= 0) call fail(1, errmsg//deck_blame(deck, errmsg))
      errmsg = initial_velocity_warning(model%load%free, deck%initial%velocity)
      if (len(errmsg) > 0) call model%warnings%add(errmsg)

      write (output_unit, '(a)') program_name//' '//program_version//': '//printable(cli%deck//' -> '//cli%output)
      if (.not. cli%quiet) then
         write (output_unit, '(a)') '--- effective deck ---'
         write (output_unit, '(a)', advance='no') deck%effective
         write (output_unit, '(a)') '----------------------'
      end if
      do i = 1, model%warnings%n
         write (error_unit, '(a)') program_name//': warning: '//printable(trim(model%warnings%items(i)))
      end do
      if (model%mesh%nx > 0) then
         errmsg = str(model%mesh%nx)//' x '//str(model%mesh%ny)//' ='
      else
         errmsg = 'from '//trim(deck%mesh%file)//':'
      end if
      write (output_unit, '(a)') 'mesh '//errmsg//' '// &
         str(model%mesh%nel)//' Q1 elements, '//str(model%mesh%nnode)//' nodes, '// &
         str(model%stiff%nshape)//' distinct element matrix(es)'
      if (deck%solver%method == 'static') then
         ! the static engine (docs/static.md); decks it cannot honour were refused by the deck reader
         ! output safety as for the explicit engine: lock, temporary file, move into place
         call opath%acquire(stat, errmsg)
         if (stat /= 0) call fail(1, errmsg)
         ! SIGINT/SIGTERM: the static engine stops before its next increment and the file ends
         ! with status 'interrupted', as an explicit run's; during the set-up nothing is written
         stat = sys_signals_install()
         if (stat /= 0) call fail(2, 'cannot install the SIGINT/SIGTERM handler: '//sys_strerror(stat))
         call static_run(deck, model, opath%partial, .false., clock0, stat, errmsg, sidecar=opath%xmf_partial, &
                         target=opath%target, written=static_written, opened=static_opened, &
                         replacing=opath%replacing, ended=static_ended)
         if (static_written) then
            dest = opath%destination(static_ended)
            keep_partial = .true.   ! complete: a move that fails (named in its message) keeps it
            call opath%publish(i, static_msg, static_ended)
            if (i /= 0) call fail(2, static_msg)
            keep_partial = dest /= opath%target   ! kept at its temporary name: not removed below
         else if (stat == 2 .and. static_opened) then
            call fail_write(errmsg//'; what was written so far is in '//opath%partial)
         else if (stat == 2) then
            call fail_now(2, errmsg, .false.)   ! the file could not be created: no file kept
         end if
         i = sys_signal_pending()
         if (i /= 0) then
            call opath%abandon(keep_partial)
            if (static_written) then
               static_msg = '; '//dest//" holds the increments done (status 'interrupted')"//kept_note(dest)
            else
               static_msg = ' during the static engine''s set-up; nothing was written'
            end if
            write (error_unit, '(a)') program_name//': interrupted by '//trim(merge('SIGINT ', 'SIGTERM', i == 2))// &
               static_msg
            stop 128 + i, quiet=.true.
         end if
         if (stat /= 0) call fail(stat, errmsg)
         call opath%abandon(keep_partial)
         return
      end if
      dt_initial = model%dt
      fallback_step = -1
      call print_time_step(model, deck%solver%power_iterations)
      if (model%added_mass > 0) then
         write (output_unit, '(a)') 'mass scaling: '//sci(model%added_mass)//' t added at '//str(model%scaled_nodes)// &
            ' node(s) ('//sci(model%added_mass/model%body_mass)//' of the body mass) for a stable step of '// &
            sci(deck%solver%mass_scaling)//' s'
      end if

      errmsg = ramp_warning(deck, model%dt)
      if (len(errmsg) > 0) write (error_unit, '(a)') program_name//': warning: '//errmsg

      call solver%init(model%stiff, model%load, model%dt, model%damping, deck%solver%alpha, &
                       deck%solver%damping_interval)
      ! the guard watches only a step taken from the power estimate (contact2d_timestep)
      solver%guard = model%dt_guarded
      solver%guard_after = model%load%end_time()
      if (any(deck%initial%velocity /= 0)) call initial_velocity_apply(solver, model%load%free, deck%initial%velocity)
      ! the run's state: the engine's fields by pointer, a copy of the model's contact operator
      call state%init(model%contact, model%dt)
      call state_from_explicit(state, solver)
      ! the lock, then the temporary file; SIGINT/SIGTERM from now on end the run cleanly
      call opath%acquire(stat, errmsg)
      if (stat /= 0) call fail(1, errmsg)
      stat = sys_signals_install()
      if (stat /= 0) call fail(2, 'cannot install the SIGINT/SIGTERM handler: '//sys_strerror(stat))
      call out%open(opath%partial, .false., deck, model, state, stat, errmsg, sidecar=opath%xmf_partial, &
                    target=opath%target)
      if (stat /= 0) call fail_now(2, errmsg, .false.)   ! nothing readable yet: no file kept
      keep_partial = .true.
      call out%file%attr(out%file%id, 'method', 'explicit')
      call out%file%attr(out%file%id, 'omega_max_element', sqrt(model%stiff%omega2_element))
      call out%file%attr(out%file%id, 'dt_limit', trim(deck%solver%dt_limit))
      call out%file%attr(out%file%id, 'added_mass', model%added_mass)
      call out%file%attr(out%file%id, 'body_mass', model%body_mass)
      if (model%omega2_power > 0) then
         call out%file%attr(out%file%id, 'omega_max_power', sqrt(model%omega2_power))
         call out%file%attr(out%file%id, 'dt_stable_estimate', 2/sqrt(model%omega2_power))
      end if
      ! the kind of run and the energy put in at t = 0 (docs/output.md)
      call out%file%attr(out%file%id, 'dynamic', merge(1, 0, deck%dynamic))
      call out%file%attr(out%file%id, 'convergence_test', merge(1, 0, deck%convergence_test))
      call out%file%attr(out%file%id, 'initial_kinetic_energy', solver%initial_kinetic)
      call out%sample(state, 0.0_wp)
      call check_output(out)

      call tuner%init(model%stiff%nnode >= omp_min_nodes)
      call system_clock(clock1)
      timings = 0
      timings(1) = real(clock1 - clock0, wp)/rate
      t_steps = 0
      t_output = 0
      clock_last_progress = clock1
      interactive = deck%output%progress .and. isatty(output_unit)
      t_load_end = model%load%end_time()
      converged = .false.
      done = .false.
      state%status = 'not converged'
      if (.not. deck%convergence_test) state%status = trim(merge('dynamic            ', 'no convergence test', deck%dynamic))
      residual = huge(1.0_wp)
      scale_peak = 0
      strain_peak = 0
      isnap = 1
      snap_step = next_snapshot(deck, state%dt, isnap, 0_i8, 0.0_wp)
      associate (hist => int(deck%output%history_interval, i8), check => int(deck%solver%check_interval, i8))
         do while (.not. done)
            ! the chunk ends at the next history sample, convergence check, snapshot, max_steps
            ! or the step that reaches t_end, whichever comes first
            nstep = int(min(hist - mod(solver%step, hist), check - mod(solver%step, check), &
                            int(deck%solver%max_steps, i8) - solver%step, snap_step - solver%step, &
                            end_step(solver, deck%solver%t_end) - solver%step))
            call system_clock(tick)
            call solver%advance(model%stiff, model%load, state%contact, nstep)
            call system_clock(clock1)
            t_steps = t_steps + (clock1 - tick)
            call tuner%update(real(clock1 - tick, wp)/rate, nstep)
            if (solver%growing) then
               ! a growing mode: back to the element bound from the next step on
               state%dt = timestep_fallback(deck, model%dt_critical)
               call solver%set_dt(state%dt)
               solver%guard = .false.
               fallback_step = solver%step
               write (error_unit, '(a)') program_name//': warning: a growing mode at step '//str(solver%step)// &
                  ' with dt = '//sci(dt_initial)//' s; the element-bound step '//sci(state%dt)//' s from here on'
               snap_step = next_snapshot(deck, state%dt, isnap, solver%step, solver%time)
            end if
            sampled = .false.
            if (solver%step == snap_step) then
               call state_from_explicit(state, solver)
               call out%snapshot(model, state)
               call check_output(out)
               ! snapshot times that fall in one step share its snapshot (docs/deck.md)
               isnap = isnap + 1
               do while (isnap <= deck%output%nsnapshot)
                  if (deck%output%snapshot_times(isnap) > solver%time + 1.0e-9_wp*state%dt) exit
                  isnap = isnap + 1
               end do
               snap_step = next_snapshot(deck, state%dt, isnap, solver%step, solver%time)
            end if
            if (sys_signal_pending() /= 0) then
               state%status = 'interrupted'
               done = .true.
            else if (solver%blown_up) then
               state%status = 'blow-up'
               done = .true.
            else if (state%contact%stat /= 0) then
               state%status = 'contact solver failure'
               done = .true.
            else
               if (deck%convergence_test .and. mod(solver%step, check) == 0 .and. solver%time >= t_load_end) then
                  ! absolute floors: the largest force scale and strain energy reached so far
                  residual = solver%residual(model%load, scale_peak, scale_now)
                  scale_peak = max(scale_peak, scale_now)
                  strain_peak = max(strain_peak, solver%strain)
                  kin_ratio = merge(solver%kinetic/strain_peak, solver%kinetic, strain_peak > 0)
                  if (residual < deck%solver%tol_residual .and. kin_ratio < deck%solver%tol_kinetic) then
                     converged = .true.
                     state%status = 'converged'
                     done = .true.
                  end if
               end if
               ! (end_step cuts the chunks at the step this first holds)
               if (solver%time >= deck%solver%t_end*(1 - 1.0e-12_wp) .or. &
                   solver%step >= deck%solver%max_steps) done = .true.
            end if
            if (mod(solver%step, hist) == 0 .or. done) then
               call system_clock(tick)
               residual = solver%residual(model%load, scale_peak, scale_now)
               scale_peak = max(scale_peak, scale_now)
               strain_peak = max(strain_peak, solver%strain)
               call state_from_explicit(state, solver)
               call out%sample(state, residual)
               call check_output(out)
               sampled = .true.
               call system_clock(clock1)
               t_output = t_output + (clock1 - tick)
            end if
            if (interactive .and. real(clock1 - clock_last_progress, wp) > progress_seconds*rate) then
               call progress_line(solver, deck, residual, real(clock1 - clock0, wp)/rate - timings(1))
               clock_last_progress = clock1
            end if
         end do
      end associate
      if (interactive) write (output_unit, '(a)', advance='no') achar(13)//repeat(' ', 100)//achar(13)

      ! the step-loop time includes the contact time, reported on its own as well
      timings(2) = real(t_steps, wp)/rate
      timings(3) = real(state%contact%clock_ticks, wp)/rate
      timings(4) = real(t_output, wp)/rate
      ! solver:compare_static: energy distance of the end state to the static solution
      if (deck%solver%compare_static) then
         call static_distance(deck, model, solver%u, static_dist, static_converged, stat, errmsg)
         if (stat /= 0) then
            ! interrupted: said once, at the end
            if (sys_signal_pending() == 0) write (error_unit, '(a)') program_name//': warning: compare_static: '//errmsg
         else
            call out%file%attr(out%file%id, 'static_distance_energy', static_dist)
            call out%file%attr(out%file%id, 'static_converged', merge(1, 0, static_converged))
         end if
      end if
      call system_clock(clock1)
      wall = real(clock1 - clock0, wp)/rate
      ! output:snapshot_times after the end of the run: said in the file and the summary
      snap_missed = deck%output%snapshot_times(isnap:deck%output%nsnapshot)
      if (size(snap_missed) > 0) call out%file%attr(out%file%id, 'snapshot_times_not_reached', snap_missed)
      call out%file%attr(out%file%id, 'dt_initial', dt_initial)
      call out%file%attr(out%file%id, 'dt_fallback_step', int(fallback_step))
      ! the small-strain, small-displacement range of a run that reached its end (docs/output.md):
      ! measured on the end state, stored now, said after the summary
      if (.not. any(state%status == [character(len=24) :: 'interrupted', 'blow-up', 'contact solver failure'])) then
         call validity%measure(model%mesh, solver%u)
         call validity%write(out%file)
      end if
      state%converged = converged
      call state_from_explicit(state, solver)
      call out%finish(model, state, wall, timings, stat, errmsg)
      if (stat /= 0) call fail_write(errmsg//'; what was written so far is in '//opath%partial)
      ! complete: move the files into place (every end: converged or not, blow-up, interrupted;
      ! but a run that did not reach its end does not replace an existing result, docs/output.md)
      ended = .not. any(state%status == [character(len=24) :: 'interrupted', 'blow-up', 'contact solver failure'])
      dest = opath%destination(ended)
      call opath%publish(stat, errmsg, ended)
      if (stat /= 0) call fail(2, errmsg)
      keep_partial = dest /= opath%target   ! kept at its temporary name: fail() below must not remove it
      call summary(model, deck, state, solver, dest, residual, wall, timings, dt_initial, fallback_step, snap_missed)
      call validity%report()
      if (tuner%active) write (output_unit, '(a)') ' threads             auto: '//str(tuner%nmax)//' on '// &
         fixed(100*real(tuner%steps(2), wp)/max(1.0_wp, real(sum(tuner%steps), wp)), 1)//' % of the steps, 1 on the rest ('// &
         'started on '//str(tuner%started)//', '//str(tuner%switches)//' switches; set OMP_NUM_THREADS to fix the count)'
      if (allocated(tuner%forced)) write (output_unit, '(a)') ' threads             forced: '//str(tuner%nmax)// &
         ' on '//str(tuner%steps(2))//' steps, 1 on '//str(tuner%steps(1))//' ('//str(tuner%switches)// &
         ' switches, CONTACT2D_THREAD_SWITCHES)'
      if (deck%solver%compare_static .and. static_dist < huge(1.0_wp)) then
         write (output_unit, '(a)') ' static distance     '//sci(static_dist)//' (energy norm ||u - u_static||_K / '// &
            '||u_static||_K'//trim(merge('); static NOT converged', ')                      ', .not. static_converged))
      end if
      if (state%status == 'interrupted') then
         stat = sys_signal_pending()
         write (error_unit, '(a)') program_name//': interrupted by '//trim(merge('SIGINT ', 'SIGTERM', stat == 2))// &
            ' at step '//str(solver%step)//' (t = '//sci(solver%time)//' s); '//dest// &
            " holds the state at that step (status 'interrupted')"//kept_note(dest)
         stop 128 + stat, quiet=.true.
      else if (sys_signal_pending() /= 0) then
         ! a signal after the steps (during solver:compare_static): the run's file is complete
         stat = sys_signal_pending()
         write (error_unit, '(a)') program_name//': interrupted by '//trim(merge('SIGINT ', 'SIGTERM', stat == 2))// &
            ' after the steps; '//cli%output//" holds the finished run (status '"//state%status//"')"// &
            trim(merge(', without the static comparison', '                               ', &
                       deck%solver%compare_static .and. static_dist == huge(1.0_wp)))
         stop 128 + stat, quiet=.true.
      end if
      if (solver%blown_up) then
         call fail(2, 'the run blew up at step '//str(solver%step)//' (t = '//sci(solver%time)// &
                   ' s): kinetic energy '//sci(solver%kinetic)//' mJ exceeds 1000 x the work put in ('// &
                   sci(solver%work_in)//' mJ) with dt = '//fixed(state%dt/model%dt_critical, 3)// &
                   ' dt_critical; '//dest//' holds the history up to the failure'//kept_note(dest))
      end if
      if (state%contact%stat /= 0) then
         call fail(2, state%contact%errmsg//' at step '//str(solver%step)//'; '//dest// &
                   ' holds the history up to the failure'//kept_note(dest))
      end if
   end subroutine driver_main

   !> Point the state at the explicit engine's fields and copy its scalars (between chunks of
   !> steps: the engine swaps u and u~ by pointer, so the views are set again each time).
   subroutine state_from_explicit(state, solver)
      type(state_t), intent(inout) :: state
      type(explicit_t), intent(in), target :: solver
      state%u => solver%u
      state%v => solver%v
      state%fint => solver%fint
      state%fext => solver%fext
      state%step = solver%step
      state%time = solver%time
      state%dt = solver%dt
      state%alpha = solver%alpha
      state%kinetic = solver%kinetic
      state%strain = solver%strain
      state%kinetic_step = solver%kinetic_step
      state%strain_step = solver%strain_step
      state%external_work = solver%external_work
      state%damping_dissipation = solver%damping_dissipation
      state%initial_kinetic = solver%initial_kinetic
   end subroutine state_from_explicit

   !> The step at which the run reaches t_end: the first step after the current one whose time
   !> t_k = time0 + (k - step0) dt (as the solver forms it) is >= t_end (1 - 1e-12), the test
   !> that ends the run. The chunk of steps between two checks is cut there, so every run stops
   !> at that step whatever its history and check intervals (docs/deck.md, solver:t_end).
   integer(i8) function end_step(solver, t_end) result(step)
      type(explicit_t), intent(in) :: solver
      real(wp), intent(in) :: t_end
      real(wp) :: limit, r
      limit = t_end*(1 - 1.0e-12_wp)
      r = (limit - solver%time0)/solver%dt
      if (.not. r < 2.0_wp**60) then
         step = huge(1_i8)
         return
      end if
      step = max(solver%step + 1, solver%step0 + ceiling(r, i8))
      ! the rounding of r: settle on the solver's own formula for t_k
      do while (step > solver%step + 1 .and. at(step - 1) >= limit)
         step = step - 1
      end do
      do while (at(step) < limit)
         step = step + 1
      end do
   contains
      real(wp) function at(k)
         integer(i8), intent(in) :: k
         at = solver%time0 + real(k - solver%step0, wp)*solver%dt
      end function at
   end function end_step

   !> Step of snapshot k (the first step at or after its time), or huge if there is none; the
   !> run is at step0, time0 and goes on with dt.
   integer(i8) function next_snapshot(deck, dt, k, step0, time0) result(step)
      type(deck_t), intent(in) :: deck
      real(wp), intent(in) :: dt, time0
      integer, intent(in) :: k
      integer(i8), intent(in) :: step0
      real(wp) :: r
      step = huge(1_i8)
      if (k > deck%output%nsnapshot) return
      ! steps to the snapshot; beyond 2**60 steps it is never reached (and ceiling(r, i8) would
      ! overflow: snapshot_times = 1e30 s trapped in the Debug build)
      r = (deck%output%snapshot_times(k) - time0)/dt - 1.0e-9_wp
      if (r < 2.0_wp**60) step = max(step0 + 1, step0 + ceiling(r, i8))
   end function next_snapshot

   !> '' when the run's file went to the output, else (a run that did not reach its end would
   !> have replaced an existing result: outpath destination) a note that the result was kept.
   function kept_note(dest) result(note)
      character(len=*), intent(in) :: dest
      character(len=:), allocatable :: note
      note = ''
      if (dest /= opath%target) note = '; the existing '//opath%target//' is kept (--force replaces a result '// &
                                       'only with a run that reaches its end)'
   end function kept_note

   !> One line on stderr, release the output lock (removing temporary files unless the partial
   !> result is worth keeping), exit with the code.
   subroutine fail(code, msg)
      integer, intent(in) :: code
      character(len=*), intent(in) :: msg
      ! one line whatever the message quotes (a --set value with a newline, an escape sequence)
      write (error_unit, '(a)') program_name//': error: '//printable(msg)
      call opath%abandon(keep_partial)
      stop code, quiet=.true.
   end subroutine fail

   !> fail() after a failed write: the file is left as it is on disk (no HDF5 exit handler
   !> touches it again), the lock released, exit 2.
   subroutine fail_write(msg)
      character(len=*), intent(in) :: msg
      call fail_now(2, msg, .true.)
   end subroutine fail_write

   !> fail() without exit handlers: after an HDF5 write failed, the library's own exit handler
   !> would flush the broken file again (seen to crash, SIGSEGV, when the output could not even
   !> be created on a full disk). keep: keep the temporary file (it holds what was flushed).
   subroutine fail_now(code, msg, keep)
      integer, intent(in) :: code
      character(len=*), intent(in) :: msg
      logical, intent(in) :: keep
      write (error_unit, '(a)') program_name//': error: '//printable(msg)
      call opath%abandon(keep)
      flush (output_unit)
      flush (error_unit)
      call sys_exit_now(code)
   end subroutine fail_now

   !> Stop at once (exit 2) when a write to the output failed; what was flushed before stays
   !> readable in the temporary file, which is named in the message.
   subroutine check_output(out)
      type(output_t), intent(in) :: out
      if (.not. out%file%ok()) call fail_write(out%file%errmsg//'; the run stopped; what was written before is in '// &
                                               opath%partial)
   end subroutine check_output

   !> Refuse a mesh whose arrays do not fit in the memory this process may use: one line naming
   !> the mesh and the bytes asked for, before any output. The probe is an allocation of the
   !> estimated size (not touched), so a limit on the address space (ulimit -v) is honoured;
   !> memory overcommitted by the system cannot be detected this way.
   subroutine memory_check(deck, stat, errmsg)
      type(deck_t), intent(in) :: deck
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp) :: nel, nnode, bytes
      real(wp), allocatable :: probe(:)
      integer :: ios
      stat = 0
      errmsg = ''
      ! a Gmsh mesh's size is known only once Gmsh has read it (nx, ny are unset): no probe
      if (len_trim(deck%mesh%file) > 0) return
      nel = real(deck%mesh%nx, wp)*real(deck%mesh%ny, wp)*4.0_wp**deck%mesh%level
      nnode = (real(deck%mesh%nx, wp)*2.0_wp**deck%mesh%level + 1)*(real(deck%mesh%ny, wp)*2.0_wp**deck%mesh%level + 1)
      ! nodal arrays of the model, the integrator and the output (about 40 reals per node),
      ! connectivity, element shape index and stress (about 12 words per element)
      bytes = 8*(40*nnode + 12*nel)
      allocate (probe(int(bytes/8, i8)), stat=ios)
      if (ios /= 0) then
         stat = 1
         errmsg = 'mesh '//str(nint(nel, i8))//' elements, '//str(nint(nnode, i8))//' nodes: cannot allocate the '// &
                  str(nint(bytes/2.0_wp**20, i8))//' MiB it needs (allocation failed)'
         return
      end if
      deallocate (probe)
   end subroutine memory_check



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

   subroutine print_time_step(model, iterations)
      type(model_t), intent(in) :: model
      integer, intent(in) :: iterations
      character(len=:), allocatable :: bound
      bound = 'element bound 2/omega_max'
      if (model%scaled_nodes > 0) bound = 'bound with mass scaling'
      if (model%contact%penalty) bound = bound//trim(merge(' and ', ' with', model%scaled_nodes > 0))//' the penalty springs'
      write (output_unit, '(a)') 'dt = '//sci(model%dt)//' s = '//fixed(model%dt/model%dt_critical, 3)// &
         ' dt_critical ('//bound//' = '//sci(model%dt_critical)//' s)'
      associate (omega2_power => model%omega2_power)
      if (omega2_power > 0) then
         write (output_unit, '(a)') 'power iteration ('//str(iterations)//' its): omega_max >= '// &
            sci(sqrt(omega2_power))//' 1/s, true stable limit <= '//sci(2/sqrt(omega2_power))//' s = '// &
            fixed(2/sqrt(omega2_power)/model%dt_critical, 3)//' dt_critical (the element bound is conservative)'
      end if
      end associate
   end subroutine print_time_step

   subroutine progress_line(solver, deck, residual, elapsed)
      type(explicit_t), intent(in) :: solver
      type(deck_t), intent(in) :: deck
      real(wp), intent(in) :: residual, elapsed
      real(wp) :: frac, eta
      character(len=:), allocatable :: line
      frac = max(solver%time/deck%solver%t_end, real(solver%step, wp)/deck%solver%max_steps)
      eta = elapsed*(1 - frac)/max(frac, 1.0e-12_wp)
      line = 'step '//str(solver%step)//'  t = '//sci(solver%time)//' s  residual '// &
             sci(residual)//'  ETA <= '//fixed(eta, 1)//' s   '
      write (output_unit, '(a)', advance='no') achar(13)//line
      flush (output_unit)
   end subroutine progress_line

   !> Contact lines of the summary: status counts, extent, pressure sign, penetration.
   subroutine contact_summary(state)
      type(state_t), intent(in) :: state
      integer :: status(state%contact%nc), info, nneg
      real(wp) :: pressure(state%contact%nc), shear(state%contact%nc)
      associate (c => state%contact)
         call c%status(status)
         call c%fields(pressure, shear, info)
         call summary_contact_status(c, status)
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
      end associate
   end subroutine contact_summary

   subroutine summary(model, deck, state, solver, path, residual, wall, timings, dt_initial, fallback_step, snap_missed)
      type(model_t), intent(in) :: model
      type(deck_t), intent(in) :: deck
      type(state_t), intent(in) :: state
      type(explicit_t), intent(in) :: solver
      character(len=*), intent(in) :: path
      real(wp), intent(in) :: residual, wall, timings(4), dt_initial
      integer(i8), intent(in) :: fallback_step
      real(wp), intent(in) :: snap_missed(:)   !< output:snapshot_times after the end [s]
      character(len=:), allocatable :: conv, times
      real(wp) :: rate
      integer :: k
      associate (c => state%contact, converged => state%converged, status => state%status)
         if (converged) then
            conv = 'yes (relative residual '//sci(residual)//' < '//sci(deck%solver%tol_residual)//')'
         else if (.not. deck%convergence_test) then
            conv = 'not tested (solver:convergence_test = '''//trim(deck%solver%convergence_test)// &
                   '''); status: '//status
         else
            conv = 'NO: '//status
            ! why the steps ended (a blow-up, a contact failure or a signal say so in the status)
            if (status == 'not converged') then
               if (solver%step >= deck%solver%max_steps) then
                  conv = conv//', solver:max_steps = '//str(deck%solver%max_steps)//' reached'
               else
                  conv = conv//', solver:t_end = '//sci(deck%solver%t_end)//' s reached'
               end if
            end if
            conv = conv//' (relative residual '//sci(residual)//', tolerance '//sci(deck%solver%tol_residual)//')'
         end if
         rate = real(solver%step, wp)*model%mesh%nel/max(timings(2), 1.0e-9_wp)
         write (output_unit, '(a)') repeat('-', 72)
         write (output_unit, '(a)') ' steps               '//str(solver%step)//'   (t = '//sci(solver%time)//' s)'
         write (output_unit, '(a)') ' dt / dt_critical    '//fixed(state%dt/model%dt_critical, 4)//'   (dt_limit = '// &
            trim(deck%solver%dt_limit)//')'
         if (fallback_step >= 0) write (output_unit, '(a)') ' growing mode        at step '//str(fallback_step)// &
            ': dt '//sci(dt_initial)//' s -> '//sci(state%dt)//' s (element bound)'
         if (model%added_mass > 0) write (output_unit, '(a)') ' added mass          '//sci(model%added_mass)// &
            ' t at '//str(model%scaled_nodes)//' node(s) = '//sci(model%added_mass/model%body_mass)//' x body mass'
         if (deck%dynamic) write (output_unit, '(a)') ' run                 dynamic: initial velocity ('// &
            sci(deck%initial%velocity(1))//', '//sci(deck%initial%velocity(2))//') mm/s, no damping, '// &
            trim(merge('stops when converged or at t_end =', 'ends at t_end =                   ', deck%convergence_test))//' '// &
            sci(deck%solver%t_end)//' s; initial kinetic energy '//sci(solver%initial_kinetic)//' mJ'
         write (output_unit, '(a)') ' converged           '//conv
         if (size(snap_missed) > 0) then
            times = str(snap_missed(1))
            do k = 2, size(snap_missed)
               times = times//', '//str(snap_missed(k))
            end do
            write (output_unit, '(a)') ' snapshots           not reached: output:snapshot_times '//times// &
               ' s (the run ended at t = '//sci(solver%time)//' s); '// &
               str(deck%output%nsnapshot - size(snap_missed))//' of '//str(deck%output%nsnapshot)//' written'
         end if
         write (output_unit, '(a)') ' energy balance      '//sci(state%balance_error())// &
            ' (relative error; W_ext = '//sci(solver%external_work)//' mJ)'
         if (c%active) call contact_summary(state)
         write (output_unit, '(a)') ' wall time           '//fixed(wall, 3)//' s (set-up '//fixed(timings(1), 3)// &
            ', steps '//fixed(timings(2), 3)//', contact '//fixed(timings(3), 3)//', output '//fixed(timings(4), 3)//')'
         write (output_unit, '(a)') ' element-steps / s   '//sci(rate)
         write (output_unit, '(a)') ' output              '//printable(path)
         write (output_unit, '(a)') repeat('-', 72)
      end associate
   end subroutine summary
end module contact2d_driver
