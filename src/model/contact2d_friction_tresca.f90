!> Tresca friction (SPEC section 3): the limit of node i is s_i w_i, independent of the normal
!> force; with tresca_scope = 'contact' it is 0 on a node that carries no normal force. The law
!> forms its thresholds s_i itself from the contact nodes' abscissae (uniform, or piecewise
!> linear in the abscissa, docs/friction.md) and gives them to the writer (/contact/threshold).
!> A member of the friction-law seam (contact2d_friction, docs/friction.md section 2).
module contact2d_friction_tresca
   use contact2d_kinds, only: wp
   use contact2d_friction, only: friction_law_t, parameter_name_len
   implicit none
   private
   public :: tresca_law_t

   !> Nodal Tresca: limit_i = s_i w_i (0 where the tangential dof is prescribed).
   type, extends(friction_law_t) :: tresca_law_t
      real(wp), allocatable :: s(:)          !< thresholds s_i per contact node [MPa]
      real(wp), allocatable :: bound(:)      !< s_i w_i [N] (0 where the tangential dof is prescribed)
      logical :: in_contact_only = .false.   !< tresca_scope = 'contact'
   contains
      procedure :: init => tresca_law_init
      procedure :: limits => tresca_law_limits
      procedure :: linear_in_fn => tresca_law_no
      procedure :: fn_slopes => tresca_law_fn_slopes
      procedure :: depends_on_fn => tresca_law_no
      procedure :: parameters => tresca_law_parameters
      procedure :: node_thresholds => tresca_law_node_thresholds
   end type tresca_law_t

contains

   !> abscissa, weight, slides: the contact nodes' abscissae [mm], weights w_i [mm] and whether
   !> their tangential dof is free; threshold: the uniform s [MPa], used when profile_s is empty;
   !> profile_s, profile_values: the piecewise-linear s(abscissa) [mm, MPa], held beyond its ends;
   !> in_contact_only: tresca_scope = 'contact'. Limits s_i w_i (SPEC section 3), none where the
   !> tangential dof is prescribed (the reaction carries it).
   subroutine tresca_law_init(this, abscissa, weight, slides, threshold, profile_s, profile_values, in_contact_only)
      class(tresca_law_t), intent(out) :: this
      real(wp), intent(in) :: abscissa(:), weight(:)
      logical, intent(in) :: slides(:)
      real(wp), intent(in) :: threshold, profile_s(:), profile_values(:)
      logical, intent(in) :: in_contact_only
      integer :: i
      this%label = 'tresca'
      allocate (this%s(size(abscissa)))
      if (size(profile_s) > 0) then
         do i = 1, size(abscissa)
            this%s(i) = interpolate(profile_s, profile_values, abscissa(i))
         end do
      else
         this%s = threshold
      end if
      this%bound = merge(this%s*weight, 0.0_wp, slides)
      this%in_contact_only = in_contact_only
      this%fixed = .not. in_contact_only   ! with tresca_scope = 'all' s_i w_i never change
   end subroutine tresca_law_init

   !> s(x) piecewise linear through (xs_k, ys_k), held constant beyond the ends.
   pure real(wp) function interpolate(xs, ys, x) result(y)
      real(wp), intent(in) :: xs(:), ys(:), x
      integer :: k
      if (x <= xs(1)) then
         y = ys(1)
      else if (x >= xs(size(xs))) then
         y = ys(size(ys))
      else
         do k = 1, size(xs) - 1
            if (x <= xs(k + 1)) exit
         end do
         y = ys(k) + (ys(k + 1) - ys(k))*(x - xs(k))/(xs(k + 1) - xs(k))
      end if
   end function interpolate

   !> limit_i = s_i w_i, or 0 where node i is not in contact with tresca_scope = 'contact'
   !> (SPEC section 3: judged like the status, per dual cell for P0). F_n itself plays no part.
   pure subroutine tresca_law_limits(this, fn, closed, limit)
      class(tresca_law_t), intent(in) :: this
      real(wp), intent(in) :: fn(:)
      real(wp), intent(in) :: closed(:)
      real(wp), intent(out) :: limit(:)
      integer :: i
      if (size(fn) /= size(limit)) error stop 'tresca_law_limits: fn and limit differ in size'
      if (this%in_contact_only) then
         do i = 1, size(limit)
            limit(i) = merge(this%bound(i), 0.0_wp, closed(i) > 0)
         end do
      else
         limit = this%bound
      end if
   end subroutine tresca_law_limits

   !> Tresca's limit s_i w_i does not depend on the normal force (tresca_scope = 'contact' only
   !> switches it off out of contact): neither linear in F_n nor driven by it.
   pure logical function tresca_law_no(this) result(no)
      class(tresca_law_t), intent(in) :: this
      no = .false.
   end function tresca_law_no

   !> d limit_i / d F_n,i = 0.
   pure subroutine tresca_law_fn_slopes(this, slope)
      class(tresca_law_t), intent(in) :: this
      real(wp), intent(out) :: slope(:)
      if (size(slope) /= size(this%bound)) error stop 'tresca_law_fn_slopes: slope and bound differ in size'
      slope = 0
   end subroutine tresca_law_fn_slopes

   !> None: the thresholds s_i are per-node data, written as /contact/threshold.
   pure subroutine tresca_law_parameters(this, names, values)
      class(tresca_law_t), intent(in) :: this
      character(len=parameter_name_len), allocatable, intent(out) :: names(:)
      real(wp), allocatable, intent(out) :: values(:)
      allocate (names(0), values(0))
   end subroutine tresca_law_parameters

   !> The thresholds s_i [MPa] (written as /contact/threshold).
   pure subroutine tresca_law_node_thresholds(this, s)
      class(tresca_law_t), intent(in) :: this
      real(wp), intent(out) :: s(:)
      s = this%s
   end subroutine tresca_law_node_thresholds
end module contact2d_friction_tresca
