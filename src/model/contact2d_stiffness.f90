!> The assembled linear operator of the body: element stiffness matrices formed once (one per
!> distinct element shape), the internal force K u element by element, the lumped mass and the
!> critical time step (SPEC sections 2 and 4).
module contact2d_stiffness
   use contact2d_kinds, only: wp
   use contact2d_mesh, only: mesh_t, node_elements
   use contact2d_material, only: material_t
   use contact2d_element, only: element_t
   use contact2d_element_factory, only: element_create
   implicit none
   private
   public :: stiffness_t

   !> Shapes are compared on coordinates relative to the first node, to this relative tolerance.
   real(wp), parameter :: shape_tol = 1.0e-12_wp
   !> How many known shapes a new element is compared with before it gets its own matrix.
   integer, parameter :: shape_search = 8

   !> Meshes with fewer nodes run the kernels on one thread (a parallel region costs more than
   !> the work; see docs/performance.md).
   integer, parameter, public :: omp_min_nodes = 4096

   !> Offsets (i, j) of the four local nodes of a structured element from its bottom-left node.
   integer, parameter :: off(2, 4) = reshape([0, 0, 1, 0, 1, 1, 0, 1], [2, 4])

   !> Precomputed element matrices and nodal masses of a mesh.
   !>
   !> K u is a gather over nodes (each node sums the rows of its elements' matrices), so it is
   !> race-free and gives the same bits for any number of OpenMP threads. A structured mesh of
   !> equal elements uses the assembled 9-point stencil of 2 x 2 blocks on interior nodes.
   type :: stiffness_t
      integer :: nshape = 0
      integer :: nnode = 0
      real(wp), allocatable :: ke(:, :, :)     !< element stiffness per shape (8, 8, nshape) [N/mm]
      integer, allocatable :: shape_of(:)      !< shape id of each element (nel)
      integer, allocatable :: conn(:, :)       !< copy of the connectivity (4, nel)
      real(wp), allocatable :: mass(:)         !< lumped nodal mass (nnode) [t]
      real(wp) :: omega2_element = 0           !< largest element omega^2 [1/s^2]
      !> the element (the element seam): its matrices and masses here, the stresses in the writer
      class(element_t), allocatable :: element
      ! rows of K in block-CSR form (2 x 2 blocks): every node of a general mesh, the boundary
      ! nodes of a structured one
      integer, allocatable :: row_node(:)      !< node of each block row
      integer, allocatable :: row_start(:)     !< first block of each row, (nrow + 1)
      integer, allocatable :: blk_col(:)       !< node of each block
      real(wp), allocatable :: blk(:, :, :)    !< (2, 2, nblock) [N/mm]
      ! structured mesh of equal elements
      logical :: structured = .false.
      integer :: nx = 0, ny = 0
      real(wp) :: stencil(2, 2, -1:1, -1:1) = 0   !< interior stencil blocks [N/mm]
   contains
      procedure :: init => stiffness_init
      procedure :: init_bodies => stiffness_init_bodies
      procedure :: apply => stiffness_apply
      procedure :: apply_elements => stiffness_apply_elements
      procedure :: dt_critical => stiffness_dt_critical
      procedure :: power_omega2 => stiffness_power_omega2
   end type stiffness_t

contains

   !> Form the element matrices (once per distinct shape), the lumped mass and the element
   !> bound on omega_max, every element of material `mat` (one body). stat /= 0 if LAPACK fails
   !> or an element is inverted.
   subroutine stiffness_init(this, mesh, mat, stat, errmsg)
      class(stiffness_t), intent(out) :: this
      type(mesh_t), intent(in) :: mesh
      type(material_t), intent(in) :: mat
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer :: e
      call stiffness_init_bodies(this, mesh, [mat], [(1, e=1, mesh%nel)], stat, errmsg)
   end subroutine stiffness_init

   !> As stiffness_init with element e of material mats(body_of(e)) (several bodies): a shape is
   !> a geometry and a material, so two equal elements of two bodies get two matrices and two
   !> lumped masses, and the element bound on omega_max is the largest over every body's shapes
   !> (SPEC section 4: the critical step of the whole mesh).
   subroutine stiffness_init_bodies(this, mesh, mats, body_of, stat, errmsg)
      class(stiffness_t), intent(out) :: this
      type(mesh_t), intent(in) :: mesh
      type(material_t), intent(in) :: mats(:)
      integer, intent(in) :: body_of(:)   !< (nel) index into mats of each element
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp), allocatable :: rel(:, :, :), me(:, :)
      integer, allocatable :: shape_body(:)
      real(wp) :: xe(2, 4), r(2, 4), omega2, scale
      integer :: e, s, first, info
      character(len=64) :: buf

      ! the mesh's elements have four nodes: Q1 (docs/architecture.md, "Seams")
      call element_create('q1', this%element, stat, errmsg)
      if (stat /= 0) return
      allocate (this%shape_of(mesh%nel), this%mass(mesh%nnode), rel(2, 4, mesh%nel))
      allocate (this%ke(8, 8, mesh%nel), me(4, mesh%nel), shape_body(mesh%nel))
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
         r = xe - spread(xe(:, 1), 2, 4)
         scale = shape_tol*maxval(abs(r))
         this%shape_of(e) = 0
         first = max(1, this%nshape - shape_search + 1)
         do s = this%nshape, first, -1
            if (shape_body(s) /= body_of(e)) cycle
            if (all(abs(rel(:, :, s) - r) <= scale)) then
               this%shape_of(e) = s
               exit
            end if
         end do
         if (this%shape_of(e) == 0) then
            this%nshape = this%nshape + 1
            rel(:, :, this%nshape) = r
            shape_body(this%nshape) = body_of(e)
            this%shape_of(e) = this%nshape
            associate (mat => mats(body_of(e)))
               call this%element%stiffness(xe, mat%dmat(), this%ke(:, :, this%nshape))
               call this%element%lumped_mass(xe, mat%density(), me(:, this%nshape))
            end associate
         end if
         ! the lumped mass of the element's shape, as its stiffness: every element of a shape
         ! the same masses to the bit (docs/performance.md "Masses by shape")
         this%mass(mesh%conn(:, e)) = this%mass(mesh%conn(:, e)) + me(:, this%shape_of(e))
      end do
      this%ke = this%ke(:, :, 1:this%nshape)
      ! element bound on omega_max: one eigenproblem per shape with that shape's lumped mass
      this%omega2_element = 0
      do s = 1, this%nshape
         call this%element%max_frequency_squared(this%ke(:, :, s), me(:, s), omega2, info)
         if (info /= 0) then
            write (buf, '(i0)') info
            stat = 2
            errmsg = 'LAPACK dsygv failed in the element eigenproblem (info = '//trim(buf)//')'
            return
         end if
         this%omega2_element = max(this%omega2_element, omega2)
      end do
      this%nnode = mesh%nnode
      this%structured = mesh%nx > 0 .and. this%nshape == 1
      if (this%structured) then
         this%nx = mesh%nx
         this%ny = mesh%ny
         call build_stencil(this)
         call build_rows(this, perimeter(mesh%nx, mesh%ny))
      else
         call build_rows(this, [(e, e=1, mesh%nnode)])
      end if
   end subroutine stiffness_init_bodies

   !> Block-CSR rows of K for the given nodes: K(n, m) = sum over the elements holding n and m of
   !> the 2 x 2 block of K_e, columns in increasing node order.
   subroutine build_rows(this, rows)
      type(stiffness_t), intent(inout) :: this
      integer, intent(in) :: rows(:)
      integer, allocatable :: adj_start(:), adj_elem(:), cols(:)
      real(wp), allocatable :: blocks(:, :, :)
      integer :: e, a, b, n, m, r, k, nel, ncol, pos, nb
      logical, allocatable :: is_row(:)

      nel = size(this%conn, 2)
      ! node -> elements
      call node_elements(this%conn, this%nnode, adj_start, adj_elem)
      allocate (is_row(this%nnode))
      is_row = .false.
      is_row(rows) = .true.
      ! at most four blocks per element of the row's node before merging duplicates (a node of
      ! valence 8 has 17 distinct columns: no fixed bound)
      k = 0
      nb = 0
      do r = 1, size(rows)
         ncol = 4*(adj_start(rows(r) + 1) - adj_start(rows(r)))
         k = max(k, ncol)
         nb = nb + ncol
      end do
      allocate (cols(k), blocks(2, 2, k))
      allocate (this%row_node(size(rows)), this%row_start(size(rows) + 1), &
                this%blk_col(nb), this%blk(2, 2, nb))
      nb = 0
      do r = 1, size(rows)
         n = rows(r)
         this%row_node(r) = n
         this%row_start(r) = nb + 1
         ncol = 0
         do k = adj_start(n), adj_start(n + 1) - 1
            e = adj_elem(k)
            a = findloc(this%conn(:, e), n, dim=1)
            do b = 1, 4
               m = this%conn(b, e)
               pos = 0
               if (ncol > 0) pos = findloc(cols(1:ncol), m, dim=1)
               if (pos == 0) then
                  ncol = ncol + 1
                  cols(ncol) = m
                  blocks(:, :, ncol) = 0
                  pos = ncol
               end if
               blocks(:, :, pos) = blocks(:, :, pos) + this%ke(2*a - 1:2*a, 2*b - 1:2*b, this%shape_of(e))
            end do
         end do
         ! columns in increasing order: a fixed summation order
         do k = 1, ncol
            pos = minloc(cols(1:ncol), dim=1)
            nb = nb + 1
            this%blk_col(nb) = cols(pos)
            this%blk(:, :, nb) = blocks(:, :, pos)
            cols(pos) = huge(1)
         end do
      end do
      this%row_start(size(rows) + 1) = nb + 1
      this%blk_col = this%blk_col(1:nb)
      this%blk = this%blk(:, :, 1:nb)
   end subroutine build_rows

   !> Node ids of the boundary of a structured (nx, ny) mesh.
   pure function perimeter(nx, ny) result(nodes)
      integer, intent(in) :: nx, ny
      integer, allocatable :: nodes(:)
      integer :: i, j
      nodes = [integer ::]
      do j = 0, ny
         do i = 0, nx
            if (i == 0 .or. i == nx .or. j == 0 .or. j == ny) nodes = [nodes, i + (nx + 1)*j + 1]
         end do
      end do
   end function perimeter

   !> Interior stencil: S(d) = sum over the four elements around a node of the block K_ab of
   !> the element matrix, with d = offset(b) - offset(a).
   subroutine build_stencil(this)
      type(stiffness_t), intent(inout) :: this
      integer :: a, b, d(2)
      this%stencil = 0
      do a = 1, 4
         do b = 1, 4
            d = off(:, b) - off(:, a)
            this%stencil(:, :, d(1), d(2)) = this%stencil(:, :, d(1), d(2)) + this%ke(2*a - 1:2*a, 2*b - 1:2*b, 1)
         end do
      end do
   end subroutine build_stencil

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

   !> f = K u (a gather over nodes; the same bits for any number of threads).
   subroutine stiffness_apply(this, u, f)
      class(stiffness_t), intent(in) :: this
      real(wp), intent(in) :: u(:, :)      !< displacements (2, nnode) [mm]
      real(wp), intent(inout) :: f(:, :)   !< internal forces (2, nnode) [N], all overwritten
      ! one parallel region; the loops inside are work-shared (orphaned omp do)
      !$omp parallel if(this%nnode >= omp_min_nodes)
      if (this%structured) call apply_structured(this, this%nx, this%ny, u, f)
      call apply_rows(this, u, f)
      !$omp end parallel
   end subroutine stiffness_apply

   !> f(:, n) = sum of the 2 x 2 blocks of row n times u, for the block rows of K.
   subroutine apply_rows(this, u, f)
      type(stiffness_t), intent(in) :: this
      real(wp), intent(in) :: u(:, :)
      real(wp), intent(inout) :: f(:, :)
      integer :: r, k, m, n
      real(wp) :: fx, fy
      !$omp do schedule(static)
      do r = 1, size(this%row_node)
         fx = 0
         fy = 0
         do k = this%row_start(r), this%row_start(r + 1) - 1
            m = this%blk_col(k)
            fx = fx + this%blk(1, 1, k)*u(1, m) + this%blk(1, 2, k)*u(2, m)
            fy = fy + this%blk(2, 1, k)*u(1, m) + this%blk(2, 2, k)*u(2, m)
         end do
         n = this%row_node(r)
         f(1, n) = fx
         f(2, n) = fy
      end do
      !$omp end do
   end subroutine apply_rows

   !> Structured mesh of equal elements, u and f seen as (2, 0:nx, 0:ny): the 9-point stencil on
   !> interior nodes (vectorised along rows, rows shared among threads), block rows on the
   !> boundary nodes.
   subroutine apply_structured(this, nx, ny, u, f)
      type(stiffness_t), intent(in) :: this
      integer, intent(in) :: nx, ny
      real(wp), intent(in) :: u(2, 0:nx, 0:ny)
      real(wp), intent(inout) :: f(2, 0:nx, 0:ny)
      integer :: i, j
      real(wp) :: fx, fy, s(2, 2, -1:1, -1:1)
      s = this%stencil   ! a local copy: the compiler then sees no aliasing and vectorises
      !$omp do schedule(static)
      do j = 1, ny - 1
         do i = 1, nx - 1
            fx = s(1, 1, -1, -1)*u(1, i - 1, j - 1) + s(1, 2, -1, -1)*u(2, i - 1, j - 1) &
                 + s(1, 1, 0, -1)*u(1, i, j - 1) + s(1, 2, 0, -1)*u(2, i, j - 1) &
                 + s(1, 1, 1, -1)*u(1, i + 1, j - 1) + s(1, 2, 1, -1)*u(2, i + 1, j - 1) &
                 + s(1, 1, -1, 0)*u(1, i - 1, j) + s(1, 2, -1, 0)*u(2, i - 1, j) &
                 + s(1, 1, 0, 0)*u(1, i, j) + s(1, 2, 0, 0)*u(2, i, j) &
                 + s(1, 1, 1, 0)*u(1, i + 1, j) + s(1, 2, 1, 0)*u(2, i + 1, j) &
                 + s(1, 1, -1, 1)*u(1, i - 1, j + 1) + s(1, 2, -1, 1)*u(2, i - 1, j + 1) &
                 + s(1, 1, 0, 1)*u(1, i, j + 1) + s(1, 2, 0, 1)*u(2, i, j + 1) &
                 + s(1, 1, 1, 1)*u(1, i + 1, j + 1) + s(1, 2, 1, 1)*u(2, i + 1, j + 1)
            fy = s(2, 1, -1, -1)*u(1, i - 1, j - 1) + s(2, 2, -1, -1)*u(2, i - 1, j - 1) &
                 + s(2, 1, 0, -1)*u(1, i, j - 1) + s(2, 2, 0, -1)*u(2, i, j - 1) &
                 + s(2, 1, 1, -1)*u(1, i + 1, j - 1) + s(2, 2, 1, -1)*u(2, i + 1, j - 1) &
                 + s(2, 1, -1, 0)*u(1, i - 1, j) + s(2, 2, -1, 0)*u(2, i - 1, j) &
                 + s(2, 1, 0, 0)*u(1, i, j) + s(2, 2, 0, 0)*u(2, i, j) &
                 + s(2, 1, 1, 0)*u(1, i + 1, j) + s(2, 2, 1, 0)*u(2, i + 1, j) &
                 + s(2, 1, -1, 1)*u(1, i - 1, j + 1) + s(2, 2, -1, 1)*u(2, i - 1, j + 1) &
                 + s(2, 1, 0, 1)*u(1, i, j + 1) + s(2, 2, 0, 1)*u(2, i, j + 1) &
                 + s(2, 1, 1, 1)*u(1, i + 1, j + 1) + s(2, 2, 1, 1)*u(2, i + 1, j + 1)
            f(1, i, j) = fx
            f(2, i, j) = fy
         end do
      end do
      ! no barrier: the boundary rows that follow write other nodes and only read u
      !$omp end do nowait
   end subroutine apply_structured

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

   !> Power iteration on M^-1 K (plus an optional diagonal stiffness) restricted to the free dofs: a lower estimate of the true
   !> omega_max^2 of the discrete system (its Rayleigh quotient), to measure how conservative the
   !> element bound is. free(2, nnode) is 1 on free dofs and 0 on prescribed ones.
   function stiffness_power_omega2(this, free, iterations, extra) result(omega2)
      class(stiffness_t), intent(in) :: this
      real(wp), intent(in), contiguous :: free(:, :)
      integer, intent(in) :: iterations
      !> an extra diagonal stiffness (2, nnode) added to K, e.g. contact penalty springs [N/mm]
      real(wp), intent(in), optional :: extra(:, :)
      real(wp) :: omega2
      real(wp), allocatable :: x(:, :), y(:, :)
      real(wp) :: xmx, xy, ymy, ynorm, y1, y2
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
         ! omega2 = x'y / x'Mx with y = free (K + extra) x; then x = M^-1 y / |M^-1 y|_M
         if (present(extra)) y = y + extra*x
         xmx = 0
         xy = 0
         ymy = 0
         ! (a vector loop: the iterations are a set-up cost of the order of 100 steps)
         !$omp simd private(y1, y2) reduction(+:xmx, xy, ymy)
         do i = 1, size(x, 2)
            y1 = y(1, i)*free(1, i)
            y2 = y(2, i)*free(2, i)
            xmx = xmx + this%mass(i)*(x(1, i)**2 + x(2, i)**2)
            xy = xy + (x(1, i)*y1 + x(2, i)*y2)
            y1 = y1/this%mass(i)
            y2 = y2/this%mass(i)
            ymy = ymy + this%mass(i)*(y1**2 + y2**2)
            y(1, i) = y1
            y(2, i) = y2
         end do
         omega2 = xy/xmx
         ynorm = sqrt(ymy)
         !$omp simd
         do i = 1, size(x, 2)
            x(1, i) = y(1, i)/ynorm
            x(2, i) = y(2, i)/ynorm
         end do
      end do
   end function stiffness_power_omega2
end module contact2d_stiffness
