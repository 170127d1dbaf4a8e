!> contact:friction = 'frictionless': no variables and no law (the contact step then applies no
!> tangential force, docs/friction.md). A member of the input side of the friction-law seam
!> (contact2d_friction_input).
module contact2d_friction_frictionless_input
   use contact2d_kinds, only: wp
   use contact2d_friction, only: friction_law_t
   use contact2d_friction_input, only: friction_input_t
   implicit none
   private
   public :: frictionless_input_t

   !> No friction.
   type, extends(friction_input_t) :: frictionless_input_t
   contains
      procedure :: name => frictionless_input_name
      procedure :: variables => frictionless_input_variables
      procedure :: make => frictionless_input_make
   end type frictionless_input_t

contains

   function frictionless_input_name(this) result(text)
      class(frictionless_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = 'frictionless'
   end function frictionless_input_name

   function frictionless_input_variables(this) result(text)
      class(frictionless_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = ''
   end function frictionless_input_variables

   !> No law: law stays unallocated.
   subroutine frictionless_input_make(this, abscissa, weight, slides, law)
      class(frictionless_input_t), intent(in) :: this
      real(wp), intent(in) :: abscissa(:), weight(:)
      logical, intent(in) :: slides(:)
      class(friction_law_t), allocatable, intent(out) :: law
   end subroutine frictionless_input_make
end module contact2d_friction_frictionless_input
