!> One explicit run (SPEC sections 4 to 6): the engine and its state, the output file, the
!> chunks of steps between history samples, snapshots and convergence checks (SPEC section 5),
!> the end of the run and its summary. The model is read only.
module contact2d_run_explicit
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   use contact2d_kinds, only: wp, i8
   use contact2d_version, only: program_name
   use contact2d_strings, only: str, fixed, sci
   use contact2d_deck, only: deck_t
   use contact2d_model, only: model_t
   use contact2d_state, only: state_t
   use contact2d_explicit, only: explicit_t
   use contact2d_initial, only: initial_velocity_apply
   use contact2d_timestep, only: timestep_fallback
   use contact2d_output, only: output_t
   use contact2d_comm, only: comm_max, comm_rank, comm_size
   use contact2d_sys, only: sys_signals_install, sys_signal_pending, sys_strerror
   use contact2d_threads, only: thread_tuner_t
   use contact2d_stiffness, only: omp_min_nodes
   use contact2d_run_static, only: static_distance
   use contact2d_validity, only: validity_t
   use contact2d_report, only: report_time_step, ramp_warning, progress_line, report_summary, report_threads
   use contact2d_run_exit, only: opath, keep_partial, fail, fail_now, fail_write, check_output, kept_note, &
                                 stop_interrupted, run_ended
   implicit none
   private
   public :: run_explicit

   !> Seconds between progress-line updates.
   real(wp), parameter :: progress_seconds = 0.5_wp

   !> Bookkeeping of the march between chunks of steps.
   type :: march_t
      integer :: isnap = 1                   !< next output:snapshot_times entry
      integer(i8) :: snap_step = 0           !< the step of that snapshot (huge: none)
      integer(i8) :: fallback_step = -1      !< step of the growing-mode fallback (-1: none)
      real(wp) :: dt_initial = 0             !< the step the run started with [s]
      real(wp) :: residual = huge(1.0_wp)    !< relative residual of the last check or sample
      real(wp) :: scale_peak = 0             !< largest force scale so far [N]
      real(wp) :: strain_peak = 0            !< largest strain energy so far [mJ]
      real(wp) :: timings(4) = 0             !< set-up, steps, contact, output [s]
      real(wp), allocatable :: snap_missed(:)   !< snapshot times after the end [s]
   end type march_t

