!> &contact: a candidate boundary against a rigid obstacle (SPEC section 3, docs/deck.md,
!> docs/friction.md, docs/geometry.md): its variables with their defaults, its namelist read,
!> its validation and its echo lines. The check against the engine (penalty with the static
!> engine) is a cross-group check of the deck core.
module contact2d_deck_contact
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower
   use contact2d_checks, only: check_finite
   use contact2d_deck_syntax, only: unset, max_points, line_len, override_t, read_failed, too_long, &
                                    place_problem, place_text, range_text, kv, quoted, reals, upper2
   implicit none
   private
   public :: contact_cfg_t, contact_variables, contact_cfg_read, contact_cfg_not_finite
   public :: contact_cfg_validate, contact_cfg_echo

   !> The variables of &contact, as the namelist in contact_cfg_read declares them.
   character(len=*), parameter :: contact_variables = &
      'edge boundary xmin xmax ymin ymax obstacle obstacle_point obstacle_normal obstacle_center '// &
      'obstacle_radius obstacle_side origin direction multiplier friction friction_coefficient threshold '// &
      'threshold_abscissa threshold_values tresca_scope method penalty_stiffness'
   !> The plane obstacle y = 0 with its normal +y when the deck gives no obstacle_point/normal.
   real(wp), parameter :: default_obstacle_point(2) = [0.0_wp, 0.0_wp], default_obstacle_normal(2) = [0.0_wp, 1.0_wp]

   !> &contact: a candidate boundary against a rigid straight obstacle (SPEC section 3).
   type :: contact_cfg_t
      logical :: present = .false.                 !< derived: the deck has a &contact group
      character(len=16) :: edge = ''               !< candidate side (built-in mesh)
      character(len=64) :: boundary = ''           !< candidate Gmsh physical curve (instead of edge)
      character(len=8) :: obstacle = 'plane'       !< 'plane' | 'circle'
      real(wp) :: obstacle_center(2) = [unset, unset]  !< circle centre [mm]
      real(wp) :: obstacle_radius = unset          !< circle radius [mm], > 0
      character(len=8) :: obstacle_side = 'outside'  !< body 'outside' (indenter) | 'inside' (cavity)
      real(wp) :: xmin = -unset, xmax = unset      !< x range of the candidate boundary [mm]
      real(wp) :: ymin = -unset, ymax = unset      !< y range of the candidate boundary [mm]
      !> a point P of the obstacle line [mm]; plane only (not given: default_obstacle_point)
      real(wp) :: obstacle_point(2) = [unset, unset]
      !> unit normal nu, obstacle -> body; plane only (not given: default_obstacle_normal)
      real(wp) :: obstacle_normal(2) = [unset, unset]
      real(wp) :: origin(2) = [unset, unset]       !< point O of the abscissa; default: first node
      character(len=4) :: direction = 'ccw'        !< abscissa runs 'ccw' or 'cw' along the boundary
      character(len=4) :: multiplier = 'P1'        !< 'P1' | 'P0'
      character(len=16) :: friction = 'frictionless'  !< 'frictionless' | 'tresca' | 'coulomb'
      real(wp) :: friction_coefficient = 0         !< Coulomb mu [-], >= 0 (docs/friction.md)
      real(wp) :: threshold = 0                    !< uniform Tresca threshold s [MPa], >= 0
      real(wp) :: threshold_abscissa(max_points) = unset  !< abscissae of a piecewise-linear s [mm]
      real(wp) :: threshold_values(max_points) = unset    !< s at those abscissae [MPa]
      integer :: npoints = 0                       !< derived: points of the s profile (0: uniform)
      character(len=8) :: tresca_scope = 'all'     !< 'all' (as in the paper) | 'contact'
      character(len=8) :: method = 'lagrange'      !< 'lagrange' | 'penalty'
      real(wp) :: penalty_stiffness = 0            !< k_p per unit length [MPa/mm], method='penalty'
   end type contact_cfg_t

