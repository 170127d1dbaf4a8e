!> &dirichlet (prescribed displacement) and &traction (surface traction), each as many times as
!> needed (docs/deck.md): the variables of one group with their defaults, its namelist read,
!> its validation (place, component, load curve) and its echo lines.
module contact2d_deck_loads
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower
   use contact2d_checks, only: check_finite
   use contact2d_deck_syntax, only: unset, max_stages, line_len, override_t, read_failed, too_long, &
                                    place_problem, place_text, range_text, kv, quoted, reals
   implicit none
   private
   public :: edge_load_cfg_t, edge_load_variables, edge_load_cfg_read, edge_load_cfg_not_finite
   public :: edge_load_cfg_validate, edge_load_cfg_echo

   !> The variables of &dirichlet and &traction, as the namelists in edge_load_cfg_read
   !> declare them.
   character(len=*), parameter :: edge_load_variables = 'edge boundary xmin xmax ymin ymax component values times'

   !> &dirichlet (prescribed displacement [mm]) or &traction (surface traction [MPa]) on the
   !> nodes of one side of the bounding box within an optional coordinate range.
   type :: edge_load_cfg_t
      character(len=16) :: edge = ''               !< 'bottom' | 'right' | 'top' | 'left' (built-in mesh)
      character(len=64) :: boundary = ''           !< name of a Gmsh physical curve (instead of edge)
      real(wp) :: xmin = -unset, xmax = unset      !< x range of the selection [mm]
      real(wp) :: ymin = -unset, ymax = unset      !< y range of the selection [mm]
      !> 'x' | 'y', required; tractions also 'normal' | 'tangential' (along the outward normal n
      !> of each edge and t = (-n2, n1))
      character(len=16) :: component = ''
      real(wp) :: values(max_stages) = unset       !< value at the end of each stage, required
      real(wp) :: times(max_stages) = unset        !< end time of each stage [s]
      integer :: nstage = 0                        !< derived: number of stages
      integer :: line = 0                          !< deck line of the group (for messages)
   end type edge_load_cfg_t

