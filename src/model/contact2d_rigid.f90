!> The rigid motions of a body that neither its supports nor contact can stop (docs/static.md
!> "Bodies held by contact"): pure algebra on plain arrays, so that a hand-made body checks it
!> (tests/model/test_rigid.pf).
!>
!> A rigid motion of a 2D body is r(x) = a1 e_x + a2 e_y + a3 (-(y - yc), x - xc)/rho: two
!> translations and the rotation about the centroid c of its nodes, scaled by rho, the root mean
!> square distance of the nodes from c, so that the three columns have the same size. Each
!> support (a prescribed dof (comp, node)) is the row e_comp . r(x_node); each contact node i
!> the row n_i . r(x_i) (its initial normal; a contact force along n_i does work on r unless
!> the row is zero), and where the friction law can carry a tangential force also t_i . r(x_i).
!> A motion is free when every row annihilates it: the null space of the rows, i.e. of the
!> 3 x 3 Gram matrix G = sum_rows row^T row (LAPACK dsyev). An eigenvalue of G below
!> null_tol times the number of rows counts as zero (the rows are of order 1, so a motion a
!> support or contact truly stops gives an eigenvalue of order 1 or more times a squared lever
!> arm / rho^2).
module contact2d_rigid
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   implicit none
   private
   public :: rigid_t, rigid_free_motions, rigid_describe, rigid_field, rigid_drive

   !> An eigenvalue of G at most null_tol * (number of rows) is a free motion.
   real(wp), parameter :: null_tol = 1.0e-10_wp
   !> A free motion whose coefficient on one basis motion is 1 within this is named after it.
   real(wp), parameter :: pure_tol = 1.0e-9_wp

   !> The body's rigid-motion basis and the motions its supports and contact leave free.
   type :: rigid_t
      real(wp) :: centroid(2) = 0   !< centroid c of the body's nodes [mm]
      real(wp) :: rho = 1           !< rms distance of the nodes from c (rotation scale) [mm]
      integer :: nfree = 0          !< free motions (0 to 3)
      !> the free motions, coefficients (a1, a2, a3) of the basis, orthonormal columns (3, nfree)
      real(wp), allocatable :: motion(:, :)
   end type rigid_t

