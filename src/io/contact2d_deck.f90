!> The input deck: Fortran namelist groups, their defaults (here and nowhere else), command-line
!> overrides, validation and the echo of the effective values (docs/deck.md documents every
!> variable).
!>
!> A deck is a text file of namelist groups. Text outside groups must be blank or a `!` comment.
!> Groups: &mesh, &material, &solver, &output, &contact and &initial once each, &dirichlet and &traction as
!> many times as needed. Each group is read from its own block with iostat/iomsg; a failure
!> names the deck line of the group and the runtime's message.
!>
!> Nothing is misread: lines are read whole and refused beyond line_len, '&end' and
!> nested groups are refused, a variable given twice in one group is refused, only regular files
!> up to max_deck_bytes are read. To add a
!> variable: a string is read into a local of length line_len and checked with too_long()
!> against its field's length; a real is added to any_not_finite() in validate() (it uses
!> check_finite of contact2d_checks, which must run before any comparison of the value), then
!> range-checked; derived quantities are checked in the model with check_positive. Every name
!> goes into group_variables (suggestions for misspellings), a logical also into logical_vars.
!> Before any of this, value_problem reads every value of the text (deck and --set): literals
!> beyond the double range or equal to the 'not given' marker are refused there, so a marker
!> left in a variable after the read always means "not given".
module contact2d_deck
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower, join, printable
   use contact2d_material, only: material_t, material_init
   use contact2d_mesh, only: mesh_max_elements
   use contact2d_checks, only: check_finite, check_range, max_magnitude
   use contact2d_sys, only: sys_path_info, sys_strerror, kind_missing, kind_file, kind_dangling, kind_names
   use, intrinsic :: iso_c_binding, only: c_long_long
   use, intrinsic :: ieee_exceptions, only: ieee_status_type, ieee_get_status, ieee_set_status, &
                                            ieee_set_halting_mode, ieee_usual
   implicit none
   private
   public :: deck_t, deck_read, deck_blame, mesh_cfg_t, material_cfg_t, edge_load_cfg_t, contact_cfg_t
   public :: solver_cfg_t, output_cfg_t, initial_cfg_t, unset, max_stages, max_points, edge_id, group_names
   public :: group_variables

   !> Marks a real variable the deck did not set.
   real(wp), parameter :: unset = huge(1.0_wp)
   !> Marks an integer variable the deck did not set.
   integer, parameter :: unset_int = -huge(1)
   !> Most stages of a load curve and most points of a threshold profile.
   integer, parameter :: max_stages = 16, max_points = 64
   !> Longest accepted deck line (longer lines are refused, never cut).
   integer, parameter :: line_len = 1024
   !> Largest accepted deck file [bytes].
   integer, parameter :: max_deck_bytes = 1048576
   !> Blank characters of a deck line: space and tab.
   character(len=*), parameter :: blanks = ' '//achar(9)

   character(len=9), parameter :: group_names(8) = [character(len=9) :: &
                                                    'mesh', 'material', 'dirichlet', 'traction', 'contact', 'solver', 'output', &
                                                    'initial']
   !> The plane obstacle y = 0 with its normal +y when the deck gives no obstacle_point/normal.
   real(wp), parameter :: default_obstacle_point(2) = [0.0_wp, 0.0_wp], default_obstacle_normal(2) = [0.0_wp, 1.0_wp]
   character(len=6), parameter :: edges(4) = [character(len=6) :: 'bottom', 'right', 'top', 'left']
   !> The variables of each group (of group_names), as the namelists in read_mesh, ...,
   !> read_output declare them (test_deck checks that each is accepted); for suggestions.
   character(len=*), parameter :: group_variables(8) = [character(len=320) :: &
      'lx ly nx ny level file', &
      'young poisson density', &
      'edge boundary xmin xmax ymin ymax component values times', &
      'edge boundary xmin xmax ymin ymax component values times', &
      'edge boundary xmin xmax ymin ymax obstacle obstacle_point obstacle_normal obstacle_center '// &
      'obstacle_radius obstacle_side origin direction multiplier friction friction_coefficient threshold '// &
      'threshold_abscissa threshold_values tresca_scope method penalty_stiffness', &
      'dt dt_factor allow_unstable t_ramp t_end max_steps damping alpha damping_interval tol_residual '// &
      'tol_kinetic check_interval power_iterations dt_limit mass_scaling method static_increments '// &
      'compare_static convergence_test', &
      'history_interval xdmf progress snapshot_times', &
      'velocity']

   !> The logical variables (group:variable). Their values are checked as text before the
   !> namelist read: Fortran reads any word whose first letter after an optional '.' is T or F
   !> as a logical (F2018 13.7.3), so `xdmf = fish` would read as .false.
   character(len=*), parameter :: logical_vars(4) = [character(len=21) :: 'solver:allow_unstable', &
                                                      'solver:compare_static', 'output:xdmf', 'output:progress']
   !> The spellings of a logical value accepted (lower case).
   character(len=*), parameter :: logical_words(10) = [character(len=7) :: '.true.', '.false.', 't', 'f', &
                                                        '.t.', '.f.', '.t', '.f', 'true', 'false']

   !> &mesh: structured rectangle [0, lx] x [0, ly] with (nx 2^level) x (ny 2^level) elements,
   !> or a Gmsh file (.msh, or .geo meshed at start-up) refined `level` times (docs/geometry.md).
   type :: mesh_cfg_t
      character(len=256) :: file = ''  !< Gmsh mesh or geometry; '' for the built-in rectangle
      real(wp) :: lx = unset          !< width [mm], required, > 0
      real(wp) :: ly = unset          !< height [mm], required, > 0
      integer :: nx = unset_int       !< divisions along x at level 0, required, >= 1
      integer :: ny = unset_int       !< divisions along y at level 0, required, >= 1
      integer :: level = 0            !< refinement level k: each division split in 2^k, 0..12
   end type mesh_cfg_t

   !> &material: isotropic Hooke law, plane strain.
   type :: material_cfg_t
      real(wp) :: young = unset       !< E [MPa], required, > 0
      real(wp) :: poisson = unset     !< nu [-], required, -1 < nu < 0.5
      real(wp) :: density = unset     !< rho [t/mm^3], required, > 0
   end type material_cfg_t

   !> &dirichlet (prescribed displacement [mm]) or &traction (surface traction [MPa]) on the
   !> nodes of one side of the bounding box within an optional coordinate range.
   type :: edge_load_cfg_t
      character(len=16) :: edge = ''               !< 'bottom' | 'right' | 'top' | 'left' (built-in mesh)
      character(len=64) :: boundary = ''           !< name of a Gmsh physical curve (instead of edge)
      real(wp) :: xmin = -unset, xmax = unset      !< x range of the selection [mm]
      real(wp) :: ymin = -unset, ymax = unset      !< y range of the selection [mm]
      !> 'x' | 'y', required; tractions also 'normal' | 'tangential' (along the outward normal n
      !> of each edge and t = (-n2, n1))
      character(len=16) :: component = ''
      real(wp) :: values(max_stages) = unset       !< value at the end of each stage, required
      real(wp) :: times(max_stages) = unset        !< end time of each stage [s]
      integer :: nstage = 0                        !< derived: number of stages
      integer :: line = 0                          !< deck line of the group (for messages)
   end type edge_load_cfg_t

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

   !> &initial: the state at t = 0 (docs/deck.md).
   type :: initial_cfg_t
      real(wp) :: velocity(2) = [0.0_wp, 0.0_wp]   !< uniform initial velocity (vx, vy) [mm/s]
   end type initial_cfg_t

   !> &output: what is written and how often.
   type :: output_cfg_t
      integer :: history_interval = 10    !< steps between history samples, >= 1
      logical :: xdmf = .true.            !< write the XDMF sidecar <output>.xmf for ParaView
      logical :: progress = .true.        !< progress line when the terminal is interactive
      real(wp) :: snapshot_times(max_stages) = unset  !< times of /fields/<step> snapshots [s]
      integer :: nsnapshot = 0            !< derived: number of snapshot times
   end type output_cfg_t

   !> One --set override: group, 1-based occurrence (0: not given) and the assignment text.
   type :: override_t
      character(len=16) :: group = ''
      integer :: index = 0
      character(len=:), allocatable :: assignment
      character(len=:), allocatable :: spec
   end type override_t

   !> A whole deck after overrides and validation.
   type :: deck_t
      character(len=:), allocatable :: path        !< deck file as given
      character(len=:), allocatable :: text        !< deck file contents
      character(len=:), allocatable :: effective   !< echo of the effective values (a valid deck)
      type(mesh_cfg_t) :: mesh
      type(material_cfg_t) :: material
      type(edge_load_cfg_t), allocatable :: dirichlet(:)
      type(edge_load_cfg_t), allocatable :: traction(:)
      type(contact_cfg_t) :: contact
      type(solver_cfg_t) :: solver
      type(output_cfg_t) :: output
      type(initial_cfg_t) :: initial
      !> derived: a dynamic run (non-zero initial velocity and damping = 'none')
      logical :: dynamic = .false.
      !> derived: the run stops at convergence (solver:convergence_test resolved)
      logical :: convergence_test = .true.
      !> the --set overrides applied (for deck_blame)
      type(override_t), allocatable :: overrides(:)
   end type deck_t

   !> One group occurrence in the deck: its name, first and last line.
   type :: block_t
      character(len=16) :: name = ''
      integer :: first = 0, last = 0
   end type block_t

