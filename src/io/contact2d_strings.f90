!> Small string helpers for messages and echoes.
module contact2d_strings
   use contact2d_kinds, only: wp, i8
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: str, lower, join, fixed, sci

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
      if (x == 0) then
         s = '0'
         return
      end if
      if (x /= x .or. abs(x) > huge(x)) then
         write (buf, *) x
         s = trim(adjustl(buf))
         return
      end if
      ! fewest significant digits that read back to x
      do d = 1, 17
         write (fmt, '(a,i0,a,i0,a)') '(es', d + 10, '.', d - 1, 'e3)'
         write (buf, fmt) x
         read (buf, *, iostat=ios) back
         if (ios == 0 .and. back == x) exit
      end do
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

   !> A real in short scientific notation.
   function sci(x) result(s)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      write (buf, '(es10.3)') x
      s = trim(adjustl(buf))
   end function sci

end module contact2d_strings
