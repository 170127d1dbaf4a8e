!> Output safety (docs/output.md, "Output safety"): where a run writes, and when its files take
!> their names.
!>
!> - The output OUT.h5 (and its sidecar OUT.xmf) are checked before any set-up: not the deck
!>   (same device and inode, so also through links), not a directory, device, FIFO or dangling
!>   link, a folder that exists and can be written, names the system accepts; an existing file
!>   needs --force. Each refusal is one line with the system's reason where there is one.
!> - A run writes OUT.h5.<pid>.partial (and OUT.xmf.<pid>.partial) beside the target, or, when
!>   either name is taken (an earlier run's kept file: in a container every run may be PID 1),
!>   OUT.h5.<pid>.<k>.partial with the smallest free k >= 1, chosen under the lock; it moves
!>   them into place only when complete, at every end (converged, not converged, blow-up,
!>   contact failure, interrupted). Without --force the move never replaces a file (link +
!>   unlink, atomic); with --force it is one rename(). An existing result is therefore intact
!>   until the new one is complete. A run killed (kill -9) or stopped by a write error leaves
!>   OUT.h5.<pid>.partial, readable up to its last flush.
!> - The lock .OUT.h5.lock (flock, beside the target) is held from before the file is created
!>   until it is in place: a second run aimed at the same output refuses with one line. So is
!>   .OUT.xmf.lock for the sidecar, which two outputs may share (run.h5 and run.dat). A lock path
!>   that is a symbolic link, not a regular file, or a file holding anything but a process id is
!>   refused (one line), never followed, truncated or removed; a stale lock is taken over.
!> - The run moves into place or removes only files it created itself (contact2d_sys registers
!>   them by device and inode); the one exception is the replaced result's old sidecar below.
!> - --force replaces this output's own sidecar only: an existing OUT.xmf that points at another
!>   HDF5 file is refused; with output:xdmf = .false. the old sidecar of OUT.h5 (which would
!>   describe the replaced file) is removed once the new result is in place, under the sidecar's
!>   lock, if it is still a regular file describing OUT.h5 (a symbolic link is left alone).
module contact2d_outpath
   use, intrinsic :: iso_c_binding, only: c_long_long
   use contact2d_strings, only: str
   use contact2d_sys, only: sys_path_info, sys_strerror, sys_dir_writable, sys_lock, sys_unlock, &
                            sys_publish, sys_remove, sys_remove_own, sys_getpid, sys_lock_check, &
                            kind_missing, kind_file, kind_directory, kind_dangling, kind_names
   implicit none
   private
   public :: outpath_t, sidecar_name

   !> Names of one run's output files and the state of its lock.
   type :: outpath_t
      character(len=:), allocatable :: target       !< OUT.h5 as given
      character(len=:), allocatable :: partial      !< OUT.h5.<pid>.partial (or .<pid>.<k>.partial)
      character(len=:), allocatable :: xmf          !< OUT.xmf ('' without sidecar)
      character(len=:), allocatable :: xmf_partial  !< OUT.xmf.<pid>.partial (same suffix as partial)
      character(len=:), allocatable :: lock         !< .OUT.h5.lock in the same folder
      character(len=:), allocatable :: xlock        !< .OUT.xmf.lock ('' without sidecar)
      character(len=:), allocatable :: stale        !< OUT.xmf of the replaced result, to remove
      logical :: force = .false.
      !> this process writes the output (rank 0 of several, or the only one); the other ranks of
      !> mpirun take no lock and leave every file alone (docs/mpi.md)
      logical :: writer = .true.
      !> --force and OUT.h5 existed when the lock was taken: only a run that reaches its end
      !> replaces it (destination)
      logical :: replacing = .false.
      integer :: fd = -1                            !< lock descriptor (-1: not locked)
      integer :: xfd = -1                           !< sidecar lock descriptor
   contains
      procedure :: check => outpath_check
      procedure :: acquire => outpath_acquire
      procedure :: publish => outpath_publish
      procedure :: destination => outpath_destination
      procedure :: abandon => outpath_abandon
   end type outpath_t

contains

   !> The XDMF sidecar of an HDF5 path: the extension replaced by .xmf (or .xmf appended).
   function sidecar_name(h5path) result(xmf)
      character(len=*), intent(in) :: h5path
      character(len=:), allocatable :: xmf
      integer :: dot, slash
      dot = index(h5path, '.', back=.true.)
      slash = index(h5path, '/', back=.true.)
      if (dot > slash + 1) then
         xmf = h5path(1:dot - 1)//'.xmf'
      else
         xmf = h5path//'.xmf'
      end if
   end function sidecar_name

   !> Check the output (and sidecar) names before any set-up. stat = 1 with one line on refusal.
   !> mesh_path: the deck's Gmsh mesh or geometry ('' for none), an input like the deck.
   subroutine outpath_check(this, target, deck_path, mesh_path, force, sidecar, stat, errmsg)
      class(outpath_t), intent(inout) :: this
      character(len=*), intent(in) :: target, deck_path, mesh_path
      logical, intent(in) :: force, sidecar
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer(c_long_long) :: ddev(2), dino(2), dsize
      integer :: dkind(2), err, slash
      character(len=:), allocatable :: dir, base, pid, refers

      stat = 1
      this%force = force
      this%target = target
      pid = str(sys_getpid())
      this%partial = target//'.'//pid//'.partial'
      slash = index(target, '/', back=.true.)
      dir = target(1:slash)
      base = target(slash + 1:)
      this%lock = dir//'.'//base//'.lock'
      this%xmf = ''
      this%xmf_partial = ''
      this%xlock = ''
      this%stale = ''
      if (len(target) == 0) then
         errmsg = 'the output file name is empty'
         return
      end if
      if (len(base) == 0) then
         errmsg = "output '"//target//"' names a directory, not a file"
         return
      end if
      ! the inputs an output must not be: the deck, the mesh (by device and inode)
      call sys_path_info(deck_path, dkind(1), ddev(1), dino(1), dsize, err)
      if (err /= 0) dkind(1) = kind_missing
      dkind(2) = kind_missing
      if (len(mesh_path) > 0) call sys_path_info(mesh_path, dkind(2), ddev(2), dino(2), dsize, err)
      if (err /= 0) dkind(2) = kind_missing
      call check_one(target, 'output', errmsg)
      if (len(errmsg) > 0) return
      if (sidecar) then
         this%xmf = sidecar_name(target)
         this%xmf_partial = this%xmf//'.'//pid//'.partial'
         if (this%xmf == target) then
            errmsg = "output '"//target//"' would be overwritten by its own XDMF sidecar; "// &
                     "choose a name not ending in .xmf (or set output:xdmf = .false.)"
            return
         end if
         call check_one(this%xmf, 'XDMF sidecar', errmsg)
         if (len(errmsg) > 0) return
         slash = index(this%xmf, '/', back=.true.)
         this%xlock = this%xmf(1:slash)//'.'//this%xmf(slash + 1:)//'.lock'
         refers = sidecar_refers(this%xmf)
         if (len(refers) > 0 .and. refers /= base) then
            errmsg = "XDMF sidecar '"//this%xmf//"' exists and describes '"//refers//"', not '"//base// &
                     "'; --force replaces only this output's own files: remove it, choose another name "// &
                     'with -o, or set output:xdmf = .false.'
            return
         end if
      else if (force) then
         ! the sidecar of the result being replaced would describe the old file: removed at the
         ! end, under its lock (no other run publishes it meanwhile), if it still describes it
         if (sidecar_refers(sidecar_name(target)) == base) then
            this%stale = sidecar_name(target)
            slash = index(this%stale, '/', back=.true.)
            this%xlock = this%stale(1:slash)//'.'//this%stale(slash + 1:)//'.lock'
         end if
      end if
      ! the folder must exist and take new files (the system's reason otherwise)
      if (len(dir) == 0) dir = './'
      err = sys_dir_writable(dir)
      if (err /= 0) then
         errmsg = "cannot write output '"//target//"': folder '"//dir//"': "//sys_strerror(err)
         return
      end if
      ! the temporary and lock names must be valid too (a name near the length limit)
      call check_name(this%partial, errmsg)
      if (len(errmsg) > 0) return
      if (sidecar) then
         call check_name(this%xmf_partial, errmsg)
         if (len(errmsg) > 0) return
      end if
      ! the lock names: valid, and not a link or another file (refused now, before any set-up;
      ! acquire checks again when it takes the lock)
      err = sys_lock_check(this%lock)
      if (err /= 0) then
         errmsg = lock_refusal("output '"//target//"'", this%lock, err)
         return
      end if
      if (len(this%xlock) > 0) then
         err = sys_lock_check(this%xlock)
         if (err /= 0) then
            errmsg = lock_refusal("XDMF sidecar '"//sidecar_name(target)//"'", this%xlock, err)
            return
         end if
      end if
      stat = 0
      errmsg = ''
   contains
      subroutine check_one(path, what, msg)
         character(len=*), intent(in) :: path, what
         character(len=:), allocatable, intent(out) :: msg
         integer(c_long_long) :: dev, ino, size
         integer :: kind, e
         msg = ''
         call sys_path_info(path, kind, dev, ino, size, e)
         if (e /= 0) then
            msg = 'cannot write '//what//" '"//path//"': "//sys_strerror(e)
         else if (kind == kind_dangling) then
            msg = what//" '"//path//"' is a dangling symbolic link: "//sys_strerror(2)
         else if (kind == kind_directory) then
            msg = what//" '"//path//"' is a directory: "//sys_strerror(21)
         else if (kind /= kind_missing .and. kind /= kind_file) then
            msg = what//" '"//path//"' is a "//trim(kind_names(kind))//', not a regular file'
         else if (kind == kind_file .and. dkind(1) == kind_file .and. dev == ddev(1) .and. ino == dino(1)) then
            msg = what//" '"//path//"' is the deck '"//deck_path//"' itself; choose another name with -o"
         else if (kind == kind_file .and. dkind(2) == kind_file .and. dev == ddev(2) .and. ino == dino(2)) then
            msg = what//" '"//path//"' is the deck's mesh:file '"//mesh_path//"' itself; choose another name with -o"
         else if (kind == kind_file .and. .not. force) then
            msg = what//" '"//path//"' exists; use --force to overwrite it or -o to choose another"
         end if
      end subroutine check_one
      subroutine check_name(path, msg)
         character(len=*), intent(in) :: path
         character(len=:), allocatable, intent(out) :: msg
         integer(c_long_long) :: dev, ino, size
         integer :: kind, e
         msg = ''
         call sys_path_info(path, kind, dev, ino, size, e)
         if (e /= 0) msg = "cannot write output '"//target//"': its temporary name '"//path//"': "//sys_strerror(e)
      end subroutine check_name
   end subroutine outpath_check

   !> Take the lock; without --force re-check under the lock that the targets are still free.
   subroutine outpath_acquire(this, stat, errmsg)
      class(outpath_t), intent(inout) :: this
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer(c_long_long) :: dev, ino, size
      integer :: err, kind, e
      if (.not. this%writer) then
         stat = 0
         errmsg = ''
         this%partial = ''
         this%xmf_partial = ''
         return
      end if
      stat = 1
      err = sys_lock(this%lock, this%fd)
      if (err == 11) then   ! EWOULDBLOCK = EAGAIN
         this%fd = -1
         errmsg = "output '"//this%target//"' is being written by another run (lock "//this%lock// &
                  " held); wait for it or choose another name with -o"
         return
      else if (err /= 0) then
         this%fd = -1
         errmsg = lock_refusal("output '"//this%target//"'", this%lock, err)
         return
      end if
      if (len(this%xlock) > 0) then
         err = sys_lock(this%xlock, this%xfd)
         if (err /= 0) then
            this%xfd = -1
            call this%abandon(.false.)
            if (err == 11) then
               errmsg = "XDMF sidecar '"//sidecar_name(this%target)//"' is being written by another run (lock "// &
                        this%xlock//" held); wait for it or choose another name with -o"
            else
               errmsg = lock_refusal("XDMF sidecar '"//sidecar_name(this%target)//"'", this%xlock, err)
            end if
            return
         end if
      end if
      call sys_path_info(this%target, kind, dev, ino, size, e)
      this%replacing = kind /= kind_missing
      if (this%replacing .and. .not. this%force) then
         call this%abandon(.false.)
         errmsg = "output file '"//this%target//"' exists; use --force to overwrite it or -o to choose another"
         return
      end if
      call choose_temporaries(this, errmsg)
      if (len(errmsg) > 0) then
         call this%abandon(.false.)
         return
      end if
      stat = 0
      errmsg = ''
   end subroutine outpath_acquire

   !> The temporary names, chosen under the lock: OUT.h5.<pid>.partial and OUT.xmf.<pid>.partial,
   !> or, when either name is taken by anything (an earlier run's kept file: with PID namespaces
   !> every run in a container may have the same pid; a link), OUT.h5.<pid>.<k>.partial and
   !> OUT.xmf.<pid>.<k>.partial with the smallest k >= 1 for which both are free. A taken name
   !> is left alone; errmsg /= '' if none of 1000 is free or a name cannot be looked up.
   subroutine choose_temporaries(this, errmsg)
      class(outpath_t), intent(inout) :: this
      character(len=:), allocatable, intent(out) :: errmsg
      character(len=:), allocatable :: suffix, pid
      integer, parameter :: tries = 1000
      integer :: k
      logical :: taken
      pid = str(sys_getpid())
      do k = 0, tries - 1
         suffix = '.'//pid//'.partial'
         if (k > 0) suffix = '.'//pid//'.'//str(k)//'.partial'
         call name_taken(this%target//suffix, taken, errmsg)
         if (len(errmsg) > 0) return
         if (.not. taken .and. len(this%xmf) > 0) call name_taken(this%xmf//suffix, taken, errmsg)
         if (len(errmsg) > 0) return
         if (taken) cycle
         this%partial = this%target//suffix
         if (len(this%xmf) > 0) this%xmf_partial = this%xmf//suffix
         return
      end do
      errmsg = "cannot write output '"//this%target//"': its "//str(tries)//" temporary names "// &
               this%target//'.'//pid//'[.<k>].partial are all taken; move old .partial files away'
   contains
      subroutine name_taken(path, taken, msg)
         character(len=*), intent(in) :: path
         logical, intent(out) :: taken
         character(len=:), allocatable, intent(out) :: msg
         integer(c_long_long) :: dev, ino, size
         integer :: kind, e
         integer, parameter :: eloop = 40
         msg = ''
         call sys_path_info(path, kind, dev, ino, size, e)
         ! a link loop is a name in use as well
         taken = kind /= kind_missing .or. e == eloop
         if (e /= 0 .and. e /= eloop) msg = "cannot write output '"//this%target//"': its temporary name '"// &
                                            path//"': "//sys_strerror(e)
      end subroutine name_taken
   end subroutine choose_temporaries

   !> The one line refusing a lock path: `what` names the output or sidecar it guards.
   function lock_refusal(what, lock, err) result(msg)
      character(len=*), intent(in) :: what, lock
      integer, intent(in) :: err
      character(len=:), allocatable :: msg
      if (err < 0) then
         ! not a lock file this program may take: it is left exactly as it is
         msg = 'cannot lock '//what//": its lock file '"//lock//"' "//sys_strerror(err)// &
               '; it is left as it is (never followed, truncated or removed): move it away or choose '// &
               'another name with -o'
      else
         msg = 'cannot lock '//what//' ('//lock//'): '//sys_strerror(err)
      end if
   end function lock_refusal

   !> Where a finished file ends: the target, except for a run that did not reach its end (ended
   !> false: interrupted, blow-up, solver failure) replacing an existing result with --force,
   !> which keeps its file under the temporary name and leaves that result as it is.
   function outpath_destination(this, ended) result(path)
      class(outpath_t), intent(in) :: this
      logical, intent(in) :: ended
      character(len=:), allocatable :: path
      path = this%target
      if (this%replacing .and. .not. ended) path = this%partial
   end function outpath_destination

   !> Move the complete files into place (sidecar first), then release the lock. ended: the run
   !> reached its end (see destination); if not, and it would replace a result, the file stays
   !> at its temporary name (its sidecar, which names the target, is removed).
   subroutine outpath_publish(this, stat, errmsg, ended)
      class(outpath_t), intent(inout) :: this
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      logical, intent(in) :: ended
      integer :: err
      stat = 0
      errmsg = ''
      if (.not. this%writer) return
      if (this%destination(ended) /= this%target) then
         call this%abandon(.true.)
         return
      end if
      if (len(this%xmf) > 0) then
         err = sys_publish(this%xmf_partial, this%xmf, this%force)
         if (err /= 0) then
            stat = 2
            errmsg = "cannot move '"//this%xmf_partial//"' to '"//this%xmf//"': "//sys_strerror(err)// &
                     '; the complete result stays in '//this%partial
         end if
      end if
      if (stat == 0) then
         err = sys_publish(this%partial, this%target, this%force)
         if (err /= 0) then
            stat = 2
            errmsg = "cannot move '"//this%partial//"' to '"//this%target//"': "//sys_strerror(err)// &
                     '; the complete result stays in '//this%partial
            ! the sidecar, moved first, names the target, which is not this run's result (a file
            ! that appeared meanwhile): taken back (without --force no sidecar was there before)
            if (len(this%xmf) > 0 .and. .not. this%force) err = sys_remove_own(this%xmf)
         end if
      end if
      ! the replaced result's old sidecar, if it still describes this output (a regular file:
      ! sys_remove leaves a link alone)
      if (stat == 0 .and. len(this%stale) > 0) then
         if (sidecar_refers(this%stale) == this%target(index(this%target, '/', back=.true.) + 1:)) &
            err = sys_remove(this%stale)
      end if
      call release(this)
   end subroutine outpath_publish

   !> Release the locks.
   subroutine release(this)
      class(outpath_t), intent(inout) :: this
      if (this%xfd >= 0) call sys_unlock(this%xlock, this%xfd)
      this%xfd = -1
      if (this%fd >= 0) call sys_unlock(this%lock, this%fd)
      this%fd = -1
   end subroutine release

   !> The HDF5 file name an existing XDMF sidecar points at ('' if path is no readable file
   !> or names none): the text before ':' of its first `Format="HDF">` data item.
   function sidecar_refers(path) result(name)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: name
      character(len=1024) :: line
      integer :: unit, ios, k, colon
      character(len=*), parameter :: key = 'Format="HDF">'
      integer(c_long_long) :: dev, ino, size
      integer :: kind, e
      name = ''
      ! a regular file of sidecar size only (never open a FIFO or a device)
      call sys_path_info(path, kind, dev, ino, size, e)
      if (e /= 0 .or. kind /= kind_file .or. size > 1048576) return
      open (newunit=unit, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         k = index(line, key)
         if (k == 0) cycle
         colon = index(line(k + len(key):), ':/')
         if (colon > 1) name = line(k + len(key):k + len(key) + colon - 2)
         exit
      end do
      close (unit)
   end function sidecar_refers

   !> Give up: remove the sidecar's temporary file, the result's one unless keep_partial, and
   !> release the lock. Only files this run created are removed (an earlier run's file under the
   !> same name stays); the target files are not touched.
   subroutine outpath_abandon(this, keep_partial)
      class(outpath_t), intent(inout) :: this
      logical, intent(in) :: keep_partial
      integer :: err
      if (.not. allocated(this%partial) .or. .not. this%writer) return
      if (len(this%xmf_partial) > 0) err = sys_remove_own(this%xmf_partial)
      if (.not. keep_partial) err = sys_remove_own(this%partial)
      call release(this)
   end subroutine outpath_abandon
end module contact2d_outpath
