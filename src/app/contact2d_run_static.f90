!> One static run (solver:method = 'static' or --static; docs/static.md): the output safety of an
!> explicit run (lock, temporary file, move into place) around the static engine, which factorises
!> once and then solves increment by increment; the same HDF5 file as an explicit run (SPEC
!> section 8 with dt = 0, steps = increments, method = 'static' and the KKT residuals as
!> attributes) and the summary. Also the energy-norm distance of an explicit end state to the
!> static solution (solver:compare_static). The model is read only.
module contact2d_run_static
   use, intrinsic :: iso_fortran_env, only: output_unit
   use contact2d_kinds, only: wp, i8
   use contact2d_strings, only: str, sci
   use contact2d_deck, only: deck_t
   use contact2d_model, only: model_t
   use contact2d_state, only: state_t
   use contact2d_output, only: output_t, static_figures_t
   use contact2d_static, only: static_t, static_saved_t
   use contact2d_sys, only: sys_signals_install, sys_signal_pending, sys_strerror
   use contact2d_validity, only: validity_t
   use contact2d_report, only: report_static_summary
   use contact2d_run_exit, only: opath, keep_partial, fail, fail_now, fail_write, kept_note, stop_interrupted, run_ended
   implicit none
   private
   public :: run_static, static_distance

   !> The static run: the engine, the state the writer reads (at rest after each increment: v = 0,
   !> dt = 0) and what the increments leave for the file, the summary and the exit.
   type :: static_state_t
      type(static_t) :: engine
      type(state_t) :: state
      type(validity_t) :: validity
      integer :: increments = 0           !< solver:static_increments
      integer :: splits = 0               !< halvings made (advance)
      real(wp) :: kkt_max(4) = 0          !< largest relative KKT residuals of the accepted steps
      real(wp) :: residual = 0            !< KKT residual of the last accepted step (history)
      real(wp) :: wall = 0                !< wall time at the end of the increments [s]
      logical :: converged = .true.       !< every increment settled
      logical :: ended = .false.          !< the run reached its end (not interrupted, no failure)
      character(len=:), allocatable :: status, reason
      !> the last accepted step, for the work and dissipation of the next one (accept_step)
      real(wp), allocatable :: uprev(:, :), react_prev(:, :), fext_prev(:, :), d(:), dprev(:)
   end type static_state_t

   !> How the increments went (increments): interrupted before increment k; stat /= 0 with errmsg
   !> when the engine failed in increment k; settled = .false. with message when an increment
   !> (k, the first) did not settle; splits: the halvings made.
   type :: increments_t
      integer :: k = 0
      integer :: splits = 0
      integer :: stat = 0
      logical :: interrupted = .false.
      logical :: settled = .true.
      character(len=:), allocatable :: message, errmsg
   end type increments_t

   abstract interface
      !> What follows each settled (sub-)increment that ends at time t.
      subroutine accept_i(t)
         import :: wp
         real(wp), intent(in) :: t
      end subroutine accept_i
   end interface

