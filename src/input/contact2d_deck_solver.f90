!> &solver: time step, load ramp, damping, convergence and the engine (docs/deck.md,
!> docs/static.md): its variables with their defaults, its namelist read, its validation and
!> its echo lines.
module contact2d_deck_solver
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower
   use contact2d_checks, only: check_finite, check_range, max_magnitude
   use contact2d_deck_syntax, only: unset, line_len, override_t, read_failed, too_long, kv, quoted
   implicit none
   private
   public :: solver_cfg_t, solver_variables, solver_logicals, solver_cfg_read, solver_cfg_not_finite
   public :: solver_cfg_validate, solver_cfg_echo

   !> The variables of &solver offered as suggestions for a misspelled name.
   character(len=*), parameter :: solver_variables = &
      'dt dt_factor allow_unstable t_ramp t_end max_steps damping alpha damping_interval tol_residual '// &
      'tol_kinetic check_interval power_iterations dt_limit mass_scaling method static_increments '// &
      'compare_static convergence_test'
   !> The logical variables of &solver (their values are checked as text before the read).
   character(len=*), parameter :: solver_logicals(2) = [character(len=14) :: 'allow_unstable', 'compare_static']

   !> &solver: time step, load ramp, damping and convergence.
   type :: solver_cfg_t
      real(wp) :: dt = 0                  !< time step [s]; 0: dt_factor * dt_critical
      real(wp) :: dt_factor = 0.9_wp      !< dt / dt_critical when dt = 0, > 0
      logical :: allow_unstable = .false. !< accept dt > dt_critical (stability studies)
      real(wp) :: t_ramp = unset          !< duration of a one-stage load without its own times [s]
      real(wp) :: t_end = 0               !< end time [s]; 0: 10 x the end of the last stage
      integer :: max_steps = 10000000     !< step limit, >= 1
      character(len=8) :: damping = 'auto'  !< 'auto' | 'given' | 'none'
      real(wp) :: alpha = 0               !< mass-proportional damping for 'given' [1/s], >= 0
      integer :: damping_interval = 20    !< steps between estimates of omega_1 ('auto')
      real(wp) :: tol_residual = 1.0e-8_wp  !< relative out-of-balance force at convergence
      real(wp) :: tol_kinetic = 1.0e-12_wp  !< kinetic / strain energy at convergence
      integer :: check_interval = 10      !< steps between convergence checks
      integer :: power_iterations = 100   !< power iterations for the true omega_max (0: skip)
      !> 'element': dt from the element bound; 'power': from the power-iteration estimate of the
      !> true limit, with a growing-mode guard falling back to the element bound
      character(len=8) :: dt_limit = 'element'
      real(wp) :: mass_scaling = 0        !< target stable step [s] of mass scaling; 0: off
      character(len=8) :: method = 'explicit'  !< 'explicit' | 'static' (docs/static.md)
      integer :: static_increments = 1    !< static load increments along the load curves, >= 1
      !> static: active-set iterations of one solve before an increment counts as not settled
      integer :: static_iterations = 200
      !> static: halvings of an increment that does not settle (up to 2^static_splits parts)
      integer :: static_splits = 6
      logical :: compare_static = .false. !< explicit run: report the energy distance to the static solution
      !> 'auto' | 'on' | 'off': stop at convergence; 'auto' is off for dynamic runs
      character(len=8) :: convergence_test = 'auto'
   end type solver_cfg_t

