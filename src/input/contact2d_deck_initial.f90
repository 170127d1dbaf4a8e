!> &initial: the state at t = 0 (docs/deck.md): its variables with their defaults, its
!> namelist read, its validation and its echo lines. What the initial state means for the
!> other groups (a dynamic run, the static engine, mass scaling) is checked by the deck core.
module contact2d_deck_initial
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_checks, only: check_finite
   use contact2d_deck_syntax, only: line_len, override_t, read_failed, kv, reals
   implicit none
   private
   public :: initial_cfg_t, initial_variables, initial_cfg_read, initial_cfg_not_finite
   public :: initial_cfg_validate, initial_cfg_echo

   !> The variables of &initial, as the namelist in initial_cfg_read declares them.
   character(len=*), parameter :: initial_variables = 'velocity'

   !> &initial: the state at t = 0 (docs/deck.md).
   type :: initial_cfg_t
      real(wp) :: velocity(2) = [0.0_wp, 0.0_wp]   !< uniform initial velocity (vx, vy) [mm/s]
   end type initial_cfg_t

contains

   !> &initial: the uniform initial velocity; the group's lines blk (none: absent), then the
   !> --set overrides ovr.
   subroutine initial_cfg_read(blk, ovr, where, cfg, stat, errmsg)
      character(len=line_len), intent(in) :: blk(:)
      type(override_t), intent(in) :: ovr(:)
      character(len=*), intent(in) :: where
      type(initial_cfg_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: velocity(2)
      integer :: ios, i
      character(len=256) :: msg
      namelist /initial/ velocity
      velocity = cfg%velocity
      if (size(blk) > 0) then
         read (blk, nml=initial, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, initial_variables, where, stat, errmsg)) return
      end if
      do i = 1, size(ovr)
         read (ovr(i)%assignment, nml=initial, iostat=ios, iomsg=msg)
         if (read_failed(ios, msg, initial_variables, "--set '"//ovr(i)%spec//"': ", stat, errmsg)) return
      end do
      cfg%velocity = velocity
   end subroutine initial_cfg_read

   !> check_finite on every real of the group; true if one is bad.
   logical function initial_cfg_not_finite(cfg, errmsg) result(bad)
      type(initial_cfg_t), intent(in) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = check_finite('initial:velocity', cfg%velocity, errmsg)
   end function initial_cfg_not_finite

   !> A finite velocity, each component named; true if refused.
   logical function initial_cfg_validate(cfg, errmsg) result(bad)
      type(initial_cfg_t), intent(in) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: i
      bad = .true.
      do i = 1, 2
         if (.not. ieee_is_finite(cfg%velocity(i))) then
            ! named without arithmetic on the value (Debug builds trap invalid operations)
            if (ieee_is_nan(cfg%velocity(i))) then
               errmsg = 'NaN'
            else
               errmsg = trim(merge('+Infinity', '-Infinity', sign(1.0_wp, cfg%velocity(i)) > 0))
            end if
            errmsg = 'initial:velocity('//str(i)//') = '//errmsg//' must be finite (mm/s)'
            return
         end if
      end do
      bad = .false.
   end function initial_cfg_validate

   !> The group's effective values as deck text.
   function initial_cfg_echo(cfg) result(text)
      type(initial_cfg_t), intent(in) :: cfg
      character(len=:), allocatable :: text
      character(len=1), parameter :: nl = new_line('a')
      text = '&initial'//nl//kv('velocity', reals(cfg%velocity))//'/'//nl
   end function initial_cfg_echo
end module contact2d_deck_initial
