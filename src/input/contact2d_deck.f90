!> The input deck (docs/deck.md documents every variable; docs/architecture.md, "Input", how a
!> feature reads its variables): the deck core. It reads the lines and finds the groups
!> (contact2d_deck_blocks), parses the --set overrides, checks every value as text first
!> (value_problem), hands each group occurrence with its overrides to its group's module, which
!> reads it with its own namelist, then validates each group in a fixed order and runs the
!> checks that span groups, and assembles the echo of the effective values.
!>
!> Each group (mesh, material, dirichlet/traction, contact, solver, initial, output) owns its
!> cfg type with its defaults (there and nowhere else), its namelist read, its checks and its
!> echo lines, in src/input/contact2d_deck_<group>.f90. To add a variable to a group: declare it
!> in the group's cfg type and its namelist, add it to the group's list of variables
!> (<group>_variables: did-you-mean suggestions; a logical also to <group>_logicals), read a
!> string into a local of length line_len and check it with too_long() against its field, add
!> a real to the group's <group>_cfg_not_finite (check_finite of contact2d_checks, which must
!> run before any comparison of the value), then range-check it in <group>_cfg_validate and
!> echo it in <group>_cfg_echo. Derived quantities are checked in the model with
!> check_positive. Before any read, value_problem reads every value of the text (deck and
!> --set): literals beyond the double range or equal to the 'not given' marker are refused
!> there, so a marker left in a variable after the read always means "not given".
module contact2d_deck
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower, join
   use contact2d_checks, only: max_magnitude
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use, intrinsic :: ieee_exceptions, only: ieee_status_type, ieee_get_status, ieee_set_status, &
                                            ieee_set_halting_mode, ieee_usual
   use contact2d_deck_syntax, only: unset, max_stages, max_points, line_len, blanks, override_t, edge_id, &
                                    syntax_only, assigned_names
   use contact2d_deck_blocks, only: block_t, group_names, read_lines, split_blocks
   use contact2d_deck_mesh, only: mesh_cfg_t, mesh_variables, mesh_cfg_read, mesh_cfg_not_finite, &
                                  mesh_cfg_validate, mesh_cfg_echo
   use contact2d_deck_material, only: material_cfg_t, material_variables, material_cfg_read, &
                                      material_cfg_not_finite, material_cfg_validate, material_cfg_echo
   use contact2d_deck_body, only: body_cfg_t, body_variables, body_cfg_read, body_cfg_not_finite, &
                                  body_cfg_validate, body_cfg_echo
   use contact2d_deck_loads, only: edge_load_cfg_t, edge_load_variables, edge_load_cfg_read, &
                                   edge_load_cfg_not_finite, edge_load_cfg_validate, edge_load_cfg_echo
   use contact2d_deck_contact, only: contact_cfg_t, contact_variables, contact_cfg_read, contact_cfg_not_finite, &
                                     contact_cfg_validate, contact_cfg_echo, contact_cfg_publish, &
                                     contact_default_name, contact_name_refused
   use contact2d_deck_solver, only: solver_cfg_t, solver_variables, solver_logicals, solver_cfg_read, &
                                    solver_cfg_not_finite, solver_cfg_validate, solver_cfg_echo
   use contact2d_deck_initial, only: initial_cfg_t, initial_variables, initial_cfg_read, initial_cfg_not_finite, &
                                     initial_cfg_validate, initial_cfg_echo
   use contact2d_deck_output, only: output_cfg_t, output_variables, output_logicals, output_cfg_read, &
                                    output_cfg_not_finite, output_cfg_validate, output_cfg_echo
   implicit none
   private
   public :: deck_t, deck_read, deck_blame, mesh_cfg_t, material_cfg_t, edge_load_cfg_t, contact_cfg_t
   public :: solver_cfg_t, output_cfg_t, initial_cfg_t, unset, max_stages, max_points, edge_id, group_names
   public :: group_variables, body_cfg_t

   !> The variables of each group (of group_names), from the group modules (test_deck checks
   !> that each is accepted); for suggestions.
   character(len=*), parameter :: group_variables(9) = [character(len=420) :: &
      mesh_variables, material_variables, edge_load_variables, edge_load_variables, contact_variables, &
      solver_variables, output_variables, initial_variables, body_variables]

   !> The logical variables (group:variable). Their values are checked as text before the
   !> namelist read: Fortran reads any word whose first letter after an optional '.' is T or F
   !> as a logical (F2018 13.7.3), so `xdmf = fish` would read as .false.
   character(len=*), parameter :: logical_vars(4) = [character(len=21) :: 'solver:'//solver_logicals, &
                                                      'output:'//output_logicals]
   !> The spellings of a logical value accepted (lower case).
   character(len=*), parameter :: logical_words(10) = [character(len=7) :: '.true.', '.false.', 't', 'f', &
                                                        '.t.', '.f.', '.t', '.f', 'true', 'false']

   !> A whole deck after overrides and validation.
   type :: deck_t
      character(len=:), allocatable :: path        !< deck file as given
      character(len=:), allocatable :: text        !< deck file contents
      character(len=:), allocatable :: effective   !< echo of the effective values (a valid deck)
      type(mesh_cfg_t) :: mesh
      type(material_cfg_t) :: material
      !> the &body groups (none: one body, every element, &material)
      type(body_cfg_t), allocatable :: body(:)
      type(edge_load_cfg_t), allocatable :: dirichlet(:)
      type(edge_load_cfg_t), allocatable :: traction(:)
      !> the &contact groups, one per contact pair (none: no contact)
      type(contact_cfg_t), allocatable :: contacts(:)
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

contains

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
         if (g == 'dirichlet' .or. g == 'traction' .or. g == 'body') then
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

   ! ---- overrides and values as text ------------------------------------------------------

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
         if (group == 'body' .and. nocc == 0) then
            errmsg = "--set '"//spec//"': the deck has no &body group"
            return
         end if
         if (group == 'contact') then
            ! a --set without a number changes the first &contact (the one pair of most decks)
            if (ovr(i)%index > nocc) then
               errmsg = "--set '"//spec//"': the deck has only "//str(nocc)//' &'//group//' groups'
               return
            end if
            ovr(i)%index = max(ovr(i)%index, 1)
         else if (group == 'dirichlet' .or. group == 'traction' .or. group == 'body') then
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

   ! ---- dispatch to the group readers -------------------------------------------------------

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
      integer :: b, nd, nt, nb, nc, k, at
      character(len=:), allocatable :: where, label

      stat = 0
      errmsg = ''
      ! every value as text first (value_problem), the deck's groups, then the --set ones
      nd = 0
      nt = 0
      nb = 0
      nc = 0
      do b = 1, size(blocks)
         label = trim(blocks(b)%name)
         if (label == 'dirichlet') then
            nd = nd + 1
            label = label//'#'//str(nd)
         else if (label == 'traction') then
            nt = nt + 1
            label = label//'#'//str(nt)
         else if (label == 'body') then
            nb = nb + 1
            label = label//'#'//str(nb)
         else if (label == 'contact') then
            nc = nc + 1
            if (nc > 1) label = label//'#'//str(nc)
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
         if (label == 'dirichlet' .or. label == 'traction' .or. label == 'body') &
            label = label//'#'//str(max(ovr(k)%index, 1))
         if (label == 'contact' .and. ovr(k)%index > 1) label = label//'#'//str(ovr(k)%index)
         errmsg = value_problem([ovr(k)%assignment], trim(ovr(k)%group), label, at)
         if (len(errmsg) > 0) then
            stat = 1
            errmsg = "--set '"//ovr(k)%spec//"': "//errmsg
            return
         end if
      end do
      allocate (deck%dirichlet(count(blocks%name == 'dirichlet')))
      allocate (deck%traction(count(blocks%name == 'traction')))
      allocate (deck%body(count(blocks%name == 'body')))
      allocate (deck%contacts(count(blocks%name == 'contact')))
      nd = 0
      nt = 0
      nb = 0
      nc = 0
      ! singletons absent from the deck keep their defaults but still take their overrides
      do k = 1, size(group_names)
         if (any(blocks%name == group_names(k))) cycle
         where = path//': &'//trim(group_names(k))//': '
         select case (trim(group_names(k)))
         case ('mesh'); call mesh_cfg_read(none, pick(ovr, 'mesh', 1), where, deck%mesh, stat, errmsg)
         case ('material'); call material_cfg_read(none, pick(ovr, 'material', 1), where, deck%material, stat, errmsg)
         case ('solver'); call solver_cfg_read(none, pick(ovr, 'solver', 1), where, deck%solver, stat, errmsg)
         case ('output'); call output_cfg_read(none, pick(ovr, 'output', 1), where, deck%output, stat, errmsg)
         case ('initial'); call initial_cfg_read(none, pick(ovr, 'initial', 1), where, deck%initial, stat, errmsg)
         end select
         if (stat /= 0) return
      end do
      do b = 1, size(blocks)
         where = path//':'//str(blocks(b)%first)//': &'//trim(blocks(b)%name)//': '
         associate (blk => lines(blocks(b)%first:blocks(b)%last))
            select case (trim(blocks(b)%name))
            case ('mesh'); call mesh_cfg_read(blk, pick(ovr, 'mesh', 1), where, deck%mesh, stat, errmsg)
            case ('material'); call material_cfg_read(blk, pick(ovr, 'material', 1), where, deck%material, stat, errmsg)
            case ('solver'); call solver_cfg_read(blk, pick(ovr, 'solver', 1), where, deck%solver, stat, errmsg)
            case ('output'); call output_cfg_read(blk, pick(ovr, 'output', 1), where, deck%output, stat, errmsg)
            case ('initial'); call initial_cfg_read(blk, pick(ovr, 'initial', 1), where, deck%initial, stat, errmsg)
            case ('contact')
               nc = nc + 1
               deck%contacts(nc)%present = .true.
               call contact_cfg_read(blk, pick(ovr, 'contact', nc), where, deck%contacts(nc), stat, errmsg)
            case ('dirichlet')
               nd = nd + 1
               deck%dirichlet(nd)%line = blocks(b)%first
               call edge_load_cfg_read(blk, 'dirichlet', pick(ovr, 'dirichlet', nd), where, deck%dirichlet(nd), stat, errmsg)
            case ('traction')
               nt = nt + 1
               deck%traction(nt)%line = blocks(b)%first
               call edge_load_cfg_read(blk, 'traction', pick(ovr, 'traction', nt), where, deck%traction(nt), stat, errmsg)
            case ('body')
               nb = nb + 1
               deck%body(nb)%line = blocks(b)%first
               call body_cfg_read(blk, pick(ovr, 'body', nb), where, deck%body(nb), stat, errmsg)
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
   ! ---- validation: each group in turn, then the checks that span groups --------------------

   !> Check every value right after reading; fill derived values (stage counts, default times).
   !> The order is fixed (the first refused value is the one named): every real of every group
   !> finite, then mesh, material, solver, initial (and what it means for the engine), output,
   !> the loads and the end time, contact and its engine.
   subroutine validate(deck, stat, errmsg)
      type(deck_t), intent(inout) :: deck
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp) :: last_stage
      logical :: t_end_default
      integer :: i, j

      stat = 1
      errmsg = ''
      ! every real first: finite and of sane magnitude, before any comparison (contact2d_checks)
      if (any_not_finite(deck, errmsg)) return
      if (mesh_cfg_validate(deck%mesh, errmsg)) return
      ! &material: the material of the one body; with &body groups the default of their values
      if (size(deck%body) == 0) then
         if (material_cfg_validate(deck%material, errmsg)) return
      end if
      do i = 1, size(deck%body)
         if (body_cfg_validate(deck%body(i), i, deck%body(1:i - 1), deck%material, deck%mesh%file, errmsg)) return
      end do
      if (solver_cfg_validate(deck%solver, errmsg)) return
      if (initial_cfg_validate(deck%initial, errmsg)) return
      if (initial_state_refused(deck, errmsg)) return
      if (output_cfg_validate(deck%output, errmsg)) return

      last_stage = 0
      do i = 1, size(deck%dirichlet)
         if (edge_load_cfg_validate(deck%dirichlet(i), 'dirichlet', i, deck%mesh%file, deck%solver%t_ramp, errmsg)) then
            stat = 2
            return
         end if
         last_stage = max(last_stage, deck%dirichlet(i)%times(deck%dirichlet(i)%nstage))
      end do
      do i = 1, size(deck%traction)
         if (edge_load_cfg_validate(deck%traction(i), 'traction', i, deck%mesh%file, deck%solver%t_ramp, errmsg)) then
            stat = 2
            return
         end if
         last_stage = max(last_stage, deck%traction(i)%times(deck%traction(i)%nstage))
      end do
      ! no &dirichlet is fine where contact holds the body: the model's rigid-motion check
      ! (contact2d_rigid, docs/static.md "Bodies held by contact") refuses a free mechanism
      t_end_default = deck%solver%t_end == 0
      if (deck%solver%t_end == 0) then
         deck%solver%t_end = 10*last_stage
      else if (deck%solver%t_end < last_stage) then
         errmsg = 'solver:t_end = '//str(deck%solver%t_end)//' ends before the last load stage ('// &
                  str(last_stage)//' s)'
         return
      end if

      do i = 1, size(deck%contacts)
         if (contact_cfg_validate(deck%contacts(i), deck%mesh%file, errmsg)) then
            ! the k-th group's messages say contact#k (the first's, contact, as before)
            if (i > 1 .and. index(errmsg, 'contact:') == 1) errmsg = 'contact#'//str(i)//errmsg(8:)
            return
         end if
         if (contact_name_refused(deck%contacts(i)%name, 'contact', errmsg)) then
            if (i > 1) errmsg = 'contact#'//str(i)//errmsg(8:)
            return
         end if
         if (len_trim(deck%contacts(i)%name) == 0) deck%contacts(i)%name = contact_default_name(i)
         do j = 1, i - 1
            if (deck%contacts(j)%name == deck%contacts(i)%name) then
               errmsg = "contact#"//str(i)//":name = '"//trim(deck%contacts(i)%name)//"' is the name of "// &
                        'contact#'//str(j)//' too; each pair needs its own name'
               return
            end if
         end do
      end do
      ! the static engine condenses onto the unknowns of one contact chain (docs/static.md)
      if (size(deck%contacts) > 1 .and. (deck%solver%method == 'static' .or. deck%solver%compare_static)) then
         errmsg = 'solver:'//trim(merge("method = 'static'", 'compare_static   ', deck%solver%method == 'static'))// &
                  ' solves one contact pair; the deck has '//str(size(deck%contacts))//' &contact groups'
         return
      end if
      do i = 1, size(deck%contacts)
       associate (c => deck%contacts(i))
         ! the static engine solves the multiplier problem (13) only (docs/static.md)
         if (c%method == 'penalty' .and. (deck%solver%method == 'static' .or. deck%solver%compare_static)) then
            errmsg = 'solver:'//trim(merge("method = 'static'", 'compare_static   ', deck%solver%method == 'static'))// &
                     " needs contact:method = 'lagrange': the static engine solves the multiplier problem (13), "// &
                     'not the penalty one'
            return
         end if
         ! contact between two bodies (contact:master): the explicit engine only, so far
         if (len_trim(c%master) > 0 .and. (deck%solver%method == 'static' .or. deck%solver%compare_static)) then
            errmsg = 'solver:'//trim(merge("method = 'static'", 'compare_static   ', deck%solver%method == 'static'))// &
                     " refuses contact:master = '"//trim(c%master)//"': contact between two bodies "// &
                     'has the explicit engine only (docs/geometry.md "Two bodies")'
            return
         end if
         ! a moving obstacle, or the current configuration: the static engine solves one
         ! equilibrium in the initial configuration, and the quasi-static answer of a dragged
         ! frictional contact depends on the path (docs/geometry.md "Moving obstacles")
         if (c%motion%current() .and. (deck%solver%method == 'static' .or. deck%solver%compare_static)) then
            errmsg = 'solver:'//trim(merge("method = 'static'", 'compare_static   ', deck%solver%method == 'static'))// &
                     ' refuses '//trim(merge("a moving obstacle (contact:obstacle_motion_times)", &
                                             "contact:geometry = 'current'                     ", &
                                             c%motion%moving()))// &
                     ': the static engine solves in the initial configuration, and a dragged frictional '// &
                     'contact has no single quasi-static answer (it depends on the path)'
            return
         end if
         ! the default end time counts the obstacle's motion stages as load stages
         if (t_end_default .and. c%motion%moving()) deck%solver%t_end = &
            max(deck%solver%t_end, 10*max(last_stage, c%motion%obstacle_motion_times(c%motion%nstage)))
       end associate
      end do
      ! the obstacles' and friction laws' values under the names the model reads
      do i = 1, size(deck%contacts)
         call contact_cfg_publish(deck%contacts(i))
      end do
      stat = 0
      errmsg = ''
   end subroutine validate

   !> check_finite on every real of the deck (NaN, Inf, |x| > max_magnitude), naming it: each
   !> group's own list, in the order of the groups in the deck's documentation.
   logical function any_not_finite(deck, errmsg) result(bad)
      type(deck_t), intent(in) :: deck
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: j
      bad = .true.
      if (mesh_cfg_not_finite(deck%mesh, errmsg)) return
      if (material_cfg_not_finite(deck%material, errmsg)) return
      do j = 1, size(deck%body)
         if (body_cfg_not_finite(deck%body(j), 'body#'//str(j), errmsg)) return
      end do
      do j = 1, size(deck%dirichlet)
         if (edge_load_cfg_not_finite(deck%dirichlet(j), 'dirichlet#'//str(j), errmsg)) return
      end do
      do j = 1, size(deck%traction)
         if (edge_load_cfg_not_finite(deck%traction(j), 'traction#'//str(j), errmsg)) return
      end do
      do j = 1, size(deck%contacts)
         if (contact_cfg_not_finite(deck%contacts(j), errmsg)) then
            if (j > 1 .and. index(errmsg, 'contact:') == 1) errmsg = 'contact#'//str(j)//errmsg(8:)
            return
         end if
      end do
      if (solver_cfg_not_finite(deck%solver, errmsg)) return
      if (initial_cfg_not_finite(deck%initial, errmsg)) return
      if (output_cfg_not_finite(deck%output, errmsg)) return
      bad = .false.
   end function any_not_finite

   !> What the initial state means for the run: with damping = 'none' a non-zero velocity makes
   !> the run dynamic (no convergence test unless solver:convergence_test = 'on'; t_end bounds
   !> it); the static engine and mass scaling refuse a velocity. Fills deck%dynamic and
   !> deck%convergence_test; true if refused.
   logical function initial_state_refused(deck, errmsg) result(bad)
      type(deck_t), intent(inout) :: deck
      character(len=:), allocatable, intent(inout) :: errmsg
      logical :: moving
      integer :: b
      character(len=:), allocatable :: what
      bad = .true.
      ! an initial velocity: initial:velocity, or a body's own (&body velocity)
      moving = any(deck%initial%velocity /= 0)
      what = "initial:velocity = "//str(deck%initial%velocity(1))//", "//str(deck%initial%velocity(2))
      do b = 1, size(deck%body)
         if (all(deck%body(b)%velocity /= unset)) then
            if (any(deck%body(b)%velocity /= 0) .and. .not. moving) &
               what = "body#"//str(b)//":velocity = "//str(deck%body(b)%velocity(1))//", "//str(deck%body(b)%velocity(2))
            moving = moving .or. any(deck%body(b)%velocity /= 0)
         end if
      end do
      deck%dynamic = moving .and. deck%solver%damping == 'none'
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
      if (moving .and. (deck%solver%method == 'static' .or. deck%solver%compare_static)) then
         errmsg = what// &
                  " has no meaning for the static engine (solver:method = 'static' or compare_static)"
         return
      end if
      ! mass scaling changes the dynamics: refused with an initial velocity (the damping check
      ! of &solver refuses damping = 'none' and 'given')
      if (moving .and. deck%solver%mass_scaling > 0) then
         errmsg = "solver:mass_scaling = "//str(deck%solver%mass_scaling)//" is refused with "//what// &
                  " (fictitious mass changes the dynamics)"
         return
      end if
      bad = .false.
   end function initial_state_refused

   ! ---- echo -------------------------------------------------------------------------------

   !> The effective values as a deck (reading it back gives the same values): each group's own
   !> echo, in the order of the documentation.
   function echo(deck) result(text)
      type(deck_t), intent(in) :: deck
      character(len=:), allocatable :: text
      integer :: i
      text = mesh_cfg_echo(deck%mesh)
      ! with &body groups each body echoes its values (the defaults filled in): &material only
      ! when it is complete (it may be a partial default)
      if (size(deck%body) == 0 .or. all([deck%material%young, deck%material%poisson, deck%material%density] /= unset)) &
         text = text//material_cfg_echo(deck%material)
      do i = 1, size(deck%body)
         text = text//body_cfg_echo(deck%body(i))
      end do
      do i = 1, size(deck%dirichlet)
         text = text//edge_load_cfg_echo(deck%dirichlet(i), 'dirichlet')
      end do
      do i = 1, size(deck%traction)
         text = text//edge_load_cfg_echo(deck%traction(i), 'traction')
      end do
      do i = 1, size(deck%contacts)
         text = text//contact_cfg_echo(deck%contacts(i))
      end do
      text = text//solver_cfg_echo(deck%solver)//initial_cfg_echo(deck%initial)//output_cfg_echo(deck%output)
   end function echo
end module contact2d_deck
