!> &material: the isotropic Hooke law in plane strain (docs/deck.md): its variables with their
!> defaults, its namelist read, its validation (material_init's own checks) and its echo.
module contact2d_deck_material
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_checks, only: check_finite, check_range, max_magnitude
   use contact2d_material, only: material_t, material_init
   use contact2d_deck_syntax, only: unset, line_len, override_t, read_failed, kv
   implicit none
   private
   public :: material_cfg_t, material_variables, material_cfg_read, material_cfg_not_finite
   public :: material_cfg_validate, material_cfg_echo

   !> The variables of &material, as the namelist in material_cfg_read declares them.
   character(len=*), parameter :: material_variables = 'young poisson density'

   !> &material: isotropic Hooke law, plane strain.
   type :: material_cfg_t
      real(wp) :: young = unset       !< E [MPa], required, > 0
      real(wp) :: poisson = unset     !< nu [-], required, -1 < nu < 0.5
      real(wp) :: density = unset     !< rho [t/mm^3], required, > 0
   end type material_cfg_t

contains

   !> Read the group's lines blk (none: the group is absent), then the --set overrides ovr.
   subroutine material_cfg_read(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(material_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: young, poisson, density
      integer :: ios, i
      character(len=256) :: msg
      namelist /material/ young, poisson, density
      young = cfg%young; poisson = cfg%poisson; density = cfg%density
      if (size(blk) > 0) then
         read (blk, nml=material, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, material_variables, where, stat, errmsg)) return
      end if
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=material, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, material_variables, "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      cfg%young = young; cfg%poisson = poisson; cfg%density = density
   end subroutine material_cfg_read

   !> check_finite on every real of the group; true if one is bad.
   logical function material_cfg_not_finite(a, errmsg) result(bad)
      type(material_cfg_t), intent(in) :: a
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('material:young', a%young, errmsg)) return
      if (check_finite('material:poisson', a%poisson, errmsg)) return
      if (check_finite('material:density', a%density, errmsg)) return
      bad = .false.
   end function material_cfg_not_finite

   !> Required values, then the law's own checks (material_init) and the ranges; true if a
   !> value is refused.
   logical function material_cfg_validate(m, errmsg) result(bad)
      type(material_cfg_t), intent(in) :: m
      character(len=:), allocatable, intent(inout) :: errmsg
      type(material_t) :: mat
      integer :: stat
      bad = .true.
      if (m%young == unset) then; errmsg = 'material:young is required (MPa)'; return; end if
      if (m%poisson == unset) then; errmsg = 'material:poisson is required'; return; end if
      if (m%density == unset) then; errmsg = 'material:density is required (t/mm^3)'; return; end if
      call material_init(mat, m%young, m%poisson, m%density, stat, errmsg)
      if (stat /= 0) return
      if (check_range('material:young', m%young, 1.0e-30_wp, max_magnitude, errmsg)) return
      if (check_range('material:density', m%density, 1.0e-30_wp, max_magnitude, errmsg)) return
      bad = .false.
   end function material_cfg_validate

   !> The group's effective values as deck text.
   function material_cfg_echo(m) result(text)
      type(material_cfg_t), intent(in) :: m
      character(len=:), allocatable :: text
      character(len=1), parameter :: nl = new_line('a')
      text = '&material'//nl//kv('young', str(m%young))//kv('poisson', str(m%poisson))// &
             kv('density', str(m%density))//'/'//nl
   end function material_cfg_echo
end module contact2d_deck_material
