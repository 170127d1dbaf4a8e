!> The sweep of contact2d_sweep on a general (Gmsh) mesh (docs/performance.md
!> "general path"): chunk by chunk of block rows, the internal force K u^n from the block rows
!> of contact2d_stiffness, then, while the chunk is in cache, the predictor v* (written into v),
!> u~ and the energy sums of v* (the quantities of contact2d_sweep's module header).
!>
!> The rows of a general mesh are all its nodes in node order (stiffness_init builds them so:
!> row r is node r), so the per-node state is addressed directly and, inside a chunk, as flat
!> arrays of interleaved (x, y) dofs: the predictor and the sums are one plain vector loop with
!> per-dof masses (held here: a general mesh has no row pattern to keep them shorter).
!>
!> Rows are taken by groups of four (4k - 3 .. 4k) and stored in a fixed layout of 16 column
!> slots (slot_mask): a node of a regular quad mesh has 9 neighbours, itself included (94 % of
!> the rows of the refined Hertz meshes), and the four nodes of one element have 16 distinct
!> columns, 4 of them in all four rows, 8 in two rows (an edge's), 4 in one; contact2d_renumber
!> numbers most nodes so that a group is an element's nodes in cyclic order. Free slots hold
!> zero blocks on the group's first node; blocks that find no slot go to a small CSR remainder,
!> added after the chunk's fixed-layout pass. So the product of a group is straight-line code
!> with no loop and no data-dependent branch, and each column's u is loaded once for the 2.25
!> blocks that use it on average (the products 30 % fewer instructions on the Hertz
!> mesh than with rows one by one; docs/performance.md). Each
!> 2 x 2 block B is stored as (b11, b22, b12, b21) and u is first copied, node by node, into
!> ud = (ux, uy, uy, ux): the product of a block is then one 4-wide multiply-add, lanes
!> (b11 ux, b22 uy, b12 uy, b21 ux), whose lanes 1 + 3 and 2 + 4 are the row's x and y (two
!> accumulators per row: short dependency chains, eight in all). Column offsets are 32-bit
!> (4 (m - 1) into ud: fewer bytes; the sign-extending load costs no instruction more). The
!> order of every sum is fixed by the layout, and chunks are fixed (chunk_rows rows) with their
!> partial sums added in chunk order by the caller, so the bits do not depend on the number of
!> threads or on which thread does which chunk.
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
   public :: rows_t, chunk_rows

   !> Column slots of a group of four rows (1, 2, 3, 4 = a, b, c, d: the nodes of one element in
   !> their cyclic order where contact2d_renumber found one): slots 1-4 for all four rows, 5-6 for
   !> rows (1, 2), 7-8 (2, 3), 9-10 (3, 4), 11-12 (1, 4), 13-16 for rows 1, 2, 3, 4 alone. Each
   !> row has 9 slots (a node of a regular quad mesh has 9 neighbours, itself included), a group
   !> 36 blocks over 16 columns.
   integer, parameter :: group_rows = 4, group_width = 16, group_blocks = 36
   !> rows of each slot, as bits (row i: bit i - 1)
   integer, parameter :: slot_mask(group_width) = [15, 15, 15, 15, 3, 3, 6, 6, 12, 12, 9, 9, 1, 2, 4, 8]
   !> block of row i in slot s: slot_block(i, s) (0: row i has no block in slot s); blocks are
   !> stored slot by slot, rows in increasing order within a slot
   integer, parameter :: slot_block(group_rows, group_width) = reshape([ &
                         1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 0, 0, 19, 20, 0, 0, &
                         0, 21, 22, 0, 0, 23, 24, 0, 0, 0, 25, 26, 0, 0, 27, 28, 29, 0, 0, 30, 31, 0, 0, 32, &
                         33, 0, 0, 0, 0, 34, 0, 0, 0, 0, 35, 0, 0, 0, 0, 36], [group_rows, group_width])
   !> Block rows per chunk (and per partial sum; a multiple of group_rows, so that no group
   !> straddles two chunks): the
   !> chunk's u, v, K u, u~ and masses (2 x 256 doubles each) stay in the first-level cache from
   !> the products to the predictor loop.
   integer, parameter :: chunk_rows = 256

   !> The block rows of K of a general mesh (row r is node r), laid out for the sweep by groups of
   !> four rows (4k - 3 .. 4k).
   type :: rows_t
      integer :: nnode = 0
      integer :: ngroup = 0
      !> offset 4 (m - 1) into ud of the column node m of each slot of each group (group_width, ngroup)
      integer(int32), allocatable :: col(:, :)
      !> (b11, b22, b12, b21) of each block of a group (4, group_blocks, ngroup), as slot_block [N/mm]
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
      !> the lowest and highest node whose u the rows of chunk c read, reach(:, c) (several
      !> processes: a rank's halo is what its chunks reach beyond its own nodes, docs/mpi.md)
      integer, allocatable :: reach(:, :)
   contains
      procedure :: init => rows_init
      procedure :: parts => rows_parts
      procedure :: sweep => rows_sweep
   end type rows_t

contains

   !> Set-up: the block rows of a general mesh (stiff%row_start, blk_col, blk; row r is node r)
   !> in the layout of the sweep, by groups of four rows: the distinct columns of a group's rows,
   !> those of more rows first (then by node), each into the free slot that holds most of its
   !> rows, then fewest others (zero blocks for them), then the first; what finds no slot goes to
   !> the remainder. Free slots hold zero blocks on the group's first node. The node numbering of
   !> contact2d_renumber makes most groups the nodes of one element, whose 36 blocks then fill
   !> the 16 slots exactly. Also the per-dof masses (stiff%mass, after any mass scaling). (4 nnode
   !> must fit 32 bits: meshes of fewer than 5e8 nodes.)
   subroutine rows_init(this, stiff)
      class(rows_t), intent(out) :: this
      type(stiffness_t), intent(in) :: stiff
      integer :: r, k, nx, c, nc, i, m, nu, t, best, sl, ov, bov, rest, brest, left, mx
      integer, allocatable :: ucol(:), umask(:), uk(:, :), tcol(:), trow(:), tk(:), order(:), xorder(:)
      logical :: free(group_width)
      this%nnode = stiff%nnode
      this%ngroup = (this%nnode + group_rows - 1)/group_rows
      allocate (this%col(group_width, this%ngroup), this%blk(4, group_blocks, this%ngroup))
      allocate (this%xstart(this%nnode + 1), tcol(size(stiff%blk_col)), trow(size(stiff%blk_col)), &
                tk(size(stiff%blk_col)))
      mx = 0
      do r = 1, this%nnode
         mx = max(mx, stiff%row_start(r + 1) - stiff%row_start(r))
      end do
      allocate (ucol(group_rows*mx), umask(group_rows*mx), uk(group_rows, group_rows*mx), order(group_rows*mx))
      nx = 0
      do k = 1, this%ngroup
         this%col(:, k) = 4*(group_rows*(k - 1))
         this%blk(:, :, k) = 0
         ! the distinct columns of the group's rows, which rows have them, and where
         nu = 0
         do i = 1, group_rows
            r = group_rows*(k - 1) + i
            if (r > this%nnode) exit
            do t = stiff%row_start(r), stiff%row_start(r + 1) - 1
               m = findloc(ucol(1:nu), stiff%blk_col(t), dim=1)
               if (m == 0) then
                  nu = nu + 1
                  m = nu
                  ucol(m) = stiff%blk_col(t)
                  umask(m) = 0
               end if
               umask(m) = ior(umask(m), ishft(1, i - 1))
               uk(i, m) = t
            end do
         end do
         ! by decreasing number of rows, then increasing node (insertion sort: short lists)
         do i = 1, nu
            m = i
            do while (m > 1)
               if (before(order(m - 1), i)) exit
               order(m) = order(m - 1)
               m = m - 1
            end do
            order(m) = i
         end do
         free = .true.
         do t = 1, nu
            m = order(t)
            left = umask(m)
            do while (left /= 0)
               best = 0
               bov = 0
               brest = 0
               do sl = 1, group_width
                  if (.not. free(sl)) cycle
                  ov = popcnt(iand(slot_mask(sl), left))
                  rest = popcnt(slot_mask(sl)) - ov
                  if (ov == 0) cycle
                  if (best == 0 .or. ov > bov .or. (ov == bov .and. rest < brest)) then
                     best = sl
                     bov = ov
                     brest = rest
                  end if
               end do
               if (best == 0) then
                  ! no free slot holds any of these rows: the remainder
                  do i = 1, group_rows
                     if (.not. btest(left, i - 1)) cycle
                     nx = nx + 1
                     tcol(nx) = 4*(ucol(m) - 1)
                     trow(nx) = group_rows*(k - 1) + i
                     tk(nx) = uk(i, m)
                  end do
                  exit
               end if
               free(best) = .false.
               this%col(best, k) = 4*(ucol(m) - 1)
               do i = 1, group_rows
                  if (.not. btest(iand(left, slot_mask(best)), i - 1)) cycle
                  this%blk(:, slot_block(i, best), k) = lanes(stiff%blk(:, :, uk(i, m)))
               end do
               left = iand(left, not(slot_mask(best)))
            end do
         end do
      end do
      ! the remainder by rows (stable: a row's blocks in the order found)
      allocate (this%xcol(nx), this%xrow(nx), this%xblk(4, nx), xorder(nx))
      this%xstart = 0
      do i = 1, nx
         this%xstart(trow(i)) = this%xstart(trow(i)) + 1
      end do
      t = 1
      do r = 1, this%nnode
         c = this%xstart(r)
         this%xstart(r) = t
         t = t + c
      end do
      this%xstart(this%nnode + 1) = t
      deallocate (order)
      allocate (order(this%nnode))
      order = 0   ! blocks of each row placed so far
      do i = 1, nx
         r = trow(i)
         xorder(this%xstart(r) + order(r)) = i
         order(r) = order(r) + 1
      end do
      do i = 1, nx
         this%xcol(i) = tcol(xorder(i))
         this%xrow(i) = trow(xorder(i))
         this%xblk(:, i) = lanes(stiff%blk(:, :, tk(xorder(i))))
      end do
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
      ! the nodes each chunk's products read (a group's free slots point at its own first node)
      allocate (this%reach(2, nc))
      do c = 1, nc
         this%reach(1, c) = (c - 1)*chunk_rows + 1
         this%reach(2, c) = min(c*chunk_rows, this%nnode)
         do k = (this%reach(1, c) + group_rows - 1)/group_rows, (this%reach(2, c) + group_rows - 1)/group_rows
            this%reach(1, c) = min(this%reach(1, c), minval(this%col(:, k))/4 + 1)
            this%reach(2, c) = max(this%reach(2, c), maxval(this%col(:, k))/4 + 1)
         end do
         do t = this%xstart((c - 1)*chunk_rows + 1), this%xstart(min(c*chunk_rows, this%nnode) + 1) - 1
            this%reach(1, c) = min(this%reach(1, c), this%xcol(t)/4 + 1)
            this%reach(2, c) = max(this%reach(2, c), this%xcol(t)/4 + 1)
         end do
      end do
   contains
      !> Column a goes before column b: more rows, or as many and a lower node.
      logical function before(a, b)
         integer, intent(in) :: a, b
         before = popcnt(umask(a)) > popcnt(umask(b)) .or. &
                  (popcnt(umask(a)) == popcnt(umask(b)) .and. ucol(a) < ucol(b))
      end function before
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
   !> rows, and the third sum left zero (module header). chunks: only the chunks chunks(1) ..
   !> chunks(2) (default all), which read u at the nodes of their reach only (several
   !> processes: contact2d_explicit); each chunk's values and sums are those of the whole sweep.
   subroutine rows_sweep(this, u, v, f, ca, cb, dt, w, partial, full, chunks)
      class(rows_t), intent(inout), target :: this
      real(wp), intent(in) :: u(:, :)       !< u^n (2, nnode) [mm]
      real(wp), intent(inout) :: v(:, :)    !< v^(n-1/2) in, v* out [mm/s]
      real(wp), intent(inout) :: f(:, :)    !< K u^n out [N]
      real(wp), intent(in) :: ca, cb, dt    !< (1 - a dt/2)/(1 + a dt/2), dt/(1 + a dt/2) [s], dt [s]
      real(wp), intent(inout) :: w(:, :)    !< u~ out [mm]
      real(wp), intent(inout) :: partial(:, :)   !< (4, rows_parts)
      logical, intent(in) :: full           !< K u at every node and the sum u~ . K u
      integer, intent(in), optional :: chunks(2)
      integer :: ud0, c0, c1, s0, s1
      ! the first element of ud on a 64-byte boundary (where the array is now)
      ud0 = int(modulo(-transfer(c_loc(this%ud(1)), 0_c_intptr_t), 64_c_intptr_t)/8)
      c0 = 1
      c1 = size(this%reach, 2)
      s0 = 1
      s1 = this%nnode
      if (present(chunks)) then
         c0 = chunks(1)
         c1 = chunks(2)
         if (c1 < c0) return
         s0 = minval(this%reach(1, c0:c1))
         s1 = maxval(this%reach(2, c0:c1))
      end if
      call sweep_chunks(this%nnode, this%ngroup, size(this%xcol), this%col, this%blk, this%xstart, this%xcol, &
                        this%xrow, this%xblk, &
                        u, v, f, this%mdof, this%minvdof, ca, cb, dt, w, partial, this%ud(ud0 + 1:), &
                        this%nnode >= omp_min_nodes, full, size(this%krow), this%kstart, this%krow, c0, c1, s0, s1)
   end subroutine rows_sweep

   !> The chunks c0 .. c1, shared among threads (explicit-shape arrays: unit strides known to the
   !> compiler): first the nodes s0 .. s1 (those the chunks read) into ud, by pieces of chunk_rows,
   !> then (all of them being needed by the products) the rows.
   subroutine sweep_chunks(nnode, ngroup, nx, col, blk, xstart, xcol, xrow, xblk, u, v, f, mdof, minvdof, ca, cb, &
                           dt, w, partial, ud, par, full, nk, kstart, krow, c0, c1, s0, s1)
      integer, intent(in) :: nnode, ngroup, nx, nk, c0, c1, s0, s1
      integer(int32), intent(in) :: col(group_width, ngroup), xcol(nx)
      real(wp), intent(in) :: blk(4, group_blocks, ngroup), xblk(4, nx)
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
      do c = 1, (s1 - s0 + chunk_rows)/chunk_rows
         r0 = s0 + (c - 1)*chunk_rows
         r1 = min(s0 + c*chunk_rows - 1, s1)
         call spread_u(r0, r1, u(2*r0 - 1), ud(4*r0 - 3))
      end do
      !$omp end do
      !$omp do schedule(dynamic)
      do c = c0, c1
         r0 = (c - 1)*chunk_rows + 1
         r1 = min(c*chunk_rows, nnode)
         if (full) then
            call products(nnode, ngroup, nx, r0, r1, col, blk, xstart, xcol, xrow, xblk, ud, f(2*r0 - 1))
            call predict_full(2*(r1 - r0 + 1), u(2*r0 - 1), v(2*r0 - 1), f(2*r0 - 1), mdof(2*r0 - 1), &
                              minvdof(2*r0 - 1), ca, cb, dt, w(2*r0 - 1), partial(:, c))
         else
            call products(nnode, ngroup, nx, r0, r1, col, blk, xstart, xcol, xrow, xblk, ud, g)
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

   !> K u of the rows r0 .. r1 into g (g(1:2) the row r0; r0 = 4 j + 1: whole groups), group by
   !> group (group_sum); the x and y outputs of two rows are one 4-wide add. Then the remainder
   !> blocks, added in order.
   subroutine products(nnode, ngroup, nx, r0, r1, col, blk, xstart, xcol, xrow, xblk, ud, g)
      integer, intent(in) :: nnode, ngroup, nx, r0, r1
      integer(int32), intent(in) :: col(group_width, ngroup), xcol(nx)
      real(wp), intent(in) :: blk(4, group_blocks, ngroup), xblk(4, nx)
      integer, intent(in) :: xstart(nnode + 1), xrow(nx)
      real(wp), intent(in) :: ud(4*nnode)
      real(wp), intent(inout) :: g(2*r0 - 1:2*r1)
      integer :: r, k, l, i, s
      integer(i8) :: j
      real(wp) :: pa(4), pb(4), pc(4), pd(4), p(4), a(4), b(4)
      ! (one call of group_sum, so that it is inlined)
      do k = (r0 + 3)/4, r1/4
         call group_sum(col(:, k), blk(:, :, k), ud, pa, pb, pc, pd)
         ! rows 1, 2: x1 y1 x2 y2 = (pa(1:2), pb(1:2)) + (pa(3:4), pb(3:4)); rows 3, 4 alike
         a(1:2) = pa(1:2)
         a(3:4) = pb(1:2)
         b(1:2) = pa(3:4)
         b(3:4) = pb(3:4)
         !$omp simd simdlen(4)
         do l = 1, 4
            g(8*k - 8 + l) = a(l) + b(l)
         end do
         a(1:2) = pc(1:2)
         a(3:4) = pd(1:2)
         b(1:2) = pc(3:4)
         b(3:4) = pd(3:4)
         !$omp simd simdlen(4)
         do l = 1, 4
            g(8*k - 4 + l) = a(l) + b(l)
         end do
      end do
      if (mod(r1, 4) /= 0) then
         ! the last nodes of a mesh of 4 j + 1, 2 or 3 nodes: its last group's rows, slot by slot
         k = (r1 + 3)/4
         do i = 1, mod(r1, 4)
            p = 0
            do s = 1, group_width
               if (slot_block(i, s) == 0) cycle
               j = int(col(s, k), i8)
               p = p + blk(:, slot_block(i, s), k)*ud(j + 1:j + 4)
            end do
            r = 4*(k - 1) + i
            g(2*r - 1) = p(1) + p(3)
            g(2*r) = p(2) + p(4)
         end do
      end if
      ! the blocks that found no slot (rare), added in order
      do k = xstart(r0), xstart(r1 + 1) - 1
         r = xrow(k)
         j = int(xcol(k), i8)
         g(2*r - 1) = g(2*r - 1) + (xblk(1, k)*ud(j + 1) + xblk(3, k)*ud(j + 2))
         g(2*r) = g(2*r) + (xblk(4, k)*ud(j + 1) + xblk(2, k)*ud(j + 2))
      end do
   end subroutine products

   !> The sums of a group of four block rows: each column slot's u (spread as (ux, uy, uy, ux))
   !> loaded once, then one 4-wide multiply-add per row of the slot. A row's 9 blocks, in slot
   !> order, go in turn into two accumulators (the first two products, not multiply-adds on zero:
   !> the same values); returned as their sum, pa .. pd for rows 1 .. 4. Written out slot by slot
   !> (blocks as slot_block).
   pure subroutine group_sum(col, blk, ud, pa, pb, pc, pd)
      integer(int32), intent(in) :: col(group_width)
      real(wp), intent(in) :: blk(4, group_blocks), ud(*)
      real(wp), intent(out) :: pa(4), pb(4), pc(4), pd(4)
      real(wp) :: a1(4), a2(4), b1(4), b2(4), c1(4), c2(4), d1(4), d2(4)
      integer :: l
      integer(i8) :: j
      j = int(col(1), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         a1(l) = blk(l, 1)*ud(j + l)
         b1(l) = blk(l, 2)*ud(j + l)
         c1(l) = blk(l, 3)*ud(j + l)
         d1(l) = blk(l, 4)*ud(j + l)
      end do
      j = int(col(2), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         a2(l) = blk(l, 5)*ud(j + l)
         b2(l) = blk(l, 6)*ud(j + l)
         c2(l) = blk(l, 7)*ud(j + l)
         d2(l) = blk(l, 8)*ud(j + l)
      end do
      j = int(col(3), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         a1(l) = a1(l) + blk(l, 9)*ud(j + l)
         b1(l) = b1(l) + blk(l, 10)*ud(j + l)
         c1(l) = c1(l) + blk(l, 11)*ud(j + l)
         d1(l) = d1(l) + blk(l, 12)*ud(j + l)
      end do
      j = int(col(4), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         a2(l) = a2(l) + blk(l, 13)*ud(j + l)
         b2(l) = b2(l) + blk(l, 14)*ud(j + l)
         c2(l) = c2(l) + blk(l, 15)*ud(j + l)
         d2(l) = d2(l) + blk(l, 16)*ud(j + l)
      end do
      j = int(col(5), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         a1(l) = a1(l) + blk(l, 17)*ud(j + l)
         b1(l) = b1(l) + blk(l, 18)*ud(j + l)
      end do
      j = int(col(6), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         a2(l) = a2(l) + blk(l, 19)*ud(j + l)
         b2(l) = b2(l) + blk(l, 20)*ud(j + l)
      end do
      j = int(col(7), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         b1(l) = b1(l) + blk(l, 21)*ud(j + l)
         c1(l) = c1(l) + blk(l, 22)*ud(j + l)
      end do
      j = int(col(8), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         b2(l) = b2(l) + blk(l, 23)*ud(j + l)
         c2(l) = c2(l) + blk(l, 24)*ud(j + l)
      end do
      j = int(col(9), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         c1(l) = c1(l) + blk(l, 25)*ud(j + l)
         d1(l) = d1(l) + blk(l, 26)*ud(j + l)
      end do
      j = int(col(10), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         c2(l) = c2(l) + blk(l, 27)*ud(j + l)
         d2(l) = d2(l) + blk(l, 28)*ud(j + l)
      end do
      j = int(col(11), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         a1(l) = a1(l) + blk(l, 29)*ud(j + l)
         d1(l) = d1(l) + blk(l, 30)*ud(j + l)
      end do
      j = int(col(12), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         a2(l) = a2(l) + blk(l, 31)*ud(j + l)
         d2(l) = d2(l) + blk(l, 32)*ud(j + l)
      end do
      j = int(col(13), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         a1(l) = a1(l) + blk(l, 33)*ud(j + l)
      end do
      j = int(col(14), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         b1(l) = b1(l) + blk(l, 34)*ud(j + l)
      end do
      j = int(col(15), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         c1(l) = c1(l) + blk(l, 35)*ud(j + l)
      end do
      j = int(col(16), i8)
      !$omp simd simdlen(4)
      do l = 1, 4
         d1(l) = d1(l) + blk(l, 36)*ud(j + l)
      end do
      !$omp simd simdlen(4)
      do l = 1, 4
         pa(l) = a1(l) + a2(l)
         pb(l) = b1(l) + b2(l)
         pc(l) = c1(l) + c2(l)
         pd(l) = d1(l) + d2(l)
      end do
   end subroutine group_sum

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
