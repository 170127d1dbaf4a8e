!> &body, as many times as needed (docs/deck.md): one deformable body of a Gmsh mesh, the
!> elements of a physical surface with their own plane-strain Hooke law. Its variables with their
!> defaults, its namelist read, its validation and its echo. A value the body leaves out is
!> taken from &material (the default material of every body); without &body groups the model
!> has one body, every element with &material, as before.
module contact2d_deck_body
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_checks, only: check_finite, check_range, max_magnitude
   use contact2d_material, only: material_t, material_init
   use contact2d_deck_syntax, only: unset, line_len, override_t, read_failed, too_long, kv, quoted, reals
   use contact2d_deck_material, only: material_cfg_t
   implicit none
   private
   public :: body_cfg_t, body_variables, body_cfg_read, body_cfg_not_finite, body_cfg_validate, body_cfg_echo

   !> The variables of &body, as the namelist in body_cfg_read declares them.
   character(len=*), parameter :: body_variables = 'name surface young poisson density velocity'

   !> &body: a named body made of the elements of one Gmsh physical surface.
   type :: body_cfg_t
      character(len=64) :: name = ''      !< as the output and the messages name it, required
      character(len=64) :: surface = ''   !< the Gmsh physical surface of its elements, required
      real(wp) :: young = unset           !< E [MPa], > 0; default material:young
      real(wp) :: poisson = unset         !< nu [-], -1 < nu < 0.5; default material:poisson
      real(wp) :: density = unset         !< rho [t/mm^3], > 0; default material:density
      !> the body's initial velocity (vx, vy) [mm/s]; default initial:velocity (docs/deck.md)
      real(wp) :: velocity(2) = [unset, unset]
      integer :: line = 0                 !< deck line of the group (for messages)
   end type body_cfg_t

contains

   !> Read one group occurrence, then its overrides ovr.
   subroutine body_cfg_read(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(body_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      character(len=line_len) :: name, surface   ! long enough to see over-long values
      real(wp) :: young, poisson, density, velocity(2)
      integer :: ios, i
      character(len=256) :: msg
      namelist /body/ name, surface, young, poisson, density, velocity
      name = cfg%name; surface = cfg%surface
      young = cfg%young; poisson = cfg%poisson; density = cfg%density; velocity = cfg%velocity
      read (blk, nml=body, iostat=ios, iomsg=msg)
      if (read_failed(ios, msg, body_variables, where, stat, errmsg)) return
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=body, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, body_variables, "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      if (too_long(where, 'name', name, len(cfg%name), stat, errmsg)) return
      if (too_long(where, 'surface', surface, len(cfg%surface), stat, errmsg)) return
      cfg%name = name; cfg%surface = surface
      cfg%young = young; cfg%poisson = poisson; cfg%density = density; cfg%velocity = velocity
   end subroutine body_cfg_read

   !> check_finite on every real of the group, named 'label:variable'; true if one is bad.
   logical function body_cfg_not_finite(cfg, label, errmsg) result(bad)
      type(body_cfg_t), intent(in) :: cfg
      character(len=*), intent(in) :: label
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite(label//':young', cfg%young, errmsg)) return
      if (check_finite(label//':poisson', cfg%poisson, errmsg)) return
      if (check_finite(label//':density', cfg%density, errmsg)) return
      if (check_finite(label//':velocity', cfg%velocity, errmsg)) return
      bad = .false.
   end function body_cfg_not_finite

   !> Validate occurrence k: name and surface given, the name not that of an earlier body
   !> (earlier: the groups before it), a built-in mesh refused (mesh_file = ''; it has no surfaces), each material
   !> value given here or in &material (default), then the law's checks. Fills the values left
   !> out from `material`. True if refused.
   logical function body_cfg_validate(cfg, k, earlier, material, mesh_file, errmsg) result(bad)
      type(body_cfg_t), intent(inout) :: cfg
      integer, intent(in) :: k
      type(body_cfg_t), intent(in) :: earlier(:)
      character(len=*), intent(in) :: mesh_file
      type(material_cfg_t), intent(in) :: material
      character(len=:), allocatable, intent(inout) :: errmsg
      character(len=:), allocatable :: g
      type(material_t) :: mat
      integer :: stat
      g = 'line '//str(cfg%line)//': &body (#'//str(k)//')'
      bad = .true.
      if (len_trim(mesh_file) == 0) then
         errmsg = g//': a body is the elements of a Gmsh physical surface; the built-in rectangle has none '// &
                  '(give mesh:file, or leave &body out: one body, every element, &material)'
         return
      end if
      if (len_trim(cfg%name) == 0) then
         errmsg = g//": name is required (e.g. name = 'upper')"
         return
      end if
      if (any(earlier%name == cfg%name)) then
         errmsg = g//": name = '"//trim(cfg%name)//"' is the name of an earlier &body"
         return
      end if
      if (len_trim(cfg%surface) == 0) then
         errmsg = g//" '"//trim(cfg%name)//"': surface is required (a Gmsh physical surface of "//trim(mesh_file)//')'
         return
      end if
      if (cfg%young == unset) cfg%young = material%young
      if (cfg%poisson == unset) cfg%poisson = material%poisson
      if (cfg%density == unset) cfg%density = material%density
      if (cfg%young == unset) then; errmsg = missing('young', 'MPa'); return; end if
      if (cfg%poisson == unset) then; errmsg = missing('poisson', '-'); return; end if
      if (cfg%density == unset) then; errmsg = missing('density', 't/mm^3'); return; end if
      call material_init(mat, cfg%young, cfg%poisson, cfg%density, stat, errmsg)
      if (stat /= 0) then
         errmsg = g//" '"//trim(cfg%name)//"': "//errmsg
         return
      end if
      if (check_range('body#'//str(k)//':young', cfg%young, 1.0e-30_wp, max_magnitude, errmsg)) return
      if (check_range('body#'//str(k)//':density', cfg%density, 1.0e-30_wp, max_magnitude, errmsg)) return
      if (count(cfg%velocity == unset) == 1) then
         errmsg = g//" '"//trim(cfg%name)//"': velocity has one component; give both, velocity = vx, vy (mm/s)"
         return
      end if
      bad = .false.
   contains
      function missing(var, unit) result(msg)
         character(len=*), intent(in) :: var, unit
         character(len=:), allocatable :: msg
         msg = g//" '"//trim(cfg%name)//"': "//var//' is required ('//unit//'): give it here or in &material '// &
               '(the default of every body)'
      end function missing
   end function body_cfg_validate

   !> One group occurrence's effective values (the defaults from &material filled in) as deck text.
   function body_cfg_echo(cfg) result(text)
      type(body_cfg_t), intent(in) :: cfg
      character(len=:), allocatable :: text
      character(len=1), parameter :: nl = new_line('a')
      text = '&body'//nl//kv('name', quoted(cfg%name))//kv('surface', quoted(cfg%surface))// &
             kv('young', str(cfg%young))//kv('poisson', str(cfg%poisson))//kv('density', str(cfg%density))
      if (all(cfg%velocity /= unset)) text = text//kv('velocity', reals(cfg%velocity))
      text = text//'/'//nl
   end function body_cfg_echo
end module contact2d_deck_body
