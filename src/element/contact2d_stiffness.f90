!> The assembled linear operator of the body: element stiffness matrices formed once (one per
!> distinct element shape), the internal force K u element by element, the lumped mass and the
!> critical time step (SPEC sections 2 and 4).
module contact2d_stiffness
   use contact2d_kinds, only: wp
   use contact2d_mesh, only: mesh_t
   use contact2d_material, only: material_t
   use contact2d_q1, only: q1_stiffness, q1_lumped_mass, q1_max_frequency_squared
   implicit none
   private
   public :: stiffness_t

   !> Shapes are compared on coordinates relative to the first node, to this relative tolerance.
   real(wp), parameter :: shape_tol = 1.0e-12_wp
   !> How many known shapes a new element is compared with before it gets its own matrix.
   integer, parameter :: shape_search = 8

   !> Precomputed element matrices and nodal masses of a mesh.
   type :: stiffness_t
      integer :: nshape = 0
      real(wp), allocatable :: ke(:, :, :)     !< element stiffness per shape (8, 8, nshape) [N/mm]
      integer, allocatable :: shape_of(:)      !< shape id of each element (nel)
      integer, allocatable :: conn(:, :)       !< copy of the connectivity (4, nel)
      real(wp), allocatable :: mass(:)         !< lumped nodal mass (nnode) [t]
      real(wp) :: omega2_element = 0           !< largest element omega^2 [1/s^2]
   contains
      procedure :: init => stiffness_init
      procedure :: apply => stiffness_apply
      procedure :: apply_elements => stiffness_apply_elements
      procedure :: dt_critical => stiffness_dt_critical
      procedure :: power_omega2 => stiffness_power_omega2
   end type stiffness_t

