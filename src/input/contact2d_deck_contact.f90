module contact2d_deck_contact
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower
   use contact2d_checks, only: check_finite
   use contact2d_deck_syntax, only: unset, max_points, line_len, override_t, read_failed, too_long, &
                                    place_problem, place_text, range_text, kv, quoted, reals, upper2, &
                                    assignment_t, split_assignments, assigned_names, syntax_only
   use contact2d_friction_input, only: friction_input_t, friction_input_box_t
   use contact2d_friction_frictionless_input, only: frictionless_input_t
   use contact2d_friction_coulomb_input, only: coulomb_input_t, coulomb_names
   use contact2d_friction_tresca_input, only: tresca_input_t, tresca_names
   use contact2d_obstacle_input, only: obstacle_input_t, obstacle_input_box_t
   use contact2d_obstacle_plane_input, only: plane_input_t, plane_names
   use contact2d_obstacle_circle_input, only: circle_input_t, circle_names
   use contact2d_obstacle_motion_input, only: motion_input_t, motion_names
   implicit none
   private
   public :: contact_cfg_t, contact_variables, contact_cfg_read, contact_cfg_not_finite
   public :: contact_cfg_validate, contact_cfg_echo, contact_cfg_publish, friction_registry, friction_law_names
   public :: obstacle_registry, obstacle_shape_names, contact_default_name, contact_name_refused

   !> The obstacle shapes' variables, for the did-you-mean (a shape's names: its _input module).
   character(len=*), parameter :: obstacle_variables = plane_names//' '//circle_names

   !> The friction laws' variables, for the did-you-mean (a law's names: its _input module).
   character(len=*), parameter :: friction_variables = tresca_names//' '//coulomb_names

   !> The variables of &contact (the group's own, the obstacles' and the friction laws'), for
   !> the did-you-mean of a misspelled name.
   character(len=*), parameter :: contact_variables = &
      'name edge boundary xmin xmax ymin ymax obstacle master '//obstacle_variables//' '//motion_names//' '// &
      'origin direction multiplier friction '//friction_variables//' method penalty_stiffness'

   !> &contact: a candidate boundary against a rigid obstacle (SPEC section 3); one group per
   !> contact pair (docs/deck.md &contact).
   type :: contact_cfg_t
      logical :: present = .false.                 !< derived: the deck has a &contact group
      !> the pair's name (output groups, messages); '' until validated: then 'contact' for the
      !> first group, 'contact_<k>' for the k-th (contact_default_name)
      character(len=32) :: name = ''
      character(len=16) :: edge = ''               !< candidate side (built-in mesh)
      character(len=64) :: boundary = ''           !< candidate Gmsh physical curve (instead of edge)
      !> a name of obstacle_registry; '' until validated, then 'plane' unless master is given
      character(len=8) :: obstacle = ''
      !> the master side as another body's boundary: a Gmsh physical curve (instead of an
      !> obstacle; node-to-segment contact between bodies, docs/geometry.md "Two bodies")
      character(len=64) :: master = ''
      real(wp) :: xmin = -unset, xmax = unset      !< x range of the candidate boundary [mm]
      real(wp) :: ymin = -unset, ymax = unset      !< y range of the candidate boundary [mm]
      real(wp) :: origin(2) = [unset, unset]       !< point O of the abscissa; default: first node
      character(len=4) :: direction = 'ccw'        !< abscissa runs 'ccw' or 'cw' along the boundary
      character(len=4) :: multiplier = 'P1'        !< 'P1' | 'P0'
      character(len=16) :: friction = 'frictionless'  !< a name of friction_registry
      character(len=8) :: method = 'lagrange'      !< 'lagrange' | 'penalty'
      real(wp) :: penalty_stiffness = 0            !< k_p per unit length [MPa/mm], method='penalty'
      !> every shape's variables as read (obstacle_registry's order): a shape's variables given
      !> with another shape are refused by that shape's module, so all are read and checked
      type(obstacle_input_box_t), allocatable :: shapes(:)
      !> the chosen shape's input (contact:obstacle), set once the deck is valid
      !> (contact_cfg_publish); the model makes the obstacle from it (obstacle_input_t%make)
      class(obstacle_input_t), allocatable :: shape
      !> the obstacle's prescribed motion and the contact geometry (docs/geometry.md)
      type(motion_input_t) :: motion
      !> every law's variables as read (friction_registry's order): a law's variables given
      !> with another law are refused by that law's module, so all are read and checked
      type(friction_input_box_t), allocatable :: laws(:)
      !> the chosen law's input (contact:friction), set once the deck is valid
      !> (contact_cfg_publish); the model makes the law from it (friction_input_t%make)
      class(friction_input_t), allocatable :: law
   end type contact_cfg_t

