!> The deck variables of Tresca friction (contact2d_friction_tresca, docs/friction.md): the
!> uniform `threshold` or the piecewise-linear profile `threshold_abscissa`/`threshold_values`,
!> and `tresca_scope`, with their defaults, their namelist read, their checks and their echo.
!> The &contact reader (contact2d_deck_contact) routes to this module every assignment of a
!> name it claims (tresca_claims), so that a new parameter of the law touches this file (and
!> its row in docs/deck.md) only.
module contact2d_friction_tresca_input
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower
   use contact2d_checks, only: check_finite
   use contact2d_deck_syntax, only: unset, max_points, line_len, read_failed, too_long, kv, quoted, reals
   implicit none
   private
   public :: tresca_input_t, tresca_names, tresca_claims, tresca_input_read, tresca_input_too_long
   public :: tresca_input_not_finite, tresca_input_count, tresca_input_unused, tresca_input_validate
   public :: tresca_input_echo, tresca_scope_echo, scope_len

   !> The &contact variables of the law (blank-separated).
   character(len=*), parameter :: tresca_names = 'threshold threshold_abscissa threshold_values tresca_scope'
   !> Longest accepted tresca_scope.
   integer, parameter :: scope_len = 8

   !> Tresca's deck variables. tresca_scope is held at line_len characters while the deck is
   !> read, so that an over-long value is refused (tresca_input_too_long), never cut.
   type :: tresca_input_t
      real(wp) :: threshold = 0                    !< uniform threshold s [MPa], >= 0
      real(wp) :: threshold_abscissa(max_points) = unset  !< abscissae of a piecewise-linear s [mm]
      real(wp) :: threshold_values(max_points) = unset    !< s at those abscissae [MPa]
      integer :: npoints = 0                       !< derived: points of the s profile (0: uniform)
      character(len=line_len) :: tresca_scope = 'all'  !< 'all' (as in the paper) | 'contact'
   end type tresca_input_t

