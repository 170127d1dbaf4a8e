!> &output: what is written and how often (docs/deck.md, docs/output.md): its variables with
!> their defaults, its namelist read, its validation and its echo lines.
module contact2d_deck_output
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_checks, only: check_finite
   use contact2d_deck_syntax, only: unset, max_stages, line_len, override_t, read_failed, kv, reals
   implicit none
   private
   public :: output_cfg_t, output_variables, output_logicals, output_cfg_read, output_cfg_not_finite
   public :: output_cfg_validate, output_cfg_echo

   !> The variables of &output, as the namelist in output_cfg_read declares them.
   character(len=*), parameter :: output_variables = 'history_interval xdmf progress snapshot_times'
   !> The logical variables of &output (their values are checked as text before the read).
   character(len=*), parameter :: output_logicals(2) = [character(len=8) :: 'xdmf', 'progress']

   !> &output: what is written and how often.
   type :: output_cfg_t
      integer :: history_interval = 10    !< steps between history samples, >= 1
      logical :: xdmf = .true.            !< write the XDMF sidecar <output>.xmf for ParaView
      logical :: progress = .true.        !< progress line when the terminal is interactive
      real(wp) :: snapshot_times(max_stages) = unset  !< times of /fields/<step> snapshots [s]
      integer :: nsnapshot = 0            !< derived: number of snapshot times
   end type output_cfg_t

contains

   !> Read the group's lines blk (none: the group is absent), then the --set overrides ovr.
   subroutine output_cfg_read(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(output_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: history_interval, ios, i
      logical :: xdmf, progress
      real(wp) :: snapshot_times(max_stages)
      character(len=256) :: msg
      namelist /output/ history_interval, xdmf, progress, snapshot_times
      history_interval = cfg%history_interval; xdmf = cfg%xdmf; progress = cfg%progress
      snapshot_times = cfg%snapshot_times
      if (size(blk) > 0) then
         read (blk, nml=output, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, output_variables, where, stat, errmsg)) return
      end if
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=output, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, output_variables, "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      cfg%history_interval = history_interval; cfg%xdmf = xdmf; cfg%progress = progress
      cfg%snapshot_times = snapshot_times
   end subroutine output_cfg_read

   !> check_finite on every real of the group; true if one is bad.
   logical function output_cfg_not_finite(cfg, errmsg) result(bad)
      type(output_cfg_t), intent(in) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = check_finite('output:snapshot_times', cfg%snapshot_times, errmsg)
   end function output_cfg_not_finite

   !> Ranges; fills nsnapshot. True if a value is refused.
   logical function output_cfg_validate(o, errmsg) result(bad)
      type(output_cfg_t), intent(inout) :: o
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: i
      bad = .true.
      if (o%history_interval < 1) then
         errmsg = 'output:history_interval = '//str(o%history_interval)//' must be >= 1'
         return
      end if
      o%nsnapshot = count(o%snapshot_times /= unset)
      if (any(o%snapshot_times(o%nsnapshot + 1:) /= unset)) then
         errmsg = 'output:snapshot_times must be given from the first entry on'
         return
      end if
      do i = 1, o%nsnapshot
         if (.not. o%snapshot_times(i) > 0 .or. &
             (i > 1 .and. .not. o%snapshot_times(i) > o%snapshot_times(max(i - 1, 1)))) then
            errmsg = 'output:snapshot_times must be > 0 and increase strictly (entry '//str(i)//')'
            return
         end if
      end do
      bad = .false.
   end function output_cfg_validate

   !> The group's effective values as deck text.
   function output_cfg_echo(o) result(text)
      type(output_cfg_t), intent(in) :: o
      character(len=:), allocatable :: text
      character(len=1), parameter :: nl = new_line('a')
      text = '&output'//nl//kv('history_interval', str(o%history_interval))// &
             kv('xdmf', str(o%xdmf))//kv('progress', str(o%progress))
      if (o%nsnapshot > 0) text = text//kv('snapshot_times', reals(o%snapshot_times(1:o%nsnapshot)))
      text = text//'/'//nl
   end function output_cfg_echo
end module contact2d_deck_output
