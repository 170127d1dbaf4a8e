!> Coulomb friction (docs/friction.md section 1): the limit of node i in a step is mu F_n,i of
!> the same step (P1: Lambda_n,i; P0: (D^T mu_n)_i), so a node without normal force carries no
!> friction. A member of the friction-law seam (contact2d_friction, docs/friction.md section 2).
module contact2d_friction_coulomb
   use contact2d_kinds, only: wp
   use contact2d_friction, only: friction_law_t, parameter_name_len
   implicit none
   private
   public :: coulomb_law_t

   !> Nodal Coulomb: limit_i = mu_i max(F_n,i, 0), mu_i = 0 where the tangential dof is prescribed.
   type, extends(friction_law_t) :: coulomb_law_t
      real(wp), allocatable :: coefficient(:)   !< mu_i per contact node [-]
      real(wp) :: mu = 0                        !< the deck's friction coefficient mu [-]
   contains
      procedure :: init => coulomb_law_init
      procedure :: limits => coulomb_law_limits
      procedure :: linear_in_fn => coulomb_law_linear_in_fn
      procedure :: fn_slopes => coulomb_law_fn_slopes
      procedure :: depends_on_fn => coulomb_law_depends_on_fn
      procedure :: parameters => coulomb_law_parameters
   end type coulomb_law_t

contains

   !> coefficient: the friction coefficient mu >= 0; slides(i): node i's tangential dof is free.
   subroutine coulomb_law_init(this, coefficient, slides)
      class(coulomb_law_t), intent(out) :: this
      real(wp), intent(in) :: coefficient
      logical, intent(in) :: slides(:)
      this%label = 'coulomb'
      this%mu = coefficient
      this%coefficient = merge(coefficient, 0.0_wp, slides)
   end subroutine coulomb_law_init

   !> limit_i = mu_i F_n,i (docs/friction.md, equation (C1)); F_n,i < 0 cannot occur (P1 max(0, .),
   !> P0 D mu with mu >= 0 and D >= 0), max() only guards round-off. The limit follows F_n,i
   !> itself (a node with F_n,i = 0 carries none), whatever the contact measure says.
   pure subroutine coulomb_law_limits(this, fn, closed, limit)
      class(coulomb_law_t), intent(in) :: this
      real(wp), intent(in) :: fn(:)
      real(wp), intent(in) :: closed(:)
      real(wp), intent(out) :: limit(:)
      if (size(closed) /= size(limit)) error stop 'coulomb_law_limits: closed and limit differ in size'
      limit = this%coefficient*max(fn, 0.0_wp)
   end subroutine coulomb_law_limits

   !> limit_i = mu_i F_n,i: linear in the normal forces, mu_i fixed at set-up.
   pure logical function coulomb_law_linear_in_fn(this) result(linear)
      class(coulomb_law_t), intent(in) :: this
      linear = allocated(this%coefficient)
   end function coulomb_law_linear_in_fn

   !> d limit_i / d F_n,i = mu_i (0 where the tangential dof is prescribed).
   pure subroutine coulomb_law_fn_slopes(this, slope)
      class(coulomb_law_t), intent(in) :: this
      real(wp), intent(out) :: slope(:)
      slope = this%coefficient
   end subroutine coulomb_law_fn_slopes

   !> A node with F_n,i > 0 carries friction mu F_n,i whenever mu > 0 (docs/friction.md section 1).
   pure logical function coulomb_law_depends_on_fn(this) result(depends)
      class(coulomb_law_t), intent(in) :: this
      depends = this%mu > 0
   end function coulomb_law_depends_on_fn

   !> friction_coefficient = mu (the deck's contact:friction_coefficient).
   pure subroutine coulomb_law_parameters(this, names, values)
      class(coulomb_law_t), intent(in) :: this
      character(len=parameter_name_len), allocatable, intent(out) :: names(:)
      real(wp), allocatable, intent(out) :: values(:)
      names = [character(len=parameter_name_len) :: 'friction_coefficient']
      values = [this%mu]
   end subroutine coulomb_law_parameters
end module contact2d_friction_coulomb
