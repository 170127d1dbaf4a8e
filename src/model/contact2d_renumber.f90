!> Node renumbering of a general (Gmsh) mesh at reading (docs/performance.md "The
!> general (Gmsh) path"): reverse Cuthill-McKee on the graph of nodes that share an element, so
!> that the block rows of K (row r is node r, contact2d_rows) read columns close to their own
!> row. Gmsh numbers the nodes of each refinement after all the older ones, so without it an
!> element's nodes lie thousands of ids apart on a refined mesh.
!>
!> Then group_order makes the nodes 4k - 3 .. 4k the nodes of one element where it can, as the
!> block rows of contact2d_rows are swept by such groups (the rows of an element's four nodes on
!> a regular mesh have 16 distinct columns: 16 loads of u for 36 blocks, not 36).
!>
!> The order is a function of the connectivity alone (ties broken by the old number), so it is
!> the same on every run and every thread count.
module contact2d_renumber
   use contact2d_mesh, only: node_elements
   implicit none
   private
   public :: rcm_order, group_order

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

   !> Groups of four of an order: perm (perm(k) = old number of the node at place k, e.g. from
   !> rcm_order) is reordered so that places 4k - 3 .. 4k hold the nodes of one element, in the
   !> element's cyclic order, where it can. Along the order, each node not yet in a group takes,
   !> of its elements whose nodes are all free, the one whose nodes lie in the fewest such
   !> elements (then the first); the group takes the place of its first node. The nodes left
   !> over are matched along element edges the same way (the neighbour with the fewest free
   !> neighbours left, then the earliest); a node with no free neighbour waits for the next such
   !> node and the two make a pair; two consecutive pairs make a group; a last incomplete group
   !> goes at the end. An element's nodes start at its first edge on the mesh's boundary, if
   !> any, so that both nodes of that edge are side by side (the prescribed and contact dofs of
   !> contact2d_explicit then form fewer, longer runs). A grouped element's nodes stay within
   !> about the order's bandwidth of their places; a waiting pair or node does not: it joins the
   !> next left-over one wherever that is (on the Hertz cylinder the bandwidth grows from 120 to
   !> 494 at level 1 and from 240 to 1740 at level 2, and such groups' blocks that share no
   !> column slot go to contact2d_rows' remainder: docs/performance.md "The general (Gmsh)
   !> path"). Elements have four distinct nodes (contact2d_gmsh refuses others).
   subroutine group_order(conn, nnode, perm)
      integer, intent(in) :: conn(:, :)   !< (4, nel) element nodes
      integer, intent(in) :: nnode
      integer, intent(inout) :: perm(:)   !< (nnode) the order in, the grouped order out
      integer, allocatable :: adj_start(:), adj_elem(:), nfe(:), quad(:), pos(:), out(:)
      integer, allocatable :: estart(:), enbr(:), nfree(:), mate(:)
      logical, allocatable :: efree(:), placed(:)
      integer :: n, k, e, a, m, i, j, best, bscore, score, nfill, first, side, t, e2, nv
      integer :: pend_pair(2), npend, pend_one
      call node_elements(conn, nnode, adj_start, adj_elem)
      allocate (nfe(nnode), quad(nnode), pos(nnode), out(nnode), efree(size(conn, 2)), placed(nnode))
      nv = size(conn, 1)
      do k = 1, nnode
         pos(perm(k)) = k
      end do
      ! elements whose nodes are all free, and how many of them hold each node
      efree = .true.
      do n = 1, nnode
         nfe(n) = adj_start(n + 1) - adj_start(n)
      end do
      quad = 0
      do k = 1, nnode
         i = perm(k)
         if (quad(i) /= 0) cycle
         best = 0
         bscore = 0
         do t = adj_start(i), adj_start(i + 1) - 1
            e = adj_elem(t)
            if (.not. efree(e)) cycle
            score = sum(nfe(conn(:, e)))
            if (best == 0 .or. score < bscore) then
               best = e
               bscore = score
            end if
         end do
         if (best == 0) cycle
         do a = 1, nv
            m = conn(a, best)
            quad(m) = best
            do t = adj_start(m), adj_start(m + 1) - 1
               e2 = adj_elem(t)
               if (.not. efree(e2)) cycle
               efree(e2) = .false.
               nfe(conn(:, e2)) = nfe(conn(:, e2)) - 1
            end do
         end do
      end do
      ! the nodes left over: edge neighbours among them, matched
      allocate (estart(nnode + 1), enbr(2*size(adj_elem)), nfree(nnode), mate(nnode))
      nfill = 0
      do n = 1, nnode
         estart(n) = nfill + 1
         first = nfill
         if (quad(n) == 0) then
            do t = adj_start(n), adj_start(n + 1) - 1
               e = adj_elem(t)
               do a = 1, nv
                  if (conn(a, e) /= n) cycle
                  do side = 1, 3, 2
                     m = conn(mod(a - 1 + side, nv) + 1, e)
                     if (m == n .or. quad(m) /= 0 .or. any(enbr(first + 1:nfill) == m)) cycle
                     nfill = nfill + 1
                     enbr(nfill) = m
                  end do
               end do
            end do
         end if
         nfree(n) = nfill - first
      end do
      estart(nnode + 1) = nfill + 1
      mate = 0
      do k = 1, nnode
         i = perm(k)
         if (quad(i) /= 0 .or. mate(i) /= 0) cycle
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
         nfree(enbr(estart(i):estart(i + 1) - 1)) = nfree(enbr(estart(i):estart(i + 1) - 1)) - 1
         nfree(enbr(estart(best):estart(best + 1) - 1)) = nfree(enbr(estart(best):estart(best + 1) - 1)) - 1
      end do
      ! the groups in the order of their first nodes
      placed = .false.
      n = 0
      npend = 0
      pend_one = 0
      do k = 1, nnode
         i = perm(k)
         if (placed(i)) cycle
         if (quad(i) /= 0) then
            ! starting at the first edge on the mesh's boundary, if any (its two nodes' dofs
            ! then lie side by side: longer runs of prescribed and contact dofs)
            e = quad(i)
            side = 1
            do a = 1, nv
               m = conn(mod(a, nv) + 1, e)
               ! the elements of the edge's first node that also hold its second
               t = count([(any(conn(:, adj_elem(j)) == m), j=adj_start(conn(a, e)), &
                           adj_start(conn(a, e) + 1) - 1)])
               if (t == 1) then
                  side = a
                  exit
               end if
            end do
            out(n + 1:n + nv) = cshift(conn(:, e), side - 1)
            placed(conn(:, quad(i))) = .true.
            n = n + nv
            cycle
         end if
         placed(i) = .true.
         if (mate(i) /= 0) then
            j = mate(i)
            placed(j) = .true.
         else if (pend_one == 0) then
            pend_one = i
            cycle
         else
            j = i
            i = pend_one
            pend_one = 0
         end if
         ! a pair (i, j): with the pending one, a group
         if (npend == 0) then
            pend_pair = [i, j]
            npend = 2
         else
            out(n + 1:n + 4) = [pend_pair, i, j]
            n = n + 4
            npend = 0
         end if
      end do
      if (npend /= 0) then
         out(n + 1:n + 2) = pend_pair
         n = n + 2
      end if
      if (pend_one /= 0) then
         n = n + 1
         out(n) = pend_one
      end if
      perm = out
   end subroutine group_order

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
