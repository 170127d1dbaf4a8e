!> The domain-decomposition data layout of one process: which mesh nodes it owns, which it only
!> mirrors (ghosts: nodes of its elements owned by another process), and the halo lists that keep
!> the ghosts up to date (per neighbour, the owned nodes it sends and the ghosts it receives).
!>
!> Local numbering puts the owned nodes first (1 .. nowned), then the ghosts (nowned + 1 ..
!> nlocal), so a sum or maximum over what this process owns is a loop over 1 .. nowned with no
!> index list: the energies and residuals of the explicit engine are reduced that way, and summed
!> across processes once each is a distributed one. One process: owned = every node in the mesh's
!> order, no ghost, no neighbour, empty halo, so its reductions are the loops of before, in the
!> same order (the same bits).
!>
!> A node belongs to the lowest-numbered part among the elements that hold it; the elements are
!> split by a partition vector (part of each element, 0 .. nparts - 1).
module contact2d_layout
   implicit none
   private
   public :: layout_t

   !> One process's share of the nodes and its halo.
   type :: layout_t
      integer :: rank = 0                   !< this process's part, 0 .. nparts - 1
      integer :: nparts = 1                 !< number of parts (processes)
      integer :: nowned = 0                 !< nodes this process owns (local 1 .. nowned)
      integer :: nghost = 0                 !< ghost nodes (local nowned + 1 .. nlocal)
      integer :: nlocal = 0                 !< nowned + nghost
      integer, allocatable :: global(:)     !< mesh node of each local node (nlocal)
      integer, allocatable :: neighbour(:)  !< the parts this one exchanges with, ascending
      !> local owned nodes sent to neighbour k: send_node(send_start(k) : send_start(k+1) - 1)
      integer, allocatable :: send_start(:), send_node(:)
      !> local ghosts received from neighbour k: recv_node(recv_start(k) : recv_start(k+1) - 1)
      integer, allocatable :: recv_start(:), recv_node(:)
   contains
      procedure :: init_single => layout_init_single
      procedure :: init_partition => layout_init_partition
      procedure :: neighbours => layout_neighbours
   end type layout_t

contains

   !> The layout of a run on one process: every one of the nnode nodes owned, in the mesh's order.
   subroutine layout_init_single(this, nnode)
      class(layout_t), intent(out) :: this
      integer, intent(in) :: nnode
      integer :: n
      this%rank = 0
      this%nparts = 1
      this%nowned = nnode
      this%nghost = 0
      this%nlocal = nnode
      this%global = [(n, n=1, nnode)]
      allocate (this%neighbour(0), this%send_node(0), this%recv_node(0))
      this%send_start = [1]
      this%recv_start = [1]
   end subroutine layout_init_single

   !> The layout of part rank for the element partition part(nel) (values 0 .. nparts - 1) of a
   !> mesh with connectivity conn(:, nel) and nnode nodes. stat /= 0 with a one-line errmsg if a
   !> part number is out of range or rank is not one of them.
   subroutine layout_init_partition(this, conn, nnode, part, nparts, rank, stat, errmsg)
      class(layout_t), intent(out) :: this
      integer, intent(in) :: conn(:, :), nnode, part(:), nparts, rank
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer, allocatable :: owner(:), local(:)
      logical, allocatable :: mine(:), sends(:, :)
      integer :: e, n, p, k

      stat = 1
      if (size(part) /= size(conn, 2) .or. any(part < 0) .or. any(part >= nparts)) then
         errmsg = 'layout: the partition does not give every element a part in 0 .. nparts - 1'
         return
      end if
      if (rank < 0 .or. rank >= nparts) then
         errmsg = 'layout: rank is not a part of the partition'
         return
      end if
      stat = 0
      errmsg = ''
      this%rank = rank
      this%nparts = nparts
      ! owner: the lowest part among a node's elements; mine: the node is on one of rank's elements;
      ! sends(n, p): node n is on an element of part p (so p mirrors it unless p owns it)
      allocate (owner(nnode), mine(nnode), sends(nnode, 0:nparts - 1), local(nnode))
      owner = nparts
      mine = .false.
      sends = .false.
      do e = 1, size(conn, 2)
         do k = 1, size(conn, 1)
            n = conn(k, e)
            owner(n) = min(owner(n), part(e))
            sends(n, part(e)) = .true.
            if (part(e) == rank) mine(n) = .true.
         end do
      end do
      ! local numbers: owned nodes in the mesh's order, then the ghosts in the mesh's order
      this%nowned = count(owner == rank)
      this%nghost = count(mine .and. owner /= rank)
      this%nlocal = this%nowned + this%nghost
      this%global = [pack([(n, n=1, nnode)], owner == rank), pack([(n, n=1, nnode)], mine .and. owner /= rank)]
      local = 0
      local(this%global) = [(k, k=1, this%nlocal)]
      ! neighbours: the owners of the ghosts and the parts that mirror an owned node
      allocate (this%neighbour(0))
      do p = 0, nparts - 1
         if (p == rank) cycle
         if (any(mine .and. owner == p) .or. any(owner == rank .and. sends(:, p))) &
            this%neighbour = [this%neighbour, p]
      end do
      allocate (this%send_start(size(this%neighbour) + 1), this%recv_start(size(this%neighbour) + 1))
      allocate (this%send_node(0), this%recv_node(0))
      this%send_start(1) = 1
      this%recv_start(1) = 1
      do k = 1, size(this%neighbour)
         p = this%neighbour(k)
         ! send: owned nodes on p's elements; receive: ghosts that p owns (both in the mesh's order)
         this%send_node = [this%send_node, local(pack([(n, n=1, nnode)], owner == rank .and. sends(:, p)))]
         this%recv_node = [this%recv_node, local(pack([(n, n=1, nnode)], mine .and. owner == p))]
         this%send_start(k + 1) = size(this%send_node) + 1
         this%recv_start(k + 1) = size(this%recv_node) + 1
      end do
   end subroutine layout_init_partition

   !> Number of neighbouring parts.
   pure integer function layout_neighbours(this) result(n)
      class(layout_t), intent(in) :: this
      n = size(this%neighbour)
   end function layout_neighbours
end module contact2d_layout
