!> The automatic damping of the explicit engine (dynamic relaxation, SPEC section 5):
!> alpha = 2 omega_1, with omega_1^2 the Rayleigh quotient of the free part du_f of the
!> displacement increment since the last estimate, du_f^T K du_f / du_f^T M du_f. The engine
!> (contact2d_explicit) calls it every solver:damping_interval steps, right after f_int = K u^n.
module contact2d_damping_estimate
   use contact2d_kinds, only: wp
   use contact2d_stiffness, only: stiffness_t, omp_min_nodes
   use contact2d_loading, only: loading_t
   implicit none
   private
   public :: damping_estimate_t

   !> The marks of the last estimate and the dofs where the prescribed increment acts.
   type :: damping_estimate_t
      !> u and K u at the last estimate; work: du_p on the prescribed dofs, else 0
      real(wp), allocatable :: u_mark(:, :), f_mark(:, :), work(:, :)
      integer, allocatable :: pres_elements(:)   !< elements touching a prescribed dof
      !> the dofs of pres_elements (flattened), where K du_p is not zero
      integer, allocatable :: pres_dofs(:)
      !> per dof (flattened): 1 free, 0 prescribed, -1 free among pres_dofs (rayleigh_blocks)
      real(wp), allocatable :: rmask(:)
      real(wp), allocatable :: kdu(:, :)   !< K du_f at pres_dofs [N]
   contains
      procedure :: init => damping_estimate_init
      procedure :: estimate => damping_estimate_estimate
   end type damping_estimate_t

