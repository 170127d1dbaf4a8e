!> Minimal stand-in for pFUnit 4's `funit` module, used only when pFUnit is not
!> installed (see cmake/Contact2dTesting.cmake and tests/README.md).
!>
!> Provides exactly what funitproc_fallback.py generates calls to, with
!> pFUnit's argument conventions and pass/fail semantics:
!>   assertEqual(expected, actual [, tolerance] [, message] [, location])
!>       real64 (any rank <= 3, tolerance real64, default 0 = exact),
!>       default integer (rank <= 3), logical (rank <= 3, message= keyword only),
!>       character scalars (leading/trailing blanks and tabs ignored, as pFUnit).
!>       A scalar `expected` is compared against every element of `actual`.
!>   assertRelativelyEqual(expected, actual, tolerance [, message]) real64:
!>       passes iff |e-a| <= tolerance*|e|; a zero expected value always fails.
!>   assertTrue/assertFalse(condition [, message]) scalar or 1-D logical.
!>   assertLessThan/LessThanOrEqual/GreaterThan/GreaterThanOrEqual(lhs, rhs)
!>       real64 or default integer (integer: message= keyword only), pass iff
!>       lhs <op> rhs.
!>   throw(message [, location]), anyExceptions(), type SourceLocation.
!> NaN never compares equal/ordered (the assertion fails, it does not trap).
!> Mixed kinds (e.g. integer expected with real64 actual) are rejected at
!> compile time, which is stricter than pFUnit.
module funit
   use, intrinsic :: iso_fortran_env, only: real64, int32, output_unit
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite, ieee_class, &
        ieee_positive_zero, ieee_negative_zero, operator(==)
   implicit none
   private

   public :: SourceLocation, throw, anyExceptions
   public :: assertEqual, assertRelativelyEqual, assertTrue, assertFalse
   public :: assertLessThan, assertLessThanOrEqual, assertGreaterThan, assertGreaterThanOrEqual
   public :: funit_run_test, funit_finish   ! used by the generated driver only

   type :: SourceLocation
      character(len=256) :: fileName = '<unknown file>'
      integer :: lineNumber = -1
   end type SourceLocation

   !> Private type: arguments after it can only be passed by keyword (as in pFUnit).
   type :: KeywordEnforcer
   end type KeywordEnforcer

   abstract interface
      subroutine funit_procedure()
      end subroutine funit_procedure
   end interface

   interface assertEqual
      module procedure eq_real, eq_real_tol, eq_int, eq_logical, eq_string
   end interface assertEqual
   interface assertRelativelyEqual
      module procedure rel_real
   end interface assertRelativelyEqual
   interface assertTrue
      module procedure true_0d, true_1d
   end interface assertTrue
   interface assertFalse
      module procedure false_0d, false_1d
   end interface assertFalse
   interface assertLessThan
      module procedure lt_real, lt_int
   end interface assertLessThan
   interface assertLessThanOrEqual
      module procedure le_real, le_int
   end interface assertLessThanOrEqual
   interface assertGreaterThan
      module procedure gt_real, gt_int
   end interface assertGreaterThan
   interface assertGreaterThanOrEqual
      module procedure ge_real, ge_int
   end interface assertGreaterThanOrEqual

   character(len=*), parameter :: NL = new_line('a')
   character(len=*), parameter :: RANK_MSG = 'assertion on an array of rank > 3: not supported by the fallback'
   character(len=:), allocatable :: failure_log   ! failures of the current test
   integer :: n_exceptions = 0, n_tests = 0, n_failed = 0

