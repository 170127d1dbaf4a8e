!> The element seam (docs/architecture.md, "Seams"): what set-up and output ask of a
!> plane-strain element with Gauss integration: shape functions and their gradients at the Gauss
!> points, the strain-displacement matrix B, the element stiffness and lumped mass, the element's
!> largest frequency (the stable step bound, SPEC section 4) and the average stress of the
!> element. Member: contact2d_q1 (q1_element_t); contact2d_element_factory makes one by name.
!> Called at set-up and output only: the step kernels (contact2d_sweep, contact2d_rows) work on
!> the assembled 2 x 2 blocks of K and never call an element.
module contact2d_element
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: element_t

   !> An isoparametric plane-strain element; dofs ordered (x1, y1, x2, y2, ...) over its nodes.
   type, abstract :: element_t
   contains
      !> Nodes per element (mesh_t%conn holds four).
      procedure(element_count), deferred :: nodes
      !> Gauss points of the element's rule.
      procedure(element_count), deferred :: gauss_points
      !> Shape functions, physical gradients and det J at Gauss point q (weights folded in det J).
      procedure(element_gauss), deferred :: gauss
      !> Strain-displacement matrix B (3 x 2 nodes), engineering shear, from the gradients.
      procedure(element_bmat), deferred :: bmat
      !> Element stiffness K_e = integral of B^T D B (unit thickness) [N/mm].
      procedure(element_stiffness), deferred :: stiffness
      !> Lumped (row-sum) nodal masses [t].
      procedure(element_mass), deferred :: lumped_mass
      !> Largest omega^2 of K_e phi = omega^2 M_e phi with the lumped M_e [1/s^2].
      procedure(element_frequency), deferred :: max_frequency_squared
      !> Average of the Gauss-point stresses D B u_e (sxx, syy, sxy) [MPa].
      procedure(element_stress), deferred :: stress_average
   end type element_t

   abstract interface
      pure integer function element_count(this) result(n)
         import :: element_t
         class(element_t), intent(in) :: this
      end function element_count

      pure subroutine element_gauss(this, xe, q, n, dndx, detj)
         import :: element_t, wp
         class(element_t), intent(in) :: this
         real(wp), intent(in) :: xe(:, :)       !< nodal coordinates (2, nodes) [mm]
         integer, intent(in) :: q               !< Gauss point, 1 .. gauss_points()
         real(wp), intent(out) :: n(:)          !< shape functions (nodes)
         real(wp), intent(out) :: dndx(:, :)    !< dN_a/dx, dN_a/dy (2, nodes) [1/mm]
         real(wp), intent(out) :: detj          !< det J times the Gauss weight [mm^2]
      end subroutine element_gauss

      pure subroutine element_bmat(this, dndx, b)
         import :: element_t, wp
         class(element_t), intent(in) :: this
         real(wp), intent(in) :: dndx(:, :)     !< (2, nodes) [1/mm]
         real(wp), intent(out) :: b(:, :)       !< (3, 2 nodes) [1/mm]
      end subroutine element_bmat

      pure subroutine element_stiffness(this, xe, dmat, ke)
         import :: element_t, wp
         class(element_t), intent(in) :: this
         real(wp), intent(in) :: xe(:, :)       !< nodal coordinates (2, nodes) [mm]
         real(wp), intent(in) :: dmat(3, 3)     !< plane-strain elasticity matrix [MPa]
         real(wp), intent(out) :: ke(:, :)      !< (2 nodes, 2 nodes) [N/mm]
      end subroutine element_stiffness

      pure subroutine element_mass(this, xe, density, me)
         import :: element_t, wp
         class(element_t), intent(in) :: this
         real(wp), intent(in) :: xe(:, :)       !< nodal coordinates (2, nodes) [mm]
         real(wp), intent(in) :: density        !< rho [t/mm^3]
         real(wp), intent(out) :: me(:)         !< nodal masses (nodes) [t]
      end subroutine element_mass

      subroutine element_frequency(this, ke, me, omega2, stat)
         import :: element_t, wp
         class(element_t), intent(in) :: this
         real(wp), intent(in) :: ke(:, :)       !< element stiffness [N/mm]
         real(wp), intent(in) :: me(:)          !< lumped nodal masses [t]
         real(wp), intent(out) :: omega2        !< largest omega^2 [1/s^2]
         integer, intent(out) :: stat           !< LAPACK's info
      end subroutine element_frequency

      pure function element_stress(this, xe, dmat, ue) result(sig)
         import :: element_t, wp
         class(element_t), intent(in) :: this
         real(wp), intent(in) :: xe(:, :)       !< nodal coordinates (2, nodes) [mm]
         real(wp), intent(in) :: dmat(3, 3)     !< elasticity matrix [MPa]
         real(wp), intent(in) :: ue(:)          !< element displacements (2 nodes) [mm]
         real(wp) :: sig(3)
      end function element_stress
   end interface
end module contact2d_element
