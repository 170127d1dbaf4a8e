!> Prescribed displacements and surface tractions driven by load curves (SPEC sections 2, 5).
!>
!> Dirichlet data: a list of prescribed dofs, each following one curve. Tractions: nodal forces
!> sum_l curve_l(t) * weight, the weights being the consistent (exact for a uniform traction)
!> half-edge lengths of the loaded segments.
module contact2d_loading
   use contact2d_kinds, only: wp
   use contact2d_loadcurve, only: loadcurve_t
   implicit none
   private
   public :: loading_t

   !> Time-dependent boundary data of a model.
   type :: loading_t
      integer :: ncurve = 0
      type(loadcurve_t), allocatable :: curves(:)
      !> prescribed dofs: node, component (1 = x, 2 = y) and curve
      integer :: npres = 0
      integer, allocatable :: pnode(:), pcomp(:), pcurve(:)
      !> traction entries: node, component, curve and weight [mm] (force = value * weight)
      integer :: ntrac = 0
      integer, allocatable :: tnode(:), tcomp(:), tcurve(:)
      real(wp), allocatable :: tweight(:)
      !> 1 on free dofs, 0 on prescribed ones (2, nnode)
      real(wp), allocatable :: free(:, :)
   contains
      procedure :: init => loading_init
      procedure :: add_curve => loading_add_curve
      procedure :: prescribe => loading_prescribe
      procedure :: add_traction => loading_add_traction
      procedure :: add_traction_rotated => loading_add_traction_rotated
      procedure :: finalize => loading_finalize
      procedure :: curve_values => loading_curve_values
      procedure :: end_time => loading_end_time
   end type loading_t

contains

   subroutine loading_init(this, nnode)
      class(loading_t), intent(out) :: this
      integer, intent(in) :: nnode
      allocate (this%curves(0), this%pnode(0), this%pcomp(0), this%pcurve(0))
      allocate (this%tnode(0), this%tcomp(0), this%tcurve(0), this%tweight(0))
      allocate (this%free(2, nnode))
      this%free = 1
   end subroutine loading_init

   !> Register a curve; returns its id.
   integer function loading_add_curve(this, times, values) result(id)
      class(loading_t), intent(inout) :: this
      real(wp), intent(in) :: times(:), values(:)
      type(loadcurve_t) :: c
      call c%init(times, values)
      this%curves = [this%curves, c]
      this%ncurve = size(this%curves)
      id = this%ncurve
   end function loading_add_curve

   !> Prescribe component comp of the given nodes to follow curve id. A dof already prescribed
   !> to a different curve is reported in `conflict` (its node), else conflict = 0.
   subroutine loading_prescribe(this, nodes, comp, id, conflict)
      class(loading_t), intent(inout) :: this
      integer, intent(in) :: nodes(:), comp, id
      integer, intent(out) :: conflict
      integer :: k, j
      conflict = 0
      do k = 1, size(nodes)
         j = findloc(this%pnode*10 + this%pcomp, nodes(k)*10 + comp, dim=1)
         if (j > 0) then
            if (.not. same_curve(this%curves(this%pcurve(j)), this%curves(id))) then
               conflict = nodes(k)
               return
            end if
            cycle
         end if
         this%pnode = [this%pnode, nodes(k)]
         this%pcomp = [this%pcomp, comp]
         this%pcurve = [this%pcurve, id]
         this%free(comp, nodes(k)) = 0
      end do
      this%npres = size(this%pnode)
   end subroutine loading_prescribe

   pure logical function same_curve(a, b)
      type(loadcurve_t), intent(in) :: a, b
      same_curve = a%nstage == b%nstage
      if (same_curve) same_curve = all(a%times == b%times) .and. all(a%values == b%values)
   end function same_curve

   !> Add a uniform traction (per unit value of curve id) in component comp on segments.
   subroutine loading_add_traction(this, x, seg, comp, id)
      class(loading_t), intent(inout) :: this
      real(wp), intent(in) :: x(:, :)       !< node coordinates (2, nnode) [mm]
      integer, intent(in) :: seg(:, :)      !< segments (2, nseg)
      integer, intent(in) :: comp, id
      integer :: s, a
      real(wp) :: half
      do s = 1, size(seg, 2)
         half = 0.5_wp*norm2(x(:, seg(2, s)) - x(:, seg(1, s)))
         do a = 1, 2
            this%tnode = [this%tnode, seg(a, s)]
            this%tcomp = [this%tcomp, comp]
            this%tcurve = [this%tcurve, id]
            this%tweight = [this%tweight, half]
         end do
      end do
      this%ntrac = size(this%tnode)
   end subroutine loading_add_traction

   !> Add a uniform traction (per unit value of curve id) along each segment's outward normal n
   !> (or, with tangential, along t = (-n2, n1)): consistent nodal forces value (L/2) n at both
   !> ends of each straight edge (docs/geometry.md). Segments run with the body on their left,
   !> so n = (e2, -e1) with e the unit edge direction.
   subroutine loading_add_traction_rotated(this, x, seg, tangential, id)
      class(loading_t), intent(inout) :: this
      real(wp), intent(in) :: x(:, :)       !< node coordinates (2, nnode) [mm]
      integer, intent(in) :: seg(:, :)      !< segments (2, nseg), body on the left
      logical, intent(in) :: tangential
      integer, intent(in) :: id
      integer :: s, a, c
      real(wp) :: d(2), len_, n(2), dir(2)
      do s = 1, size(seg, 2)
         d = x(:, seg(2, s)) - x(:, seg(1, s))
         len_ = norm2(d)
         n = [d(2), -d(1)]/len_
         if (tangential) then
            dir = [-n(2), n(1)]
         else
            dir = n
         end if
         do a = 1, 2
            do c = 1, 2
               this%tnode = [this%tnode, seg(a, s)]
               this%tcomp = [this%tcomp, c]
               this%tcurve = [this%tcurve, id]
               this%tweight = [this%tweight, 0.5_wp*len_*dir(c)]
            end do
         end do
      end do
      this%ntrac = size(this%tnode)
   end subroutine loading_add_traction_rotated

   !> Drop traction entries on prescribed dofs (the reaction there takes the load).
   subroutine loading_finalize(this)
      class(loading_t), intent(inout) :: this
      logical, allocatable :: keep(:)
      integer :: k
      allocate (keep(this%ntrac))
      do k = 1, this%ntrac
         keep(k) = this%free(this%tcomp(k), this%tnode(k)) > 0
      end do
      this%tnode = pack(this%tnode, keep)
      this%tcomp = pack(this%tcomp, keep)
      this%tcurve = pack(this%tcurve, keep)
      this%tweight = pack(this%tweight, keep)
      this%ntrac = size(this%tnode)
   end subroutine loading_finalize

   !> Values of all curves at time t.
   pure subroutine loading_curve_values(this, t, values)
      class(loading_t), intent(in) :: this
      real(wp), intent(in) :: t
      real(wp), intent(out) :: values(:)
      integer :: c
      do c = 1, this%ncurve
         values(c) = this%curves(c)%value(t)
      end do
   end subroutine loading_curve_values

   !> End of the last stage of all curves [s].
   pure real(wp) function loading_end_time(this) result(t)
      class(loading_t), intent(in) :: this
      integer :: c
      t = 0
      do c = 1, this%ncurve
         t = max(t, this%curves(c)%end_time())
      end do
   end function loading_end_time
end module contact2d_loading