contains

   !> The explicit engine from the built model to the published file and the summary.
   subroutine run_explicit(cli_output, deck, model, clock0, rate, tuner)
      character(len=*), intent(in) :: cli_output   !< the output as given (-o)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      integer(i8), intent(in) :: clock0, rate      !< system_clock at program start, its rate
      type(thread_tuner_t), intent(inout) :: tuner
      type(explicit_t), target :: solver
      type(state_t), target :: state
      type(output_t) :: out
      type(march_t) :: march
      type(validity_t) :: validity
      character(len=:), allocatable :: dest
      real(wp) :: static_dist, wall
      logical :: static_converged

      call report_time_step(model, deck%solver%power_iterations, deck%solver%mass_scaling)
      call warn(ramp_warning(deck, model%dt))
      call engine_start(deck, model, solver, state)
      call output_start(deck, model, solver, state, out)
      call tuner%init(model%stiff%nnode >= omp_min_nodes)
      call integrate(deck, model, solver, state, out, tuner, clock0, rate, march)
      call compare_static(deck, model, state, out, static_dist, static_converged)
      call output_end(deck, model, state, out, march, validity, clock0, rate, wall, dest)
      call report_summary(model, deck, state, dest, march%residual, wall, march%timings, march%dt_initial, &
                          march%fallback_step, march%snap_missed)
      call validity%report()
      call report_threads(tuner)
      if (deck%solver%compare_static .and. static_dist < huge(1.0_wp)) then
         write (output_unit, '(a)') ' static distance     '//sci(static_dist)//' (energy norm ||u - u_static||_K / '// &
            '||u_static||_K'//trim(merge('); static NOT converged', ')                      ', .not. static_converged))
      end if
      call run_end(cli_output, deck, model, solver, state, dest, static_dist)
   end subroutine run_explicit

   !> A warning line on stderr unless msg is ''.
   subroutine warn(msg)
      character(len=*), intent(in) :: msg
      if (len(msg) > 0) write (error_unit, '(a)') program_name//': warning: '//msg
   end subroutine warn

   !> The engine at t = 0 (the initial velocity applied) and the run's state: the engine's fields
   !> by pointer, a copy of the model's contact operator.
   subroutine engine_start(deck, model, solver, state)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(explicit_t), intent(inout), target :: solver
      type(state_t), intent(inout), target :: state
      integer :: stat
      character(len=:), allocatable :: errmsg
      call solver%init(model%stiff, model%load, model%dt, model%damping, deck%solver%alpha, &
                       deck%solver%damping_interval)
      ! mpirun -np N: the grid rows shared among the processes (docs/mpi.md)
      if (comm_size() > 1) then
         call solver%distribute(comm_size(), comm_rank(), stat, errmsg)
         if (stat /= 0) call fail(1, errmsg)
      end if
      ! the guard watches only a step taken from the power estimate (contact2d_timestep)
      solver%guard = model%dt_guarded
      solver%guard_after = loading_end(model)
      if (any(model%velocity0 /= 0)) call initial_velocity_apply(solver, model%load%free, model%velocity0)
      call state%init(model%contacts, model%dt)
      call state_from_explicit(state, solver)
   end subroutine engine_start

   !> The lock, the SIGINT/SIGTERM handler (from now on a signal ends the run cleanly), the
   !> temporary file with the explicit run's root attributes and the sample at t = 0.
   subroutine output_start(deck, model, solver, state, out)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(explicit_t), intent(in) :: solver
      type(state_t), intent(inout) :: state
      type(output_t), intent(inout) :: out
      integer :: stat
      character(len=:), allocatable :: errmsg
      call opath%acquire(stat, errmsg)
      ! (several processes: rank 0 alone takes the lock; every rank stops when it failed)
      if (comm_max(stat) /= 0) call fail(1, errmsg)
      stat = sys_signals_install()
      if (stat /= 0) call fail(2, 'cannot install the SIGINT/SIGTERM handler: '//sys_strerror(stat))
      out%writer = opath%writer
      call out%open(opath%partial, .false., deck, model, state, stat, errmsg, sidecar=opath%xmf_partial, &
                    target=opath%target)
      if (comm_max(stat) /= 0) call fail_now(2, errmsg, .false.)   ! nothing readable yet: no file kept
      keep_partial = .true.
      call out%attributes_explicit(deck, model, solver%initial_kinetic)
      call out%sample(state, 0.0_wp)
      call check_output(out)
   end subroutine output_start

   !> The march: chunks of steps, each ending at the next history sample, convergence check,
   !> snapshot, max_steps or the step that reaches t_end, whichever comes first; after each the
   !> growing-mode fallback, the snapshot, the end tests (signal, blow-up, contact failure,
   !> convergence, t_end, max_steps), the sample and the progress line.
   subroutine integrate(deck, model, solver, state, out, tuner, clock0, rate, march)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(explicit_t), intent(inout), target :: solver
      type(state_t), intent(inout) :: state
      type(output_t), intent(inout) :: out
      type(thread_tuner_t), intent(inout) :: tuner
      integer(i8), intent(in) :: clock0, rate
      type(march_t), intent(inout) :: march
      integer(i8) :: clock1, clock_last_progress, t_steps, t_output, tick
      real(wp) :: t_load_end, scale_now, kin_ratio
      logical :: done, interactive
      integer :: nstep

      march%dt_initial = model%dt
      call system_clock(clock1)
      march%timings = 0
      march%timings(1) = real(clock1 - clock0, wp)/rate
      t_steps = 0
      t_output = 0
      clock_last_progress = clock1
      ! (not under mpirun: its ranks' output is a pseudo-terminal even when mpirun's is a file)
      interactive = deck%output%progress .and. isatty(output_unit) .and. comm_size() == 1
      t_load_end = loading_end(model)
      done = .false.
      state%status = 'not converged'
      if (.not. deck%convergence_test) state%status = trim(merge('dynamic            ', 'no convergence test', deck%dynamic))
      march%snap_step = next_snapshot(deck, state%dt, march%isnap, 0_i8, 0.0_wp)
      associate (hist => int(deck%output%history_interval, i8), check => int(deck%solver%check_interval, i8))
         do while (.not. done)
            nstep = int(min(hist - mod(solver%step, hist), check - mod(solver%step, check), &
                            int(deck%solver%max_steps, i8) - solver%step, march%snap_step - solver%step, &
                            end_step(solver, deck%solver%t_end) - solver%step))
            call system_clock(tick)
            call solver%advance(model%stiff, model%load, state%contacts, nstep)
            call system_clock(clock1)
            t_steps = t_steps + (clock1 - tick)
            call tuner%update(real(clock1 - tick, wp)/rate, nstep)
            if (solver%growing) call fall_back(deck, model, solver, state, march)
            if (solver%step == march%snap_step) call snapshot(deck, model, solver, state, out, march)
            if (sys_signal_pending() /= 0) then
               state%status = 'interrupted'
               done = .true.
            else if (solver%blown_up) then
               state%status = 'blow-up'
               done = .true.
            else if (any(state%contacts%stat /= 0)) then
               state%status = 'contact solver failure'
               done = .true.
            else
               if (deck%convergence_test .and. mod(solver%step, check) == 0 .and. solver%time >= t_load_end) then
                  ! absolute floors: the largest force scale and strain energy reached so far
                  march%residual = solver%residual(model%load, march%scale_peak, scale_now)
                  march%scale_peak = max(march%scale_peak, scale_now)
                  march%strain_peak = max(march%strain_peak, solver%strain)
                  kin_ratio = merge(solver%kinetic/march%strain_peak, solver%kinetic, march%strain_peak > 0)
                  if (march%residual < deck%solver%tol_residual .and. kin_ratio < deck%solver%tol_kinetic) then
                     state%converged = .true.
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
               march%residual = solver%residual(model%load, march%scale_peak, scale_now)
               march%scale_peak = max(march%scale_peak, scale_now)
               march%strain_peak = max(march%strain_peak, solver%strain)
               call state_from_explicit(state, solver)
               call out%sample(state, march%residual)
               call check_output(out)
               call system_clock(clock1)
               t_output = t_output + (clock1 - tick)
            end if
            if (interactive .and. real(clock1 - clock_last_progress, wp) > progress_seconds*rate) then
               call state_from_explicit(state, solver)
               call progress_line(state, deck, march%residual, real(clock1 - clock0, wp)/rate - march%timings(1))
               clock_last_progress = clock1
            end if
         end do
      end associate
      if (interactive) write (output_unit, '(a)', advance='no') achar(13)//repeat(' ', 100)//achar(13)
      ! the step-loop time includes the contact time, reported on its own as well
      march%timings(2) = real(t_steps, wp)/rate
      march%timings(3) = real(sum(state%contacts%clock_ticks), wp)/rate
      march%timings(4) = real(t_output, wp)/rate
      call state_from_explicit(state, solver)
   end subroutine integrate

   !> A growing mode (contact2d_explicit guard): back to the element-bound step from the next
   !> step on (contact2d_timestep), said once on stderr.
   subroutine fall_back(deck, model, solver, state, march)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(explicit_t), intent(inout) :: solver
      type(state_t), intent(inout) :: state
      type(march_t), intent(inout) :: march
      state%dt = timestep_fallback(deck, model%dt_critical)
      call solver%set_dt(state%dt)
      solver%guard = .false.
      march%fallback_step = solver%step
      write (error_unit, '(a)') program_name//': warning: a growing mode at step '//str(solver%step)// &
         ' with dt = '//sci(march%dt_initial)//' s; the element-bound step '//sci(state%dt)//' s from here on'
      march%snap_step = next_snapshot(deck, state%dt, march%isnap, solver%step, solver%time)
   end subroutine fall_back

   !> /fields/<step> at this step; snapshot times that fall in one step share its snapshot
   !> (docs/deck.md); the step of the next one.
   subroutine snapshot(deck, model, solver, state, out, march)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(explicit_t), intent(in), target :: solver
      type(state_t), intent(inout) :: state
      type(output_t), intent(inout) :: out
      type(march_t), intent(inout) :: march
      call state_from_explicit(state, solver)
      call out%snapshot(model, state)
      call check_output(out)
      march%isnap = march%isnap + 1
      do while (march%isnap <= deck%output%nsnapshot)
         if (deck%output%snapshot_times(march%isnap) > solver%time + 1.0e-9_wp*state%dt) exit
         march%isnap = march%isnap + 1
      end do
      march%snap_step = next_snapshot(deck, state%dt, march%isnap, solver%step, solver%time)
   end subroutine snapshot

   !> solver:compare_static: the energy distance of the end state to the static solution, stored
   !> as root attributes; dist = huge when there is none.
   subroutine compare_static(deck, model, state, out, dist, converged)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: state
      type(output_t), intent(inout) :: out
      real(wp), intent(out) :: dist
      logical, intent(out) :: converged
      integer :: stat
      character(len=:), allocatable :: errmsg
      dist = huge(1.0_wp)
      converged = .false.
      if (.not. deck%solver%compare_static) return
      call static_distance(deck, model, state%u, dist, converged, stat, errmsg)
      if (stat /= 0) then
         ! interrupted: said once, at the end
         if (sys_signal_pending() == 0) write (error_unit, '(a)') program_name//': warning: compare_static: '//errmsg
      else
         call out%attributes_compare_static(dist, converged)
      end if
   end subroutine compare_static

   !> The closing attributes, the validity range of a run that reached its end (docs/output.md),
   !> /final; then the files moved into place (every end: converged or not, blow-up,
   !> interrupted; but a run that did not reach its end does not replace an existing result).
   !> dest: where the file went.
   subroutine output_end(deck, model, state, out, march, validity, clock0, rate, wall, dest)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: state
      type(output_t), intent(inout) :: out
      type(march_t), intent(inout) :: march
      type(validity_t), intent(inout) :: validity
      integer(i8), intent(in) :: clock0, rate
      real(wp), intent(out) :: wall
      character(len=:), allocatable, intent(out) :: dest
      integer(i8) :: clock1
      integer :: stat
      character(len=:), allocatable :: errmsg
      logical :: ended
      call system_clock(clock1)
      wall = real(clock1 - clock0, wp)/rate
      ! output:snapshot_times after the end of the run: said in the file and the summary
      march%snap_missed = deck%output%snapshot_times(march%isnap:deck%output%nsnapshot)
      call out%attributes_explicit_end(march%snap_missed, march%dt_initial, int(march%fallback_step))
      ended = run_ended(state%status)
      ! the small-strain, small-displacement range: measured on the end state, said after the summary
      if (ended) then
         call validity%measure(model%mesh, state%u)
         if (out%writer) call validity%write(out%file)
      end if
      call out%finish(model, state, wall, march%timings, stat, errmsg)
      if (stat /= 0) call fail_write(errmsg//'; what was written so far is in '//opath%partial)
      dest = opath%destination(ended)
      call opath%publish(stat, errmsg, ended)
      if (stat /= 0) call fail(2, errmsg)
      keep_partial = dest /= opath%target   ! kept at its temporary name: fail() below must not remove it
   end subroutine output_end

   !> The exit of a run that did not end normally: a signal (128 + signal), a blow-up or a
   !> contact failure (exit 2, one line naming the step and the file).
   subroutine run_end(cli_output, deck, model, solver, state, dest, static_dist)
      character(len=*), intent(in) :: cli_output, dest
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(explicit_t), intent(in) :: solver
      type(state_t), intent(in) :: state
      real(wp), intent(in) :: static_dist
      integer :: signal, k
      character(len=:), allocatable :: which
      signal = sys_signal_pending()
      if (state%status == 'interrupted') then
         call stop_interrupted(signal, ' at step '//str(solver%step)//' (t = '//sci(solver%time)//' s); '//dest// &
                               " holds the state at that step (status 'interrupted')"//kept_note(dest))
      else if (signal /= 0) then
         ! a signal after the steps (during solver:compare_static): the run's file is complete
         call stop_interrupted(signal, ' after the steps; '//cli_output//" holds the finished run (status '"// &
                               state%status//"')"//trim(merge(', without the static comparison', &
                                                              '                               ', &
                                                              deck%solver%compare_static .and. &
                                                              static_dist == huge(1.0_wp))))
      end if
      if (solver%blown_up) then
         call fail(2, 'the run blew up at step '//str(solver%step)//' (t = '//sci(solver%time)// &
                   ' s): kinetic energy '//sci(solver%kinetic)//' mJ exceeds 1000 x the work put in ('// &
                   sci(solver%work_in)//' mJ) with dt = '//fixed(state%dt/model%dt_critical, 3)// &
                   ' dt_critical; '//dest//' holds the history up to the failure'//kept_note(dest))
      end if
      k = findloc(state%contacts%stat /= 0, .true., 1)
      if (k > 0) then
         ! several pairs: the message names the pair that failed
         which = ''
         if (size(state%contacts) > 1) which = "contact pair '"//model%pairs(k)%name//"': "
         call fail(2, which//state%contacts(k)%errmsg//' at step '//str(solver%step)//'; '//dest// &
                   ' holds the history up to the failure'//kept_note(dest))
      end if
   end subroutine run_end

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

   !> The end of the last stage of the loads and of a moving obstacle's motion (docs/geometry.md):
   !> the convergence test and the growing-mode guard start there [s].
   real(wp) function loading_end(model) result(t)
      type(model_t), intent(in) :: model
      integer :: k
      t = model%load%end_time()
      do k = 1, size(model%contacts)
         if (allocated(model%contacts(k)%obstacle)) then
            if (model%contacts(k)%obstacle%moving) t = max(t, model%contacts(k)%obstacle%velocity(1)%end_time())
         end if
      end do
   end function loading_end

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
end module contact2d_run_explicit
