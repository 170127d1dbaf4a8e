module contact2d_deck_contact
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower
   use contact2d_checks, only: check_finite
   use contact2d_deck_syntax, only: unset, max_points, line_len, override_t, read_failed, too_long, &
                                    place_problem, place_text, range_text, kv, quoted, reals, upper2, &
                                    assignment_t, split_assignments, assigned_names, syntax_only
   use contact2d_friction_coulomb_input, only: coulomb_input_t, coulomb_names, coulomb_claims, coulomb_input_read, &
                                               coulomb_input_not_finite, coulomb_input_unused, &
                                               coulomb_input_validate, coulomb_input_echo
   use contact2d_friction_tresca_input, only: tresca_input_t, tresca_names, tresca_claims, tresca_input_read, &
                                              tresca_input_too_long, tresca_input_not_finite, tresca_input_count, &
                                              tresca_input_unused, tresca_input_validate, tresca_input_echo, &
                                              tresca_scope_echo
   use contact2d_obstacle_plane_input, only: plane_input_t, plane_names, plane_claims, plane_input_read, &
                                             plane_input_not_finite, plane_input_unused, plane_input_complete, &
                                             plane_input_validate, plane_input_echo
   use contact2d_obstacle_circle_input, only: circle_input_t, circle_names, circle_claims, circle_input_read, &
                                              circle_input_too_long, circle_input_not_finite, circle_input_side, &
                                              circle_input_unused, circle_input_validate, circle_input_echo
   implicit none
   private
   public :: contact_cfg_t, contact_variables, contact_cfg_read, contact_cfg_not_finite
   public :: contact_cfg_validate, contact_cfg_echo, contact_cfg_publish

   !> The variables of &contact (the group's own, the obstacles' and the friction laws'), for
   !> the did-you-mean of a misspelled name.
   character(len=*), parameter :: contact_variables = &
      'edge boundary xmin xmax ymin ymax obstacle '//plane_names//' '//circle_names//' '// &
      'origin direction multiplier friction '//coulomb_names//' '//tresca_names//' method penalty_stiffness'

   !> &contact: a candidate boundary against a rigid obstacle (SPEC section 3).
   type :: contact_cfg_t
      logical :: present = .false.                 !< derived: the deck has a &contact group
      character(len=16) :: edge = ''               !< candidate side (built-in mesh)
      character(len=64) :: boundary = ''           !< candidate Gmsh physical curve (instead of edge)
      character(len=8) :: obstacle = 'plane'       !< 'plane' | 'circle'
      real(wp) :: xmin = -unset, xmax = unset      !< x range of the candidate boundary [mm]
      real(wp) :: ymin = -unset, ymax = unset      !< y range of the candidate boundary [mm]
      real(wp) :: origin(2) = [unset, unset]       !< point O of the abscissa; default: first node
      character(len=4) :: direction = 'ccw'        !< abscissa runs 'ccw' or 'cw' along the boundary
      character(len=4) :: multiplier = 'P1'        !< 'P1' | 'P0'
      character(len=16) :: friction = 'frictionless'  !< 'frictionless' | 'tresca' | 'coulomb'
      character(len=8) :: method = 'lagrange'      !< 'lagrange' | 'penalty'
      real(wp) :: penalty_stiffness = 0            !< k_p per unit length [MPa/mm], method='penalty'
      type(plane_input_t) :: plane                 !< the plane obstacle's variables (their defaults)
      type(circle_input_t) :: circle               !< the circular obstacle's variables
      type(coulomb_input_t) :: coulomb             !< Coulomb friction's variables
      type(tresca_input_t) :: tresca               !< Tresca friction's variables
      !> The names the model reads, copied from the obstacles' and laws' own input once the deck
      !> is valid (contact2d_deck's validate calls contact_cfg_publish): their meaning, units
      !> and defaults are those of plane, circle, coulomb and tresca above.
      real(wp) :: obstacle_point(2), obstacle_normal(2), obstacle_center(2), obstacle_radius
      character(len=8) :: obstacle_side
      real(wp) :: friction_coefficient, threshold
      real(wp) :: threshold_abscissa(max_points), threshold_values(max_points)
      integer :: npoints
      character(len=8) :: tresca_scope
   end type contact_cfg_t

contains

   !> Read the group's lines blk, then the --set overrides ovr: each assignment, in the order
   !> of the text, by the module that claims its name (read_one).
   subroutine contact_cfg_read(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(contact_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      type(assignment_t), allocatable :: parts(:)
      character(len=line_len), allocatable :: names(:)
      character(len=line_len) :: edge, friction, direction, multiplier, method, boundary, obstacle
      character(len=:), allocatable :: name
      integer :: i, paren
      ! the group's own strings at full length while reading, so that an over-long value is
      ! refused (too_long), never cut
      edge = cfg%edge; friction = cfg%friction; direction = cfg%direction; multiplier = cfg%multiplier
      method = cfg%method; boundary = cfg%boundary; obstacle = cfg%obstacle
      parts = split_assignments(blk, 'contact')
      do i = 1, size(parts)
         call read_one(parts(i)%name, parts(i)%records, where)
         if (stat /= 0) return
      end do
      do i = 1, size(ovr)
         names = assigned_names(syntax_only(ovr(i)%assignment))
         name = ''
         if (size(names) > 0) then
            paren = scan(names(1)//'(', '(')
            name = trim(names(1)(1:paren - 1))
         end if
         ! pick (the deck core) made each override one record '&contact assignment /'
         call read_one(name, [ovr(i)%assignment], "--set '"//ovr(i)%spec//"': ")
         if (stat /= 0) return
      end do
      if (too_long(where, 'edge', edge, len(cfg%edge), stat, errmsg)) return
      if (too_long(where, 'friction', friction, len(cfg%friction), stat, errmsg)) return
      if (too_long(where, 'direction', direction, len(cfg%direction), stat, errmsg)) return
      if (too_long(where, 'multiplier', multiplier, len(cfg%multiplier), stat, errmsg)) return
      if (tresca_input_too_long(cfg%tresca, where, stat, errmsg)) return
      if (too_long(where, 'method', method, len(cfg%method), stat, errmsg)) return
      if (too_long(where, 'boundary', boundary, len(cfg%boundary), stat, errmsg)) return
      if (too_long(where, 'obstacle', obstacle, len(cfg%obstacle), stat, errmsg)) return
      if (circle_input_too_long(cfg%circle, where, stat, errmsg)) return
      cfg%edge = edge; cfg%friction = friction; cfg%direction = direction; cfg%multiplier = multiplier
      cfg%method = method; cfg%boundary = boundary; cfg%obstacle = obstacle
   contains
      !> One assignment (namelist records) read by the module that claims the variable name.
      subroutine read_one(name, records, prefix)
         character(len=*), intent(in) :: name, records(:), prefix
         if (plane_claims(name)) then
            call plane_input_read(records, prefix, contact_variables, cfg%plane, stat, errmsg)
         else if (circle_claims(name)) then
            call circle_input_read(records, prefix, contact_variables, cfg%circle, stat, errmsg)
         else if (coulomb_claims(name)) then
            call coulomb_input_read(records, prefix, contact_variables, cfg%coulomb, stat, errmsg)
         else if (tresca_claims(name)) then
            call tresca_input_read(records, prefix, contact_variables, cfg%tresca, stat, errmsg)
         else
            call read_own(records, prefix)
         end if
      end subroutine read_one
      !> An assignment of the group's own variables (or of no known name: the runtime's refusal).
      subroutine read_own(records, prefix)
         character(len=*), intent(in) :: records(:), prefix
         real(wp) :: xmin, xmax, ymin, ymax, origin(2), penalty_stiffness
         integer :: ios
         character(len=256) :: msg
         namelist /contact/ edge, boundary, xmin, xmax, ymin, ymax, obstacle, origin, direction, multiplier, &
            friction, method, penalty_stiffness
         xmin = cfg%xmin; xmax = cfg%xmax; ymin = cfg%ymin; ymax = cfg%ymax; origin = cfg%origin
         penalty_stiffness = cfg%penalty_stiffness
         read (records, nml=contact, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, contact_variables, prefix, stat, errmsg)) return
         cfg%xmin = xmin; cfg%xmax = xmax; cfg%ymin = ymin; cfg%ymax = ymax; cfg%origin = origin
         cfg%penalty_stiffness = penalty_stiffness
      end subroutine read_own
   end subroutine contact_cfg_read

   !> check_finite on every real of the group, the obstacles' and the laws' included; true if
   !> one is bad.
   logical function contact_cfg_not_finite(c, errmsg) result(bad)
      type(contact_cfg_t), intent(in) :: c
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('contact:xmin', c%xmin, errmsg)) return
      if (check_finite('contact:xmax', c%xmax, errmsg)) return
      if (check_finite('contact:ymin', c%ymin, errmsg)) return
      if (check_finite('contact:ymax', c%ymax, errmsg)) return
      if (plane_input_not_finite(c%plane, errmsg)) return
      if (check_finite('contact:origin', c%origin, errmsg)) return
      if (tresca_input_not_finite(c%tresca, errmsg)) return
      if (check_finite('contact:penalty_stiffness', c%penalty_stiffness, errmsg)) return
      if (coulomb_input_not_finite(c%coulomb, errmsg)) return
      if (circle_input_not_finite(c%circle, errmsg)) return
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

   !> The obstacle (its shape and that shape's variables, the other shapes' left unset), the
   !> origin of the abscissa and the candidate range; fills the plane's defaults. True if refused.
   logical function obstacle_refused(c, errmsg) result(bad)
      type(contact_cfg_t), intent(inout) :: c
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      c%obstacle = lower(c%obstacle)
      if (.not. any(c%obstacle == [character(len=8) :: 'plane', 'circle'])) then
         errmsg = "contact:obstacle = '"//trim(c%obstacle)//"' is not one of 'plane', 'circle'"
         return
      end if
      if (circle_input_side(c%circle, errmsg)) return
      if (count(c%origin == unset) == 1) then
         errmsg = 'contact:origin = '//str(minval(c%origin))// &
                  ' has one component; give both, origin = x, y (mm)'
         return
      end if
      if (c%obstacle == 'circle') then
         if (circle_input_validate(c%circle, errmsg)) return
      end if
      if (plane_input_unused(c%plane, c%obstacle, errmsg)) return
      if (circle_input_unused(c%circle, c%obstacle, errmsg)) return
      if (plane_input_complete(c%plane, errmsg)) return
      if (.not. (c%xmin <= c%xmax .and. c%ymin <= c%ymax)) then
         errmsg = 'contact: the range needs xmin <= xmax and ymin <= ymax'
         return
      end if
      if (plane_input_validate(c%plane, errmsg)) return
      bad = .false.
   end function obstacle_refused

   !> The friction law and the variables of each law (docs/friction.md): a law's variables
   !> given with another law are refused by that law's module. True if refused.
   logical function friction_refused(c, errmsg) result(bad)
      type(contact_cfg_t), intent(inout) :: c
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      c%friction = lower(c%friction)
      if (.not. any(c%friction == [character(len=16) :: 'frictionless', 'tresca', 'coulomb'])) then
         errmsg = "contact:friction = '"//trim(c%friction)//"' is not one of 'frictionless', 'tresca', 'coulomb'"
         return
      end if
      if (tresca_input_count(c%tresca, errmsg)) return
      if (coulomb_input_unused(c%coulomb, c%friction, errmsg)) return
      if (tresca_input_unused(c%tresca, c%friction, errmsg)) return
      if (coulomb_input_validate(c%coulomb, errmsg)) return
      if (tresca_input_validate(c%tresca, c%friction, errmsg)) return
      bad = .false.
   end function friction_refused

   !> Copy the obstacles' and laws' values into the names the model reads (contact_cfg_t).
   subroutine contact_cfg_publish(c)
      type(contact_cfg_t), intent(inout) :: c
      c%obstacle_point = c%plane%obstacle_point
      c%obstacle_normal = c%plane%obstacle_normal
      c%obstacle_center = c%circle%obstacle_center
      c%obstacle_radius = c%circle%obstacle_radius
      c%obstacle_side = c%circle%obstacle_side
      c%friction_coefficient = c%coulomb%friction_coefficient
      c%threshold = c%tresca%threshold
      c%threshold_abscissa = c%tresca%threshold_abscissa
      c%threshold_values = c%tresca%threshold_values
      c%npoints = c%tresca%npoints
      c%tresca_scope = c%tresca%tresca_scope
   end subroutine contact_cfg_publish

   !> The group's effective values as deck text (only the variables of the chosen obstacle,
   !> friction law and method).
   function contact_cfg_echo(c) result(text)
      type(contact_cfg_t), intent(in) :: c
      character(len=:), allocatable :: text
      character(len=1), parameter :: nl = new_line('a')
      text = '&contact'//nl//place_text(c%edge, c%boundary)//range_text(c%xmin, c%xmax, c%ymin, c%ymax)// &
             kv('obstacle', quoted(c%obstacle))
      if (c%obstacle == 'circle') then
         text = text//circle_input_echo(c%circle)
      else
         text = text//plane_input_echo(c%plane)
      end if
      if (all(c%origin /= unset)) text = text//kv('origin', reals(c%origin))
      text = text//kv('direction', quoted(c%direction))//kv('multiplier', quoted(c%multiplier))// &
             kv('friction', quoted(c%friction))
      if (c%friction == 'coulomb') then
         text = text//coulomb_input_echo(c%coulomb)
      else if (c%friction == 'tresca') then
         text = text//tresca_input_echo(c%tresca)
      end if
      text = text//tresca_scope_echo(c%tresca)//kv('method', quoted(c%method))
      if (c%method == 'penalty') text = text//kv('penalty_stiffness', str(c%penalty_stiffness))
      text = text//'/'//nl
   end function contact_cfg_echo
end module contact2d_deck_contact
