!> What every group of the deck shares (docs/architecture.md, "Input"): the 'not given'
!> markers, the namelist syntax seen as text (syntax_only, assigned_names), a failed namelist
!> read turned into one message (read_failed, with the did-you-mean of nearest_names), string
!> values refused when too long (too_long), the place of a boundary group (an edge of the
!> built-in rectangle or a Gmsh physical curve) and the pieces of the effective-deck echo.
!>
!> The group modules (contact2d_deck_mesh, ..._material, ..._loads, ..._contact, ..._solver,
!> ..._initial, ..._output) use this module; the deck core (contact2d_deck) uses them.
module contact2d_deck_syntax
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower, join, printable
   implicit none
   private
   public :: unset, unset_int, max_stages, max_points, line_len, blanks, override_t
   public :: syntax_only, assigned_names, is_name_char, is_letter, assignment_t, split_assignments
   public :: read_failed, too_long, nearest_names
   public :: edges, edge_id, place_problem, place_text, range_text
   public :: kv, quoted, reals, ends_with, upper2

   !> Marks a real variable the deck did not set.
   real(wp), parameter :: unset = huge(1.0_wp)
   !> Marks an integer variable the deck did not set.
   integer, parameter :: unset_int = -huge(1)
   !> Most stages of a load curve and most points of a threshold profile.
   integer, parameter :: max_stages = 16, max_points = 64
   !> Longest accepted deck line (longer lines are refused, never cut).
   integer, parameter :: line_len = 1024
   !> Blank characters of a deck line: space and tab.
   character(len=*), parameter :: blanks = ' '//achar(9)
   !> The sides of the built-in rectangle, in the order of edge_id.
   character(len=6), parameter :: edges(4) = [character(len=6) :: 'bottom', 'right', 'top', 'left']

   !> One --set override: group, 1-based occurrence (0: not given) and the assignment text.
   type :: override_t
      character(len=16) :: group = ''
      integer :: index = 0
      character(len=:), allocatable :: assignment
      character(len=:), allocatable :: spec
   end type override_t

   !> One assignment of a group's text, as namelist records that a reader of that group can
   !> read on their own: '&group', the assignment's text (its lines, comments kept), '/'.
   type :: assignment_t
      !> the variable's name in lower case, without subscript; '' for text before the first
      !> assignment (no assignment: the group's own reader reports what it is)
      character(len=:), allocatable :: name
      character(len=line_len + 16), allocatable :: records(:)
   end type assignment_t

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

   !> The variables a line of namelist syntax (from syntax_only) assigns: each 'name =' or
   !> 'name(subscript) =', in lower case without blanks, e.g. 'young', 'values(2)'.
   function assigned_names(code) result(names)
      character(len=*), intent(in) :: code
      character(len=line_len), allocatable :: names(:)
      integer, allocatable :: starts(:)
      call find_assignments(code, names, starts)
   end function assigned_names

   !> The assignments of a line of namelist syntax: their designators (as assigned_names) and
   !> the column where each name starts.
   subroutine find_assignments(code, names, starts)
      character(len=*), intent(in) :: code
      character(len=line_len), allocatable, intent(out) :: names(:)
      integer, allocatable, intent(out) :: starts(:)
      integer :: pos, k, close, first
      character(len=:), allocatable :: designator
      allocate (names(0), starts(0))
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
         first = pos
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
         if (code(k:k) == '=') then
            names = [character(len=line_len) :: names, designator]
            starts = [starts, first]
         end if
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
   end subroutine find_assignments

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

   !> The assignments of one group occurrence (its lines from '&group' to the closing '/', as
   !> split_blocks found them), in the order of the text: each from its name to the next name
   !> or the closing '/'. Quotes are followed across lines, so that text inside a string is
   !> never taken for a name. Non-blank text between the group name and the first assignment
   !> is one more part, with the name ''.
   function split_assignments(blk, group) result(parts)
      character(len=*), intent(in) :: blk(:)
      character(len=*), intent(in) :: group
      type(assignment_t), allocatable :: parts(:)
      character(len=len(blk)) :: code(size(blk))
      character(len=line_len), allocatable :: names(:), here(:)
      integer, allocatable :: at_line(:), at_col(:), cols(:)
      integer :: l, c0, l_end, c_end, k, slash
      character(len=1) :: quote
      ! the syntax of every line, the quote state carried from one line to the next
      quote = ' '
      do l = 1, size(blk)
         code(l) = code_of(blk(l), quote)
      end do
      ! the text starts after '&group' on the first line and ends before the closing '/'
      c0 = index(code(1), '&') + 1
      do while (c0 <= len(code(1)))
         if (.not. is_name_char(code(1)(c0:c0))) exit
         c0 = c0 + 1
      end do
      l_end = size(blk)
      c_end = len(blk) + 1
      do l = 1, size(blk)
         k = 1
         if (l == 1) k = c0
         slash = index(code(l)(k:), '/')
         if (slash > 0) then
            l_end = l
            c_end = k + slash - 1
            exit
         end if
      end do
      allocate (names(0), at_line(0), at_col(0))
      do l = 1, l_end
         call find_assignments(code(l), here, cols)
         do k = 1, size(cols)
            if (l == 1 .and. cols(k) < c0) cycle
            if (l == l_end .and. cols(k) >= c_end) cycle
            names = [character(len=line_len) :: names, here(k)]
            at_line = [at_line, l]
            at_col = [at_col, cols(k)]
         end do
      end do
      allocate (parts(0))
      if (size(names) == 0) then
         if (has_code(1, c0, l_end, c_end)) parts = [part('', 1, c0, l_end, c_end)]
         return
      end if
      if (has_code(1, c0, at_line(1), at_col(1))) parts = [part('', 1, c0, at_line(1), at_col(1))]
      do k = 1, size(names)
         if (k < size(names)) then
            parts = [parts, part(base(names(k)), at_line(k), at_col(k), at_line(k + 1), at_col(k + 1))]
         else
            parts = [parts, part(base(names(k)), at_line(k), at_col(k), l_end, c_end)]
         end if
      end do
   contains
      !> a line with quoted text and comments blanked; quote: the quote open at its start and end
      function code_of(line, quote) result(c)
         character(len=*), intent(in) :: line
         character(len=1), intent(inout) :: quote
         character(len=len(line)) :: c
         integer :: j
         c = line
         do j = 1, len(line)
            if (quote /= ' ') then
               if (line(j:j) == quote) then
                  quote = ' '
               else
                  c(j:j) = ' '
               end if
            else if (line(j:j) == "'" .or. line(j:j) == '"') then
               quote = line(j:j)
            else if (line(j:j) == '!') then
               c(j:) = ' '
               exit
            end if
         end do
      end function code_of
      !> the text from (l1, c1) up to (l2, c2), excluded, has syntax (not only blanks/comments)
      logical function has_code(l1, c1, l2, c2)
         integer, intent(in) :: l1, c1, l2, c2
         integer :: m
         has_code = .false.
         do m = l1, l2
            if (m == l1 .and. m == l2) then
               has_code = verify(code(m)(c1:c2 - 1), blanks) > 0
            else if (m == l1) then
               has_code = verify(code(m)(c1:), blanks) > 0
            else if (m == l2) then
               has_code = verify(code(m)(1:c2 - 1), blanks) > 0
            else
               has_code = verify(code(m), blanks) > 0
            end if
            if (has_code) return
         end do
      end function has_code
      !> the records '&group', the text from (l1, c1) up to (l2, c2) excluded, '/'
      function part(name, l1, c1, l2, c2) result(p)
         character(len=*), intent(in) :: name
         integer, intent(in) :: l1, c1, l2, c2
         type(assignment_t) :: p
         integer :: m
         p%name = name
         allocate (p%records(l2 - l1 + 3))
         p%records(1) = '&'//group
         do m = l1, l2
            if (m == l1 .and. m == l2) then
               p%records(2) = blk(m)(c1:c2 - 1)
            else if (m == l1) then
               p%records(2) = blk(m)(c1:)
            else if (m == l2) then
               p%records(m - l1 + 2) = blk(m)(1:c2 - 1)
            else
               p%records(m - l1 + 2) = blk(m)
            end if
         end do
         p%records(size(p%records)) = '/'
      end function part
      pure function base(designator) result(b)
         character(len=*), intent(in) :: designator
         character(len=:), allocatable :: b
         b = trim(designator(1:scan(designator//'(', '(') - 1))
      end function base
   end function split_assignments

   pure logical function is_name_char(ch)
      character(len=1), intent(in) :: ch
      is_name_char = is_letter(ch) .or. verify(ch, '0123456789_') == 0
   end function is_name_char

   pure logical function is_letter(ch)
      character(len=1), intent(in) :: ch
      is_letter = verify(ch, 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ') == 0
   end function is_letter

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

   !> "; did you mean 'young'?" for an unknown variable name of a group whose variables are
   !> the blank-separated list `variables`: the variables nearest to it in
   !> optimal-string-alignment distance (insertions, deletions, substitutions and swaps of two
   !> neighbours, each 1), when that distance is at most 1 for names of up to 4 letters and
   !> at most 2 beyond; '' when none is that near.
   function nearest_names(name, variables) result(hint)
      character(len=*), intent(in) :: name, variables
      character(len=:), allocatable :: hint, list, word, best
      integer :: p, e, d, dmin, nbest
      hint = ''
      list = trim(variables)//' '
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

   !> Turn a failed namelist read into a message; true if it failed. variables: the group's
   !> variable names, blank-separated (for the did-you-mean of a misspelled name).
   logical function read_failed(ios, msg, variables, where, stat, errmsg)
      integer, intent(in) :: ios
      character(len=*), intent(in) :: msg, variables, where
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
            errmsg = errmsg//nearest_names(name, variables)
         end if
      end if
   end function read_failed

   !> What is wrong with the place of a boundary group ('' if nothing): an `edge` of the
   !> built-in rectangle or a `boundary` (Gmsh physical curve), one of them, matching the mesh.
   !> g names the group in the message ('contact', 'line 7: &dirichlet (#1)'); sep joins it to
   !> a variable name (':' gives 'contact:edge', ': ' gives 'line 7: &dirichlet (#1): edge').
   function place_problem(g, sep, edge, boundary, mesh_file) result(msg)
      character(len=*), intent(in) :: g, sep, edge, boundary, mesh_file
      character(len=:), allocatable :: msg
      msg = ''
      if (len_trim(boundary) > 0) then
         if (len_trim(edge) > 0) then
            msg = g//': give edge or boundary, not both'
         else if (len_trim(mesh_file) == 0) then
            msg = g//sep//"boundary = '"//trim(boundary)//"' needs a Gmsh mesh (mesh:file); the "// &
                  "built-in rectangle takes edge = 'bottom' | 'right' | 'top' | 'left'"
         end if
      else if (len_trim(edge) == 0) then
         ! neither (both empty, e.g. after --set "contact:boundary=''"): what to give
         if (len_trim(mesh_file) > 0) then
            msg = g//": boundary is empty: give boundary = '<physical curve>' of the Gmsh mesh "// &
                  trim(mesh_file)
         else
            msg = g//": edge is empty: give edge = "//join(edges, ' | ')//" (the built-in rectangle's sides)"
         end if
      else if (edge_id(edge) == 0) then
         msg = g//sep//"edge = '"//trim(edge)//"' is not one of "//join(edges, ', ')// &
               " (or give boundary = '<physical curve>' with a Gmsh mesh)"
      else if (len_trim(mesh_file) > 0) then
         msg = g//sep//"edge = '"//trim(edge)//"' needs the built-in rectangle; with a Gmsh mesh "// &
               "name a physical curve: boundary = '...'"
      end if
   end function place_problem

   ! ---- pieces of the echo (the effective values as a deck) ----------------------------------

   !> One echo line: '   key = value'.
   function kv(key, value) result(line)
      character(len=*), intent(in) :: key, value
      character(len=:), allocatable :: line
      line = '   '//key//' = '//value//new_line('a')
   end function kv

   !> A quoted text; control characters escaped (printable), so that the echo is plain text.
   function quoted(s) result(t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: t
      t = "'"//printable(trim(s))//"'"
   end function quoted

   !> Reals as a namelist value list 'a, b, c'.
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

   !> The bounds of a coordinate range that were given.
   function range_text(x0, x1, y0, y1) result(t)
      real(wp), intent(in) :: x0, x1, y0, y1
      character(len=:), allocatable :: t
      t = ''
      if (x0 /= -unset) t = t//kv('xmin', str(x0))
      if (x1 /= unset) t = t//kv('xmax', str(x1))
      if (y0 /= -unset) t = t//kv('ymin', str(y0))
      if (y1 /= unset) t = t//kv('ymax', str(y1))
   end function range_text

   !> The place of a boundary group: its boundary when given, else its edge.
   function place_text(edge, boundary) result(t)
      character(len=*), intent(in) :: edge, boundary
      character(len=:), allocatable :: t
      if (len_trim(boundary) > 0) then
         t = kv('boundary', quoted(boundary))
      else
         t = kv('edge', quoted(edge))
      end if
   end function place_text

   pure logical function ends_with(s, tail)
      character(len=*), intent(in) :: s, tail
      integer :: n
      n = len_trim(s)
      ends_with = .false.
      if (n >= len(tail)) ends_with = lower(s(n - len(tail) + 1:n)) == tail
   end function ends_with

   !> s in upper case (ASCII letters).
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
end module contact2d_deck_syntax
