!> The growing-mode guard of the explicit engine (docs/deck.md, solver:dt_limit = 'power'):
!> a step from the power-iteration estimate may lie above the true stability limit of the
!> contact system; the guard tells, every step, when a mode grows, so that the run falls back to
!> the element-bound step (contact2d_timestep).
module contact2d_growth_guard
   use contact2d_kinds, only: wp, i8
   implicit none
   private
   public :: growth_guard_t

   !> Rise factor per step of the alternating energy, rises in a row and alternating ratio that
   !> mean a fast-growing mode; steps between the checks of the slow test and its rises in a row
   !> under constant loads.
   integer, parameter :: guard_interval = 10
   real(wp), parameter :: guard_factor = 1.05_wp, guard_ratio = 2.0_wp
   integer, parameter :: guard_rises = 12, guard_kin_rises = 30

   !> The guard's memory between steps.
   type :: growth_guard_t
      real(wp) :: alt = 0, kin = 0        !< alternating energy at the last step, at the last check [mJ]
      integer :: rise = 0, kin_rise = 0   !< consecutive rises
   contains
      procedure :: check => growth_guard_check
      procedure :: reset => growth_guard_reset
   end type growth_guard_t

contains

   !> Every step: a mode above the stability limit changes sign every step and grows
   !> geometrically, so its alternating energy rises at every step (guard_rises in a row by
   !> guard_factor or more) and soon dominates the kinetic energy (alternating ratio above
   !> guard_ratio; 4 for a pure sign-changing mode, near 0 for smooth motion); once the loads
   !> are constant (time > after) and the damping takes energy out of every mode, a slowly
   !> growing mode shows as alternating energy that rises at every check of guard_interval
   !> steps (guard_kin_rises in a row). .true.: a growing mode.
   logical function growth_guard_check(this, alternating_energy, alternating, step, time, after) result(growing)
      class(growth_guard_t), intent(inout) :: this
      real(wp), intent(in) :: alternating_energy   !< 1/2 sum m (v^(n+1/2) - v^(n-1/2))^2 [mJ]
      real(wp), intent(in) :: alternating          !< its ratio to the kinetic sum [-]
      integer(i8), intent(in) :: step              !< steps done
      real(wp), intent(in) :: time, after          !< t_n and the end of loading [s]
      if (alternating_energy > guard_factor*this%alt .and. this%alt > 0) then
         this%rise = this%rise + 1
      else
         this%rise = 0
      end if
      this%alt = alternating_energy
      if (mod(step, int(guard_interval, i8)) == 0) then
         if (time > after .and. alternating_energy > this%kin .and. this%kin > 0) then
            this%kin_rise = this%kin_rise + 1
         else
            this%kin_rise = 0
         end if
         this%kin = alternating_energy
      end if
      growing = (this%rise >= guard_rises .and. alternating > guard_ratio) .or. this%kin_rise >= guard_kin_rises
   end function growth_guard_check

   !> A new time step: the rises in a row start again (the last values are kept).
   subroutine growth_guard_reset(this)
      class(growth_guard_t), intent(inout) :: this
      this%rise = 0
      this%kin_rise = 0
   end subroutine growth_guard_reset
end module contact2d_growth_guard
