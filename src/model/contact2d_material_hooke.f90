!> Isotropic Hooke law in plane strain (SPEC section 2; the paper's constitutive law):
!> sigma = lambda tr(eps) I + 2 mu eps, lambda = E nu/((1 + nu)(1 - 2 nu)), mu = E/(2(1 + nu)).
!> A member of the material seam (contact2d_material_law).
module contact2d_material_hooke
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_material_law, only: material_law_t
   implicit none
   private
   public :: hooke_law_t

   !> Homogeneous isotropic linear elastic material.
   type, extends(material_law_t) :: hooke_law_t
      real(wp) :: young = 0      !< Young's modulus E [MPa]
      real(wp) :: poisson = 0    !< Poisson's ratio nu [-]
      real(wp) :: rho = 0        !< mass density [t/mm^3]
      real(wp) :: lambda = 0     !< first Lame constant [MPa]
      real(wp) :: mu = 0         !< shear modulus [MPa]
      real(wp) :: d(3, 3) = 0    !< plane-strain elasticity matrix (xx, yy, xy) [MPa]
   contains
      procedure :: init => hooke_law_init
      procedure :: dmat => hooke_law_dmat
      procedure :: density => hooke_law_density
      procedure :: sigma_zz => hooke_law_sigma_zz
      procedure :: describe => hooke_law_describe
   end type hooke_law_t

contains

   !> Set up the law from E, nu, rho. stat /= 0 with a one-line message naming the deck variable
   !> if a value is out of range (E > 0, -1 < nu < 0.5, rho > 0).
   subroutine hooke_law_init(this, young, poisson, density, stat, errmsg)
      class(hooke_law_t), intent(out) :: this
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
      this%rho = density
      this%lambda = young*poisson/((1 + poisson)*(1 - 2*poisson))
      this%mu = young/(2*(1 + poisson))
      this%d = 0
      this%d(1, 1) = this%lambda + 2*this%mu
      this%d(2, 2) = this%lambda + 2*this%mu
      this%d(1, 2) = this%lambda
      this%d(2, 1) = this%lambda
      this%d(3, 3) = this%mu
   end subroutine hooke_law_init

   !> D = [[lambda + 2 mu, lambda, 0], [lambda, lambda + 2 mu, 0], [0, 0, mu]] [MPa].
   pure function hooke_law_dmat(this) result(d)
      class(hooke_law_t), intent(in) :: this
      real(wp) :: d(3, 3)
      d = this%d
   end function hooke_law_dmat

   !> rho [t/mm^3].
   pure real(wp) function hooke_law_density(this) result(rho)
      class(hooke_law_t), intent(in) :: this
      rho = this%rho
   end function hooke_law_density

   !> Plane strain, eps_zz = 0: sigma_zz = nu (sigma_xx + sigma_yy) [MPa].
   pure real(wp) function hooke_law_sigma_zz(this, sxx, syy) result(szz)
      class(hooke_law_t), intent(in) :: this
      real(wp), intent(in) :: sxx, syy
      szz = this%poisson*(sxx + syy)
   end function hooke_law_sigma_zz

   !> 'isotropic Hooke law, plane strain: E = ... MPa, nu = ..., rho = ... t/mm^3'.
   function hooke_law_describe(this) result(line)
      class(hooke_law_t), intent(in) :: this
      character(len=:), allocatable :: line
      line = 'isotropic Hooke law, plane strain: E = '//str(this%young)//' MPa, nu = '//str(this%poisson)// &
             ', rho = '//str(this%rho)//' t/mm^3'
   end function hooke_law_describe
end module contact2d_material_hooke
