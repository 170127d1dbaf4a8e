!> Factory of the element seam (contact2d_element): one element by name. The mesh stores four
!> nodes per element (mesh_t%conn(4, nel)), so today the one member is 'q1'.
module contact2d_element_factory
   use contact2d_element, only: element_t
   use contact2d_q1, only: q1_element_t
   implicit none
   private
   public :: element_create

contains

   !> Make the element named name ('q1'). stat /= 0 with a one-line errmsg for an unknown name.
   subroutine element_create(name, element, stat, errmsg)
      character(len=*), intent(in) :: name
      class(element_t), allocatable, intent(out) :: element
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      stat = 0
      errmsg = ''
      select case (name)
      case ('q1')
         allocate (q1_element_t :: element)
      case default
         stat = 1
         errmsg = "element '"//trim(name)//"' is not one of 'q1'"
      end select
   end subroutine element_create
end module contact2d_element_factory
