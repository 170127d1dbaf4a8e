!> One static run (solver:method = 'static' or --static; docs/static.md): the output safety of
!> an explicit run (lock, temporary file, move into place) around the static engine's own run
!> (contact2d_static_run: solve, write, summary), and the end of the run. The model is read only.
module contact2d_run_static
   use contact2d_kinds, only: i8
   use contact2d_deck, only: deck_t
   use contact2d_model, only: model_t
   use contact2d_static_run, only: static_run
   use contact2d_sys, only: sys_signals_install, sys_signal_pending, sys_strerror
   use contact2d_run_exit, only: opath, keep_partial, fail, fail_now, fail_write, kept_note, stop_interrupted
   implicit none
   private
   public :: run_static

contains

   !> The static engine from the built model to the published file. Decks it cannot honour were
   !> refused by the deck reader or are refused by static_run before anything is written.
   subroutine run_static(deck, model, clock0)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      integer(i8), intent(in) :: clock0   !< system_clock at program start
      integer :: stat, signal
      character(len=:), allocatable :: errmsg, msg, dest
      logical :: written, opened, ended

      call opath%acquire(stat, errmsg)
      if (stat /= 0) call fail(1, errmsg)
      ! SIGINT/SIGTERM: the static engine stops before its next increment and the file ends
      ! with status 'interrupted', as an explicit run's; during the set-up nothing is written
      stat = sys_signals_install()
      if (stat /= 0) call fail(2, 'cannot install the SIGINT/SIGTERM handler: '//sys_strerror(stat))
      call static_run(deck, model, opath%partial, .false., clock0, stat, errmsg, sidecar=opath%xmf_partial, &
                      target=opath%target, written=written, opened=opened, &
                      replacing=opath%replacing, ended=ended)
      if (written) then
         dest = opath%destination(ended)
         keep_partial = .true.   ! complete: a move that fails (named in its message) keeps it
         call opath%publish(signal, msg, ended)
         if (signal /= 0) call fail(2, msg)
         keep_partial = dest /= opath%target   ! kept at its temporary name: not removed below
      else if (stat == 2 .and. opened) then
         call fail_write(errmsg//'; what was written so far is in '//opath%partial)
      else if (stat == 2) then
         call fail_now(2, errmsg, .false.)   ! the file could not be created: no file kept
      end if
      signal = sys_signal_pending()
      if (signal /= 0) then
         call opath%abandon(keep_partial)
         if (written) then
            msg = '; '//dest//" holds the increments done (status 'interrupted')"//kept_note(dest)
         else
            msg = ' during the static engine''s set-up; nothing was written'
         end if
         call stop_interrupted(signal, msg)
      end if
      if (stat /= 0) call fail(stat, errmsg)
      call opath%abandon(keep_partial)
   end subroutine run_static
end module contact2d_run_static