contains

   !> Zero marks; the elements touching prescribed dofs, their dofs and the mask. work must be
   !> allocated (2, nnode) by the caller (the engine allocates it with its other nodal arrays).
   subroutine damping_estimate_init(this, stiff, load, nnode)
      class(damping_estimate_t), intent(inout) :: this
      type(stiffness_t), intent(in) :: stiff
      type(loading_t), intent(in) :: load
      integer, intent(in) :: nnode
      logical, allocatable :: touches(:), mark(:, :)
      integer :: e, a, n
      allocate (this%u_mark(2, nnode), this%f_mark(2, nnode))
      this%u_mark = 0
      this%f_mark = 0
      this%work = 0
      allocate (touches(size(stiff%conn, 2)))
      do e = 1, size(touches)
         touches(e) = any(load%free(:, stiff%conn(:, e)) == 0)
      end do
      this%pres_elements = pack([(e, e=1, size(touches))], touches)
      ! the dofs where K du_p is not zero, and the mask of rayleigh_blocks
      allocate (mark(2, nnode))
      mark = .false.
      do e = 1, size(this%pres_elements)
         do a = 1, size(stiff%conn, 1)
            mark(:, stiff%conn(a, this%pres_elements(e))) = .true.
         end do
      end do
      this%pres_dofs = pack([(n, n=1, 2*nnode)], reshape(mark, [2*nnode]))
      this%rmask = reshape(merge(-load%free, load%free, mark .and. load%free > 0), [2*nnode])
      allocate (this%kdu(2, nnode))
      this%kdu = 0
   end subroutine damping_estimate_init

   !> A new alpha_next = min(2 omega_1, 2/dt) from (u, f_int = K u), kept when either quotient
   !> sum is not positive. (u, f_int) and the stored mark are consistent pairs:
   !> K du_f = (f_int - f_mark) - K du_p, and K du_p only involves the elements that touch a
   !> prescribed dof. K du_f is formed apart on their dofs only (kdu) and put in f_mark as
   !> -K du_f; one pass over all dofs then takes f_int - f_mark elsewhere, and f_mark itself
   !> there (rayleigh_blocks). partial(1:2, :) is the caller's per-block work array.
   !> nowned: the Rayleigh sums run over the nodes 1 .. nowned that this process owns (contact2d_layout)
   subroutine damping_estimate_estimate(this, stiff, load, nowned, nblock, block_size, u, fint, mdof, partial, dt, &
                                        alpha_next)
      class(damping_estimate_t), intent(inout) :: this
      type(stiffness_t), intent(in) :: stiff
      type(loading_t), intent(in) :: load
      integer, intent(in) :: nowned, nblock, block_size
      real(wp), intent(in), contiguous :: u(:, :), fint(:, :)   !< u^n [mm], K u^n [N]
      real(wp), intent(in), contiguous :: mdof(:)              !< lumped mass per dof [t]
      real(wp), intent(inout), contiguous :: partial(:, :)     !< per-block sums (4, nblock)
      real(wp), intent(in) :: dt                               !< [s]
      real(wp), intent(inout) :: alpha_next                    !< [1/s]
      real(wp) :: num, den
      integer :: p, b
      ! K du = f_int - f_mark on the dofs of the elements that touch a prescribed dof; then
      ! subtract K du_p there, du_p being zero but on the prescribed dofs
      call pres_difference(size(this%pres_dofs), this%pres_dofs, fint, this%f_mark, this%kdu)
      do p = 1, load%npres
         this%work(load%pcomp(p), load%pnode(p)) = u(load%pcomp(p), load%pnode(p)) &
                                                   - this%u_mark(load%pcomp(p), load%pnode(p))
      end do
      call stiff%apply_elements(this%pres_elements, this%work, this%kdu, subtract=.true.)
      do p = 1, load%npres
         this%work(load%pcomp(p), load%pnode(p)) = 0
      end do
      call pres_negate(size(this%pres_dofs), this%pres_dofs, this%kdu, this%f_mark)
      ! du_f^T K du_f and du_f^T M du_f by blocks; the marks move to (u, f_int)
      call rayleigh_blocks(2*nowned, nblock, block_size, u, fint, this%rmask, mdof, &
                           this%u_mark, this%f_mark, partial)
      num = 0
      den = 0
      do b = 1, nblock
         num = num + partial(1, b)
         den = den + partial(2, b)
      end do
      if (num > 0 .and. den > 0) alpha_next = min(2*sqrt(num/den), 2/dt)
   end subroutine damping_estimate_estimate

   !> d = a - f at the listed dofs (flattened arrays).
   subroutine pres_difference(n, dof, a, f, d)
      integer, intent(in) :: n, dof(n)
      real(wp), intent(in) :: a(*), f(*)
      real(wp), intent(inout) :: d(*)
      integer :: q
      do q = 1, n
         d(dof(q)) = a(dof(q)) - f(dof(q))
      end do
   end subroutine pres_difference

   !> f = -d at the listed dofs (flattened arrays).
   subroutine pres_negate(n, dof, d, f)
      integer, intent(in) :: n, dof(n)
      real(wp), intent(in) :: d(*)
      real(wp), intent(inout) :: f(*)
      integer :: q
      do q = 1, n
         f(dof(q)) = -d(dof(q))
      end do
   end subroutine pres_negate

   !> Per block: sum of du_f kdu and of m du_f^2 with du_f = (u - u_mark) |mask| and
   !> kdu = max(mask, 0) f_int - f_mark: f_int - f_mark where mask = 1 (exact: 1 f_int = f_int),
   !> -f_mark where mask = -1 (exact: 0 f_int - f_mark, also if contracted to an FMA), du_f = 0
   !> where mask = 0; then u_mark = u, f_mark = f_int. Block sums are added in order by the
   !> caller (thread-independent bits).
   subroutine rayleigh_blocks(ndof, nblock, block_size, u, fint, mask, mdof, u_mark, f_mark, partial)
      integer, intent(in) :: ndof, nblock, block_size
      real(wp), intent(in) :: u(ndof), fint(ndof), mask(ndof), mdof(ndof)
      real(wp), intent(inout) :: u_mark(ndof), f_mark(ndof)
      real(wp), intent(inout) :: partial(4, nblock)
      integer :: b, i
      real(wp) :: du, num, den
      !$omp parallel do schedule(static) private(i, du, num, den) if(ndof >= 2*omp_min_nodes)
      do b = 1, nblock
         num = 0
         den = 0
         !$omp simd private(du) reduction(+:num, den)
         do i = 2*(b - 1)*block_size + 1, min(2*b*block_size, ndof)
            du = (u(i) - u_mark(i))*abs(mask(i))
            num = num + du*(max(mask(i), 0.0_wp)*fint(i) - f_mark(i))
            den = den + mdof(i)*du*du
            u_mark(i) = u(i)
            f_mark(i) = fint(i)
         end do
         partial(1, b) = num
         partial(2, b) = den
      end do
      !$omp end parallel do
   end subroutine rayleigh_blocks
end module contact2d_damping_estimate
