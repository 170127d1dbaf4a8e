!> The rigid obstacle seam (SPEC section 3, extended in docs/geometry.md): a shape answers, once
!> at set-up, the gap and the normal of a point of the body in the initial configuration. The
!> contact step only reads the per-node gaps and normals filled from it (small deformation), so
!> a new shape is one new file implementing `project` plus a line in the factory.
module contact2d_obstacle
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: obstacle_t

   !> A rigid obstacle.
   type, abstract :: obstacle_t
   contains
      procedure(obstacle_project), deferred :: project
      procedure(obstacle_describe), deferred :: describe
   end type obstacle_t

   abstract interface
      !> Closest point of the obstacle to x: the signed gap g (> 0 outside the obstacle, < 0
      !> inside it) [mm] and the unit normal nu of the obstacle at that point, pointing from the
      !> obstacle towards the body (the body's outward normal there is n = -nu).
      pure subroutine obstacle_project(this, x, gap, nu)
         import :: obstacle_t, wp
         class(obstacle_t), intent(in) :: this
         real(wp), intent(in) :: x(2)
         real(wp), intent(out) :: gap
         real(wp), intent(out) :: nu(2)
      end subroutine obstacle_project
      !> One line describing the obstacle (for messages).
      function obstacle_describe(this) result(s)
         import :: obstacle_t
         class(obstacle_t), intent(in) :: this
         character(len=:), allocatable :: s
      end function obstacle_describe
   end interface
end module contact2d_obstacle