contains

   !> name (lower case, no subscript) is a variable of this law.
   pure logical function tresca_claims(name)
      character(len=*), intent(in) :: name
      tresca_claims = index(' '//tresca_names//' ', ' '//name//' ') > 0
   end function tresca_claims

   !> Read one assignment (namelist records '&contact', text, '/'); variables: every &contact
   !> variable, for the did-you-mean of read_failed; where: the message's prefix.
   subroutine tresca_input_read(records, where, variables, cfg, stat, errmsg)
      character(len=*), intent(in) :: records(:), where, variables
      type(tresca_input_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: threshold, threshold_abscissa(max_points), threshold_values(max_points)
      character(len=line_len) :: tresca_scope
      integer :: ios
      character(len=256) :: msg
      namelist /contact/ threshold, threshold_abscissa, threshold_values, tresca_scope
      threshold = cfg%threshold; threshold_abscissa = cfg%threshold_abscissa
      threshold_values = cfg%threshold_values; tresca_scope = cfg%tresca_scope
      read (records, nml=contact, iostat=ios, iomsg=msg)
      if (read_failed(ios, msg, variables, where, stat, errmsg)) return
      cfg%threshold = threshold; cfg%threshold_abscissa = threshold_abscissa
      cfg%threshold_values = threshold_values; cfg%tresca_scope = tresca_scope
   end subroutine tresca_input_read

   !> A string longer than its field (scope_len) is refused; true if so.
   logical function tresca_input_too_long(cfg, where, stat, errmsg) result(bad)
      type(tresca_input_t), intent(in) :: cfg
      character(len=*), intent(in) :: where
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = too_long(where, 'tresca_scope', cfg%tresca_scope, scope_len, stat, errmsg)
   end function tresca_input_too_long

   !> check_finite on every real of the law; true if one is bad.
   logical function tresca_input_not_finite(cfg, errmsg) result(bad)
      type(tresca_input_t), intent(in) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('contact:threshold', cfg%threshold, errmsg)) return
      if (check_finite('contact:threshold_abscissa', cfg%threshold_abscissa, errmsg)) return
      if (check_finite('contact:threshold_values', cfg%threshold_values, errmsg)) return
      bad = .false.
   end function tresca_input_not_finite

   !> The points of the profile (npoints); true if abscissae and values differ in number.
   logical function tresca_input_count(cfg, errmsg) result(bad)
      type(tresca_input_t), intent(inout) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      cfg%npoints = count(cfg%threshold_abscissa /= unset)
      bad = count(cfg%threshold_values /= unset) /= cfg%npoints
      if (bad) errmsg = 'contact: threshold_abscissa and threshold_values need the same number of entries'
   end function tresca_input_count

   !> A threshold given while friction is another law: true, with the message. A zero
   !> threshold is no friction law of its own, so it goes with any law: `--set
   !> contact:friction='coulomb' --set contact:threshold=0` switches a Tresca deck to Coulomb.
   logical function tresca_input_unused(cfg, friction, errmsg) result(bad)
      type(tresca_input_t), intent(in) :: cfg
      character(len=*), intent(in) :: friction
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = friction /= 'tresca' .and. (cfg%threshold /= 0 .or. cfg%npoints > 0)
      if (bad) errmsg = "contact: a threshold is given but friction = '"//trim(friction)//"'; use friction = 'tresca'"
   end function tresca_input_unused

   !> The threshold (uniform or profile) and tresca_scope (lower-cased); friction: the chosen
   !> law (Coulomb acts where F_n > 0 and takes no other scope). True if refused.
   logical function tresca_input_validate(cfg, friction, errmsg) result(bad)
      type(tresca_input_t), intent(inout) :: cfg
      character(len=*), intent(in) :: friction
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: i
      bad = .true.
      if (cfg%npoints > 0 .and. cfg%threshold /= 0) then
         errmsg = 'contact: give either threshold or threshold_abscissa/threshold_values, not both'
         return
      end if
      if (.not. cfg%threshold >= 0) then
         errmsg = 'contact:threshold = '//str(cfg%threshold)//' must be >= 0 (MPa)'
         return
      end if
      if (cfg%npoints > 0) then
         if (any(cfg%threshold_abscissa(cfg%npoints + 1:) /= unset) .or. &
             any(cfg%threshold_values(cfg%npoints + 1:) /= unset)) then
            errmsg = 'contact: threshold_abscissa/threshold_values must be given from the first entry on'
            return
         end if
         if (any(cfg%threshold_values(1:cfg%npoints) < 0)) then
            errmsg = 'contact:threshold_values must all be >= 0 (MPa)'
            return
         end if
         do i = 2, cfg%npoints
            if (.not. cfg%threshold_abscissa(i) > cfg%threshold_abscissa(i - 1)) then
               errmsg = 'contact:threshold_abscissa must increase strictly (entry '//str(i)//')'
               return
            end if
         end do
      end if
      cfg%tresca_scope = lower(cfg%tresca_scope)
      if (.not. any(cfg%tresca_scope == [character(len=scope_len) :: 'all', 'contact'])) then
         errmsg = "contact:tresca_scope = '"//trim(cfg%tresca_scope)//"' is not one of 'all', 'contact'"
         return
      end if
      if (friction == 'coulomb' .and. cfg%tresca_scope /= 'all') then
         errmsg = "contact:tresca_scope = '"//trim(cfg%tresca_scope)//"' applies to Tresca only; "// &
                  "Coulomb friction acts where F_n > 0"
         return
      end if
      bad = .false.
   end function tresca_input_validate

   !> The law's threshold echo lines (when it is the chosen law).
   function tresca_input_echo(cfg) result(text)
      type(tresca_input_t), intent(in) :: cfg
      character(len=:), allocatable :: text
      if (cfg%npoints > 0) then
         text = kv('threshold_abscissa', reals(cfg%threshold_abscissa(1:cfg%npoints)))// &
                kv('threshold_values', reals(cfg%threshold_values(1:cfg%npoints)))
      else
         text = kv('threshold', str(cfg%threshold))
      end if
   end function tresca_input_echo

   !> The echo line of tresca_scope (written whatever the law: a frictionless deck may carry it).
   function tresca_scope_echo(cfg) result(text)
      type(tresca_input_t), intent(in) :: cfg
      character(len=:), allocatable :: text
      text = kv('tresca_scope', quoted(cfg%tresca_scope))
   end function tresca_scope_echo
end module contact2d_friction_tresca_input
