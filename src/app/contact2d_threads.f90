!> Threads that never hurt (docs/performance.md "Threads that never hurt"): the run
!> measures its own time per step with one thread and with the full team and keeps the faster,
!> probing the other now and then, so a busy core (another process) sends it to one thread and
!> an idle machine back to the team. It also reads how busy other processes keep the CPUs
!> (/proc/stat against its own CPU time): a run whose set-up saw the other CPUs idle starts on
!> the team, and a quiet machine soon brings back a team that was left. The decisions are
!> contact2d_thread_policy's; this module measures and applies them. Results do not depend on the
!> choice: every sum has a fixed order (per-row and per-block partial sums), so any thread count
!> gives the same bits.
!>
!> Active only when the user did not set OMP_NUM_THREADS (then the team is the user's), or when
!> CONTACT2D_THREAD_SWITCHES lists steps (comma-separated, increasing): then no policy runs and
!> the count goes from the team to one thread and back, alternately, at the end of the first
!> chunk of steps that reaches each listed step (a check of the bits under switching: the
!> results must equal one thread's; docs/performance.md).
module contact2d_threads
   use contact2d_kinds, only: wp
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use, intrinsic :: iso_fortran_env, only: error_unit
   use omp_lib, only: omp_get_max_threads, omp_set_num_threads, omp_get_thread_num
   use contact2d_thread_policy, only: thread_policy_t, one_thread
   implicit none
   private
   public :: thread_tuner_t

   !> shortest window over which other processes' CPU use is measured (seconds): /proc/stat counts
   !> idle time in ticks of 10 ms, so over 0.05 s the error is below 0.4 CPU on two CPUs: a
   !> CPU-bound process never looks like an idle CPU (quiet_below in contact2d_thread_policy)
   real(wp), parameter :: window_run = 0.05_wp
   !> the set-up window (program start to the step loop) is used from this length on; over it
   !> (tens of ms) /proc/stat's ticks make an error of up to 2 ticks/window CPUs, so the start
   !> counts the other CPUs idle below quiet_start, and only when no other thread was runnable at
   !> the window's two ends (a CPU-bound process always is)
   real(wp), parameter :: window_start = 0.02_wp, quiet_start = 0.5_wp

   interface
      !> Move the calling thread to the k-th CPU allowed to it, then allow them all again
      !> (contact2d_affinity.c); 0 on success.
      integer(c_int) function affinity_nudge(k) bind(C, name='contact2d_affinity_nudge')
         import :: c_int
         integer(c_int), value :: k
      end function affinity_nudge
      !> Idle seconds of the allowed CPUs since boot, this process's CPU seconds, a monotonic
      !> clock, the allowed CPUs (contact2d_affinity.c); 0 on success.
      integer(c_int) function cpu_times(idle, own, wall, ncpu) bind(C, name='contact2d_cpu_times')
         import :: c_int, c_double
         real(c_double), intent(out) :: idle, own, wall
         integer(c_int), intent(out) :: ncpu
      end function cpu_times
      !> The CPU the calling thread runs on (glibc).
      integer(c_int) function sched_getcpu() bind(C, name='sched_getcpu')
         import :: c_int
      end function sched_getcpu
      !> Runnable threads on the machine other than this process's, now (contact2d_affinity.c);
      !> -1 when unknown.
      integer(c_int) function runnable_others() bind(C, name='contact2d_runnable_others')
         import :: c_int
      end function runnable_others
   end interface

   !> one reading of contact2d_cpu_times, and system_clock's count then (a cheap test of the
   !> window's length before /proc/stat is read again)
   type :: cpu_sample_t
      logical :: ok = .false.
      real(c_double) :: idle = 0, own = 0, wall = 0
      integer(c_int) :: ncpu = 0
      integer(8) :: count = 0
   end type cpu_sample_t

   type :: thread_tuner_t
      logical :: active = .false.
      integer :: nmax = 1                !< the full team
      integer :: current = 1             !< threads in use
      type(thread_policy_t) :: policy
      type(cpu_sample_t) :: mark         !< the start of the current window of CPU use
      integer :: runnable = -1           !< other runnable threads at the program's start
      real(wp) :: others = -1            !< other processes' CPUs over the latest window (< 0: unknown)
      real(wp) :: others_start = -1      !< ... over the set-up
      integer :: switches = 0            !< changes of the thread count
      integer :: started = 1             !< threads of the first chunk
      integer :: nudges = 0              !< team spread again after a chunk with two threads on one CPU
      integer(8) :: steps(2) = 0         !< steps run with one thread and with nmax
      !> forced switches (CONTACT2D_THREAD_SWITCHES): the listed steps and the next one to reach
      integer(8), allocatable :: forced(:)
      integer :: next_forced = 1
   contains
      procedure :: begin => tuner_begin
      procedure :: init => tuner_init
      procedure :: update => tuner_update
   end type thread_tuner_t

contains

   !> At the program's start: the beginning of the set-up window (nothing to do when the user
   !> fixed the thread count or there is one thread).
   subroutine tuner_begin(this)
      class(thread_tuner_t), intent(inout) :: this
      integer :: length, status
      ! (read before anything is written: a bad value stops the run with nothing left behind)
      call forced_steps(this%forced)
      call get_environment_variable('OMP_NUM_THREADS', length=length, status=status)
      if (status == 0 .or. omp_get_max_threads() < 2) return
      this%mark = cpu_sample()
      this%runnable = runnable_others()
   end subroutine tuner_begin

   !> Active if OMP_NUM_THREADS is unset, the machine has more than one thread and the mesh is
   !> large enough for the kernels to go parallel. An active tuner starts on the team when other
   !> processes left the other CPUs idle during the set-up, else on one thread.
   subroutine tuner_init(this, parallel_mesh)
      class(thread_tuner_t), intent(inout) :: this
      logical, intent(in) :: parallel_mesh
      integer :: length, status
      call get_environment_variable('OMP_NUM_THREADS', length=length, status=status)
      this%nmax = omp_get_max_threads()
      this%current = this%nmax
      this%switches = 0
      this%steps = 0
      this%active = status /= 0 .and. this%nmax > 1 .and. parallel_mesh
      if (allocated(this%forced)) then
         ! a forced schedule: the team first, no policy
         this%active = .false.
         this%started = this%current
         return
      end if
      if (.not. this%active) return
      call measure(this, window_start)
      this%others_start = this%others
      if (this%others_start >= 0 .and. this%others_start < quiet_start .and. &
          this%runnable == 0 .and. runnable_others() == 0) then
         call this%policy%start(0.0_wp)
      else
         call this%policy%start(max(this%others_start, quiet_start))
      end if
      this%current = 1
      call omp_set_num_threads(1)
      call apply(this)
      this%switches = 0
      this%started = this%current
   end subroutine tuner_init

   !> After a chunk of nsteps steps that took seconds: the policy's count for the next chunk.
   subroutine tuner_update(this, seconds, nsteps)
      class(thread_tuner_t), intent(inout) :: this
      real(wp), intent(in) :: seconds
      integer, intent(in) :: nsteps
      integer :: k
      if (nsteps <= 0) return
      k = merge(1, 2, this%current == 1)
      this%steps(k) = this%steps(k) + nsteps
      if (allocated(this%forced)) then
         do while (this%next_forced <= size(this%forced))
            if (sum(this%steps) < this%forced(this%next_forced)) exit
            this%next_forced = this%next_forced + 1
            this%current = merge(this%nmax, 1, this%current == 1)
            this%switches = this%switches + 1
            call omp_set_num_threads(this%current)
         end do
         return
      end if
      if (.not. this%active) return
      if (this%current > 1) call keep_apart(this)
      call measure(this, window_run)
      call this%policy%chunk(seconds, nsteps, this%others)
      call apply(this)
   end subroutine tuner_update

   !> Other processes' CPUs since the mark, once the window is at least shortest seconds long.
   subroutine measure(this, shortest)
      type(thread_tuner_t), intent(inout) :: this
      real(wp), intent(in) :: shortest
      type(cpu_sample_t) :: now
      real(wp) :: span
      integer(8) :: count, rate
      if (.not. this%mark%ok) then
         this%mark = cpu_sample()
         return
      end if
      call system_clock(count, rate)
      if (real(count - this%mark%count, wp) < shortest*rate) return
      now = cpu_sample()
      if (.not. now%ok) return
      span = now%wall - this%mark%wall
      if (span < shortest) return
      if (now%ncpu == this%mark%ncpu) then
         this%others = max(0.0_wp, (now%ncpu*span - (now%idle - this%mark%idle) - (now%own - this%mark%own))/span)
      else
         this%others = -1
      end if
      this%mark = now
   end subroutine measure

   !> After a team chunk: if two threads of the team run on one CPU (a worker that slept is woken
   !> on the waker's CPU on the project's VM and stays there while both are busy), spread the
   !> team again. One small parallel region per chunk (about a microsecond while the threads spin).
   subroutine keep_apart(this)
      type(thread_tuner_t), intent(inout) :: this
      integer, parameter :: most = 64
      integer(c_int) :: cpus(0:most - 1), rc
      integer :: i, n
      logical :: shared
      n = min(this%current, most)
      cpus = -1
      !$omp parallel num_threads(n)
      if (omp_get_thread_num() < most) cpus(omp_get_thread_num()) = sched_getcpu()
      !$omp end parallel
      shared = .false.
      do i = 1, n - 1
         if (cpus(i) >= 0) shared = shared .or. any(cpus(0:i - 1) == cpus(i))
      end do
      if (.not. shared) return
      this%nudges = this%nudges + 1
      !$omp parallel num_threads(n) private(rc)
      rc = affinity_nudge(int(omp_get_thread_num(), c_int))
      !$omp end parallel
   end subroutine keep_apart

   !> The steps of CONTACT2D_THREAD_SWITCHES (unallocated when it is unset or empty); a value
   !> that is not a list of increasing positive integers stops the run with one line.
   subroutine forced_steps(steps)
      integer(8), allocatable, intent(out) :: steps(:)
      character(len=:), allocatable :: text
      integer :: length, status, i, j, n, ios
      integer(8) :: k
      call get_environment_variable('CONTACT2D_THREAD_SWITCHES', length=length, status=status)
      if (status /= 0 .or. length == 0) return
      allocate (character(len=length) :: text)
      call get_environment_variable('CONTACT2D_THREAD_SWITCHES', text)
      if (len_trim(text) == 0) return
      n = 1
      do i = 1, len(text)
         if (text(i:i) == ',') n = n + 1
      end do
      allocate (steps(n))
      i = 1
      do j = 1, n
         length = index(text(i:), ',') - 1
         if (length < 0) length = len(text) - i + 1
         ios = 1
         if (length > 0 .and. verify(trim(adjustl(text(i:i + length - 1))), '0123456789') == 0) &
            read (text(i:i + length - 1), *, iostat=ios) k
         if (ios /= 0) call bad()
         if (k < 1) call bad()
         if (j > 1) then
            if (k <= steps(j - 1)) call bad()
         end if
         steps(j) = k
         i = i + length + 1
      end do
   contains
      subroutine bad()
         write (error_unit, '(a)') 'contact2d: error: CONTACT2D_THREAD_SWITCHES = "'//text// &
            '": give increasing positive step numbers separated by commas'
         stop 1, quiet=.true.
      end subroutine bad
   end subroutine forced_steps

   type(cpu_sample_t) function cpu_sample() result(s)
      call system_clock(s%count)
      s%ok = cpu_times(s%idle, s%own, s%wall, s%ncpu) == 0
   end function cpu_sample

   !> Use the policy's count from the next chunk on; a team is spread over the CPUs once (each
   !> thread of it moved to a CPU of its own, then free again): woken threads otherwise share the
   !> waker's core on the project's VM (docs/performance.md).
   subroutine apply(this)
      type(thread_tuner_t), intent(inout) :: this
      integer(c_int) :: rc
      integer :: n
      n = merge(1, this%nmax, this%policy%current == one_thread)
      if (n == this%current) return
      this%switches = this%switches + 1
      this%current = n
      call omp_set_num_threads(n)
      if (n > 1) then
         !$omp parallel num_threads(n) private(rc)
         rc = affinity_nudge(int(omp_get_thread_num(), c_int))
         !$omp end parallel
      end if
   end subroutine apply
end module contact2d_threads
