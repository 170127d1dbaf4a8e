!> A contact pair: which boundary may touch what (SPEC section 3). The slave side is a chain of
!> boundary nodes of a body; the master side is a rigid obstacle or another body's boundary
!> (contact:master; docs/architecture.md, "Seams"). The model holds a list of pairs, one per &contact
!> group; model%contacts(k), the contact operator of pairs(k) (contact2d_contact), is what the
!> engines work on.
module contact2d_pair
   implicit none
   private
   public :: contact_pair_t, pair_init, master_obstacle, master_body

   !> Kinds of master side.
   integer, parameter :: master_obstacle = 1   !< a rigid obstacle (contact2d_obstacle)
   integer, parameter :: master_body = 2       !< the boundary of another body (contact:master)

   !> One slave boundary against one master.
   type :: contact_pair_t
      integer :: slave_body = 1                 !< index of the slave body in model%bodies (the body of
                                                !< every edge of the slave boundary)
      integer, allocatable :: slave_nodes(:)    !< its contact nodes (mesh numbering, by abscissa)
      integer :: master_kind = master_obstacle
      integer :: master_body = 0                !< index of the master body (master_body kind)
      character(len=:), allocatable :: master   !< what the master is, in words
      !> the pair's name (contact:name): its output group and series names, messages
      character(len=:), allocatable :: name
   end type contact_pair_t

contains

   !> A pair `name` of body `slave_body`'s nodes against a rigid obstacle described as `obstacle`.
   subroutine pair_init(pair, name, slave_body, slave_nodes, obstacle)
      type(contact_pair_t), intent(out) :: pair
      character(len=*), intent(in) :: name
      integer, intent(in) :: slave_body
      integer, intent(in) :: slave_nodes(:)
      character(len=*), intent(in) :: obstacle
      pair%name = name
      pair%slave_body = slave_body
      pair%slave_nodes = slave_nodes
      pair%master_kind = master_obstacle
      pair%master_body = 0
      pair%master = obstacle
   end subroutine pair_init
end module contact2d_pair
