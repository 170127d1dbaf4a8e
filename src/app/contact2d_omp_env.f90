!> Bounded spin-then-sleep OpenMP waiting unless the user chose (issue 13, docs/performance.md
!> "Threads that never hurt").
!>
!> libgomp's default wait spins for 300 000 pause instructions (about 12 ms on this project's
!> machine) before it sleeps: with another process on the cores, a team of 2 threads then took
!> 30-40x the time of one thread. Waiting passively (OMP_WAIT_POLICY=passive: sleep at once)
!> removes that, but costs a futex wake-up per parallel region, and on the project's VM the
!> kernel places the woken thread on the waker's vCPU (measured: both threads on one vCPU in
!> 96-100 % of the steps, an idle vCPU beside them), so two threads gave no gain at all. A short
!> spin (GOMP_SPINCOUNT = spin_count, about 80 us here: longer than the serial part of a step,
!> far shorter than a scheduler time slice) keeps the team on its own cores between the
!> parallel parts of a step and still lets a thread that waits longer sleep. libgomp reads the
!> setting once, when it is loaded, so the program sets it and re-executes itself (same
!> arguments) before anything else happens. Nothing is done when the user set
!> OMP_WAIT_POLICY or GOMP_SPINCOUNT, when the user set a thread binding (OMP_PROC_BIND,
!> OMP_PLACES, GOMP_CPU_AFFINITY: libgomp has then bound this process to one CPU, a binding the
!> re-executed program would inherit), when only one thread is allowed, or if the
!> re-execution fails (the run then goes on as it is).
module contact2d_omp_env
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_ptr, c_null_char, c_null_ptr, c_loc
   use omp_lib, only: omp_get_max_threads
   implicit none
   private
   public :: omp_env_wait

   !> libgomp spin count (pause instructions, about 40 ns each on the project's machine) before
   !> a waiting thread sleeps
   character(len=*), parameter :: spin_count = '2000'

   interface
      integer(c_int) function c_setenv(name, value, overwrite) bind(C, name='setenv')
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: name(*), value(*)
         integer(c_int), value :: overwrite
      end function c_setenv
      integer(c_int) function c_execv(path, argv) bind(C, name='execv')
         import :: c_char, c_int, c_ptr
         character(kind=c_char), intent(in) :: path(*)
         type(c_ptr), intent(in) :: argv(*)
      end function c_execv
   end interface

contains

   subroutine omp_env_wait()
      integer :: status, n, i, length, longest
      character(kind=c_char, len=:), allocatable, target :: args(:)
      type(c_ptr), allocatable :: argv(:)
      integer(c_int) :: rc
      character(len=*), parameter :: user_vars(5) = [character(len=17) :: 'OMP_WAIT_POLICY', 'GOMP_SPINCOUNT', &
                                                     'OMP_PROC_BIND', 'OMP_PLACES', 'GOMP_CPU_AFFINITY']
      do i = 1, size(user_vars)
         call get_environment_variable(trim(user_vars(i)), status=status)
         if (status /= 1) return   ! set (or unreadable): the user's choice
      end do
      if (omp_get_max_threads() <= 1) return
      rc = c_setenv('GOMP_SPINCOUNT'//c_null_char, spin_count//c_null_char, 1_c_int)
      if (rc /= 0) return
      n = command_argument_count()
      longest = 1
      do i = 0, n
         call get_command_argument(i, length=length)
         longest = max(longest, length + 1)
      end do
      allocate (character(kind=c_char, len=longest) :: args(0:n))
      allocate (argv(0:n + 1))
      do i = 0, n
         call get_command_argument(i, args(i), length=length)
         args(i)(length + 1:length + 1) = c_null_char   ! exact length: trailing blanks kept
         argv(i) = c_loc(args(i))
      end do
      argv(n + 1) = c_null_ptr
      rc = c_execv('/proc/self/exe'//c_null_char, argv)
      ! only reached if execv failed: go on with the default policy
   end subroutine omp_env_wait
end module contact2d_omp_env
