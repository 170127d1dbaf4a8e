!> Bilinear quadrilateral (Q1) plane-strain element with 2x2 Gauss integration (SPEC section 2).
!>
!> Local nodes are counter-clockwise, 1 = (-1,-1), 2 = (1,-1), 3 = (1,1), 4 = (-1,1) in the
!> reference square; local dofs are ordered (x1, y1, x2, y2, x3, y3, x4, y4).
!> Every routine here works on one element: the time loop never calls them. q1_element_t is the
!> member of the element seam (contact2d_element); the q1_* routines are its kernels.
module contact2d_q1
   use contact2d_kinds, only: wp
   use contact2d_element, only: element_t
   implicit none
   private
   public :: q1_stiffness, q1_lumped_mass, q1_area, q1_stress_average, q1_max_frequency_squared
   public :: q1_gradients, q1_element_t

   real(wp), parameter :: g = 0.577350269189625764509148780502_wp   ! 1/sqrt(3)
   !> Gauss points of the 2x2 rule (weights are all 1).
   real(wp), parameter :: gauss_xi(4) = [-g, g, g, -g]
   real(wp), parameter :: gauss_eta(4) = [-g, -g, g, g]
   !> Reference coordinates of the four nodes.
   real(wp), parameter :: node_xi(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp]
   real(wp), parameter :: node_eta(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]

   !> The Q1 element with 2 x 2 Gauss points, the member of the element seam.
   type, extends(element_t) :: q1_element_t
   contains
      procedure :: nodes => q1_element_nodes
      procedure :: gauss_points => q1_element_nodes   ! four nodes, four Gauss points
      procedure :: gauss => q1_element_gauss
      procedure :: bmat => q1_element_bmat
      procedure :: stiffness => q1_element_stiffness
      procedure :: lumped_mass => q1_element_lumped_mass
      procedure :: max_frequency_squared => q1_element_max_frequency_squared
      procedure :: stress_average => q1_element_stress_average
   end type q1_element_t

