!> The body's material: one law of the material seam (contact2d_material_law) behind a concrete
!> type that the deck reader and the model declare and set up with material_init. The element
!> matrices (contact2d_stiffness) and the writer's stresses (contact2d_output) ask it for the
!> elasticity matrix and the density through the law's interface, never for a law by name.
module contact2d_material
   use contact2d_kinds, only: wp
   use contact2d_material_law, only: material_law_t
   use contact2d_material_factory, only: material_law_create
   implicit none
   private
   public :: material_t, material_init

   !> The body's homogeneous linear elastic material (plane strain).
   type :: material_t
      class(material_law_t), allocatable :: law   !< the constitutive law (set by material_init)
   contains
      procedure :: dmat => material_dmat
      procedure :: density => material_density
      procedure :: sigma_zz => material_sigma_zz
      procedure :: describe => material_describe
   end type material_t

contains

   !> Set up the material from the deck's E [MPa], nu [-], rho [t/mm^3] (the isotropic Hooke
   !> law, the one law the deck offers). stat /= 0 with a one-line message naming the deck
   !> variable if a value is out of range.
   subroutine material_init(this, young, poisson, density, stat, errmsg)
      type(material_t), intent(out) :: this
      real(wp), intent(in) :: young, poisson, density
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      call material_law_create('hooke', young, poisson, density, this%law, stat, errmsg)
   end subroutine material_init

   !> Plane-strain elasticity matrix, Voigt order (xx, yy, xy) with engineering shear [MPa].
   pure function material_dmat(this) result(d)
      class(material_t), intent(in) :: this
      real(wp) :: d(3, 3)
      d = this%law%dmat()
   end function material_dmat

   !> Mass density rho [t/mm^3].
   pure real(wp) function material_density(this) result(rho)
      class(material_t), intent(in) :: this
      rho = this%law%density()
   end function material_density

   !> Out-of-plane stress of plane strain from sigma_xx, sigma_yy [MPa].
   elemental real(wp) function material_sigma_zz(this, sxx, syy) result(szz)
      class(material_t), intent(in) :: this
      real(wp), intent(in) :: sxx, syy
      szz = this%law%sigma_zz(sxx, syy)
   end function material_sigma_zz

   !> One line naming the law and its constants.
   function material_describe(this) result(line)
      class(material_t), intent(in) :: this
      character(len=:), allocatable :: line
      line = this%law%describe()
   end function material_describe
end module contact2d_material
