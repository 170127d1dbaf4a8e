!> Threads that never hurt (issue 13, docs/performance.md "Threads"): the run measures its own
!> time per step with one thread and with the full team and keeps the faster, probing the other
!> now and then, so a busy core (another process) sends it to one thread and an idle machine
!> back to two. Results do not depend on the choice: every sum has a fixed order (per-row and
!> per-block partial sums), so any thread count gives the same bits.
!>
!> Active only when the user did not set OMP_NUM_THREADS (then the team is the user's).
module contact2d_threads
   use contact2d_kinds, only: wp
   use, intrinsic :: iso_c_binding, only: c_int
   use omp_lib, only: omp_get_max_threads, omp_set_num_threads, omp_get_thread_num
   implicit none
   private
   public :: thread_tuner_t

   !> Chunks (calls of the step loop) between probes of the other thread count (doubled after each
   !> probe that did not switch, up to probe_every_max: a team on a busy core can be many times
   !> slower than one thread, and each probe pays for it), chunks per probe, the weight of a new
   !> measurement in the running estimate, and the slowdown of a probe's first counted chunk
   !> against the count in use that ends the probe at once.
   integer, parameter :: probe_every = 40, probe_every_max = 640, probe_chunks = 3
   real(wp), parameter :: weight = 0.3_wp, probe_abort = 1.5_wp
   !> The team is left for one thread at once when its running estimate becomes this much slower
   !> than one thread's: a probe lasts a few ms, less than a scheduler time slice, so a team can
   !> look fast in its probe on a core another process shares and be slow afterwards.
   real(wp), parameter :: team_back = 1.25_wp

   interface
      !> Move the calling thread to the k-th CPU allowed to it, then allow them all again
      !> (contact2d_affinity.c); 0 on success.
      integer(c_int) function affinity_nudge(k) bind(C, name='contact2d_affinity_nudge')
         import :: c_int
         integer(c_int), value :: k
      end function affinity_nudge
   end interface

   type :: thread_tuner_t
      logical :: active = .false.
      integer :: nmax = 1                !< the full team
      integer :: current = 1             !< threads in use
      real(wp) :: per_step(2) = 0        !< running seconds per step: (1) one thread, (2) nmax
      integer :: chunks = 0              !< chunks since the last decision
      integer :: probing = 0             !< chunks left in a probe of the other count
      integer :: interval = probe_every  !< chunks between probes now
      integer :: before = 1              !< count in use before the probe
      logical :: fresh = .true.          !< the next chunk is the first with this count: not counted
      integer :: switches = 0            !< changes of the thread count
      integer(8) :: steps(2) = 0         !< steps run with one thread and with nmax
   contains
      procedure :: init => tuner_init
      procedure :: update => tuner_update
   end type thread_tuner_t

contains

   !> Active if OMP_NUM_THREADS is unset, the machine has more than one thread and the mesh is
   !> large enough for the kernels to go parallel. An active tuner starts on one thread and
   !> probes the full team after a few chunks: a team on a busy core is the costly mistake.
   subroutine tuner_init(this, parallel_mesh)
      class(thread_tuner_t), intent(out) :: this
      logical, intent(in) :: parallel_mesh
      integer :: length, status
      call get_environment_variable('OMP_NUM_THREADS', length=length, status=status)
      this%nmax = omp_get_max_threads()
      this%current = this%nmax
      this%active = status /= 0 .and. this%nmax > 1 .and. parallel_mesh
      if (this%active) then
         this%current = 1
         call omp_set_num_threads(1)
      end if
   end subroutine tuner_init

   !> After a chunk of nsteps steps that took seconds: update the estimate of the count in use,
   !> then keep, probe or switch.
   subroutine tuner_update(this, seconds, nsteps)
      class(thread_tuner_t), intent(inout) :: this
      real(wp), intent(in) :: seconds
      integer, intent(in) :: nsteps
      integer :: k, best
      if (nsteps <= 0) return
      k = merge(1, 2, this%current == 1)
      this%steps(k) = this%steps(k) + nsteps
      if (.not. this%active) return
      this%chunks = this%chunks + 1
      if (this%fresh) then
         ! the first chunk of the run and the first after a switch wake the threads: not
         ! counted, the estimate restarts
         this%per_step(k) = 0
         this%fresh = .false.
      else if (this%per_step(k) == 0) then
         this%per_step(k) = seconds/nsteps
      else
         this%per_step(k) = (1 - weight)*this%per_step(k) + weight*seconds/nsteps
      end if
      if (this%probing > 0) then
         this%probing = this%probing - 1
         ! a first counted chunk much slower than the count in use ends the probe
         if (this%probing > 0 .and. this%probing < probe_chunks - 1 .and. this%per_step(3 - k) > 0) then
            if (this%per_step(k) > probe_abort*this%per_step(3 - k)) this%probing = 0
         end if
         if (this%probing > 0) return
         ! probe over: the faster of the two; probe less often while the count does not change
         best = minloc(this%per_step, dim=1)
         call use_count(this, merge(1, this%nmax, best == 1))
         if (this%current == this%before) then
            this%interval = min(2*this%interval, probe_every_max)
         else
            this%interval = probe_every
         end if
         this%chunks = 0
         return
      end if
      ! the team slower than one thread: back to one thread now (never wait for the next probe)
      if (this%current == this%nmax .and. this%per_step(1) > 0 .and. &
          this%per_step(2) > team_back*this%per_step(1)) then
         call use_count(this, 1)
         this%chunks = 0
         return
      end if
      ! the first probe soon (both estimates), then every interval chunks
      if ((this%per_step(3 - k) == 0 .and. this%chunks >= 4) .or. this%chunks >= this%interval) then
         this%before = this%current
         call use_count(this, merge(this%nmax, 1, this%current == 1))
         this%probing = probe_chunks
         this%chunks = 0
      end if
   end subroutine tuner_update

   !> Use n threads from the next chunk on; a team is spread over the CPUs once (each thread of
   !> it moved to a CPU of its own, then free again): woken threads otherwise share the waker's
   !> core on the project's VM (docs/performance.md).
   subroutine use_count(this, n)
      type(thread_tuner_t), intent(inout) :: this
      integer, intent(in) :: n
      integer(c_int) :: rc
      if (n /= this%current) then
         this%switches = this%switches + 1
         this%current = n
         this%fresh = .true.
         call omp_set_num_threads(n)
         if (n > 1) then
            !$omp parallel num_threads(n) private(rc)
            rc = affinity_nudge(int(omp_get_thread_num(), c_int))
            !$omp end parallel
         end if
      end if
   end subroutine use_count
end module contact2d_threads
