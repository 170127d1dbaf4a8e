!> Node-to-segment contact between two deformable bodies (docs/geometry.md "Two bodies"): the
!> slave nodes of one body against the master boundary of another, in the current configuration
!> each step (finite sliding), with forward-increment Lagrange multipliers (Carpenter, Taylor &
!> Katona 1991; SPEC sections 3, 4, 6), frictionless, P1 (one multiplier per slave node).
!>
!> Each step, from the predicted positions x + u~ of both boundaries:
!>  - search: the closest master segment of each slave node. A bucket search (a uniform grid of
!>    cells as wide as the longest master segment; each segment listed in the cells its bounding
!>    box touches; a node looks in its cell and the eight around it: O(n + m)) runs when the
!>    nodes have moved, relative to each other, more than search_fraction of the shortest master
!>    segment since the last search; between searches each node walks to the closest of its
!>    segment and the two next to it;
!>  - projection xi in [0, 1] onto the segment (a node whose projection falls off an end of the
!>    master chain is off the master: no contact there), the master's normal interpolated
!>    between averaged nodal normals N_a, N_b (continuous across segments: n = ((1 - xi) N_a +
!>    xi N_b)/|..|, pointing out of the master body), and the predicted gap
!>    g~ = (x_s - (1 - xi) x_a - xi x_b) . n;
!>  - the constraint rows B_i (slave node +n, master nodes -(1 - xi) n and -xi n: the change of
!>    the gap with the displacements) and the LCP
!>        lambda >= 0,  w = (B M^-1 B^T) lambda - (-g~/c) >= 0,  lambda . w = 0,
!>    solved exactly (contact2d_lcp: active set with banded Cholesky, Murty's pivoting as the
!>    fallback; slave nodes that share a master node couple, so the matrix is banded along the
!>    interface); the forces B^T lambda on both bodies, u^(n+1) = u~ + c M^-1 B^T lambda
!>    (M^-1 zero on prescribed dofs). After the correction the linearised gap is c w >= 0.
!> Nothing is allocated in the step.
module contact2d_master_body
   use contact2d_kinds, only: wp, i8
   use contact2d_strings, only: str
   use contact2d_lcp, only: lcp_t
   implicit none
   private
   public :: master_body_t, search_fraction

   !> a search runs when the nodes may have moved, relative to each other, by more than this
   !> fraction of the shortest master segment since the last one
   real(wp), parameter :: search_fraction = 0.25_wp
   !> a projection more than this fraction of a segment beyond an end of the chain is off it
   real(wp), parameter :: end_tol = 1.0e-6_wp

   type :: master_body_t
      integer :: nc = 0                      !< slave nodes
      integer :: nm = 0                      !< master nodes (nm - 1 segments)
      integer, allocatable :: snode(:)       !< slave mesh nodes (nc)
      integer, allocatable :: mnode(:)       !< master chain's mesh nodes, in chain order (nm)
      real(wp), allocatable :: xs0(:, :), xm0(:, :)   !< initial positions (2, nc), (2, nm) [mm]
      real(wp), allocatable :: ims(:, :), imm(:, :)   !< inverse masses per dof, 0 where prescribed [1/t]
      real(wp) :: side = 1                   !< outward normal of segment (a, b): side*(ty, -tx)/|t|
      real(wp), allocatable :: xs(:, :), xm(:, :)     !< predicted positions of this step
      real(wp), allocatable :: xs_at(:, :), xm_at(:, :)  !< positions at the last search
      real(wp), allocatable :: nodal(:, :)   !< averaged nodal normals of the master (2, nm)
      integer, allocatable :: seg(:)         !< closest segment of each slave node (0: none near)
      logical, allocatable :: on(:)          !< the projection falls on the master chain
      real(wp), allocatable :: xi(:)         !< projection parameter in [0, 1]
      real(wp), allocatable :: n(:, :)       !< master normal at the projection (2, nc)
      real(wp), allocatable :: g(:)          !< predicted gap (nc) [mm]
      real(wp), allocatable :: b(:), lam(:)  !< LCP right-hand side -g~/c, normal forces [N]
      ! the bucket grid (capacities fixed at init)
      integer :: ncell_max = 0
      integer, allocatable :: cell_start(:), cell_item(:), cell_fill(:)
      !> first and last slave node (chain index) projecting next to each master node (assemble)
      integer, allocatable :: mfirst(:), mlast(:)
      real(wp) :: h_short = 0                !< shortest master segment at the last search [mm]
      integer :: kd = 0                      !< band width allowed for B M^-1 B^T
      type(lcp_t) :: lcp
      ! statistics
      integer(i8) :: steps = 0               !< steps taken
      integer(i8) :: searches = 0            !< bucket searches run (the first, at init, included)
      integer(i8) :: search_ticks = 0        !< time spent in the searches (system_clock ticks)
      integer(i8) :: lcp_iterations = 0      !< active-set iterations summed over the steps
      real(wp) :: residual_max = 0           !< largest LCP violation max(-min(w), 0)/max|b| seen
   contains
      procedure :: init => master_body_init
      procedure :: step => master_body_step
   end type master_body_t

