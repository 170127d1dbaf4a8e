!> Node renumbering of a general (Gmsh) mesh at reading (issue 13, docs/performance.md "The
!> general (Gmsh) path"): reverse Cuthill-McKee on the graph of nodes that share an element, so
!> that the block rows of K (row r is node r, contact2d_rows) read columns close to their own
!> row. Gmsh numbers the nodes of each refinement after all the older ones, so without it an
!> element's nodes lie thousands of ids apart on a refined mesh.
!>
!> Then pair_order makes the nodes 2k - 1 and 2k two ends of one element edge where it can, as
!> the block rows of contact2d_rows are swept by such pairs (two rows of nodes that share an edge
!> have 6 of their 9 columns in common: 12 loads of u for 18 blocks, not 18).
!>
!> The order is a function of the connectivity alone (ties broken by the old number), so it is
!> the same on every run and every thread count.
module contact2d_renumber
   use contact2d_mesh, only: node_elements
   implicit none
   private
   public :: rcm_order, pair_order

contains

   !> perm(k) = old number of the node that becomes node k (reverse Cuthill-McKee; each
   !> connected part from a pseudo-peripheral node of least degree, neighbours by increasing
   !> degree, then old number).
   subroutine rcm_order(conn, nnode, perm)
      integer, intent(in) :: conn(:, :)   !< (4, nel) element nodes
      integer, intent(in) :: nnode
      integer, allocatable, intent(out) :: perm(:)
      integer, allocatable :: adj_start(:), adj_elem(:), nstart(:), nbr(:), deg(:), level(:), tmp(:)
      logical, allocatable :: seen(:)
      integer :: n, k, e, a, m, nfill, first, head, tail, start, i, j, t, depth, new_depth
      ! node graph: the distinct other nodes of the elements of each node, by increasing number
      call node_elements(conn, nnode, adj_start, adj_elem)
      allocate (nstart(nnode + 1), deg(nnode), seen(nnode), tmp(4*(maxval(adj_start(2:) - adj_start(:nnode)) + 1)))
      allocate (nbr(3*size(adj_elem)))
      nfill = 0
      seen = .false.
      do n = 1, nnode
         nstart(n) = nfill + 1
         first = nfill
         do k = adj_start(n), adj_start(n + 1) - 1
            e = adj_elem(k)
            do a = 1, size(conn, 1)
               m = conn(a, e)
               if (m == n .or. seen(m)) cycle
               seen(m) = .true.
               nfill = nfill + 1
               nbr(nfill) = m
            end do
         end do
         seen(nbr(first + 1:nfill)) = .false.
         call sort_ints(nbr(first + 1:nfill))
         deg(n) = nfill - first
      end do
      nstart(nnode + 1) = nfill + 1
      ! Cuthill-McKee, one connected part after another
      allocate (perm(nnode), level(nnode))
      seen = .false.
      tail = 0
      do
         ! the unnumbered node of least degree (lowest number on ties)
         start = 0
         do n = 1, nnode
            if (seen(n)) cycle
            if (start == 0) then
               start = n
            else if (deg(n) < deg(start)) then
               start = n
            end if
         end do
         if (start == 0) exit
         ! pseudo-peripheral: move to a node of least degree in the last level while the depth grows
         depth = -1
         do
            call bfs_levels(start, nstart, nbr, seen, level, new_depth, i)
            if (new_depth <= depth) exit
            depth = new_depth
            start = i
         end do
         ! breadth-first numbering from start, neighbours by increasing degree
         head = tail + 1
         tail = tail + 1
         perm(tail) = start
         seen(start) = .true.
         do while (head <= tail)
            n = perm(head)
            head = head + 1
            t = 0
            do k = nstart(n), nstart(n + 1) - 1
               m = nbr(k)
               if (seen(m)) cycle
               seen(m) = .true.
               t = t + 1
               tmp(t) = m
            end do
            ! insertion sort by (degree, number): short lists
            do i = 2, t
               m = tmp(i)
               j = i - 1
               do while (j >= 1)
                  if (deg(tmp(j)) < deg(m) .or. (deg(tmp(j)) == deg(m) .and. tmp(j) < m)) exit
                  tmp(j + 1) = tmp(j)
                  j = j - 1
               end do
               tmp(j + 1) = m
            end do
            perm(tail + 1:tail + t) = tmp(1:t)
            tail = tail + t
         end do
      end do
      perm = perm(nnode:1:-1)
   end subroutine rcm_order

   !> Pairs of an order: perm (perm(k) = old number of the node at place k, e.g. from rcm_order)
   !> is reordered so that places 2k - 1 and 2k hold two ends of one element edge where it can.
   !> A greedy matching along the order: each node not yet matched takes, among its edge
   !> neighbours not yet matched, the one with the fewest such neighbours left (then the one
   !> earliest in the order), and the pair takes the place of its first node; the nodes left
   !> without a partner are paired with each other in order (a last odd one goes at the end).
   !> Every node keeps its place to within a few places of the matching, so the locality of the
   !> order stays.
   subroutine pair_order(conn, nnode, perm)
      integer, intent(in) :: conn(:, :)   !< (4, nel) element nodes
      integer, intent(in) :: nnode
      integer, intent(inout) :: perm(:)   !< (nnode) the order in, the paired order out
      integer, allocatable :: adj_start(:), adj_elem(:), estart(:), enbr(:), nfree(:), mate(:), pos(:), out(:)
      logical, allocatable :: placed(:)
      integer :: n, k, e, a, m, i, j, best, nfill, first, pending, t, side
      call node_elements(conn, nnode, adj_start, adj_elem)
      ! edge neighbours of each node (distinct)
      allocate (estart(nnode + 1), enbr(2*size(adj_elem)), nfree(nnode), mate(nnode), pos(nnode), out(nnode))
      allocate (placed(nnode))
      nfill = 0
      do n = 1, nnode
         estart(n) = nfill + 1
         first = nfill
         do k = adj_start(n), adj_start(n + 1) - 1
            e = adj_elem(k)
            do a = 1, size(conn, 1)
               if (conn(a, e) /= n) cycle
               do side = 1, 3, 2
                  m = conn(mod(a - 1 + side, size(conn, 1)) + 1, e)
                  if (m == n .or. any(enbr(first + 1:nfill) == m)) cycle
                  nfill = nfill + 1
                  enbr(nfill) = m
               end do
            end do
         end do
         nfree(n) = nfill - first
      end do
      estart(nnode + 1) = nfill + 1
      do k = 1, nnode
         pos(perm(k)) = k
      end do
      mate = 0
      do k = 1, nnode
         i = perm(k)
         if (mate(i) /= 0) cycle
         best = 0
         do t = estart(i), estart(i + 1) - 1
            j = enbr(t)
            if (mate(j) /= 0) cycle
            if (best == 0) then
               best = j
            else if (nfree(j) < nfree(best) .or. (nfree(j) == nfree(best) .and. pos(j) < pos(best))) then
               best = j
            end if
         end do
         if (best == 0) cycle
         mate(i) = best
         mate(best) = i
         do t = estart(i), estart(i + 1) - 1
            nfree(enbr(t)) = nfree(enbr(t)) - 1
         end do
         do t = estart(best), estart(best + 1) - 1
            nfree(enbr(t)) = nfree(enbr(t)) - 1
         end do
      end do
      placed = .false.
      n = 0
      pending = 0
      do k = 1, nnode
         i = perm(k)
         if (placed(i)) cycle
         placed(i) = .true.
         if (mate(i) /= 0) then
            placed(mate(i)) = .true.
            out(n + 1) = i
            out(n + 2) = mate(i)
            n = n + 2
         else if (pending == 0) then
            pending = i
         else
            out(n + 1) = pending
            out(n + 2) = i
            n = n + 2
            pending = 0
         end if
      end do
      if (pending /= 0) then
         n = n + 1
         out(n) = pending
      end if
      perm = out
   end subroutine pair_order

   !> Breadth-first levels of the unnumbered part (seen = .false.) holding start: depth is the
   !> last level's index, last a node of least degree in it (lowest number on ties).
   subroutine bfs_levels(start, nstart, nbr, seen, level, depth, last)
      integer, intent(in) :: start, nstart(:), nbr(:)
      logical, intent(in) :: seen(:)
      integer, intent(inout) :: level(:)
      integer, intent(out) :: depth, last
      integer, allocatable :: queue(:)
      integer :: head, tail, n, m, k
      allocate (queue(size(seen)))
      level = -1
      head = 1
      tail = 1
      queue(1) = start
      level(start) = 0
      do while (head <= tail)
         n = queue(head)
         head = head + 1
         do k = nstart(n), nstart(n + 1) - 1
            m = nbr(k)
            if (seen(m) .or. level(m) >= 0) cycle
            level(m) = level(n) + 1
            tail = tail + 1
            queue(tail) = m
         end do
      end do
      depth = level(queue(tail))
      last = queue(tail)
      do k = tail, 1, -1
         n = queue(k)
         if (level(n) < depth) exit
         if (nstart(n + 1) - nstart(n) < nstart(last + 1) - nstart(last) .or. &
             (nstart(n + 1) - nstart(n) == nstart(last + 1) - nstart(last) .and. n < last)) last = n
      end do
   end subroutine bfs_levels

   !> Ascending insertion sort (short lists).
   pure subroutine sort_ints(a)
      integer, intent(inout) :: a(:)
      integer :: i, j, x
      do i = 2, size(a)
         x = a(i)
         j = i - 1
         do while (j >= 1)
            if (a(j) <= x) exit
            a(j + 1) = a(j)
            j = j - 1
         end do
         a(j + 1) = x
      end do
   end subroutine sort_ints
end module contact2d_renumber