contains

   !> The static engine from the built model to the published file. Decks it cannot honour were
   !> refused by the deck reader or are refused here (static_start) before anything is written.
   subroutine run_static(deck, model, clock0)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      integer(i8), intent(in) :: clock0   !< system_clock at program start
      type(static_state_t), target :: run
      type(output_t) :: out

      call lock_and_signals()
      call static_start(deck, model, run)
      call output_start(deck, model, run, out)
      call solve(deck, model, run, out)
      call output_end(model, run, out, clock0)
      call report_static_summary(run%engine, run%state, run%increments, run%splits, run%kkt_max, run%wall, &
                                 opath%destination(run%ended))
      call run%validity%report()
      call run%engine%free()
      call run_end(run)
   end subroutine run_static

   !> The output lock and the SIGINT/SIGTERM handler: from now on a signal stops the engine before
   !> its next increment and the file ends with status 'interrupted', as an explicit run's; during
   !> the set-up nothing is written.
   subroutine lock_and_signals()
      integer :: stat
      character(len=:), allocatable :: errmsg
      call opath%acquire(stat, errmsg)
      if (stat /= 0) call fail(1, errmsg)
      stat = sys_signals_install()
      if (stat /= 0) call fail(2, 'cannot install the SIGINT/SIGTERM handler: '//sys_strerror(stat))
   end subroutine lock_and_signals

   !> The engine's set-up (the friction law checked, the stiffness factorised and condensed onto
   !> Gamma_c), its line, and the state at t = 0. A refusal or a signal stops the run here.
   subroutine static_start(deck, model, run)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(static_state_t), intent(inout), target :: run
      integer :: stat
      character(len=:), allocatable :: errmsg
      call run%engine%setup(model, stat, errmsg)
      if (stat /= 0) then
         call run%engine%free()
         call refuse(errmsg)
      end if
      if (sys_signal_pending() /= 0) then
         call run%engine%free()
         call refuse('')   ! the signal is said, not a message
      end if
      associate (st => run%engine)
         run%increments = deck%solver%static_increments
         write (output_unit, '(a)') 'static engine: '//str(st%nfree)//' free dofs, '//str(st%ncdof)// &
            ' condensed onto Gamma_c ('//str(st%nc)//' normal, '//str(st%nt)//' tangential unknowns); CHOLMOD factor '// &
            str(nint(st%chol%lnz))//' nonzeros, '//sci(st%chol%flops)//' flops, smallest pivot / diagonal '// &
            sci(st%chol%pivot_ratio)//'; '//str(run%increments)//' increment(s) to t = '//sci(model%load%end_time())//' s'
      end associate
      call run%state%init(model%contacts, 0.0_wp)
      call run%state%own_fields(model%mesh%nnode)
   end subroutine static_start

   !> A deck or model the engine refuses (exit 1), or a signal during its set-up (128 + signal).
   subroutine refuse(errmsg)
      character(len=*), intent(in) :: errmsg
      integer :: signal
      signal = sys_signal_pending()
      if (signal /= 0) then
         call opath%abandon(keep_partial)
         call stop_interrupted(signal, ' during the static engine''s set-up; nothing was written')
      end if
      call fail(1, errmsg)
   end subroutine refuse

   !> The temporary file with the static run's root attributes and the sample at t = 0.
   subroutine output_start(deck, model, run, out)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(static_state_t), intent(inout), target :: run
      type(output_t), intent(inout) :: out
      integer :: stat
      character(len=:), allocatable :: errmsg
      call out%open(opath%partial, .false., deck, model, run%state, stat, errmsg, sidecar=opath%xmf_partial, &
                    target=opath%target)
      if (stat /= 0) then
         call run%engine%free()
         call fail_now(2, errmsg, .false.)   ! the file could not be created: no file kept
      end if
      call out%attributes_static(deck, model)
      call out%sample(run%state, 0.0_wp)
   end subroutine output_start

   !> The increments to the end of the load (docs/static.md), a history sample after each settled
   !> step; the first that fails or does not settle ends them, as does a signal.
   subroutine solve(deck, model, run, out)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      type(static_state_t), intent(inout), target :: run
      type(output_t), intent(inout) :: out
      type(increments_t) :: res
      allocate (run%uprev(2, model%mesh%nnode), run%react_prev(2, model%mesh%nnode), run%fext_prev(2, model%mesh%nnode))
      run%uprev = 0
      run%react_prev = 0
      run%fext_prev = 0
      allocate (run%d(run%engine%nc), run%dprev(run%engine%nc))
      run%dprev = 0
      ! (the static engine solves one pair: the deck refuses more, contact2d_deck)
      if (size(run%state%contacts) > 0) run%dprev = -run%state%contacts(1)%gap
      run%status = 'converged'
      run%reason = ''
      call increments(run%engine, deck, model, .true., res, accept)
      run%splits = res%splits
      run%converged = .not. res%interrupted .and. res%stat == 0 .and. res%settled
      if (res%interrupted) then
         run%status = 'interrupted'
      else if (res%stat /= 0) then
         run%status = 'static solver failure'
         run%reason = res%errmsg//' (increment '//str(res%k)//')'
      else if (.not. res%settled) then
         run%status = 'not converged: '//res%message//' (increment '//str(res%k)//')'
         if (deck%solver%static_splits > 0) run%status = run%status//', also in '// &
            str(2**deck%solver%static_splits)//' parts (solver:static_splits = '//str(deck%solver%static_splits)//')'
      end if
   contains
      subroutine accept(t)
         real(wp), intent(in) :: t
         call accept_step(run, model, t)
         call out%sample(run%state, run%residual)
      end subroutine accept
   end subroutine solve

   !> After each settled (sub-)increment at time t: the state for the writer, the work and
   !> dissipation of the increment, the largest KKT residuals.
   subroutine accept_step(run, model, t)
      type(static_state_t), intent(inout), target :: run
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: t
      integer :: i
      real(wp) :: w, wf, wn
      associate (st => run%engine, state => run%state, uprev => run%uprev, d => run%d, dprev => run%dprev)
         run%kkt_max = max(run%kkt_max, st%kkt)
         ! the state for the writer: at rest (v = 0, no kinetic energy)
         state%u = st%u
         state%v = 0
         state%fint = st%fint
         state%fext = st%fext
         state%step = state%step + 1
         state%time = t
         state%kinetic = 0
         state%strain = 0.5_wp*sum(st%u*st%fint)
         state%strain_step = state%strain   ! a state at rest: the physical energies are these
         state%kinetic_step = 0
         ! work of the loads and reactions: trapezoid over the increment (exact when the increment
         ! is linear; a diagnostic otherwise, see docs/static.md)
         ! (reactions live on the prescribed dofs, tractions on the free ones)
         w = 0.5_wp*sum((run%react_prev + run%fext_prev + (st%fint - st%fext)*(1 - model%load%free) + st%fext)* &
                        (st%u - uprev))
         state%external_work = state%external_work + w
         if (size(state%contacts) > 0) then
         associate (c => state%contacts(1))
            if (c%active) then
               c%fn = st%fn
               c%ft = st%ft
               c%mu = st%mu
               ! the limits of these forces, for the statuses (stick / slip), as the explicit step sets them
               if (c%friction) then
                  if (st%p0) then
                     call c%law%limits(c%fn, c%mu, c%slip_limit)
                  else
                     call c%law%limits(c%fn, c%fn, c%slip_limit)
                  end if
               end if
               do i = 1, st%nc
                  d(i) = dot_product(st%u(:, c%node(i)), c%normal(:, i)) - c%gap(i)
               end do
               ! friction: F_t times the slip of the increment (backward Euler, exact for the law);
               ! normal work: F_n times the change of d
               wf = 0
               do i = 1, st%nc
                  wf = wf + st%ft(i)*dot_product(st%u(:, c%node(i)) - uprev(:, c%node(i)), c%tangent(:, i))
               end do
               wn = sum(st%fn*(d - dprev))
               c%friction_dissipation = c%friction_dissipation + wf
               c%normal_work = c%normal_work + wn
               c%normal_total = sum(st%fn)
               c%tangential_total = sum(st%ft)
               c%penetration_max = max(0.0_wp, c%penetration(st%u))
               c%stat = 0
               dprev = d
            end if
         end associate
         end if
         run%residual = st%kkt(4)
         run%react_prev = (st%fint - st%fext)*(1 - model%load%free)
         run%fext_prev = st%fext
         uprev = st%u
      end associate
   end subroutine accept_step

   !> The closing attributes, the validity range of a run that reached its end (docs/output.md),
   !> /final. A failed write stops the run (exit 2) and keeps the temporary file.
   subroutine output_end(model, run, out, clock0)
      type(model_t), intent(in) :: model
      type(static_state_t), intent(inout), target :: run
      type(output_t), intent(inout) :: out
      integer(i8), intent(in) :: clock0
      integer(i8) :: clock1, rate
      integer :: stat
      character(len=:), allocatable :: errmsg
      real(wp) :: timings(4)
      call system_clock(clock1, rate)
      run%wall = real(clock1 - clock0, wp)/rate
      timings = [run%engine%time_factor + run%engine%time_condense, run%engine%time_pdas, 0.0_wp, 0.0_wp]
      call out%attributes_static_end(figures(run))
      run%ended = run_ended(run%status)
      ! the small-strain, small-displacement range of the end state (docs/output.md)
      if (run%ended) then
         call run%validity%measure(model%mesh, run%state%u)
         call run%validity%write(out%file)
      end if
      run%state%converged = run%converged
      run%state%status = run%status
      call out%finish(model, run%state, run%wall, timings, stat, errmsg)
      if (stat /= 0) then
         call run%engine%free()
         call fail_write(errmsg//'; what was written so far is in '//opath%partial)
      end if
   end subroutine output_end

   !> What the engine and the increments leave for the closing root attributes.
   type(static_figures_t) function figures(run) result(fig)
      type(static_state_t), intent(in) :: run
      fig%kkt_max = run%kkt_max
      fig%increments = run%increments
      fig%steps = int(run%state%step)
      fig%splits = run%splits
      fig%iterations = run%engine%iterations
      fig%outer_iterations = run%engine%outer_iterations
      fig%factor_nonzeros = run%engine%chol%lnz
      fig%factor_flops = run%engine%chol%flops
      fig%time_factor = run%engine%time_factor
      fig%time_condense = run%engine%time_condense
      fig%time_solve = run%engine%time_pdas
   end function figures

   !> The file moved into place (a run that did not reach its end does not replace an existing
   !> result: it stays at its temporary name, docs/output.md); then the exit of a run that was
   !> interrupted (128 + signal) or did not converge (exit 2), each naming where the file is.
   subroutine run_end(run)
      type(static_state_t), intent(in) :: run
      integer :: signal
      character(len=:), allocatable :: msg, dest
      dest = opath%destination(run%ended)
      keep_partial = .true.   ! complete: a move that fails (named in its message) keeps it
      call opath%publish(signal, msg, run%ended)
      if (signal /= 0) call fail(2, msg)
      keep_partial = dest /= opath%target   ! kept at its temporary name: not removed below
      signal = sys_signal_pending()
      if (signal /= 0) then
         call opath%abandon(keep_partial)
         call stop_interrupted(signal, '; '//dest//" holds the increments done (status 'interrupted')"//kept_note(dest))
      end if
      if (.not. run%converged) then
         msg = 'static engine: '//run%status
         if (len(run%reason) > 0) msg = msg//': '//run%reason
         call fail(2, msg//'; '//dest//' holds the last iterate'//kept_note(dest))
      end if
      call opath%abandon(keep_partial)
   end subroutine run_end

   !> The increments 1 .. solver:static_increments to the end of the load, each by advance: the
   !> one loop of the static run (accept after each settled step; stop_unsettled: the first
   !> increment that does not settle ends them) and of static_distance (no accept; every
   !> increment is solved). A signal ends them before the next increment.
   subroutine increments(engine, deck, model, stop_unsettled, res, accept)
      type(static_t), intent(inout), target :: engine   !< (accept may read it through the run)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      logical, intent(in) :: stop_unsettled
      type(increments_t), intent(out) :: res
      procedure(accept_i), optional :: accept
      integer :: k
      engine%max_iter = deck%solver%static_iterations
      do k = 1, deck%solver%static_increments
         if (sys_signal_pending() /= 0) then
            res%interrupted = .true.
            res%k = k
            return
         end if
         call advance(engine, deck, model, k, res, accept)
         if (res%stat /= 0) return
         if (.not. res%settled .and. stop_unsettled) return
      end do
   end subroutine increments

   !> Take the static engine through increment k, from t_end (k - 1)/nk to t_end k/nk: one step
   !> or, when that does not settle (the active set cycles or needs more than
   !> solver:static_iterations iterations), the same span in two halves, each from the last
   !> settled state, and so on down to 2^solver:static_splits parts (a smaller step changes fewer
   !> contact and slip states at once). Each halving adds one to res%splits. accept(t), if given,
   !> follows every settled step. A step of the smallest size that does not settle has its last
   !> iterate accepted too and ends the increment: res%settled = .false. with res%message and
   !> res%k the first time. res%stat /= 0 with res%errmsg and res%k when the engine fails.
   subroutine advance(st, deck, model, k, res, accept)
      type(static_t), intent(inout), target :: st   !< (accept may read it through the run)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      integer, intent(in) :: k
      type(increments_t), intent(inout) :: res
      procedure(accept_i), optional :: accept
      type(static_saved_t) :: saved
      integer(i8) :: parts, pos, size
      integer :: nk
      real(wp) :: t_end, t_from, t_to, t
      logical :: ok
      character(len=:), allocatable :: message
      nk = deck%solver%static_increments
      t_end = model%load%end_time()
      t_from = t_end*real(k - 1, wp)/nk
      t_to = t_end*real(k, wp)/nk
      ! positions in units of 1 / 2^static_splits of the span; the last step ends at t_to exactly
      parts = 2_i8**deck%solver%static_splits
      pos = 0
      size = parts
      do while (pos < parts)
         if (pos + size == parts) then
            t = t_to
         else
            t = t_from + (t_to - t_from)*(real(pos + size, wp)/real(parts, wp))
         end if
         if (size > 1) call st%save(saved)
         call st%increment(model, t, ok, message, res%stat, res%errmsg)
         if (res%stat /= 0) then
            res%k = k
            return
         end if
         if (.not. ok .and. size > 1) then
            call st%restore(saved)
            size = size/2
            res%splits = res%splits + 1
            cycle
         end if
         if (present(accept)) call accept(t)
         if (.not. ok) then
            if (res%settled) then
               res%settled = .false.
               res%k = k
               res%message = message
            end if
            return
         end if
         pos = pos + size
      end do
   end subroutine advance

   !> Energy-norm distance ||u - u_s||_K / ||u_s||_K of the displacement u to the static solution
   !> of the same model (solver:static_increments increments; only the end state is kept).
   !> stat /= 0 with errmsg if the static engine refuses, fails or a signal stops it;
   !> converged = .false. if an increment did not settle.
   subroutine static_distance(deck, model, u, dist, converged, stat, errmsg)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:, :)
      real(wp), intent(out) :: dist
      logical, intent(out) :: converged
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(static_t) :: st
      type(increments_t) :: res
      real(wp), allocatable :: du(:, :), kdu(:, :)

      dist = huge(1.0_wp)
      converged = .false.
      call st%setup(model, stat, errmsg)
      if (stat /= 0) return
      call increments(st, deck, model, .false., res)
      if (res%interrupted) then
         ! SIGINT/SIGTERM: give up the comparison (the caller finishes the run's own file)
         stat = 1
         errmsg = 'interrupted by a signal before increment '//str(res%k)//'; no comparison written'
         return
      end if
      if (res%stat /= 0) then
         stat = res%stat
         errmsg = res%errmsg
         return
      end if
      converged = res%settled
      du = u - st%u
      allocate (kdu, mold=du)
      call model%stiff%apply(du, kdu)
      dist = sqrt(max(sum(du*kdu), 0.0_wp))/sqrt(max(sum(st%u*st%fint), tiny(1.0_wp)))
      call st%free()
   end subroutine static_distance

end module contact2d_run_static
