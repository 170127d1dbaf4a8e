!> The deck variables of the obstacle's prescribed motion and of the contact geometry
!> (docs/geometry.md "Moving obstacles", docs/deck.md &contact): `obstacle_velocity_x`,
!> `obstacle_velocity_y` [mm/s] and `obstacle_spin` [rad/s, counterclockwise about a circle's
!> centre], stage end values of load curves (contact2d_loadcurve, the style of &dirichlet's
!> values/times) sharing the stage end times `obstacle_motion_times` [s]; and `geometry`
!> = 'initial' | 'current', where the contact step takes its gaps and normals from. Common to
!> every obstacle shape: the &contact reader (contact2d_deck_contact) routes the assignments of
!> these names here; the obstacle made by the shape's input gets the motion (apply).
module contact2d_obstacle_motion_input
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower
   use contact2d_checks, only: check_finite
   use contact2d_obstacle, only: obstacle_t
   use contact2d_deck_syntax, only: unset, max_stages, line_len, read_failed, too_long, kv, quoted, reals
   implicit none
   private
   public :: motion_input_t, motion_names

   !> The &contact variables of the motion and the geometry (blank-separated).
   character(len=*), parameter :: motion_names = &
      'obstacle_velocity_x obstacle_velocity_y obstacle_spin obstacle_motion_times geometry'
   !> Longest accepted geometry.
   integer, parameter :: geometry_len = 8

   !> The motion's and the geometry's deck variables; nstage and geometry derived by validate.
   type :: motion_input_t
      real(wp) :: obstacle_velocity_x(max_stages) = unset  !< vx at each stage end [mm/s]
      real(wp) :: obstacle_velocity_y(max_stages) = unset  !< vy at each stage end [mm/s]
      real(wp) :: obstacle_spin(max_stages) = unset        !< omega at each stage end [rad/s]
      real(wp) :: obstacle_motion_times(max_stages) = unset  !< stage end times [s]
      !> 'initial' | 'current' ('' not given: 'current' for a moving obstacle, else 'initial');
      !> held at line_len characters while read, so that an over-long value is refused
      character(len=line_len) :: geometry = ''
      integer :: nstage = 0   !< derived: stages of the motion (0: the obstacle is fixed)
   contains
      procedure :: claims => motion_claims
      procedure :: read => motion_read
      procedure :: too_long => motion_too_long
      procedure :: not_finite => motion_not_finite
      procedure :: validate => motion_validate
      procedure :: moving => motion_moving
      procedure :: current => motion_current
      procedure :: echo => motion_echo
      procedure :: apply => motion_apply
   end type motion_input_t

