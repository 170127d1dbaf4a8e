!> The state of a run: what changes while the model (contact2d_model) stays as model_build made
!> it. Time, step, time step, status, the nodal fields, the energies the writer samples
!> (SPEC section 6) and the contact operator of each pair with its multipliers (SPEC section 3).
!>
!> Both engines fill it and the writer (contact2d_output) reads only it and the model. The
!> explicit engine keeps its own aligned store (contact2d_explicit) and points the state's
!> nodal fields at it (no copy per sample, nothing in the step loop); the static engine gives
!> the state arrays of its own (state_own_fields) and copies its solution into them.
module contact2d_state
   use contact2d_kinds, only: wp, i8
   use contact2d_contact, only: contact_t
   implicit none
   private
   public :: state_t

   !> One run's changing quantities.
   type :: state_t
      integer(i8) :: step = 0          !< steps (explicit) or increments (static) done
      real(wp) :: time = 0             !< t_n [s]
      real(wp) :: dt = 0               !< time step [s] (0 for the static engine)
      logical :: converged = .false.   !< the run met its convergence test
      !> 'running', then how the run ended ('converged', 'not converged', 'blow-up', ...)
      character(len=:), allocatable :: status
      !> nodal fields (2, nnode): views of the engine's arrays or of the own_* arrays below
      real(wp), pointer, contiguous :: u(:, :) => null()     !< u^n [mm]
      real(wp), pointer, contiguous :: v(:, :) => null()     !< v^(n-1/2) [mm/s] (0 at rest)
      real(wp), pointer, contiguous :: fint(:, :) => null()  !< K u^n [N]
      real(wp), pointer, contiguous :: fext(:, :) => null()  !< f_ext(t_n) [N]
      real(wp), allocatable :: own_u(:, :), own_v(:, :), own_fint(:, :), own_fext(:, :)
      ! energies (SPEC section 6) [mJ]; kinetic and strain staggered, *_step at the whole step
      real(wp) :: kinetic = 0
      real(wp) :: strain = 0
      real(wp) :: kinetic_step = 0
      real(wp) :: strain_step = 0
      real(wp) :: external_work = 0
      real(wp) :: damping_dissipation = 0
      real(wp) :: initial_kinetic = 0  !< energy put in at t = 0 (docs/deck.md &initial)
      real(wp) :: alpha = 0            !< mass-proportional damping of the last step [1/s]
      !> the contact operators the engine works on, one per pair (model%pairs' order): copies of
      !> the model's, built and validated by model_build, whose multipliers, statuses and work
      !> sums change during the run
      type(contact_t), allocatable :: contacts(:)
   contains
      procedure :: init => state_init
      procedure :: own_fields => state_own_fields
      procedure :: balance_error => state_balance_error
   end type state_t

contains

   !> A state at t = 0 with time step dt and the model's contact operators (copied).
   subroutine state_init(this, contacts, dt)
      class(state_t), intent(out) :: this
      type(contact_t), intent(in) :: contacts(:)
      real(wp), intent(in) :: dt
      this%dt = dt
      this%status = 'running'
      this%contacts = contacts
   end subroutine state_init

   !> Nodal fields held by the state itself, zero (an engine without a store of its own).
   subroutine state_own_fields(this, nnode)
      class(state_t), intent(inout), target :: this
      integer, intent(in) :: nnode
      allocate (this%own_u(2, nnode), this%own_v(2, nnode), this%own_fint(2, nnode), this%own_fext(2, nnode))
      this%own_u = 0
      this%own_v = 0
      this%own_fint = 0
      this%own_fext = 0
      this%u => this%own_u
      this%v => this%own_v
      this%fint => this%own_fint
      this%fext => this%own_fext
   end subroutine state_own_fields

   !> |E_kin0 + W_ext + W_obstacle - (E_kin + E_strain + D_friction + D_damping + W_normal)| /
   !> max(terms) (SPEC section 6, with the initial kinetic energy of docs/deck.md &initial and the
   !> work of a moving obstacle on the body, docs/geometry.md; 0 for a fixed obstacle).
   real(wp) function state_balance_error(this) result(err)
      class(state_t), intent(in) :: this
      real(wp) :: scale, friction, normal_work, obstacle_work
      integer :: k
      ! the pairs' sums (each pair's own terms: docs/output.md)
      friction = 0
      normal_work = 0
      obstacle_work = 0
      do k = 1, size(this%contacts)
         friction = friction + this%contacts(k)%friction_dissipation
         normal_work = normal_work + this%contacts(k)%normal_work
         obstacle_work = obstacle_work + this%contacts(k)%obstacle_work
      end do
         scale = max(abs(this%external_work), abs(this%kinetic), abs(this%strain), abs(friction), &
                     abs(this%damping_dissipation), abs(normal_work), this%initial_kinetic, abs(obstacle_work))
         if (scale > 0) then
            err = abs(this%initial_kinetic + this%external_work + obstacle_work - (this%kinetic + this%strain + &
                                             friction + this%damping_dissipation + normal_work))/scale
         else
            err = 0
         end if
   end function state_balance_error
end module contact2d_state
