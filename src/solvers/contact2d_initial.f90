!> The initial state of a run (docs/deck.md &initial): a uniform initial velocity.
!>
!> Central differences need v^(-1/2). The start-up is v^(-1/2) = v^0 - (dt/2) a^0 with
!> a^0 = M^-1 (f_ext(0) - K u^0), and a^0 = 0 here: u^0 = 0 and every load curve starts at 0
!> (SPEC section 5), so v^(-1/2) = v^0 exactly. A contact force at t = 0 (a zero gap) is not part
!> of a^0: it is the forward-increment force of the first step, which acts on v^(1/2).
!> The velocity is given to the free dofs; prescribed dofs follow their load curves, which start
!> at rest. The initial kinetic energy 1/2 v^(-1/2) M v^(-1/2) enters the energy balance as
!> energy put in at t = 0 (SPEC section 6 extended: E_kin0 + W_ext = E_kin + E_strain + ...).
module contact2d_initial
   use contact2d_kinds, only: wp
   use contact2d_explicit, only: explicit_t
   implicit none
   private
   public :: initial_velocity_apply, initial_velocity_warning

   !> the initial velocity, uniform (velocity(2)) or per node (velocity(2, nnode): &body velocity)
   interface initial_velocity_apply
      module procedure initial_velocity_uniform, initial_velocity_field
   end interface initial_velocity_apply

contains

   !> v^(-1/2) = velocity on the free dofs, 0 on the prescribed ones; the initial kinetic energy.
   subroutine initial_velocity_uniform(solver, free, velocity)
      type(explicit_t), intent(inout) :: solver   !< initialised integrator, before the first step
      real(wp), intent(in) :: free(:, :)          !< (2, nnode): 1 on free dofs, 0 on prescribed ones
      real(wp), intent(in) :: velocity(2)         !< (vx, vy) [mm/s]
      real(wp), allocatable :: field(:, :)
      allocate (field(2, size(free, 2)))
      field(1, :) = velocity(1)
      field(2, :) = velocity(2)
      call initial_velocity_field(solver, free, field)
   end subroutine initial_velocity_uniform

   !> The same with a velocity per node.
   subroutine initial_velocity_field(solver, free, velocity)
      type(explicit_t), intent(inout) :: solver   !< initialised integrator, before the first step
      real(wp), intent(in) :: free(:, :)          !< (2, nnode): 1 on free dofs, 0 on prescribed ones
      real(wp), intent(in) :: velocity(:, :)      !< (2, nnode): (vx, vy) of each node [mm/s]
      integer :: j
      do j = 1, 2
         solver%v(j, :) = velocity(j, :)*free(j, :)
      end do
      solver%vsum_stale = .true.   ! sum m v^2 formed again by the next advance
      solver%kinetic = 0.5_wp*sum(solver%mass*(solver%v(1, :)**2 + solver%v(2, :)**2))
      solver%initial_kinetic = solver%kinetic
      solver%kinetic_step = solver%kinetic   ! v^0 = v^(-1/2) (above)
      ! the blow-up guard compares the kinetic energy with the energy put in
      solver%work_in = solver%work_in + solver%kinetic
   end subroutine initial_velocity_field

   !> A warning when the initial velocity has a component on prescribed dofs (they keep their
   !> load curve, which starts at rest); '' otherwise.
   function initial_velocity_warning(free, velocity) result(msg)
      real(wp), intent(in) :: free(:, :)          !< (2, nnode): 1 on free dofs, 0 on prescribed ones
      real(wp), intent(in) :: velocity(2)         !< (vx, vy) [mm/s]
      character(len=:), allocatable :: msg
      character(len=1), parameter :: names(2) = ['x', 'y']
      character(len=32) :: buf
      integer :: j, n
      msg = ''
      do j = 1, 2
         if (velocity(j) == 0) cycle
         n = count(free(j, :) == 0)
         if (n == 0) cycle
         write (buf, '(i0)') n
         if (len(msg) > 0) msg = msg//'; '
         msg = msg//'initial:velocity: '//trim(buf)//' node(s) with a prescribed '//names(j)// &
               ' displacement keep their load curve (they start at rest), not the initial v'//names(j)
      end do
   end function initial_velocity_warning
end module contact2d_initial
