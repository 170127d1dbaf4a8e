!> The part of an explicit step that is local to a segment of dofs (a grid row of a structured
!> mesh), done by the thread that swept the segment, right after it, inside the sweep's parallel
!> region (issue 13, docs/performance.md "SERIAL2"): the master thread then no longer does it
!> alone while the other threads wait. Per segment, in this order:
!>   1. keep v* and u~ at the listed dofs (loaded, prescribed, contact) and give v^(n-1/2) back;
!>   2. the prescribed values at t_(n+1), on the dofs that nothing changes later;
!>   3. on the steps of the damping estimate, K du_f at the dofs of the elements that touch a
!>      prescribed dof, and the Rayleigh sums of the blocks of dofs that end in the segment;
!>   4. v^(n+1/2) and the correction sums at the listed dofs that nothing changes later ("early"
!>      runs; the runs with a loaded or a contact dof are "late": corrected after the contact
!>      step by correct_late, on one thread).
!> Sums are per run and per block of rayleigh_block dofs, stored in fixed slots and added in
!> order by the caller: the bits do not depend on the number of threads or on which thread did
!> a segment. The Rayleigh block sums are those of the former pass over all dofs, block by block
!> (the same loop on the same range), so alpha keeps its bits; the correction sums are per run
!> (runs split at segment boundaries), which moves the energies in their last bits only.
!> The step does no allocation and no I/O here.
module contact2d_stepwork
   use contact2d_kinds, only: wp
   use contact2d_stiffness, only: omp_min_nodes
   implicit none
   private
   public :: stepwork_t

   !> dofs per block of the Rayleigh sums (fixed, so sums do not depend on the thread count)
   integer, parameter :: rayleigh_block = 2048

   !> Lists and state of the per-segment work.
   type, public :: stepwork_t
      integer :: ndof = 0                  !< 2 nnode
      integer :: nseg = 1                  !< segments (grid rows, or one for a general mesh)
      integer :: seglen = 0                !< dofs per segment (the last may be shorter)
      ! listed dofs (contact2d_explicit special_dofs), as runs of consecutive dofs within a segment
      integer :: nrun = 0
      integer, allocatable :: run(:, :)    !< (3, nrun): first dof, place in the list, length
      integer, allocatable :: seg_run(:)   !< (0:nseg): the runs of segment j are seg_run(j) + 1 .. seg_run(j + 1)
      logical, allocatable :: late(:)      !< (nrun): corrected after the contact step
      real(wp), allocatable :: vold(:), vstar(:), wstar(:)   !< v^(n-1/2), v*, u~ per listed dof
      real(wp), allocatable :: mass(:), pres(:)   !< mass, 1 if prescribed, per listed dof
      real(wp), allocatable :: rsum(:, :)  !< (4, nrun): m dv (v + v*), du . f, m dv (...), reaction work
      ! prescribed values: early entries by segment (load order within), late ones, all
      integer, allocatable :: pdof(:), pcurve(:), seg_p(:)
      integer, allocatable :: lpdof(:), lpcurve(:)
      integer, allocatable :: adof(:)      !< every prescribed dof (load order)
      real(wp), allocatable :: cnext(:)    !< curve values at t_(n+1)
      real(wp) :: dt = 0, alpha = 0
      ! damping estimate (automatic damping only)
      logical :: auto = .false.            !< the estimate's data are set up
      logical :: damp = .false.            !< this step forms the estimate
      !> u and K u at the last estimate; 1 free, 0 prescribed, -1 free among the dofs of pd;
      !> mass per dof; du_p at the prescribed dofs (0 elsewhere) (flattened, 2 nnode)
      real(wp), allocatable :: u_mark(:), f_mark(:), rmask(:), mdof(:), dup(:)
      !> dofs of the elements that touch a prescribed dof (ascending), by segment (0:nseg)
      integer, allocatable :: pd(:), seg_pd(:)
      !> per dof of pd, its element terms in element order: slot of fe and local dof (1..8)
      integer, allocatable :: pd_ptr(:), pd_slot(:), pd_loc(:)
      !> element slots of each segment (0:nseg): the elements (index into pel) with a node in it
      integer, allocatable :: sl_el(:), seg_sl(:)
      real(wp), allocatable :: fe(:, :)    !< (8, slots): -K_e du_p of the slot's element
      integer, allocatable :: pel_conn(:, :), pel_shape(:)
      real(wp), allocatable :: ke(:, :, :)
      integer :: nblock = 0
      integer, allocatable :: blk_first(:), seg_blk(:)   !< first segment of a block; blocks ending in a segment (0:nseg)
      logical, allocatable :: rdone(:)
      real(wp), allocatable :: rpart(:, :) !< (2, nblock): du_f . K du_f, du_f . M du_f
      ! the contact step in the sweep's parallel region (split, balance)
      integer :: c_lo = -1, c_hi = -1     !< segments of the first and last contact node (-1: none)
      !> running estimate of the contact step's time (with its late work) in segments' times:
      !> the thread that does it gets that many fewer segments, shared among all threads
      real(wp) :: c_rows = 0
      !> the split of this step (plan): thread t sweeps segments bnd(t) .. bnd(t + 1) - 1; cthread
      !> does the contact step (-1: none, the caller does it after the region)
      integer, allocatable :: bnd(:)
      integer :: cthread = -1
   contains
      procedure :: init => stepwork_init
      procedure :: set_damping => stepwork_set_damping
      procedure :: set_list => stepwork_set_list
      procedure :: gather => stepwork_gather
      procedure :: prepare => stepwork_prepare
      procedure :: after_row => stepwork_after_row
      procedure :: after_rows => stepwork_after_rows
      procedure :: all_rows => stepwork_all_rows
      procedure :: estimate_all => stepwork_estimate_all
      procedure :: set_late_prescribed => stepwork_set_late_prescribed
      procedure :: correct_late => stepwork_correct_late
      procedure :: sums => stepwork_sums
      procedure :: estimate => stepwork_estimate
      procedure :: set_contact => stepwork_set_contact
      procedure :: reserve => stepwork_reserve
      procedure :: plan => stepwork_plan
      procedure :: split => stepwork_split
      procedure :: balance => stepwork_balance
   end type stepwork_t

