!> Q1 meshes: the structured rectangle mesher and boundary selections (SPEC sections 2 and 8).
!>
!> Structured numbering (SPEC section 8): node (i, j), 0 <= i <= nx, 0 <= j <= ny, has id
!> i + (nx+1) j + 1; element (i, j) has id i + nx j + 1 and nodes counter-clockwise from its
!> bottom-left corner.
module contact2d_mesh
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   implicit none
   private
   public :: mesh_t, side_names, node_elements, mesh_max_elements

   !> The most elements this program is meant for: the built-in rectangle's nx ny 4^level and a
   !> Gmsh mesh's element count times 4^level (each refinement splits a quadrilateral in four) are
   !> refused above it before any mesh is made (docs/deck.md, docs/geometry.md).
   real(wp), parameter :: mesh_max_elements = 5.0e7_wp

   !> Names of the four sides of the bounding box, in the order used by side ids 1..4.
   character(len=6), parameter :: side_names(4) = [character(len=6) :: 'bottom', 'right', 'top', 'left']

   !> An unstructured list of Q1 elements; nx, ny > 0 when it came from the structured mesher.
   type :: mesh_t
      integer :: nnode = 0                !< number of nodes
      integer :: nel = 0                  !< number of elements
      integer :: nx = 0, ny = 0           !< structured divisions (0 if not structured)
      real(wp), allocatable :: x(:, :)    !< coordinates (2, nnode) [mm]
      integer, allocatable :: conn(:, :)  !< connectivity (4, nel), 1-based, counter-clockwise
      real(wp) :: bbox(2, 2) = 0          !< (min, max) of x in column 1 and of y in column 2 [mm]
      !> id of each element in the mesh file (Gmsh tag), for messages; absent: its index
      integer, allocatable :: elem_id(:)
      !> named boundary groups (Gmsh physical curves): names, and their edges (2, nseg) as
      !> a list per group: edges of group g are gseg(:, gstart(g):gstart(g+1)-1)
      character(len=64), allocatable :: group_name(:)
      integer, allocatable :: gstart(:)
      integer, allocatable :: gseg(:, :)
      logical, allocatable :: gboundary(:)   !< the group edge belongs to one element only
      !> number of each node in the mesh file's order (Gmsh: 1..n in increasing tag) when the
      !> nodes were renumbered at reading (renumber); absent: the same as its id. Outputs are
      !> written in the file's order (docs/output.md).
      integer, allocatable :: file_node(:)
      !> named element groups (Gmsh physical surfaces): names, and their elements as a list per
      !> surface: the elements of surface s are selem(sstart(s):sstart(s+1)-1) (indices into conn);
      !> not allocated for the built-in rectangle
      character(len=64), allocatable :: surface_name(:)
      integer, allocatable :: sstart(:)
      integer, allocatable :: selem(:)
   contains
      procedure :: init_rectangle => mesh_init_rectangle
      procedure :: init_arrays => mesh_init_arrays
      procedure :: select_nodes => mesh_select_nodes
      procedure :: select_segments => mesh_select_segments
      procedure :: element_coordinates => mesh_element_coordinates
      procedure :: tolerance => mesh_tolerance
      procedure :: set_groups => mesh_set_groups
      procedure :: group_index => mesh_group_index
      procedure :: group_list => mesh_group_list
      procedure :: surface_index => mesh_surface_index
      procedure :: surface_list => mesh_surface_list
      procedure :: select_group => mesh_select_group
      procedure :: group_chain => mesh_group_chain
      procedure :: orient => mesh_orient
      procedure :: id_of => mesh_id_of
      procedure :: renumber => mesh_renumber
      procedure :: file_id => mesh_file_id
      procedure :: file_order => mesh_file_order
   end type mesh_t

