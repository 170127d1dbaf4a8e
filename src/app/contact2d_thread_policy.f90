!> The thread tuner's decisions (docs/performance.md "Threads that never hurt"):
!> which thread count runs the next chunk of steps, one thread or the full team, from
!> the seconds per step of the chunks so far and, where the system tells it, how many CPUs other
!> processes kept busy. Logic only (no OpenMP, no clock, no I/O): contact2d_threads applies the
!> count and measures; tests/app feeds synthetic chunk times.
!>
!> - Each count keeps its last `window` counted chunks (the first chunk after a switch wakes the
!>   threads and is not counted); a probe compares their means. Between probes the team is left
!>   when each of its latest three chunks, or the mean of its window (three chunks at least), is
!>   team_back times one thread's mean: one or two slow chunks among many (a time slice lost, a
!>   rare slow region entry) do not send an idle machine's run to one thread, a team slow on
!>   every chunk or on every third (sharing a core by time slices) is left.
!> - The other count is probed now and then for `probe_chunks` chunks (the team's first not
!>   counted, one thread's probe a chunk shorter: nothing to wake); a team probe whose first
!>   counted chunk is probe_abort times slower than one thread ends at once.
!> - Each time the team loses (a probe or the check above) the wait before the next team probe doubles, up to
!>   probe_every_max chunks; a win resets it. On the team one thread is probed once the team's
!>   window is full (the check above needs its time), then after 4 probe_every chunks, doubled per
!>   probe that keeps the team: the check, not these probes, catches a team slowed by a new load.
!> - Other processes' CPUs (`others`, from /proc/stat; negative when unknown): a run starts on the
!>   team when they were idle during the set-up, and a quiet machine brings back a team that was
!>   left (after quiet_gap chunks, doubled per loss), so one slow stretch does not keep a run on one
!>   thread for hundreds of chunks. When the others were busy at the start the first team probe
!>   waits probe_every chunks instead of first_probe.
module contact2d_thread_policy
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: thread_policy_t

   integer, parameter, public :: one_thread = 1, full_team = 2
   !> counted chunks per count kept for the estimates
   integer, parameter, public :: window = 8
   !> chunks before the first probe of the other count, between probes (doubled per loss of the
   !> team, or per probe of one thread that kept it, up to probe_every_max), chunks per probe
   integer, parameter, public :: first_probe = 4, probe_every = 40, probe_every_max = 640, probe_chunks = 3
   !> chunks on one thread before a quiet machine brings the team back (doubled per loss)
   integer, parameter, public :: quiet_gap = 4
   real(wp), parameter, public :: probe_abort = 1.5_wp, team_back = 1.25_wp
   !> other processes' CPUs below which the other cores count as idle
   real(wp), parameter, public :: quiet_below = 0.3_wp
   !> ... and above which they count as busy (no quick first probe of the team)
   real(wp), parameter, public :: busy_above = 0.7_wp

   type :: thread_policy_t
      integer :: current = one_thread      !< count of the next chunk: one_thread or full_team
      real(wp) :: recent(window, 2) = 0    !< seconds per step of the last counted chunks
      integer :: nrecent(2) = 0            !< how many of them are set
      integer :: chunks = 0                !< chunks since the last decision
      integer :: probing = 0               !< chunks left in a probe of the other count
      integer :: before = one_thread       !< count in use before the probe
      logical :: fresh = .true.            !< the next chunk is the first with this count
      integer :: losses = 0                !< team losses since its last win
      integer :: wins = 0                  !< one-thread probes that kept the team in a row
      integer :: first_wait = first_probe  !< chunks before the first team probe (started on one)
      integer :: switches = 0              !< changes of the count
   contains
      procedure :: start => policy_start
      procedure :: chunk => policy_chunk
      procedure :: estimate => policy_estimate
   end type thread_policy_t

contains

   !> Start of the step loop; others: other processes' CPUs during the set-up (negative: unknown).
   !> Starts on the team only when they were idle.
   pure subroutine policy_start(this, others)
      class(thread_policy_t), intent(inout) :: this
      real(wp), intent(in) :: others
      type(thread_policy_t) :: new
      select type (this)
      type is (thread_policy_t)
         this = new
      end select
      this%current = merge(full_team, one_thread, others >= 0 .and. others < quiet_below)
      this%first_wait = merge(probe_every, first_probe, others > busy_above)
   end subroutine policy_start

   !> Seconds per step of a count: the mean of its last counted chunks (robust = .false.: the
   !> cost, also of a team that shares a core and loses a time slice now and then), or the
   !> fastest of the latest three (robust = .true.: a team slow on every chunk, not one or two
   !> slow chunks); 0 when none.
   pure real(wp) function policy_estimate(this, k, robust) result(e)
      class(thread_policy_t), intent(in) :: this
      integer, intent(in) :: k
      logical, intent(in) :: robust
      associate (r => this%recent(:, k), n => this%nrecent(k))
         if (n == 0) then
            e = 0
         else if (.not. robust) then
            e = sum(r(1:n))/n
         else if (n == 1) then
            e = r(1)
         else
            e = minval(r(1:min(n, 3)))
         end if
      end associate
   end function policy_estimate

   !> After a chunk of nsteps steps run with this%current that took seconds; others: other
   !> processes' CPUs over the latest window (negative: unknown or not yet measured). Sets
   !> this%current for the next chunk.
   pure subroutine policy_chunk(this, seconds, nsteps, others)
      class(thread_policy_t), intent(inout) :: this
      real(wp), intent(in) :: seconds, others
      integer, intent(in) :: nsteps
      integer :: k, best
      real(wp) :: e1
      if (nsteps <= 0) return
      k = this%current
      this%chunks = this%chunks + 1
      if (this%fresh) then
         this%fresh = .false.
      else
         this%recent(2:window, k) = this%recent(1:window - 1, k)
         this%recent(1, k) = seconds/nsteps
         this%nrecent(k) = min(this%nrecent(k) + 1, window)
      end if
      if (this%probing > 0) then
         this%probing = this%probing - 1
         ! a first counted chunk of the team much slower than one thread ends the probe
         if (k == full_team .and. this%probing > 0 .and. this%nrecent(k) == 1 .and. this%nrecent(3 - k) > 0) then
            if (this%estimate(k, .false.) > probe_abort*this%estimate(3 - k, .false.)) this%probing = 0
         end if
         if (this%probing > 0) return
         best = k
         if (this%nrecent(3 - k) > 0) then
            if (this%estimate(3 - k, .false.) <= this%estimate(k, .false.)) best = 3 - k
         end if
         if (best == one_thread) then
            call lose(this)
         else if (this%before == one_thread) then
            this%losses = 0
            this%wins = 0
         else
            this%wins = this%wins + 1
         end if
         call use_count(this, best)
         return
      end if
      ! the team slower than one thread: back to one thread now (slow lately, or costly on average)
      e1 = this%estimate(one_thread, .false.)
      if (k == full_team .and. this%nrecent(full_team) >= 2 .and. e1 > 0 .and. &
          (this%estimate(full_team, .true.) > team_back*e1 .or. &
           (this%nrecent(full_team) >= 3 .and. this%estimate(full_team, .false.) > team_back*e1))) then
         call lose(this)
         call use_count(this, one_thread)
         return
      end if
      if (k == one_thread) then
         if (this%chunks >= team_wait(this, others >= 0 .and. others < quiet_below)) &
            call begin_probe(this)
      else
         ! on the team: one thread's time once the team's window is full (the check above needs
         ! it; the team's first chunks after the set-up are slower than later ones) or sooner if
         ! other processes took the other CPUs meanwhile, then rarely
         if ((this%nrecent(one_thread) == 0 .and. (this%nrecent(full_team) >= window .or. &
              (others > busy_above .and. this%nrecent(full_team) >= first_probe - 1))) .or. &
             this%chunks >= min(probe_every*2**min(this%wins + 2, 4), probe_every_max)) &
            call begin_probe(this)
      end if
   end subroutine policy_chunk

   !> Chunks on one thread before the next probe of the team; quiet: the other CPUs are idle.
   pure integer function team_wait(this, quiet)
      type(thread_policy_t), intent(in) :: this
      logical, intent(in) :: quiet
      if (this%nrecent(full_team) == 0 .and. this%losses == 0) then
         team_wait = this%first_wait
      else
         team_wait = min(probe_every*2**min(this%losses, 4), probe_every_max)
      end if
      if (quiet) team_wait = min(team_wait, quiet_gap*2**min(this%losses, 6))
   end function team_wait

   !> A probe of the other count: the team's first chunk wakes its threads and is not counted,
   !> one thread needs no waking (its probe is one chunk shorter).
   pure subroutine begin_probe(this)
      type(thread_policy_t), intent(inout) :: this
      this%before = this%current
      call use_count(this, 3 - this%current)
      this%probing = probe_chunks
      if (this%current == one_thread) then
         this%fresh = .false.
         this%probing = probe_chunks - 1
      end if
   end subroutine begin_probe

   pure subroutine lose(this)
      type(thread_policy_t), intent(inout) :: this
      this%losses = min(this%losses + 1, 30)
      this%wins = 0
   end subroutine lose

   !> The count of the next chunk; a new count restarts its estimate.
   pure subroutine use_count(this, n)
      type(thread_policy_t), intent(inout) :: this
      integer, intent(in) :: n
      this%chunks = 0
      if (n /= this%current) then
         this%switches = this%switches + 1
         this%current = n
         this%fresh = .true.
         this%nrecent(n) = 0
      end if
   end subroutine use_count
end module contact2d_thread_policy
