!> Factory of the material seam (contact2d_material_law): one law by name. Today the deck's
!> &material group gives E, nu, rho of the one law, 'hooke'; a new law is a new member file and
!> a case here (and its deck variables).
module contact2d_material_factory
   use contact2d_kinds, only: wp
   use contact2d_material_law, only: material_law_t
   use contact2d_material_hooke, only: hooke_law_t
   implicit none
   private
   public :: material_law_create

contains

   !> Make the law named name from the deck's constants (E [MPa], nu [-], rho [t/mm^3]).
   !> stat /= 0 with a one-line errmsg for an unknown name or a value the law refuses.
   subroutine material_law_create(name, young, poisson, density, law, stat, errmsg)
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: young, poisson, density
      class(material_law_t), allocatable, intent(out) :: law
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      select case (name)
      case ('hooke')
         allocate (hooke_law_t :: law)
         select type (law)
         type is (hooke_law_t)
            call law%init(young, poisson, density, stat, errmsg)
         end select
      case default
         stat = 1
         errmsg = "material: law '"//trim(name)//"' is not one of 'hooke'"
      end select
      if (stat /= 0 .and. allocated(law)) deallocate (law)
   end subroutine material_law_create
end module contact2d_material_factory
