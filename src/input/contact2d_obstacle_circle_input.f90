!> The deck variables of the circular obstacle (contact2d_obstacle_circle, docs/geometry.md):
!> `obstacle_center`, `obstacle_radius` and `obstacle_side` of &contact, with their defaults,
!> their namelist read, their checks, their echo and the making of the obstacle. A member of
!> the input side of the obstacle seam (contact2d_obstacle_input): a new parameter of the
!> obstacle touches this file and the shape's own (and its row in docs/deck.md) only.
module contact2d_obstacle_circle_input
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower
   use contact2d_checks, only: check_finite
   use contact2d_obstacle, only: obstacle_t
   use contact2d_obstacle_circle, only: circle_obstacle_t
   use contact2d_obstacle_input, only: obstacle_input_t
   use contact2d_deck_syntax, only: unset, line_len, read_failed, too_long, kv, quoted, reals
   implicit none
   private
   public :: circle_input_t, circle_names, side_len

   !> The &contact variables of the obstacle (blank-separated).
   character(len=*), parameter :: circle_names = 'obstacle_center obstacle_radius obstacle_side'
   !> Longest accepted obstacle_side.
   integer, parameter :: side_len = 8

   !> The circle's deck variables. obstacle_side is held at line_len characters while the deck
   !> is read, so that an over-long value is refused (circle_input_too_long), never cut.
   type, extends(obstacle_input_t) :: circle_input_t
      real(wp) :: obstacle_center(2) = [unset, unset]  !< circle centre [mm]
      real(wp) :: obstacle_radius = unset          !< circle radius [mm], > 0
      character(len=line_len) :: obstacle_side = 'outside'  !< body 'outside' (indenter) | 'inside' (cavity)
   contains
      procedure :: name => circle_input_name
      procedure :: variables => circle_input_variables
      procedure :: read => circle_input_read
      procedure :: too_long => circle_input_too_long
      procedure :: not_finite => circle_input_not_finite
      procedure :: prepare => circle_input_side
      procedure :: validate_chosen => circle_input_validate
      procedure :: unused => circle_input_unused
      procedure :: echo => circle_input_echo
      procedure :: make => circle_input_make
   end type circle_input_t

contains

   function circle_input_name(this) result(text)
      class(circle_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = 'circle'
   end function circle_input_name

   function circle_input_variables(this) result(text)
      class(circle_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = circle_names
   end function circle_input_variables

   !> Read one assignment (namelist records '&contact', text, '/'); variables: every &contact
   !> variable, for the did-you-mean of read_failed; where: the message's prefix.
   subroutine circle_input_read(this, records, where, variables, stat, errmsg)
      class(circle_input_t), intent(inout) :: this
      character(len=*), intent(in) :: records(:), where, variables
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: obstacle_center(2), obstacle_radius
      character(len=line_len) :: obstacle_side
      integer :: ios
      character(len=256) :: msg
      namelist /contact/ obstacle_center, obstacle_radius, obstacle_side
      obstacle_center = this%obstacle_center; obstacle_radius = this%obstacle_radius
      obstacle_side = this%obstacle_side
      read (records, nml=contact, iostat=ios, iomsg=msg)
      if (read_failed(ios, msg, variables, where, stat, errmsg)) return
      this%obstacle_center = obstacle_center; this%obstacle_radius = obstacle_radius
      this%obstacle_side = obstacle_side
   end subroutine circle_input_read

   !> A string longer than its field (side_len) is refused; true if so.
   logical function circle_input_too_long(this, where, stat, errmsg) result(bad)
      class(circle_input_t), intent(in) :: this
      character(len=*), intent(in) :: where
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = too_long(where, 'obstacle_side', this%obstacle_side, side_len, stat, errmsg)
   end function circle_input_too_long

   !> check_finite on every real of the obstacle; true if one is bad.
   logical function circle_input_not_finite(this, errmsg) result(bad)
      class(circle_input_t), intent(in) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('contact:obstacle_center', this%obstacle_center, errmsg)) return
      if (check_finite('contact:obstacle_radius', this%obstacle_radius, errmsg)) return
      bad = .false.
   end function circle_input_not_finite

   !> obstacle_side (lower-cased) is a known side; checked whatever the obstacle, as its
   !> default goes with any. True if refused.
   logical function circle_input_side(this, errmsg) result(bad)
      class(circle_input_t), intent(inout) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      this%obstacle_side = lower(this%obstacle_side)
      bad = .not. any(this%obstacle_side == [character(len=side_len) :: 'outside', 'inside'])
      if (bad) errmsg = "contact:obstacle_side = '"//trim(this%obstacle_side)//"' is not one of 'outside', 'inside'"
   end function circle_input_side

   !> The centre or the radius given while the obstacle is another shape: true, with the message.
   logical function circle_input_unused(this, obstacle, errmsg) result(bad)
      class(circle_input_t), intent(in) :: this
      character(len=*), intent(in) :: obstacle
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = obstacle /= 'circle' .and. (any(this%obstacle_center /= unset) .or. this%obstacle_radius /= unset)
      if (bad) errmsg = "contact:obstacle_center/obstacle_radius are set but obstacle = '"//trim(obstacle)// &
                        "' ignores them; use obstacle = 'circle'"
   end function circle_input_unused

   !> The circle needs its centre and a radius > 0; true if refused.
   logical function circle_input_validate(this, errmsg) result(bad)
      class(circle_input_t), intent(inout) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (any(this%obstacle_center == unset)) then
         errmsg = "contact:obstacle = 'circle' needs obstacle_center (mm)"
         return
      end if
      if (this%obstacle_radius == unset) then
         errmsg = "contact:obstacle = 'circle' needs obstacle_radius (mm)"
         return
      end if
      if (.not. this%obstacle_radius > 0) then
         errmsg = 'contact:obstacle_radius = '//str(this%obstacle_radius)//' must be > 0 (mm)'
         return
      end if
      bad = .false.
   end function circle_input_validate

   !> The obstacle's echo lines (when it is the chosen obstacle).
   function circle_input_echo(this) result(text)
      class(circle_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = kv('obstacle_center', reals(this%obstacle_center))//kv('obstacle_radius', str(this%obstacle_radius))// &
             kv('obstacle_side', quoted(this%obstacle_side))
   end function circle_input_echo

   !> The circle of obstacle_center and obstacle_radius, the body outside or inside it.
   subroutine circle_input_make(this, obstacle)
      class(circle_input_t), intent(in) :: this
      class(obstacle_t), allocatable, intent(out) :: obstacle
      type(circle_obstacle_t) :: circle
      call circle%init(this%obstacle_center, this%obstacle_radius, trim(this%obstacle_side) == 'inside')
      allocate (obstacle, source=circle)
   end subroutine circle_input_make
end module contact2d_obstacle_circle_input