contains

   !> Form the element matrices (once per distinct shape), the lumped mass and the element
   !> bound on omega_max. stat /= 0 if LAPACK fails or an element is inverted.
   subroutine stiffness_init(this, mesh, mat, stat, errmsg)
      class(stiffness_t), intent(out) :: this
      type(mesh_t), intent(in) :: mesh
      type(material_t), intent(in) :: mat
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp), allocatable :: rel(:, :, :)
      real(wp) :: xe(2, 4), r(2, 4), omega2, scale
      integer :: e, s, first, info
      character(len=64) :: buf

      stat = 0
      errmsg = ''
      allocate (this%shape_of(mesh%nel), this%mass(mesh%nnode), rel(2, 4, mesh%nel))
      allocate (this%ke(8, 8, mesh%nel))
      this%conn = mesh%conn
      this%mass = 0
      this%nshape = 0
      do e = 1, mesh%nel
         xe = mesh%element_coordinates(e)
         if (signed_area(xe) <= 0) then
            write (buf, '(i0)') e
            stat = 1
            errmsg = 'element '//trim(buf)//' is inverted or not counter-clockwise'
            return
         end if
         this%mass(mesh%conn(:, e)) = this%mass(mesh%conn(:, e)) + q1_lumped_mass(xe, mat%density)
         r = xe - spread(xe(:, 1), 2, 4)
         scale = shape_tol*maxval(abs(r))
         this%shape_of(e) = 0
         first = max(1, this%nshape - shape_search + 1)
         do s = this%nshape, first, -1
            if (all(abs(rel(:, :, s) - r) <= scale)) then
               this%shape_of(e) = s
               exit
            end if
         end do
         if (this%shape_of(e) == 0) then
            this%nshape = this%nshape + 1
            rel(:, :, this%nshape) = r
            this%shape_of(e) = this%nshape
            call q1_stiffness(xe, mat%dmat, this%ke(:, :, this%nshape))
         end if
      end do
      this%ke = this%ke(:, :, 1:this%nshape)
      ! element bound on omega_max: one eigenproblem per shape with that shape's lumped mass
      this%omega2_element = 0
      do s = 1, this%nshape
         e = findloc(this%shape_of, s, dim=1)
         call q1_max_frequency_squared(this%ke(:, :, s), &
                                       q1_lumped_mass(mesh%element_coordinates(e), mat%density), omega2, info)
         if (info /= 0) then
            write (buf, '(i0)') info
            stat = 2
            errmsg = 'LAPACK dsygv failed in the element eigenproblem (info = '//trim(buf)//')'
            return
         end if
         this%omega2_element = max(this%omega2_element, omega2)
      end do
   end subroutine stiffness_init

   pure real(wp) function signed_area(xe)
      real(wp), intent(in) :: xe(2, 4)
      signed_area = 0.5_wp*((xe(1, 3) - xe(1, 1))*(xe(2, 4) - xe(2, 2)) &
                            - (xe(1, 4) - xe(1, 2))*(xe(2, 3) - xe(2, 1)))
   end function signed_area

   !> Critical time step 2/omega_max from the element bound [s].
   pure real(wp) function stiffness_dt_critical(this) result(dt)
      class(stiffness_t), intent(in) :: this
      dt = 2/sqrt(this%omega2_element)
   end function stiffness_dt_critical

   !> f = K u, element by element.
   subroutine stiffness_apply(this, u, f)
      class(stiffness_t), intent(in) :: this
      real(wp), intent(in) :: u(:, :)      !< displacements (2, nnode) [mm]
      real(wp), intent(out) :: f(:, :)     !< internal forces (2, nnode) [N]
      real(wp) :: ue(8), fe(8)
      integer :: e, a, n
      f = 0
      do e = 1, size(this%conn, 2)
         do a = 1, 4
            ue(2*a - 1:2*a) = u(:, this%conn(a, e))
         end do
         fe = matmul(this%ke(:, :, this%shape_of(e)), ue)
         do a = 1, 4
            n = this%conn(a, e)
            f(:, n) = f(:, n) + fe(2*a - 1:2*a)
         end do
      end do
   end subroutine stiffness_apply

   !> f = f + K_E u (or f - K_E u with subtract) over the listed elements only.
   subroutine stiffness_apply_elements(this, elements, u, f, subtract)
      class(stiffness_t), intent(in) :: this
      integer, intent(in) :: elements(:)
      real(wp), intent(in) :: u(:, :)
      real(wp), intent(inout) :: f(:, :)
      logical, intent(in) :: subtract
      real(wp) :: ue(8), fe(8), sgn
      integer :: k, e, a, n
      sgn = merge(-1.0_wp, 1.0_wp, subtract)
      do k = 1, size(elements)
         e = elements(k)
         do a = 1, 4
            ue(2*a - 1:2*a) = u(:, this%conn(a, e))
         end do
         fe = sgn*matmul(this%ke(:, :, this%shape_of(e)), ue)
         do a = 1, 4
            n = this%conn(a, e)
            f(:, n) = f(:, n) + fe(2*a - 1:2*a)
         end do
      end do
   end subroutine stiffness_apply_elements

   !> Power iteration on M^-1 K restricted to the free dofs: a lower estimate of the true
   !> omega_max^2 of the discrete system (its Rayleigh quotient), to measure how conservative the
   !> element bound is. free(2, nnode) is 1 on free dofs and 0 on prescribed ones.
   function stiffness_power_omega2(this, free, iterations) result(omega2)
      class(stiffness_t), intent(in) :: this
      real(wp), intent(in) :: free(:, :)
      integer, intent(in) :: iterations
      real(wp) :: omega2
      real(wp), allocatable :: x(:, :), y(:, :)
      real(wp) :: xmx
      integer :: it, i

      allocate (x, mold=free)
      allocate (y, mold=free)
      ! start from a node-alternating pattern (rich in the highest modes), slightly perturbed
      do i = 1, size(x, 2)
         x(:, i) = [(-1.0_wp)**i*(1 + 0.1_wp*sin(1.3_wp*i)), (-1.0_wp)**(i/2)*(1 + 0.1_wp*cos(0.7_wp*i))]
      end do
      x = x*free
      omega2 = 0
      do it = 1, iterations
         call this%apply(x, y)
         y = y*free
         xmx = sum(spread(this%mass, 1, 2)*x*x)
         omega2 = sum(x*y)/xmx
         y = y/spread(this%mass, 1, 2)
         x = y/sqrt(sum(spread(this%mass, 1, 2)*y*y))
      end do
   end function stiffness_power_omega2
end module contact2d_stiffness
