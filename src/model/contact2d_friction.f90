!> The friction-law seam (docs/friction.md section 2): an abstract law that turns this step's
!> nodal normal forces F_n into each contact node's tangential limit [N]. The contact step
!> (SPEC section 4, step 3, as extended in docs/friction.md) finds the normal forces first,
!> calls limits() once, then projects the trial stick forces onto [-limit_i, limit_i] node by
!> node. Members: contact2d_friction_tresca (s_i w_i), contact2d_friction_coulomb (mu F_n,i);
!> the law's input (contact2d_friction_input, one contact2d_friction_<law>_input per law) makes
!> one from the deck's contact:friction and its variables.
module contact2d_friction
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: friction_law_t, parameter_name_len

   !> Length of a parameter's name (friction_law_t%parameters).
   integer, parameter :: parameter_name_len = 32

   !> A friction law: per-node tangential limits from per-node normal forces.
   type, abstract :: friction_law_t
      character(len=16) :: label = ''   !< the deck's name of the law, set by the member's init
      !> set by a member's init when limits() does not depend on its fn and closed arguments (the
      !> same limits every step): the contact step then takes them once and finds F_n and F_t in
      !> one pass. A law that does not say so is asked every step.
      logical :: fixed = .false.
   contains
      !> Fill limit(i) >= 0 [N] from this step's nodal normal forces fn(i) >= 0 [N] and the
      !> measure by which node i is judged in contact, closed(i) > 0 (SPEC section 3: F_n,i for P1,
      !> the node's own dual-cell multiplier mu_n,i for P0).
      procedure(friction_law_limits), deferred :: limits
      !> The deck's name of the law ('tresca', 'coulomb'), for messages and the output file's
      !> attribute: no caller chooses an algorithm by it (the procedures below say what they need).
      procedure :: name => friction_law_name
      !> Whether limit_i = slope_i F_n,i exactly, slopes fixed at set-up (Coulomb): the static
      !> engine's fixed-set solve and semismooth Newton step (docs/static.md) need limits linear
      !> in the normal forces; a law that is not linear gets its fixed point only.
      procedure(friction_law_flag), deferred :: linear_in_fn
      !> Fill slope(i) = d limit_i / d F_n,i [-] (Coulomb mu_i; 0 for a law whose limit does not
      !> depend on F_n, as Tresca's).
      procedure(friction_law_slopes), deferred :: fn_slopes
      !> Whether a node carries friction as soon as its own nodal F_n,i > 0 (Coulomb with mu > 0):
      !> with P0 such a node counts as touching even where its own dual cell is open
      !> (docs/friction.md section 1).
      procedure(friction_law_flag), deferred :: depends_on_fn
      !> The law's parameters as name/value pairs, written as attributes of /contact by the
      !> output file (docs/output.md); none for a law whose data are per-node arrays only.
      procedure(friction_law_parameters), deferred :: parameters
      !> Fill s(i), the law's per-node threshold [MPa] that the output file writes as
      !> /contact/threshold (docs/output.md): Tresca's s_i; zeros for a law without one.
      procedure :: node_thresholds => friction_law_node_thresholds
   end type friction_law_t

   abstract interface
      pure subroutine friction_law_limits(this, fn, closed, limit)
         import :: friction_law_t, wp
         class(friction_law_t), intent(in) :: this
         real(wp), intent(in) :: fn(:)       !< nodal normal forces of this step [N]
         real(wp), intent(in) :: closed(:)   !< in contact where > 0 (P1: fn, P0: mu_n per dual cell)
         real(wp), intent(out) :: limit(:)   !< tangential limits of this step [N]
      end subroutine friction_law_limits

      pure logical function friction_law_flag(this)
         import :: friction_law_t
         class(friction_law_t), intent(in) :: this
      end function friction_law_flag

      pure subroutine friction_law_slopes(this, slope)
         import :: friction_law_t, wp
         class(friction_law_t), intent(in) :: this
         real(wp), intent(out) :: slope(:)   !< d limit_i / d F_n,i per contact node [-]
      end subroutine friction_law_slopes

      pure subroutine friction_law_parameters(this, names, values)
         import :: friction_law_t, wp, parameter_name_len
         class(friction_law_t), intent(in) :: this
         !> attribute names (the deck's variable names)
         character(len=parameter_name_len), allocatable, intent(out) :: names(:)
         real(wp), allocatable, intent(out) :: values(:)   !< their values (units of the deck)
      end subroutine friction_law_parameters
   end interface

contains

   pure function friction_law_name(this) result(name)
      class(friction_law_t), intent(in) :: this
      character(len=:), allocatable :: name
      name = trim(this%label)
   end function friction_law_name

   !> No per-node threshold: zeros.
   pure subroutine friction_law_node_thresholds(this, s)
      class(friction_law_t), intent(in) :: this
      real(wp), intent(out) :: s(:)
      s = 0
   end subroutine friction_law_node_thresholds
end module contact2d_friction
