!> Mass scaling for quasi-static runs (docs/deck.md solver:mass_scaling): fictitious
!> nodal masses so that every node reaches a target stable time step.
!>
!> The bound used is Gershgorin's on M^-1 K, row by row: omega_max^2 <= max over dofs d of
!> R_d / m_d with R_d the absolute row sum of K, itself bounded by the sum over the elements of
!> the node of the absolute row sums of their matrices. A node whose bound exceeds (2/dt_t)^2
!> gets the mass R dt_t^2 / 4 (the largest R of its two dofs); then every row meets the
!> target, so dt_t is stable for the scaled system.
module contact2d_mass_scaling
   use contact2d_kinds, only: wp
   use contact2d_stiffness, only: stiffness_t
   implicit none
   private
   public :: mass_scale

contains

   !> Scale stiff%mass in place for the target step dt_target [s]; added is the total added
   !> mass [t], nscaled the number of nodes that got mass, dt_bound the Gershgorin bound on the
   !> stable step of the scaled system [s] (>= dt_target).
   subroutine mass_scale(stiff, dt_target, added, nscaled, dt_bound)
      type(stiffness_t), intent(inout) :: stiff
      real(wp), intent(in) :: dt_target
      real(wp), intent(out) :: added, dt_bound
      integer, intent(out) :: nscaled
      real(wp), allocatable :: rowsum(:, :)
      real(wp) :: need, omega2
      integer :: e, a, n, s

      allocate (rowsum(2, size(stiff%mass)))
      rowsum = 0
      do e = 1, size(stiff%conn, 2)
         s = stiff%shape_of(e)
         do a = 1, 4
            n = stiff%conn(a, e)
            rowsum(1, n) = rowsum(1, n) + sum(abs(stiff%ke(2*a - 1, :, s)))
            rowsum(2, n) = rowsum(2, n) + sum(abs(stiff%ke(2*a, :, s)))
         end do
      end do
      added = 0
      nscaled = 0
      omega2 = 0
      do n = 1, size(stiff%mass)
         need = maxval(rowsum(:, n))*dt_target**2/4
         if (need > stiff%mass(n)) then
            added = added + (need - stiff%mass(n))
            nscaled = nscaled + 1
            stiff%mass(n) = need
         end if
         omega2 = max(omega2, maxval(rowsum(:, n))/stiff%mass(n))
      end do
      dt_bound = 2/sqrt(omega2)
   end subroutine mass_scale
end module contact2d_mass_scaling