contains

   !> Side id 1..4 of an edge name, 0 if unknown.
   pure integer function edge_id(name)
      character(len=*), intent(in) :: name
      integer :: i
      edge_id = 0
      do i = 1, size(edges)
         if (lower(trim(name)) == trim(edges(i))) edge_id = i
      end do
   end function edge_id

   !> Read, override and validate a deck. overrides are 'group[#i]:variable=value' strings.
   subroutine deck_read(path, overrides, deck, stat, errmsg)
      character(len=*), intent(in) :: path
      character(len=*), intent(in) :: overrides(:)
      type(deck_t), intent(out) :: deck
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      character(len=line_len), allocatable :: lines(:)
      type(block_t), allocatable :: blocks(:)
      type(override_t), allocatable :: ovr(:)

      deck%path = path
      call read_lines(path, lines, deck%text, stat, errmsg)
      if (stat /= 0) return
      call split_blocks(lines, blocks, stat, errmsg)
      if (stat /= 0) then
         errmsg = path//':'//errmsg
         return
      end if
      call parse_overrides(overrides, blocks, ovr, stat, errmsg)
      if (stat /= 0) return
      deck%overrides = ovr
      call read_groups(path, lines, blocks, ovr, deck, stat, errmsg)
      if (stat /= 0) return
      call validate(deck, stat, errmsg)
      if (stat /= 0) then
         errmsg = path//': '//errmsg//deck_blame(deck, errmsg)
         return
      end if
      deck%effective = echo(deck)
   end subroutine deck_read

   !> The --set overrides an error message about the deck is about, as " (from --set '...')",
   !> or '' when none is: an override of group G (occurrence i) and variable V is named when
   !> the message names G:V, or is about that group (starts with "G: " or "<deck>: G: ", or
   !> names "&G (#i)") and has V as a word (xmin, xmax, ymin, ymax also when it names the
   !> group's range). The message itself keeps naming the deck, where the group is.
   function deck_blame(deck, msg) result(note)
      type(deck_t), intent(in) :: deck
      character(len=*), intent(in) :: msg
      character(len=:), allocatable :: note
      character(len=:), allocatable :: m, g, v
      integer :: i, eq, paren
      logical :: about_group
      note = ''
      if (.not. allocated(deck%overrides)) return
      m = lower(msg)
      if (allocated(deck%path)) then
         if (index(m, lower(deck%path)//': ') == 1) m = m(len(deck%path) + 3:)
      end if
      associate (ovr => deck%overrides)
      do i = 1, size(ovr)
         g = trim(ovr(i)%group)
         eq = index(ovr(i)%assignment, '=')
         v = lower(trim(adjustl(ovr(i)%assignment(1:eq - 1))))
         paren = index(v, '(')
         if (paren > 0) v = trim(v(1:paren - 1))
         if (len(v) == 0) cycle
         if (g == 'dirichlet' .or. g == 'traction') then
            about_group = index(m, '&'//g//' (#'//str(ovr(i)%index)//')') > 0
         else
            about_group = index(m, g//': ') == 1
         end if
         if (has_word(m, g//':'//v) .or. (about_group .and. (has_word(m, v) .or. (has_word(m, 'range') &
             .and. any(v == [character(len=4) :: 'xmin', 'xmax', 'ymin', 'ymax']))))) then
            if (len(note) == 0) then
               note = " (from --set '"//ovr(i)%spec//"'"
            else
               note = note//", --set '"//ovr(i)%spec//"'"
            end if
         end if
      end do
      end associate
      if (len(note) > 0) note = note//')'
   contains
      !> w occurs in s with no letter, digit or underscore on either side.
      logical function has_word(s, w)
         character(len=*), intent(in) :: s, w
         integer :: k, at
         has_word = .false.
         at = 0
         do
            k = index(s(at + 1:), w)
            if (k == 0) return
            at = at + k
            if (.not. (ident(s, at - 1) .or. ident(s, at + len(w)))) then
               has_word = .true.
               return
            end if
         end do
      end function has_word
      logical function ident(s, k)
         character(len=*), intent(in) :: s
         integer, intent(in) :: k
         ident = .false.
         if (k < 1 .or. k > len(s)) return
         ident = verify(s(k:k), 'abcdefghijklmnopqrstuvwxyz0123456789_') == 0
      end function ident
   end function deck_blame

   ! ---- reading ----------------------------------------------------------------------------

   !> The deck's lines, read in full: a line longer than line_len is refused with its number
   !> (never cut). Only a regular file of at most max_deck_bytes is read (a directory, device,
   !> FIFO or oversized file is refused before reading). A leading UTF-8 byte-order mark is
   !> skipped.
   subroutine read_lines(path, lines, text, stat, errmsg)
      character(len=*), intent(in) :: path
      character(len=line_len), allocatable, intent(out) :: lines(:)
      character(len=:), allocatable, intent(out) :: text
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      character(len=*), parameter :: bom = char(239)//char(187)//char(191)
      character(len=256) :: msg, chunk
      character(len=line_len), allocatable :: tmp(:)
      character(len=:), allocatable :: buf, line
      integer :: unit, n, ios, kind, err, sz, pos, total, last_nonblank
      integer(c_long_long) :: dev, ino, bytes

      stat = 1
      call sys_path_info(path, kind, dev, ino, bytes, err)
      if (err /= 0) then
         errmsg = "cannot open deck '"//path//"': "//sys_strerror(err)
         return
      else if (kind == kind_missing) then
         errmsg = "cannot open deck '"//path//"': no such file"
         return
      else if (kind == kind_dangling) then
         errmsg = "cannot open deck '"//path//"': dangling symbolic link"
         return
      else if (kind /= kind_file) then
         errmsg = "deck '"//path//"' is a "//trim(kind_names(kind))//', not a regular file'
         return
      else if (bytes > max_deck_bytes) then
         errmsg = "deck '"//path//"' has "//str(bytes)//' bytes, more than a deck may have ('// &
                  str(max_deck_bytes)//')'
         return
      end if
      open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         errmsg = "cannot open deck '"//path//"': "//trim(msg)
         return
      end if
      allocate (lines(64))
      allocate (character(len=int(bytes) + 1) :: buf)
      pos = 0
      n = 0
      do
         ! one whole record, in chunks (non-advancing), so that nothing is cut; beyond line_len
         ! only the position of the last non-blank is kept (for the message)
         line = ''
         total = 0
         last_nonblank = 0
         do
            read (unit, '(a)', advance='no', size=sz, iostat=ios, iomsg=msg) chunk
            if (total < line_len) line = line//chunk(1:min(sz, line_len - total))
            if (len_trim(chunk(1:sz)) > 0) last_nonblank = total + len_trim(chunk(1:sz))
            total = total + sz
            if (ios /= 0) exit
         end do
         if (is_iostat_end(ios) .and. total == 0) exit
         if (n == 0 .and. index(line, bom) == 1) then
            ! a UTF-8 byte-order mark (some editors write one) is not part of the first line
            line = line(len(bom) + 1:)
            last_nonblank = max(last_nonblank - len(bom), 0)
         end if
         if (ios /= 0 .and. .not. is_iostat_eor(ios) .and. .not. is_iostat_end(ios)) then
            errmsg = path//':'//str(n + 1)//': cannot read: '//trim(msg)
            close (unit)
            return
         end if
         n = n + 1
         if (last_nonblank > line_len) then
            errmsg = path//':'//str(n)//': line has '//str(last_nonblank)//' characters, more than '// &
                     str(line_len)//'; split it (a namelist value list may span lines)'
            close (unit)
            return
         end if
         if (n > size(lines)) then
            allocate (tmp(2*size(lines)))
            tmp(1:size(lines)) = lines
            call move_alloc(tmp, lines)
         end if
         lines(n) = line
         sz = len_trim(line)
         if (pos + sz + 1 > len(buf)) buf = buf//repeat(' ', sz + 1)
         buf(pos + 1:pos + sz) = line(1:sz)
         buf(pos + sz + 1:pos + sz + 1) = new_line('a')
         pos = pos + sz + 1
         if (is_iostat_end(ios)) exit
      end do
      close (unit)
      lines = lines(1:n)
      text = buf(1:pos)
      stat = 0
      errmsg = ''
   end subroutine read_lines

   !> Find the groups: '&name' opens one (first non-blank of a line), the first '/' outside
   !> quotes and comments closes it. Anything else outside groups must be blank or a comment.
   !> A variable given twice in one group is refused (check_repeats).
   subroutine split_blocks(lines, blocks, stat, errmsg)
      character(len=line_len), intent(in) :: lines(:)
      type(block_t), allocatable, intent(out) :: blocks(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(block_t) :: tmp(size(lines))
      logical :: inside
      character(len=line_len) :: code
      integer :: i, k, n, j, first
      character(len=:), allocatable :: name

      stat = 0
      errmsg = ''
      n = 0
      inside = .false.
      do i = 1, size(lines)
         code = syntax_only(lines(i))
         k = 1
         if (.not. inside) then
            first = verify(code, blanks)
            if (first == 0) cycle   ! blank or a comment
            if (code(first:first) /= '&') then
               stat = 1
               errmsg = str(i)//': text outside any namelist group: '//trim(adjustl(lines(i)))
               return
            end if
            j = first + 1
            do while (j <= len_trim(code))
               if (.not. is_name_char(code(j:j))) exit
               j = j + 1
            end do
            name = lower(code(first + 1:j - 1))
            if (.not. any(group_names == name)) then
               stat = 1
               errmsg = str(i)//": unknown group '&"//name//"'; valid groups: "// &
                        join(group_names, ', ')
               return
            end if
            n = n + 1
            tmp(n)%name = name
            tmp(n)%first = i
            inside = .true.
            k = j
         end if
         ! look for the closing slash
         j = k - 1 + scan(code(k:), '&/')
         if (j < k) cycle
         if (code(j:j) == '&') then
            ! '&end' (a common extension) or a new group before '/': refused, never misread
            stat = 1
            if (lower(code(j:min(j + 3, len(code)))) == '&end') then
               errmsg = str(i)//": '&end' does not close a group here; close &"//trim(tmp(n)%name)// &
                        " with '/'"
            else
               errmsg = str(i)//": '&' inside group &"//trim(tmp(n)%name)//' (opened at line '// &
                        str(tmp(n)%first)//") before its closing '/'"
            end if
            return
         end if
         inside = .false.
         tmp(n)%last = i
         ! nothing but a comment may follow the slash
         if (verify(code(j + 1:), blanks) > 0) then
            stat = 1
            errmsg = str(i)//': text after the end of group &'//trim(tmp(n)%name)
            return
         end if
         call check_repeats(lines(tmp(n)%first:i), tmp(n), stat, errmsg)
         if (stat /= 0) return
      end do
      if (inside) then
         stat = 1
         errmsg = str(tmp(n)%first)//': group &'//trim(tmp(n)%name)//" is not closed by '/'"
         return
      end if
      blocks = tmp(1:n)
      do i = 1, n
         if (trim(blocks(i)%name) == 'dirichlet' .or. trim(blocks(i)%name) == 'traction') cycle
         do j = 1, i - 1
            if (blocks(j)%name == blocks(i)%name) then
               stat = 1
               errmsg = str(blocks(i)%first)//': group &'//trim(blocks(i)%name)// &
                        ' given twice (first at line '//str(blocks(j)%first)//')'
               return
            end if
         end do
      end do
   end subroutine split_blocks

   !> A variable given twice in one group occurrence is refused: the namelist would silently
   !> keep the last value. Elements of an array are distinct variables (values(1) = a,
   !> values(2) = b), but an element of an array given whole is given twice (values = a, b,
   !> values(2) = c). Only assignments whose name, subscript and '=' are on one line are seen.
   subroutine check_repeats(blk, grp, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(block_t), intent(in) :: grp
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      character(len=line_len), allocatable :: seen(:), here(:)
      integer, allocatable :: seen_line(:)
      integer :: l, i, j
      allocate (seen(0), seen_line(0))
      do l = 1, size(blk)
         here = assigned_names(syntax_only(blk(l)))
         do i = 1, size(here)
            do j = 1, size(seen)
               if (base_name(here(i)) /= base_name(seen(j))) cycle
               if (here(i) /= seen(j) .and. index(here(i), '(') > 0 .and. index(seen(j), '(') > 0) cycle
               stat = 1
               errmsg = str(grp%first + l - 1)//': &'//trim(grp%name)//': '//trim(here(i))// &
                        ' is given twice in this group (first'
               if (here(i) /= seen(j)) errmsg = errmsg//' as '//trim(seen(j))
               errmsg = errmsg//' at line '//str(grp%first + seen_line(j) - 1)//')'
               return
            end do
            seen = [character(len=line_len) :: seen, here(i)]
            seen_line = [seen_line, l]
         end do
      end do
   contains
      pure function base_name(designator) result(b)
         character(len=*), intent(in) :: designator
         character(len=:), allocatable :: b
         b = designator(1:scan(designator // '(', '(') - 1)
      end function base_name
   end subroutine check_repeats

   !> The variables a line of namelist syntax (from syntax_only) assigns: each 'name =' or
   !> 'name(subscript) =', in lower case without blanks, e.g. 'young', 'values(2)'.
   function assigned_names(code) result(names)
      character(len=*), intent(in) :: code
      character(len=line_len), allocatable :: names(:)
      integer :: pos, k, close
      character(len=:), allocatable :: designator
      allocate (names(0))
      pos = 1
      do while (pos <= len(code))
         ! a name starts with a letter after a blank or comma (not after '&': a group name)
         if (.not. is_letter(code(pos:pos))) then
            pos = pos + 1
            cycle
         end if
         if (pos > 1) then
            if (scan(code(pos - 1:pos - 1), blanks//',') == 0) then
               pos = pos + 1
               cycle
            end if
         end if
         k = pos
         do while (k <= len(code))
            if (.not. is_name_char(code(k:k))) exit
            k = k + 1
         end do
         designator = lower(code(pos:k - 1))
         pos = k
         k = next_nonblank(code, k)
         if (k <= len(code)) then
            if (code(k:k) == '(') then
               close = index(code(k:), ')')
               if (close == 0) cycle
               designator = designator//without_blanks(code(k:k + close - 1))
               k = next_nonblank(code, k + close)
            end if
         end if
         if (k > len(code)) cycle
         if (code(k:k) == '=') names = [character(len=line_len) :: names, designator]
      end do
   contains
      pure integer function next_nonblank(s, from)
         character(len=*), intent(in) :: s
         integer, intent(in) :: from
         next_nonblank = len(s) + 1
         if (from > len(s)) return
         next_nonblank = verify(s(from:), blanks)
         if (next_nonblank == 0) then
            next_nonblank = len(s) + 1
         else
            next_nonblank = from + next_nonblank - 1
         end if
      end function next_nonblank
      pure function without_blanks(s) result(t)
         character(len=*), intent(in) :: s
         character(len=:), allocatable :: t
         integer :: m
         t = ''
         do m = 1, len(s)
            if (scan(s(m:m), blanks) == 0) t = t//s(m:m)
         end do
      end function without_blanks
   end function assigned_names

   !> A line with the text inside quotes and a '!' comment outside quotes blanked, so that the
   !> names, '=', '&' and '/' left in it are namelist syntax (the quote characters are kept).
   !> open_at: position of a quote left open at the end of the line, 0 if none.
   function syntax_only(line, open_at) result(code)
      character(len=*), intent(in) :: line
      integer, intent(out), optional :: open_at
      character(len=len(line)) :: code
      character(len=1) :: quote, c
      integer :: j, opened
      code = line
      quote = ' '
      opened = 0
      do j = 1, len(line)
         c = line(j:j)
         if (quote /= ' ') then
            if (c == quote) then
               quote = ' '
               opened = 0
            else
               code(j:j) = ' '
            end if
         else if (c == "'" .or. c == '"') then
            quote = c
            opened = j
         else if (c == '!') then
            code(j:) = ' '
            exit
         end if
      end do
      if (present(open_at)) open_at = opened
   end function syntax_only

   pure logical function is_name_char(ch)
      character(len=1), intent(in) :: ch
      is_name_char = is_letter(ch) .or. verify(ch, '0123456789_') == 0
   end function is_name_char

   pure logical function is_letter(ch)
      character(len=1), intent(in) :: ch
      is_letter = verify(ch, 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ') == 0
   end function is_letter

   !> Parse 'group[#i]:assignment' strings.
   subroutine parse_overrides(specs, blocks, ovr, stat, errmsg)
      character(len=*), intent(in) :: specs(:)
      type(block_t), intent(in) :: blocks(:)
      type(override_t), allocatable, intent(out) :: ovr(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer :: i, colon, hash, ios, nocc
      character(len=:), allocatable :: spec, group

      allocate (ovr(size(specs)))
      stat = 1
      do i = 1, size(specs)
         spec = trim(adjustl(specs(i)))
         ovr(i)%spec = spec
         colon = index(spec, ':')
         if (colon < 2 .or. index(spec, '=') < colon + 2) then
            errmsg = "--set '"//spec//"': expected group:variable=value"
            return
         end if
         group = lower(spec(1:colon - 1))
         hash = index(group, '#')
         if (hash > 0) then
            read (group(hash + 1:), *, iostat=ios) ovr(i)%index
            if (ios /= 0 .or. ovr(i)%index < 1) then
               errmsg = "--set '"//spec//"': bad group index '"//group(hash + 1:)//"'"
               return
            end if
            group = group(1:hash - 1)
         end if
         if (.not. any(group_names == group)) then
            errmsg = "--set '"//spec//"': unknown group '"//group//"'; valid groups: "// &
                     join(group_names, ', ')
            return
         end if
         ovr(i)%group = group
         ovr(i)%assignment = spec(colon + 1:)
         errmsg = assignment_problem(ovr(i)%assignment)
         if (len(errmsg) > 0) then
            errmsg = "--set '"//spec//"': "//errmsg
            return
         end if
         nocc = count(blocks%name == group)
         ! a --set changes a group of the deck; these groups are not there unless the deck says so
         if (nocc == 0 .and. (group == 'dirichlet' .or. group == 'traction' .or. group == 'contact')) then
            errmsg = "--set '"//spec//"': the deck has no &"//group//' group'
            return
         end if
         if (group == 'dirichlet' .or. group == 'traction') then
            if (ovr(i)%index == 0 .and. nocc > 1) then
               errmsg = "--set '"//spec//"': the deck has "//str(nocc)//' &'//group// &
                        ' groups; say which, e.g. '//group//'#2:...'
               return
            end if
            if (ovr(i)%index > nocc) then
               errmsg = "--set '"//spec//"': the deck has only "//str(nocc)//' &'//group//' groups'
               return
            end if
            ovr(i)%index = max(ovr(i)%index, 1)
         else if (ovr(i)%index > 1) then
            errmsg = "--set '"//spec//"': &"//group//' occurs once'
            return
         end if
      end do
      stat = 0
      errmsg = ''
   end subroutine parse_overrides

   !> What keeps the 'variable=value' of a --set from being one assignment, '' if nothing: a
   !> quote left open, no value (the namelist would leave the variable as it is) or more than
   !> one variable.
   function assignment_problem(assignment) result(problem)
      character(len=*), intent(in) :: assignment
      character(len=:), allocatable :: problem
      character(len=len(assignment)) :: code
      character(len=line_len), allocatable :: names(:)
      integer :: open_at
      problem = ''
      code = syntax_only(assignment, open_at)
      if (open_at > 0) then
         problem = 'the quote opening '//assignment(open_at:)//' is not closed'
         return
      end if
      names = assigned_names(code)
      if (size(names) > 1) then
         problem = 'sets '//str(size(names))//' variables ('//join(names, ', ')//'); give one variable per --set'
      else if (verify(code(index(code, '=') + 1:), blanks//',') == 0) then
         problem = "no value after '='"
      end if
   end function assignment_problem

   !> The first value in some namelist text (the lines of one group, or one --set assignment)
   !> that the namelist read must not take, as 'label:variable = value ...', or '' if none; at:
   !> the index of its line. A real literal beyond the double range (1e999: the conversion
   !> overflows, which traps in the Debug build) or equal to +-huge, the deck's 'not given'
   !> marker, is refused as out of range (|value| <= max_magnitude), so that a marker the user
   !> types cannot pass for a value never given; a logical variable takes only .true./.false.
   !> (T, F, .t., true, ...). NaN and Infinity typed as such are left to check_finite, which
   !> names the array entry. Runs with floating-point halting off (read_groups' note).
   function value_problem(lines, group, label, at) result(problem)
      character(len=*), intent(in) :: lines(:)
      character(len=*), intent(in) :: group, label
      integer, intent(out) :: at
      character(len=:), allocatable :: problem
      character(len=*), parameter :: separators = blanks//',=/&()'
      character(len=:), allocatable :: code, token, name, word
      real(wp) :: v
      integer :: l, p, e, k, ios
      problem = ''
      name = ''
      do l = 1, size(lines)
         at = l
         code = syntax_only(lines(l))
         p = 1
         do while (p <= len(code))
            if (scan(code(p:p), separators) > 0) then
               p = p + 1
               cycle
            end if
            e = scan(code(p:), separators)
            if (e == 0) then
               e = len(code) + 1
            else
               e = p + e - 1
            end if
            token = code(p:e - 1)
            ! a name is followed by '=', after an optional subscript
            k = e
            do while (k <= len(code))
               if (scan(code(k:k), blanks) == 0) exit
               k = k + 1
            end do
            if (k <= len(code)) then
               if (code(k:k) == '(') then
                  k = k + index(code(k:), ')')
                  do while (k <= len(code))
                     if (scan(code(k:k), blanks) == 0) exit
                     k = k + 1
                  end do
               end if
            end if
            if (k <= len(code)) then
               if (code(k:k) == '=') then
                  name = lower(token)
                  p = k + 1
                  cycle
               end if
            end if
            p = e
            if (len(name) == 0 .or. scan(token, '"'//"'") > 0) cycle   ! a group name, a quoted string
            ! r*c: c repeated r times
            word = token(index(token, '*') + 1:)
            if (len(word) == 0) cycle
            if (any(logical_vars == group//':'//name)) then
               if (.not. any(logical_words == lower(word))) then
                  problem = label//':'//name//' = '//word//' is not a logical value; give .true. or .false.'
                  return
               end if
               cycle
            end if
            read (word, *, iostat=ios) v
            if (ios /= 0) cycle   ! not a number: the namelist read says what is wrong
            if (index(lower(word), 'nan') > 0 .or. index(lower(word), 'inf') > 0) cycle
            if (.not. ieee_is_finite(v) .or. abs(v) >= huge(v)) then
               problem = label//':'//name//' = '//word//' is out of range (|value| <= '//str(max_magnitude)//')'
               return
            end if
         end do
      end do
      at = 0
   end function value_problem

   !> Read every group (defaults first, then the deck block, then the overrides). The reads run
   !> with floating-point halting off and the caller's floating-point status restored after: a
   !> literal such as 1e999 overflows inside the runtime's conversion, which would trap in the
   !> Debug build (-ffpe-trap) before any check could name it; value_problem and check_finite
   !> refuse such values afterwards with the same message in both builds.
   subroutine read_groups(path, lines, blocks, ovr, deck, stat, errmsg)
      character(len=*), intent(in) :: path
      character(len=line_len), intent(in) :: lines(:)
      type(block_t), intent(in) :: blocks(:)
      type(override_t), intent(in) :: ovr(:)
      type(deck_t), intent(inout) :: deck
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(ieee_status_type) :: saved
      call ieee_get_status(saved)
      call ieee_set_halting_mode(ieee_usual, .false.)
      call read_groups_unmasked(path, lines, blocks, ovr, deck, stat, errmsg)
      call ieee_set_status(saved)
   end subroutine read_groups

   subroutine read_groups_unmasked(path, lines, blocks, ovr, deck, stat, errmsg)
      character(len=*), intent(in) :: path
      character(len=line_len), intent(in) :: lines(:)
      type(block_t), intent(in) :: blocks(:)
      type(override_t), intent(in) :: ovr(:)
      type(deck_t), intent(inout) :: deck
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      character(len=line_len) :: none(0)
      integer :: b, nd, nt, k, at
      character(len=:), allocatable :: where, label

      stat = 0
      errmsg = ''
      ! every value as text first (value_problem), the deck's groups, then the --set ones
      nd = 0
      nt = 0
      do b = 1, size(blocks)
         label = trim(blocks(b)%name)
         if (label == 'dirichlet') then
            nd = nd + 1
            label = label//'#'//str(nd)
         else if (label == 'traction') then
            nt = nt + 1
            label = label//'#'//str(nt)
         end if
         errmsg = value_problem(lines(blocks(b)%first:blocks(b)%last), trim(blocks(b)%name), label, at)
         if (len(errmsg) > 0) then
            stat = 1
            errmsg = path//':'//str(blocks(b)%first + at - 1)//': '//errmsg
            return
         end if
      end do
      do k = 1, size(ovr)
         label = trim(ovr(k)%group)
         if (label == 'dirichlet' .or. label == 'traction') label = label//'#'//str(max(ovr(k)%index, 1))
         errmsg = value_problem([ovr(k)%assignment], trim(ovr(k)%group), label, at)
         if (len(errmsg) > 0) then
            stat = 1
            errmsg = "--set '"//ovr(k)%spec//"': "//errmsg
            return
         end if
      end do
      allocate (deck%dirichlet(count(blocks%name == 'dirichlet')))
      allocate (deck%traction(count(blocks%name == 'traction')))
      nd = 0
      nt = 0
      ! singletons absent from the deck keep their defaults but still take their overrides
      do k = 1, size(group_names)
         if (any(blocks%name == group_names(k))) cycle
         where = path//': &'//trim(group_names(k))//': '
         select case (trim(group_names(k)))
         case ('mesh'); call read_mesh(none, pick(ovr, 'mesh', 1), where, deck%mesh, stat, errmsg)
         case ('material'); call read_material(none, pick(ovr, 'material', 1), where, deck%material, stat, errmsg)
         case ('solver'); call read_solver(none, pick(ovr, 'solver', 1), where, deck%solver, stat, errmsg)
         case ('output'); call read_output(none, pick(ovr, 'output', 1), where, deck%output, stat, errmsg)
         case ('initial'); call read_initial(none, pick(ovr, 'initial', 1), where, deck%initial, stat, errmsg)
         end select
         if (stat /= 0) return
      end do
      do b = 1, size(blocks)
         where = path//':'//str(blocks(b)%first)//': &'//trim(blocks(b)%name)//': '
         associate (blk => lines(blocks(b)%first:blocks(b)%last))
            select case (trim(blocks(b)%name))
            case ('mesh'); call read_mesh(blk, pick(ovr, 'mesh', 1), where, deck%mesh, stat, errmsg)
            case ('material'); call read_material(blk, pick(ovr, 'material', 1), where, deck%material, stat, errmsg)
            case ('solver'); call read_solver(blk, pick(ovr, 'solver', 1), where, deck%solver, stat, errmsg)
            case ('output'); call read_output(blk, pick(ovr, 'output', 1), where, deck%output, stat, errmsg)
            case ('initial'); call read_initial(blk, pick(ovr, 'initial', 1), where, deck%initial, stat, errmsg)
            case ('contact')
               deck%contact%present = .true.
               call read_contact(blk, pick(ovr, 'contact', 1), where, deck%contact, stat, errmsg)
            case ('dirichlet')
               nd = nd + 1
               deck%dirichlet(nd)%line = blocks(b)%first
               call read_edge_load(blk, 'dirichlet', pick(ovr, 'dirichlet', nd), where, deck%dirichlet(nd), stat, errmsg)
            case ('traction')
               nt = nt + 1
               deck%traction(nt)%line = blocks(b)%first
               call read_edge_load(blk, 'traction', pick(ovr, 'traction', nt), where, deck%traction(nt), stat, errmsg)
            end select
         end associate
         if (stat /= 0) then
            if (index(errmsg, where) == 1) errmsg = pinpoint(errmsg, where, lines, blocks(b), path)
            return
         end if
      end do
   end subroutine read_groups_unmasked

   !> A runtime message 'Cannot match namelist object name X' points at the group's first line;
   !> point it at the line holding X instead and quote that line.
   function pinpoint(msg, where, lines, blk, path) result(out)
      character(len=*), intent(in) :: msg, where, path
      character(len=line_len), intent(in) :: lines(:)
      type(block_t), intent(in) :: blk
      character(len=:), allocatable :: out, token
      integer :: k, l, e
      out = msg
      k = index(msg, 'object name ')
      if (k == 0) return
      token = msg(k + len('object name '):)
      e = scan(token, ' ,;')
      if (e > 0) token = token(:e - 1)
      if (len(token) == 0) return
      do l = blk%first, blk%last
         if (index(lower(lines(l)), lower(token)) > 0) then
            out = path//':'//str(l)//': &'//trim(blk%name)//': '//msg(len(where) + 1:)// &
                  " (in '"//trim(adjustl(lines(l)))//"')"
            return
         end if
      end do
   end function pinpoint

   !> The overrides of one group occurrence, each made a one-line namelist record.
   function pick(ovr, group, occurrence) result(sel)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: group
      integer, intent(in) :: occurrence
      type(override_t), allocatable :: sel(:)
      integer :: i
      allocate (sel(0))
      do i = 1, size(ovr)
         if (trim(ovr(i)%group) /= group) cycle
         if (max(ovr(i)%index, 1) /= occurrence) cycle
         sel = [sel, ovr(i)]
         sel(size(sel))%assignment = '&'//group//' '//ovr(i)%assignment//' /'
      end do
   end function pick

   !> A string value longer than its variable is refused, never cut (read it into a local of
   !> length line_len, then call this with the variable's length); true if too long.
   logical function too_long(where, name, value, maxlen, stat, errmsg)
      character(len=*), intent(in) :: where, name, value
      integer, intent(in) :: maxlen
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      too_long = len_trim(value) > maxlen
      if (too_long) then
         stat = 1
         errmsg = where//name//" = '"//trim(value)//"' is longer than "//str(maxlen)// &
                  ' characters, so it is no valid choice'
      end if
   end function too_long

   !> "; did you mean 'young'?" for an unknown variable name of a group: the group's variables
   !> nearest to it in optimal-string-alignment distance (insertions, deletions, substitutions
   !> and swaps of two neighbours, each 1), when that distance is at most 1 for names of up
   !> to 4 letters and at most 2 beyond; '' when none is that near.
   function nearest_names(name, group) result(hint)
      character(len=*), intent(in) :: name, group
      character(len=:), allocatable :: hint, list, word, best
      integer :: g, p, e, d, dmin, nbest
      hint = ''
      g = findloc(group_names, group, 1)
      if (g == 0) return
      list = trim(group_variables(g))//' '
      dmin = merge(1, 2, len(name) <= 4)
      best = ''
      nbest = 0
      p = 1
      do while (p < len(list))
         e = p - 1 + index(list(p:), ' ')
         word = list(p:e - 1)
         p = e + 1
         d = osa_distance(name, word)
         if (d > dmin) cycle
         if (d < dmin) then
            dmin = d
            best = ''
            nbest = 0
         end if
         if (nbest > 0) best = best//' or '
         best = best//"'"//word//"'"
         nbest = nbest + 1
      end do
      if (nbest > 0) hint = "; did you mean "//best//'?'
   end function nearest_names

   !> Optimal string alignment distance between a and b (Damerau-Levenshtein without
   !> repeated edits of a substring): the fewest insertions, deletions, substitutions and
   !> transpositions of adjacent characters turning a into b.
   pure integer function osa_distance(a, b) result(dist)
      character(len=*), intent(in) :: a, b
      integer :: d(0:len(a), 0:len(b)), i, j, cost
      do i = 0, len(a)
         d(i, 0) = i
      end do
      do j = 0, len(b)
         d(0, j) = j
      end do
      do j = 1, len(b)
         do i = 1, len(a)
            cost = merge(0, 1, a(i:i) == b(j:j))
            d(i, j) = min(d(i - 1, j) + 1, d(i, j - 1) + 1, d(i - 1, j - 1) + cost)
            if (i > 1 .and. j > 1) then
               if (a(i:i) == b(j - 1:j - 1) .and. a(i - 1:i - 1) == b(j:j)) d(i, j) = min(d(i, j), d(i - 2, j - 2) + 1)
            end if
         end do
      end do
      dist = d(len(a), len(b))
   end function osa_distance

   !> Turn a failed namelist read into a message; true if it failed.
   logical function read_failed(ios, msg, group, where, stat, errmsg)
      integer, intent(in) :: ios
      character(len=*), intent(in) :: msg, group, where
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      character(len=:), allocatable :: name
      integer :: k
      read_failed = ios /= 0
      if (read_failed) then
         stat = 1
         errmsg = where//trim(msg)
         k = index(msg, 'Cannot match namelist object name ')
         if (k == 0) return
         name = lower(trim(msg(k + 34:)))
         if (len(name) == 0) return
         if (verify(name(1:1), '0123456789') == 0) then
            ! no name but a number after a separator: a value beyond the variable's size, often
            ! a decimal comma (0,3 reads as 0 and a second value 3). Not for '.5' (nx = 2.5: an
            ! integer read stops at the point) nor for a quoted text ('abc' for a number)
            errmsg = errmsg//'; more values than the variable holds (a decimal takes a point: 0.3, not 0,3)'
         else if (is_letter(name(1:1)) .and. index(where, '--set') == 1 .and. &
                  index(lower(where(index(where, '=') + 1:)), name) > 0) then
            ! an unquoted text value (--set contact:friction=coulomb) reads as a variable name
            errmsg = errmsg//'; a text value needs quotes, e.g. --set "contact:friction='//"'coulomb'"//'"'
         else if (is_letter(name(1:1))) then
            ! a misspelled name: the nearest names of the group, when near enough
            errmsg = errmsg//nearest_names(name, group)
         end if
      end if
   end function read_failed

   subroutine read_mesh(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(mesh_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: lx, ly
      integer :: nx, ny, level, ios, i
      character(len=256) :: msg
      character(len=line_len) :: file
      namelist /mesh/ lx, ly, nx, ny, level, file
      lx = cfg%lx; ly = cfg%ly; nx = cfg%nx; ny = cfg%ny; level = cfg%level; file = cfg%file
      if (size(blk) > 0) then
         read (blk, nml=mesh, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, 'mesh', where, stat, errmsg)) return
      end if
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=mesh, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, 'mesh', "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      if (too_long(where, 'file', file, len(cfg%file), stat, errmsg)) return
      cfg%lx = lx; cfg%ly = ly; cfg%nx = nx; cfg%ny = ny; cfg%level = level; cfg%file = file
   end subroutine read_mesh

   subroutine read_material(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(material_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: young, poisson, density
      integer :: ios, i
      character(len=256) :: msg
      namelist /material/ young, poisson, density
      young = cfg%young; poisson = cfg%poisson; density = cfg%density
      if (size(blk) > 0) then
         read (blk, nml=material, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, 'material', where, stat, errmsg)) return
      end if
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=material, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, 'material', "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      cfg%young = young; cfg%poisson = poisson; cfg%density = density
   end subroutine read_material

   subroutine read_edge_load(blk, group, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      character(len=*), intent(in) :: group
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(edge_load_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      character(len=line_len) :: edge, boundary, component   ! long enough to see over-long values
      real(wp) :: xmin, xmax, ymin, ymax, values(max_stages), times(max_stages)
      integer :: ios, i
      character(len=256) :: msg
      namelist /dirichlet/ edge, boundary, xmin, xmax, ymin, ymax, component, values, times
      namelist /traction/ edge, boundary, xmin, xmax, ymin, ymax, component, values, times
      edge = cfg%edge; boundary = cfg%boundary; component = cfg%component
      xmin = cfg%xmin; xmax = cfg%xmax; ymin = cfg%ymin; ymax = cfg%ymax
      values = cfg%values; times = cfg%times
      if (group == 'dirichlet') then
         read (blk, nml=dirichlet, iostat=ios, iomsg=msg)
      else
         read (blk, nml=traction, iostat=ios, iomsg=msg)
      end if
      if (read_failed(ios, msg, group, where, stat, errmsg)) return
      do i = 1, size(ovr)
         if (group == 'dirichlet') then
            read (ovr(i)%assignment, nml=dirichlet, iostat=ios, iomsg=msg)
         else
            read (ovr(i)%assignment, nml=traction, iostat=ios, iomsg=msg)
         end if
         if (read_failed(ios, msg, group, "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      if (too_long(where, 'edge', edge, len(cfg%edge), stat, errmsg)) return
      if (too_long(where, 'boundary', boundary, len(cfg%boundary), stat, errmsg)) return
      if (too_long(where, 'component', component, len(cfg%component), stat, errmsg)) return
      cfg%edge = edge; cfg%boundary = boundary; cfg%component = component
      cfg%xmin = xmin; cfg%xmax = xmax; cfg%ymin = ymin; cfg%ymax = ymax
      cfg%values = values; cfg%times = times
   end subroutine read_edge_load

   subroutine read_contact(blk, ovr, where, cfg, stat, errmsg)
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
      if (read_failed(ios, msg, 'contact', where, stat, errmsg)) return
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=contact, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, 'contact', "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
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
   end subroutine read_contact

   subroutine read_solver(blk, ovr, where, cfg, stat, errmsg)
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
         if (read_failed(ios, msg, 'solver', where, stat, errmsg)) return
      end if
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=solver, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, 'solver', "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
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
   end subroutine read_solver

   !> &initial: the uniform initial velocity.
   subroutine read_initial(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(initial_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: velocity(2)
      integer :: ios, i
      character(len=256) :: msg
      namelist /initial/ velocity
      velocity = cfg%velocity
      if (size(blk) > 0) then
         read (blk, nml=initial, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, 'initial', where, stat, errmsg)) return
      end if
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=initial, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, 'initial', "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      cfg%velocity = velocity
   end subroutine read_initial

   subroutine read_output(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(output_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: history_interval, ios, i
      logical :: xdmf, progress
      real(wp) :: snapshot_times(max_stages)
      character(len=256) :: msg
      namelist /output/ history_interval, xdmf, progress, snapshot_times
      history_interval = cfg%history_interval; xdmf = cfg%xdmf; progress = cfg%progress
      snapshot_times = cfg%snapshot_times
      if (size(blk) > 0) then
         read (blk, nml=output, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, 'output', where, stat, errmsg)) return
      end if
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=output, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, 'output', "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      cfg%history_interval = history_interval; cfg%xdmf = xdmf; cfg%progress = progress
      cfg%snapshot_times = snapshot_times
   end subroutine read_output

   ! ---- validation -------------------------------------------------------------------------

   !> Check every value right after reading; fill derived values (stage counts, default times).
   subroutine validate(deck, stat, errmsg)
      type(deck_t), intent(inout) :: deck
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(material_t) :: mat
      real(wp) :: last_stage, norm
      integer :: i

      stat = 1
      ! every real first: finite and of sane magnitude, before any comparison (contact2d_checks)
      if (any_not_finite()) return
      associate (m => deck%mesh)
         if (len_trim(m%file) > 0) then
            if (m%lx /= unset .or. m%ly /= unset .or. m%nx /= unset_int .or. m%ny /= unset_int) then
               errmsg = "mesh:file = '"//trim(m%file)//"' is given with lx/ly/nx/ny; give either a file "// &
                        'or the rectangle'
               return
            end if
            if (.not. (ends_with(m%file, '.msh') .or. ends_with(m%file, '.geo'))) then
               errmsg = "mesh:file = '"//trim(m%file)//"' must end in .msh (a Gmsh mesh) or .geo (a Gmsh geometry)"
               return
            end if
            if (m%level < 0 .or. m%level > 8) then
               errmsg = 'mesh:level = '//str(m%level)//' must be in 0..8 for a Gmsh file'
               return
            end if
         else
         if (m%lx == unset) then; errmsg = 'mesh:lx is required (width, mm)'; return; end if
         if (m%ly == unset) then; errmsg = 'mesh:ly is required (height, mm)'; return; end if
         if (m%nx == unset_int) then; errmsg = 'mesh:nx is required (divisions along x)'; return; end if
         if (m%ny == unset_int) then; errmsg = 'mesh:ny is required (divisions along y)'; return; end if
         if (.not. m%lx > 0) then; errmsg = 'mesh:lx = '//str(m%lx)//' must be > 0'; return; end if
         if (.not. m%ly > 0) then; errmsg = 'mesh:ly = '//str(m%ly)//' must be > 0'; return; end if
         if (m%nx < 1) then; errmsg = 'mesh:nx = '//str(m%nx)//' must be >= 1'; return; end if
         if (m%ny < 1) then; errmsg = 'mesh:ny = '//str(m%ny)//' must be >= 1'; return; end if
         if (check_range('mesh:lx', m%lx, 1.0e-30_wp, max_magnitude, errmsg)) return
         if (check_range('mesh:ly', m%ly, 1.0e-30_wp, max_magnitude, errmsg)) return
         if (m%level < 0 .or. m%level > 12) then
            errmsg = 'mesh:level = '//str(m%level)//' must be in 0..12'
            return
         end if
         if (real(m%nx, wp)*real(m%ny, wp)*4.0_wp**m%level > mesh_max_elements) then
            errmsg = 'mesh: nx*ny*4**level = '//str(real(m%nx, wp)*real(m%ny, wp)*4.0_wp**m%level)// &
                     ' elements is more than this program is meant for ('//str(mesh_max_elements)//')'
            return
         end if
         end if
      end associate

      associate (m => deck%material)
         if (m%young == unset) then; errmsg = 'material:young is required (MPa)'; return; end if
         if (m%poisson == unset) then; errmsg = 'material:poisson is required'; return; end if
         if (m%density == unset) then; errmsg = 'material:density is required (t/mm^3)'; return; end if
         call material_init(mat, m%young, m%poisson, m%density, stat, errmsg)
         if (stat /= 0) return
         stat = 1
         if (check_range('material:young', m%young, 1.0e-30_wp, max_magnitude, errmsg)) return
         if (check_range('material:density', m%density, 1.0e-30_wp, max_magnitude, errmsg)) return
      end associate

      associate (s => deck%solver)
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
      end associate

      ! &initial: a finite velocity; with damping = 'none' a non-zero one makes the
      ! run dynamic (no convergence test unless solver:convergence_test = 'on'; t_end bounds it)
      do i = 1, 2
         if (.not. ieee_is_finite(deck%initial%velocity(i))) then
            ! named without arithmetic on the value (Debug builds trap invalid operations)
            if (ieee_is_nan(deck%initial%velocity(i))) then
               errmsg = 'NaN'
            else
               errmsg = trim(merge('+Infinity', '-Infinity', sign(1.0_wp, deck%initial%velocity(i)) > 0))
            end if
            errmsg = 'initial:velocity('//str(i)//') = '//errmsg//' must be finite (mm/s)'
            return
         end if
      end do
      deck%dynamic = any(deck%initial%velocity /= 0) .and. deck%solver%damping == 'none'
      select case (trim(deck%solver%convergence_test))
      case ('on'); deck%convergence_test = .true.
      case ('off'); deck%convergence_test = .false.
      case default; deck%convergence_test = .not. deck%dynamic
      end select
      if (deck%dynamic .and. deck%solver%t_end == 0) then
         errmsg = "solver:t_end is required for a dynamic run (initial:velocity /= 0 with damping = 'none')"
         return
      end if
      ! the static engine solves for equilibrium: an initial velocity has no meaning there
      if (any(deck%initial%velocity /= 0) .and. &
          (deck%solver%method == 'static' .or. deck%solver%compare_static)) then
         errmsg = "initial:velocity = "//str(deck%initial%velocity(1))//", "//str(deck%initial%velocity(2))// &
                  " has no meaning for the static engine (solver:method = 'static' or compare_static)"
         return
      end if
      ! mass scaling changes the dynamics: refused with an initial velocity (the
      ! damping check above refuses damping = 'none' and 'given')
      if (any(deck%initial%velocity /= 0) .and. deck%solver%mass_scaling > 0) then
         errmsg = "solver:mass_scaling = "//str(deck%solver%mass_scaling)//" is refused with initial:velocity = "// &
                  str(deck%initial%velocity(1))//", "//str(deck%initial%velocity(2))//" (fictitious mass changes the dynamics)"
         return
      end if

      associate (o => deck%output)
         if (o%history_interval < 1) then
            errmsg = 'output:history_interval = '//str(o%history_interval)//' must be >= 1'
            return
         end if
         o%nsnapshot = count(o%snapshot_times /= unset)
         if (any(o%snapshot_times(o%nsnapshot + 1:) /= unset)) then
            errmsg = 'output:snapshot_times must be given from the first entry on'
            return
         end if
         do i = 1, o%nsnapshot
            if (.not. o%snapshot_times(i) > 0 .or. &
                (i > 1 .and. .not. o%snapshot_times(i) > o%snapshot_times(max(i - 1, 1)))) then
               errmsg = 'output:snapshot_times must be > 0 and increase strictly (entry '//str(i)//')'
               return
            end if
         end do
      end associate

      last_stage = 0
      do i = 1, size(deck%dirichlet)
         call validate_edge_load(deck%dirichlet(i), 'dirichlet', i)
         if (stat /= 1) return
         last_stage = max(last_stage, deck%dirichlet(i)%times(deck%dirichlet(i)%nstage))
      end do
      do i = 1, size(deck%traction)
         call validate_edge_load(deck%traction(i), 'traction', i)
         if (stat /= 1) return
         last_stage = max(last_stage, deck%traction(i)%times(deck%traction(i)%nstage))
      end do
      if (size(deck%dirichlet) == 0) then
         errmsg = 'no &dirichlet group: the body needs supports (a rigid-body motion would be free)'
         return
      end if
      if (deck%solver%t_end == 0) then
         deck%solver%t_end = 10*last_stage
      else if (deck%solver%t_end < last_stage) then
         errmsg = 'solver:t_end = '//str(deck%solver%t_end)//' ends before the last load stage ('// &
                  str(last_stage)//' s)'
         return
      end if

      if (deck%contact%present) then
         associate (c => deck%contact)
            if (len_trim(c%boundary) > 0) then
               if (len_trim(c%edge) > 0) then
                  errmsg = "contact: give edge or boundary, not both"
                  return
               end if
               if (len_trim(deck%mesh%file) == 0) then
                  errmsg = "contact:boundary = '"//trim(c%boundary)//"' needs a Gmsh mesh (mesh:file); "// &
                           "the built-in rectangle takes edge = 'bottom' | 'right' | 'top' | 'left'"
                  return
               end if
            else if (len_trim(c%edge) == 0) then
               errmsg = no_place('contact')
               return
            else
               if (edge_id(c%edge) == 0) then
                  errmsg = "contact:edge = '"//trim(c%edge)//"' is not one of "//join(edges, ', ')// &
                           " (or give boundary = '<physical curve>' with a Gmsh mesh)"
                  return
               end if
               if (len_trim(deck%mesh%file) > 0) then
                  errmsg = "contact:edge = '"//trim(c%edge)//"' needs the built-in rectangle; with a Gmsh "// &
                           "mesh name a physical curve: boundary = '...'"
                  return
               end if
            end if
            c%edge = lower(c%edge)
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
            ! the static engine solves the multiplier problem (13) only (docs/static.md)
            if (c%method == 'penalty' .and. (deck%solver%method == 'static' .or. deck%solver%compare_static)) then
               errmsg = 'solver:'//trim(merge("method = 'static'", 'compare_static   ', deck%solver%method == 'static'))// &
                        " needs contact:method = 'lagrange': the static engine solves the multiplier problem (13), "// &
                        'not the penalty one'
               return
            end if
         end associate
      end if
      stat = 0
      errmsg = ''
   contains
      !> check_finite on every real of the deck (NaN, Inf, |x| > max_magnitude), naming it.
      logical function any_not_finite() result(bad)
         integer :: j
         bad = .true.
         associate (m => deck%mesh, a => deck%material, c => deck%contact, s => deck%solver)
            if (check_finite('mesh:lx', m%lx, errmsg)) return
            if (check_finite('mesh:ly', m%ly, errmsg)) return
            if (check_finite('material:young', a%young, errmsg)) return
            if (check_finite('material:poisson', a%poisson, errmsg)) return
            if (check_finite('material:density', a%density, errmsg)) return
            do j = 1, size(deck%dirichlet)
               if (edge_not_finite(deck%dirichlet(j), 'dirichlet#'//str(j))) return
            end do
            do j = 1, size(deck%traction)
               if (edge_not_finite(deck%traction(j), 'traction#'//str(j))) return
            end do
            if (c%present) then
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
            end if
            if (check_finite('solver:dt', s%dt, errmsg)) return
            if (check_finite('solver:dt_factor', s%dt_factor, errmsg)) return
            if (check_finite('solver:t_ramp', s%t_ramp, errmsg)) return
            if (check_finite('solver:t_end', s%t_end, errmsg)) return
            if (check_finite('solver:alpha', s%alpha, errmsg)) return
            if (check_finite('solver:tol_residual', s%tol_residual, errmsg)) return
            if (check_finite('solver:tol_kinetic', s%tol_kinetic, errmsg)) return
            if (check_finite('solver:mass_scaling', s%mass_scaling, errmsg)) return
            if (check_finite('initial:velocity', deck%initial%velocity, errmsg)) return
            if (check_finite('output:snapshot_times', deck%output%snapshot_times, errmsg)) return
         end associate
         bad = .false.
      end function any_not_finite

      logical function edge_not_finite(cfg, group) result(bad)
         type(edge_load_cfg_t), intent(in) :: cfg
         character(len=*), intent(in) :: group
         bad = .true.
         if (check_finite(group//':xmin', cfg%xmin, errmsg)) return
         if (check_finite(group//':xmax', cfg%xmax, errmsg)) return
         if (check_finite(group//':ymin', cfg%ymin, errmsg)) return
         if (check_finite(group//':ymax', cfg%ymax, errmsg)) return
         if (check_finite(group//':values', cfg%values, errmsg)) return
         if (check_finite(group//':times', cfg%times, errmsg)) return
         bad = .false.
      end function edge_not_finite

      !> The message for a group that names neither an edge nor a boundary (both empty, e.g.
      !> after --set "contact:boundary=''"): what to give, for the mesh the deck has.
      function no_place(g) result(msg)
         character(len=*), intent(in) :: g
         character(len=:), allocatable :: msg
         if (len_trim(deck%mesh%file) > 0) then
            msg = g//": boundary is empty: give boundary = '<physical curve>' of the Gmsh mesh "// &
                  trim(deck%mesh%file)
         else
            msg = g//": edge is empty: give edge = "//join(edges, ' | ')//" (the built-in rectangle's sides)"
         end if
      end function no_place

      subroutine validate_edge_load(cfg, group, k)
         type(edge_load_cfg_t), intent(inout) :: cfg
         character(len=*), intent(in) :: group
         integer, intent(in) :: k
         character(len=:), allocatable :: g
         integer :: ntimes, j
         g = 'line '//str(cfg%line)//': &'//group//' (#'//str(k)//')'
         stat = 2
         if (len_trim(cfg%boundary) > 0) then
            if (len_trim(cfg%edge) > 0) then
               errmsg = g//': give edge or boundary, not both'
               return
            end if
            if (len_trim(deck%mesh%file) == 0) then
               errmsg = g//": boundary = '"//trim(cfg%boundary)//"' needs a Gmsh mesh (mesh:file); the "// &
                        "built-in rectangle takes edge = 'bottom' | 'right' | 'top' | 'left'"
               return
            end if
         else if (len_trim(cfg%edge) == 0) then
            errmsg = no_place(g)
            return
         else
            if (edge_id(cfg%edge) == 0) then
               errmsg = g//": edge = '"//trim(cfg%edge)//"' is not one of "//join(edges, ', ')// &
                        " (or give boundary = '<physical curve>' with a Gmsh mesh)"
               return
            end if
            if (len_trim(deck%mesh%file) > 0) then
               errmsg = g//": edge = '"//trim(cfg%edge)//"' needs the built-in rectangle; with a Gmsh mesh "// &
                        "name a physical curve: boundary = '...'"
               return
            end if
         end if
         cfg%edge = lower(cfg%edge)
         cfg%component = lower(cfg%component)
         if (group == 'traction') then
            if (.not. any(cfg%component == [character(len=16) :: 'x', 'y', 'normal', 'tangential'])) then
               errmsg = g//": component = '"//trim(cfg%component)//"' is not one of 'x', 'y', 'normal', 'tangential'"
               return
            end if
         else if (.not. any(cfg%component == [character(len=16) :: 'x', 'y'])) then
            errmsg = g//": component = '"//trim(cfg%component)//"' is not one of 'x', 'y'"
            return
         end if
         if (.not. (cfg%xmin <= cfg%xmax .and. cfg%ymin <= cfg%ymax)) then
            errmsg = g//': the range needs xmin <= xmax and ymin <= ymax'
            return
         end if
         cfg%nstage = count(cfg%values /= unset)
         if (cfg%nstage == 0) then
            errmsg = g//': values is required (one value per load stage)'
            return
         end if
         if (any(cfg%values(cfg%nstage + 1:) /= unset)) then
            errmsg = g//': values must be given from the first entry on'
            return
         end if
         ntimes = count(cfg%times /= unset)
         if (ntimes == 0) then
            if (cfg%nstage > 1) then
               errmsg = g//': '//str(cfg%nstage)//' stages need times (the end time of each stage, s)'
               return
            end if
            if (deck%solver%t_ramp == unset) then
               errmsg = g//': no times given and solver:t_ramp is not set (the ramp duration, s)'
               return
            end if
            cfg%times(1) = deck%solver%t_ramp
         else if (ntimes /= cfg%nstage .or. any(cfg%times(cfg%nstage + 1:) /= unset)) then
            errmsg = g//': times needs one entry per value ('//str(cfg%nstage)//')'
            return
         end if
         if (.not. cfg%times(1) > 0) then
            errmsg = g//': times(1) = '//str(cfg%times(1))//' must be > 0'
            return
         end if
         do j = 2, cfg%nstage
            if (.not. cfg%times(j) > cfg%times(j - 1)) then
               errmsg = g//': times must increase strictly (times('//str(j)//') = '//str(cfg%times(j))//')'
               return
            end if
         end do
         stat = 1
      end subroutine validate_edge_load
   end subroutine validate

   pure logical function ends_with(s, tail)
      character(len=*), intent(in) :: s, tail
      integer :: n
      n = len_trim(s)
      ends_with = .false.
      if (n >= len(tail)) ends_with = lower(s(n - len(tail) + 1:n)) == tail
   end function ends_with

   pure function upper2(s) result(t)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: t
      integer :: i, c
      t = s
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c >= iachar('a') .and. c <= iachar('z')) t(i:i) = achar(c - 32)
      end do
   end function upper2

   ! ---- echo -------------------------------------------------------------------------------

   !> The effective values as a deck (reading it back gives the same values).
   function echo(deck) result(text)
      type(deck_t), intent(in) :: deck
      character(len=:), allocatable :: text
      character(len=1), parameter :: nl = new_line('a')
      integer :: i

      if (len_trim(deck%mesh%file) > 0) then
         text = '&mesh'//nl//kv('file', q(deck%mesh%file))//kv('level', str(deck%mesh%level))//'/'//nl
      else
         text = '&mesh'//nl// &
                kv('lx', str(deck%mesh%lx))//kv('ly', str(deck%mesh%ly))// &
                kv('nx', str(deck%mesh%nx))//kv('ny', str(deck%mesh%ny))// &
                kv('level', str(deck%mesh%level))//'/'//nl
      end if
      text = text//'&material'//nl// &
             kv('young', str(deck%material%young))//kv('poisson', str(deck%material%poisson))// &
             kv('density', str(deck%material%density))//'/'//nl
      do i = 1, size(deck%dirichlet)
         text = text//'&dirichlet'//nl//edge_load(deck%dirichlet(i))//'/'//nl
      end do
      do i = 1, size(deck%traction)
         text = text//'&traction'//nl//edge_load(deck%traction(i))//'/'//nl
      end do
      if (deck%contact%present) then
         associate (c => deck%contact)
            text = text//'&contact'//nl//where(c%edge, c%boundary)//range_text(c%xmin, c%xmax, c%ymin, c%ymax)// &
                   kv('obstacle', q(c%obstacle))
            if (c%obstacle == 'circle') then
               text = text//kv('obstacle_center', reals(c%obstacle_center))// &
                      kv('obstacle_radius', str(c%obstacle_radius))//kv('obstacle_side', q(c%obstacle_side))
            else
               text = text//kv('obstacle_point', reals(c%obstacle_point))// &
                      kv('obstacle_normal', reals(c%obstacle_normal))
            end if
            if (all(c%origin /= unset)) text = text//kv('origin', reals(c%origin))
            text = text//kv('direction', q(c%direction))//kv('multiplier', q(c%multiplier))// &
                   kv('friction', q(c%friction))
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
            text = text//kv('tresca_scope', q(c%tresca_scope))//kv('method', q(c%method))
            if (c%method == 'penalty') text = text//kv('penalty_stiffness', str(c%penalty_stiffness))
            text = text//'/'//nl
         end associate
      end if
      associate (s => deck%solver)
         text = text//'&solver'//nl//kv('dt', str(s%dt))//kv('dt_factor', str(s%dt_factor))// &
                kv('allow_unstable', str(s%allow_unstable))
         if (s%t_ramp /= unset) text = text//kv('t_ramp', str(s%t_ramp))
         text = text//kv('t_end', str(s%t_end))//kv('max_steps', str(s%max_steps))// &
                kv('damping', q(s%damping))//kv('alpha', str(s%alpha))// &
                kv('damping_interval', str(s%damping_interval))// &
                kv('tol_residual', str(s%tol_residual))//kv('tol_kinetic', str(s%tol_kinetic))// &
                kv('check_interval', str(s%check_interval))// &
                kv('power_iterations', str(s%power_iterations))//kv('dt_limit', q(s%dt_limit))// &
                kv('mass_scaling', str(s%mass_scaling))//kv('method', q(s%method))// &
                kv('static_increments', str(s%static_increments))//kv('compare_static', str(s%compare_static))// &
                kv('static_iterations', str(s%static_iterations))//kv('static_splits', str(s%static_splits))// &
                kv('convergence_test', q(s%convergence_test))//'/'//nl
      end associate
      text = text//'&initial'//nl//kv('velocity', reals(deck%initial%velocity))//'/'//nl
      text = text//'&output'//nl//kv('history_interval', str(deck%output%history_interval))// &
             kv('xdmf', str(deck%output%xdmf))//kv('progress', str(deck%output%progress))
      if (deck%output%nsnapshot > 0) text = text//kv('snapshot_times', &
                                                     reals(deck%output%snapshot_times(1:deck%output%nsnapshot)))
      text = text//'/'//nl
   contains
      function kv(key, value) result(line)
         character(len=*), intent(in) :: key, value
         character(len=:), allocatable :: line
         line = '   '//key//' = '//value//nl
      end function kv
      !> a quoted text; control characters escaped (printable), so that the echo is plain text
      function q(s) result(t)
         character(len=*), intent(in) :: s
         character(len=:), allocatable :: t
         t = "'"//printable(trim(s))//"'"
      end function q
      function reals(a) result(t)
         real(wp), intent(in) :: a(:)
         character(len=:), allocatable :: t
         integer :: j
         t = ''
         do j = 1, size(a)
            if (j > 1) t = t//', '
            t = t//str(a(j))
         end do
      end function reals
      function range_text(x0, x1, y0, y1) result(t)
         real(wp), intent(in) :: x0, x1, y0, y1
         character(len=:), allocatable :: t
         t = ''
         if (x0 /= -unset) t = t//kv('xmin', str(x0))
         if (x1 /= unset) t = t//kv('xmax', str(x1))
         if (y0 /= -unset) t = t//kv('ymin', str(y0))
         if (y1 /= unset) t = t//kv('ymax', str(y1))
      end function range_text
      function where(edge, boundary) result(t)
         character(len=*), intent(in) :: edge, boundary
         character(len=:), allocatable :: t
         if (len_trim(boundary) > 0) then
            t = kv('boundary', q(boundary))
         else
            t = kv('edge', q(edge))
         end if
      end function where
      function edge_load(cfg) result(t)
         type(edge_load_cfg_t), intent(in) :: cfg
         character(len=:), allocatable :: t
         t = where(cfg%edge, cfg%boundary)//range_text(cfg%xmin, cfg%xmax, cfg%ymin, cfg%ymax)// &
             kv('component', q(cfg%component))//kv('values', reals(cfg%values(1:cfg%nstage)))// &
             kv('times', reals(cfg%times(1:cfg%nstage)))
      end function edge_load
   end function echo
end module contact2d_deck
