!> The deck variables of the circular obstacle (contact2d_obstacle_circle, docs/geometry.md):
!> `obstacle_center`, `obstacle_radius` and `obstacle_side` of &contact, with their defaults,
!> their namelist read, their checks and their echo. The &contact reader
!> (contact2d_deck_contact) routes to this module every assignment of a name it claims
!> (circle_claims), so that a new parameter of the obstacle touches this file (and its row in
!> docs/deck.md) only.
module contact2d_obstacle_circle_input
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower
   use contact2d_checks, only: check_finite
   use contact2d_deck_syntax, only: unset, line_len, read_failed, too_long, kv, quoted, reals
   implicit none
   private
   public :: circle_input_t, circle_names, circle_claims, circle_input_read, circle_input_too_long
   public :: circle_input_not_finite, circle_input_side, circle_input_unused, circle_input_validate
   public :: circle_input_echo, side_len

   !> The &contact variables of the obstacle (blank-separated).
   character(len=*), parameter :: circle_names = 'obstacle_center obstacle_radius obstacle_side'
   !> Longest accepted obstacle_side.
   integer, parameter :: side_len = 8

   !> The circle's deck variables. obstacle_side is held at line_len characters while the deck
   !> is read, so that an over-long value is refused (circle_input_too_long), never cut.
   type :: circle_input_t
      real(wp) :: obstacle_center(2) = [unset, unset]  !< circle centre [mm]
      real(wp) :: obstacle_radius = unset          !< circle radius [mm], > 0
      character(len=line_len) :: obstacle_side = 'outside'  !< body 'outside' (indenter) | 'inside' (cavity)
   end type circle_input_t

contains

   !> name (lower case, no subscript) is a variable of this obstacle.
   pure logical function circle_claims(name)
      character(len=*), intent(in) :: name
      circle_claims = index(' '//circle_names//' ', ' '//name//' ') > 0
   end function circle_claims

   !> Read one assignment (namelist records '&contact', text, '/'); variables: every &contact
   !> variable, for the did-you-mean of read_failed; where: the message's prefix.
   subroutine circle_input_read(records, where, variables, cfg, stat, errmsg)
      character(len=*), intent(in) :: records(:), where, variables
      type(circle_input_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: obstacle_center(2), obstacle_radius
      character(len=line_len) :: obstacle_side
      integer :: ios
      character(len=256) :: msg
      namelist /contact/ obstacle_center, obstacle_radius, obstacle_side
      obstacle_center = cfg%obstacle_center; obstacle_radius = cfg%obstacle_radius
      obstacle_side = cfg%obstacle_side
      read (records, nml=contact, iostat=ios, iomsg=msg)
      if (read_failed(ios, msg, variables, where, stat, errmsg)) return
      cfg%obstacle_center = obstacle_center; cfg%obstacle_radius = obstacle_radius
      cfg%obstacle_side = obstacle_side
   end subroutine circle_input_read

   !> A string longer than its field (side_len) is refused; true if so.
   logical function circle_input_too_long(cfg, where, stat, errmsg) result(bad)
      type(circle_input_t), intent(in) :: cfg
      character(len=*), intent(in) :: where
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = too_long(where, 'obstacle_side', cfg%obstacle_side, side_len, stat, errmsg)
   end function circle_input_too_long

   !> check_finite on every real of the obstacle; true if one is bad.
   logical function circle_input_not_finite(cfg, errmsg) result(bad)
      type(circle_input_t), intent(in) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('contact:obstacle_center', cfg%obstacle_center, errmsg)) return
      if (check_finite('contact:obstacle_radius', cfg%obstacle_radius, errmsg)) return
      bad = .false.
   end function circle_input_not_finite

   !> obstacle_side (lower-cased) is a known side; checked whatever the obstacle, as its
   !> default goes with any. True if refused.
   logical function circle_input_side(cfg, errmsg) result(bad)
      type(circle_input_t), intent(inout) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      cfg%obstacle_side = lower(cfg%obstacle_side)
      bad = .not. any(cfg%obstacle_side == [character(len=side_len) :: 'outside', 'inside'])
      if (bad) errmsg = "contact:obstacle_side = '"//trim(cfg%obstacle_side)//"' is not one of 'outside', 'inside'"
   end function circle_input_side

   !> The centre or the radius given while the obstacle is another shape: true, with the message.
   logical function circle_input_unused(cfg, obstacle, errmsg) result(bad)
      type(circle_input_t), intent(in) :: cfg
      character(len=*), intent(in) :: obstacle
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = obstacle /= 'circle' .and. (any(cfg%obstacle_center /= unset) .or. cfg%obstacle_radius /= unset)
      if (bad) errmsg = "contact:obstacle_center/obstacle_radius are set but obstacle = '"//trim(obstacle)// &
                        "' ignores them; use obstacle = 'circle'"
   end function circle_input_unused

   !> The circle needs its centre and a radius > 0; true if refused.
   logical function circle_input_validate(cfg, errmsg) result(bad)
      type(circle_input_t), intent(in) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (any(cfg%obstacle_center == unset)) then
         errmsg = "contact:obstacle = 'circle' needs obstacle_center (mm)"
         return
      end if
      if (cfg%obstacle_radius == unset) then
         errmsg = "contact:obstacle = 'circle' needs obstacle_radius (mm)"
         return
      end if
      if (.not. cfg%obstacle_radius > 0) then
         errmsg = 'contact:obstacle_radius = '//str(cfg%obstacle_radius)//' must be > 0 (mm)'
         return
      end if
      bad = .false.
   end function circle_input_validate

   !> The obstacle's echo lines (when it is the chosen obstacle).
   function circle_input_echo(cfg) result(text)
      type(circle_input_t), intent(in) :: cfg
      character(len=:), allocatable :: text
      text = kv('obstacle_center', reals(cfg%obstacle_center))//kv('obstacle_radius', str(cfg%obstacle_radius))// &
             kv('obstacle_side', quoted(cfg%obstacle_side))
   end function circle_input_echo
end module contact2d_obstacle_circle_input