contains

   !> Read one group occurrence (group: 'dirichlet' or 'traction'), then its overrides ovr.
   subroutine edge_load_cfg_read(blk, group, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      character(len=*), intent(in) :: group
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(edge_load_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      character(len=line_len) :: edge, boundary, component   ! long enough to see over-long values
      real(wp) :: xmin, xmax, ymin, ymax, values(max_stages), times(max_stages)
      integer :: ios, i
      character(len=256) :: msg
      namelist /dirichlet/ edge, boundary, xmin, xmax, ymin, ymax, component, values, times
      namelist /traction/ edge, boundary, xmin, xmax, ymin, ymax, component, values, times
      edge = cfg%edge; boundary = cfg%boundary; component = cfg%component
      xmin = cfg%xmin; xmax = cfg%xmax; ymin = cfg%ymin; ymax = cfg%ymax
      values = cfg%values; times = cfg%times
      if (group == 'dirichlet') then
         read (blk, nml=dirichlet, iostat=ios, iomsg=msg)
      else
         read (blk, nml=traction, iostat=ios, iomsg=msg)
      end if
      if (read_failed(ios, msg, edge_load_variables, where, stat, errmsg)) return
      do i = 1, size(ovr)
         if (group == 'dirichlet') then
            read (ovr(i)%assignment, nml=dirichlet, iostat=ios, iomsg=msg)
         else
            read (ovr(i)%assignment, nml=traction, iostat=ios, iomsg=msg)
         end if
         if (read_failed(ios, msg, edge_load_variables, "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      if (too_long(where, 'edge', edge, len(cfg%edge), stat, errmsg)) return
      if (too_long(where, 'boundary', boundary, len(cfg%boundary), stat, errmsg)) return
      if (too_long(where, 'component', component, len(cfg%component), stat, errmsg)) return
      cfg%edge = edge; cfg%boundary = boundary; cfg%component = component
      cfg%xmin = xmin; cfg%xmax = xmax; cfg%ymin = ymin; cfg%ymax = ymax
      cfg%values = values; cfg%times = times
   end subroutine edge_load_cfg_read

   !> check_finite on every real of the group, named 'label:variable'; true if one is bad.
   logical function edge_load_cfg_not_finite(cfg, label, errmsg) result(bad)
      type(edge_load_cfg_t), intent(in) :: cfg
      character(len=*), intent(in) :: label
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite(label//':xmin', cfg%xmin, errmsg)) return
      if (check_finite(label//':xmax', cfg%xmax, errmsg)) return
      if (check_finite(label//':ymin', cfg%ymin, errmsg)) return
      if (check_finite(label//':ymax', cfg%ymax, errmsg)) return
      if (check_finite(label//':values', cfg%values, errmsg)) return
      if (check_finite(label//':times', cfg%times, errmsg)) return
      bad = .false.
   end function edge_load_cfg_not_finite

   !> Validate occurrence k of `group` and fill its derived values (stage count, the time of a
   !> one-stage curve without times: t_ramp, solver:t_ramp or unset); mesh_file is mesh:file
   !> ('' for the built-in rectangle). True if a value is refused.
   logical function edge_load_cfg_validate(cfg, group, k, mesh_file, t_ramp, errmsg) result(bad)
      type(edge_load_cfg_t), intent(inout) :: cfg
      character(len=*), intent(in) :: group, mesh_file
      integer, intent(in) :: k
      real(wp), intent(in) :: t_ramp
      character(len=:), allocatable, intent(inout) :: errmsg
      character(len=:), allocatable :: g
      integer :: ntimes, j
      g = 'line '//str(cfg%line)//': &'//group//' (#'//str(k)//')'
      bad = .true.
      errmsg = place_problem(g, ': ', cfg%edge, cfg%boundary, mesh_file)
      if (len(errmsg) > 0) return
      cfg%edge = lower(cfg%edge)
      cfg%component = lower(cfg%component)
      if (group == 'traction') then
         if (.not. any(cfg%component == [character(len=16) :: 'x', 'y', 'normal', 'tangential'])) then
            errmsg = g//": component = '"//trim(cfg%component)//"' is not one of 'x', 'y', 'normal', 'tangential'"
            return
         end if
      else if (.not. any(cfg%component == [character(len=16) :: 'x', 'y'])) then
         errmsg = g//": component = '"//trim(cfg%component)//"' is not one of 'x', 'y'"
         return
      end if
      if (.not. (cfg%xmin <= cfg%xmax .and. cfg%ymin <= cfg%ymax)) then
         errmsg = g//': the range needs xmin <= xmax and ymin <= ymax'
         return
      end if
      cfg%nstage = count(cfg%values /= unset)
      if (cfg%nstage == 0) then
         errmsg = g//': values is required (one value per load stage)'
         return
      end if
      if (any(cfg%values(cfg%nstage + 1:) /= unset)) then
         errmsg = g//': values must be given from the first entry on'
         return
      end if
      ntimes = count(cfg%times /= unset)
      if (ntimes == 0) then
         if (cfg%nstage > 1) then
            errmsg = g//': '//str(cfg%nstage)//' stages need times (the end time of each stage, s)'
            return
         end if
         if (t_ramp == unset) then
            errmsg = g//': no times given and solver:t_ramp is not set (the ramp duration, s)'
            return
         end if
         cfg%times(1) = t_ramp
      else if (ntimes /= cfg%nstage .or. any(cfg%times(cfg%nstage + 1:) /= unset)) then
         errmsg = g//': times needs one entry per value ('//str(cfg%nstage)//')'
         return
      end if
      if (.not. cfg%times(1) > 0) then
         errmsg = g//': times(1) = '//str(cfg%times(1))//' must be > 0'
         return
      end if
      do j = 2, cfg%nstage
         if (.not. cfg%times(j) > cfg%times(j - 1)) then
            errmsg = g//': times must increase strictly (times('//str(j)//') = '//str(cfg%times(j))//')'
            return
         end if
      end do
      bad = .false.
   end function edge_load_cfg_validate

   !> One group occurrence's effective values as deck text (group: 'dirichlet' or 'traction').
   function edge_load_cfg_echo(cfg, group) result(text)
      type(edge_load_cfg_t), intent(in) :: cfg
      character(len=*), intent(in) :: group
      character(len=:), allocatable :: text
      character(len=1), parameter :: nl = new_line('a')
      text = '&'//group//nl//place_text(cfg%edge, cfg%boundary)//range_text(cfg%xmin, cfg%xmax, cfg%ymin, cfg%ymax)// &
             kv('component', quoted(cfg%component))//kv('values', reals(cfg%values(1:cfg%nstage)))// &
             kv('times', reals(cfg%times(1:cfg%nstage)))//'/'//nl
   end function edge_load_cfg_echo
end module contact2d_deck_loads
