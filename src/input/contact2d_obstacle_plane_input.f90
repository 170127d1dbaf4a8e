!> The deck variables of the plane obstacle (contact2d_obstacle_plane, docs/geometry.md):
!> `obstacle_point` and `obstacle_normal` of &contact, with their defaults (the line y = 0,
!> normal +y), their namelist read, their checks and their echo. The &contact reader
!> (contact2d_deck_contact) routes to this module every assignment of a name it claims
!> (plane_claims), so that a new parameter of the obstacle touches this file (and its row in
!> docs/deck.md) only.
module contact2d_obstacle_plane_input
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_checks, only: check_finite
   use contact2d_obstacle, only: obstacle_t
   use contact2d_obstacle_plane, only: plane_obstacle_t
   use contact2d_obstacle_input, only: obstacle_input_t
   use contact2d_deck_syntax, only: unset, read_failed, kv, reals
   implicit none
   private
   public :: plane_input_t, plane_names

   !> The &contact variables of the obstacle (blank-separated).
   character(len=*), parameter :: plane_names = 'obstacle_point obstacle_normal'
   !> The plane y = 0 with its normal +y when the deck gives no obstacle_point/normal.
   real(wp), parameter :: default_point(2) = [0.0_wp, 0.0_wp], default_normal(2) = [0.0_wp, 1.0_wp]

   !> The plane's deck variables.
   type, extends(obstacle_input_t) :: plane_input_t
      !> a point P of the obstacle line [mm] (not given: default_point)
      real(wp) :: obstacle_point(2) = [unset, unset]
      !> unit normal nu, obstacle -> body (not given: default_normal)
      real(wp) :: obstacle_normal(2) = [unset, unset]
   contains
      procedure :: name => plane_input_name
      procedure :: variables => plane_input_variables
      procedure :: read => plane_input_read
      procedure :: not_finite => plane_input_not_finite
      procedure :: unused => plane_input_unused
      procedure :: complete => plane_input_complete
      procedure :: validate_always => plane_input_validate
      procedure :: echo => plane_input_echo
      procedure :: make => plane_input_make
      procedure :: edge_warning => plane_input_edge_warning
   end type plane_input_t

contains

   function plane_input_name(this) result(text)
      class(plane_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = 'plane'
   end function plane_input_name

   function plane_input_variables(this) result(text)
      class(plane_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = plane_names
   end function plane_input_variables

   !> Read one assignment (namelist records '&contact', text, '/'); variables: every &contact
   !> variable, for the did-you-mean of read_failed; where: the message's prefix.
   subroutine plane_input_read(this, records, where, variables, stat, errmsg)
      class(plane_input_t), intent(inout) :: this
      character(len=*), intent(in) :: records(:), where, variables
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: obstacle_point(2), obstacle_normal(2)
      integer :: ios
      character(len=256) :: msg
      namelist /contact/ obstacle_point, obstacle_normal
      obstacle_point = this%obstacle_point; obstacle_normal = this%obstacle_normal
      read (records, nml=contact, iostat=ios, iomsg=msg)
      if (read_failed(ios, msg, variables, where, stat, errmsg)) return
      this%obstacle_point = obstacle_point; this%obstacle_normal = obstacle_normal
   end subroutine plane_input_read

   !> check_finite on every real of the obstacle; true if one is bad.
   logical function plane_input_not_finite(this, errmsg) result(bad)
      class(plane_input_t), intent(in) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('contact:obstacle_point', this%obstacle_point, errmsg)) return
      if (check_finite('contact:obstacle_normal', this%obstacle_normal, errmsg)) return
      bad = .false.
   end function plane_input_not_finite

   !> A variable of the plane given while the obstacle is another shape: true, with the message.
   logical function plane_input_unused(this, obstacle, errmsg) result(bad)
      class(plane_input_t), intent(in) :: this
      character(len=*), intent(in) :: obstacle
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = obstacle /= 'plane' .and. (any(this%obstacle_point /= unset) .or. any(this%obstacle_normal /= unset))
      if (bad) errmsg = "contact: obstacle_point and obstacle_normal are set but obstacle = '"//trim(obstacle)// &
                        "' ignores them (the circle is obstacle_center and obstacle_radius)"
   end function plane_input_unused

   !> Both components of each vector or none, then the defaults for those not given; true if
   !> refused.
   logical function plane_input_complete(this, errmsg) result(bad)
      class(plane_input_t), intent(inout) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = count(this%obstacle_point == unset) == 1 .or. count(this%obstacle_normal == unset) == 1
      if (bad) then
         errmsg = 'contact:obstacle_point and obstacle_normal take two components each (x, y)'
         return
      end if
      if (all(this%obstacle_point == unset)) this%obstacle_point = default_point
      if (all(this%obstacle_normal == unset)) this%obstacle_normal = default_normal
   end function plane_input_complete

   !> The normal is a unit vector (SPEC section 3: nu of unit length); true if refused.
   logical function plane_input_validate(this, errmsg) result(bad)
      class(plane_input_t), intent(inout) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: norm
      norm = norm2(this%obstacle_normal)
      bad = abs(norm - 1) > 1.0e-6_wp
      if (bad) errmsg = 'contact:obstacle_normal = '//str(this%obstacle_normal(1))//', '// &
                        str(this%obstacle_normal(2))//' must be a unit vector (length '//str(norm)//')'
   end function plane_input_validate

   !> The obstacle's echo lines (when it is the chosen obstacle).
   function plane_input_echo(this) result(text)
      class(plane_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = kv('obstacle_point', reals(this%obstacle_point))//kv('obstacle_normal', reals(this%obstacle_normal))
   end function plane_input_echo

   !> The plane through obstacle_point with normal obstacle_normal.
   subroutine plane_input_make(this, obstacle)
      class(plane_input_t), intent(in) :: this
      class(obstacle_t), allocatable, intent(out) :: obstacle
      type(plane_obstacle_t) :: plane
      call plane%init(this%obstacle_point, this%obstacle_normal)
      allocate (obstacle, source=plane)
   end subroutine plane_input_make

   !> A plane whose normal nu (from the obstacle into the body) points along the built-in
   !> edge's outward normal: no node can ever touch (a warning, not a refusal).
   function plane_input_edge_warning(this, edge, outward) result(text)
      class(plane_input_t), intent(in) :: this
      character(len=*), intent(in) :: edge
      real(wp), intent(in) :: outward(2)
      character(len=:), allocatable :: text
      text = ''
      if (dot_product(this%obstacle_normal, outward) > 0) &
         text = 'contact:obstacle_normal = ('//str(this%obstacle_normal(1))//', '// &
                str(this%obstacle_normal(2))//") points away from the body at edge '"//edge// &
                "' (it must point from the obstacle into the body): no node can touch the obstacle"
   end function plane_input_edge_warning
end module contact2d_obstacle_plane_input
