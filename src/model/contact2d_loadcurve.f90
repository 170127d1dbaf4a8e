!> Load curves: stages ramped smoothly, then held (SPEC section 5).
!>
!> Stage k runs from times(k-1) to times(k) (times(0) = 0) and moves the value from values(k-1)
!> (values(0) = 0) to values(k) with r(tau) = tau - sin(2 pi tau)/(2 pi), whose first and second
!> derivatives vanish at both ends. After the last stage the value is held.
module contact2d_loadcurve
   use contact2d_kinds, only: wp, pi
   implicit none
   private
   public :: loadcurve_t, smooth_ramp

   !> A piecewise smooth-ramped load curve.
   type :: loadcurve_t
      integer :: nstage = 0
      real(wp), allocatable :: times(:)    !< stage end times (0:nstage), times(0) = 0 [s]
      real(wp), allocatable :: values(:)   !< stage end values (0:nstage), values(0) = 0
   contains
      procedure :: init => loadcurve_init
      procedure :: value => loadcurve_value
      procedure :: end_time => loadcurve_end_time
      procedure :: integral => loadcurve_integral
   end type loadcurve_t

contains

   !> The smooth ramp r(tau) on [0, 1] (clamped outside).
   elemental real(wp) function smooth_ramp(tau) result(r)
      real(wp), intent(in) :: tau
      real(wp) :: s
      s = min(max(tau, 0.0_wp), 1.0_wp)
      r = s - sin(2*pi*s)/(2*pi)
   end function smooth_ramp

   !> Build from stage end times (strictly increasing, > 0) and stage end values.
   subroutine loadcurve_init(this, times, values)
      class(loadcurve_t), intent(out) :: this
      real(wp), intent(in) :: times(:), values(:)
      this%nstage = size(times)
      allocate (this%times(0:this%nstage), this%values(0:this%nstage))
      this%times(0) = 0
      this%values(0) = 0
      this%times(1:) = times
      this%values(1:) = values
   end subroutine loadcurve_init

   !> Value at time t.
   pure real(wp) function loadcurve_value(this, t) result(v)
      class(loadcurve_t), intent(in) :: this
      real(wp), intent(in) :: t   !< time [s]
      integer :: k
      do k = 1, this%nstage
         if (t < this%times(k)) then
            v = this%values(k - 1) + (this%values(k) - this%values(k - 1)) &
                *smooth_ramp((t - this%times(k - 1))/(this%times(k) - this%times(k - 1)))
            return
         end if
      end do
      v = this%values(this%nstage)
   end function loadcurve_value

   !> The integral of the curve from 0 to t, in closed form (an obstacle's displacement from its
   !> velocity curve, docs/geometry.md): over a whole stage of length T from a to b it is
   !> T (a + b)/2 (r(1 - tau) = 1 - r(tau)); over the part s of a stage
   !> T (a s + (b - a) R(s)) with R(s) = integral_0^s r = s^2/2 - sin^2(pi s)/(2 pi^2);
   !> after the last stage the held value times the time since. t <= 0 gives 0.
   pure real(wp) function loadcurve_integral(this, t) result(q)
      class(loadcurve_t), intent(in) :: this
      real(wp), intent(in) :: t   !< time [s]
      integer :: k
      real(wp) :: a, b, tk, s
      q = 0
      if (t <= 0) return
      do k = 1, this%nstage
         a = this%values(k - 1)
         b = this%values(k)
         tk = this%times(k) - this%times(k - 1)
         if (t < this%times(k)) then
            s = (t - this%times(k - 1))/tk
            q = q + tk*(a*s + (b - a)*(0.5_wp*s*s - sin(pi*s)**2/(2*pi*pi)))
            return
         end if
         q = q + 0.5_wp*tk*(a + b)
      end do
      q = q + this%values(this%nstage)*(t - this%times(this%nstage))
   end function loadcurve_integral

   !> End of the last stage [s].
   pure real(wp) function loadcurve_end_time(this) result(t)
      class(loadcurve_t), intent(in) :: this
      t = this%times(this%nstage)
   end function loadcurve_end_time
end module contact2d_loadcurve
