!> A body of the model: its name, its elements and its material (docs/architecture.md, "Seams"):
!> the model holds a list of bodies, the deck's &body groups or one, the whole mesh with the
!> deck's &material; the element matrices and masses of each element (contact2d_stiffness) are
!> built from its body's material.
module contact2d_body
   use contact2d_material, only: material_t
   implicit none
   private
   public :: body_t, body_init

   !> One deformable body.
   type :: body_t
      character(len=:), allocatable :: name   !< as the output and the messages name it
      integer, allocatable :: elements(:)     !< its elements (indices into mesh_t%conn)
      type(material_t) :: material            !< its plane-strain Hooke law
   end type body_t

contains

   !> A body named `name` made of `elements` with `material`.
   subroutine body_init(body, name, elements, material)
      type(body_t), intent(out) :: body
      character(len=*), intent(in) :: name
      integer, intent(in) :: elements(:)
      type(material_t), intent(in) :: material
      body%name = name
      body%elements = elements
      body%material = material
   end subroutine body_init
end module contact2d_body
