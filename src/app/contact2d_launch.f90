!> contact2d: the launcher. Sets a bounded spin-then-sleep OpenMP wait unless the user chose one,
!> then starts the program itself, contact2d-solver, from the same directory with the same
!> arguments (docs/performance.md "Threads that never hurt" and "Start-up").
!>
!> libgomp's default wait spins for 300 000 pause instructions (about 12 ms on this project's
!> machine) before it sleeps: with another process on the cores, a team of 2 threads then took
!> 30-40x the time of one thread. Waiting passively (OMP_WAIT_POLICY=passive: sleep at once)
!> removes that, but costs a futex wake-up per parallel region, and on the project's VM the
!> kernel places the woken thread on the waker's vCPU (measured: both threads on one vCPU in
!> 96-100 % of the steps, an idle vCPU beside them), so two threads gave no gain at all. A short
!> spin (GOMP_SPINCOUNT = spin_count, about 80 us here: longer than the serial part of a step,
!> far shorter than a scheduler time slice) keeps the team on its own cores between the
!> parallel parts of a step and still lets a thread that waits longer sleep.
!>
!> libgomp reads the setting once, when it is loaded, before any code of the program runs, so it
!> has to be in the environment before the program starts. The program used to set it and
!> re-execute itself, which cost a second load of its ~50 shared libraries (HDF5 and its network
!> stack, CHOLMOD, OpenBLAS: ~14 ms per run). This launcher links only the Fortran run-time, so
!> the solver is loaded once. Nothing is set when the user set OMP_WAIT_POLICY or
!> GOMP_SPINCOUNT, or a thread binding (OMP_PROC_BIND, OMP_PLACES, GOMP_CPU_AFFINITY): the
!> user's choice stands. With one thread the setting has no effect.
program contact2d_launch
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_ptr, c_size_t, c_null_char, c_null_ptr, c_loc
   use, intrinsic :: iso_fortran_env, only: error_unit
   implicit none

   !> the program the launcher starts, in the launcher's own directory
   character(len=*), parameter :: solver_name = 'contact2d-solver'
   !> libgomp spin count (pause instructions, about 40 ns each on the project's machine) before
   !> a waiting thread sleeps
   character(len=*), parameter :: spin_count = '2000'
   character(len=*), parameter :: user_vars(5) = [character(len=17) :: 'OMP_WAIT_POLICY', 'GOMP_SPINCOUNT', &
                                                  'OMP_PROC_BIND', 'OMP_PLACES', 'GOMP_CPU_AFFINITY']

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
      integer(c_size_t) function c_readlink(path, buf, size) bind(C, name='readlink')
         import :: c_char, c_size_t
         character(kind=c_char), intent(in) :: path(*)
         character(kind=c_char), intent(out) :: buf(*)
         integer(c_size_t), value :: size
      end function c_readlink
   end interface

   integer :: status, n, i, length, longest, cut
   character(kind=c_char, len=:), allocatable, target :: args(:)
   type(c_ptr), allocatable :: argv(:)
   character(kind=c_char, len=4096) :: self
   character(len=:), allocatable :: solver
   integer(c_size_t) :: nself
   integer(c_int) :: rc
   logical :: user_set

   user_set = .false.
   do i = 1, size(user_vars)
      call get_environment_variable(trim(user_vars(i)), status=status)
      if (status /= 1) user_set = .true.   ! set (or unreadable): the user's choice
   end do
   if (.not. user_set) rc = c_setenv('GOMP_SPINCOUNT'//c_null_char, spin_count//c_null_char, 1_c_int)

   ! the solver sits beside the launcher: the launcher's own path (/proc/self/exe, else argv(0))
   nself = c_readlink('/proc/self/exe'//c_null_char, self, int(len(self) - 1, c_size_t))
   if (nself > 0 .and. nself < len(self) - 1) then
      solver = self(1:nself)
   else
      call get_command_argument(0, self, length=length)
      solver = self(1:min(length, len(self)))
   end if
   cut = index(solver, '/', back=.true.)
   solver = solver(1:cut)//solver_name

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
   rc = c_execv(solver//c_null_char, argv)
   ! only reached if execv failed
   write (error_unit, '(a)') 'contact2d: error: cannot start the solver '//solver// &
      ' (it is built beside this launcher: rebuild, or run it directly)'
   stop 1, quiet=.true.
end program contact2d_launch
