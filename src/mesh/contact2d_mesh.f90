!> Q1 meshes: the structured rectangle mesher and boundary selections (SPEC sections 2 and 8).
!>
!> Structured numbering (SPEC section 8): node (i, j), 0 <= i <= nx, 0 <= j <= ny, has id
!> i + (nx+1) j + 1; element (i, j) has id i + nx j + 1 and nodes counter-clockwise from its
!> bottom-left corner.
module contact2d_mesh
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: mesh_t, side_names

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
   contains
      procedure :: init_rectangle => mesh_init_rectangle
      procedure :: init_arrays => mesh_init_arrays
      procedure :: select_nodes => mesh_select_nodes
      procedure :: select_segments => mesh_select_segments
      procedure :: element_coordinates => mesh_element_coordinates
      procedure :: tolerance => mesh_tolerance
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
end module contact2d_mesh