contains

   !> The registry of friction laws: every law's input with its defaults, one line per law, in
   !> the order the messages and the documentation list them (docs/friction.md section 2).
   function friction_registry() result(laws)
      type(friction_input_box_t), allocatable :: laws(:)
      allocate (laws(3))
      allocate (laws(1)%input, source=frictionless_input_t())
      allocate (laws(2)%input, source=tresca_input_t())
      allocate (laws(3)%input, source=coulomb_input_t())
   end function friction_registry

   !> The registry's law names, quoted and comma-separated, for messages.
   function friction_law_names() result(text)
      character(len=:), allocatable :: text
      type(friction_input_box_t), allocatable :: laws(:)
      integer :: k
      laws = friction_registry()
      text = ''
      do k = 1, size(laws)
         if (k > 1) text = text//', '
         text = text//"'"//laws(k)%input%name()//"'"
      end do
   end function friction_law_names

   !> The registry of obstacle shapes: every shape's input with its defaults, one line per
   !> shape, in the order the messages and the documentation list them (docs/geometry.md).
   function obstacle_registry() result(shapes)
      type(obstacle_input_box_t), allocatable :: shapes(:)
      allocate (shapes(2))
      allocate (shapes(1)%input, source=plane_input_t())
      allocate (shapes(2)%input, source=circle_input_t())
   end function obstacle_registry

   !> The registry's shape names, quoted and comma-separated, for messages.
   function obstacle_shape_names() result(text)
      character(len=:), allocatable :: text
      type(obstacle_input_box_t), allocatable :: shapes(:)
      integer :: k
      shapes = obstacle_registry()
      text = ''
      do k = 1, size(shapes)
         if (k > 1) text = text//', '
         text = text//"'"//shapes(k)%input%name()//"'"
      end do
   end function obstacle_shape_names

   !> The group's laws and shapes as read so far (the registries' defaults before the first read).
   subroutine ensure_laws(c)
      type(contact_cfg_t), intent(inout) :: c
      if (.not. allocated(c%laws)) c%laws = friction_registry()
      if (.not. allocated(c%shapes)) c%shapes = obstacle_registry()
   end subroutine ensure_laws

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
      character(len=line_len) :: edge, friction, direction, multiplier, method, boundary, obstacle, master, pname
      character(len=:), allocatable :: name
      integer :: i, k, paren
      call ensure_laws(cfg)
      ! the group's own strings at full length while reading, so that an over-long value is
      ! refused (too_long), never cut
      edge = cfg%edge; friction = cfg%friction; direction = cfg%direction; multiplier = cfg%multiplier
      method = cfg%method; boundary = cfg%boundary; obstacle = cfg%obstacle; master = cfg%master; pname = cfg%name
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
      do k = 1, size(cfg%laws)
         if (cfg%laws(k)%input%too_long(where, stat, errmsg)) return
      end do
      if (too_long(where, 'method', method, len(cfg%method), stat, errmsg)) return
      if (too_long(where, 'boundary', boundary, len(cfg%boundary), stat, errmsg)) return
      if (too_long(where, 'obstacle', obstacle, len(cfg%obstacle), stat, errmsg)) return
      if (too_long(where, 'master', master, len(cfg%master), stat, errmsg)) return
      do k = 1, size(cfg%shapes)
         if (cfg%shapes(k)%input%too_long(where, stat, errmsg)) return
      end do
      if (cfg%motion%too_long(where, stat, errmsg)) return
      if (too_long(where, 'name', pname, len(cfg%name), stat, errmsg)) return
      cfg%edge = edge; cfg%friction = friction; cfg%direction = direction; cfg%multiplier = multiplier
      cfg%method = method; cfg%boundary = boundary; cfg%obstacle = obstacle; cfg%master = master; cfg%name = pname
   contains
      !> One assignment (namelist records) read by the module that claims the variable name.
      subroutine read_one(name, records, prefix)
         character(len=*), intent(in) :: name, records(:), prefix
         integer :: k
         if (cfg%motion%claims(name)) then
            call cfg%motion%read(records, prefix, contact_variables, stat, errmsg)
            return
         end if
         do k = 1, size(cfg%shapes)
            if (cfg%shapes(k)%input%claims(name)) then
               call cfg%shapes(k)%input%read(records, prefix, contact_variables, stat, errmsg)
               return
            end if
         end do
         do k = 1, size(cfg%laws)
            if (cfg%laws(k)%input%claims(name)) then
               call cfg%laws(k)%input%read(records, prefix, contact_variables, stat, errmsg)
               return
            end if
         end do
         call read_own(records, prefix)
      end subroutine read_one
      !> An assignment of the group's own variables (or of no known name: the runtime's refusal).
      subroutine read_own(records, prefix)
         character(len=*), intent(in) :: records(:), prefix
         real(wp) :: xmin, xmax, ymin, ymax, origin(2), penalty_stiffness
         integer :: ios
         character(len=256) :: msg
         character(len=line_len) :: name
         namelist /contact/ name, edge, boundary, xmin, xmax, ymin, ymax, obstacle, master, origin, direction, multiplier, &
            friction, method, penalty_stiffness
         xmin = cfg%xmin; xmax = cfg%xmax; ymin = cfg%ymin; ymax = cfg%ymax; origin = cfg%origin
         penalty_stiffness = cfg%penalty_stiffness
         name = pname
         read (records, nml=contact, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, contact_variables, prefix, stat, errmsg)) return
         pname = name
         cfg%xmin = xmin; cfg%xmax = xmax; cfg%ymin = ymin; cfg%ymax = ymax; cfg%origin = origin
         cfg%penalty_stiffness = penalty_stiffness
      end subroutine read_own
   end subroutine contact_cfg_read

   !> check_finite on every real of the group, the obstacles' and the laws' included; true if
   !> one is bad.
   logical function contact_cfg_not_finite(c, errmsg) result(bad)
      type(contact_cfg_t), intent(in) :: c
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: k
      bad = .true.
      if (check_finite('contact:xmin', c%xmin, errmsg)) return
      if (check_finite('contact:xmax', c%xmax, errmsg)) return
      if (check_finite('contact:ymin', c%ymin, errmsg)) return
      if (check_finite('contact:ymax', c%ymax, errmsg)) return
      if (allocated(c%shapes)) then
         do k = 1, size(c%shapes)
            if (c%shapes(k)%input%not_finite(errmsg)) return
         end do
      end if
      if (c%motion%not_finite(errmsg)) return
      if (check_finite('contact:origin', c%origin, errmsg)) return
      if (allocated(c%laws)) then
         do k = 1, size(c%laws)
            if (c%laws(k)%input%not_finite(errmsg)) return
         end do
      end if
      if (check_finite('contact:penalty_stiffness', c%penalty_stiffness, errmsg)) return
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
      if (len_trim(c%master) > 0) then
         if (master_refused(c, errmsg)) return
      else
         if (len_trim(c%obstacle) == 0) c%obstacle = 'plane'
         if (obstacle_refused(c, errmsg)) return
         if (c%motion%validate(trim(c%obstacle), errmsg)) return
      end if
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
      ! two bodies: the node-to-segment operator has P1 multipliers, no friction yet, and the
      ! forward-increment Lagrange method only (docs/geometry.md "Two bodies")
      if (len_trim(c%master) > 0) then
         if (c%multiplier /= 'P1') then
            errmsg = "contact:multiplier = '"//trim(c%multiplier)//"' with master = '"//trim(c%master)// &
                     "': contact between two bodies has P1 multipliers only (node to segment)"
            return
         end if
         if (c%friction /= 'frictionless') then
            errmsg = "contact:friction = '"//trim(c%friction)//"' with master = '"//trim(c%master)// &
                     "': contact between two bodies is frictionless only (so far)"
            return
         end if
         if (c%method /= 'lagrange') then
            errmsg = "contact:method = '"//trim(c%method)//"' with master = '"//trim(c%master)// &
                     "': contact between two bodies has the Lagrange multipliers only"
            return
         end if
      end if
      bad = .false.
   end function contact_cfg_validate

   !> The master side as another body's boundary (contact:master): the slave side is a physical
   !> curve (boundary), not the master itself, and no obstacle, obstacle variable or obstacle
   !> motion is given; the geometry is the current one (finite sliding). True if refused.
   logical function master_refused(c, errmsg) result(bad)
      type(contact_cfg_t), intent(inout) :: c
      character(len=:), allocatable, intent(inout) :: errmsg
      character(len=:), allocatable :: why
      integer :: k
      bad = .true.
      call ensure_laws(c)
      if (len_trim(c%obstacle) > 0) then
         errmsg = "contact: obstacle = '"//trim(c%obstacle)//"' and master = '"//trim(c%master)// &
                  "' are both given; the master side is a rigid obstacle or another body's boundary, not both"
         return
      end if
      why = ''
      do k = 1, size(c%shapes)
         if (c%shapes(k)%input%unused('', why)) then
            errmsg = "contact: master = '"//trim(c%master)//"' is given but so are an obstacle's variables ("// &
                     obstacle_variables//"); the master side is a rigid obstacle or another body's boundary, not both"
            return
         end if
      end do
      if (len_trim(c%boundary) == 0) then
         errmsg = "contact: master = '"//trim(c%master)//"' needs the slave side as boundary = '<physical "// &
                  "curve>' of another body (edge = '"//trim(c%edge)//"' is on the built-in mesh, one body)"
         return
      end if
      if (trim(c%master) == trim(c%boundary)) then
         errmsg = "contact: master = '"//trim(c%master)//"' is the slave boundary itself; a boundary cannot "// &
                  'be paired with itself'
         return
      end if
      if (lower(c%motion%geometry) == 'initial') then
         errmsg = "contact: master = '"//trim(c%master)//"' takes no geometry = 'initial': two bodies are in "// &
                  'contact in the current configuration (finite sliding)'
         return
      end if
      if (c%motion%validate('', errmsg)) return
      if (c%motion%moving()) then
         errmsg = "contact: master = '"//trim(c%master)//"' takes no obstacle motion (obstacle_motion_times, "// &
                  "obstacle_velocity_x, ...): the master side is another body"
         return
      end if
      c%motion%geometry = 'current'
      bad = .false.
   end function master_refused

   !> The obstacle (its shape and that shape's variables, the other shapes' left unset), the
   !> origin of the abscissa and the candidate range; fills the plane's defaults. True if refused.
   logical function obstacle_refused(c, errmsg) result(bad)
      type(contact_cfg_t), intent(inout) :: c
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: k, chosen
      bad = .true.
      call ensure_laws(c)
      c%obstacle = lower(c%obstacle)
      chosen = chosen_shape(c)
      if (chosen == 0) then
         errmsg = "contact:obstacle = '"//trim(c%obstacle)//"' is not one of "//obstacle_shape_names()
         return
      end if
      do k = 1, size(c%shapes)
         if (c%shapes(k)%input%prepare(errmsg)) return
      end do
      if (count(c%origin == unset) == 1) then
         errmsg = 'contact:origin = '//str(minval(c%origin))// &
                  ' has one component; give both, origin = x, y (mm)'
         return
      end if
      if (c%shapes(chosen)%input%validate_chosen(errmsg)) return
      do k = 1, size(c%shapes)
         if (c%shapes(k)%input%unused(trim(c%obstacle), errmsg)) return
      end do
      do k = 1, size(c%shapes)
         if (c%shapes(k)%input%complete(errmsg)) return
      end do
      if (.not. (c%xmin <= c%xmax .and. c%ymin <= c%ymax)) then
         errmsg = 'contact: the range needs xmin <= xmax and ymin <= ymax'
         return
      end if
      do k = 1, size(c%shapes)
         if (c%shapes(k)%input%validate_always(errmsg)) return
      end do
      bad = .false.
   end function obstacle_refused

   !> The friction law and the variables of each law (docs/friction.md): a law's variables
   !> given with another law are refused by that law's module. True if refused.
   logical function friction_refused(c, errmsg) result(bad)
      type(contact_cfg_t), intent(inout) :: c
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: k
      bad = .true.
      call ensure_laws(c)
      c%friction = lower(c%friction)
      if (chosen_law(c) == 0) then
         errmsg = "contact:friction = '"//trim(c%friction)//"' is not one of "//friction_law_names()
         return
      end if
      do k = 1, size(c%laws)
         if (c%laws(k)%input%derive(errmsg)) return
      end do
      ! the unused variables, then each law's checks, the later laws first (the order of the
      ! messages of a deck with several faults)
      do k = size(c%laws), 1, -1
         if (c%laws(k)%input%unused(trim(c%friction), errmsg)) return
      end do
      do k = size(c%laws), 1, -1
         if (c%laws(k)%input%validate(trim(c%friction), errmsg)) return
      end do
      bad = .false.
   end function friction_refused

   !> The index of the chosen law (contact:friction) in c%laws; 0 for a name not registered.
   integer function chosen_law(c) result(k)
      type(contact_cfg_t), intent(in) :: c
      do k = 1, size(c%laws)
         if (c%laws(k)%input%name() == trim(c%friction)) return
      end do
      k = 0
   end function chosen_law

   !> The index of the chosen shape (contact:obstacle) in c%shapes; 0 for a name not registered.
   integer function chosen_shape(c) result(k)
      type(contact_cfg_t), intent(in) :: c
      do k = 1, size(c%shapes)
         if (c%shapes(k)%input%name() == trim(c%obstacle)) return
      end do
      k = 0
   end function chosen_shape

   !> The name of the k-th contact pair when its group gives none: 'contact' for the first (a
   !> deck with one pair keeps today's output names), 'contact_<k>' for the others.
   function contact_default_name(k) result(name)
      integer, intent(in) :: k
      character(len=:), allocatable :: name
      if (k == 1) then
         name = 'contact'
      else
         name = 'contact_'//str(k)
      end if
   end function contact_default_name

   !> A pair's name is a word of letters, digits, '_' and '-' starting with a letter (it names
   !> an HDF5 group and history series, docs/output.md). label: 'contact' or 'contact#k'. True
   !> if refused, with the message.
   logical function contact_name_refused(name, label, errmsg) result(bad)
      character(len=*), intent(in) :: name, label
      character(len=:), allocatable, intent(inout) :: errmsg
      character(len=*), parameter :: letters = 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ'
      bad = .false.
      if (len_trim(name) == 0) return
      if (verify(trim(name), letters//'0123456789_-') /= 0 .or. scan(name(1:1), letters) /= 1) then
         bad = .true.
         errmsg = label//":name = '"//trim(name)//"' is not a word of letters, digits, '_' and '-' "// &
                  'starting with a letter'
      end if
   end function contact_name_refused

   !> Keep the chosen shape's input (c%shape) and the chosen law's input (c%law).
   subroutine contact_cfg_publish(c)
      type(contact_cfg_t), intent(inout) :: c
      integer :: k
      call ensure_laws(c)
      if (allocated(c%law)) deallocate (c%law)
      k = chosen_law(c)
      if (k > 0) allocate (c%law, source=c%laws(k)%input)
      if (allocated(c%shape)) deallocate (c%shape)
      k = chosen_shape(c)
      if (k > 0) allocate (c%shape, source=c%shapes(k)%input)
   end subroutine contact_cfg_publish

   !> The group's effective values as deck text (only the variables of the chosen obstacle,
   !> friction law and method).
   function contact_cfg_echo(c) result(text)
      type(contact_cfg_t), intent(in) :: c
      character(len=:), allocatable :: text
      character(len=1), parameter :: nl = new_line('a')
      integer :: k
      text = '&contact'//nl
      ! the one-pair default name is not echoed (a deck with one pair echoes as before)
      if (trim(c%name) /= 'contact') text = text//kv('name', quoted(c%name))
      text = text//place_text(c%edge, c%boundary)//range_text(c%xmin, c%xmax, c%ymin, c%ymax)
      if (len_trim(c%master) > 0) then
         text = text//kv('master', quoted(c%master))
      else
         text = text//kv('obstacle', quoted(c%obstacle))
         k = chosen_shape(c)
         if (k > 0) text = text//c%shapes(k)%input%echo()
         text = text//c%motion%echo()
      end if
      if (all(c%origin /= unset)) text = text//kv('origin', reals(c%origin))
      text = text//kv('direction', quoted(c%direction))//kv('multiplier', quoted(c%multiplier))// &
             kv('friction', quoted(c%friction))
      k = chosen_law(c)
      if (k > 0) text = text//c%laws(k)%input%echo()
      do k = 1, size(c%laws)
         text = text//c%laws(k)%input%echo_always()
      end do
      text = text//kv('method', quoted(c%method))
      if (c%method == 'penalty') text = text//kv('penalty_stiffness', str(c%penalty_stiffness))
      text = text//'/'//nl
   end function contact_cfg_echo
end module contact2d_deck_contact