contains

   !> Segments of seglen dofs over 2 nnode dofs (seglen = 2 nnode: one segment).
   subroutine stepwork_init(this, nnode, seglen, ncurve)
      class(stepwork_t), intent(out) :: this
      integer, intent(in) :: nnode, seglen, ncurve
      this%ndof = 2*nnode
      this%seglen = seglen
      this%nseg = (this%ndof + seglen - 1)/seglen
      allocate (this%cnext(ncurve))
      this%cnext = 0
   end subroutine stepwork_init

   !> Segment of a flattened dof.
   elemental integer function seg_of(seglen, d) result(j)
      integer, intent(in) :: seglen, d
      j = (d - 1)/seglen
   end function seg_of

   !> The contact nodes' segments (nodes: the contact nodes; none: no contact step).
   subroutine stepwork_set_contact(this, nodes)
      class(stepwork_t), intent(inout) :: this
      integer, intent(in) :: nodes(:)
      if (size(nodes) == 0) then
         this%c_lo = -1
         this%c_hi = -1
      else
         this%c_lo = seg_of(this%seglen, 2*minval(nodes))
         this%c_hi = seg_of(this%seglen, 2*maxval(nodes))
      end if
   end subroutine stepwork_set_contact

   !> The segments jlo .. jhi of thread t of nt (consecutive, in thread order) and whether this
   !> thread does the contact step (mine: all contact segments are its own). Equal shares, but
   !> the thread with the contact segments, when it is the first or the last, gets
   !> c_rows (nt - 1)/nt segments fewer. The bits do not depend on the split.
   subroutine split_of(this, t, nt, jlo, jhi, mine)
      class(stepwork_t), intent(in) :: this
      integer, intent(in) :: t, nt
      integer, intent(out) :: jlo, jhi
      logical, intent(out) :: mine
      integer :: b1, s, n
      n = this%nseg
      jlo = (t*n)/nt
      jhi = ((t + 1)*n)/nt - 1
      mine = .false.
      if (this%c_lo < 0) return
      if (nt == 1) then
         mine = .true.
         return
      end if
      s = nint(this%c_rows*(nt - 1)/nt)
      if (this%c_hi < n/nt) then
         ! the first thread's: it ends s earlier (but after the contact segments)
         b1 = max(n/nt - s, this%c_hi + 1)
         if (t == 0) then
            jlo = 0
            jhi = b1 - 1
            mine = .true.
         else
            jlo = b1 + ((t - 1)*(n - b1))/(nt - 1)
            jhi = b1 + (t*(n - b1))/(nt - 1) - 1
         end if
      else if (this%c_lo >= ((nt - 1)*n)/nt) then
         ! the last thread's: it starts s later (but before the contact segments)
         b1 = min(((nt - 1)*n)/nt + s, this%c_lo)
         if (t == nt - 1) then
            jlo = b1
            jhi = n - 1
            mine = .true.
         else
            jlo = (t*b1)/(nt - 1)
            jhi = ((t + 1)*b1)/(nt - 1) - 1
         end if
      else
         mine = jlo <= this%c_lo .and. this%c_hi <= jhi
      end if
   end subroutine split_of

   !> Room for the split of up to nt threads (outside the step loop).
   subroutine stepwork_reserve(this, nt)
      class(stepwork_t), intent(inout) :: this
      integer, intent(in) :: nt
      if (allocated(this%bnd)) then
         if (size(this%bnd) >= nt + 1) return
         deallocate (this%bnd)
      end if
      allocate (this%bnd(0:nt))
   end subroutine stepwork_reserve

   !> The split of this step among nt threads (split_of), before the parallel region: every
   !> thread then reads the same one, whatever balance changes during the step.
   subroutine stepwork_plan(this, nt)
      class(stepwork_t), intent(inout) :: this
      integer, intent(in) :: nt
      integer :: t, jlo, jhi
      logical :: mine
      this%cthread = -1
      do t = 0, nt - 1
         call split_of(this, t, nt, jlo, jhi, mine)
         this%bnd(t) = jlo
         if (t == nt - 1) this%bnd(nt) = jhi + 1
         if (mine) this%cthread = t
      end do
   end subroutine stepwork_plan

   !> Thread t's segments jlo .. jhi of the plan, and whether it does the contact step.
   subroutine stepwork_split(this, t, jlo, jhi, mine)
      class(stepwork_t), intent(in) :: this
      integer, intent(in) :: t
      integer, intent(out) :: jlo, jhi
      logical, intent(out) :: mine
      jlo = this%bnd(t)
      jhi = this%bnd(t + 1) - 1
      mine = t == this%cthread
   end subroutine stepwork_split

   !> After the contact step on the sweep's thread: its segments took trows seconds for nrows
   !> segments, the contact step tc; the estimate c_rows moves 1/16 of the way to tc/(trows/nrows).
   subroutine stepwork_balance(this, trows, nrows, tc)
      class(stepwork_t), intent(inout) :: this
      real(wp), intent(in) :: trows, tc
      integer, intent(in) :: nrows
      real(wp) :: est
      if (nrows <= 0 .or. trows <= 0) return
      est = min(tc/(trows/nrows), real(this%nseg, wp)/4)
      this%c_rows = this%c_rows + (est - this%c_rows)/16
   end subroutine stepwork_balance

   !> The damping estimate's data: the elements (conn, shape_of, ke) that touch a prescribed dof
   !> (free(2, nnode) = 0), their dofs, the mask and the blocks.
   subroutine stepwork_set_damping(this, conn, shape_of, ke, free, mdof)
      class(stepwork_t), intent(inout) :: this
      integer, intent(in) :: conn(:, :), shape_of(:)
      real(wp), intent(in) :: ke(:, :, :), free(:, :), mdof(:)
      logical, allocatable :: touches(:), mark(:)
      integer, allocatable :: pel(:), cnt(:)
      real(wp), allocatable :: fr(:)
      integer :: e, a, k, n, j, q, d, s, ns, npd, c, b, lo, hi
      this%auto = .true.
      n = size(free, 2)
      allocate (touches(size(conn, 2)))
      do e = 1, size(touches)
         touches(e) = any(free(:, conn(:, e)) == 0)
      end do
      pel = pack([(e, e=1, size(touches))], touches)
      this%pel_conn = conn(:, pel)
      this%pel_shape = shape_of(pel)
      this%ke = ke
      allocate (mark(2*n))
      mark = .false.
      do k = 1, size(pel)
         do a = 1, 4
            mark(2*conn(a, pel(k)) - 1:2*conn(a, pel(k))) = .true.
         end do
      end do
      this%pd = pack([(d, d=1, 2*n)], mark)
      npd = size(this%pd)
      fr = reshape(free, [2*n])
      this%rmask = merge(-fr, fr, mark .and. fr > 0)
      this%mdof = mdof
      allocate (this%u_mark(2*n), this%f_mark(2*n), this%dup(2*n))
      this%u_mark = 0
      this%f_mark = 0
      this%dup = 0
      ! pd by segment (ascending dofs: contiguous)
      allocate (this%seg_pd(0:this%nseg))
      this%seg_pd = 0
      do q = 1, npd
         j = seg_of(this%seglen, this%pd(q))
         this%seg_pd(j + 1:) = this%seg_pd(j + 1:) + 1
      end do
      ! element slots: per segment, the elements with a node in it, in element order
      allocate (this%seg_sl(0:this%nseg))
      ns = 0
      this%seg_sl(0) = 0
      do j = 0, this%nseg - 1
         do k = 1, size(pel)
            if (any(seg_of(this%seglen, 2*conn(:, pel(k))) == j)) ns = ns + 1
         end do
         this%seg_sl(j + 1) = ns
      end do
      allocate (this%sl_el(ns), this%fe(8, ns))
      this%fe = 0
      s = 0
      do j = 0, this%nseg - 1
         do k = 1, size(pel)
            if (any(seg_of(this%seglen, 2*conn(:, pel(k))) == j)) then
               s = s + 1
               this%sl_el(s) = k
            end if
         end do
      end do
      ! per dof of pd: the element terms in element order (as stiffness_apply_elements adds them)
      allocate (cnt(npd), this%pd_ptr(npd + 1))
      cnt = 0
      do q = 1, npd
         j = seg_of(this%seglen, this%pd(q))
         do s = this%seg_sl(j) + 1, this%seg_sl(j + 1)
            do a = 1, 4
               do c = 1, 2
                  if (2*(conn(a, pel(this%sl_el(s))) - 1) + c == this%pd(q)) cnt(q) = cnt(q) + 1
               end do
            end do
         end do
      end do
      this%pd_ptr(1) = 1
      do q = 1, npd
         this%pd_ptr(q + 1) = this%pd_ptr(q) + cnt(q)
      end do
      allocate (this%pd_slot(this%pd_ptr(npd + 1) - 1), this%pd_loc(this%pd_ptr(npd + 1) - 1))
      do q = 1, npd
         j = seg_of(this%seglen, this%pd(q))
         c = this%pd_ptr(q)
         ! slots of segment j are in element order
         do s = this%seg_sl(j) + 1, this%seg_sl(j + 1)
            do a = 1, 4
               do b = 1, 2
                  if (2*(conn(a, pel(this%sl_el(s))) - 1) + b == this%pd(q)) then
                     this%pd_slot(c) = s
                     this%pd_loc(c) = 2*(a - 1) + b
                     c = c + 1
                  end if
               end do
            end do
         end do
      end do
      ! blocks of the Rayleigh sums and the segments of their first and last dofs
      this%nblock = (2*n + rayleigh_block - 1)/rayleigh_block
      allocate (this%blk_first(this%nblock), this%seg_blk(0:this%nseg), this%rdone(this%nblock), &
                this%rpart(2, this%nblock))
      this%rdone = .false.
      this%rpart = 0
      this%seg_blk = 0
      do b = 1, this%nblock
         lo = (b - 1)*rayleigh_block + 1
         hi = min(b*rayleigh_block, 2*n)
         this%blk_first(b) = seg_of(this%seglen, lo)
         j = seg_of(this%seglen, hi)
         this%seg_blk(j + 1:) = this%seg_blk(j + 1:) + 1
      end do
   end subroutine stepwork_set_damping

   !> The listed dofs: mark, pres and late per flattened dof (late: changed after the sweep by
   !> the loads or the contact step), masses per node; the prescribed entries (pdof: flattened
   !> dof, curve; load order).
   subroutine stepwork_set_list(this, mark, pres, late, mass, pdof, pcurve)
      class(stepwork_t), intent(inout) :: this
      logical, intent(in) :: mark(:), pres(:), late(:)
      real(wp), intent(in) :: mass(:)
      integer, intent(in) :: pdof(:), pcurve(:)
      integer :: n, d, i, r, j, p, ne, nl
      logical :: new
      if (allocated(this%run)) deallocate (this%run, this%seg_run, this%late, this%vold, this%vstar, &
                                           this%wstar, this%mass, this%pres, this%rsum, this%pdof, &
                                           this%pcurve, this%seg_p, this%lpdof, this%lpcurve, this%adof)
      n = count(mark)
      allocate (this%vold(n), this%vstar(n), this%wstar(n), this%mass(n), this%pres(n))
      this%vold = 0
      this%vstar = 0
      this%wstar = 0
      ! runs of consecutive listed dofs within a segment
      r = 0
      do d = 1, this%ndof
         if (.not. mark(d)) cycle
         new = d == 1
         if (.not. new) new = .not. mark(d - 1) .or. seg_of(this%seglen, d) /= seg_of(this%seglen, d - 1)
         if (new) r = r + 1
      end do
      this%nrun = r
      allocate (this%run(3, r), this%late(r), this%seg_run(0:this%nseg), this%rsum(4, r))
      this%rsum = 0
      this%seg_run = 0
      i = 0
      r = 0
      do d = 1, this%ndof
         if (.not. mark(d)) cycle
         i = i + 1
         this%mass(i) = mass((d + 1)/2)
         this%pres(i) = merge(1, 0, pres(d))
         new = d == 1
         if (.not. new) new = .not. mark(d - 1) .or. seg_of(this%seglen, d) /= seg_of(this%seglen, d - 1)
         if (new) then
            r = r + 1
            this%run(:, r) = [d, i, 0]
            this%late(r) = .false.
            j = seg_of(this%seglen, d)
            this%seg_run(j + 1:) = this%seg_run(j + 1:) + 1
         end if
         this%run(3, r) = this%run(3, r) + 1
         this%late(r) = this%late(r) .or. late(d)
      end do
      ! prescribed entries: early (by segment, load order within) and late ones
      this%adof = pdof
      ne = count(.not. late(pdof))
      nl = size(pdof) - ne
      allocate (this%pdof(ne), this%pcurve(ne), this%lpdof(nl), this%lpcurve(nl), this%seg_p(0:this%nseg))
      this%seg_p = 0
      i = 0
      do j = 0, this%nseg - 1
         do p = 1, size(pdof)
            if (late(pdof(p)) .or. seg_of(this%seglen, pdof(p)) /= j) cycle
            i = i + 1
            this%pdof(i) = pdof(p)
            this%pcurve(i) = pcurve(p)
         end do
         this%seg_p(j + 1) = i
      end do
      i = 0
      do p = 1, size(pdof)
         if (.not. late(pdof(p))) cycle
         i = i + 1
         this%lpdof(i) = pdof(p)
         this%lpcurve(i) = pcurve(p)
      end do
   end subroutine stepwork_set_list

   !> vold = v at the listed dofs (flattened v).
   subroutine stepwork_gather(this, v)
      class(stepwork_t), intent(inout) :: this
      real(wp), intent(in) :: v(*)
      integer :: r, d, q, i
      do r = 1, this%nrun
         d = this%run(1, r) - 1
         q = this%run(2, r) - 1
         !$omp simd
         do i = 1, this%run(3, r)
            this%vold(q + i) = v(d + i)
         end do
      end do
   end subroutine stepwork_gather

   !> Before the sweep: curve values at t_(n+1), dt, alpha of the step, whether it forms the
   !> damping estimate (then du_p = u - u_mark at the prescribed dofs, from u^n).
   subroutine stepwork_prepare(this, cnext, dt, alpha, damp, u)
      class(stepwork_t), intent(inout) :: this
      real(wp), intent(in) :: cnext(:), dt, alpha
      logical, intent(in) :: damp
      real(wp), intent(in) :: u(*)
      integer :: p
      this%cnext(:) = cnext
      this%dt = dt
      this%alpha = alpha
      this%damp = damp .and. this%auto
      if (this%damp) then
         do p = 1, size(this%adof)
            this%dup(this%adof(p)) = u(this%adof(p)) - this%u_mark(this%adof(p))
         end do
      end if
   end subroutine stepwork_prepare

   !> The work of segment j (module header), right after the sweep stored v*, u~ and K u there;
   !> jfirst: the first segment this thread swept in this sweep (it swept jfirst .. j): the
   !> Rayleigh blocks that end in j and start at or after jfirst are summed here, the others by
   !> after_rows. Flattened u^n, v, f = K u^n, w = u~.
   subroutine stepwork_after_row(this, j, jfirst, u, v, f, w)
      class(stepwork_t), intent(inout) :: this
      integer, intent(in) :: j, jfirst
      real(wp), intent(in) :: u(*), f(*)
      real(wp), intent(inout) :: v(*), w(*)
      integer :: r, p, b
      do r = this%seg_run(j) + 1, this%seg_run(j + 1)
         call keep_run(this%run(:, r), v, w, this%vold, this%vstar, this%wstar)
      end do
      do p = this%seg_p(j) + 1, this%seg_p(j + 1)
         w(this%pdof(p)) = this%cnext(this%pcurve(p))
      end do
      if (this%damp) then
         call pres_terms(this, j, f)
         do b = this%seg_blk(j) + 1, this%seg_blk(j + 1)
            if (this%blk_first(b) < jfirst) cycle
            call rayleigh_sums(b, this%ndof, u, f, this%rmask, this%mdof, this%u_mark, this%f_mark, this%rpart(:, b))
            this%rdone(b) = .true.
         end do
      end if
      do r = this%seg_run(j) + 1, this%seg_run(j + 1)
         if (this%late(r)) cycle
         call correct_run(this%run(:, r), this%pres, this%mass, u, w, f, this%dt, this%alpha, this%vold, &
                          this%vstar, this%wstar, v, this%rsum(:, r))
      end do
   end subroutine stepwork_after_row

   !> Inside the sweep's parallel region, after its row loop (ended without a barrier): on the
   !> steps of the damping estimate, a barrier and the Rayleigh blocks that no thread summed in
   !> the loop (those across two threads' segments); the flags are reset for the next estimate.
   subroutine stepwork_after_rows(this, u, f)
      class(stepwork_t), intent(inout) :: this
      real(wp), intent(in) :: u(*), f(*)
      integer :: b
      if (.not. this%damp) return
      !$omp barrier
      !$omp do schedule(static)
      do b = 1, this%nblock
         if (.not. this%rdone(b)) &
            call rayleigh_sums(b, this%ndof, u, f, this%rmask, this%mdof, this%u_mark, this%f_mark, this%rpart(:, b))
         this%rdone(b) = .false.
      end do
      !$omp end do nowait
   end subroutine stepwork_after_rows

   !> The work of every segment after a sweep that did none of it (general meshes), on this
   !> thread; the Rayleigh blocks by a parallel loop (estimate_all).
   subroutine stepwork_all_rows(this, u, v, f, w)
      class(stepwork_t), intent(inout) :: this
      real(wp), intent(in) :: u(*), f(*)
      real(wp), intent(inout) :: v(*), w(*)
      logical :: damp
      integer :: j
      damp = this%damp
      this%damp = .false.
      do j = 0, this%nseg - 1
         call this%after_row(j, 0, u, v, f, w)
      end do
      this%damp = damp
      if (damp) call this%estimate_all(u, f)
   end subroutine stepwork_all_rows

   !> The damping estimate's terms and sums over all segments (damp set by prepare).
   subroutine stepwork_estimate_all(this, u, f)
      class(stepwork_t), intent(inout) :: this
      real(wp), intent(in) :: u(*), f(*)
      integer :: j, b
      do j = 0, this%nseg - 1
         call pres_terms(this, j, f)
      end do
      !$omp parallel do schedule(static) if(this%ndof >= 2*omp_min_nodes)
      do b = 1, this%nblock
         call rayleigh_sums(b, this%ndof, u, f, this%rmask, this%mdof, this%u_mark, this%f_mark, this%rpart(:, b))
      end do
      !$omp end parallel do
   end subroutine stepwork_estimate_all

   !> The prescribed values on the late dofs (after the loads, before the contact step).
   subroutine stepwork_set_late_prescribed(this, w)
      class(stepwork_t), intent(in) :: this
      real(wp), intent(inout) :: w(*)
      integer :: p
      do p = 1, size(this%lpdof)
         w(this%lpdof(p)) = this%cnext(this%lpcurve(p))
      end do
   end subroutine stepwork_set_late_prescribed

   !> v^(n+1/2) and the correction sums of the late runs (after the contact step).
   subroutine stepwork_correct_late(this, u, w, f, v)
      class(stepwork_t), intent(inout) :: this
      real(wp), intent(in) :: u(*), w(*), f(*)
      real(wp), intent(inout) :: v(*)
      integer :: r
      do r = 1, this%nrun
         if (.not. this%late(r)) cycle
         call correct_run(this%run(:, r), this%pres, this%mass, u, w, f, this%dt, this%alpha, this%vold, &
                          this%vstar, this%wstar, v, this%rsum(:, r))
      end do
   end subroutine stepwork_correct_late

   !> The correction sums (m v^2, -, u . K u, m dv^2) and the reactions' work, runs in order.
   subroutine stepwork_sums(this, corr, work)
      class(stepwork_t), intent(in) :: this
      real(wp), intent(out) :: corr(4), work
      integer :: r
      corr = 0
      work = 0
      do r = 1, this%nrun
         corr(1) = corr(1) + this%rsum(1, r)
         corr(3) = corr(3) + this%rsum(2, r)
         corr(4) = corr(4) + this%rsum(3, r)
         work = work + this%rsum(4, r)
      end do
   end subroutine stepwork_sums

   !> du_f . K du_f and du_f . M du_f of the last estimate, blocks in order.
   subroutine stepwork_estimate(this, num, den)
      class(stepwork_t), intent(in) :: this
      real(wp), intent(out) :: num, den
      integer :: b
      num = 0
      den = 0
      do b = 1, this%nblock
         num = num + this%rpart(1, b)
         den = den + this%rpart(2, b)
      end do
   end subroutine stepwork_estimate

   !> At the listed dofs of one run, right after the sweep: keep v* and u~, give v^(n-1/2) back.
   subroutine keep_run(run, v, w, vold, vstar, wstar)
      integer, intent(in) :: run(3)
      real(wp), intent(inout) :: v(*)
      real(wp), intent(in) :: w(*), vold(*)
      real(wp), intent(inout) :: vstar(*), wstar(*)
      integer :: d, q, i
      d = run(1) - 1
      q = run(2) - 1
      if (run(3) == 1) then   ! (the loop below is three calls of memcpy)
         vstar(q + 1) = v(d + 1)
         wstar(q + 1) = w(d + 1)
         v(d + 1) = vold(q + 1)
         return
      end if
      !$omp simd
      do i = 1, run(3)
         vstar(q + i) = v(d + i)
         wstar(q + i) = w(d + i)
         v(d + i) = vold(q + i)
      end do
   end subroutine keep_run

   !> At the listed dofs of one run, once u^(n+1) is final there: v^(n+1/2) = (u^(n+1) - u^n)/dt,
   !> and the changes of the sweep's sums (m v^2, u . K u, m dv^2) from v* and u~ to these values
   !> (a^2 - b^2 = (a - b)(a + b); the damping sum is not needed: contact2d_explicit add_energies),
   !> and at the prescribed dofs (pres = 1) the work of the reactions, inertial and damping parts
   !> included, on the centred increment dt vbar = (u^(n+1) - u^(n-1))/2; s = these four sums.
   !> vold becomes v^(n+1/2), the next step's v^(n-1/2).
   subroutine correct_run(run, pres, mass, u, unew, fint, dt, alpha, vold, vstar, wstar, v, s)
      integer, intent(in) :: run(3)
      real(wp), intent(in) :: pres(*), mass(*), u(*), unew(*), fint(*), dt, alpha, vstar(*), wstar(*)
      real(wp), intent(inout) :: v(*), vold(*)
      real(wp), intent(out) :: s(4)
      integer :: i, q, d, q0, d0
      real(wp) :: vo, vs, vn, md, c1, c3, c4, work, vbar, acc, f
      d0 = run(1) - 1
      q0 = run(2) - 1
      if (run(3) == 1) then   ! (one dof: no vector set-up and reduction)
         q = q0 + 1
         d = d0 + 1
         vo = vold(q)
         vs = vstar(q)
         vn = (unew(d) - u(d))/dt
         vbar = 0.5_wp*(vn + vo)
         acc = (vn - vo)/dt
         f = mass(q)*(acc + alpha*vbar) + fint(d)
         md = mass(q)*(vn - vs)
         s(1) = md*(vn + vs)
         s(2) = (unew(d) - wstar(q))*fint(d)
         s(3) = md*((vn + vs) - 2*vo)
         s(4) = pres(q)*(f*dt*vbar)
         v(d) = vn
         vold(q) = vn
         return
      end if
      c1 = 0
      c3 = 0
      c4 = 0
      work = 0
      !$omp simd private(q, d, vo, vs, vn, md, vbar, acc, f) reduction(+:c1, c3, c4, work)
      do i = 1, run(3)
         q = q0 + i
         d = d0 + i
         vo = vold(q)
         vs = vstar(q)
         vn = (unew(d) - u(d))/dt
         vbar = 0.5_wp*(vn + vo)
         acc = (vn - vo)/dt
         f = mass(q)*(acc + alpha*vbar) + fint(d)
         work = work + pres(q)*(f*dt*vbar)
         md = mass(q)*(vn - vs)
         c1 = c1 + md*(vn + vs)
         c3 = c3 + (unew(d) - wstar(q))*fint(d)
         c4 = c4 + md*((vn + vs) - 2*vo)
         v(d) = vn
         vold(q) = vn   ! v^(n-1/2) of the next step
      end do
      s(1) = c1
      s(2) = c3
      s(3) = c4
      s(4) = work
   end subroutine correct_run

   !> K du_f = (f_int - f_mark) - K du_p at the dofs of pd in segment j, stored as -K du_f in
   !> f_mark: the element terms -K_e du_p of the segment's elements first (slots of fe; only
   !> the outputs at the segment's nodes, each a sum over the element's dofs in order, as the
   !> inlined matmul of stiffness_apply_elements forms it), then per dof the same subtractions
   !> in the same order as stiffness_apply_elements.
   subroutine pres_terms(this, j, f)
      type(stepwork_t), intent(inout) :: this
      integer, intent(in) :: j
      real(wp), intent(in) :: f(*)
      real(wp) :: ue(8), sgn, x
      integer :: s, k, a, q, d, c, n, e, i, b
      sgn = -1
      do s = this%seg_sl(j) + 1, this%seg_sl(j + 1)
         k = this%sl_el(s)
         do a = 1, 4
            n = this%pel_conn(a, k)
            ue(2*a - 1) = this%dup(2*n - 1)
            ue(2*a) = this%dup(2*n)
         end do
         e = this%pel_shape(k)
         do a = 1, 4
            if (seg_of(this%seglen, 2*this%pel_conn(a, k)) /= j) cycle
            do i = 2*a - 1, 2*a
               x = 0
               do b = 1, 8
                  x = x + this%ke(i, b, e)*ue(b)
               end do
               this%fe(i, s) = sgn*x
            end do
         end do
      end do
      do q = this%seg_pd(j) + 1, this%seg_pd(j + 1)
         d = this%pd(q)
         x = f(d) - this%f_mark(d)
         do c = this%pd_ptr(q), this%pd_ptr(q + 1) - 1
            x = x + this%fe(this%pd_loc(c), this%pd_slot(c))
         end do
         this%f_mark(d) = -x
      end do
   end subroutine pres_terms

   !> Block b: sum of du_f kdu and of m du_f^2 with du_f = (u - u_mark) |mask| and
   !> kdu = max(mask, 0) f_int - f_mark: f_int - f_mark where mask = 1 (exact: 1 f_int = f_int),
   !> -f_mark where mask = -1 (exact: 0 f_int - f_mark, also if contracted to an FMA), du_f = 0
   !> where mask = 0; then u_mark = u, f_mark = f_int.
   subroutine rayleigh_sums(b, ndof, u, fint, mask, mdof, u_mark, f_mark, part)
      integer, intent(in) :: b, ndof
      real(wp), intent(in) :: u(*), fint(*), mask(*), mdof(*)
      real(wp), intent(inout) :: u_mark(*), f_mark(*)
      real(wp), intent(out) :: part(2)
      integer :: i
      real(wp) :: du, num, den
      num = 0
      den = 0
      !$omp simd private(du) reduction(+:num, den)
      do i = (b - 1)*rayleigh_block + 1, min(b*rayleigh_block, ndof)
         du = (u(i) - u_mark(i))*abs(mask(i))
         num = num + du*(max(mask(i), 0.0_wp)*fint(i) - f_mark(i))
         den = den + mdof(i)*du*du
         u_mark(i) = u(i)
         f_mark(i) = fint(i)
      end do
      part(1) = num
      part(2) = den
   end subroutine rayleigh_sums
end module contact2d_stepwork