contains

   !> Read the group's lines blk, then the --set overrides ovr.
   subroutine contact_cfg_read(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(contact_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      character(len=line_len) :: edge, friction, direction, multiplier, tresca_scope, method
      character(len=line_len) :: boundary, obstacle, obstacle_side
      real(wp) :: obstacle_center(2), obstacle_radius
      real(wp) :: xmin, xmax, ymin, ymax, obstacle_point(2), obstacle_normal(2), origin(2)
      real(wp) :: threshold, threshold_abscissa(max_points), threshold_values(max_points)
      real(wp) :: penalty_stiffness, friction_coefficient
      integer :: ios, i
      character(len=256) :: msg
      namelist /contact/ edge, xmin, xmax, ymin, ymax, obstacle_point, obstacle_normal, origin, &
         direction, multiplier, friction, threshold, threshold_abscissa, threshold_values, &
         tresca_scope, method, penalty_stiffness, friction_coefficient, boundary, obstacle, &
         obstacle_center, obstacle_radius, obstacle_side
      boundary = cfg%boundary; obstacle = cfg%obstacle; obstacle_center = cfg%obstacle_center
      obstacle_radius = cfg%obstacle_radius; obstacle_side = cfg%obstacle_side
      edge = cfg%edge; xmin = cfg%xmin; xmax = cfg%xmax; ymin = cfg%ymin; ymax = cfg%ymax
      obstacle_point = cfg%obstacle_point; obstacle_normal = cfg%obstacle_normal
      origin = cfg%origin; direction = cfg%direction; multiplier = cfg%multiplier
      friction = cfg%friction; threshold = cfg%threshold
      threshold_abscissa = cfg%threshold_abscissa; threshold_values = cfg%threshold_values
      tresca_scope = cfg%tresca_scope; method = cfg%method
      penalty_stiffness = cfg%penalty_stiffness
      friction_coefficient = cfg%friction_coefficient
      read (blk, nml=contact, iostat=ios, iomsg=msg)
      if (read_failed(ios, msg, contact_variables, where, stat, errmsg)) return
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=contact, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, contact_variables, "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      if (too_long(where, 'edge', edge, len(cfg%edge), stat, errmsg)) return
      if (too_long(where, 'friction', friction, len(cfg%friction), stat, errmsg)) return
      if (too_long(where, 'direction', direction, len(cfg%direction), stat, errmsg)) return
      if (too_long(where, 'multiplier', multiplier, len(cfg%multiplier), stat, errmsg)) return
      if (too_long(where, 'tresca_scope', tresca_scope, len(cfg%tresca_scope), stat, errmsg)) return
      if (too_long(where, 'method', method, len(cfg%method), stat, errmsg)) return
      if (too_long(where, 'boundary', boundary, len(cfg%boundary), stat, errmsg)) return
      if (too_long(where, 'obstacle', obstacle, len(cfg%obstacle), stat, errmsg)) return
      if (too_long(where, 'obstacle_side', obstacle_side, len(cfg%obstacle_side), stat, errmsg)) return
      cfg%boundary = boundary; cfg%obstacle = obstacle; cfg%obstacle_center = obstacle_center
      cfg%obstacle_radius = obstacle_radius; cfg%obstacle_side = obstacle_side
      cfg%edge = edge; cfg%xmin = xmin; cfg%xmax = xmax; cfg%ymin = ymin; cfg%ymax = ymax
      cfg%obstacle_point = obstacle_point; cfg%obstacle_normal = obstacle_normal
      cfg%origin = origin; cfg%direction = direction; cfg%multiplier = multiplier
      cfg%friction = friction; cfg%threshold = threshold
      cfg%threshold_abscissa = threshold_abscissa; cfg%threshold_values = threshold_values
      cfg%tresca_scope = tresca_scope; cfg%method = method
      cfg%penalty_stiffness = penalty_stiffness
      cfg%friction_coefficient = friction_coefficient
   end subroutine contact_cfg_read

   !> check_finite on every real of the group; true if one is bad.
   logical function contact_cfg_not_finite(c, errmsg) result(bad)
      type(contact_cfg_t), intent(in) :: c
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('contact:xmin', c%xmin, errmsg)) return
      if (check_finite('contact:xmax', c%xmax, errmsg)) return
      if (check_finite('contact:ymin', c%ymin, errmsg)) return
      if (check_finite('contact:ymax', c%ymax, errmsg)) return
      if (check_finite('contact:obstacle_point', c%obstacle_point, errmsg)) return
      if (check_finite('contact:obstacle_normal', c%obstacle_normal, errmsg)) return
      if (check_finite('contact:origin', c%origin, errmsg)) return
      if (check_finite('contact:threshold', c%threshold, errmsg)) return
      if (check_finite('contact:threshold_abscissa', c%threshold_abscissa, errmsg)) return
      if (check_finite('contact:threshold_values', c%threshold_values, errmsg)) return
      if (check_finite('contact:penalty_stiffness', c%penalty_stiffness, errmsg)) return
      if (check_finite('contact:friction_coefficient', c%friction_coefficient, errmsg)) return
      if (check_finite('contact:obstacle_center', c%obstacle_center, errmsg)) return
      if (check_finite('contact:obstacle_radius', c%obstacle_radius, errmsg)) return
      bad = .false.
   end function contact_cfg_not_finite

   !> Validate the group (choices lower-cased, the plane's defaults filled, npoints derived);
   !> mesh_file is mesh:file ('' for the built-in rectangle). True if a value is refused.
   logical function contact_cfg_validate(c, mesh_file, errmsg) result(bad)
      type(contact_cfg_t), intent(inout) :: c
      character(len=*), intent(in) :: mesh_file
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      errmsg = place_problem('contact', ':', c%edge, c%boundary, mesh_file)
      if (len(errmsg) > 0) return
      c%edge = lower(c%edge)
      if (obstacle_refused(c, errmsg)) return
      c%direction = lower(c%direction)
      if (.not. any(c%direction == [character(len=4) :: 'ccw', 'cw'])) then
         errmsg = "contact:direction = '"//trim(c%direction)//"' is not one of 'ccw', 'cw'"
         return
      end if
      c%multiplier = upper2(c%multiplier)
      if (.not. any(c%multiplier == [character(len=4) :: 'P1', 'P0'])) then
         errmsg = "contact:multiplier = '"//trim(c%multiplier)//"' is not one of 'P1', 'P0'"
         return
      end if
      if (friction_refused(c, errmsg)) return
      c%method = lower(c%method)
      if (.not. any(c%method == [character(len=8) :: 'lagrange', 'penalty'])) then
         errmsg = "contact:method = '"//trim(c%method)//"' is not one of 'lagrange', 'penalty'"
         return
      end if
      if (c%method == 'penalty' .and. .not. c%penalty_stiffness > 0) then
         errmsg = "contact:method = 'penalty' needs penalty_stiffness > 0 (MPa/mm), got "// &
                  str(c%penalty_stiffness)
         return
      end if
      if (c%method == 'lagrange' .and. c%penalty_stiffness /= 0) then
         errmsg = "contact:penalty_stiffness is set but method = 'lagrange' ignores it"
         return
      end if
      bad = .false.
   end function contact_cfg_validate

   !> The obstacle (its shape and the variables of that shape), the origin of the abscissa and
   !> the candidate range; fills the plane's defaults. True if a value is refused.
   logical function obstacle_refused(c, errmsg) result(bad)
      type(contact_cfg_t), intent(inout) :: c
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: norm
      bad = .true.
      c%obstacle = lower(c%obstacle)
      if (.not. any(c%obstacle == [character(len=8) :: 'plane', 'circle'])) then
         errmsg = "contact:obstacle = '"//trim(c%obstacle)//"' is not one of 'plane', 'circle'"
         return
      end if
      c%obstacle_side = lower(c%obstacle_side)
      if (.not. any(c%obstacle_side == [character(len=8) :: 'outside', 'inside'])) then
         errmsg = "contact:obstacle_side = '"//trim(c%obstacle_side)//"' is not one of 'outside', 'inside'"
         return
      end if
      if (count(c%origin == unset) == 1) then
         errmsg = 'contact:origin = '//str(minval(c%origin))// &
                  ' has one component; give both, origin = x, y (mm)'
         return
      end if
      if (c%obstacle == 'circle') then
         if (any(c%obstacle_center == unset)) then
            errmsg = "contact:obstacle = 'circle' needs obstacle_center (mm)"
            return
         end if
         if (c%obstacle_radius == unset) then
            errmsg = "contact:obstacle = 'circle' needs obstacle_radius (mm)"
            return
         end if
         if (.not. c%obstacle_radius > 0) then
            errmsg = 'contact:obstacle_radius = '//str(c%obstacle_radius)//' must be > 0 (mm)'
            return
         end if
         if (any(c%obstacle_point /= unset) .or. any(c%obstacle_normal /= unset)) then
            errmsg = "contact: obstacle_point and obstacle_normal are set but obstacle = 'circle' ignores "// &
                     'them (the circle is obstacle_center and obstacle_radius)'
            return
         end if
      else if (any(c%obstacle_center /= unset) .or. c%obstacle_radius /= unset) then
         errmsg = "contact:obstacle_center/obstacle_radius are set but obstacle = 'plane' ignores them; "// &
                  "use obstacle = 'circle'"
         return
      end if
      if (count(c%obstacle_point == unset) == 1 .or. count(c%obstacle_normal == unset) == 1) then
         errmsg = 'contact:obstacle_point and obstacle_normal take two components each (x, y)'
         return
      end if
      if (all(c%obstacle_point == unset)) c%obstacle_point = default_obstacle_point
      if (all(c%obstacle_normal == unset)) c%obstacle_normal = default_obstacle_normal
      if (.not. (c%xmin <= c%xmax .and. c%ymin <= c%ymax)) then
         errmsg = 'contact: the range needs xmin <= xmax and ymin <= ymax'
         return
      end if
      norm = norm2(c%obstacle_normal)
      if (abs(norm - 1) > 1.0e-6_wp) then
         errmsg = 'contact:obstacle_normal = '//str(c%obstacle_normal(1))//', '// &
                  str(c%obstacle_normal(2))//' must be a unit vector (length '//str(norm)//')'
         return
      end if
      bad = .false.
   end function obstacle_refused

   !> The friction law and its variables (docs/friction.md); fills npoints. True if refused.
   logical function friction_refused(c, errmsg) result(bad)
      type(contact_cfg_t), intent(inout) :: c
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: i
      bad = .true.
      c%friction = lower(c%friction)
      if (.not. any(c%friction == [character(len=16) :: 'frictionless', 'tresca', 'coulomb'])) then
         errmsg = "contact:friction = '"//trim(c%friction)//"' is not one of 'frictionless', 'tresca', 'coulomb'"
         return
      end if
      c%npoints = count(c%threshold_abscissa /= unset)
      if (count(c%threshold_values /= unset) /= c%npoints) then
         errmsg = 'contact: threshold_abscissa and threshold_values need the same number of entries'
         return
      end if
      ! Coulomb (docs/friction.md): a finite mu >= 0, and no Tresca settings with it. A zero
      ! mu or threshold is no friction law of its own, so it goes with any law: a --set
      ! cannot remove a variable, and `--set contact:friction='coulomb' --set
      ! contact:threshold=0` is how a Tresca deck is switched to Coulomb
      if (c%friction /= 'coulomb' .and. c%friction_coefficient /= 0) then
         errmsg = "contact:friction_coefficient is set but friction = '"//trim(c%friction)// &
                  "'; use friction = 'coulomb'"
         return
      end if
      if (c%friction /= 'tresca' .and. (c%threshold /= 0 .or. c%npoints > 0)) then
         errmsg = "contact: a threshold is given but friction = '"//trim(c%friction)//"'; use friction = 'tresca'"
         return
      end if
      if (c%npoints > 0 .and. c%threshold /= 0) then
         errmsg = 'contact: give either threshold or threshold_abscissa/threshold_values, not both'
         return
      end if
      if (.not. (c%friction_coefficient >= 0 .and. c%friction_coefficient <= huge(1.0_wp))) then
         errmsg = 'contact:friction_coefficient = '//str(c%friction_coefficient)//' must be finite and >= 0'
         return
      end if
      if (.not. c%threshold >= 0) then
         errmsg = 'contact:threshold = '//str(c%threshold)//' must be >= 0 (MPa)'
         return
      end if
      if (c%npoints > 0) then
         if (any(c%threshold_abscissa(c%npoints + 1:) /= unset) .or. &
             any(c%threshold_values(c%npoints + 1:) /= unset)) then
            errmsg = 'contact: threshold_abscissa/threshold_values must be given from the first entry on'
            return
         end if
         if (any(c%threshold_values(1:c%npoints) < 0)) then
            errmsg = 'contact:threshold_values must all be >= 0 (MPa)'
            return
         end if
         do i = 2, c%npoints
            if (.not. c%threshold_abscissa(i) > c%threshold_abscissa(i - 1)) then
               errmsg = 'contact:threshold_abscissa must increase strictly (entry '//str(i)//')'
               return
            end if
         end do
      end if
      c%tresca_scope = lower(c%tresca_scope)
      if (.not. any(c%tresca_scope == [character(len=8) :: 'all', 'contact'])) then
         errmsg = "contact:tresca_scope = '"//trim(c%tresca_scope)//"' is not one of 'all', 'contact'"
         return
      end if
      if (c%friction == 'coulomb' .and. c%tresca_scope /= 'all') then
         errmsg = "contact:tresca_scope = '"//trim(c%tresca_scope)//"' applies to Tresca only; "// &
                  "Coulomb friction acts where F_n > 0"
         return
      end if
      bad = .false.
   end function friction_refused

   !> The group's effective values as deck text (only the variables of the chosen obstacle,
   !> friction law and method).
   function contact_cfg_echo(c) result(text)
      type(contact_cfg_t), intent(in) :: c
      character(len=:), allocatable :: text
      character(len=1), parameter :: nl = new_line('a')
      text = '&contact'//nl//place_text(c%edge, c%boundary)//range_text(c%xmin, c%xmax, c%ymin, c%ymax)// &
             kv('obstacle', quoted(c%obstacle))
      if (c%obstacle == 'circle') then
         text = text//kv('obstacle_center', reals(c%obstacle_center))// &
                kv('obstacle_radius', str(c%obstacle_radius))//kv('obstacle_side', quoted(c%obstacle_side))
      else
         text = text//kv('obstacle_point', reals(c%obstacle_point))// &
                kv('obstacle_normal', reals(c%obstacle_normal))
      end if
      if (all(c%origin /= unset)) text = text//kv('origin', reals(c%origin))
      text = text//kv('direction', quoted(c%direction))//kv('multiplier', quoted(c%multiplier))// &
             kv('friction', quoted(c%friction))
      if (c%friction == 'coulomb') then
         text = text//kv('friction_coefficient', str(c%friction_coefficient))
      else if (c%friction /= 'tresca') then
         continue   ! threshold is refused with the other laws
      else if (c%npoints > 0) then
         text = text//kv('threshold_abscissa', reals(c%threshold_abscissa(1:c%npoints)))// &
                kv('threshold_values', reals(c%threshold_values(1:c%npoints)))
      else
         text = text//kv('threshold', str(c%threshold))
      end if
      text = text//kv('tresca_scope', quoted(c%tresca_scope))//kv('method', quoted(c%method))
      if (c%method == 'penalty') text = text//kv('penalty_stiffness', str(c%penalty_stiffness))
      text = text//'/'//nl
   end function contact_cfg_echo
end module contact2d_deck_contact
