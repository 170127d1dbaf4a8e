!> The sweep of contact2d_sweep on a general (Gmsh) mesh (issue 13, docs/performance.md
!> "general path"): chunk by chunk of block rows, the internal force K u^n from the block rows
!> of contact2d_stiffness, then, while the chunk is in cache, the predictor v* (written into v),
!> u~ and the energy sums of v* (the quantities of contact2d_sweep's module header).
!>
!> The rows of a general mesh are all its nodes in node order (stiffness_init builds them so:
!> row r is node r), so the per-node state is addressed directly and, inside a chunk, as flat
!> arrays of interleaved (x, y) dofs: the predictor and the sums are one plain vector loop with
!> per-dof masses (held here: a general mesh has no row pattern to keep them shorter).
!>
!> Rows are taken by pairs (2k - 1, 2k) and stored in a fixed layout of 12 column slots (a node
!> of a regular quad mesh has 9 neighbours, itself included; 94 % of the rows of the refined
!> Hertz meshes; two nodes of one element edge have 6 of them in common, and contact2d_renumber
!> numbers edge neighbours in pairs): 6 slots shared by both rows, 3 of each row alone (rows_init).
!> Free slots hold zero blocks on the pair's first node; blocks that find no slot go to a small
!> CSR remainder, added after the chunk's fixed-layout pass. So the product of a pair is
!> !> straight-line code with no loop and no data-dependent branch. Each 2 x 2 block B is stored as
!> (b11, b22, b12, b21) and u is first copied, node by node, into ud = (ux, uy, uy, ux): the
!> product of a block is then one 4-wide multiply-add, lanes (b11 ux, b22 uy, b12 uy, b21 ux),
!> whose lanes 1 + 3 and 2 + 4 are the row's x and y (three accumulators of three blocks each:
!> short dependency chains). Column offsets are 32-bit (4 (m - 1) into ud: fewer bytes; the
!> sign-extending load costs no instruction more). The order of every sum is fixed by the
!> layout, and chunks are fixed (chunk_rows rows) with their partial sums added in chunk order
!> by the caller, so the bits do not depend on the number of threads or on which thread does
!> which chunk.
!>
!> With full = .false. (contact2d_sweep's module header) K u goes to a scratch of the chunk (in
!> the first-level cache) instead of f, f is stored only at the kept rows (the nodes on the
!> mesh's boundary: an edge of one element only), and the sum u~ . K u is not formed, as by the
!> inside rows of structured meshes; the values stored and the other sums are the same bits.
module contact2d_rows
   use, intrinsic :: iso_fortran_env, only: int32
   use contact2d_kinds, only: wp, i8
   use, intrinsic :: iso_c_binding, only: c_loc, c_intptr_t
   use contact2d_stiffness, only: stiffness_t, omp_min_nodes
   use contact2d_mesh, only: node_elements
   implicit none
   private
   public :: rows_t

   !> Column slots of a pair of rows: 6 shared by both rows, then 3 of the first row only and 3
   !> of the second only (pair_width = 12; each row has 9 blocks: row_width).
   integer, parameter :: pair_width = 12, row_width = 9, n_shared = 6, n_own = 3
   !> Block rows per chunk (and per partial sum; even, so that no pair straddles two chunks): the
   !> chunk's u, v, K u, u~ and masses (2 x 256 doubles each) stay in the first-level cache from
   !> the products to the predictor loop.
   integer, parameter :: chunk_rows = 256

   !> The block rows of K of a general mesh (row r is node r), laid out for the sweep by pairs of
   !> rows (2k - 1, 2k).
   type :: rows_t
      integer :: nnode = 0
      integer :: npair = 0
      !> offset 4 (m - 1) into ud of the column node m of each slot of each pair (pair_width, npair)
      integer(int32), allocatable :: col(:, :)
      !> (b11, b22, b12, b21) of each block of a pair (4, 2 n_shared + 2 n_own, npair): slot s <=
      !> n_shared of the first row at 2 s - 1, of the second at 2 s; the first row's own slots
      !> then the second's [N/mm]
      real(wp), allocatable :: blk(:, :, :)
      integer, allocatable :: xstart(:)         !< remainder: first extra block of each row (nnode + 1)
      integer(int32), allocatable :: xcol(:)    !< remainder: offsets into ud
      integer, allocatable :: xrow(:)           !< remainder: row of each extra block
      real(wp), allocatable :: xblk(:, :)       !< remainder: blocks (4, nextra), as blk [N/mm]
      real(wp), allocatable :: mdof(:), minvdof(:)   !< mass and 1/mass per dof (2 nnode) [t], [1/t]
      !> scratch of the sweep: (ux, uy, uy, ux) of each node, from the first element on a 64-byte
      !> boundary on (rows_sweep), so that every node's four values are one aligned vector (no
      !> load across two cache lines) (4 nnode + 8) [mm]
      real(wp), allocatable :: ud(:)
      !> nodes whose K u every sweep stores, full or not: those on the mesh's boundary (nnode)
      logical, allocatable :: kept(:)
      !> the kept rows of chunk c are krow(kstart(c) : kstart(c + 1) - 1), in increasing order
      integer, allocatable :: kstart(:), krow(:)
   contains
      procedure :: init => rows_init
      procedure :: parts => rows_parts
      procedure :: sweep => rows_sweep
   end type rows_t

