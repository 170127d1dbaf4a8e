!> A rigid circle of centre C and radius R (docs/geometry.md): side 'outside' means the body is
!> outside a rigid cylinder (an indenter), side 'inside' that the body is inside a rigid circular
!> cavity.
module contact2d_obstacle_circle
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_obstacle, only: obstacle_t
   implicit none
   private
   public :: circle_obstacle_t

   type, extends(obstacle_t) :: circle_obstacle_t
      real(wp) :: center(2) = 0      !< C [mm]
      real(wp) :: radius = 1         !< R [mm]
      logical :: inside = .false.    !< the body is inside the circle
   contains
      procedure :: init => circle_init
      procedure :: project => circle_project
      procedure :: describe => circle_describe
   end type circle_obstacle_t

contains

   subroutine circle_init(this, center, radius, inside)
      class(circle_obstacle_t), intent(out) :: this
      real(wp), intent(in) :: center(2), radius
      logical, intent(in) :: inside
      this%center = center
      this%pivot = center
      this%radius = radius
      this%inside = inside
   end subroutine circle_init

   !> Outside: g = |x - C| - R, nu = (x - C)/|x - C|; inside: g = R - |x - C|, nu = (C - x)/|x - C|.
   !> At the centre itself the direction is undefined: nu = (0, 1) is taken.
   pure subroutine circle_project(this, x, gap, nu)
      class(circle_obstacle_t), intent(in) :: this
      real(wp), intent(in) :: x(2)
      real(wp), intent(out) :: gap, nu(2)
      real(wp) :: r
      r = norm2(x - this%center)
      if (r > 0) then
         nu = (x - this%center)/r
      else
         nu = [0.0_wp, 1.0_wp]
      end if
      gap = r - this%radius
      if (this%inside) then
         gap = -gap
         nu = -nu
      end if
   end subroutine circle_project

   function circle_describe(this) result(s)
      class(circle_obstacle_t), intent(in) :: this
      character(len=:), allocatable :: s
      s = 'circle of centre ('//str(this%center(1))//', '//str(this%center(2))//') and radius '// &
          str(this%radius)//' mm, body '//trim(merge('inside ', 'outside', this%inside))
   end function circle_describe
end module contact2d_obstacle_circle
