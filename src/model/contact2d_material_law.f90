!> The material seam (docs/architecture.md, "Seams"): an abstract linear elastic material law
!> in plane strain (SPEC section 2). What the rest of the code asks of a material: its
!> elasticity matrix (element stiffness, element stresses), its mass density (lumped masses), the
!> out-of-plane stress of plane strain, and one line that describes it. Members:
!> contact2d_material_hooke (isotropic Hooke law); the factory contact2d_material_factory makes
!> one by name. Called at set-up and output only, never in the step loop.
module contact2d_material_law
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: material_law_t

   !> A homogeneous linear elastic material in plane strain.
   type, abstract :: material_law_t
   contains
      !> Plane-strain elasticity matrix D, Voigt order (xx, yy, xy), engineering shear [MPa].
      procedure(material_law_dmat), deferred :: dmat
      !> Mass density rho [t/mm^3].
      procedure(material_law_density), deferred :: density
      !> Out-of-plane stress sigma_zz of plane strain from the in-plane normal stresses [MPa].
      procedure(material_law_sigma_zz), deferred :: sigma_zz
      !> One line naming the law and its constants, with units.
      procedure(material_law_describe), deferred :: describe
   end type material_law_t

   abstract interface
      pure function material_law_dmat(this) result(d)
         import :: material_law_t, wp
         class(material_law_t), intent(in) :: this
         real(wp) :: d(3, 3)
      end function material_law_dmat

      pure real(wp) function material_law_density(this) result(rho)
         import :: material_law_t, wp
         class(material_law_t), intent(in) :: this
      end function material_law_density

      pure real(wp) function material_law_sigma_zz(this, sxx, syy) result(szz)
         import :: material_law_t, wp
         class(material_law_t), intent(in) :: this
         real(wp), intent(in) :: sxx, syy   !< in-plane normal stresses [MPa]
      end function material_law_sigma_zz

      function material_law_describe(this) result(line)
         import :: material_law_t
         class(material_law_t), intent(in) :: this
         character(len=:), allocatable :: line
      end function material_law_describe
   end interface
end module contact2d_material_law
