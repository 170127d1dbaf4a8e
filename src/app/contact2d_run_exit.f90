!> How a run stops: one line on stderr, the output lock released, the exit code (docs/output.md,
!> "Output safety"; exit 1: bad input or usage, exit 2: the run failed, 128 + signal: interrupted).
!> Only the driver and the engines' run routines call it; library routines return stat/errmsg.
module contact2d_run_exit
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   use contact2d_version, only: program_name
   use contact2d_strings, only: printable
   use contact2d_outpath, only: outpath_t
   use contact2d_output, only: output_t
   use contact2d_sys, only: sys_exit_now
   use contact2d_comm, only: comm_failing
   implicit none
   private
   public :: opath, keep_partial, fail, fail_now, fail_write, check_output, kept_note, stop_interrupted, run_ended

   !> This run's output names and lock: fail() releases them (docs/output.md, output safety).
   type(outpath_t), save :: opath
   !> Keep OUT.h5.<pid>.partial when the run fails (it holds what was written so far).
   logical, save :: keep_partial = .false.

contains

   !> One line on stderr, release the output lock (removing temporary files unless the partial
   !> result is worth keeping), exit with the code.
   subroutine fail(code, msg)
      integer, intent(in) :: code
      character(len=*), intent(in) :: msg
      ! one line whatever the message quotes (a --set value with a newline, an escape sequence)
      write (error_unit, '(a)') program_name//': error: '//printable(msg)
      call opath%abandon(keep_partial)
      call comm_failing()
      stop code, quiet=.true.
   end subroutine fail

   !> fail() after a failed write: the file is left as it is on disk (no HDF5 exit handler
   !> touches it again), the lock released, exit 2.
   subroutine fail_write(msg)
      character(len=*), intent(in) :: msg
      call fail_now(2, msg, .true.)
   end subroutine fail_write

   !> fail() without exit handlers: after an HDF5 write failed, the library's own exit handler
   !> would flush the broken file again (seen to crash, SIGSEGV, when the output could not even
   !> be created on a full disk). keep: keep the temporary file (it holds what was flushed).
   subroutine fail_now(code, msg, keep)
      integer, intent(in) :: code
      character(len=*), intent(in) :: msg
      logical, intent(in) :: keep
      write (error_unit, '(a)') program_name//': error: '//printable(msg)
      call opath%abandon(keep)
      flush (output_unit)
      flush (error_unit)
      call comm_failing()
      call sys_exit_now(code)
   end subroutine fail_now

   !> Stop at once (exit 2) when a write to the output failed; what was flushed before stays
   !> readable in the temporary file, which is named in the message.
   subroutine check_output(out)
      type(output_t), intent(in) :: out
      if (.not. out%file%ok()) call fail_write(out%file%errmsg//'; the run stopped; what was written before is in '// &
                                               opath%partial)
   end subroutine check_output

   !> Whether a run with this end status reached its end: not stopped by a signal, a blow-up or a
   !> failure of the contact solver (explicit) or of the static engine. A run that did not reach
   !> its end has no validity range and does not replace an existing result (docs/output.md).
   logical function run_ended(status)
      character(len=*), intent(in) :: status
      run_ended = .not. any(status == [character(len=24) :: 'interrupted', 'blow-up', 'contact solver failure', &
                                       'static solver failure'])
   end function run_ended

   !> '' when the run's file went to the output, else (a run that did not reach its end would
   !> have replaced an existing result: outpath destination) a note that the result was kept.
   function kept_note(dest) result(note)
      character(len=*), intent(in) :: dest
      character(len=:), allocatable :: note
      note = ''
      if (dest /= opath%target) note = '; the existing '//opath%target//' is kept (--force replaces a result '// &
                                       'only with a run that reaches its end)'
   end function kept_note

   !> 'interrupted by SIGINT|SIGTERM' and what follows on stderr, exit 128 + signal.
   subroutine stop_interrupted(signal, msg)
      integer, intent(in) :: signal   !< 2 (SIGINT) or 15 (SIGTERM)
      character(len=*), intent(in) :: msg
      write (error_unit, '(a)') program_name//': interrupted by '//trim(merge('SIGINT ', 'SIGTERM', signal == 2))//msg
      call comm_failing()
      stop 128 + signal, quiet=.true.
   end subroutine stop_interrupted
end module contact2d_run_exit