contains

   ! ---------------------------------------------------------------- runtime
   subroutine throw(message, location)
      character(*), intent(in) :: message
      type(SourceLocation), intent(in), optional :: location
      character(len=:), allocatable :: prefix
      prefix = ''
      if (present(location)) prefix = trim(location%fileName) // ':' // i2s(location%lineNumber) // ': '
      if (.not. allocated(failure_log)) failure_log = ''
      n_exceptions = n_exceptions + 1
      failure_log = failure_log // '    ' // prefix // message // NL
   end subroutine throw

   logical function anyExceptions()
      anyExceptions = n_exceptions > 0
   end function anyExceptions

   !> Run one test like pFUnit's TestCase%runBare: before; if it did not fail,
   !> the test and then after (also when the test failed).
   subroutine funit_run_test(suite, name, test, before, after)
      character(*), intent(in) :: suite, name
      procedure(funit_procedure) :: test
      procedure(funit_procedure), optional :: before, after
      n_exceptions = 0
      failure_log = ''
      write (output_unit, '(a)') '[ RUN      ] ' // suite // '::' // name
      flush (output_unit)
      if (present(before)) call before()
      if (n_exceptions == 0) then
         call test()
         if (present(after)) call after()
      end if
      n_tests = n_tests + 1
      if (n_exceptions == 0) then
         write (output_unit, '(a)') '[     PASS ] ' // suite // '::' // name
      else
         n_failed = n_failed + 1
         write (output_unit, '(a)') '[     FAIL ] ' // suite // '::' // name
         write (output_unit, '(a)', advance='no') failure_log
      end if
      flush (output_unit)
   end subroutine funit_run_test

   subroutine funit_finish(suite)
      character(*), intent(in) :: suite
      write (output_unit, '(a)') '[==========] ' // suite // ': ' // i2s(n_tests) // ' tests, ' &
           // i2s(n_failed) // ' failed'
      flush (output_unit)
      if (n_failed > 0) then
         write (output_unit, '(a)') 'Encountered 1 or more failures/errors during testing.'
         flush (output_unit)
         stop 1   ! exit status 1; unlike ERROR STOP, no gfortran backtrace (as pFUnit >= 4.2.3)
      end if
   end subroutine funit_finish

   ! ------------------------------------------------------------ assertEqual
   subroutine eq_real(expected, actual, message, location)
      real(real64), intent(in) :: expected(..), actual(..)
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call eq_real_tol(expected, actual, 0.0_real64, message, location)
   end subroutine eq_real

   subroutine eq_real_tol(expected, actual, tolerance, message, location)
      real(real64), intent(in) :: expected(..), actual(..), tolerance
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call check_equal('assertEqual', 'r', flat_r(expected), flat_r(actual), shape(expected), &
           shape(actual), tolerance, .false., message, location)
   end subroutine eq_real_tol

   subroutine eq_int(expected, actual, message, location)
      integer, intent(in) :: expected(..), actual(..)
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call check_equal('assertEqual', 'i', flat_i(expected), flat_i(actual), shape(expected), &
           shape(actual), 0.0_real64, .false., message, location)
   end subroutine eq_int

   subroutine eq_logical(expected, actual, unused, message, location)
      logical, intent(in) :: expected(..), actual(..)
      class(KeywordEnforcer), intent(in), optional :: unused
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      call check_equal('assertEqual', 'l', flat_l(expected), flat_l(actual), shape(expected), &
           shape(actual), 0.0_real64, .false., message, location)
   end subroutine eq_logical

   subroutine eq_string(expected, actual, message, location)
      character(*), intent(in) :: expected, actual
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (strip(expected) == strip(actual)) return
      call report('assertEqual', 'expected "' // expected // '" but found "' // actual // '"', &
           message, location)
   end subroutine eq_string

   subroutine rel_real(expected, actual, tolerance, message, location)
      real(real64), intent(in) :: expected(..), actual(..), tolerance
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call check_equal('assertRelativelyEqual', 'r', flat_r(expected), flat_r(actual), &
           shape(expected), shape(actual), tolerance, .true., message, location)
   end subroutine rel_real

   ! ------------------------------------------------------ assertTrue/False
   subroutine true_0d(condition, message, location)
      logical, intent(in) :: condition
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call check_equal('assertTrue', 'l', [1.0_real64], flat_l(condition), [integer ::], &
           [integer ::], 0.0_real64, .false., message, location)
   end subroutine true_0d

   subroutine true_1d(condition, message, location)
      logical, intent(in) :: condition(:)
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call check_equal('assertTrue', 'l', [1.0_real64], flat_l(condition), [integer ::], &
           shape(condition), 0.0_real64, .false., message, location)
   end subroutine true_1d

   subroutine false_0d(condition, message, location)
      logical, intent(in) :: condition
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call check_equal('assertFalse', 'l', [0.0_real64], flat_l(condition), [integer ::], &
           [integer ::], 0.0_real64, .false., message, location)
   end subroutine false_0d

   subroutine false_1d(condition, message, location)
      logical, intent(in) :: condition(:)
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call check_equal('assertFalse', 'l', [0.0_real64], flat_l(condition), [integer ::], &
           shape(condition), 0.0_real64, .false., message, location)
   end subroutine false_1d

   ! ------------------------------------------------------------- orderings
   subroutine lt_real(lhs, rhs, message, location)
      real(real64), intent(in) :: lhs(..), rhs(..)
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call check_order('assertLessThan', '<', 'r', flat_r(lhs), flat_r(rhs), shape(lhs), shape(rhs), &
           message, location)
   end subroutine lt_real

   subroutine le_real(lhs, rhs, message, location)
      real(real64), intent(in) :: lhs(..), rhs(..)
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call check_order('assertLessThanOrEqual', '<=', 'r', flat_r(lhs), flat_r(rhs), shape(lhs), shape(rhs), &
           message, location)
   end subroutine le_real

   subroutine gt_real(lhs, rhs, message, location)
      real(real64), intent(in) :: lhs(..), rhs(..)
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call check_order('assertGreaterThan', '>', 'r', flat_r(lhs), flat_r(rhs), shape(lhs), shape(rhs), &
           message, location)
   end subroutine gt_real

   subroutine ge_real(lhs, rhs, message, location)
      real(real64), intent(in) :: lhs(..), rhs(..)
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      call check_order('assertGreaterThanOrEqual', '>=', 'r', flat_r(lhs), flat_r(rhs), shape(lhs), shape(rhs), &
           message, location)
   end subroutine ge_real

   subroutine lt_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..), rhs(..)
      class(KeywordEnforcer), intent(in), optional :: unused
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      call check_order('assertLessThan', '<', 'i', flat_i(lhs), flat_i(rhs), shape(lhs), shape(rhs), &
           message, location)
   end subroutine lt_int

   subroutine le_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..), rhs(..)
      class(KeywordEnforcer), intent(in), optional :: unused
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      call check_order('assertLessThanOrEqual', '<=', 'i', flat_i(lhs), flat_i(rhs), shape(lhs), shape(rhs), &
           message, location)
   end subroutine le_int

   subroutine gt_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..), rhs(..)
      class(KeywordEnforcer), intent(in), optional :: unused
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      call check_order('assertGreaterThan', '>', 'i', flat_i(lhs), flat_i(rhs), shape(lhs), shape(rhs), &
           message, location)
   end subroutine gt_int

   subroutine ge_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..), rhs(..)
      class(KeywordEnforcer), intent(in), optional :: unused
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(unused)) continue
      call check_order('assertGreaterThanOrEqual', '>=', 'i', flat_i(lhs), flat_i(rhs), shape(lhs), shape(rhs), &
           message, location)
   end subroutine ge_int

   ! ------------------------------------------------------------------ cores
   !> Element-wise comparison of flattened values (integers and logicals are
   !> converted exactly to real64; fk = 'r'|'i'|'l' selects how they print).
   !> An empty eshp means a scalar `e` broadcast over every element of `a`.
   subroutine check_equal(kind, fk, e, a, eshp, ashp, tol, rel, message, location)
      character(*), intent(in) :: kind, fk
      real(real64), intent(in) :: e(:), a(:), tol
      integer, intent(in) :: eshp(:), ashp(:)
      logical, intent(in) :: rel
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      integer :: i, first, nbad
      real(real64) :: ei
      character(len=:), allocatable :: details

      if (.not. conforms(kind, eshp, ashp, message, location)) return
      first = 0
      nbad = 0
      do i = 1, size(a)
         if (.not. within(e(merge(1, i, size(eshp) == 0)), a(i), tol, rel)) then
            nbad = nbad + 1
            if (first == 0) first = i
         end if
      end do
      if (nbad == 0) return
      ei = e(merge(1, first, size(eshp) == 0))
      details = ''
      if (fk == 'r' .and. rel) then
         details = 'relative difference ' // reldiff(ei, a(first)) // ', relative tolerance ' // fmt(tol, 'r')
      else if (fk == 'r') then
         details = 'difference ' // diff(ei, a(first)) // ', tolerance ' // fmt(tol, 'r')
      end if
      call report(kind, 'expected ' // fmt(ei, fk) // ' but found ' // fmt(a(first), fk) &
           // where_str(first, nbad, ashp, details), message, location)
   end subroutine check_equal

   subroutine check_order(kind, op, fk, l, r, lshp, rshp, message, location)
      character(*), intent(in) :: kind, op, fk
      real(real64), intent(in) :: l(:), r(:)
      integer, intent(in) :: lshp(:), rshp(:)
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      integer :: i, first, nbad
      character(len=:), allocatable :: words

      if (.not. conforms(kind, lshp, rshp, message, location)) return
      first = 0
      nbad = 0
      do i = 1, size(r)
         if (.not. ordered(op, l(merge(1, i, size(lshp) == 0)), r(i))) then
            nbad = nbad + 1
            if (first == 0) first = i
         end if
      end do
      if (nbad == 0) return
      select case (op)
      case ('<');  words = ' to be less than '
      case ('<='); words = ' to be less than or equal to '
      case ('>');  words = ' to be greater than '
      case default; words = ' to be greater than or equal to '
      end select
      call report(kind, 'expected ' // fmt(l(merge(1, first, size(lshp) == 0)), fk) // words &
           // fmt(r(first), fk) // where_str(first, nbad, rshp, ''), message, location)
   end subroutine check_order

   !> pFUnit semantics; NaN never passes; written so no comparison touches a
   !> NaN and no subtraction overflows (safe under -ffpe-trap=invalid,overflow).
   logical function within(e, a, tol, rel)
      real(real64), intent(in) :: e, a, tol
      logical, intent(in) :: rel
      real(real64) :: bound
      within = .false.
      if (ieee_is_nan(e) .or. ieee_is_nan(a) .or. ieee_is_nan(tol)) return
      if (.not. (ieee_is_finite(e) .and. ieee_is_finite(a))) then
         if (.not. rel) within = ieee_class(e) == ieee_class(a)   ! same infinity
         return
      end if
      if (rel) then
         if (is_zero(e)) return            ! pFUnit: zero denominator always fails
         bound = tol * abs(e)
      else
         within = .not. (a < e .or. a > e)  ! exact equality, without -Wcompare-reals
         if (within) return
         bound = tol
      end if
      if (max(abs(e), abs(a)) < huge(e) / 2) then
         within = abs(a - e) <= bound
      else
         within = abs(a / 2 - e / 2) <= bound / 2
      end if
   end function within

   logical function ordered(op, l, r)
      character(*), intent(in) :: op
      real(real64), intent(in) :: l, r
      ordered = .false.
      if (ieee_is_nan(l) .or. ieee_is_nan(r)) return
      select case (op)
      case ('<');  ordered = l < r
      case ('<='); ordered = l <= r
      case ('>');  ordered = l > r
      case default; ordered = l >= r
      end select
   end function ordered

   ! ---------------------------------------------------------------- helpers
   logical function conforms(kind, eshp, ashp, message, location)
      character(*), intent(in) :: kind
      integer, intent(in) :: eshp(:), ashp(:)
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      conforms = size(eshp) == 0
      if (.not. conforms .and. size(eshp) == size(ashp)) conforms = all(eshp == ashp)
      if (.not. conforms) call report(kind, 'nonconforming arrays: expected shape ' // shp2s(eshp) &
           // ' but found shape ' // shp2s(ashp), message, location)
   end function conforms

   subroutine report(kind, text, message, location)
      character(*), intent(in) :: kind, text
      character(*), intent(in), optional :: message
      type(SourceLocation), intent(in), optional :: location
      if (present(message)) then
         if (len_trim(message) > 0) then
            call throw(kind // ' failure: ' // text // ' ' // trim(message), location)
            return
         end if
      end if
      call throw(kind // ' failure: ' // text, location)
   end subroutine report

   !> " at index [i,j] (details; n of m elements differ)" for arrays, " (details)" for scalars.
   function where_str(first, nbad, shp, details) result(s)
      integer, intent(in) :: first, nbad, shp(:)
      character(*), intent(in) :: details
      character(len=:), allocatable :: s, paren
      integer :: d, k, idx(size(shp))
      s = ''
      paren = details
      if (size(shp) > 0) then
         k = first - 1
         do d = 1, size(shp)
            idx(d) = mod(k, shp(d)) + 1
            k = k / shp(d)
         end do
         s = ' at index ' // shp2s(idx)
         if (len(paren) > 0) paren = paren // '; '
         paren = paren // i2s(nbad) // ' of ' // i2s(product(shp)) // ' elements differ'
      end if
      if (len(paren) > 0) s = s // ' (' // paren // ')'
   end function where_str

   function diff(e, a) result(s)
      real(real64), intent(in) :: e, a
      character(len=:), allocatable :: s
      s = 'n/a'
      if (ieee_is_finite(e) .and. ieee_is_finite(a)) then
         if (max(abs(e), abs(a)) < huge(e) / 2) s = fmt(a - e, 'r')
      end if
   end function diff

   function reldiff(e, a) result(s)
      real(real64), intent(in) :: e, a
      character(len=:), allocatable :: s
      real(real64) :: d
      s = 'n/a'
      if (is_zero(e)) s = 'undefined (expected value is zero)'
      if (is_zero(e) .or. .not. (ieee_is_finite(e) .and. ieee_is_finite(a))) return
      if (max(abs(e), abs(a)) >= huge(e) / 2) return
      d = a - e
      if (abs(e) >= 1.0_real64) then
         s = fmt(d / e, 'r')
      else if (abs(d) < abs(e) * huge(e)) then
         s = fmt(d / e, 'r')
      end if
   end function reldiff

   logical function is_zero(x)
      real(real64), intent(in) :: x
      is_zero = ieee_class(x) == ieee_positive_zero .or. ieee_class(x) == ieee_negative_zero
   end function is_zero

   function fmt(x, fk) result(s)
      real(real64), intent(in) :: x
      character(*), intent(in) :: fk
      character(len=:), allocatable :: s
      character(len=64) :: buf
      select case (fk)
      case ('i'); write (buf, '(i0)') int(x, int32)
      case ('l'); buf = merge('T', 'F', x > 0.5_real64)
      case default; write (buf, '(g0)') x
      end select
      s = trim(adjustl(buf))
   end function fmt

   function i2s(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      character(len=16) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function i2s

   function shp2s(v) result(s)
      integer, intent(in) :: v(:)
      character(len=:), allocatable :: s
      integer :: d
      s = '['
      do d = 1, size(v)
         s = s // i2s(v(d))
         if (d < size(v)) s = s // ','
      end do
      s = s // ']'
   end function shp2s

   !> pFUnit's default string comparison (TRIM_ALL): ignore leading/trailing blanks and tabs.
   function strip(str) result(s)
      character(*), intent(in) :: str
      character(len=:), allocatable :: s
      integer :: i, j
      i = 1
      j = len(str)
      do while (i <= j)
         if (str(i:i) /= ' ' .and. str(i:i) /= achar(9)) exit
         i = i + 1
      end do
      do while (j >= i)
         if (str(j:j) /= ' ' .and. str(j:j) /= achar(9)) exit
         j = j - 1
      end do
      s = str(i:j)
   end function strip

   function flat_r(x) result(v)
      real(real64), intent(in) :: x(..)
      real(real64), allocatable :: v(:)
      select rank (x)
      rank (0); v = [x]
      rank (1); v = x
      rank (2); v = reshape(x, [size(x)])
      rank (3); v = reshape(x, [size(x)])
      rank default; allocate (v(0)); call throw(RANK_MSG)
      end select
   end function flat_r

   function flat_i(x) result(v)
      integer, intent(in) :: x(..)
      real(real64), allocatable :: v(:)
      select rank (x)
      rank (0); v = [real(x, real64)]
      rank (1); v = real(x, real64)
      rank (2); v = reshape(real(x, real64), [size(x)])
      rank (3); v = reshape(real(x, real64), [size(x)])
      rank default; allocate (v(0)); call throw(RANK_MSG)
      end select
   end function flat_i

   function flat_l(x) result(v)
      logical, intent(in) :: x(..)
      real(real64), allocatable :: v(:)
      select rank (x)
      rank (0); v = [merge(1.0_real64, 0.0_real64, x)]
      rank (1); v = merge(1.0_real64, 0.0_real64, x)
      rank (2); v = reshape(merge(1.0_real64, 0.0_real64, x), [size(x)])
      rank (3); v = reshape(merge(1.0_real64, 0.0_real64, x), [size(x)])
      rank default; allocate (v(0)); call throw(RANK_MSG)
      end select
   end function flat_l

end module funit
