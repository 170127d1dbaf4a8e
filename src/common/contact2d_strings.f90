!> Small string helpers for messages and echoes.
module contact2d_strings
   use contact2d_kinds, only: wp, i8
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use, intrinsic :: ieee_exceptions, only: ieee_status_type, ieee_get_status, ieee_set_status, &
                                            ieee_set_halting_mode, ieee_usual
   implicit none
   private
   public :: str, lower, join, fixed, sci, printable

   !> Shortest text that reads back to the same value (reals), or the plain integer.
   interface str
      module procedure str_real, str_int, str_i8, str_logical
   end interface str

contains

   function str_real(x) result(s)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=40) :: buf
      character(len=20) :: fmt
      character(len=:), allocatable :: digits, sign
      real(wp) :: back
      integer :: d, ios, e, epos, point
      type(ieee_status_type) :: saved
      if (x == 0) then
         s = '0'
         return
      end if
      if (x /= x .or. abs(x) > huge(x)) then
         write (buf, *) x
         s = trim(adjustl(buf))
         return
      end if
      ! fewest significant digits that read back to x; near huge(x) a short text rounds up past
      ! it, and the read overflows: halting off, so that the Debug build does not trap
      call ieee_get_status(saved)
      call ieee_set_halting_mode(ieee_usual, .false.)
      do d = 1, 17
         write (fmt, '(a,i0,a,i0,a)') '(es', d + 10, '.', d - 1, 'e3)'
         write (buf, fmt) x
         read (buf, *, iostat=ios) back
         if (ios == 0 .and. back == x) exit
      end do
      call ieee_set_status(saved)
      buf = adjustl(buf)
      sign = ''
      if (buf(1:1) == '-') then
         sign = '-'
         buf = buf(2:)
      end if
      epos = index(buf, 'E')
      read (buf(epos + 1:), *) e
      digits = buf(1:1)//buf(3:epos - 1)          ! mantissa digits without the point
      do while (len(digits) > 1 .and. digits(len(digits):) == '0')
         digits = digits(:len(digits) - 1)
      end do
      if (e >= -4 .and. e < 7) then
         if (e >= 0) then
            if (len(digits) <= e + 1) then
               s = digits//repeat('0', e + 1 - len(digits))
            else
               point = e + 1
               s = digits(1:point)//'.'//digits(point + 1:)
            end if
         else
            s = '0.'//repeat('0', -e - 1)//digits
         end if
      else
         if (len(digits) > 1) then
            s = digits(1:1)//'.'//digits(2:)//'e'//str_int(e)
         else
            s = digits//'e'//str_int(e)
         end if
      end if
      s = sign//s
   end function str_real

   function str_int(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function str_int

   function str_i8(i) result(s)
      integer(i8), intent(in) :: i
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function str_i8

   function str_logical(l) result(s)
      logical, intent(in) :: l
      character(len=:), allocatable :: s
      if (l) then
         s = '.true.'
      else
         s = '.false.'
      end if
   end function str_logical

   !> Lower-case ASCII copy.
   pure function lower(s) result(t)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: t
      integer :: i, c
      t = s
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c >= iachar('A') .and. c <= iachar('Z')) t(i:i) = achar(c + 32)
      end do
   end function lower

   !> Join words with a separator, quoting each with ' '.
   function join(words, sep) result(s)
      character(len=*), intent(in) :: words(:)
      character(len=*), intent(in) :: sep
      character(len=:), allocatable :: s
      integer :: i
      s = ''
      do i = 1, size(words)
         if (i > 1) s = s//sep
         s = s//"'"//trim(words(i))//"'"
      end do
   end function join
   !> A real with a fixed number of decimals.
   function fixed(x, decimals) result(s)
      real(wp), intent(in) :: x
      integer, intent(in) :: decimals
      character(len=:), allocatable :: s
      character(len=32) :: buf, fmt
      if (.not. ieee_is_finite(x)) then
         s = sci(x)
         return
      else if (abs(x) >= 1.0e15_wp) then
         s = sci(x)    ! f0.d would not fit the buffer
         return
      end if
      write (fmt, '(a,i0,a)') '(f0.', decimals, ')'
      write (buf, fmt) x
      s = trim(buf)
      if (s(1:1) == '.') s = '0'//s
   end function fixed

   !> A real in short scientific notation, 4 significant digits: 1.500E+05, 4.457E-122. The
   !> exponent field has room for three digits (an Ew.d edit descriptor without Ee drops the
   !> letter E for |exponent| > 99: 4.457-122, F2018 13.7.2.3.3); a leading 0 of it is dropped.
   function sci(x) result(s)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      integer :: k
      write (buf, '(es12.3e3)') x
      s = trim(adjustl(buf))
      k = index(s, 'E')
      if (k > 0 .and. len(s) == k + 4) then
         if (s(k + 2:k + 2) == '0') s = s(:k + 1)//s(k + 3:)
      end if
   end function sci

   !> s with every control character (codes 0-31 and 127: newline, carriage return, escape,
   !> ...) written as \xNN in hexadecimal, so that a message or echo is one line of plain text
   !> on a terminal whatever the input held. Other bytes (UTF-8 text included) are kept.
   pure function printable(s) result(t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: t
      character(len=*), parameter :: hex = '0123456789abcdef'
      integer :: i, c
      t = ''
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c < 32 .or. c == 127) then
            t = t//'\x'//hex(c/16 + 1:c/16 + 1)//hex(mod(c, 16) + 1:mod(c, 16) + 1)
         else
            t = t//s(i:i)
         end if
      end do
   end function printable

end module contact2d_strings