contains

   !> The rigid motions of the body (nodes: its node indices into x) that no row stops: the
   !> supports (free(c, n) = 0 is a prescribed dof), the contact normals (cnode, normal) and,
   !> where carries(i), the contact tangents. stat 1 only if LAPACK fails.
   subroutine rigid_free_motions(x, nodes, free, cnode, normal, tangent, carries, rigid, stat)
      real(wp), intent(in) :: x(:, :)          !< node coordinates (2, nnode) [mm]
      integer, intent(in) :: nodes(:)          !< the body's nodes
      real(wp), intent(in) :: free(:, :)       !< 1 free, 0 prescribed (2, nnode)
      integer, intent(in) :: cnode(:)          !< contact nodes (node indices)
      real(wp), intent(in) :: normal(:, :)     !< their normals (2, size(cnode))
      real(wp), intent(in) :: tangent(:, :)    !< their tangents (2, size(cnode))
      logical, intent(in) :: carries(:)        !< the law can carry a tangential force there
      type(rigid_t), intent(out) :: rigid
      integer, intent(out) :: stat
      real(wp) :: g(3, 3), ev(3), work(16), row(3)
      integer :: k, n, c, nrow, info
      external :: dsyev

      stat = 0
      rigid%centroid = [sum(x(1, nodes)), sum(x(2, nodes))]/size(nodes)
      rigid%rho = sqrt(sum((x(1, nodes) - rigid%centroid(1))**2 + (x(2, nodes) - rigid%centroid(2))**2)/size(nodes))
      if (.not. rigid%rho > 0) rigid%rho = 1
      g = 0
      nrow = 0
      do k = 1, size(nodes)
         n = nodes(k)
         do c = 1, 2
            if (free(c, n) > 0) cycle
            row = basis_row(rigid, x(:, n), unit(c))
            call add(row)
         end do
      end do
      do k = 1, size(cnode)
         call add(basis_row(rigid, x(:, cnode(k)), normal(:, k)))
         if (carries(k)) call add(basis_row(rigid, x(:, cnode(k)), tangent(:, k)))
      end do
      call dsyev('V', 'U', 3, g, 3, ev, work, size(work), info)
      if (info /= 0) then
         stat = 1
         return
      end if
      ! eigenvalues ascending: the first nfree span the null space
      rigid%nfree = count(ev <= null_tol*max(nrow, 1))
      rigid%motion = named_first(g(:, 1:rigid%nfree))
   contains
      subroutine add(r)
         real(wp), intent(in) :: r(3)
         integer :: i, j
         nrow = nrow + 1
         do j = 1, 3
            do i = 1, 3
               g(i, j) = g(i, j) + r(i)*r(j)
            end do
         end do
      end subroutine add
   end subroutine rigid_free_motions

   !> The same null space, its basis motions (translation x, y, rotation) first where they lie
   !> in it (so that a message names them), the rest orthonormalised (Gram-Schmidt) after them.
   pure function named_first(v) result(m)
      real(wp), intent(in) :: v(:, :)
      real(wp) :: m(3, size(v, 2)), e(3), w(3)
      integer :: k, j, i, nm
      nm = 0
      do k = 1, 3
         if (nm == size(v, 2)) exit
         e = 0
         e(k) = 1
         ! e_k in the null space: its projection onto span(v) has norm 1
         if (norm2(matmul(transpose(v), e)) >= 1 - pure_tol) then
            nm = nm + 1
            m(:, nm) = e
         end if
      end do
      do j = 1, size(v, 2)
         if (nm == size(v, 2)) exit
         w = v(:, j)
         do i = 1, nm
            w = w - dot_product(m(:, i), w)*m(:, i)
         end do
         if (norm2(w) > 0.5_wp) then
            nm = nm + 1
            m(:, nm) = w/norm2(w)
         end if
      end do
   end function named_first

   pure function unit(c) result(e)
      integer, intent(in) :: c
      real(wp) :: e(2)
      e = 0
      e(c) = 1
   end function unit

   !> The row d . r_k(p), k = 1, 2, 3, of a direction d at the point p.
   pure function basis_row(rigid, p, d) result(row)
      type(rigid_t), intent(in) :: rigid
      real(wp), intent(in) :: p(2), d(2)
      real(wp) :: row(3)
      row(1) = d(1)
      row(2) = d(2)
      row(3) = (-d(1)*(p(2) - rigid%centroid(2)) + d(2)*(p(1) - rigid%centroid(1)))/rigid%rho
   end function basis_row

   !> The displacement field (2, size(x, 2)) of the motion with coefficients a (per unit a).
   pure function rigid_field(rigid, a, x) result(r)
      type(rigid_t), intent(in) :: rigid
      real(wp), intent(in) :: a(3), x(:, :)
      real(wp) :: r(2, size(x, 2))
      r(1, :) = a(1) - a(3)*(x(2, :) - rigid%centroid(2))/rigid%rho
      r(2, :) = a(2) + a(3)*(x(1, :) - rigid%centroid(1))/rigid%rho
   end function rigid_field

   !> Whether a load drives the free motion a: the work per unit motion of the nodal forces
   !> weight(p) e_comp(p) at node(p) of one load curve, sum_p weight_p r_comp(x_node), against
   !> the round-off of that sum (1e-12 of sum_p |weight_p r_comp|). curve(p) names the curve of
   !> each force; each curve is judged alone (its values change in time independently).
   pure logical function rigid_drive(rigid, a, x, node, comp, curve, weight) result(drives)
      type(rigid_t), intent(in) :: rigid
      real(wp), intent(in) :: a(3), x(:, :), weight(:)
      integer, intent(in) :: node(:), comp(:), curve(:)
      real(wp) :: r(2, size(x, 2)), work, scale
      integer :: p, id
      drives = .false.
      if (size(node) == 0) return
      r = rigid_field(rigid, a, x)
      do id = 1, maxval(curve)
         work = 0
         scale = 0
         do p = 1, size(node)
            if (curve(p) /= id) cycle
            work = work + weight(p)*r(comp(p), node(p))
            scale = scale + abs(weight(p)*r(comp(p), node(p)))
         end do
         if (abs(work) > 1.0e-12_wp*scale) drives = .true.
      end do
   end function rigid_drive

   !> A free motion in words: 'translate along x', 'translate along y', 'rotate about its
   !> centroid (xc, yc)', 'translate along (a, b)' or 'rotate about (px, py)' (the point a
   !> rotation plus translation leaves fixed).
   function rigid_describe(rigid, a) result(text)
      type(rigid_t), intent(in) :: rigid
      real(wp), intent(in) :: a(3)
      character(len=:), allocatable :: text
      real(wp) :: omega, p(2), b(3)
      b = a/norm2(a)
      if (abs(abs(b(1)) - 1) <= pure_tol) then
         text = 'translate along x'
      else if (abs(abs(b(2)) - 1) <= pure_tol) then
         text = 'translate along y'
      else if (abs(abs(b(3)) - 1) <= pure_tol) then
         text = 'rotate about its centroid ('//str(rigid%centroid(1))//', '//str(rigid%centroid(2))//')'
      else if (abs(b(3)) <= pure_tol) then
         text = 'translate along ('//str(b(1)/norm2(b(1:2)))//', '//str(b(2)/norm2(b(1:2)))//')'
      else
         ! r(p) = 0: t + omega (-(py - yc), px - xc) = 0 with t = (b1, b2), omega = b3 / rho
         omega = b(3)/rigid%rho
         p(1) = rigid%centroid(1) - b(2)/omega
         p(2) = rigid%centroid(2) + b(1)/omega
         text = 'rotate about ('//str(p(1))//', '//str(p(2))//')'
      end if
   end function rigid_describe
end module contact2d_rigid
