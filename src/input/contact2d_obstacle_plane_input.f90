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
   use contact2d_deck_syntax, only: unset, read_failed, kv, reals
   implicit none
   private
   public :: plane_input_t, plane_names, plane_claims, plane_input_read, plane_input_not_finite
   public :: plane_input_unused, plane_input_complete, plane_input_validate, plane_input_echo

   !> The &contact variables of the obstacle (blank-separated).
   character(len=*), parameter :: plane_names = 'obstacle_point obstacle_normal'
   !> The plane y = 0 with its normal +y when the deck gives no obstacle_point/normal.
   real(wp), parameter :: default_point(2) = [0.0_wp, 0.0_wp], default_normal(2) = [0.0_wp, 1.0_wp]

   !> The plane's deck variables.
   type :: plane_input_t
      !> a point P of the obstacle line [mm] (not given: default_point)
      real(wp) :: obstacle_point(2) = [unset, unset]
      !> unit normal nu, obstacle -> body (not given: default_normal)
      real(wp) :: obstacle_normal(2) = [unset, unset]
   end type plane_input_t

contains

   !> name (lower case, no subscript) is a variable of this obstacle.
   pure logical function plane_claims(name)
      character(len=*), intent(in) :: name
      plane_claims = index(' '//plane_names//' ', ' '//name//' ') > 0
   end function plane_claims

   !> Read one assignment (namelist records '&contact', text, '/'); variables: every &contact
   !> variable, for the did-you-mean of read_failed; where: the message's prefix.
   subroutine plane_input_read(records, where, variables, cfg, stat, errmsg)
      character(len=*), intent(in) :: records(:), where, variables
      type(plane_input_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: obstacle_point(2), obstacle_normal(2)
      integer :: ios
      character(len=256) :: msg
      namelist /contact/ obstacle_point, obstacle_normal
      obstacle_point = cfg%obstacle_point; obstacle_normal = cfg%obstacle_normal
      read (records, nml=contact, iostat=ios, iomsg=msg)
      if (read_failed(ios, msg, variables, where, stat, errmsg)) return
      cfg%obstacle_point = obstacle_point; cfg%obstacle_normal = obstacle_normal
   end subroutine plane_input_read

   !> check_finite on every real of the obstacle; true if one is bad.
   logical function plane_input_not_finite(cfg, errmsg) result(bad)
      type(plane_input_t), intent(in) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('contact:obstacle_point', cfg%obstacle_point, errmsg)) return
      if (check_finite('contact:obstacle_normal', cfg%obstacle_normal, errmsg)) return
      bad = .false.
   end function plane_input_not_finite

   !> A variable of the plane given while the obstacle is another shape: true, with the message.
   logical function plane_input_unused(cfg, obstacle, errmsg) result(bad)
      type(plane_input_t), intent(in) :: cfg
      character(len=*), intent(in) :: obstacle
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = obstacle /= 'plane' .and. (any(cfg%obstacle_point /= unset) .or. any(cfg%obstacle_normal /= unset))
      if (bad) errmsg = "contact: obstacle_point and obstacle_normal are set but obstacle = '"//trim(obstacle)// &
                        "' ignores them (the circle is obstacle_center and obstacle_radius)"
   end function plane_input_unused

   !> Both components of each vector or none, then the defaults for those not given; true if
   !> refused.
   logical function plane_input_complete(cfg, errmsg) result(bad)
      type(plane_input_t), intent(inout) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = count(cfg%obstacle_point == unset) == 1 .or. count(cfg%obstacle_normal == unset) == 1
      if (bad) then
         errmsg = 'contact:obstacle_point and obstacle_normal take two components each (x, y)'
         return
      end if
      if (all(cfg%obstacle_point == unset)) cfg%obstacle_point = default_point
      if (all(cfg%obstacle_normal == unset)) cfg%obstacle_normal = default_normal
   end function plane_input_complete

   !> The normal is a unit vector (SPEC section 3: nu of unit length); true if refused.
   logical function plane_input_validate(cfg, errmsg) result(bad)
      type(plane_input_t), intent(in) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: norm
      norm = norm2(cfg%obstacle_normal)
      bad = abs(norm - 1) > 1.0e-6_wp
      if (bad) errmsg = 'contact:obstacle_normal = '//str(cfg%obstacle_normal(1))//', '// &
                        str(cfg%obstacle_normal(2))//' must be a unit vector (length '//str(norm)//')'
   end function plane_input_validate

   !> The obstacle's echo lines (when it is the chosen obstacle).
   function plane_input_echo(cfg) result(text)
      type(plane_input_t), intent(in) :: cfg
      character(len=:), allocatable :: text
      text = kv('obstacle_point', reals(cfg%obstacle_point))//kv('obstacle_normal', reals(cfg%obstacle_normal))
   end function plane_input_echo
end module contact2d_obstacle_plane_input
