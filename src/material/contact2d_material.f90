!> Isotropic Hooke law in plane strain (SPEC section 2; the paper's constitutive law).
module contact2d_material
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   implicit none
   private
   public :: material_t, material_init

   !> Homogeneous isotropic linear elastic material.
   type :: material_t
      real(wp) :: young = 0      !< Young's modulus E [MPa]
      real(wp) :: poisson = 0    !< Poisson's ratio nu [-]
      real(wp) :: density = 0    !< mass density rho [t/mm^3]
      real(wp) :: lambda = 0     !< first Lame constant [MPa]
      real(wp) :: mu = 0         !< shear modulus [MPa]
      !> Plane-strain elasticity matrix, Voigt order (xx, yy, xy) with engineering shear [MPa].
      real(wp) :: dmat(3, 3) = 0
   contains
      procedure :: sigma_zz => material_sigma_zz
   end type material_t

contains

   !> Set up the material from E, nu, rho. stat /= 0 with a message if a value is out of range.
   subroutine material_init(this, young, poisson, density, stat, errmsg)
      type(material_t), intent(out) :: this
      real(wp), intent(in) :: young, poisson, density
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg

      stat = 1
      ! the values as the deck gives them (str: shortest text that reads back; es12.5 printed
      ! -1.00000-200 for -1e-200, the exponent letter lost)
      if (.not. (young > 0)) then
         errmsg = 'material:young = '//str(young)//' must be > 0'
         return
      end if
      if (.not. (poisson > -1 .and. poisson < 0.5_wp)) then
         errmsg = 'material:poisson = '//str(poisson)//' must satisfy -1 < poisson < 0.5'
         return
      end if
      if (.not. (density > 0)) then
         errmsg = 'material:density = '//str(density)//' must be > 0'
         return
      end if
      stat = 0
      errmsg = ''
      this%young = young
      this%poisson = poisson
      this%density = density
      this%lambda = young*poisson/((1 + poisson)*(1 - 2*poisson))
      this%mu = young/(2*(1 + poisson))
      this%dmat = 0
      this%dmat(1, 1) = this%lambda + 2*this%mu
      this%dmat(2, 2) = this%lambda + 2*this%mu
      this%dmat(1, 2) = this%lambda
      this%dmat(2, 1) = this%lambda
      this%dmat(3, 3) = this%mu
   end subroutine material_init

   !> Out-of-plane stress of plane strain, sigma_zz = nu (sigma_xx + sigma_yy) [MPa].
   elemental real(wp) function material_sigma_zz(this, sxx, syy) result(szz)
      class(material_t), intent(in) :: this
      real(wp), intent(in) :: sxx, syy
      szz = this%poisson*(sxx + syy)
   end function material_sigma_zz
end module contact2d_material
