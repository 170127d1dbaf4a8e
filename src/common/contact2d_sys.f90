!> POSIX services for output safety and interrupts (C in contact2d_sys.c, bound here):
!> file kinds and identities, the output lock, no-clobber publish, the SIGINT/SIGTERM flag and
!> the system's reason of the last HDF5 failure, and the files this process created (only those
!> are moved into place or removed: sys_publish, sys_remove_own). Every routine returns 0, an
!> errno value or one of the sys_e* refusals; sys_strerror turns it into words.
module contact2d_sys
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_long_long, c_null_char, c_int64_t
   implicit none
   private
   public :: sys_signals_install, sys_signal_pending, sys_signal_raise, sys_strerror, sys_path_info, sys_dir_writable
   public :: sys_lock, sys_unlock, sys_publish, sys_remove, sys_h5_reason, sys_getpid, sys_exit_now, sys_write_file
   public :: sys_lock_check, sys_remove_own, sys_h5_register, sys_h5_claim_failed
   public :: sys_esymlink, sys_enotreg, sys_elinks, sys_enotlock, sys_enotown
   public :: kind_missing, kind_file, kind_directory, kind_device, kind_fifo, kind_socket, &
             kind_other, kind_dangling, kind_names

   !> What a path is (sys_path_info).
   integer, parameter :: kind_missing = 0, kind_file = 1, kind_directory = 2, kind_device = 3, &
                         kind_fifo = 4, kind_socket = 5, kind_other = 6, kind_dangling = 7
   !> Refusals that are no errno (contact2d_sys.c, C2D_E*): the path is a symbolic link, not a
   !> regular file, has other hard links, holds something else than a lock, was not created by
   !> this process.
   integer, parameter :: sys_esymlink = -1, sys_enotreg = -2, sys_elinks = -3, sys_enotlock = -4, &
                         sys_enotown = -5
   character(len=24), parameter :: kind_names(0:7) = [character(len=24) :: 'missing', 'regular file', &
      'directory', 'device', 'FIFO', 'socket', 'special file', 'dangling symbolic link']

   interface
      integer(c_int) function c2d_signals_install() bind(C, name='c2d_signals_install')
         import :: c_int
      end function c2d_signals_install
      integer(c_int) function c2d_signal_pending() bind(C, name='c2d_signal_pending')
         import :: c_int
      end function c2d_signal_pending
      subroutine c2d_signal_raise(sig) bind(C, name='c2d_signal_raise')
         import :: c_int
         integer(c_int), value :: sig
      end subroutine c2d_signal_raise
      subroutine c2d_strerror(err, buf, len) bind(C, name='c2d_strerror')
         import :: c_int, c_char
         integer(c_int), value :: err, len
         character(kind=c_char) :: buf(*)
      end subroutine c2d_strerror
      integer(c_int) function c2d_path_info(path, kind, dev, ino, size) bind(C, name='c2d_path_info')
         import :: c_int, c_char, c_long_long
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), intent(out) :: kind
         integer(c_long_long), intent(out) :: dev, ino, size
      end function c2d_path_info
      integer(c_int) function c2d_dir_writable(dir) bind(C, name='c2d_dir_writable')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: dir(*)
      end function c2d_dir_writable
      integer(c_int) function c2d_lock(path, fd) bind(C, name='c2d_lock')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), intent(out) :: fd
      end function c2d_lock
      integer(c_int) function c2d_lock_check(path) bind(C, name='c2d_lock_check')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
      end function c2d_lock_check
      integer(c_int) function c2d_remove_own(path) bind(C, name='c2d_remove_own')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
      end function c2d_remove_own
      integer(c_int) function c2d_h5_register(file) bind(C, name='c2d_h5_register')
         import :: c_int, c_int64_t
         integer(c_int64_t), value :: file
      end function c2d_h5_register
      integer(c_int) function c2d_h5_claim_failed(path) bind(C, name='c2d_h5_claim_failed')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
      end function c2d_h5_claim_failed
      subroutine c2d_unlock(path, fd) bind(C, name='c2d_unlock')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value :: fd
      end subroutine c2d_unlock
      integer(c_int) function c2d_publish(from, to, replace) bind(C, name='c2d_publish')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: from(*), to(*)
         integer(c_int), value :: replace
      end function c2d_publish
      integer(c_int) function c2d_write_file(path, buf, len) bind(C, name='c2d_write_file')
         import :: c_int, c_char, c_long_long
         character(kind=c_char), intent(in) :: path(*), buf(*)
         integer(c_long_long), value :: len
      end function c2d_write_file
      integer(c_int) function c2d_remove(path) bind(C, name='c2d_remove')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
      end function c2d_remove
      subroutine c2d_h5_reason(buf, len) bind(C, name='c2d_h5_reason')
         import :: c_int, c_char
         character(kind=c_char) :: buf(*)
         integer(c_int), value :: len
      end subroutine c2d_h5_reason
      subroutine c2d_exit_now(code) bind(C, name='c2d_exit_now')
         import :: c_int
         integer(c_int), value :: code
      end subroutine c2d_exit_now
      integer(c_int) function getpid() bind(C, name='getpid')
         import :: c_int
      end function getpid
   end interface

