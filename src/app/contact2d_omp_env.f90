!> Passive OpenMP waiting unless the user chose (issue 13, docs/performance.md "Threads").
!>
!> Threads that wait actively (libgomp's default spin) slow a run many times over when another
!> process shares the cores: measured on this project's machine under load, 2 threads took 33x
!> the time of one thread with active waiting and 0.2x with OMP_WAIT_POLICY=passive. libgomp
!> reads the policy once, when it is loaded, so the program sets it and re-executes itself
!> (same arguments) before anything else happens. Nothing is done when the user set
!> OMP_WAIT_POLICY or GOMP_SPINCOUNT, when only one thread is allowed, or if the re-execution
!> fails (the run then goes on as it is).
module contact2d_omp_env
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_ptr, c_null_char, c_null_ptr, c_loc
   use omp_lib, only: omp_get_max_threads
   implicit none
   private
   public :: omp_env_passive

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

   subroutine omp_env_passive()
      integer :: status, n, i, length, longest
      character(kind=c_char, len=:), allocatable, target :: args(:)
      type(c_ptr), allocatable :: argv(:)
      integer(c_int) :: rc
      call get_environment_variable('OMP_WAIT_POLICY', status=status)
      if (status /= 1) return       ! set (or unreadable): the user's choice
      call get_environment_variable('GOMP_SPINCOUNT', status=status)
      if (status /= 1) return
      if (omp_get_max_threads() <= 1) return
      rc = c_setenv('OMP_WAIT_POLICY'//c_null_char, 'passive'//c_null_char, 1_c_int)
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
   end subroutine omp_env_passive
end module contact2d_omp_env