contains

   !> Set up the pair: slave nodes snode, master chain mnode (in order along the boundary), the
   !> initial positions x, free(2, nnode) (1 on free dofs), lumped masses, a point inside the
   !> master body next to its first segment (it orients the normals). Out: the initial gaps and
   !> the master normals nu at each slave node's projection (huge gap where off the master).
   subroutine master_body_init(this, snode, mnode, x, free, mass, inside, gap, nu, stat, errmsg)
      class(master_body_t), intent(out) :: this
      integer, intent(in) :: snode(:), mnode(:)
      real(wp), intent(in) :: x(:, :), free(:, :), mass(:), inside(2)
      real(wp), intent(out) :: gap(:), nu(:, :)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp), allocatable :: ab(:, :)
      real(wp) :: t(2), hmax, hs
      integer :: i, nseg

      stat = 1
      errmsg = ''
      this%nc = size(snode)
      this%nm = size(mnode)
      nseg = this%nm - 1
      if (nseg < 1) then
         errmsg = 'contact: the master boundary has a single node; it needs at least one element edge'
         return
      end if
      this%snode = snode
      this%mnode = mnode
      this%xs0 = x(:, snode)
      this%xm0 = x(:, mnode)
      allocate (this%ims(2, this%nc), this%imm(2, this%nm))
      do i = 1, this%nc
         this%ims(:, i) = free(:, snode(i))/mass(snode(i))
      end do
      do i = 1, this%nm
         this%imm(:, i) = free(:, mnode(i))/mass(mnode(i))
      end do
      t = this%xm0(:, 2) - this%xm0(:, 1)
      this%side = 1
      if (dot_product(inside - this%xm0(:, 1), [t(2), -t(1)]) > 0) this%side = -1
      allocate (this%xs(2, this%nc), this%xm(2, this%nm), this%xs_at(2, this%nc), this%xm_at(2, this%nm), &
                this%nodal(2, this%nm), this%seg(this%nc), this%on(this%nc), this%xi(this%nc), &
                this%n(2, this%nc), this%g(this%nc), this%b(this%nc), this%lam(this%nc))
      this%lam = 0
      ! bucket grid: at most ncell_max cells, each segment in at most four of them
      this%ncell_max = 4*nseg + 16
      allocate (this%cell_start(this%ncell_max + 1), this%cell_fill(this%ncell_max), this%cell_item(4*nseg))
      allocate (this%mfirst(this%nm), this%mlast(this%nm))
      ! band width of B M^-1 B^T: slave nodes i < j couple when they project onto segments that
      ! share a master node, i.e. within two master segments of each other along the interface
      hmax = 0
      do i = 1, nseg
         hmax = max(hmax, norm2(this%xm0(:, i + 1) - this%xm0(:, i)))
      end do
      hs = huge(1.0_wp)
      do i = 1, this%nc - 1
         hs = min(hs, norm2(this%xs0(:, i + 1) - this%xs0(:, i)))
      end do
      if (this%nc < 2) hs = hmax
      this%kd = min(max(this%nc - 1, 0), 2*ceiling(3*hmax/max(hs, tiny(1.0_wp))) + 4)
      allocate (ab(this%kd + 1, this%nc))
      ab = 0
      ab(this%kd + 1, :) = 1
      call this%lcp%init(ab, this%kd)
      ! the initial configuration: search, project, gaps and normals
      this%xs = this%xs0
      this%xm = this%xm0
      call nodal_normals(this)
      call bucket_search(this)
      call project_all(this, .false.)
      this%searches = 0
      this%search_ticks = 0
      do i = 1, this%nc
         if (this%on(i)) then
            gap(i) = this%g(i)
         else
            gap(i) = huge(1.0_wp)
         end if
         nu(:, i) = this%n(:, i)
      end do
      stat = 0
   end subroutine master_body_init

   !> The contact step (SPEC section 4, step 3) for the pair: u^n, v^(n-1/2) and u~ (unew) in;
   !> unew becomes u^(n+1) at the slave and master nodes, fc(:, node) the contact force there.
   !> Out for contact_t's output: per slave node the normal force fn, the slave's outward normal
   !> (-n) and its tangent, and gap_fixed such that u^(n+1) . normal - gap_fixed is the slave
   !> node's predicted penetration; normal_work gets -lambda . B (u^(n+1) - u^(n-1))/2 (the
   !> contact forces' work on both bodies, SPEC section 6), pen_max the largest penetration
   !> left after the correction (c max(-w, 0)).
   subroutine master_body_step(this, u, v, unew, c, dt, fc, fn, normal, tangent, gap_fixed, normal_work, &
                               pen_max, stat, errmsg)
      class(master_body_t), intent(inout) :: this
      real(wp), intent(in) :: u(:, :), v(:, :)
      real(wp), intent(inout) :: unew(:, :)
      real(wp), intent(in) :: c, dt
      real(wp), intent(inout) :: fc(:, :)
      real(wp), intent(out) :: fn(:), normal(:, :), tangent(:, :), gap_fixed(:)
      real(wp), intent(inout) :: normal_work, pen_max
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: moved_s, moved_m, rc, f(2), wn, d(2), bscale, wmin
      integer :: i, k, a, q
      integer(i8) :: t0, t1

      this%steps = this%steps + 1
      rc = 1/c
      ! predicted positions and how far they moved since the last search
      moved_s = 0
      do i = 1, this%nc
         k = this%snode(i)
         this%xs(:, i) = this%xs0(:, i) + unew(:, k)
         moved_s = max(moved_s, norm2(this%xs(:, i) - this%xs_at(:, i)))
      end do
      moved_m = 0
      do i = 1, this%nm
         k = this%mnode(i)
         this%xm(:, i) = this%xm0(:, i) + unew(:, k)
         moved_m = max(moved_m, norm2(this%xm(:, i) - this%xm_at(:, i)))
      end do
      call nodal_normals(this)
      if (moved_s + moved_m > search_fraction*this%h_short) then
         call system_clock(t0)
         call bucket_search(this)
         call system_clock(t1)
         this%search_ticks = this%search_ticks + (t1 - t0)
      end if
      call project_all(this, .true.)
      ! the LCP: b = -g~/c where the node is on the master, 0 (never active) elsewhere
      call assemble(this, stat, errmsg)
      if (stat /= 0) return
      do i = 1, this%nc
         this%b(i) = merge(-this%g(i)*rc, 0.0_wp, this%on(i))
      end do
      call this%lcp%solve(this%b, this%lam, stat, errmsg)
      if (stat /= 0) then
         errmsg = 'contact between bodies: '//errmsg
         return
      end if
      this%lcp_iterations = this%lcp_iterations + this%lcp%iterations
      bscale = max(maxval(abs(this%b)), tiny(1.0_wp))
      wmin = 0
      do i = 1, this%nc
         if (this%lam(i) > 0) then
            wmin = min(wmin, -abs(this%lcp%w(i)))
         else
            wmin = min(wmin, this%lcp%w(i))
         end if
      end do
      this%residual_max = max(this%residual_max, -wmin/bscale)
      pen_max = max(pen_max, -c*minval(this%lcp%w))
      ! forces on both bodies: slave +lambda n, master -(1 - xi) lambda n and -xi lambda n
      do i = 1, this%nc
         fc(:, this%snode(i)) = 0
      end do
      do i = 1, this%nm
         fc(:, this%mnode(i)) = 0
      end do
      wn = 0
      do i = 1, this%nc
         fn(i) = this%lam(i)
         normal(:, i) = -this%n(:, i)
         tangent(1, i) = this%n(2, i)
         tangent(2, i) = -this%n(1, i)
         if (this%lam(i) <= 0) cycle
         f = this%lam(i)*this%n(:, i)
         k = this%snode(i)
         unew(:, k) = unew(:, k) + c*this%ims(:, i)*f
         fc(:, k) = fc(:, k) + f
         a = this%seg(i)
         q = this%mnode(a)
         unew(:, q) = unew(:, q) - c*this%imm(:, a)*((1 - this%xi(i))*f)
         fc(:, q) = fc(:, q) - (1 - this%xi(i))*f
         q = this%mnode(a + 1)
         unew(:, q) = unew(:, q) - c*this%imm(:, a + 1)*(this%xi(i)*f)
         fc(:, q) = fc(:, q) - this%xi(i)*f
      end do
      ! work of the contact forces on the centred increment (u^(n+1) - u^(n-1))/2 = (du + dt v)/2
      do i = 1, this%nc
         k = this%snode(i)
         d = 0.5_wp*((unew(:, k) - u(:, k)) + dt*v(:, k))
         wn = wn + dot_product(fc(:, k), d)
      end do
      do i = 1, this%nm
         k = this%mnode(i)
         d = 0.5_wp*((unew(:, k) - u(:, k)) + dt*v(:, k))
         wn = wn + dot_product(fc(:, k), d)
      end do
      normal_work = normal_work - wn
      ! the fixed-geometry view of the slave node for the output: u . normal - gap_fixed = -g~ at u~
      do i = 1, this%nc
         k = this%snode(i)
         gap_fixed(i) = (unew(1, k) - c*this%ims(1, i)*this%lam(i)*this%n(1, i))*normal(1, i) + &
                        (unew(2, k) - c*this%ims(2, i)*this%lam(i)*this%n(2, i))*normal(2, i) + this%g(i)
      end do
   end subroutine master_body_step

   !> Averaged nodal normals of the master chain at the predicted positions: at node k the
   !> outward normal of the chord x_(k+1) - x_(k-1) (the sum of the adjacent segments' normals,
   !> each weighted by its length), at the ends the end segment's.
   subroutine nodal_normals(this)
      type(master_body_t), intent(inout) :: this
      real(wp) :: t(2)
      integer :: k, km, kp
      do k = 1, this%nm
         km = max(k - 1, 1)
         kp = min(k + 1, this%nm)
         t = this%xm(:, kp) - this%xm(:, km)
         this%nodal(1, k) = this%side*t(2)/norm2(t)
         this%nodal(2, k) = -this%side*t(1)/norm2(t)
      end do
   end subroutine nodal_normals

   !> The bucket search (O(n + m)): each slave node's closest master segment among those in its
   !> cell and the eight around it (0 if none there: every segment is then farther than a cell,
   !> at least the longest segment); the positions kept for the next test of the motion.
   subroutine bucket_search(this)
      type(master_body_t), intent(inout) :: this
      real(wp) :: lo(2), hi(2), hc, best, dist, xi
      integer :: nx, ny, j, ix, iy, ix0, ix1, iy0, iy1, cell, i, p, jx, jy, s
      logical :: on
      this%searches = this%searches + 1
      lo = minval(this%xm, dim=2)
      hi = maxval(this%xm, dim=2)
      hc = 0
      this%h_short = huge(1.0_wp)
      do j = 1, this%nm - 1
         dist = norm2(this%xm(:, j + 1) - this%xm(:, j))
         hc = max(hc, dist)
         this%h_short = min(this%h_short, dist)
      end do
      hc = max(hc, 1.0e-12_wp*maxval(hi - lo), tiny(1.0_wp))
      nx = int((hi(1) - lo(1))/hc) + 1
      ny = int((hi(2) - lo(2))/hc) + 1
      do while (real(nx, wp)*real(ny, wp) > this%ncell_max)
         hc = 2*hc
         nx = int((hi(1) - lo(1))/hc) + 1
         ny = int((hi(2) - lo(2))/hc) + 1
      end do
      ! counting sort of the segments into the cells their bounding boxes touch
      this%cell_fill(1:nx*ny) = 0
      do j = 1, this%nm - 1
         call seg_cells(j)
         do iy = iy0, iy1
            do ix = ix0, ix1
               cell = iy*nx + ix + 1
               this%cell_fill(cell) = this%cell_fill(cell) + 1
            end do
         end do
      end do
      this%cell_start(1) = 1
      do cell = 1, nx*ny
         this%cell_start(cell + 1) = this%cell_start(cell) + this%cell_fill(cell)
         this%cell_fill(cell) = 0
      end do
      do j = 1, this%nm - 1
         call seg_cells(j)
         do iy = iy0, iy1
            do ix = ix0, ix1
               cell = iy*nx + ix + 1
               this%cell_item(this%cell_start(cell) + this%cell_fill(cell)) = j
               this%cell_fill(cell) = this%cell_fill(cell) + 1
            end do
         end do
      end do
      ! each slave node: its cell and the eight around it
      do i = 1, this%nc
         jx = floor((this%xs(1, i) - lo(1))/hc)
         jy = floor((this%xs(2, i) - lo(2))/hc)
         best = huge(1.0_wp)
         s = 0
         do iy = max(jy - 1, 0), min(jy + 1, ny - 1)
            do ix = max(jx - 1, 0), min(jx + 1, nx - 1)
               cell = iy*nx + ix + 1
               do p = this%cell_start(cell), this%cell_start(cell + 1) - 1
                  j = this%cell_item(p)
                  call segment_distance(this, i, j, dist, xi, on)
                  if (dist < best .or. (dist == best .and. j < s)) then
                     best = dist
                     s = j
                  end if
               end do
            end do
         end do
         this%seg(i) = s
      end do
      this%xs_at = this%xs
      this%xm_at = this%xm
   contains
      subroutine seg_cells(j)
         integer, intent(in) :: j
         ix0 = min(max(floor((min(this%xm(1, j), this%xm(1, j + 1)) - lo(1))/hc), 0), nx - 1)
         ix1 = min(max(floor((max(this%xm(1, j), this%xm(1, j + 1)) - lo(1))/hc), 0), nx - 1)
         iy0 = min(max(floor((min(this%xm(2, j), this%xm(2, j + 1)) - lo(2))/hc), 0), ny - 1)
         iy1 = min(max(floor((max(this%xm(2, j), this%xm(2, j + 1)) - lo(2))/hc), 0), ny - 1)
      end subroutine seg_cells
   end subroutine bucket_search

   !> Distance from slave node i (predicted position) to master segment j, the clamped
   !> projection parameter xi, and whether the projection falls on the chain (not beyond the
   !> free end of an end segment by more than end_tol of it).
   pure subroutine segment_distance(this, i, j, dist, xi, on)
      type(master_body_t), intent(in) :: this
      integer, intent(in) :: i, j
      real(wp), intent(out) :: dist, xi
      logical, intent(out) :: on
      real(wp) :: t(2), r(2), raw
      t = this%xm(:, j + 1) - this%xm(:, j)
      r = this%xs(:, i) - this%xm(:, j)
      raw = dot_product(r, t)/dot_product(t, t)
      on = .not. ((j == 1 .and. raw < -end_tol) .or. (j == this%nm - 1 .and. raw > 1 + end_tol))
      xi = min(max(raw, 0.0_wp), 1.0_wp)
      dist = norm2(r - xi*t)
   end subroutine segment_distance

   !> Each slave node: the closest of its segment and the two next to it (the walk between
   !> searches; walk = .false. keeps the searched one), xi, the interpolated normal and the gap.
   subroutine project_all(this, walk)
      type(master_body_t), intent(inout) :: this
      logical, intent(in) :: walk
      real(wp) :: best, dist, xi, xib, nv(2), xp(2)
      integer :: i, j, s, sb
      logical :: on, onb
      do i = 1, this%nc
         s = this%seg(i)
         if (s == 0) then
            this%on(i) = .false.
            this%xi(i) = 0
            this%g(i) = huge(1.0_wp)
            this%n(:, i) = [0.0_wp, 1.0_wp]
            cycle
         end if
         best = huge(1.0_wp)
         sb = s
         xib = 0
         onb = .false.
         do j = merge(max(s - 1, 1), s, walk), merge(min(s + 1, this%nm - 1), s, walk)
            call segment_distance(this, i, j, dist, xi, on)
            if (dist < best) then
               best = dist
               sb = j
               xib = xi
               onb = on
            end if
         end do
         this%seg(i) = sb
         this%xi(i) = xib
         this%on(i) = onb
         nv = (1 - xib)*this%nodal(:, sb) + xib*this%nodal(:, sb + 1)
         nv = nv/norm2(nv)
         this%n(:, i) = nv
         xp = (1 - xib)*this%xm(:, sb) + xib*this%xm(:, sb + 1)
         this%g(i) = dot_product(this%xs(:, i) - xp, nv)
      end do
   end subroutine project_all

   !> B M^-1 B^T into the LCP's band storage (lcp_t's ab and arow, its factor dropped):
   !> A_ij = sum over the nodes p of row i and q of row j that are the same mesh node of
   !> w_ip w_jq n_i^T diag(M^-1) n_j (w = 1 at the slave node, -(1 - xi), -xi at the master
   !> nodes); a node off the master is a row of its own (diagonal 1, b = 0: never active).
   !> stat 1 when two coupled slave nodes lie farther apart in the chain than the band.
   subroutine assemble(this, stat, errmsg)
      type(master_body_t), intent(inout) :: this
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: i, j, kd, si, sj, k
      real(wp) :: aij, wi(2), wj(2)
      stat = 0
      kd = this%kd
      ! couplings beyond the band: slave nodes far apart in the chain on one master node
      this%mfirst = huge(1)
      this%mlast = 0
      do i = 1, this%nc
         si = this%seg(i)
         if (si == 0 .or. .not. this%on(i)) cycle
         this%mfirst(si:si + 1) = min(this%mfirst(si:si + 1), i)
         this%mlast(si:si + 1) = max(this%mlast(si:si + 1), i)
      end do
      do k = 1, this%nm
         if (this%mlast(k) - this%mfirst(k) > kd) then
            stat = 1
            errmsg = 'contact between bodies: slave nodes '//str(this%mfirst(k))//' and '//str(this%mlast(k))// &
                     ' of the chain share master node '//str(k)//' but lie beyond the band '//str(kd)// &
                     ' of the multiplier matrix (the slave chain folds over the master)'
            return
         end if
      end do
      do i = 1, this%nc
         si = this%seg(i)
         ! a node off the master (no segment near, or beyond an end): a row of its own
         if (.not. this%on(i)) si = 0
         ! diagonal
         if (si == 0) then
            aij = 1
         else
            wi = [1 - this%xi(i), this%xi(i)]
            aij = sum(this%ims(:, i)*this%n(:, i)**2) + &
                  wi(1)**2*sum(this%imm(:, si)*this%n(:, i)**2) + wi(2)**2*sum(this%imm(:, si + 1)*this%n(:, i)**2)
            if (.not. aij > 0) aij = 1
         end if
         call put(i, i, aij)
         ! the band to the right
         do j = i + 1, min(i + kd, this%nc)
            call put(i, j, 0.0_wp)
         end do
         if (si == 0) cycle
         wi = [1 - this%xi(i), this%xi(i)]
         do j = i + 1, min(i + kd, this%nc)
            sj = this%seg(j)
            if (sj == 0 .or. .not. this%on(j)) cycle
            if (abs(sj - si) > 1) cycle
            wj = [1 - this%xi(j), this%xi(j)]
            aij = 0
            ! shared master nodes: si + p - 1 == sj + q - 1
            if (si == sj) then
               aij = wi(1)*wj(1)*sum(this%imm(:, si)*this%n(:, i)*this%n(:, j)) + &
                     wi(2)*wj(2)*sum(this%imm(:, si + 1)*this%n(:, i)*this%n(:, j))
            else if (sj == si + 1) then
               aij = wi(2)*wj(1)*sum(this%imm(:, sj)*this%n(:, i)*this%n(:, j))
            else
               aij = wi(1)*wj(2)*sum(this%imm(:, si)*this%n(:, i)*this%n(:, j))
            end if
            call put(i, j, aij)
         end do
      end do
      this%lcp%have_factor = .false.
      this%lcp%set_moved = .true.
   contains
      subroutine put(i, j, val)
         integer, intent(in) :: i, j
         real(wp), intent(in) :: val
         this%lcp%ab(kd + 1 + i - j, j) = val
         this%lcp%arow(j - i, i) = val
         this%lcp%arow(i - j, j) = val
      end subroutine put
   end subroutine assemble
end module contact2d_master_body