contains

   !> Catch SIGINT and SIGTERM: the run stops at the end of the current step (0 or errno).
   integer function sys_signals_install() result(err)
      err = int(c2d_signals_install())
   end function sys_signals_install

   !> The signal received so far (0: none). Cheap; called once per step.
   integer function sys_signal_pending() result(sig)
      sig = int(c2d_signal_pending())
   end function sys_signal_pending

   !> Record signal sig as received (several processes: one that reached another rank).
   subroutine sys_signal_raise(sig)
      integer, intent(in) :: sig
      call c2d_signal_raise(int(sig, c_int))
   end subroutine sys_signal_raise

   !> End the process now with the code, without exit handlers (the caller flushes its units).
   subroutine sys_exit_now(code)
      integer, intent(in) :: code
      call c2d_exit_now(int(code, c_int))
   end subroutine sys_exit_now

   integer function sys_getpid() result(pid)
      pid = int(getpid())
   end function sys_getpid

   !> The system's text for an errno value.
   function sys_strerror(err) result(text)
      integer, intent(in) :: err
      character(len=:), allocatable :: text
      character(kind=c_char, len=256) :: buf
      call c2d_strerror(int(err, c_int), buf, int(len(buf), c_int))
      text = cstring(buf)
   end function sys_strerror

   !> Kind (kind_* above), identity and size of a path; err /= 0 if stat failed other than ENOENT.
   subroutine sys_path_info(path, kind, dev, ino, size, err)
      character(len=*), intent(in) :: path
      integer, intent(out) :: kind, err
      integer(c_long_long), intent(out) :: dev, ino, size
      integer(c_int) :: k
      err = int(c2d_path_info(path//c_null_char, k, dev, ino, size))
      kind = int(k)
   end subroutine sys_path_info

   !> 0 if a file can be created in dir, else the errno.
   integer function sys_dir_writable(dir) result(err)
      character(len=*), intent(in) :: dir
      err = int(c2d_dir_writable(dir//c_null_char))
   end function sys_dir_writable

   !> Exclusive non-blocking lock on a lock file (created); fd to release it with sys_unlock.
   integer function sys_lock(path, fd) result(err)
      character(len=*), intent(in) :: path
      integer, intent(out) :: fd
      integer(c_int) :: f
      f = -1
      err = int(c2d_lock(path//c_null_char, f))
      fd = int(f)
   end function sys_lock

   !> 0 if path may serve as a lock file (missing, or a regular file with one link holding a
   !> process id or nothing: a stale lock), else sys_esymlink, sys_enotreg, sys_elinks,
   !> sys_enotlock or an errno. Writes nothing.
   integer function sys_lock_check(path) result(err)
      character(len=*), intent(in) :: path
      err = int(c2d_lock_check(path//c_null_char))
   end function sys_lock_check

   !> Remove path only if it is a file this process created (a missing file is no error;
   !> anything else is left as it is and sys_enotown returned).
   integer function sys_remove_own(path) result(err)
      character(len=*), intent(in) :: path
      err = int(c2d_remove_own(path//c_null_char))
   end function sys_remove_own

   !> Remember the HDF5 file just created exclusively on file id `file` as this process's own.
   integer function sys_h5_register(file) result(err)
      integer(c_int64_t), intent(in) :: file
      err = int(c2d_h5_register(file))
   end function sys_h5_register

   !> After an exclusive HDF5 create of path failed: the file there is this process's own unless
   !> the name existed (EEXIST in the HDF5 error stack). 0 if claimed, else ENOENT or EEXIST.
   integer function sys_h5_claim_failed(path) result(err)
      character(len=*), intent(in) :: path
      err = int(c2d_h5_claim_failed(path//c_null_char))
   end function sys_h5_claim_failed

   !> Remove the lock file (if the path still names it) and release the lock.
   subroutine sys_unlock(path, fd)
      character(len=*), intent(in) :: path
      integer, intent(in) :: fd
      call c2d_unlock(path//c_null_char, int(fd, c_int))
   end subroutine sys_unlock

   !> Move from -> to; without replace an existing `to` is an error (EEXIST), atomically. `from`
   !> must be a file this process created (else sys_enotown, nothing moved).
   integer function sys_publish(from, to, replace) result(err)
      character(len=*), intent(in) :: from, to
      logical, intent(in) :: replace
      err = int(c2d_publish(from//c_null_char, to//c_null_char, merge(1_c_int, 0_c_int, replace)))
   end function sys_publish

   !> Write text as the whole content of path, created (it must not exist; a link there is not
   !> followed); 0 or the errno of the create or the first failed write, fsync or close.
   integer function sys_write_file(path, text) result(err)
      character(len=*), intent(in) :: path, text
      err = int(c2d_write_file(path//c_null_char, text, int(len(text), c_long_long)))
   end function sys_write_file

   !> Remove a regular file (a missing file is no error; a link or another kind of file is left
   !> alone: sys_esymlink, sys_enotreg). Only for the old sidecar a user's --force gives up
   !> (docs/output.md); temporary files go with sys_remove_own.
   integer function sys_remove(path) result(err)
      character(len=*), intent(in) :: path
      err = int(c2d_remove(path//c_null_char))
   end function sys_remove

   !> The system's reason stored in the HDF5 error stack by the last failed call ('' if none).
   function sys_h5_reason() result(text)
      character(len=:), allocatable :: text
      character(kind=c_char, len=256) :: buf
      buf = ''
      call c2d_h5_reason(buf, int(len(buf), c_int))
      text = cstring(buf)
   end function sys_h5_reason

   function cstring(buf) result(s)
      character(len=*), intent(in) :: buf
      character(len=:), allocatable :: s
      integer :: n
      n = index(buf, c_null_char)
      if (n == 0) then
         s = trim(buf)
      else
         s = buf(1:n - 1)
      end if
   end function cstring
end module contact2d_sys
