!> One sweep over memory per explicit step (docs/performance.md): row by row, the
!> internal force K u^n, the predictor of this step in velocity form and the energy sums of the
!> predicted velocity, so that every node is loaded once and u^(n-1) is not kept at all.
!>
!>    v* = ca v^(n-1/2) - cb M^-1 K u^n,   u~ = u^n + dt v*   (v overwritten by v*),
!>    partial = (sum m v*^2, sum m ((v* + v^(n-1/2))/2)^2, sum u~ . K u^n, sum m (v* - v^(n-1/2))^2).
!>
!> With full = .false. the inside rows of structured meshes, and the block rows of general ones
!> but at the mesh's boundary, neither store K u at their interior nodes (sweep_t%kept: where it
!> is always stored) nor form the third sum: the steps on which nobody reads them
!> (contact2d_explicit).
!>
!> The grid rows of structured meshes leave the second sum zero: the caller has it from the
!> others and sum m (v^(n-1/2))^2, (a + b)^2 = 2 a^2 + 2 b^2 - (a - b)^2 (contact2d_explicit).
!>
!> v* is v^(n+1/2) wherever nothing changes u~ after the sweep; the caller corrects the velocity
!> and these sums at the loaded, prescribed and contact dofs (contact2d_explicit).
!>
!> Structured meshes of equal elements use nine stencils of 2 x 2 blocks (interior, four edges,
!> four corners): every grid row is one vectorised loop, its two end nodes are done apart;
!> inside rows of a mesh of equal axis-aligned rectangles use the stencil's nine distinct values
!> on row sums and differences, fused with the predictor and the sums (grid_row_sym). The
!> nodal masses of such a mesh are the same along a grid row but for its end nodes (interior,
!> edge and corner masses; mass scaling keeps that, every interior node of a row having the same
!> row of K), so they are kept per class of row (bottom, inside, top): three short arrays that
!> stay in cache instead of two per-dof arrays streamed from memory; a mesh whose masses do not
!> follow the pattern keeps one class per row. Other meshes use the fixed-width block rows of
!> contact2d_rows (with per-dof masses). Sums are per grid row (or per fixed chunk of block
!> rows) and added in order by the caller, so the bits do not depend on the number of threads or
!> on how rows are shared among them. Inside rows start their vector blocks where u starts a
!> cache line when u itself starts one, as contact2d_explicit keeps it (grid_row_sym); which
!> outputs go by blocks is set by the mesh alone, so neither do the bits depend on where u is.
module contact2d_sweep
   use contact2d_kinds, only: wp
   use contact2d_stiffness, only: stiffness_t, omp_min_nodes
   use contact2d_rows, only: rows_t
   use contact2d_build_config, only: sweep_lanes
   use contact2d_align, only: line_reals, line_slot, line_skip
   use omp_lib, only: omp_get_max_threads, omp_get_num_procs, omp_get_thread_num
   implicit none
   private
   public :: sweep_t

   !> Offsets (i, j) of the four local nodes of a structured element from its bottom-left node.
   integer, parameter :: off(2, 4) = reshape([0, 0, 1, 0, 1, 1, 0, 1], [2, 4])

   !> Operator data and masses of the sweep, formed once from the stiffness.
   type :: sweep_t
      logical :: structured = .false.
      integer :: nx = 0, ny = 0
      real(wp) :: s(2, 2, -1:1, -1:1, 3, 3) = 0   !< the nine stencils (structured)
      real(wp) :: cv(0:7, -3:3, 3, 3) = 0         !< flat interior coefficients (structured)
      real(wp) :: cs(0:7, -3:3, 3, 3) = 0         !< the same for blocks that start at odd p
      real(wp) :: e(2, 4, -1:1, 2, 3) = 0         !< end-node stencils (end_coefficients)
      !> the interior stencil has the symmetries of a rectangle (symmetric_coefficients): inside
      !> rows then use its nine distinct values, qs, on sums and differences of rows
      logical :: sym = .false.
      real(wp) :: qs(0:7, 5) = 0
      !> per thread, the sum and difference rows of grid_row_sym for two consecutive rows (this
      !> row's and the next one's, formed in this row's loop), (0:nrow - 1, 4, 0:nscr - 1) with
      !> nrow = 2 (nx + 1) rounded up to whole lines, plus a line: each row starts where its
      !> grid row's first value sits in its line (sweep_grid)
      real(wp), allocatable :: scr(:, :, :)
      !> place in its line of scr(0, 1, 0), and so of every scr(0, k, t) (whole lines apart)
      integer :: scr_slot = 0
      integer :: nscr = 0
      !> per-dof masses and inverses of each class of grid row, (2 (nx + 1), nclass) [t], [1/t]
      real(wp), allocatable :: rmass(:, :), rminv(:, :)
      !> cb rminv for the cb of cb_last (formed again when cb changes: the damping) [s/t]
      real(wp), allocatable :: rcbm(:, :)
      !> rmass and rcbm again, aligned like the grid rows that use them (the inside rows of
      !> grid_row_sym): copy(s, c) is the index in amc(:, 1) (masses) and amc(:, 2) (cb M^-1) of
      !> the first value of the copy of class c whose first value sits at place s of a line
      !> (contact2d_align), formed for the places of the inside rows of class c (row_place); 0
      !> where none
      real(wp), allocatable :: amc(:, :)
      integer, allocatable :: copy(:, :)
      real(wp) :: cb_last = -1
      integer, allocatable :: rclass(:)           !< class of each grid row (0:ny)
      type(rows_t) :: rows                        !< block rows and masses (general meshes)
      real(wp), allocatable :: partial(:, :)      !< sums of the last sweep (4, parts)
   contains
      procedure :: init => sweep_init
      procedure :: step => sweep_step
      procedure :: kept => sweep_kept
   end type sweep_t

contains

   !> Stencils, masses and partial sums for this stiffness (after any mass scaling).
   subroutine sweep_init(this, stiff)
      class(sweep_t), intent(out) :: this
      type(stiffness_t), intent(in) :: stiff
      real(wp), allocatable :: mrow(:, :)
      integer :: j, n, nx, ny, rep(3)
      logical :: uniform
      this%structured = stiff%structured
      if (.not. stiff%structured) then
         call this%rows%init(stiff)
         allocate (this%partial(4, this%rows%parts()))
         return
      end if
      nx = stiff%nx
      ny = stiff%ny
      this%nx = nx
      this%ny = ny
      n = 2*(nx + 1)
      call sweep_stencils(stiff%ke(:, :, 1), this%s)
      call flat_coefficients(this%s, this%cv)
      this%cs = this%cv([1, 0, 3, 2, 5, 4, 7, 6], :, :, :)
      call end_coefficients(this%s, this%e)
      call symmetric_coefficients(this%s(:, :, :, :, 2, 2), this%sym, this%qs)
      ! (allocated even when unused: it is passed to sweep_grid)
      this%nscr = max(omp_get_max_threads(), omp_get_num_procs())
      allocate (this%scr(0:line_reals*((n + line_reals - 1)/line_reals) + line_reals - 1, 4, 0:this%nscr - 1))
      this%scr = 0
      this%scr_slot = line_slot(this%scr(0, 1, 0))
      ! per-dof masses of every row; the class of row j is its row type (1 bottom, 2 inside, 3 top)
      mrow = reshape(spread(stiff%mass, 1, 2), [n, ny + 1])
      allocate (this%rclass(0:ny))
      do j = 0, ny
         this%rclass(j) = row_type(j, ny)
      end do
      rep = [0, min(1, ny), ny]   ! a row of each type (ny = 1: no inside row, never used)
      uniform = .true.
      do j = 0, ny
         uniform = uniform .and. all(mrow(:, j + 1) == mrow(:, rep(this%rclass(j)) + 1))
      end do
      if (uniform) then
         this%rmass = mrow(:, rep + 1)
      else
         this%rmass = mrow
         this%rclass = [(j + 1, j=0, ny)]
      end if
      this%rminv = 1/this%rmass
      this%rcbm = this%rminv
      this%cb_last = -1
      call aligned_copies(this, n)
      allocate (this%partial(4, ny + 1))
   end subroutine sweep_init

   !> The aligned copies of the row masses (amc, copy of sweep_t) for the places in a line of the
   !> grid rows of each class when u starts a line, and of cb M^-1 for the cb of rcbm.
   subroutine aligned_copies(this, n)
      type(sweep_t), intent(inout) :: this
      integer, intent(in) :: n
      integer :: j, c, s, ncopy, len, o
      allocate (this%copy(0:line_reals - 1, size(this%rmass, 2)))
      this%copy = 0
      do j = 1, this%ny - 1   ! the inside rows
         this%copy(row_place(j, n), this%rclass(j)) = 1
      end do
      ncopy = count(this%copy > 0)
      ! each copy in its own stretch of whole lines (len reals), starting at its place s; whole
      ! lines per column, so that both columns are placed alike
      len = line_reals*((n + line_reals - 1)/line_reals + 1)
      allocate (this%amc((ncopy + 1)*len, 2))
      this%amc = 0
      o = line_skip(this%amc(1, 1))
      ncopy = 0
      do c = 1, size(this%rmass, 2)
         do s = 0, line_reals - 1
            if (this%copy(s, c) == 0) cycle
            this%copy(s, c) = o + ncopy*len + 1 + s
            ncopy = ncopy + 1
         end do
      end do
      call fill_copies(this%copy, this%rmass, this%amc(:, 1))
      call fill_copies(this%copy, this%rcbm, this%amc(:, 2))
   end subroutine aligned_copies

   !> The copies of the rows of r (one per class) at the places of copy (aligned_copies).
   subroutine fill_copies(copy, r, a)
      integer, intent(in) :: copy(0:, :)
      real(wp), intent(in) :: r(:, :)
      real(wp), intent(inout) :: a(:)
      integer :: c, s
      do c = 1, size(copy, 2)
         do s = 0, size(copy, 1) - 1
            if (copy(s, c) > 0) a(copy(s, c):copy(s, c) + size(r, 1) - 1) = r(:, c)
         end do
      end do
   end subroutine fill_copies

   !> Where grid row j (n reals a row) starts in a 64-byte line when u starts one: the place
   !> the sweep's aligned blocks and the masses' copies are chosen by (from the mesh, not from
   !> addresses, so that no result depends on where u is).
   pure integer function row_place(j, n)
      integer, intent(in) :: j, n
      row_place = mod(j*n, line_reals)
   end function row_place

   pure integer function row_type(j, ny)
      integer, intent(in) :: j, ny
      row_type = merge(1, merge(3, 2, j == ny), j == 0)
   end function row_type

   !> The nine stencils s(:, :, di, dj, ct, rt) of a structured mesh: column type ct and row type
   !> rt are 1 on the low boundary (i = 0 or j = 0), 2 inside, 3 on the high boundary; blocks of
   !> missing neighbours are zero. A node sums the blocks of the elements around it that exist,
   !> in the local-node order of the interior stencil (the same bits as contact2d_stiffness).
   pure subroutine sweep_stencils(ke, s)
      real(wp), intent(in) :: ke(8, 8)
      real(wp), intent(out) :: s(2, 2, -1:1, -1:1, 3, 3)
      integer :: ct, rt, a, b, d(2)
      s = 0
      do rt = 1, 3
         do ct = 1, 3
            do a = 1, 4
               ! node is local node a of the element whose bottom-left node is at -off(:, a)
               if (ct == 1 .and. off(1, a) == 1) cycle   ! no element to the left
               if (ct == 3 .and. off(1, a) == 0) cycle   ! none to the right
               if (rt == 1 .and. off(2, a) == 1) cycle   ! none below
               if (rt == 3 .and. off(2, a) == 0) cycle   ! none above
               do b = 1, 4
                  d = off(:, b) - off(:, a)
                  s(:, :, d(1), d(2), ct, rt) = s(:, :, d(1), d(2), ct, rt) + ke(2*a - 1:2*a, 2*b - 1:2*b)
               end do
            end do
         end do
      end do
   end subroutine sweep_stencils

   !> One sweep: f = K u, v = v* = ca v - cb M^-1 f, w = u + dt v*, and the partial sums of
   !> this%partial (see the module header).
   subroutine sweep_step(this, stiff, u, v, f, ca, cb, dt, w, full, rows)
      class(sweep_t), intent(inout) :: this
      type(stiffness_t), intent(in) :: stiff
      real(wp), intent(in) :: u(:, :)       !< u^n (2, nnode) [mm]
      real(wp), intent(inout) :: v(:, :)    !< v^(n-1/2) in, v* out [mm/s]
      real(wp), intent(inout) :: f(:, :)    !< K u^n out [N]
      real(wp), intent(in) :: ca, cb, dt    !< (1 - a dt/2)/(1 + a dt/2), dt/(1 + a dt/2) [s], dt [s]
      real(wp), intent(inout) :: w(:, :)    !< u~ out [mm]
      !> K u at every node and the sum u~ . K u (default); else only where kept (module header)
      logical, intent(in), optional :: full
      !> only the parts rows(1) .. rows(2), counted from 0 (default all): structured meshes the
      !> grid rows (0 .. ny), which read u on the rows rows(1) - 1 .. rows(2) + 2 only; general
      !> meshes the chunks rows(1) + 1 .. rows(2) + 1 of contact2d_rows, which read u on their
      !> reach only (several processes: contact2d_explicit)
      integer, intent(in), optional :: rows(2)
      logical :: all_out
      integer :: j0, j1
      all_out = .true.
      if (present(full)) all_out = full
      j0 = 0
      j1 = this%ny
      if (present(rows)) then
         j0 = rows(1)
         j1 = rows(2)
      end if
      if (this%structured) then
         ! cb M^-1 per class of row, formed once per value of cb: the same bits as cb*minv(p)*f(p)
         if (cb /= this%cb_last) then
            this%rcbm = cb*this%rminv
            this%cb_last = cb
            call fill_copies(this%copy, this%rcbm, this%amc(:, 2))
         end if
         call sweep_grid(this%nx, this%ny, this%e, this%cv, this%cs, this%rmass, this%rcbm, this%rclass, &
                         u, v, f, ca, dt, w, this%partial, stiff%nnode >= omp_min_nodes, this%sym, this%qs, &
                         this%scr, this%scr_slot, this%nscr, all_out, this%amc, this%copy, j0, j1)
      else
         if (present(rows)) then
            call this%rows%sweep(u, v, f, ca, cb, dt, w, this%partial, all_out, rows + 1)
         else
            call this%rows%sweep(u, v, f, ca, cb, dt, w, this%partial, all_out)
         end if
      end if
   end subroutine sweep_step

   !> Is K u at this node stored by every sweep, full or not (module header)? The boundary
   !> nodes (general meshes: contact2d_rows).
   pure logical function sweep_kept(this, node) result(yes)
      class(sweep_t), intent(in) :: this
      integer, intent(in) :: node
      integer :: i, j
      if (.not. this%structured) then
         yes = this%rows%kept(node)
         return
      end if
      i = mod(node - 1, this%nx + 1)
      j = (node - 1)/(this%nx + 1)
      yes = i == 0 .or. i == this%nx .or. j == 0 .or. j == this%ny
   end function sweep_kept

   subroutine sweep_grid(nx, ny, e, cv, cs, rmass, rcbm, rclass, u, v, f, ca, dt, w, partial, par, sym, qs, &
                         scr, scr_slot, nscr, full, amc, copy, j0, j1)
      integer, intent(in) :: nx, ny
      integer, intent(in) :: j0, j1   !< the grid rows swept (0 .. ny: all)
      real(wp), intent(in) :: e(2, 4, -1:1, 2, 3), cv(0:7, -3:3, 3, 3), cs(0:7, -3:3, 3, 3)
      ! (contiguous: the rows passed on need no contiguity test or packing per row)
      real(wp), intent(in), contiguous :: rmass(:, :), rcbm(:, :)
      integer, intent(in) :: rclass(0:ny)
      real(wp), intent(in) :: u(2, 0:nx, 0:ny)
      real(wp), intent(inout) :: v(2, 0:nx, 0:ny), f(2, 0:nx, 0:ny), w(2, 0:nx, 0:ny)
      real(wp), intent(in) :: ca, dt
      logical, intent(in) :: par, sym, full
      real(wp), intent(inout) :: partial(4, 0:ny)
      real(wp), intent(in) :: qs(0:7, 5)
      integer, intent(in) :: nscr
      ! (scr and amc not contiguous: with the attribute the step took 1.11x as long, A B B A at
      ! k = 4 and 5, docs/performance.md "Aligned blocks")
      real(wp), intent(inout) :: scr(0:, :, 0:)
      integer, intent(in) :: scr_slot
      real(wp), intent(in) :: amc(:, :)
      integer, intent(in) :: copy(0:, :)
      integer :: j, rt, t, jmade, k, kn, s0, s1, h, c, i0, d0, d1
      ! at most nscr threads: each uses its own scratch rows (the bits do not depend on it).
      ! Static rows: each thread keeps the same block of rows every step, so they stay in its own
      ! cache (with dynamic sharing rows moved between cores: one thread took 0.67 s for half the
      ! rows where one thread alone took 0.58 s for all, docs/performance.md "Tried and
      ! not kept")
      ! Each inside row forms the sum and difference rows of the next one in its own loop (scratch
      ! slots 3 - k, 4 - k); jmade is the row they were formed for (one thread's rows are
      ! consecutive: only its first inside row forms its own)
      jmade = -1
      !$omp parallel do schedule(static) if(par) private(rt, t, k, kn, s0, s1, h, c, i0, d0, d1) &
      !$omp firstprivate(jmade) &
      !$omp num_threads(max(1, min(omp_get_max_threads(), nscr)))
      do j = j0, j1
         rt = row_type(j, ny)
         if (sym .and. rt == 2) then
            t = omp_get_thread_num()
            k = 2*mod(j, 2) + 1
            kn = 4 - k
            ! (the last inside row forms nothing that is used: row j + 1 stands for j + 2)
            ! aligned blocks (grid_row_sym): where rows j and j + 1 start in their lines when u
            ! starts a line (as contact2d_explicit keeps it), the scratch rows placed alike, the
            ! masses' copy for row j's place. Taken from the mesh, not from u's address, so that
            ! the outputs that go by blocks, and so the bits, do not depend on where u is: u
            ! elsewhere only makes the sweep slower.
            s0 = row_place(j, 2*(nx + 1))
            s1 = row_place(j + 1, 2*(nx + 1))
            d0 = modulo(s0 - scr_slot, line_reals)
            d1 = modulo(s1 - scr_slot, line_reals)
            h = modulo(-s0 - 2, line_reals)
            c = rclass(j)
            i0 = copy(s0, c)
            call grid_row_sym(2*(nx + 1), u(1, 0, j - 1), u(1, 0, j), u(1, 0, j + 1), u(1, 0, min(j + 2, ny)), &
                              f(1, 0, j), qs, e(1, 1, -1, 1, rt), scr(d0:, k, t), scr(d0:, k + 1, t), &
                              scr(d1:, kn, t), scr(d1:, kn + 1, t), jmade == j, v(1, 0, j), amc(i0:, 1), &
                              amc(i0:, 2), ca, dt, w(1, 0, j), partial(1, j), full, h)
            jmade = j + 1
         else
            call grid_row(2*(nx + 1), u(1, 0, max(j - 1, 0)), u(1, 0, j), u(1, 0, min(j + 1, ny)), f(1, 0, j), &
                          cv(0, -3, 1, rt), cs(0, -3, 1, rt), e(1, 1, -1, 1, rt))
            call row_update(2*(nx + 1), u(1, 0, j), v(1, 0, j), f(1, 0, j), rmass(:, rclass(j)), rcbm(:, rclass(j)), &
                            ca, dt, w(1, 0, j), partial(1, j))
         end if
      end do
      !$omp end parallel do
   end subroutine sweep_grid

   !> The predictor and the energy sums on one grid row as flat arrays of interleaved (x, y)
   !> values, right after its K u (the row is in cache); cbm = cb M^-1 of the row.
   subroutine row_update(n, u0, v, f, m, cbm, ca, dt, w, part)
      integer, intent(in) :: n
      real(wp), intent(in) :: u0(0:n - 1), f(0:n - 1), m(0:n - 1), cbm(0:n - 1), ca, dt
      real(wp), intent(inout) :: v(0:n - 1), w(0:n - 1)
      real(wp), intent(out) :: part(4)
      integer :: p
      real(wp) :: vo, vs, wn, ek, es, ea
      ek = 0
      es = 0
      ea = 0
      !$omp simd private(vo, vs, wn) reduction(+:ek, es, ea)
      do p = 0, n - 1
         vo = v(p)
         vs = ca*vo - cbm(p)*f(p)
         wn = u0(p) + dt*vs
         ek = ek + m(p)*vs*vs
         es = es + wn*f(p)
         ea = ea + m(p)*(vs - vo)**2
         v(p) = vs
         w(p) = wn
      end do
      ! (element by element: an array constructor here allocates in Debug builds)
      part(1) = ek
      part(2) = 0
      part(3) = es
      part(4) = ea
   end subroutine row_update

   !> The same on the few outputs p0 .. p1 of a row left over by grid_row_sym's blocks (no
   !> vector set-up), added to ek, es, ea.
   subroutine tail_update(p0, p1, n, u0, v, f, m, cbm, ca, dt, w, ek, es, ea)
      integer, intent(in) :: p0, p1, n
      real(wp), intent(in) :: u0(0:n - 1), f(0:n - 1), m(0:n - 1), cbm(0:n - 1), ca, dt
      real(wp), intent(inout) :: v(0:n - 1), w(0:n - 1), ek, es, ea
      integer :: p
      real(wp) :: vo, vs, wn
      do p = p0, p1
         vo = v(p)
         vs = ca*vo - cbm(p)*f(p)
         wn = u0(p) + dt*vs
         ek = ek + m(p)*vs*vs
         es = es + wn*f(p)
         ea = ea + m(p)*(vs - vo)**2
         v(p) = vs
         w(p) = wn
      end do
   end subroutine tail_update

   !> K u on the interior nodes of one grid row as flat arrays of interleaved (x, y) values
   !> (n = 2 (nx + 1)).
   subroutine grid_row(n, um, u0, up, f, cv, c, e)
      integer, intent(in) :: n
      real(wp), intent(in) :: um(0:n - 1), u0(0:n - 1), up(0:n - 1)
      real(wp), intent(in) :: e(2, 4, -1:1, 2)   !< end-node stencils of this row type
      real(wp), intent(in) :: cv(0:7, -3:3, 3)
      real(wp), intent(in) :: c(0:7, -3:3, 3)   !< cv for blocks that start at odd p (a y output)
      real(wp), intent(inout) :: f(0:n - 1)
      integer :: b, l, p, nb
      real(wp) :: sm, s0, sp
      ! (array elements for the explicit-shape dummies: no temporaries)
      call end_node(e(1, 1, -1, 1), um(0), u0(0), up(0), f(0))
      call end_node(e(1, 1, -1, 2), um(n - 4), u0(n - 4), up(n - 4), f(n - 2))
      if (n < 6) return   ! one column of elements: no interior node
      ! outputs p = 2 .. n - 3 (the interior nodes); u_r(p + o) must stay within 0 .. n - 1, so
      ! the first (x, offset -3) and the last (y, offset +3) output leave out the term whose
      ! coefficient is zero; the others go by blocks of eight, then one by one
      p = 2
      f(p) = ((cv(0, -2, 1)*um(p - 2) + cv(0, -1, 1)*um(p - 1) + cv(0, 0, 1)*um(p) + cv(0, 1, 1)*um(p + 1) &
               + cv(0, 2, 1)*um(p + 2) + cv(0, 3, 1)*um(p + 3)) &
              + (cv(0, -2, 2)*u0(p - 2) + cv(0, -1, 2)*u0(p - 1) + cv(0, 0, 2)*u0(p) + cv(0, 1, 2)*u0(p + 1) &
                 + cv(0, 2, 2)*u0(p + 2) + cv(0, 3, 2)*u0(p + 3))) &
             + (cv(0, -2, 3)*up(p - 2) + cv(0, -1, 3)*up(p - 1) + cv(0, 0, 3)*up(p) + cv(0, 1, 3)*up(p + 1) &
                + cv(0, 2, 3)*up(p + 2) + cv(0, 3, 3)*up(p + 3))
      nb = (n - 6)/8
      do b = 0, nb - 1
         !$omp simd private(p, sm, s0, sp)
         do l = 0, 7
            p = 3 + 8*b + l
            sm = c(l, -3, 1)*um(p - 3) + c(l, -2, 1)*um(p - 2) + c(l, -1, 1)*um(p - 1) + c(l, 0, 1)*um(p) &
                 + c(l, 1, 1)*um(p + 1) + c(l, 2, 1)*um(p + 2) + c(l, 3, 1)*um(p + 3)
            s0 = c(l, -3, 2)*u0(p - 3) + c(l, -2, 2)*u0(p - 2) + c(l, -1, 2)*u0(p - 1) + c(l, 0, 2)*u0(p) &
                 + c(l, 1, 2)*u0(p + 1) + c(l, 2, 2)*u0(p + 2) + c(l, 3, 2)*u0(p + 3)
            sp = c(l, -3, 3)*up(p - 3) + c(l, -2, 3)*up(p - 2) + c(l, -1, 3)*up(p - 1) + c(l, 0, 3)*up(p) &
                 + c(l, 1, 3)*up(p + 1) + c(l, 2, 3)*up(p + 2) + c(l, 3, 3)*up(p + 3)
            f(p) = (sm + s0) + sp
         end do
      end do
      do p = 3 + 8*nb, n - 4
         l = mod(p, 2)
         sm = cv(l, -3, 1)*um(p - 3) + cv(l, -2, 1)*um(p - 2) + cv(l, -1, 1)*um(p - 1) + cv(l, 0, 1)*um(p) &
              + cv(l, 1, 1)*um(p + 1) + cv(l, 2, 1)*um(p + 2) + cv(l, 3, 1)*um(p + 3)
         s0 = cv(l, -3, 2)*u0(p - 3) + cv(l, -2, 2)*u0(p - 2) + cv(l, -1, 2)*u0(p - 1) + cv(l, 0, 2)*u0(p) &
              + cv(l, 1, 2)*u0(p + 1) + cv(l, 2, 2)*u0(p + 2) + cv(l, 3, 2)*u0(p + 3)
         sp = cv(l, -3, 3)*up(p - 3) + cv(l, -2, 3)*up(p - 2) + cv(l, -1, 3)*up(p - 1) + cv(l, 0, 3)*up(p) &
              + cv(l, 1, 3)*up(p + 1) + cv(l, 2, 3)*up(p + 2) + cv(l, 3, 3)*up(p + 3)
         f(p) = (sm + s0) + sp
      end do
      p = n - 3
      f(p) = ((cv(1, -3, 1)*um(p - 3) + cv(1, -2, 1)*um(p - 2) + cv(1, -1, 1)*um(p - 1) + cv(1, 0, 1)*um(p) &
               + cv(1, 1, 1)*um(p + 1) + cv(1, 2, 1)*um(p + 2)) &
              + (cv(1, -3, 2)*u0(p - 3) + cv(1, -2, 2)*u0(p - 2) + cv(1, -1, 2)*u0(p - 1) + cv(1, 0, 2)*u0(p) &
                 + cv(1, 1, 2)*u0(p + 1) + cv(1, 2, 2)*u0(p + 2))) &
             + (cv(1, -3, 3)*up(p - 3) + cv(1, -2, 3)*up(p - 2) + cv(1, -1, 3)*up(p - 1) + cv(1, 0, 3)*up(p) &
                + cv(1, 1, 3)*up(p + 1) + cv(1, 2, 3)*up(p + 2))
   end subroutine grid_row

   !> K u on the interior nodes of an inside grid row (rows j - 1, j, j + 1: um, u0, up) with a
   !> stencil of the symmetries of a rectangle (symmetric_coefficients), fused with the
   !> predictor and the energy sums. With the row sum S = um + up and difference D = up - um,
   !>    f(p) = A0 u0(p) + A2 (u0(p - 2) + u0(p + 2)) + B0 S(p) + B2 (S(p - 2) + S(p + 2))
   !>           + CX (D(p + 3) - D(p - 1)) + CY (D(p + 1) - D(p - 3)),
   !> coefficients by the parity of p (x or y output; CY = 0 for x, CX = 0 for y, CX = CY = C
   !> otherwise). The difference row is kept with x and y swapped, E(p) = D(p xor 1), so that the
   !> last term is C (E(p + 2) - E(p - 2)) on either parity: 6 multiply-adds and 8 loads per
   !> output instead of 21 and 21. Blocks of eight outputs: one vector of eight lanes of partial
   !> sums when the build's flags give 512-bit vectors, else two groups in a vector of four lanes
   !> (sweep_lanes, contact2d_build_config), so that coefficients and sums stay in registers.
   !> cbm = cb M^-1 of the row.
   !>
   !> Aligned blocks (docs/performance.md "Aligned blocks"): the blocks start at output 2 + h,
   !> where u0 starts a 64-byte line, and the caller places v, w, f, m, cbm, sb and eb alike, so
   !> that their vector loads and stores of eight values read one line, not two (the loads at
   !> p -+ 2 still read two). The outputs before and after the blocks go one by one. Which outputs
   !> go by blocks, and so the order of the energy sums' terms, depends on h; the caller takes h
   !> from the row and nx alone (where the row starts in a line when u starts one), so the bits
   !> do not depend on where u is, nor on the thread count.
   subroutine grid_row_sym(n, um, u0, up, u2, f, q, e, sb, eb, sn, en, have, v, m, cbm, ca, dt, w, part, full, h)
      integer, intent(in) :: n
      real(wp), intent(in) :: um(0:n - 1), u0(0:n - 1), up(0:n - 1), q(0:7, 5)
      real(wp), intent(in) :: u2(0:n - 1)        !< row j + 2 (for the next row's sb, eb)
      real(wp), intent(in) :: e(2, 4, -1:1, 2)   !< end-node stencils of this row type
      real(wp), intent(inout) :: f(0:n - 1), sb(0:n - 1), eb(0:n - 1)
      !> sb and eb of the next row (u2 + u0, u2 - u0 swapped), formed here
      real(wp), intent(inout) :: sn(0:n - 1), en(0:n - 1)
      logical, intent(in) :: have   !< sb and eb already hold this row's (formed by the row before)
      real(wp), intent(in) :: m(0:n - 1), cbm(0:n - 1), ca, dt
      real(wp), intent(inout) :: v(0:n - 1), w(0:n - 1)
      real(wp), intent(out) :: part(4)
      logical, intent(in) :: full   !< store f and form the u~ . f sum at the interior outputs
      integer, intent(in) :: h      !< the blocks start at output 2 + h (even, 0 .. 6)
      integer, parameter :: nl = sweep_lanes, nu = 8/sweep_lanes   !< lanes, groups per block
      integer :: b, l, p, nb, pa, k, i
      real(wp) :: fp, vo, vs, wn, ek, es, ea, ekl(0:nl - 1), esl(0:nl - 1), eal(0:nl - 1)
      ! (array elements for the explicit-shape dummies: no temporaries)
      call end_node(e(1, 1, -1, 1), um(0), u0(0), up(0), f(0))
      call end_node(e(1, 1, -1, 2), um(n - 4), u0(n - 4), up(n - 4), f(n - 2))
      ek = 0
      es = 0
      ea = 0
      if (n >= 6) then   ! else one column of elements: no interior node
         if (.not. have) then
            !$omp simd
            do p = 0, n - 2, 2
               sb(p) = um(p) + up(p)
               sb(p + 1) = um(p + 1) + up(p + 1)
               eb(p) = up(p + 1) - um(p + 1)
               eb(p + 1) = up(p) - um(p)
            end do
         end if
         ! outputs pa .. pa + 8 nb - 1 by blocks of eight, nu groups of nl lanes (lane l has the
         ! parity of l; contact2d_build_config); the others one by one
         pa = 2 + h
         nb = max(0, (n - 2 - pa)/8)
         if (nb == 0) pa = 2
         ekl = 0
         esl = 0
         eal = 0
         if (full) then
            do b = 0, nb - 1
               !$omp simd private(p, i, fp, vo, vs, wn)
               do l = 0, nl - 1
                  do i = 0, nu - 1
                     p = pa + 8*b + nl*i + l
                     fp = ((q(l, 1)*u0(p) + q(l, 2)*(u0(p - 2) + u0(p + 2))) &
                           + (q(l, 3)*sb(p) + q(l, 4)*(sb(p - 2) + sb(p + 2)))) &
                          + q(l, 5)*(eb(p + 2) - eb(p - 2))
                     f(p) = fp
                     vo = v(p)
                     vs = ca*vo - cbm(p)*fp
                     wn = u0(p) + dt*vs
                     ekl(l) = ekl(l) + m(p)*vs*vs
                     esl(l) = esl(l) + wn*fp
                     eal(l) = eal(l) + m(p)*(vs - vo)**2
                     v(p) = vs
                     w(p) = wn
                  end do
               end do
               !$omp simd private(p)
               do k = 0, 6, 2
                  p = pa + 8*b + k
                  sn(p) = u0(p) + u2(p)
                  sn(p + 1) = u0(p + 1) + u2(p + 1)
                  en(p) = u2(p + 1) - u0(p + 1)
                  en(p + 1) = u2(p) - u0(p)
               end do
            end do
         else
            ! the same without f and the u~ . f sum (written twice on purpose: one loop with
            ! `if (full)` inside ran 3x slower, one block loop branching per block to the two
            ! lane loops 0.85-0.93x, docs/performance.md "512-bit lanes")
            do b = 0, nb - 1
               !$omp simd private(p, i, fp, vo, vs)
               do l = 0, nl - 1
                  do i = 0, nu - 1
                     p = pa + 8*b + nl*i + l
                     fp = ((q(l, 1)*u0(p) + q(l, 2)*(u0(p - 2) + u0(p + 2))) &
                           + (q(l, 3)*sb(p) + q(l, 4)*(sb(p - 2) + sb(p + 2)))) &
                          + q(l, 5)*(eb(p + 2) - eb(p - 2))
                     vo = v(p)
                     vs = ca*vo - cbm(p)*fp
                     ekl(l) = ekl(l) + m(p)*vs*vs
                     eal(l) = eal(l) + m(p)*(vs - vo)**2
                     v(p) = vs
                     w(p) = u0(p) + dt*vs
                  end do
               end do
               !$omp simd private(p)
               do k = 0, 6, 2
                  p = pa + 8*b + k
                  sn(p) = u0(p) + u2(p)
                  sn(p + 1) = u0(p + 1) + u2(p + 1)
                  en(p) = u2(p + 1) - u0(p + 1)
                  en(p + 1) = u2(p) - u0(p)
               end do
            end do
         end if
         ! the next row's sums at the positions the blocks left out: 0, 2 .. pa - 2 and
         ! pa + 8 nb .. n - 2
         do k = -1, (n - 2 - 8*nb)/2 - 1
            p = merge(0, merge(2 + 2*k, 8*nb + 2 + 2*k, 2 + 2*k < pa), k < 0)
            sn(p) = u0(p) + u2(p)
            sn(p + 1) = u0(p + 1) + u2(p + 1)
            en(p) = u2(p + 1) - u0(p + 1)
            en(p + 1) = u2(p) - u0(p)
         end do
         ! K u at the outputs the blocks left out: 2 .. pa - 1 and pa + 8 nb .. n - 3
         do k = 0, n - 5 - 8*nb
            p = merge(2 + k, 8*nb + 2 + k, 2 + k < pa)
            l = mod(p, 2)
            f(p) = ((q(l, 1)*u0(p) + q(l, 2)*(u0(p - 2) + u0(p + 2))) &
                    + (q(l, 3)*sb(p) + q(l, 4)*(sb(p - 2) + sb(p + 2)))) &
                   + q(l, 5)*(eb(p + 2) - eb(p - 2))
         end do
         do l = 0, nl - 1
            ek = ek + ekl(l)
            es = es + esl(l)
            ea = ea + eal(l)
         end do
         ! the outputs left over: the end nodes (K u above) and those before and after the blocks
         call tail_update(0, pa - 1, n, u0, v, f, m, cbm, ca, dt, w, ek, es, ea)
         call tail_update(pa + 8*nb, n - 1, n, u0, v, f, m, cbm, ca, dt, w, ek, es, ea)
      else
         call tail_update(0, n - 1, n, u0, v, f, m, cbm, ca, dt, w, ek, es, ea)
      end if
      ! (element by element: an array constructor here allocates in Debug builds)
      part(1) = ek
      part(2) = 0
      part(3) = es
      part(4) = ea
   end subroutine grid_row_sym

   !> The interior stencil s2 = s(:, :, :, :, 2, 2) of a mesh of equal rectangles aligned with
   !> the axes is even in both directions in its xx and yy blocks and odd in both in its xy and
   !> yx blocks, which are equal: nine values (a00, a10, a01, a11 of xx, the same of yy, c).
   !> ok if s2 has these symmetries to 1e-12 of its largest entry; q then holds, per lane of
   !> eight flat outputs (even lanes x, odd lanes y), A0, A2, B0, B2, C of grid_row_sym,
   !> each the mean of the entries it stands for.
   pure subroutine symmetric_coefficients(s2, ok, q)
      real(wp), intent(in) :: s2(2, 2, -1:1, -1:1)
      logical, intent(out) :: ok
      real(wp), intent(out) :: q(0:7, 5)
      real(wp) :: r(2, 2, -1:1, -1:1), a(0:1, 0:1, 2), c
      integer :: k, di, dj
      do k = 1, 2
         a(0, 0, k) = s2(k, k, 0, 0)
         a(1, 0, k) = 0.5_wp*(s2(k, k, -1, 0) + s2(k, k, 1, 0))
         a(0, 1, k) = 0.5_wp*(s2(k, k, 0, -1) + s2(k, k, 0, 1))
         a(1, 1, k) = 0.25_wp*((s2(k, k, -1, -1) + s2(k, k, 1, 1)) + (s2(k, k, 1, -1) + s2(k, k, -1, 1)))
      end do
      c = 0.125_wp*(((s2(1, 2, 1, 1) + s2(1, 2, -1, -1)) - (s2(1, 2, 1, -1) + s2(1, 2, -1, 1))) &
                    + ((s2(2, 1, 1, 1) + s2(2, 1, -1, -1)) - (s2(2, 1, 1, -1) + s2(2, 1, -1, 1))))
      do dj = -1, 1
         do di = -1, 1
            r(1, 1, di, dj) = a(abs(di), abs(dj), 1)
            r(2, 2, di, dj) = a(abs(di), abs(dj), 2)
            r(1, 2, di, dj) = c*di*dj
            r(2, 1, di, dj) = c*di*dj
         end do
      end do
      ok = maxval(abs(r - s2)) <= 1.0e-12_wp*maxval(abs(s2))
      do k = 0, 7, 2
         q(k, :) = [a(0, 0, 1), a(1, 0, 1), a(0, 1, 1), a(1, 1, 1), c]
         q(k + 1, :) = [a(0, 0, 2), a(1, 0, 2), a(0, 1, 2), a(1, 1, 2), c]
      end do
   end subroutine symmetric_coefficients

   !> The interior stencils of the three row types on a grid row seen as one flat array of
   !> interleaved (x, y) values: output p takes sum over rows r and offsets o = -3..3 of
   !> cv(mod(p, 8), o, r) u_r(p + o) (cv repeats with period 2: x and y outputs), so eight
   !> outputs are one vector operation with no shuffles.
   pure subroutine flat_coefficients(s, cv)
      real(wp), intent(in) :: s(2, 2, -1:1, -1:1, 3, 3)
      real(wp), intent(out) :: cv(0:7, -3:3, 3, 3)
      integer :: rt, r, di, l
      cv = 0
      do rt = 1, 3
         do r = 1, 3
            do di = -1, 1
               do l = 0, 7, 2
                  ! x output at flat 2i: u_x(i + di) at offset 2 di, u_y(i + di) at 2 di + 1
                  cv(l, 2*di, r, rt) = s(1, 1, di, r - 2, 2, rt)
                  cv(l, 2*di + 1, r, rt) = s(1, 2, di, r - 2, 2, rt)
                  ! y output at flat 2i + 1: u_x(i + di) at 2 di - 1, u_y(i + di) at 2 di
                  cv(l + 1, 2*di - 1, r, rt) = s(2, 1, di, r - 2, 2, rt)
                  cv(l + 1, 2*di, r, rt) = s(2, 2, di, r - 2, 2, rt)
               end do
            end do
         end do
      end do
   end subroutine flat_coefficients

   !> The end-node stencils of end_node: e(c, :, dj, side, rt) are the coefficients of output c
   !> (x, y) of the low (side 1, i = 0) or high (side 2, i = nx) end node of a row of type rt on
   !> the four values (x, y of the column i0, x, y of i0 + 1; i0 = 0 or nx - 1) of row j + dj.
   pure subroutine end_coefficients(s, e)
      real(wp), intent(in) :: s(2, 2, -1:1, -1:1, 3, 3)
      real(wp), intent(out) :: e(2, 4, -1:1, 2, 3)
      integer :: rt, dj, side, c, di0, ct
      do rt = 1, 3
         do side = 1, 2
            ct = merge(1, 3, side == 1)
            di0 = merge(0, -1, side == 1)
            do dj = -1, 1
               do c = 1, 2
                  e(c, :, dj, side, rt) = [s(c, 1, di0, dj, ct, rt), s(c, 2, di0, dj, ct, rt), &
                                           s(c, 1, di0 + 1, dj, ct, rt), s(c, 2, di0 + 1, dj, ct, rt)]
               end do
            end do
         end do
      end do
   end subroutine end_coefficients

   !> K u at an end node of a grid row from the four values (x, y of two columns) at its end of
   !> rows j - 1, j, j + 1 (a, b, c) and its end-node stencil (end_coefficients; the blocks of
   !> missing rows are zero, adding nothing), in the order of the full stencil (dj, then di); x
   !> and y outputs side by side.
   pure subroutine end_node(e, a, b, c, g)
      real(wp), intent(in) :: e(2, 4, -1:1), a(4), b(4), c(4)
      real(wp), intent(out) :: g(2)
      g = 0
      g = g + e(:, 1, -1)*a(1) + e(:, 2, -1)*a(2) + e(:, 3, -1)*a(3) + e(:, 4, -1)*a(4)
      g = g + e(:, 1, 0)*b(1) + e(:, 2, 0)*b(2) + e(:, 3, 0)*b(3) + e(:, 4, 0)*b(4)
      g = g + e(:, 1, 1)*c(1) + e(:, 2, 1)*c(2) + e(:, 3, 1)*c(3) + e(:, 4, 1)*c(4)
   end subroutine end_node
end module contact2d_sweep
