!> The processes of a run, built without MPI (CONTACT2D_MPI off): one process, rank 0 of 1; the
!> gathers copy, the halo exchange has no neighbour. The same interface as contact2d_comm_mpi.f90
!> (docs/mpi.md).
module contact2d_comm
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: comm_init, comm_end, comm_rank, comm_size, comm_barrier, comm_allgatherv, comm_allgatherv_inplace, &
             comm_max, comm_halo_start, comm_halo_wait, comm_abort, comm_failing, comm_mpi

   !> Built without MPI.
   logical, parameter :: comm_mpi = .false.

contains

   subroutine comm_init()
   end subroutine comm_init

   subroutine comm_end()
   end subroutine comm_end

   subroutine comm_failing()
   end subroutine comm_failing

   subroutine comm_abort(code)
      integer, intent(in) :: code
      if (.false.) print *, code
   end subroutine comm_abort

   integer function comm_rank()
      comm_rank = 0
   end function comm_rank

   integer function comm_size()
      comm_size = 1
   end function comm_size

   subroutine comm_barrier()
   end subroutine comm_barrier

   subroutine comm_allgatherv(send, recv, count, displ)
      real(wp), intent(in) :: send(*)
      real(wp), intent(inout) :: recv(*)
      integer, intent(in) :: count(0:), displ(0:)
      recv(displ(0) + 1:displ(0) + count(0)) = send(1:count(0))
   end subroutine comm_allgatherv

   subroutine comm_allgatherv_inplace(x, count, displ)
      real(wp), intent(inout) :: x(*)
      integer, intent(in) :: count(0:), displ(0:)
      if (.false.) x(1) = x(1) + count(0) + displ(0)
   end subroutine comm_allgatherv_inplace

   integer function comm_max(i)
      integer, intent(in) :: i
      comm_max = i
   end function comm_max

   subroutine comm_halo_start(send, recv, n, below, above)
      integer, intent(in) :: n, below, above
      real(wp), intent(in), asynchronous :: send(n, 2)
      real(wp), intent(inout), asynchronous :: recv(n, 2)
      if (below >= 0 .or. above >= 0) recv = send   ! (never: one process has no neighbour)
   end subroutine comm_halo_start

   subroutine comm_halo_wait(recv)
      real(wp), intent(inout), asynchronous :: recv(:, :)
      if (size(recv) < 0) recv = 0
   end subroutine comm_halo_wait
end module contact2d_comm
