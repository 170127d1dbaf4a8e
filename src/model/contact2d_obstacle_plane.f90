!> A rigid half-plane {(x - P).nu <= 0} (SPEC section 3: the paper's straight obstacle).
module contact2d_obstacle_plane
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_obstacle, only: obstacle_t
   implicit none
   private
   public :: plane_obstacle_t

   !> The obstacle line through `point` with unit normal `nu` pointing towards the body.
   type, extends(obstacle_t) :: plane_obstacle_t
      real(wp) :: point(2) = 0       !< a point P of the line [mm]
      real(wp) :: nu(2) = [0, 1]     !< unit normal, obstacle -> body
   contains
      procedure :: init => plane_init
      procedure :: project => plane_project
      procedure :: describe => plane_describe
   end type plane_obstacle_t

contains

   subroutine plane_init(this, point, normal)
      class(plane_obstacle_t), intent(out) :: this
      real(wp), intent(in) :: point(2), normal(2)
      this%point = point
      this%pivot = point
      this%nu = normal/norm2(normal)
   end subroutine plane_init

   !> g = (x - P).nu, the same normal everywhere.
   pure subroutine plane_project(this, x, gap, nu)
      class(plane_obstacle_t), intent(in) :: this
      real(wp), intent(in) :: x(2)
      real(wp), intent(out) :: gap, nu(2)
      gap = dot_product(x - this%point, this%nu)
      nu = this%nu
   end subroutine plane_project

   function plane_describe(this) result(s)
      class(plane_obstacle_t), intent(in) :: this
      character(len=:), allocatable :: s
      s = 'plane through ('//str(this%point(1))//', '//str(this%point(2))//') with normal ('// &
          str(this%nu(1))//', '//str(this%nu(2))//')'
   end function plane_describe
end module contact2d_obstacle_plane
