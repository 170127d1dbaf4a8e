!> Factory of the friction-law seam (docs/friction.md section 2): one law from the deck's
!> contact:friction. 'frictionless' makes none (the contact step then applies no tangential force).
module contact2d_friction_factory
   use contact2d_kinds, only: wp
   use contact2d_friction, only: friction_law_t
   use contact2d_friction_tresca, only: tresca_law_t
   use contact2d_friction_coulomb, only: coulomb_law_t
   implicit none
   private
   public :: friction_law_create

contains

   !> Make the law named name. abscissa, weight, slides: the contact nodes' abscissae [mm],
   !> weights w_i [mm] and free tangential dofs; coefficient: Coulomb mu; threshold, profile_s,
   !> profile_values, tresca_scope: Tresca's uniform s [MPa] or profile [mm, MPa] and scope.
   !> law is left unallocated for 'frictionless'; stat /= 0 for an unknown name.
   subroutine friction_law_create(name, abscissa, weight, slides, coefficient, threshold, profile_s, profile_values, &
                                  tresca_scope, law, stat, errmsg)
      character(len=*), intent(in) :: name, tresca_scope
      real(wp), intent(in) :: abscissa(:), weight(:)
      logical, intent(in) :: slides(:)
      real(wp), intent(in) :: coefficient, threshold, profile_s(:), profile_values(:)
      class(friction_law_t), allocatable, intent(out) :: law
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      stat = 0
      errmsg = ''
      select case (name)
      case ('frictionless')
      case ('tresca')
         allocate (tresca_law_t :: law)
         select type (law)
         type is (tresca_law_t)
            call law%init(abscissa, weight, slides, threshold, profile_s, profile_values, tresca_scope == 'contact')
         end select
      case ('coulomb')
         allocate (coulomb_law_t :: law)
         select type (law)
         type is (coulomb_law_t)
            call law%init(coefficient, slides)
         end select
      case default
         stat = 1
         errmsg = "contact: friction law '"//trim(name)//"' is not one of 'frictionless', 'tresca', 'coulomb'"
      end select
   end subroutine friction_law_create
end module contact2d_friction_factory
