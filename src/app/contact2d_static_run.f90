!> The driver's static branch (solver:method = 'static' or --static; docs/static.md): solve,
!> write the same HDF5 file as an explicit run (SPEC section 8 with dt = 0, steps = increments,
!> method = 'static' and the KKT residuals as attributes) and print the summary. Also the
!> energy-norm distance of an explicit end state to the static solution (solver:compare_static).
!> Nothing here stops the program: the driver does, with the code and message returned.
module contact2d_static_run
   use, intrinsic :: iso_fortran_env, only: output_unit
   use contact2d_kinds, only: wp, i8
   use contact2d_strings, only: str, fixed, sci
   use contact2d_deck, only: deck_t
   use contact2d_model, only: model_t
   use contact2d_state, only: state_t
   use contact2d_output, only: output_t
   use contact2d_static, only: static_t, static_saved_t
   use contact2d_kkt, only: kkt_names
   use contact2d_sys, only: sys_signal_pending
   use contact2d_validity, only: validity_t
   use contact2d_report, only: report_static_summary
   implicit none
   private
   public :: static_run, static_distance

contains

   !> Run the static engine and write `path`. code: 0 converged; 1 refused before anything was
   !> written (singular stiffness, model not supported); 2 written but not converged or failed.
   !> Output safety (docs/output.md): the driver passes the temporary file as `path`, the sidecar's
   !> temporary name as `sidecar` and the final name as `target`; `written` tells it whether the
   !> file was finished (then it is moved into place), `opened` whether it was created at all.
   !> `replacing`: the target exists and --force replaces it; a run that does not reach its end
   !> (`ended` false: interrupted, solver failure) then keeps its file at `path` (docs/output.md).
   subroutine static_run(deck, model, path, overwrite, clock0, code, errmsg, sidecar, target, written, opened, &
                         replacing, ended)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      character(len=*), intent(in) :: path
      logical, intent(in) :: overwrite
      integer(i8), intent(in) :: clock0   !< system_clock at program start
      integer, intent(out) :: code
      character(len=:), allocatable, intent(out) :: errmsg
      character(len=*), intent(in), optional :: sidecar, target
      logical, intent(out), optional :: written, opened
      logical, intent(in), optional :: replacing
      logical, intent(out), optional :: ended
      type(static_t) :: st
      type(state_t), target :: state   !< at rest after each increment: v = 0, dt = 0
      type(output_t) :: out
      type(validity_t) :: validity
      integer :: k, nk, stat, i, splits
      integer(i8) :: clock1, rate
      real(wp) :: t_end, t, wall, timings(4), w_prev, wf, wn, kkt_max(4), residual
      real(wp), allocatable :: uprev(:, :), react_prev(:, :), fext_prev(:, :), fn_prev(:), d(:), dprev(:)
      logical :: converged, ok, run_ended
      character(len=:), allocatable :: message, status, reason, final

      code = 1
      reason = ''
      if (present(written)) written = .false.
      if (present(opened)) opened = .false.
      call supported(deck, stat, errmsg)
      if (stat /= 0) return
      call st%setup(model, stat, errmsg)
      if (stat /= 0) then
         call st%free()
         return
      end if
      if (sys_signal_pending() /= 0) then
         ! SIGINT/SIGTERM during the factorisation (the driver reports it; nothing written)
         errmsg = 'interrupted'
         call st%free()
         return
      end if
      nk = deck%solver%static_increments
      st%max_iter = deck%solver%static_iterations
      t_end = model%load%end_time()
      write (output_unit, '(a)') 'static engine: '//str(st%nfree)//' free dofs, '//str(st%ncdof)// &
         ' condensed onto Gamma_c ('//str(st%nc)//' normal, '//str(st%nt)//' tangential unknowns); CHOLMOD factor '// &
         str(nint(st%chol%lnz))//' nonzeros, '//sci(st%chol%flops)//' flops, smallest pivot / diagonal '// &
         sci(st%chol%pivot_ratio)//'; '//str(nk)//' increment(s) to t = '//sci(t_end)//' s'

      call state%init(model%contact, 0.0_wp)
      call state%own_fields(model%mesh%nnode)
      if (present(sidecar) .and. present(target)) then
         call out%open(path, overwrite, deck, model, state, stat, errmsg, sidecar=sidecar, target=target)
      else
         call out%open(path, overwrite, deck, model, state, stat, errmsg)
      end if
      if (stat /= 0) then
         code = 2
         call st%free()
         return
      end if
      if (present(opened)) opened = .true.
      call attributes_open(out, deck, model)
      call out%sample(state, 0.0_wp)

      allocate (uprev(2, model%mesh%nnode), react_prev(2, model%mesh%nnode), fext_prev(2, model%mesh%nnode))
      uprev = 0
      react_prev = 0
      fext_prev = 0
      allocate (fn_prev(st%nc), d(st%nc), dprev(st%nc))
      fn_prev = 0
      dprev = 0
      if (state%contact%active) dprev = -state%contact%gap
      converged = .true.
      status = 'converged'
      kkt_max = 0
      residual = 0
      splits = 0
      do k = 1, nk
         if (sys_signal_pending() /= 0) then
            converged = .false.
            status = 'interrupted'
            exit
         end if
         call advance(st, model, t_end*real(k - 1, wp)/nk, t_end*real(k, wp)/nk, deck%solver%static_splits, splits, &
                      accept, ok, message, stat, errmsg)
         if (stat /= 0) then
            converged = .false.
            status = 'static solver failure'
            reason = errmsg//' (increment '//str(k)//')'
            exit
         end if
         if (.not. ok) then
            converged = .false.
            status = 'not converged: '//message//' (increment '//str(k)//')'
            if (deck%solver%static_splits > 0) status = status//', also in '// &
               str(2**deck%solver%static_splits)//' parts (solver:static_splits = '//str(deck%solver%static_splits)//')'
            exit
         end if
      end do

      call system_clock(clock1, rate)
      wall = real(clock1 - clock0, wp)/rate
      timings = [st%time_factor + st%time_condense, st%time_pdas, 0.0_wp, 0.0_wp]
      call attributes_end(out, st, kkt_max, nk, int(state%step), splits)
      ! the small-strain, small-displacement range of the end state (docs/output.md)
      if (status /= 'interrupted' .and. status /= 'static solver failure') then
         call validity%measure(model%mesh, state%u)
         call validity%write(out%file)
      end if
      state%converged = converged
      state%status = status
      call out%finish(model, state, wall, timings, stat, errmsg)
      if (stat /= 0) then
         code = 2
         call st%free()
         return
      end if
      if (present(written)) written = .true.
      run_ended = status /= 'interrupted' .and. status /= 'static solver failure'
      if (present(ended)) ended = run_ended
      final = path
      if (present(target)) final = target
      if (present(target) .and. present(replacing)) then
         if (replacing .and. .not. run_ended) final = path
      end if
      call report_static_summary(st, state, nk, splits, kkt_max, wall, final)
      call validity%report()
      call st%free()
      if (converged) then
         code = 0
         errmsg = ''
      else
         code = 2
         errmsg = 'static engine: '//status
         if (len(reason) > 0) errmsg = errmsg//': '//reason
         errmsg = errmsg//'; '//final//' holds the last iterate'
         if (present(target) .and. final == path) errmsg = errmsg//'; the existing '//target// &
            ' is kept (--force replaces a result only with a run that reaches its end)'
      end if
   contains
      !> After each settled (sub-)increment at time t: the state for the writer, the work and
      !> dissipation of the increment, one history sample.
      subroutine accept(t)
         real(wp), intent(in) :: t
         kkt_max = max(kkt_max, st%kkt)
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
         w_prev = 0.5_wp*sum((react_prev + fext_prev + (st%fint - st%fext)*(1 - model%load%free) + st%fext)* &
                             (st%u - uprev))
         state%external_work = state%external_work + w_prev
         associate (c => state%contact)
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
         residual = st%kkt(4)
         react_prev = (st%fint - st%fext)*(1 - model%load%free)
         fext_prev = st%fext
         uprev = st%u
         call out%sample(state, residual)
      end subroutine accept

   end subroutine static_run

   !> The root attributes an explicit file has, with their static values (docs/output.md).
   subroutine attributes_open(out, deck, model)
      type(output_t), intent(inout) :: out
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      call out%file%attr(out%file%id, 'method', 'static')
      call out%file%attr(out%file%id, 'omega_max_element', sqrt(model%stiff%omega2_element))
      call out%file%attr(out%file%id, 'dt_limit', trim(deck%solver%dt_limit))
      call out%file%attr(out%file%id, 'dt_initial', 0.0_wp)
      call out%file%attr(out%file%id, 'dt_fallback_step', -1)
      call out%file%attr(out%file%id, 'added_mass', model%added_mass)
      call out%file%attr(out%file%id, 'body_mass', model%body_mass)
      call out%file%attr(out%file%id, 'dynamic', 0)
      call out%file%attr(out%file%id, 'convergence_test', 1)
      call out%file%attr(out%file%id, 'initial_kinetic_energy', 0.0_wp)
   end subroutine attributes_open

   !> The static engine's closing attributes: the largest KKT residuals, the increments, steps
   !> and halvings, the iterations, the factor's size and the engine's times (docs/output.md).
   subroutine attributes_end(out, st, kkt_max, nk, steps, splits)
      type(output_t), intent(inout) :: out
      type(static_t), intent(in) :: st
      real(wp), intent(in) :: kkt_max(4)
      integer, intent(in) :: nk, steps, splits
      integer :: i
      do i = 1, 4
         call out%file%attr(out%file%id, 'kkt_'//trim(kkt_names(i)), kkt_max(i))
      end do
      call out%file%attr(out%file%id, 'static_increments', nk)
      call out%file%attr(out%file%id, 'static_steps', steps)
      call out%file%attr(out%file%id, 'static_splits', splits)
      call out%file%attr(out%file%id, 'static_iterations', st%iterations)
      call out%file%attr(out%file%id, 'static_outer_iterations', st%outer_iterations)
      call out%file%attr(out%file%id, 'factor_nonzeros', st%chol%lnz)
      call out%file%attr(out%file%id, 'factor_flops', st%chol%flops)
      call out%file%attr(out%file%id, 'time_factor_seconds', st%time_factor)
      call out%file%attr(out%file%id, 'time_condense_seconds', st%time_condense)
      call out%file%attr(out%file%id, 'time_solve_seconds', st%time_pdas)
   end subroutine attributes_end

   !> Take the static engine from its state at t_from to t_to: one increment or, when that does not
   !> settle (the active set cycles or needs more than solver:static_iterations iterations), the
   !> same span in two halves, each from the last settled state, and so on down to
   !> 2^max_splits parts (a smaller step changes fewer contact and slip states at once). Each
   !> halving adds one to splits. accept(t) follows every settled step. ok = .false. with message
   !> when a step of the smallest size does not settle: that step's last iterate is accepted too.
   !> stat /= 0 with errmsg when the engine fails.
   subroutine advance(st, model, t_from, t_to, max_splits, splits, accept, ok, message, stat, errmsg)
      type(static_t), intent(inout) :: st
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: t_from, t_to
      integer, intent(in) :: max_splits
      integer, intent(inout) :: splits
      interface
         subroutine accept(t)
            import :: wp
            real(wp), intent(in) :: t
         end subroutine accept
      end interface
      logical, intent(out) :: ok
      character(len=:), allocatable, intent(out) :: message
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(static_saved_t) :: saved
      integer(i8) :: parts, pos, size
      real(wp) :: t
      ! positions in units of 1 / 2^max_splits of the span; the last step ends at t_to exactly
      parts = 2_i8**max_splits
      pos = 0
      size = parts
      do while (pos < parts)
         if (pos + size == parts) then
            t = t_to
         else
            t = t_from + (t_to - t_from)*(real(pos + size, wp)/real(parts, wp))
         end if
         if (size > 1) call st%save(saved)
         call st%increment(model, t, ok, message, stat, errmsg)
         if (stat /= 0) return
         if (.not. ok .and. size > 1) then
            call st%restore(saved)
            size = size/2
            splits = splits + 1
            cycle
         end if
         call accept(t)
         if (.not. ok) return
         pos = pos + size
      end do
   end subroutine advance

   !> Energy-norm distance ||u - u_s||_K / ||u_s||_K of the displacement u to the static solution
   !> of the same model (solver:static_increments increments). stat /= 0 with errmsg if the
   !> static engine refuses or fails; converged = .false. if it did not converge.
   subroutine static_distance(deck, model, u, dist, converged, stat, errmsg)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: u(:, :)
      real(wp), intent(out) :: dist
      logical, intent(out) :: converged
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(static_t) :: st
      real(wp), allocatable :: du(:, :), kdu(:, :)
      character(len=:), allocatable :: message
      real(wp) :: t_end
      integer :: k, nk, splits
      logical :: ok

      dist = huge(1.0_wp)
      converged = .false.
      call supported(deck, stat, errmsg)
      if (stat /= 0) return
      call st%setup(model, stat, errmsg)
      if (stat /= 0) return
      nk = deck%solver%static_increments
      t_end = model%load%end_time()
      st%max_iter = deck%solver%static_iterations
      converged = .true.
      splits = 0
      do k = 1, nk
         ! SIGINT/SIGTERM: give up the comparison (the caller finishes the run's own file)
         if (sys_signal_pending() /= 0) then
            stat = 1
            errmsg = 'interrupted by a signal before increment '//str(k)//'; no comparison written'
            return
         end if
         call advance(st, model, t_end*real(k - 1, wp)/nk, t_end*real(k, wp)/nk, deck%solver%static_splits, splits, &
                      no_sample, ok, message, stat, errmsg)
         if (stat /= 0) return
         converged = converged .and. ok
      end do
      du = u - st%u
      allocate (kdu, mold=du)
      call model%stiff%apply(du, kdu)
      dist = sqrt(max(sum(du*kdu), 0.0_wp))/sqrt(max(sum(st%u*st%fint), tiny(1.0_wp)))
      call st%free()
   contains
      subroutine no_sample(t)
         real(wp), intent(in) :: t
         if (.false.) dist = t   ! (the comparison keeps only the end state)
      end subroutine no_sample
   end subroutine static_distance

   !> The friction laws the static engine solves: frictionless, Tresca and Coulomb
   !> (docs/static.md). Another law is refused rather than solved as something else.
   subroutine supported(deck, stat, errmsg)
      type(deck_t), intent(in) :: deck
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      stat = 0
      errmsg = ''
      if (.not. deck%contact%present) return
      if (.not. any(trim(deck%contact%friction) == [character(len=12) :: 'frictionless', 'tresca', 'coulomb'])) then
         stat = 1
         errmsg = "the static engine solves frictionless, Tresca and Coulomb contact only; contact:friction = '"// &
                  trim(deck%contact%friction)//"' is not supported with solver:method = 'static' or compare_static"
      end if
   end subroutine supported


end module contact2d_static_run
