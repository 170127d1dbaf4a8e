!> Contact with a rigid straight obstacle: forward-increment Lagrange multipliers (SPEC 3, 4).
!> (Skeleton: filled in by the contact issue.)
module contact2d_contact
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: contact_t

   type :: contact_t
      logical :: active = .false.
      real(wp) :: friction_dissipation = 0
      real(wp) :: normal_work = 0
      real(wp) :: normal_total = 0
      real(wp) :: tangential_total = 0
   contains
      procedure :: enforce => contact_enforce
   end type contact_t

contains

   subroutine contact_enforce(this, u, v, unew, mass, c, dt, fc)
      class(contact_t), intent(inout) :: this
      real(wp), intent(in) :: u(:, :), v(:, :), mass(:), c, dt
      real(wp), intent(inout) :: unew(:, :), fc(:, :)
      fc = 0*u + 0*v + 0*unew + 0*c + 0*dt + 0*sum(mass)
      this%normal_work = 0
   end subroutine contact_enforce
end module contact2d_contact
