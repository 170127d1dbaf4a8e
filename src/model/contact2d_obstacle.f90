!> The rigid obstacle seam (SPEC section 3, extended in docs/geometry.md): a shape answers the
!> gap and the normal of a point of the body. A fixed obstacle is asked once, at set-up, in the
!> initial configuration, and the contact step reads the per-node gaps and normals filled from
!> it (small deformation); a new shape is one new file implementing `project` plus a line in the
!> factory.
!>
!> Prescribed motion (docs/geometry.md "Moving obstacles"), common to every shape: a translation
!> velocity (vx(t), vy(t)) and a spin omega(t) about the pivot (a circle's centre), each a load
!> curve (contact2d_loadcurve). The displacement d(t) and the angle theta(t) are the curves'
!> exact integrals (closed form: they do not depend on the time step). The shape itself is
!> invariant under its own spin (a circle) or has none (a plane), so the obstacle at t is the
!> shape translated by d(t): project_at(t, x) = project(x - d(t)).
module contact2d_obstacle
   use contact2d_kinds, only: wp
   use contact2d_loadcurve, only: loadcurve_t
   implicit none
   private
   public :: obstacle_t

   !> A rigid obstacle.
   type, abstract :: obstacle_t
      !> the obstacle moves (a velocity or a spin curve was given)
      logical :: moving = .false.
      type(loadcurve_t) :: velocity(2)   !< translation velocity vx(t), vy(t) [mm/s]
      type(loadcurve_t) :: spin          !< angular velocity omega(t), counterclockwise [rad/s]
      !> the point the spin turns about at t = 0 (a circle's centre; set by the shape's init) [mm]
      real(wp) :: pivot(2) = 0
   contains
      procedure(obstacle_project), deferred :: project
      procedure(obstacle_describe), deferred :: describe
      procedure, non_overridable :: set_motion => obstacle_set_motion
      procedure, non_overridable :: displacement => obstacle_displacement
      procedure, non_overridable :: angle => obstacle_angle
      procedure, non_overridable :: project_at => obstacle_project_at
      procedure, non_overridable :: surface_displacement => obstacle_surface_displacement
   end type obstacle_t

   abstract interface
      !> Closest point of the obstacle to x: the signed gap g (> 0 outside the obstacle, < 0
      !> inside it) [mm] and the unit normal nu of the obstacle at that point, pointing from the
      !> obstacle towards the body (the body's outward normal there is n = -nu). The closest
      !> point itself is x - g nu.
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

contains

   !> The motion: stage end times (strictly increasing, > 0) and the stage end values of vx, vy
   !> [mm/s] and omega [rad/s] (the curves of contact2d_loadcurve: smooth ramps from 0, then
   !> held). The pivot is the shape's own (set by its init).
   subroutine obstacle_set_motion(this, times, vx, vy, omega)
      class(obstacle_t), intent(inout) :: this
      real(wp), intent(in) :: times(:), vx(:), vy(:), omega(:)
      call this%velocity(1)%init(times, vx)
      call this%velocity(2)%init(times, vy)
      call this%spin%init(times, omega)
      this%moving = .true.
   end subroutine obstacle_set_motion

   !> d(t) = integral_0^t (vx, vy) [mm] (exact); 0 for a fixed obstacle.
   pure function obstacle_displacement(this, t) result(d)
      class(obstacle_t), intent(in) :: this
      real(wp), intent(in) :: t   !< [s]
      real(wp) :: d(2)
      d = 0
      if (.not. this%moving) return
      d(1) = this%velocity(1)%integral(t)
      d(2) = this%velocity(2)%integral(t)
   end function obstacle_displacement

   !> theta(t) = integral_0^t omega [rad] (exact); 0 for a fixed obstacle.
   pure real(wp) function obstacle_angle(this, t) result(theta)
      class(obstacle_t), intent(in) :: this
      real(wp), intent(in) :: t   !< [s]
      theta = 0
      if (this%moving) theta = this%spin%integral(t)
   end function obstacle_angle

   !> Gap and normal of x against the obstacle at time t (the shape translated by d(t)); d: d(t).
   pure subroutine obstacle_project_at(this, d, x, gap, nu)
      class(obstacle_t), intent(in) :: this
      real(wp), intent(in) :: d(2)   !< the obstacle's displacement d(t) [mm]
      real(wp), intent(in) :: x(2)   !< a point of the body at t [mm]
      real(wp), intent(out) :: gap, nu(2)
      call this%project(x - d, gap, nu)
   end subroutine obstacle_project_at

   !> The displacement, from t1 to t2, of the obstacle's material point that is at xs at t2
   !> [mm]: d(t2) - d(t1) plus the spin's part r - Rot(-(theta2 - theta1)) r, r = xs - (pivot +
   !> d(t2)). d1, d2: d(t1), d(t2); dtheta = theta(t2) - theta(t1). (The rigid motion x(t) =
   !> pivot + d(t) + Rot(theta(t)) (X - pivot), read backwards from t2.)
   pure function obstacle_surface_displacement(this, d1, d2, dtheta, xs) result(ds)
      class(obstacle_t), intent(in) :: this
      real(wp), intent(in) :: d1(2), d2(2), dtheta, xs(2)
      real(wp) :: ds(2)
      real(wp) :: r(2), c, s
      ds = d2 - d1
      if (dtheta == 0) return
      r = xs - (this%pivot + d2)
      c = cos(dtheta)
      s = sin(dtheta)
      ! Rot(-a) r = (c r1 + s r2, -s r1 + c r2)
      ds(1) = ds(1) + r(1) - (c*r(1) + s*r(2))
      ds(2) = ds(2) + r(2) - (-s*r(1) + c*r(2))
   end function obstacle_surface_displacement
end module contact2d_obstacle
