!> Coulomb friction (docs/friction.md section 1): the limit of node i in a step is mu F_n,i of
!> the same step (P1: Lambda_n,i; P0: (D^T mu_n)_i), so a node without normal force carries no
!> friction. A member of the friction-law seam (contact2d_friction, docs/friction.md section 2).
module contact2d_friction_coulomb
   use contact2d_kinds, only: wp
   use contact2d_friction, only: friction_law_t
   implicit none
   private
   public :: coulomb_law_t

   !> Nodal Coulomb: limit_i = mu_i max(F_n,i, 0), mu_i = 0 where the tangential dof is prescribed.
   type, extends(friction_law_t) :: coulomb_law_t
      real(wp), allocatable :: coefficient(:)   !< mu_i per contact node [-]
   contains
      procedure :: init => coulomb_law_init
      procedure :: limits => coulomb_law_limits
   end type coulomb_law_t

contains

   !> coefficient: the friction coefficient mu >= 0; slides(i): node i's tangential dof is free.
   subroutine coulomb_law_init(this, coefficient, slides)
      class(coulomb_law_t), intent(out) :: this
      real(wp), intent(in) :: coefficient
      logical, intent(in) :: slides(:)
      this%label = 'coulomb'
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
end module contact2d_friction_coulomb