contains

   !> Four nodes (and four Gauss points).
   pure integer function q1_element_nodes(this) result(n)
      class(q1_element_t), intent(in) :: this
      n = 4
   end function q1_element_nodes

   !> q1_gradients at Gauss point q of the 2 x 2 rule (weights 1).
   pure subroutine q1_element_gauss(this, xe, q, n, dndx, detj)
      class(q1_element_t), intent(in) :: this
      real(wp), intent(in) :: xe(:, :)
      integer, intent(in) :: q
      real(wp), intent(out) :: n(:), dndx(:, :), detj
      real(wp) :: n4(4), d4(2, 4)
      call q1_gradients(xe, gauss_xi(q), gauss_eta(q), n4, d4, detj)
      n = n4
      dndx = d4
   end subroutine q1_element_gauss

   !> b_matrix of the gradients.
   pure subroutine q1_element_bmat(this, dndx, b)
      class(q1_element_t), intent(in) :: this
      real(wp), intent(in) :: dndx(:, :)
      real(wp), intent(out) :: b(:, :)
      b = b_matrix(dndx)
   end subroutine q1_element_bmat

   !> q1_stiffness.
   pure subroutine q1_element_stiffness(this, xe, dmat, ke)
      class(q1_element_t), intent(in) :: this
      real(wp), intent(in) :: xe(:, :), dmat(3, 3)
      real(wp), intent(out) :: ke(:, :)
      real(wp) :: k8(8, 8)
      call q1_stiffness(xe, dmat, k8)
      ke = k8
   end subroutine q1_element_stiffness

   !> q1_lumped_mass.
   pure subroutine q1_element_lumped_mass(this, xe, density, me)
      class(q1_element_t), intent(in) :: this
      real(wp), intent(in) :: xe(:, :), density
      real(wp), intent(out) :: me(:)
      me = q1_lumped_mass(xe, density)
   end subroutine q1_element_lumped_mass

   !> q1_max_frequency_squared.
   subroutine q1_element_max_frequency_squared(this, ke, me, omega2, stat)
      class(q1_element_t), intent(in) :: this
      real(wp), intent(in) :: ke(:, :), me(:)
      real(wp), intent(out) :: omega2
      integer, intent(out) :: stat
      call q1_max_frequency_squared(ke, me, omega2, stat)
   end subroutine q1_element_max_frequency_squared

   !> q1_stress_average.
   pure function q1_element_stress_average(this, xe, dmat, ue) result(sig)
      class(q1_element_t), intent(in) :: this
      real(wp), intent(in) :: xe(:, :), dmat(3, 3), ue(:)
      real(wp) :: sig(3)
      sig = q1_stress_average(xe, dmat, ue)
   end function q1_element_stress_average

   !> Shape-function values and physical gradients at (xi, eta); det J is returned in detj.
   pure subroutine q1_gradients(xe, xi, eta, n, dndx, detj)
      real(wp), intent(in) :: xe(2, 4)     !< nodal coordinates [mm]
      real(wp), intent(in) :: xi, eta      !< reference point
      real(wp), intent(out) :: n(4)        !< shape functions
      real(wp), intent(out) :: dndx(2, 4)  !< dN_a/dx, dN_a/dy [1/mm]
      real(wp), intent(out) :: detj        !< Jacobian determinant [mm^2]
      real(wp) :: dnref(2, 4), jac(2, 2), jinv(2, 2)

      n = 0.25_wp*(1 + node_xi*xi)*(1 + node_eta*eta)
      dnref(1, :) = 0.25_wp*node_xi*(1 + node_eta*eta)
      dnref(2, :) = 0.25_wp*node_eta*(1 + node_xi*xi)
      ! jac(i, j) = d x_j / d xi_i
      jac = matmul(dnref, transpose(xe))
      detj = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
      jinv(1, 1) = jac(2, 2)/detj
      jinv(2, 2) = jac(1, 1)/detj
      jinv(1, 2) = -jac(1, 2)/detj
      jinv(2, 1) = -jac(2, 1)/detj
      dndx = matmul(jinv, dnref)
   end subroutine q1_gradients

   !> Strain-displacement matrix B (3 x 8), engineering shear, from the gradients.
   pure function b_matrix(dndx) result(b)
      real(wp), intent(in) :: dndx(2, 4)
      real(wp) :: b(3, 8)
      integer :: a
      b = 0
      do a = 1, 4
         b(1, 2*a - 1) = dndx(1, a)
         b(2, 2*a) = dndx(2, a)
         b(3, 2*a - 1) = dndx(2, a)
         b(3, 2*a) = dndx(1, a)
      end do
   end function b_matrix

   !> Element stiffness K_e = sum over Gauss points of B^T D B det J (unit thickness) [N/mm].
   pure subroutine q1_stiffness(xe, dmat, ke)
      real(wp), intent(in) :: xe(2, 4)     !< nodal coordinates [mm]
      real(wp), intent(in) :: dmat(3, 3)   !< plane-strain elasticity matrix [MPa]
      real(wp), intent(out) :: ke(8, 8)    !< element stiffness [N/mm]
      real(wp) :: n(4), dndx(2, 4), detj, b(3, 8)
      integer :: q

      ke = 0
      do q = 1, 4
         call q1_gradients(xe, gauss_xi(q), gauss_eta(q), n, dndx, detj)
         b = b_matrix(dndx)
         ke = ke + matmul(transpose(b), matmul(dmat, b))*detj
      end do
      ! Symmetrize exactly: the sum above is symmetric up to round-off only.
      ke = 0.5_wp*(ke + transpose(ke))
   end subroutine q1_stiffness

   !> Row-sum lumped mass: m_a = rho * integral of N_a (exact with 2x2 Gauss) [t].
   pure function q1_lumped_mass(xe, density) result(me)
      real(wp), intent(in) :: xe(2, 4)     !< nodal coordinates [mm]
      real(wp), intent(in) :: density      !< rho [t/mm^3]
      real(wp) :: me(4)
      real(wp) :: n(4), dndx(2, 4), detj
      integer :: q
      me = 0
      do q = 1, 4
         call q1_gradients(xe, gauss_xi(q), gauss_eta(q), n, dndx, detj)
         me = me + density*n*detj
      end do
   end function q1_lumped_mass

   !> Element area (exact for a bilinear map) [mm^2].
   pure real(wp) function q1_area(xe) result(area)
      real(wp), intent(in) :: xe(2, 4)
      area = 0.5_wp*((xe(1, 3) - xe(1, 1))*(xe(2, 4) - xe(2, 2)) &
                     - (xe(1, 4) - xe(1, 2))*(xe(2, 3) - xe(2, 1)))
   end function q1_area

   !> Average of the four Gauss-point stresses (sxx, syy, sxy) [MPa].
   pure function q1_stress_average(xe, dmat, ue) result(sig)
      real(wp), intent(in) :: xe(2, 4)     !< nodal coordinates [mm]
      real(wp), intent(in) :: dmat(3, 3)   !< elasticity matrix [MPa]
      real(wp), intent(in) :: ue(8)        !< element displacements [mm]
      real(wp) :: sig(3)
      real(wp) :: n(4), dndx(2, 4), detj
      integer :: q
      sig = 0
      do q = 1, 4
         call q1_gradients(xe, gauss_xi(q), gauss_eta(q), n, dndx, detj)
         sig = sig + matmul(dmat, matmul(b_matrix(dndx), ue))
      end do
      sig = 0.25_wp*sig
   end function q1_stress_average

   !> Largest eigenvalue omega^2 of K_e phi = omega^2 M_e phi with the lumped M_e (SPEC section 4),
   !> from LAPACK dsygv. stat is LAPACK's info.
   subroutine q1_max_frequency_squared(ke, me, omega2, stat)
      real(wp), intent(in) :: ke(8, 8)     !< element stiffness [N/mm]
      real(wp), intent(in) :: me(4)        !< lumped nodal masses [t]
      real(wp), intent(out) :: omega2      !< largest omega^2 [1/s^2]
      integer, intent(out) :: stat
      real(wp) :: a(8, 8), b(8, 8), w(8), work(64)
      integer :: i
      external :: dsygv

      a = ke
      b = 0
      do i = 1, 4
         b(2*i - 1, 2*i - 1) = me(i)
         b(2*i, 2*i) = me(i)
      end do
      call dsygv(1, 'N', 'U', 8, a, 8, b, 8, w, work, size(work), stat)
      omega2 = w(8)
   end subroutine q1_max_frequency_squared
end module contact2d_q1