contains

   !> name (lower case, no subscript) is a variable of this module.
   logical function motion_claims(this, name) result(claims)
      class(motion_input_t), intent(in) :: this
      character(len=*), intent(in) :: name
      claims = index(' '//motion_names//' ', ' '//name//' ') > 0
   end function motion_claims

   !> Read one assignment (namelist records '&contact', text, '/'); variables: every &contact
   !> variable, for the did-you-mean of read_failed; where: the message's prefix.
   subroutine motion_read(this, records, where, variables, stat, errmsg)
      class(motion_input_t), intent(inout) :: this
      character(len=*), intent(in) :: records(:), where, variables
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp), dimension(max_stages) :: obstacle_velocity_x, obstacle_velocity_y, obstacle_spin, &
                                         obstacle_motion_times
      character(len=line_len) :: geometry
      integer :: ios
      character(len=256) :: msg
      namelist /contact/ obstacle_velocity_x, obstacle_velocity_y, obstacle_spin, obstacle_motion_times, geometry
      obstacle_velocity_x = this%obstacle_velocity_x; obstacle_velocity_y = this%obstacle_velocity_y
      obstacle_spin = this%obstacle_spin; obstacle_motion_times = this%obstacle_motion_times
      geometry = this%geometry
      read (records, nml=contact, iostat=ios, iomsg=msg)
      if (read_failed(ios, msg, variables, where, stat, errmsg)) return
      this%obstacle_velocity_x = obstacle_velocity_x; this%obstacle_velocity_y = obstacle_velocity_y
      this%obstacle_spin = obstacle_spin; this%obstacle_motion_times = obstacle_motion_times
      this%geometry = geometry
   end subroutine motion_read

   !> A geometry longer than geometry_len is refused; true if so.
   logical function motion_too_long(this, where, stat, errmsg) result(bad)
      class(motion_input_t), intent(in) :: this
      character(len=*), intent(in) :: where
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = too_long(where, 'geometry', this%geometry, geometry_len, stat, errmsg)
   end function motion_too_long

   !> check_finite on every real; true if one is bad.
   logical function motion_not_finite(this, errmsg) result(bad)
      class(motion_input_t), intent(in) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('contact:obstacle_velocity_x', this%obstacle_velocity_x, errmsg)) return
      if (check_finite('contact:obstacle_velocity_y', this%obstacle_velocity_y, errmsg)) return
      if (check_finite('contact:obstacle_spin', this%obstacle_spin, errmsg)) return
      if (check_finite('contact:obstacle_motion_times', this%obstacle_motion_times, errmsg)) return
      bad = .false.
   end function motion_not_finite

   !> The motion (every curve given has one value per stage, from the first entry on; the stage
   !> end times > 0 and strictly increasing; a spin needs a circle, the shape that turns about
   !> its centre) and the geometry (lower-cased; a moving obstacle needs 'current': its initial
   !> position says nothing of where it is later). obstacle: the chosen shape. True if refused.
   logical function motion_validate(this, obstacle, errmsg) result(bad)
      class(motion_input_t), intent(inout) :: this
      character(len=*), intent(in) :: obstacle
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: ntimes, j
      logical :: any_curve
      bad = .true.
      this%geometry = lower(this%geometry)
      if (.not. any(this%geometry == [character(len=geometry_len) :: '', 'initial', 'current'])) then
         errmsg = "contact:geometry = '"//trim(this%geometry)//"' is not one of 'initial', 'current'"
         return
      end if
      ntimes = count(this%obstacle_motion_times /= unset)
      if (any(this%obstacle_motion_times(ntimes + 1:) /= unset)) then
         errmsg = 'contact:obstacle_motion_times must be given from the first entry on'
         return
      end if
      any_curve = any(this%obstacle_velocity_x /= unset) .or. any(this%obstacle_velocity_y /= unset) .or. &
                  any(this%obstacle_spin /= unset)
      if (ntimes > 0 .and. .not. any_curve) then
         errmsg = 'contact:obstacle_motion_times is set but no obstacle_velocity_x, obstacle_velocity_y '// &
                  'or obstacle_spin uses it'
         return
      end if
      if (any_curve .and. ntimes == 0) then
         errmsg = 'contact: the obstacle motion needs obstacle_motion_times (the end time of each stage, s)'
         return
      end if
      if (curve_bad('obstacle_velocity_x', this%obstacle_velocity_x)) return
      if (curve_bad('obstacle_velocity_y', this%obstacle_velocity_y)) return
      if (curve_bad('obstacle_spin', this%obstacle_spin)) return
      if (ntimes > 0) then
         if (.not. this%obstacle_motion_times(1) > 0) then
            errmsg = 'contact:obstacle_motion_times(1) = '//str(this%obstacle_motion_times(1))//' must be > 0'
            return
         end if
         do j = 2, ntimes
            if (.not. this%obstacle_motion_times(j) > this%obstacle_motion_times(j - 1)) then
               errmsg = 'contact:obstacle_motion_times must increase strictly (obstacle_motion_times('// &
                        str(j)//') = '//str(this%obstacle_motion_times(j))//')'
               return
            end if
         end do
      end if
      if (any(this%obstacle_spin /= unset) .and. obstacle /= 'circle') then
         errmsg = "contact:obstacle_spin is set but obstacle = '"//obstacle// &
                  "' has no centre to turn about; a spin needs obstacle = 'circle'"
         return
      end if
      this%nstage = ntimes
      if (this%nstage > 0 .and. this%geometry == 'initial') then
         errmsg = "contact:geometry = 'initial' cannot follow a moving obstacle (obstacle_motion_times "// &
                  "is set): use geometry = 'current'"
         return
      end if
      if (this%geometry == '') this%geometry = merge('current', 'initial', this%nstage > 0)
      bad = .false.
   contains
      !> A curve given has exactly one value per stage time, from the first entry on.
      logical function curve_bad(name, values) result(bad)
         character(len=*), intent(in) :: name
         real(wp), intent(in) :: values(:)
         integer :: n
         n = count(values /= unset)
         bad = n > 0 .and. (n /= ntimes .or. any(values(n + 1:) /= unset))
         if (bad) errmsg = 'contact:'//name//' needs one value per obstacle_motion_times entry ('// &
                           str(ntimes)//'), from the first entry on; got '//str(n)
      end function curve_bad
   end function motion_validate

   !> The obstacle moves (after validate).
   logical function motion_moving(this)
      class(motion_input_t), intent(in) :: this
      motion_moving = this%nstage > 0
   end function motion_moving

   !> The contact step works in the current configuration (after validate).
   logical function motion_current(this)
      class(motion_input_t), intent(in) :: this
      motion_current = trim(this%geometry) == 'current'
   end function motion_current

   !> The echo lines: the motion when the obstacle moves, the geometry when it is 'current'
   !> (a fixed obstacle in the initial configuration echoes nothing, as before these variables).
   function motion_echo(this) result(text)
      class(motion_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      integer :: n
      text = ''
      n = this%nstage
      if (n > 0) then
         text = kv('obstacle_velocity_x', reals(curve(this%obstacle_velocity_x)))// &
                kv('obstacle_velocity_y', reals(curve(this%obstacle_velocity_y)))
         if (any(this%obstacle_spin /= unset)) text = text//kv('obstacle_spin', reals(curve(this%obstacle_spin)))
         text = text//kv('obstacle_motion_times', reals(this%obstacle_motion_times(1:n)))
      end if
      if (this%current()) text = text//kv('geometry', quoted(this%geometry))
   contains
      function curve(values) result(v)
         real(wp), intent(in) :: values(:)
         real(wp), allocatable :: v(:)
         v = merge(values(1:n), 0.0_wp, values(1:n) /= unset)
      end function curve
   end function motion_echo

   !> Give the obstacle its motion (a curve not given is zero); nothing for a fixed obstacle.
   subroutine motion_apply(this, obstacle)
      class(motion_input_t), intent(in) :: this
      class(obstacle_t), intent(inout) :: obstacle
      integer :: n
      n = this%nstage
      if (n == 0) return
      call obstacle%set_motion(this%obstacle_motion_times(1:n), curve(this%obstacle_velocity_x), &
                               curve(this%obstacle_velocity_y), curve(this%obstacle_spin))
   contains
      function curve(values) result(v)
         real(wp), intent(in) :: values(:)
         real(wp), allocatable :: v(:)
         v = merge(values(1:n), 0.0_wp, values(1:n) /= unset)
      end function curve
   end subroutine motion_apply
end module contact2d_obstacle_motion_input
