!> &mesh: the built-in rectangle or a Gmsh file (docs/deck.md, docs/geometry.md): its
!> variables with their defaults, its namelist read, its validation and its echo lines.
module contact2d_deck_mesh
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_checks, only: check_finite, check_range, max_magnitude
   use contact2d_mesh, only: mesh_max_elements
   use contact2d_deck_syntax, only: unset, unset_int, line_len, override_t, read_failed, too_long, &
                                    ends_with, kv, quoted
   implicit none
   private
   public :: mesh_cfg_t, mesh_variables, mesh_cfg_read, mesh_cfg_not_finite, mesh_cfg_validate, mesh_cfg_echo

   !> The variables of &mesh, as the namelist in mesh_cfg_read declares them (suggestions).
   character(len=*), parameter :: mesh_variables = 'lx ly nx ny level file'

   !> &mesh: structured rectangle [0, lx] x [0, ly] with (nx 2^level) x (ny 2^level) elements,
   !> or a Gmsh file (.msh, or .geo meshed at start-up) refined `level` times (docs/geometry.md).
   type :: mesh_cfg_t
      character(len=256) :: file = ''  !< Gmsh mesh or geometry; '' for the built-in rectangle
      real(wp) :: lx = unset          !< width [mm], required, > 0
      real(wp) :: ly = unset          !< height [mm], required, > 0
      integer :: nx = unset_int       !< divisions along x at level 0, required, >= 1
      integer :: ny = unset_int       !< divisions along y at level 0, required, >= 1
      integer :: level = 0            !< refinement level k: each division split in 2^k, 0..12
   end type mesh_cfg_t

contains

   !> Read the group's lines blk (none: the group is absent), then the --set overrides ovr.
   subroutine mesh_cfg_read(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(mesh_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: lx, ly
      integer :: nx, ny, level, ios, i
      character(len=256) :: msg
      character(len=line_len) :: file
      namelist /mesh/ lx, ly, nx, ny, level, file
      lx = cfg%lx; ly = cfg%ly; nx = cfg%nx; ny = cfg%ny; level = cfg%level; file = cfg%file
      if (size(blk) > 0) then
         read (blk, nml=mesh, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, mesh_variables, where, stat, errmsg)) return
      end if
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=mesh, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, mesh_variables, "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      if (too_long(where, 'file', file, len(cfg%file), stat, errmsg)) return
      cfg%lx = lx; cfg%ly = ly; cfg%nx = nx; cfg%ny = ny; cfg%level = level; cfg%file = file
   end subroutine mesh_cfg_read

   !> check_finite on every real of the group (contact2d_checks); true if one is bad.
   logical function mesh_cfg_not_finite(m, errmsg) result(bad)
      type(mesh_cfg_t), intent(in) :: m
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('mesh:lx', m%lx, errmsg)) return
      if (check_finite('mesh:ly', m%ly, errmsg)) return
      bad = .false.
   end function mesh_cfg_not_finite

   !> Required values and ranges; true if a value is refused (errmsg says which).
   logical function mesh_cfg_validate(m, errmsg) result(bad)
      type(mesh_cfg_t), intent(in) :: m
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (len_trim(m%file) > 0) then
         if (m%lx /= unset .or. m%ly /= unset .or. m%nx /= unset_int .or. m%ny /= unset_int) then
            errmsg = "mesh:file = '"//trim(m%file)//"' is given with lx/ly/nx/ny; give either a file "// &
                     'or the rectangle'
            return
         end if
         if (.not. (ends_with(m%file, '.msh') .or. ends_with(m%file, '.geo'))) then
            errmsg = "mesh:file = '"//trim(m%file)//"' must end in .msh (a Gmsh mesh) or .geo (a Gmsh geometry)"
            return
         end if
         if (m%level < 0 .or. m%level > 8) then
            errmsg = 'mesh:level = '//str(m%level)//' must be in 0..8 for a Gmsh file'
            return
         end if
      else
         if (m%lx == unset) then; errmsg = 'mesh:lx is required (width, mm)'; return; end if
         if (m%ly == unset) then; errmsg = 'mesh:ly is required (height, mm)'; return; end if
         if (m%nx == unset_int) then; errmsg = 'mesh:nx is required (divisions along x)'; return; end if
         if (m%ny == unset_int) then; errmsg = 'mesh:ny is required (divisions along y)'; return; end if
         if (.not. m%lx > 0) then; errmsg = 'mesh:lx = '//str(m%lx)//' must be > 0'; return; end if
         if (.not. m%ly > 0) then; errmsg = 'mesh:ly = '//str(m%ly)//' must be > 0'; return; end if
         if (m%nx < 1) then; errmsg = 'mesh:nx = '//str(m%nx)//' must be >= 1'; return; end if
         if (m%ny < 1) then; errmsg = 'mesh:ny = '//str(m%ny)//' must be >= 1'; return; end if
         if (check_range('mesh:lx', m%lx, 1.0e-30_wp, max_magnitude, errmsg)) return
         if (check_range('mesh:ly', m%ly, 1.0e-30_wp, max_magnitude, errmsg)) return
         if (m%level < 0 .or. m%level > 12) then
            errmsg = 'mesh:level = '//str(m%level)//' must be in 0..12'
            return
         end if
         if (real(m%nx, wp)*real(m%ny, wp)*4.0_wp**m%level > mesh_max_elements) then
            errmsg = 'mesh: nx*ny*4**level = '//str(real(m%nx, wp)*real(m%ny, wp)*4.0_wp**m%level)// &
                     ' elements is more than this program is meant for ('//str(mesh_max_elements)//')'
            return
         end if
      end if
      bad = .false.
   end function mesh_cfg_validate

   !> The group's effective values as deck text.
   function mesh_cfg_echo(m) result(text)
      type(mesh_cfg_t), intent(in) :: m
      character(len=:), allocatable :: text
      character(len=1), parameter :: nl = new_line('a')
      if (len_trim(m%file) > 0) then
         text = '&mesh'//nl//kv('file', quoted(m%file))//kv('level', str(m%level))//'/'//nl
      else
         text = '&mesh'//nl//kv('lx', str(m%lx))//kv('ly', str(m%ly))//kv('nx', str(m%nx))// &
                kv('ny', str(m%ny))//kv('level', str(m%level))//'/'//nl
      end if
   end function mesh_cfg_echo
end module contact2d_deck_mesh
