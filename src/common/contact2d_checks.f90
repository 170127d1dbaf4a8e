!> Value checks for the deck and for derived quantities, each naming the variable.
!>
!> How to use them for a new deck variable (docs/deck.md, "Validation"):
!>   1. every real, scalar or array, goes through `check_finite('group:variable', x, errmsg)`
!>      FIRST, before any ordered comparison (<, >, ...) or arithmetic: in the Debug build
!>      (-ffpe-trap=invalid,overflow) comparing a NaN traps, these checks do not (they classify
!>      the bits with ieee_arithmetic and compare nothing). They refuse NaN, +-Infinity and
!>      magnitudes above `max_magnitude` (1e30 in the user's units: beyond any physical input,
!>      and low enough that set-up products cannot overflow). Values equal to +-huge are the
!>      deck's 'not given' marker and are skipped: the deck reader refuses a typed marker (and
!>      any literal beyond the double range) from the text before the read (value_problem).
!>   2. then the variable's own range: `check_range('group:variable', x, lo, hi, errmsg)` for a
!>      closed interval, or a plain test with its own message.
!>   3. derived quantities (masses, element stiffness, dt_critical) are checked before use with
!>      `check_positive('what (from which variables)', x, errmsg)`.
!> Each function returns .true. when the value is BAD, with a one-line errmsg, so a caller
!> writes `if (check_finite('mesh:lx', m%lx, errmsg)) return`.
module contact2d_checks
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan, ieee_class, ieee_negative_inf, &
                                            operator(==)
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   implicit none
   private
   public :: check_finite, check_range, check_positive, max_magnitude

   !> Largest accepted magnitude of any real in a deck.
   real(wp), parameter :: max_magnitude = 1.0e30_wp

   interface check_finite
      module procedure check_finite_scalar, check_finite_array
   end interface check_finite

contains

   !> A description of a non-finite value without arithmetic on it.
   function nonfinite_text(x) result(s)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: s
      if (ieee_is_nan(x)) then
         s = 'NaN'
      else if (ieee_class(x) == ieee_negative_inf) then
         s = '-Infinity'
      else
         s = '+Infinity'
      end if
   end function nonfinite_text

   !> Bad if x is NaN, infinite or larger in magnitude than max_magnitude.
   logical function check_finite_scalar(name, x, errmsg) result(bad)
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: x
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .not. ieee_is_finite(x)
      if (bad) then
         errmsg = name//' = '//nonfinite_text(x)//' must be finite'
         return
      end if
      if (abs(x) == huge(x)) return   ! the 'not given' marker
      bad = abs(x) > max_magnitude
      if (bad) errmsg = name//' = '//str(x)//' is out of range (|value| <= '//str(max_magnitude)//')'
   end function check_finite_scalar

   !> check_finite on every entry; the message names the entry.
   logical function check_finite_array(name, a, errmsg) result(bad)
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: a(:)
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: i
      bad = .false.
      do i = 1, size(a)
         bad = check_finite_scalar(name//'('//str(i)//')', a(i), errmsg)
         if (bad) return
      end do
   end function check_finite_array

   !> Bad if x (finite, already checked) is outside [lo, hi].
   logical function check_range(name, x, lo, hi, errmsg) result(bad)
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: x, lo, hi
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .not. (x >= lo .and. x <= hi)
      if (bad) errmsg = name//' = '//str(x)//' is out of range ['//str(lo)//', '//str(hi)//']'
   end function check_range

   !> Bad if a derived quantity is not finite or not > 0 (names what it comes from).
   logical function check_positive(name, x, errmsg) result(bad)
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: x
      character(len=:), allocatable, intent(inout) :: errmsg
      if (.not. ieee_is_finite(x)) then
         bad = .true.
         errmsg = name//' = '//nonfinite_text(x)//' is not finite'
         return
      end if
      bad = .not. x > 0
      if (bad) errmsg = name//' = '//str(x)//' must be > 0'
   end function check_positive
end module contact2d_checks
