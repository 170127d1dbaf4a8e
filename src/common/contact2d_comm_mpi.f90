!> The processes of a run and their messages (docs/mpi.md):
!> the only module that uses MPI, so that no other file includes it. This file is built when
!> CONTACT2D_MPI is on; contact2d_comm_serial.f90, the same interface for one process, when off.
!>
!> MPI is started only when the program was launched by mpirun (OMPI_COMM_WORLD_SIZE or
!> PMI_SIZE set): a plain run does not initialise MPI at all and is one process as without MPI.
!> Every message is between the ranks of MPI_COMM_WORLD; the gathers put each rank's block at its
!> place, so what every rank holds afterwards does not depend on arrival order (the same bits).
module contact2d_comm
   use mpi
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: comm_init, comm_end, comm_rank, comm_size, comm_barrier, comm_allgatherv, comm_allgatherv_inplace, &
             comm_max, comm_halo_start, comm_halo_wait, comm_abort, comm_failing, comm_mpi

   !> Built with MPI (this file): the serial stand-in says .false.
   logical, parameter :: comm_mpi = .true.

   logical, save :: started = .false.
   integer, save :: my_rank = 0, nproc = 1
   !> the requests of the halo exchange in flight (at most two neighbours, a send and a receive each)
   integer, save :: req(4) = MPI_REQUEST_NULL
   integer, save :: nreq = 0

contains

   !> Start MPI when launched by mpirun; else one process (rank 0 of 1).
   subroutine comm_init()
      integer :: ierr, n
      logical :: done
      call get_environment_variable('OMPI_COMM_WORLD_SIZE', length=n)
      if (n == 0) call get_environment_variable('PMI_SIZE', length=n)
      if (n == 0) return
      call MPI_Initialized(done, ierr)
      if (.not. done) call MPI_Init(ierr)
      started = .true.
      call MPI_Comm_rank(MPI_COMM_WORLD, my_rank, ierr)
      call MPI_Comm_size(MPI_COMM_WORLD, nproc, ierr)
   end subroutine comm_init

   !> End MPI (every rank, before the program stops); nothing when MPI was not started.
   subroutine comm_end()
      integer :: ierr
      logical :: done
      if (.not. started) return
      call MPI_Finalized(done, ierr)
      if (.not. done) call MPI_Finalize(ierr)
      started = .false.
   end subroutine comm_end

   !> Before a failed run stops (exit code /= 0, one line from rank 0): MPI is not ended, since
   !> the failure may be this rank's alone and MPI_Finalize waits for every rank; mpirun ends the
   !> others once one exits with a non-zero code. A rank other than 0 waits two seconds first, so
   !> that when every rank fails alike rank 0 (the one that prints) is the first to exit.
   subroutine comm_failing()
      if (.not. started) return
      if (my_rank /= 0) call sleep(2)
      started = .false.
   end subroutine comm_failing

   !> Stop every process of the run with this exit code (one rank failed alone).
   subroutine comm_abort(code)
      integer, intent(in) :: code
      integer :: ierr
      if (started) call MPI_Abort(MPI_COMM_WORLD, code, ierr)
   end subroutine comm_abort

   !> This process's rank, 0 .. comm_size() - 1.
   integer function comm_rank()
      comm_rank = my_rank
   end function comm_rank

   !> Number of processes of the run.
   integer function comm_size()
      comm_size = nproc
   end function comm_size

   subroutine comm_barrier()
      integer :: ierr
      if (started) call MPI_Barrier(MPI_COMM_WORLD, ierr)
   end subroutine comm_barrier

   !> recv(displ(r) + 1 : displ(r) + count(r)) = send(1 : count(r)) of rank r, on every rank.
   subroutine comm_allgatherv(send, recv, count, displ)
      real(wp), intent(in) :: send(*)
      real(wp), intent(inout) :: recv(*)
      integer, intent(in) :: count(0:), displ(0:)
      integer :: ierr
      if (.not. started) then
         recv(displ(0) + 1:displ(0) + count(0)) = send(1:count(0))
         return
      end if
      call MPI_Allgatherv(send, count(my_rank), MPI_DOUBLE_PRECISION, recv, count, displ, MPI_DOUBLE_PRECISION, &
                          MPI_COMM_WORLD, ierr)
   end subroutine comm_allgatherv

   !> x(displ(r) + 1 : displ(r) + count(r)) of rank r copied to every rank (in place).
   subroutine comm_allgatherv_inplace(x, count, displ)
      real(wp), intent(inout) :: x(*)
      integer, intent(in) :: count(0:), displ(0:)
      integer :: ierr
      if (.not. started) return
      call MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, x, count, displ, MPI_DOUBLE_PRECISION, &
                          MPI_COMM_WORLD, ierr)
   end subroutine comm_allgatherv_inplace

   !> The largest of i over the ranks (exact: the same on every rank).
   integer function comm_max(i)
      integer, intent(in) :: i
      integer :: ierr
      comm_max = i
      if (started) call MPI_Allreduce(i, comm_max, 1, MPI_INTEGER, MPI_MAX, MPI_COMM_WORLD, ierr)
   end function comm_max

   !> Start the exchange of n values with the ranks below and above (-1: none): send(:, 1) to
   !> below and send(:, 2) to above, receive recv(:, 1) from below and recv(:, 2) from above
   !> (non-blocking: comm_halo_wait; neither buffer may be touched before it).
   subroutine comm_halo_start(send, recv, n, below, above)
      integer, intent(in) :: n, below, above
      real(wp), intent(in), asynchronous :: send(n, 2)
      real(wp), intent(inout), asynchronous :: recv(n, 2)
      integer :: ierr
      nreq = 0
      if (.not. started) return
      if (below >= 0) then
         call MPI_Irecv(recv(1, 1), n, MPI_DOUBLE_PRECISION, below, 1, MPI_COMM_WORLD, req(nreq + 1), ierr)
         call MPI_Isend(send(1, 1), n, MPI_DOUBLE_PRECISION, below, 2, MPI_COMM_WORLD, req(nreq + 2), ierr)
         nreq = nreq + 2
      end if
      if (above >= 0) then
         call MPI_Irecv(recv(1, 2), n, MPI_DOUBLE_PRECISION, above, 2, MPI_COMM_WORLD, req(nreq + 1), ierr)
         call MPI_Isend(send(1, 2), n, MPI_DOUBLE_PRECISION, above, 1, MPI_COMM_WORLD, req(nreq + 2), ierr)
         nreq = nreq + 2
      end if
   end subroutine comm_halo_start

   !> Wait for the exchange started by comm_halo_start (recv passed again: its values change).
   subroutine comm_halo_wait(recv)
      real(wp), intent(inout), asynchronous :: recv(:, :)
      integer :: ierr
      if (nreq == 0) return
      call MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE, ierr)
      nreq = 0
      if (size(recv) < 0) recv = 0
   end subroutine comm_halo_wait
end module contact2d_comm
