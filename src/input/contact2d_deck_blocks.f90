!> The deck as text: its lines, read whole (never cut), and its groups, each a block of lines
!> from '&name' to the closing '/'. Text outside groups must be blank or a `!` comment; '&end'
!> and nested groups are refused; a variable given twice in one group is refused (the
!> namelist would keep the last value silently); only regular files up to max_deck_bytes are
!> read. The deck core (contact2d_deck) reads each block with its group's module.
module contact2d_deck_blocks
   use contact2d_strings, only: str, lower, join
   use contact2d_sys, only: sys_path_info, sys_strerror, kind_missing, kind_file, kind_dangling, kind_names
   use contact2d_deck_syntax, only: line_len, blanks, syntax_only, assigned_names, is_name_char
   use, intrinsic :: iso_c_binding, only: c_long_long
   implicit none
   private
   public :: block_t, group_names, read_lines, split_blocks

   !> Largest accepted deck file [bytes].
   integer, parameter :: max_deck_bytes = 1048576
   !> The groups of a deck: &mesh, &material, &solver, &output and &initial once each,
   !> &dirichlet, &traction, &body and &contact (one per contact pair) as many times as needed.
   character(len=9), parameter :: group_names(9) = [character(len=9) :: &
                                                    'mesh', 'material', 'dirichlet', 'traction', 'contact', 'solver', 'output', &
                                                    'initial', 'body']

   !> One group occurrence in the deck: its name, first and last line.
   type :: block_t
      character(len=16) :: name = ''
      integer :: first = 0, last = 0
   end type block_t

contains


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
         if (any(trim(blocks(i)%name) == [character(len=9) :: 'dirichlet', 'traction', 'body', 'contact'])) cycle
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
end module contact2d_deck_blocks