contains

   !> Read the group's lines blk (none: the group is absent), then the --set overrides ovr.
   subroutine solver_cfg_read(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(solver_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: dt, dt_factor, t_ramp, t_end, alpha, tol_residual, tol_kinetic, mass_scaling
      logical :: allow_unstable
      integer :: max_steps, damping_interval, check_interval, power_iterations, ios, i
      character(len=line_len) :: damping, dt_limit, method, convergence_test
      integer :: static_increments, static_iterations, static_splits
      logical :: compare_static
      character(len=256) :: msg
      namelist /solver/ dt, dt_factor, allow_unstable, t_ramp, t_end, max_steps, damping, &
         alpha, damping_interval, tol_residual, tol_kinetic, check_interval, power_iterations, &
         dt_limit, mass_scaling, method, static_increments, compare_static, convergence_test, &
         static_iterations, static_splits
      dt_limit = cfg%dt_limit; mass_scaling = cfg%mass_scaling
      method = cfg%method; static_increments = cfg%static_increments; compare_static = cfg%compare_static
      dt = cfg%dt; dt_factor = cfg%dt_factor; allow_unstable = cfg%allow_unstable
      t_ramp = cfg%t_ramp; t_end = cfg%t_end; max_steps = cfg%max_steps
      damping = cfg%damping; alpha = cfg%alpha; damping_interval = cfg%damping_interval
      tol_residual = cfg%tol_residual; tol_kinetic = cfg%tol_kinetic
      check_interval = cfg%check_interval; power_iterations = cfg%power_iterations
      convergence_test = cfg%convergence_test
      static_iterations = cfg%static_iterations; static_splits = cfg%static_splits
      if (size(blk) > 0) then
         read (blk, nml=solver, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, solver_variables, where, stat, errmsg)) return
      end if
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=solver, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, solver_variables, "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      if (too_long(where, 'damping', damping, len(cfg%damping), stat, errmsg)) return
      if (too_long(where, 'method', method, len(cfg%method), stat, errmsg)) return
      if (too_long(where, 'dt_limit', dt_limit, len(cfg%dt_limit), stat, errmsg)) return
      if (too_long(where, 'convergence_test', convergence_test, len(cfg%convergence_test), stat, errmsg)) return
      cfg%dt = dt; cfg%dt_factor = dt_factor; cfg%allow_unstable = allow_unstable
      cfg%t_ramp = t_ramp; cfg%t_end = t_end; cfg%max_steps = max_steps
      cfg%damping = damping; cfg%alpha = alpha; cfg%damping_interval = damping_interval
      cfg%tol_residual = tol_residual; cfg%tol_kinetic = tol_kinetic
      cfg%check_interval = check_interval; cfg%power_iterations = power_iterations
      cfg%dt_limit = dt_limit; cfg%mass_scaling = mass_scaling
      cfg%method = method; cfg%static_increments = static_increments; cfg%compare_static = compare_static
      cfg%convergence_test = convergence_test
      cfg%static_iterations = static_iterations; cfg%static_splits = static_splits
   end subroutine solver_cfg_read

   !> check_finite on every real of the group; true if one is bad.
   logical function solver_cfg_not_finite(s, errmsg) result(bad)
      type(solver_cfg_t), intent(in) :: s
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('solver:dt', s%dt, errmsg)) return
      if (check_finite('solver:dt_factor', s%dt_factor, errmsg)) return
      if (check_finite('solver:t_ramp', s%t_ramp, errmsg)) return
      if (check_finite('solver:t_end', s%t_end, errmsg)) return
      if (check_finite('solver:alpha', s%alpha, errmsg)) return
      if (check_finite('solver:tol_residual', s%tol_residual, errmsg)) return
      if (check_finite('solver:tol_kinetic', s%tol_kinetic, errmsg)) return
      if (check_finite('solver:mass_scaling', s%mass_scaling, errmsg)) return
      bad = .false.
   end function solver_cfg_not_finite

   !> Ranges and choices (lower-cased), exclusive options; true if a value is refused.
   logical function solver_cfg_validate(s, errmsg) result(bad)
      type(solver_cfg_t), intent(inout) :: s
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (.not. s%dt >= 0) then; errmsg = 'solver:dt = '//str(s%dt)//' must be >= 0 (0: automatic)'; return; end if
      if (.not. s%dt_factor > 0) then
         errmsg = 'solver:dt_factor = '//str(s%dt_factor)//' must be > 0'
         return
      end if
      ! a step below 1e-30 (s) is no physical input; a subnormal one overflows the step count
      ! t_end/dt (Debug: a trap)
      if (check_range('solver:dt_factor', s%dt_factor, 1.0e-30_wp, max_magnitude, errmsg)) return
      if (s%dt /= 0) then
         if (check_range('solver:dt', s%dt, 1.0e-30_wp, max_magnitude, errmsg)) return
      end if
      if (s%t_ramp /= unset .and. .not. s%t_ramp > 0) then
         errmsg = 'solver:t_ramp = '//str(s%t_ramp)//' must be > 0'
         return
      end if
      if (.not. s%t_end >= 0) then; errmsg = 'solver:t_end = '//str(s%t_end)//' must be >= 0'; return; end if
      if (s%max_steps < 1) then; errmsg = 'solver:max_steps = '//str(s%max_steps)//' must be >= 1'; return; end if
      s%damping = lower(s%damping)
      if (.not. any(s%damping == [character(len=8) :: 'auto', 'given', 'none'])) then
         errmsg = "solver:damping = '"//trim(s%damping)//"' is not one of 'auto', 'given', 'none'"
         return
      end if
      if (.not. s%alpha >= 0) then; errmsg = 'solver:alpha = '//str(s%alpha)//' must be >= 0'; return; end if
      if (s%damping == 'given' .and. s%alpha == 0) then
         errmsg = "solver:damping = 'given' needs solver:alpha > 0 (1/s); use 'none' for no damping"
         return
      end if
      if (s%damping /= 'given' .and. s%alpha /= 0) then
         errmsg = "solver:alpha is set but solver:damping = '"//trim(s%damping)//"' ignores it; "// &
                  "use damping = 'given'"
         return
      end if
      if (s%damping_interval < 1) then
         errmsg = 'solver:damping_interval = '//str(s%damping_interval)//' must be >= 1'
         return
      end if
      if (.not. s%tol_residual > 0) then
         errmsg = 'solver:tol_residual = '//str(s%tol_residual)//' must be > 0'
         return
      end if
      if (.not. s%tol_kinetic > 0) then
         errmsg = 'solver:tol_kinetic = '//str(s%tol_kinetic)//' must be > 0'
         return
      end if
      if (s%check_interval < 1) then
         errmsg = 'solver:check_interval = '//str(s%check_interval)//' must be >= 1'
         return
      end if
      if (s%power_iterations < 0) then
         errmsg = 'solver:power_iterations = '//str(s%power_iterations)//' must be >= 0'
         return
      end if
      s%dt_limit = lower(s%dt_limit)
      if (.not. any(s%dt_limit == [character(len=8) :: 'element', 'power'])) then
         errmsg = "solver:dt_limit = '"//trim(s%dt_limit)//"' is not one of 'element', 'power'"
         return
      end if
      if (s%dt_limit == 'power' .and. s%power_iterations == 0) then
         errmsg = "solver:dt_limit = 'power' needs solver:power_iterations > 0"
         return
      end if
      if (.not. s%mass_scaling >= 0) then
         errmsg = 'solver:mass_scaling = '//str(s%mass_scaling)//' must be >= 0 (target time step, s; 0: off)'
         return
      end if
      ! fictitious masses change the dynamics: quasi-static runs (automatic damping) only
      if (s%mass_scaling > 0 .and. s%damping /= 'auto') then
         errmsg = "solver:mass_scaling = "//str(s%mass_scaling)//" is refused for a dynamic run (damping = '"// &
                  trim(s%damping)//"'); it needs damping = 'auto' (quasi-static relaxation)"
         return
      end if
      ! the static engine (docs/static.md)
      s%method = lower(s%method)
      if (.not. any(s%method == [character(len=8) :: 'explicit', 'static'])) then
         errmsg = "solver:method = '"//trim(s%method)//"' is not one of 'explicit', 'static'"
         return
      end if
      if (s%static_increments < 1) then
         errmsg = 'solver:static_increments = '//str(s%static_increments)//' must be >= 1'
         return
      end if
      if (s%static_iterations < 1) then
         errmsg = 'solver:static_iterations = '//str(s%static_iterations)//' must be >= 1'
         return
      end if
      if (s%static_splits < 0 .or. s%static_splits > 20) then
         errmsg = 'solver:static_splits = '//str(s%static_splits)//' must be between 0 and 20'
         return
      end if
      if (s%method == 'static' .and. s%compare_static) then
         errmsg = "solver:compare_static = .true. compares an explicit run with the static solution; "// &
                  "it has no meaning with method = 'static'"
         return
      end if
      s%convergence_test = lower(s%convergence_test)
      if (.not. any(s%convergence_test == [character(len=8) :: 'auto', 'on', 'off'])) then
         errmsg = "solver:convergence_test = '"//trim(s%convergence_test)//"' is not one of 'auto', 'on', 'off'"
         return
      end if
      bad = .false.
   end function solver_cfg_validate

   !> The group's effective values as deck text.
   function solver_cfg_echo(s) result(text)
      type(solver_cfg_t), intent(in) :: s
      character(len=:), allocatable :: text
      character(len=1), parameter :: nl = new_line('a')
      text = '&solver'//nl//kv('dt', str(s%dt))//kv('dt_factor', str(s%dt_factor))// &
             kv('allow_unstable', str(s%allow_unstable))
      if (s%t_ramp /= unset) text = text//kv('t_ramp', str(s%t_ramp))
      text = text//kv('t_end', str(s%t_end))//kv('max_steps', str(s%max_steps))// &
             kv('damping', quoted(s%damping))//kv('alpha', str(s%alpha))// &
             kv('damping_interval', str(s%damping_interval))// &
             kv('tol_residual', str(s%tol_residual))//kv('tol_kinetic', str(s%tol_kinetic))// &
             kv('check_interval', str(s%check_interval))// &
             kv('power_iterations', str(s%power_iterations))//kv('dt_limit', quoted(s%dt_limit))// &
             kv('mass_scaling', str(s%mass_scaling))//kv('method', quoted(s%method))// &
             kv('static_increments', str(s%static_increments))//kv('compare_static', str(s%compare_static))// &
             kv('static_iterations', str(s%static_iterations))//kv('static_splits', str(s%static_splits))// &
             kv('convergence_test', quoted(s%convergence_test))//'/'//nl
   end function solver_cfg_echo
end module contact2d_deck_solver
