!> Creates the obstacle named by the deck (contact:obstacle = 'plane' | 'circle').
module contact2d_obstacle_factory
   use contact2d_kinds, only: wp
   use contact2d_obstacle, only: obstacle_t
   use contact2d_obstacle_plane, only: plane_obstacle_t
   use contact2d_obstacle_circle, only: circle_obstacle_t
   implicit none
   private
   public :: obstacle_create, obstacle_kinds

   !> The shapes the factory knows.
   character(len=6), parameter :: obstacle_kinds(2) = [character(len=6) :: 'plane', 'circle']

contains

   !> The obstacle of the given kind from its settings; stat /= 0 for an unknown kind.
   subroutine obstacle_create(kind, point, normal, center, radius, side, obstacle, stat, errmsg)
      character(len=*), intent(in) :: kind
      real(wp), intent(in) :: point(2), normal(2)   !< plane: a point and the normal [mm]
      real(wp), intent(in) :: center(2), radius     !< circle: centre and radius [mm]
      character(len=*), intent(in) :: side          !< circle: 'outside' | 'inside'
      class(obstacle_t), allocatable, intent(out) :: obstacle
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(plane_obstacle_t) :: plane
      type(circle_obstacle_t) :: circle
      stat = 0
      errmsg = ''
      select case (trim(kind))
      case ('plane')
         call plane%init(point, normal)
         allocate (obstacle, source=plane)
      case ('circle')
         call circle%init(center, radius, trim(side) == 'inside')
         allocate (obstacle, source=circle)
      case default
         stat = 1
         errmsg = "contact:obstacle = '"//trim(kind)//"' is not one of 'plane', 'circle'"
      end select
   end subroutine obstacle_create
end module contact2d_obstacle_factory