contains

   !> Structured mesh of the rectangle [0, lx] x [0, ly] with nx x ny equal elements.
   subroutine mesh_init_rectangle(this, lx, ly, nx, ny)
      class(mesh_t), intent(inout) :: this
      real(wp), intent(in) :: lx, ly      !< sides [mm]
      integer, intent(in) :: nx, ny       !< element divisions, >= 1
      integer :: i, j, e, n

      this%nx = nx
      this%ny = ny
      this%nnode = (nx + 1)*(ny + 1)
      this%nel = nx*ny
      if (allocated(this%x)) deallocate (this%x)
      if (allocated(this%conn)) deallocate (this%conn)
      allocate (this%x(2, this%nnode), this%conn(4, this%nel))
      do j = 0, ny
         do i = 0, nx
            n = i + (nx + 1)*j + 1
            ! i*lx/nx rather than i*h keeps the far side exactly at lx
            this%x(1, n) = lx*real(i, wp)/real(nx, wp)
            this%x(2, n) = ly*real(j, wp)/real(ny, wp)
         end do
      end do
      do j = 0, ny - 1
         do i = 0, nx - 1
            e = i + nx*j + 1
            n = i + (nx + 1)*j + 1
            this%conn(:, e) = [n, n + 1, n + nx + 2, n + nx + 1]
         end do
      end do
      call set_bbox(this)
   end subroutine mesh_init_rectangle

   !> Mesh from given arrays (any Q1 mesh; used by tests and by future mesh readers).
   subroutine mesh_init_arrays(this, x, conn)
      class(mesh_t), intent(inout) :: this
      real(wp), intent(in) :: x(:, :)     !< coordinates (2, nnode) [mm]
      integer, intent(in) :: conn(:, :)   !< connectivity (4, nel), counter-clockwise
      this%nx = 0
      this%ny = 0
      this%nnode = size(x, 2)
      this%nel = size(conn, 2)
      this%x = x
      this%conn = conn
      call set_bbox(this)
   end subroutine mesh_init_arrays

   subroutine set_bbox(this)
      type(mesh_t), intent(inout) :: this
      this%bbox(1, :) = minval(this%x, dim=2)
      this%bbox(2, :) = maxval(this%x, dim=2)
   end subroutine set_bbox

   !> Geometric tolerance for selections: 1e-9 of the larger side [mm].
   pure real(wp) function mesh_tolerance(this) result(tol)
      class(mesh_t), intent(in) :: this
      tol = 1.0e-9_wp*max(this%bbox(2, 1) - this%bbox(1, 1), this%bbox(2, 2) - this%bbox(1, 2))
   end function mesh_tolerance

   !> Coordinates of the four nodes of element e.
   pure function mesh_element_coordinates(this, e) result(xe)
      class(mesh_t), intent(in) :: this
      integer, intent(in) :: e
      real(wp) :: xe(2, 4)
      xe = this%x(:, this%conn(:, e))
   end function mesh_element_coordinates

   !> Nodes on a side of the bounding box ('bottom', 'right', 'top', 'left') whose coordinates lie
   !> in [range(1), range(2)] x [range(3), range(4)] (closed, with the mesh tolerance), ordered
   !> counter-clockwise along the boundary (x increasing on bottom, y increasing on right, ...).
   subroutine mesh_select_nodes(this, side, range, nodes)
      class(mesh_t), intent(in) :: this
      integer, intent(in) :: side                 !< 1 bottom, 2 right, 3 top, 4 left
      real(wp), intent(in) :: range(4)            !< xmin, xmax, ymin, ymax [mm]
      integer, allocatable, intent(out) :: nodes(:)
      logical :: mask(this%nnode)
      real(wp) :: key(this%nnode), tol
      integer :: i, j, t

      tol = this%tolerance()
      mask = on_side(this, side, tol) &
             .and. this%x(1, :) >= range(1) - tol .and. this%x(1, :) <= range(2) + tol &
             .and. this%x(2, :) >= range(3) - tol .and. this%x(2, :) <= range(4) + tol
      nodes = pack([(i, i=1, this%nnode)], mask)
      select case (side)
      case (1); key = this%x(1, :)
      case (2); key = this%x(2, :)
      case (3); key = -this%x(1, :)
      case default; key = -this%x(2, :)
      end select
      ! insertion sort by the counter-clockwise key (selections are short)
      do i = 2, size(nodes)
         t = nodes(i)
         j = i - 1
         do while (j >= 1)
            if (key(nodes(j)) <= key(t)) exit
            nodes(j + 1) = nodes(j)
            j = j - 1
         end do
         nodes(j + 1) = t
      end do
   end subroutine mesh_select_nodes

   pure function on_side(this, side, tol) result(mask)
      type(mesh_t), intent(in) :: this
      integer, intent(in) :: side
      real(wp), intent(in) :: tol
      logical :: mask(this%nnode)
      select case (side)
      case (1); mask = abs(this%x(2, :) - this%bbox(1, 2)) <= tol
      case (2); mask = abs(this%x(1, :) - this%bbox(2, 1)) <= tol
      case (3); mask = abs(this%x(2, :) - this%bbox(2, 2)) <= tol
      case default; mask = abs(this%x(1, :) - this%bbox(1, 1)) <= tol
      end select
   end function on_side

   !> Element edges whose two nodes are both in the selection `nodes` (a side selection), as
   !> (2, nseg) node pairs in the element's counter-clockwise order.
   subroutine mesh_select_segments(this, nodes, seg)
      class(mesh_t), intent(in) :: this
      integer, intent(in) :: nodes(:)
      integer, allocatable, intent(out) :: seg(:, :)
      logical :: sel(this%nnode)
      integer :: e, a, b, n
      integer, allocatable :: tmp(:, :)

      allocate (tmp(2, 4*this%nel))
      sel = .false.
      sel(nodes) = .true.
      n = 0
      do e = 1, this%nel
         do a = 1, 4
            b = mod(a, 4) + 1
            if (sel(this%conn(a, e)) .and. sel(this%conn(b, e))) then
               n = n + 1
               tmp(:, n) = [this%conn(a, e), this%conn(b, e)]
            end if
         end do
      end do
      seg = tmp(:, 1:n)
   end subroutine mesh_select_segments
   !> Named boundary groups: names(g) holds the edges seg(:, gstart(g):gstart(g+1)-1).
   subroutine mesh_set_groups(this, names, gstart, seg)
      class(mesh_t), intent(inout) :: this
      character(len=*), intent(in) :: names(:)
      integer, intent(in) :: gstart(:), seg(:, :)
      allocate (this%group_name(size(names)))
      this%group_name = names
      this%gstart = gstart
      this%gseg = seg
   end subroutine mesh_set_groups

   !> Index of the group called `name` (exact match), 0 if none.
   pure integer function mesh_group_index(this, name) result(g)
      class(mesh_t), intent(in) :: this
      character(len=*), intent(in) :: name
      integer :: k
      g = 0
      if (.not. allocated(this%group_name)) return
      do k = 1, size(this%group_name)
         if (trim(this%group_name(k)) == trim(name)) then
            g = k
            return
         end if
      end do
   end function mesh_group_index

   !> The group names as "'a', 'b'" (or 'none' when the mesh has none).
   function mesh_group_list(this) result(s)
      class(mesh_t), intent(in) :: this
      character(len=:), allocatable :: s
      integer :: k
      s = ''
      if (allocated(this%group_name)) then
         do k = 1, size(this%group_name)
            if (k > 1) s = s//', '
            s = s//"'"//trim(this%group_name(k))//"'"
         end do
      end if
      if (len(s) == 0) s = 'none (the mesh has no physical curve)'
   end function mesh_group_list

   !> Index of the physical surface called `name` (exact match), 0 if none.
   pure integer function mesh_surface_index(this, name) result(s)
      class(mesh_t), intent(in) :: this
      character(len=*), intent(in) :: name
      integer :: k
      s = 0
      if (.not. allocated(this%surface_name)) return
      do k = 1, size(this%surface_name)
         if (trim(this%surface_name(k)) == trim(name)) then
            s = k
            return
         end if
      end do
   end function mesh_surface_index

   !> The physical surface names as "'a', 'b'" (or 'none' when the mesh has none).
   function mesh_surface_list(this) result(s)
      class(mesh_t), intent(in) :: this
      character(len=:), allocatable :: s
      integer :: k
      s = ''
      if (allocated(this%surface_name)) then
         do k = 1, size(this%surface_name)
            if (k > 1) s = s//', '
            s = s//"'"//trim(this%surface_name(k))//"'"
         end do
      end if
      if (len(s) == 0) s = 'none (the mesh has no physical surface)'
   end function mesh_surface_list

   !> Id of element e in the mesh file (its index when the mesh was not read from a file).
   pure integer function mesh_id_of(this, e) result(id)
      class(mesh_t), intent(in) :: this
      integer, intent(in) :: e
      id = e
      if (allocated(this%elem_id)) id = this%elem_id(e)
   end function mesh_id_of

   !> Edges of group g with both nodes in [range(1), range(2)] x [range(3), range(4)] (closed, with
   !> the mesh tolerance), oriented as their element runs counter-clockwise (the body on the left),
   !> and the distinct nodes of the group inside the range, in increasing id.
   subroutine mesh_select_group(this, g, range, nodes, seg, interior)
      class(mesh_t), intent(in) :: this
      integer, intent(in) :: g
      real(wp), intent(in) :: range(4)
      integer, allocatable, intent(out) :: nodes(:), seg(:, :)
      !> number of selected edges that are not boundary edges (held by two elements)
      integer, intent(out), optional :: interior
      logical :: inside(this%nnode), mark(this%nnode)
      logical, allocatable :: keep(:)
      real(wp) :: tol
      integer :: s, i
      tol = this%tolerance()
      inside = this%x(1, :) >= range(1) - tol .and. this%x(1, :) <= range(2) + tol &
               .and. this%x(2, :) >= range(3) - tol .and. this%x(2, :) <= range(4) + tol
      associate (gs => this%gseg(:, this%gstart(g):this%gstart(g + 1) - 1))
         allocate (keep(size(gs, 2)))
         do s = 1, size(gs, 2)
            keep(s) = inside(gs(1, s)) .and. inside(gs(2, s))
         end do
         allocate (seg(2, count(keep)))
         seg(1, :) = pack(gs(1, :), keep)
         seg(2, :) = pack(gs(2, :), keep)
         if (present(interior)) then
            interior = 0
            if (allocated(this%gboundary)) &
               interior = count(keep .and. .not. this%gboundary(this%gstart(g):this%gstart(g + 1) - 1))
         end if
      end associate
      ! the nodes: every node of the group inside the range (a single node is a selection too)
      mark = .false.
      associate (gs => this%gseg(:, this%gstart(g):this%gstart(g + 1) - 1))
         mark(pack(gs, .true.)) = .true.
      end associate
      nodes = pack([(i, i=1, this%nnode)], mark .and. inside)
   end subroutine mesh_select_group

   !> The edges of group g within the range as one chain of boundary edges, nodes in order
   !> along the boundary: counter-clockwise (the body on the left) or, with reverse, clockwise.
   !> stat /= 0 with a message if the selection is not one open chain of boundary edges.
   subroutine mesh_group_chain(this, g, range, reverse, nodes, stat, errmsg)
      class(mesh_t), intent(in) :: this
      integer, intent(in) :: g
      real(wp), intent(in) :: range(4)
      logical, intent(in) :: reverse
      integer, allocatable, intent(out) :: nodes(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer, allocatable :: sel(:), seg(:, :), nxt(:), nin(:)
      integer :: s, n, start, k, interior
      stat = 1
      call this%select_group(g, range, sel, seg, interior)
      if (size(seg, 2) == 0) then
         errmsg = 'holds no element edge within the range'
         return
      end if
      if (interior > 0) then
         errmsg = 'is not one chain of boundary edges: '//str(interior)//' of its edges lie inside the mesh '// &
                  '(held by two elements)'
         return
      end if
      allocate (nxt(this%nnode), nin(this%nnode))
      nxt = 0
      nin = 0
      do s = 1, size(seg, 2)
         if (nxt(seg(1, s)) /= 0) then
            errmsg = 'is not one chain of boundary edges: node '//str(seg(1, s))//' starts two edges '// &
                     '(an interior edge, a branch, or the same edge twice)'
            return
         end if
         nxt(seg(1, s)) = seg(2, s)
         nin(seg(2, s)) = nin(seg(2, s)) + 1
      end do
      start = 0
      do k = 1, size(sel)
         n = sel(k)
         if (nin(n) == 0) then
            if (start /= 0) then
               errmsg = 'is not one connected chain of boundary edges (it has at least two pieces, '// &
                        'starting at nodes '//str(start)//' and '//str(n)//')'
               return
            end if
            start = n
         end if
      end do
      if (start == 0) then
         errmsg = 'is a closed loop; Gamma_c must be an open chain (split the curve or give a range)'
         return
      end if
      allocate (nodes(size(seg, 2) + 1))
      nodes(1) = start
      do k = 2, size(nodes)
         nodes(k) = nxt(nodes(k - 1))
         if (nodes(k) == 0) then
            errmsg = 'is not one connected chain of boundary edges (it has at least two pieces)'
            return
         end if
      end do
      if (reverse) nodes = nodes(size(nodes):1:-1)
      stat = 0
      errmsg = ''
   end subroutine mesh_group_chain

   !> Make every element counter-clockwise (clockwise ones are reversed; nflip counts them),
   !> refuse an element whose Jacobian is not positive at one of its 2 x 2 Gauss points, and
   !> orient each group edge as its element runs (the body on its left). stat /= 0 with a
   !> message naming the element (its id in the mesh file) or the edge.
   subroutine mesh_orient(this, nflip, stat, errmsg)
      class(mesh_t), intent(inout) :: this
      integer, intent(out) :: nflip
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp), parameter :: gp = 1/sqrt(3.0_wp)
      real(wp), parameter :: xi(4) = [-1, 1, 1, -1], eta(4) = [-1, -1, 1, 1]
      real(wp) :: xe(2, 4), jac(2, 2), area
      integer, allocatable :: adj_start(:), adj_elem(:)
      integer :: e, q, a, b, k, s, n, hold
      logical :: forward

      stat = 1
      nflip = 0
      do e = 1, this%nel
         xe = this%x(:, this%conn(:, e))
         area = 0.5_wp*((xe(1, 3) - xe(1, 1))*(xe(2, 4) - xe(2, 2)) - (xe(1, 4) - xe(1, 2))*(xe(2, 3) - xe(2, 1)))
         if (area < 0) then
            this%conn(:, e) = this%conn([1, 4, 3, 2], e)
            nflip = nflip + 1
            xe = this%x(:, this%conn(:, e))
         end if
         do q = 1, 4
            ! dx/dxi and dx/deta at Gauss point (xi(q), eta(q)) / sqrt(3)
            jac = 0
            do a = 1, 4
               jac(:, 1) = jac(:, 1) + 0.25_wp*xe(:, a)*xi(a)*(1 + eta(a)*eta(q)*gp)
               jac(:, 2) = jac(:, 2) + 0.25_wp*xe(:, a)*eta(a)*(1 + xi(a)*xi(q)*gp)
            end do
            if (.not. jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1) > 0) then
               errmsg = 'element '//str(this%id_of(e))//' has a non-positive Jacobian at a Gauss point '// &
                        '(degenerate, self-intersecting or too distorted quadrilateral)'
               return
            end if
         end do
      end do
      if (.not. allocated(this%gseg)) then
         stat = 0
         errmsg = ''
         return
      end if
      ! node -> elements, to find the element of each group edge
      call node_elements(this%conn, this%nnode, adj_start, adj_elem)
      allocate (this%gboundary(size(this%gseg, 2)))
      do s = 1, size(this%gseg, 2)
         n = this%gseg(1, s)
         hold = 0
         forward = .true.
         do k = adj_start(n), adj_start(n + 1) - 1
            e = adj_elem(k)
            do a = 1, 4
               b = mod(a, 4) + 1
               if (this%conn(a, e) == this%gseg(1, s) .and. this%conn(b, e) == this%gseg(2, s)) then
                  hold = hold + 1
                  forward = .true.
               else if (this%conn(b, e) == this%gseg(1, s) .and. this%conn(a, e) == this%gseg(2, s)) then
                  hold = hold + 1
                  forward = .false.
               end if
            end do
         end do
         if (hold == 0) then
            errmsg = 'the boundary edge ('//str(this%gseg(1, s))//', '//str(this%gseg(2, s))// &
                     ') of a physical curve is not an edge of any quadrilateral'
            return
         end if
         ! an edge held by one element is a boundary edge: orient it with that element; an
         ! interior edge (two elements) keeps its direction (usable for Dirichlet data only)
         if (hold == 1 .and. .not. forward) this%gseg(:, s) = this%gseg([2, 1], s)
         this%gboundary(s) = hold == 1
      end do
      stat = 0
      errmsg = ''
   end subroutine mesh_orient
   !> Renumber the nodes: node k becomes the old node perm(k) (coordinates, connectivity, groups;
   !> file_node keeps each node's number in the file's order).
   subroutine mesh_renumber(this, perm)
      class(mesh_t), intent(inout) :: this
      integer, intent(in) :: perm(:)   !< (nnode) a permutation of 1..nnode
      integer, allocatable :: newid(:)
      integer :: k
      allocate (newid(this%nnode))
      do k = 1, this%nnode
         newid(perm(k)) = k
      end do
      if (.not. allocated(this%file_node)) this%file_node = [(k, k=1, this%nnode)]
      this%file_node = this%file_node(perm)
      this%x = this%x(:, perm)
      this%conn = reshape(newid(pack(this%conn, .true.)), shape(this%conn))
      if (allocated(this%gseg)) then
         if (size(this%gseg) > 0) this%gseg = reshape(newid(pack(this%gseg, .true.)), shape(this%gseg))
      end if
   end subroutine mesh_renumber

   !> The number in the file's order of node n (file_node; n itself if not renumbered).
   elemental integer function mesh_file_id(this, n) result(id)
      class(mesh_t), intent(in) :: this
      integer, intent(in) :: n
      id = n
      if (allocated(this%file_node)) id = this%file_node(n)
   end function mesh_file_id

   !> A nodal field (k, nnode) with its columns in the file's order of the nodes (for output).
   pure function mesh_file_order(this, a) result(b)
      class(mesh_t), intent(in) :: this
      real(wp), intent(in) :: a(:, :)
      real(wp) :: b(size(a, 1), size(a, 2))
      if (allocated(this%file_node)) then
         b(:, this%file_node) = a
      else
         b = a
      end if
   end function mesh_file_order

   !> Node -> element adjacency in compressed form: the elements holding node n are
   !> adj_elem(adj_start(n) : adj_start(n+1) - 1), in increasing element order.
   pure subroutine node_elements(conn, nnode, adj_start, adj_elem)
      integer, intent(in) :: conn(:, :)   !< (4, nel) element nodes
      integer, intent(in) :: nnode
      integer, allocatable, intent(out) :: adj_start(:), adj_elem(:)
      integer, allocatable :: fill(:)
      integer :: e, a, n
      allocate (adj_start(nnode + 1), adj_elem(size(conn)), fill(nnode))
      adj_start = 0
      do e = 1, size(conn, 2)
         do a = 1, size(conn, 1)
            adj_start(conn(a, e) + 1) = adj_start(conn(a, e) + 1) + 1
         end do
      end do
      adj_start(1) = 1
      do n = 1, nnode
         adj_start(n + 1) = adj_start(n + 1) + adj_start(n)
      end do
      fill = adj_start(1:nnode)
      do e = 1, size(conn, 2)
         do a = 1, size(conn, 1)
            adj_elem(fill(conn(a, e))) = e
            fill(conn(a, e)) = fill(conn(a, e)) + 1
         end do
      end do
   end subroutine node_elements
end module contact2d_mesh