contains

   !> Set-up: the block rows of a general mesh (stiff%row_start, blk_col, blk; row r is node r)
   !> in the layout of the sweep, by pairs of rows (2k - 1, 2k): the columns of both rows in the
   !> shared slots (increasing column node), then each row's other columns in its own slots, then
   !> (if its own slots are full) in the free shared slots with a zero block for the other row,
   !> then in the remainder. Empty slots hold zero blocks on the pair's first node. The node
   !> numbering of contact2d_renumber makes most pairs two nodes of one element edge, whose 9 + 9
   !> columns are 12 distinct nodes. Also the per-dof masses (stiff%mass, after any mass
   !> scaling). (4 nnode must fit 32 bits: meshes of fewer than 5e8 nodes.)
   subroutine rows_init(this, stiff)
      class(rows_t), intent(out) :: this
      type(stiffness_t), intent(in) :: stiff
      integer :: r, k, nx, c, nc, ra, rb, ka, kb, ns, na, nb, i, m
      integer :: nal, nbl
      integer, allocatable :: tcol(:), trow(:), tk(:), aleft(:), bleft(:)
      this%nnode = stiff%nnode
      this%npair = (this%nnode + 1)/2
      allocate (this%col(pair_width, this%npair), this%blk(4, 2*n_shared + 2*n_own, this%npair))
      allocate (this%xstart(this%nnode + 1), tcol(size(stiff%blk_col)), trow(size(stiff%blk_col)), &
                tk(size(stiff%blk_col)))
      k = 0
      do r = 1, this%nnode
         k = max(k, stiff%row_start(r + 1) - stiff%row_start(r))
      end do
      allocate (aleft(k), bleft(k))
      nx = 0
      do k = 1, this%npair
         ra = 2*k - 1
         rb = min(2*k, this%nnode)
         this%col(:, k) = 4*(ra - 1)
         this%blk(:, :, k) = 0
         ! shared columns (both rows' lists increase), the others left over
         ka = stiff%row_start(ra)
         kb = stiff%row_start(rb)
         if (rb == ra) kb = stiff%row_start(rb + 1)   ! no second row
         ns = 0
         nal = 0
         nbl = 0
         do while (ka < stiff%row_start(ra + 1) .or. kb < stiff%row_start(rb + 1))
            if (kb >= stiff%row_start(rb + 1)) then
               nal = nal + 1
               aleft(nal) = ka
               ka = ka + 1
            else if (ka >= stiff%row_start(ra + 1)) then
               nbl = nbl + 1
               bleft(nbl) = kb
               kb = kb + 1
            else if (stiff%blk_col(ka) < stiff%blk_col(kb)) then
               nal = nal + 1
               aleft(nal) = ka
               ka = ka + 1
            else if (stiff%blk_col(kb) < stiff%blk_col(ka)) then
               nbl = nbl + 1
               bleft(nbl) = kb
               kb = kb + 1
            else if (ns < n_shared) then
               ns = ns + 1
               this%col(ns, k) = 4*(stiff%blk_col(ka) - 1)
               this%blk(:, 2*ns - 1, k) = lanes(stiff%blk(:, :, ka))
               this%blk(:, 2*ns, k) = lanes(stiff%blk(:, :, kb))
               ka = ka + 1
               kb = kb + 1
            else
               nal = nal + 1
               aleft(nal) = ka
               nbl = nbl + 1
               bleft(nbl) = kb
               ka = ka + 1
               kb = kb + 1
            end if
         end do
         ! the first row's other columns: own slots, free shared slots, remainder
         na = 0
         do i = 1, nal
            m = aleft(i)
            if (na < n_own) then
               na = na + 1
               this%col(n_shared + na, k) = 4*(stiff%blk_col(m) - 1)
               this%blk(:, 2*n_shared + na, k) = lanes(stiff%blk(:, :, m))
            else if (ns < n_shared) then
               ns = ns + 1
               this%col(ns, k) = 4*(stiff%blk_col(m) - 1)
               this%blk(:, 2*ns - 1, k) = lanes(stiff%blk(:, :, m))
            else
               nx = nx + 1
               tcol(nx) = 4*(stiff%blk_col(m) - 1)
               trow(nx) = ra
               tk(nx) = m
            end if
         end do
         nb = 0
         do i = 1, nbl
            m = bleft(i)
            if (nb < n_own) then
               nb = nb + 1
               this%col(n_shared + n_own + nb, k) = 4*(stiff%blk_col(m) - 1)
               this%blk(:, 2*n_shared + n_own + nb, k) = lanes(stiff%blk(:, :, m))
            else if (ns < n_shared) then
               ns = ns + 1
               this%col(ns, k) = 4*(stiff%blk_col(m) - 1)
               this%blk(:, 2*ns, k) = lanes(stiff%blk(:, :, m))
            else
               nx = nx + 1
               tcol(nx) = 4*(stiff%blk_col(m) - 1)
               trow(nx) = rb
               tk(nx) = m
            end if
         end do
      end do
      ! the remainder by rows (collected in increasing row order)
      allocate (this%xcol(nx), this%xrow(nx), this%xblk(4, nx))
      do i = 1, nx
         this%xcol(i) = tcol(i)
         this%xrow(i) = trow(i)
         this%xblk(:, i) = lanes(stiff%blk(:, :, tk(i)))
      end do
      i = 1
      do r = 1, this%nnode
         this%xstart(r) = i
         do while (i <= nx)
            if (trow(i) /= r) exit
            i = i + 1
         end do
      end do
      this%xstart(this%nnode + 1) = nx + 1
      this%mdof = reshape(spread(stiff%mass, 1, 2), [2*this%nnode])
      this%minvdof = 1/this%mdof
      allocate (this%ud(4*this%nnode + 8))
      this%ud = 0
      call boundary_nodes(stiff%conn, this%nnode, this%kept)
      nc = (this%nnode + chunk_rows - 1)/chunk_rows
      allocate (this%kstart(nc + 1), this%krow(count(this%kept)))
      nx = 0
      do c = 1, nc
         this%kstart(c) = nx + 1
         do r = (c - 1)*chunk_rows + 1, min(c*chunk_rows, this%nnode)
            if (.not. this%kept(r)) cycle
            nx = nx + 1
            this%krow(nx) = r
         end do
      end do
      this%kstart(nc + 1) = nx + 1
   end subroutine rows_init

   !> The nodes of the edges that belong to one element only (the mesh's boundary).
   subroutine boundary_nodes(conn, nnode, bnd)
      integer, intent(in) :: conn(:, :)   !< (4, nel)
      integer, intent(in) :: nnode
      logical, allocatable, intent(out) :: bnd(:)
      integer, allocatable :: adj_start(:), adj_elem(:)
      integer :: e, a, n1, n2, k, shared
      call node_elements(conn, nnode, adj_start, adj_elem)
      allocate (bnd(nnode))
      bnd = .false.
      do e = 1, size(conn, 2)
         do a = 1, 4
            n1 = conn(a, e)
            n2 = conn(mod(a, 4) + 1, e)
            shared = 0
            do k = adj_start(n1), adj_start(n1 + 1) - 1
               if (any(conn(:, adj_elem(k)) == n2)) shared = shared + 1
            end do
            if (shared == 1) then
               bnd(n1) = .true.
               bnd(n2) = .true.
            end if
         end do
      end do
   end subroutine boundary_nodes

   !> A block in the lanes of the sweep: (b11, b22, b12, b21), multiplied by (ux, uy, uy, ux).
   pure function lanes(b) result(l)
      real(wp), intent(in) :: b(2, 2)
      real(wp) :: l(4)
      l = [b(1, 1), b(2, 2), b(1, 2), b(2, 1)]
   end function lanes

   !> Number of partial sums (chunks of block rows) of rows_sweep.
   pure integer function rows_parts(this) result(n)
      class(rows_t), intent(in) :: this
      n = (this%nnode + chunk_rows - 1)/chunk_rows
   end function rows_parts

   !> One sweep on a general mesh, chunk by chunk of block rows: f = K u, then on the chunk's
   !> dofs v* = ca v - cb M^-1 f (written into v), w = u + dt v* and the chunk's partial sums
   !>    (sum m v*^2, 0, sum w . f, sum m (v* - v)^2: the second sum left to the caller)
   !> (the quantities of contact2d_sweep's module header). full = .false.: f only at the kept
   !> rows, and the third sum left zero (module header).
   subroutine rows_sweep(this, u, v, f, ca, cb, dt, w, partial, full)
      class(rows_t), intent(inout), target :: this
      real(wp), intent(in) :: u(:, :)       !< u^n (2, nnode) [mm]
      real(wp), intent(inout) :: v(:, :)    !< v^(n-1/2) in, v* out [mm/s]
      real(wp), intent(inout) :: f(:, :)    !< K u^n out [N]
      real(wp), intent(in) :: ca, cb, dt    !< (1 - a dt/2)/(1 + a dt/2), dt/(1 + a dt/2) [s], dt [s]
      real(wp), intent(inout) :: w(:, :)    !< u~ out [mm]
      real(wp), intent(inout) :: partial(:, :)   !< (4, rows_parts)
      logical, intent(in) :: full           !< K u at every node and the sum u~ . K u
      integer :: ud0
      ! the first element of ud on a 64-byte boundary (where the array is now)
      ud0 = int(modulo(-transfer(c_loc(this%ud(1)), 0_c_intptr_t), 64_c_intptr_t)/8)
      call sweep_chunks(this%nnode, this%npair, size(this%xcol), this%col, this%blk, this%xstart, this%xcol, &
                        this%xrow, this%xblk, &
                        u, v, f, this%mdof, this%minvdof, ca, cb, dt, w, partial, this%ud(ud0 + 1:), &
                        this%nnode >= omp_min_nodes, full, size(this%krow), this%kstart, this%krow)
   end subroutine rows_sweep

   !> The chunks, shared among threads (explicit-shape arrays: unit strides known to the compiler):
   !> first every chunk's nodes into ud, then (all of ud being needed by the products) the rows.
   subroutine sweep_chunks(nnode, npair, nx, col, blk, xstart, xcol, xrow, xblk, u, v, f, mdof, minvdof, ca, cb, &
                           dt, w, partial, ud, par, full, nk, kstart, krow)
      integer, intent(in) :: nnode, npair, nx, nk
      integer(int32), intent(in) :: col(pair_width, npair), xcol(nx)
      real(wp), intent(in) :: blk(4, 2*n_shared + 2*n_own, npair), xblk(4, nx)
      integer, intent(in) :: xstart(nnode + 1), xrow(nx), kstart(*), krow(nk)
      real(wp), intent(in) :: u(2*nnode), mdof(2*nnode), minvdof(2*nnode), ca, cb, dt
      real(wp), intent(inout) :: v(2*nnode), f(2*nnode), w(2*nnode), ud(4*nnode)
      logical, intent(in) :: par, full
      real(wp), intent(inout) :: partial(4, *)
      integer :: c, r0, r1, k, r
      !> K u of the chunk on steps that are not full (first-level cache; a fixed size, no allocation)
      real(wp) :: g(2*chunk_rows)
      !$omp parallel if(par) private(r0, r1, k, r, g)
      !$omp do schedule(static)
      do c = 1, (nnode + chunk_rows - 1)/chunk_rows
         r0 = (c - 1)*chunk_rows + 1
         r1 = min(c*chunk_rows, nnode)
         call spread_u(r0, r1, u(2*r0 - 1), ud(4*r0 - 3))
      end do
      !$omp end do
      !$omp do schedule(dynamic)
      do c = 1, (nnode + chunk_rows - 1)/chunk_rows
         r0 = (c - 1)*chunk_rows + 1
         r1 = min(c*chunk_rows, nnode)
         if (full) then
            call products(nnode, npair, nx, r0, r1, col, blk, xstart, xcol, xrow, xblk, ud, f(2*r0 - 1))
            call predict_full(2*(r1 - r0 + 1), u(2*r0 - 1), v(2*r0 - 1), f(2*r0 - 1), mdof(2*r0 - 1), &
                              minvdof(2*r0 - 1), ca, cb, dt, w(2*r0 - 1), partial(:, c))
         else
            call products(nnode, npair, nx, r0, r1, col, blk, xstart, xcol, xrow, xblk, ud, g)
            call predict(2*(r1 - r0 + 1), u(2*r0 - 1), v(2*r0 - 1), g, mdof(2*r0 - 1), &
                         minvdof(2*r0 - 1), ca, cb, dt, w(2*r0 - 1), partial(:, c))
            ! K u at the kept rows
            do k = kstart(c), kstart(c + 1) - 1
               r = krow(k)
               f(2*r - 1) = g(2*(r - r0) + 1)
               f(2*r) = g(2*(r - r0) + 2)
            end do
         end if
      end do
      !$omp end do
      !$omp end parallel
   end subroutine sweep_chunks

   !> ud = (ux, uy, uy, ux) of the nodes r0 .. r1 (u and ud from node r0 on).
   subroutine spread_u(r0, r1, u, ud)
      integer, intent(in) :: r0, r1
      real(wp), intent(in) :: u(2, r0:r1)
      real(wp), intent(out) :: ud(4, r0:r1)
      integer :: r
      !GCC$ unroll 4
      do r = r0, r1
         ud(1, r) = u(1, r)
         ud(2, r) = u(2, r)
         ud(3, r) = u(2, r)
         ud(4, r) = u(1, r)
      end do
   end subroutine spread_u

   !> K u of the rows r0 .. r1 into g (g(1:2) the row r0; r0 odd: whole pairs), pair by pair
   !> (pair_sum); the x and y outputs of the two rows of a pair are one 4-wide add. Then the
   !> remainder blocks, added in order.
   subroutine products(nnode, npair, nx, r0, r1, col, blk, xstart, xcol, xrow, xblk, ud, g)
      integer, intent(in) :: nnode, npair, nx, r0, r1
      integer(int32), intent(in) :: col(pair_width, npair), xcol(nx)
      real(wp), intent(in) :: blk(4, 2*n_shared + 2*n_own, npair), xblk(4, nx)
      integer, intent(in) :: xstart(nnode + 1), xrow(nx)
      real(wp), intent(in) :: ud(4*nnode)
      real(wp), intent(inout) :: g(2*r0 - 1:2*r1)
      integer :: r, k, l
      integer(i8) :: j
      real(wp) :: p(4), p2(4), a(4), b(4)
      ! (one call of pair_sum, so that it is inlined)
      do k = (r0 + 1)/2, r1/2
         call pair_sum(col(:, k), blk(:, :, k), ud, p, p2)
         a(1) = p(1)
         a(2) = p(2)
         a(3) = p2(1)
         a(4) = p2(2)
         b(1) = p(3)
         b(2) = p(4)
         b(3) = p2(3)
         b(4) = p2(4)
         !$omp simd simdlen(4)
         do l = 1, 4
            g(4*k - 4 + l) = a(l) + b(l)
         end do
      end do
      if (mod(r1, 2) == 1) then
         ! the last node of an odd mesh: the first row of a pair without second row (its blocks
         ! are the first row's: 2 i - 1 of the shared slots i, then 13-15)
         p = 0
         do l = 1, pair_width
            j = int(col(l, (r1 + 1)/2), i8)
            k = merge(2*l - 1, l + n_shared, l <= n_shared)
            if (l > n_shared + n_own) cycle
            p = p + blk(:, k, (r1 + 1)/2)*ud(j + 1:j + 4)
         end do
         g(2*r1 - 1) = p(1) + p(3)
         g(2*r1) = p(2) + p(4)
      end if
      ! the blocks that found no slot (rare), added in order
      do k = xstart(r0), xstart(r1 + 1) - 1
         r = xrow(k)
         j = int(xcol(k), i8)
         g(2*r - 1) = g(2*r - 1) + (xblk(1, k)*ud(j + 1) + xblk(3, k)*ud(j + 2))
         g(2*r) = g(2*r) + (xblk(4, k)*ud(j + 1) + xblk(2, k)*ud(j + 2))
      end do
   end subroutine products

   !> The sums of a pair of block rows: each column slot's u (spread as (ux, uy, uy, ux)) loaded
   !> once; a shared slot two 4-wide multiply-adds (one per row), an own slot one. A row's slots
   !> (its 9 blocks in slot order: shared 1-6, then its own 1-3) go in turn into three
   !> accumulators, slots 1, 4, 7 into p, 2, 5, 8 into q, 3, 6, 9 into s (short chains; the
   !> first three a product, not a multiply-add on zero: the same value); returned as
   !> (p + q) + s for the first row (p) and the second (p2). Written out slot by slot (the block
   !> index of the first row's slot i <= n_shared is 2 i - 1, of the second's 2 i; the own slots
   !> are blocks 13-15 and 16-18).
   pure subroutine pair_sum(col, blk, ud, p, p2)
      integer(int32), intent(in) :: col(pair_width)
      real(wp), intent(in) :: blk(4, 2*n_shared + 2*n_own), ud(*)
      real(wp), intent(out) :: p(4), p2(4)
      real(wp) :: q(4), s(4), q2(4), s2(4)
      integer :: l
      integer(i8) :: j
      j = int(col(1), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         p(l) = blk(l, 1)*ud(j + l)
         p2(l) = blk(l, 2)*ud(j + l)
      end do
      j = int(col(2), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         q(l) = blk(l, 3)*ud(j + l)
         q2(l) = blk(l, 4)*ud(j + l)
      end do
      j = int(col(3), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         s(l) = blk(l, 5)*ud(j + l)
         s2(l) = blk(l, 6)*ud(j + l)
      end do
      j = int(col(4), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         p(l) = p(l) + blk(l, 7)*ud(j + l)
         p2(l) = p2(l) + blk(l, 8)*ud(j + l)
      end do
      j = int(col(5), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         q(l) = q(l) + blk(l, 9)*ud(j + l)
         q2(l) = q2(l) + blk(l, 10)*ud(j + l)
      end do
      j = int(col(6), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         s(l) = s(l) + blk(l, 11)*ud(j + l)
         s2(l) = s2(l) + blk(l, 12)*ud(j + l)
      end do
      j = int(col(7), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         p(l) = p(l) + blk(l, 13)*ud(j + l)
      end do
      j = int(col(8), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         q(l) = q(l) + blk(l, 14)*ud(j + l)
      end do
      j = int(col(9), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         s(l) = s(l) + blk(l, 15)*ud(j + l)
      end do
      j = int(col(10), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         p2(l) = p2(l) + blk(l, 16)*ud(j + l)
      end do
      j = int(col(11), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         q2(l) = q2(l) + blk(l, 17)*ud(j + l)
      end do
      j = int(col(12), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         s2(l) = s2(l) + blk(l, 18)*ud(j + l)
      end do
      !$omp simd simdlen(4)
      do l = 1, 4
         p(l) = (p(l) + q(l)) + s(l)
         p2(l) = (p2(l) + q2(l)) + s2(l)
      end do
   end subroutine pair_sum

   !> Predictor and sums on the n flat dofs of a chunk while it is in cache (as row_update of
   !> contact2d_sweep; the second sum is left zero, as by the grid rows: the caller has it from
   !> the others).
   subroutine predict_full(n, u, v, f, mdof, minvdof, ca, cb, dt, w, part)
      integer, intent(in) :: n
      real(wp), intent(in) :: u(n), f(n), mdof(n), minvdof(n), ca, cb, dt
      real(wp), intent(inout) :: v(n), w(n)
      real(wp), intent(out) :: part(4)
      integer :: d
      real(wp) :: vo, vs, wn, ek, es, ea
      ek = 0
      es = 0
      ea = 0
      !$omp simd private(vo, vs, wn) reduction(+:ek, es, ea)
      do d = 1, n
         vo = v(d)
         vs = ca*vo - cb*minvdof(d)*f(d)
         wn = u(d) + dt*vs
         ek = ek + mdof(d)*vs*vs
         es = es + wn*f(d)
         ea = ea + mdof(d)*(vs - vo)**2
         v(d) = vs
         w(d) = wn
      end do
      part(1) = ek
      part(2) = 0
      part(3) = es
      part(4) = ea
   end subroutine predict_full

   !> The same without the sum u~ . K u (left zero).
   subroutine predict(n, u, v, f, mdof, minvdof, ca, cb, dt, w, part)
      integer, intent(in) :: n
      real(wp), intent(in) :: u(n), f(n), mdof(n), minvdof(n), ca, cb, dt
      real(wp), intent(inout) :: v(n), w(n)
      real(wp), intent(out) :: part(4)
      integer :: d
      real(wp) :: vo, vs, ek, ea
      ek = 0
      ea = 0
      !$omp simd private(vo, vs) reduction(+:ek, ea)
      do d = 1, n
         vo = v(d)
         vs = ca*vo - cb*minvdof(d)*f(d)
         ek = ek + mdof(d)*vs*vs
         ea = ea + mdof(d)*(vs - vo)**2
         v(d) = vs
         w(d) = u(d) + dt*vs
      end do
      part(1) = ek
      part(2) = 0
      part(3) = 0
      part(4) = ea
   end subroutine predict
end module contact2d_rows
