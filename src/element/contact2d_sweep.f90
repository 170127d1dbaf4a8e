!> One sweep over memory per explicit step (issue 13, docs/performance.md): row by row, the
!> corrector of the previous step (velocities and the kinetic, damping and strain energies), the
!> internal force K u^n and the predictor of this step, so that every node is loaded once.
!>
!> Structured meshes of equal elements use nine stencils of 2 x 2 blocks (interior, four edges,
!> four corners): every grid row is one vectorised loop, its two end nodes are done apart. Other
!> meshes use the block-CSR rows of contact2d_stiffness. Sums are per grid row (or per fixed
!> chunk of block rows) and added in order by the caller, so the bits do not depend on the
!> number of threads or on how rows are shared among them.
module contact2d_sweep
   use contact2d_kinds, only: wp
   use contact2d_stiffness, only: stiffness_t, omp_min_nodes
   implicit none
   private
   public :: sweep_stencils, sweep_parts, sweep_step

   !> Block rows per partial sum on general meshes.
   integer, parameter :: chunk_rows = 256
   !> Offsets (i, j) of the four local nodes of a structured element from its bottom-left node.
   integer, parameter :: off(2, 4) = reshape([0, 0, 1, 0, 1, 1, 0, 1], [2, 4])

contains

   !> The nine stencils s(:, :, di, dj, ct, rt) of a structured mesh: column type ct and row type
   !> rt are 1 on the low boundary (i = 0 or j = 0), 2 inside, 3 on the high boundary; blocks of
   !> missing neighbours are zero. A node sums the blocks of the elements around it that exist,
   !> in the local-node order of the interior stencil (the same bits as contact2d_stiffness).
   pure subroutine sweep_stencils(ke, s)
      real(wp), intent(in) :: ke(8, 8)
      real(wp), intent(out) :: s(2, 2, -1:1, -1:1, 3, 3)
      integer :: ct, rt, a, b, d(2)
      s = 0
      do rt = 1, 3
         do ct = 1, 3
            do a = 1, 4
               ! node is local node a of the element whose bottom-left node is at -off(:, a)
               if (ct == 1 .and. off(1, a) == 1) cycle   ! no element to the left
               if (ct == 3 .and. off(1, a) == 0) cycle   ! none to the right
               if (rt == 1 .and. off(2, a) == 1) cycle   ! none below
               if (rt == 3 .and. off(2, a) == 0) cycle   ! none above
               do b = 1, 4
                  d = off(:, b) - off(:, a)
                  s(:, :, d(1), d(2), ct, rt) = s(:, :, d(1), d(2), ct, rt) + ke(2*a - 1:2*a, 2*b - 1:2*b)
               end do
            end do
         end do
      end do
   end subroutine sweep_stencils

   !> Number of partial sums (grid rows or chunks of block rows) of sweep_step.
   pure integer function sweep_parts(stiff) result(n)
      type(stiffness_t), intent(in) :: stiff
      if (stiff%structured) then
         n = stiff%ny + 1
      else
         n = (size(stiff%row_node) + chunk_rows - 1)/chunk_rows
      end if
   end function sweep_parts

   !> One sweep: if pending, first the corrector of the previous step at each node,
   !>    v = (u - uold)/dt,  partial = (sum m v^2, sum m ((v + v_old)/2)^2, sum u . f_old,
   !>    sum m (v - v_old)^2);
   !> then f = K u and w = u + c1 v - c2 M^-1 f.
   subroutine sweep_step(stiff, s, u, uold, v, f, minv, mass, mdof, minvdof, c1, c2, rdt, pending, w, partial)
      type(stiffness_t), intent(in) :: stiff
      real(wp), intent(in) :: s(2, 2, -1:1, -1:1, 3, 3)   !< stencils (structured meshes)
      real(wp), intent(in) :: u(:, :)       !< u^n (2, nnode) [mm]
      real(wp), intent(in) :: uold(:, :)    !< u^(n-1) (used if pending) [mm]
      real(wp), intent(inout) :: v(:, :)    !< v^(n-3/2) in, v^(n-1/2) out if pending [mm/s]
      real(wp), intent(inout) :: f(:, :)    !< K u^(n-1) in, K u^n out [N]
      real(wp), intent(in) :: minv(:), mass(:)         !< per node
      real(wp), intent(in) :: mdof(:), minvdof(:)      !< per dof (2 nnode)
      real(wp), intent(in) :: c1, c2, rdt
      logical, intent(in) :: pending
      real(wp), intent(inout) :: w(:, :)    !< u~ out [mm]
      real(wp), intent(inout) :: partial(:, :)   !< (4, sweep_parts)
      if (stiff%structured) then
         call sweep_grid(stiff%nx, stiff%ny, s, u, uold, v, f, mdof, minvdof, c1, c2, rdt, pending, w, partial, &
                         stiff%nnode >= omp_min_nodes)
      else
         call sweep_rows(stiff, u, uold, v, f, minv, mass, c1, c2, rdt, pending, w, partial)
      end if
   end subroutine sweep_step

   subroutine sweep_grid(nx, ny, s, u, uold, v, f, mdof, minvdof, c1, c2, rdt, pending, w, partial, par)
      integer, intent(in) :: nx, ny
      real(wp), intent(in) :: s(2, 2, -1:1, -1:1, 3, 3)
      real(wp), intent(in) :: u(2, 0:nx, 0:ny), uold(2, 0:nx, 0:ny), mdof(2, 0:nx, 0:ny), minvdof(2, 0:nx, 0:ny)
      real(wp), intent(inout) :: v(2, 0:nx, 0:ny), f(2, 0:nx, 0:ny), w(2, 0:nx, 0:ny)
      real(wp), intent(in) :: c1, c2, rdt
      logical, intent(in) :: pending, par
      real(wp), intent(inout) :: partial(4, 0:ny)
      integer :: j, rt
      real(wp) :: cv(0:7, -3:3, 3, 3)
      call flat_coefficients(s, cv)
      !$omp parallel do schedule(dynamic) if(par) private(rt)
      do j = 0, ny
         rt = merge(1, merge(3, 2, j == ny), j == 0)
         call grid_row(2*(nx + 1), u(1, 0, max(j - 1, 0)), u(1, 0, j), u(1, 0, min(j + 1, ny)), uold(1, 0, j), &
                       v(1, 0, j), f(1, 0, j), mdof(1, 0, j), minvdof(1, 0, j), cv(:, :, :, rt), c1, c2, rdt, &
                       pending, w(1, 0, j), partial(:, j))
         call end_node(nx, ny, s, 0, j, 1, rt, u, v, f, minvdof, c1, c2, w)
         call end_node(nx, ny, s, nx, j, 3, rt, u, v, f, minvdof, c1, c2, w)
      end do
      !$omp end parallel do
   end subroutine sweep_grid

   !> One grid row as flat arrays of interleaved (x, y) values (n = 2 (nx + 1)): the corrector
   !> of the last step on the whole row (if pending; it reads f before it is overwritten), then
   !> K u and the predictor on the interior nodes while the row is in cache.
   subroutine grid_row(n, um, u0, up, uo, v, f, m, minv, cv, c1, c2, rdt, pending, w, part)
      integer, intent(in) :: n
      real(wp), intent(in) :: um(0:n - 1), u0(0:n - 1), up(0:n - 1), uo(0:n - 1), m(0:n - 1), minv(0:n - 1)
      real(wp), intent(in) :: cv(0:7, -3:3, 3), c1, c2, rdt
      real(wp), intent(inout) :: v(0:n - 1), f(0:n - 1), w(0:n - 1)
      logical, intent(in) :: pending
      real(wp), intent(out) :: part(4)
      integer :: b, l, p, nb
      real(wp) :: c(0:7, -3:3, 3), sm, s0, sp, vn, ek, ed, es, ea
      ek = 0
      ed = 0
      es = 0
      ea = 0
      if (pending) then
         !$omp simd private(vn) reduction(+:ek, ed, es, ea)
         do p = 0, n - 1
            vn = (u0(p) - uo(p))*rdt
            ek = ek + m(p)*vn*vn
            ed = ed + m(p)*(0.5_wp*(vn + v(p)))**2
            es = es + u0(p)*f(p)
            ea = ea + m(p)*(vn - v(p))**2
            v(p) = vn
         end do
      end if
      part = [ek, ed, es, ea]
      if (n < 6) return   ! one column of elements: no interior node (the end nodes follow)
      ! blocks start at odd p (a y output): c(l) holds the coefficients of parity mod(l + 1, 2);
      ! a local copy, so no aliasing and the coefficients stay in registers
      do l = 0, 7
         c(l, :, :) = cv(mod(l + 1, 2), :, :)
      end do
      ! outputs p = 2 .. n - 3 (the interior nodes); u_r(p + o) must stay within 0 .. n - 1, so
      ! the first (x, offset -3) and the last (y, offset +3) output leave out the term whose
      ! coefficient is zero; the others go by blocks of eight, then one by one
      p = 2
      f(p) = ((cv(0, -2, 1)*um(p - 2) + cv(0, -1, 1)*um(p - 1) + cv(0, 0, 1)*um(p) + cv(0, 1, 1)*um(p + 1) &
               + cv(0, 2, 1)*um(p + 2) + cv(0, 3, 1)*um(p + 3)) &
              + (cv(0, -2, 2)*u0(p - 2) + cv(0, -1, 2)*u0(p - 1) + cv(0, 0, 2)*u0(p) + cv(0, 1, 2)*u0(p + 1) &
                 + cv(0, 2, 2)*u0(p + 2) + cv(0, 3, 2)*u0(p + 3))) &
             + (cv(0, -2, 3)*up(p - 2) + cv(0, -1, 3)*up(p - 1) + cv(0, 0, 3)*up(p) + cv(0, 1, 3)*up(p + 1) &
                + cv(0, 2, 3)*up(p + 2) + cv(0, 3, 3)*up(p + 3))
      w(p) = u0(p) + c1*v(p) - c2*minv(p)*f(p)
      nb = (n - 6)/8
      do b = 0, nb - 1
         !$omp simd private(p, sm, s0, sp)
         do l = 0, 7
            p = 3 + 8*b + l
            sm = c(l, -3, 1)*um(p - 3) + c(l, -2, 1)*um(p - 2) + c(l, -1, 1)*um(p - 1) + c(l, 0, 1)*um(p) &
                 + c(l, 1, 1)*um(p + 1) + c(l, 2, 1)*um(p + 2) + c(l, 3, 1)*um(p + 3)
            s0 = c(l, -3, 2)*u0(p - 3) + c(l, -2, 2)*u0(p - 2) + c(l, -1, 2)*u0(p - 1) + c(l, 0, 2)*u0(p) &
                 + c(l, 1, 2)*u0(p + 1) + c(l, 2, 2)*u0(p + 2) + c(l, 3, 2)*u0(p + 3)
            sp = c(l, -3, 3)*up(p - 3) + c(l, -2, 3)*up(p - 2) + c(l, -1, 3)*up(p - 1) + c(l, 0, 3)*up(p) &
                 + c(l, 1, 3)*up(p + 1) + c(l, 2, 3)*up(p + 2) + c(l, 3, 3)*up(p + 3)
            f(p) = (sm + s0) + sp
            w(p) = u0(p) + c1*v(p) - c2*minv(p)*f(p)
         end do
      end do
      do p = 3 + 8*nb, n - 4
         l = mod(p, 2)
         sm = cv(l, -3, 1)*um(p - 3) + cv(l, -2, 1)*um(p - 2) + cv(l, -1, 1)*um(p - 1) + cv(l, 0, 1)*um(p) &
              + cv(l, 1, 1)*um(p + 1) + cv(l, 2, 1)*um(p + 2) + cv(l, 3, 1)*um(p + 3)
         s0 = cv(l, -3, 2)*u0(p - 3) + cv(l, -2, 2)*u0(p - 2) + cv(l, -1, 2)*u0(p - 1) + cv(l, 0, 2)*u0(p) &
              + cv(l, 1, 2)*u0(p + 1) + cv(l, 2, 2)*u0(p + 2) + cv(l, 3, 2)*u0(p + 3)
         sp = cv(l, -3, 3)*up(p - 3) + cv(l, -2, 3)*up(p - 2) + cv(l, -1, 3)*up(p - 1) + cv(l, 0, 3)*up(p) &
              + cv(l, 1, 3)*up(p + 1) + cv(l, 2, 3)*up(p + 2) + cv(l, 3, 3)*up(p + 3)
         f(p) = (sm + s0) + sp
         w(p) = u0(p) + c1*v(p) - c2*minv(p)*f(p)
      end do
      p = n - 3
      f(p) = ((cv(1, -3, 1)*um(p - 3) + cv(1, -2, 1)*um(p - 2) + cv(1, -1, 1)*um(p - 1) + cv(1, 0, 1)*um(p) &
               + cv(1, 1, 1)*um(p + 1) + cv(1, 2, 1)*um(p + 2)) &
              + (cv(1, -3, 2)*u0(p - 3) + cv(1, -2, 2)*u0(p - 2) + cv(1, -1, 2)*u0(p - 1) + cv(1, 0, 2)*u0(p) &
                 + cv(1, 1, 2)*u0(p + 1) + cv(1, 2, 2)*u0(p + 2))) &
             + (cv(1, -3, 3)*up(p - 3) + cv(1, -2, 3)*up(p - 2) + cv(1, -1, 3)*up(p - 1) + cv(1, 0, 3)*up(p) &
                + cv(1, 1, 3)*up(p + 1) + cv(1, 2, 3)*up(p + 2))
      w(p) = u0(p) + c1*v(p) - c2*minv(p)*f(p)
   end subroutine grid_row

   !> The interior stencils of the three row types on a grid row seen as one flat array of
   !> interleaved (x, y) values: output p takes sum over rows r and offsets o = -3..3 of
   !> cv(mod(p, 8), o, r) u_r(p + o) (cv repeats with period 2: x and y outputs), so eight
   !> outputs are one vector operation with no shuffles.
   pure subroutine flat_coefficients(s, cv)
      real(wp), intent(in) :: s(2, 2, -1:1, -1:1, 3, 3)
      real(wp), intent(out) :: cv(0:7, -3:3, 3, 3)
      integer :: rt, r, di, l
      cv = 0
      do rt = 1, 3
         do r = 1, 3
            do di = -1, 1
               do l = 0, 7, 2
                  ! x output at flat 2i: u_x(i + di) at offset 2 di, u_y(i + di) at 2 di + 1
                  cv(l, 2*di, r, rt) = s(1, 1, di, r - 2, 2, rt)
                  cv(l, 2*di + 1, r, rt) = s(1, 2, di, r - 2, 2, rt)
                  ! y output at flat 2i + 1: u_x(i + di) at 2 di - 1, u_y(i + di) at 2 di
                  cv(l + 1, 2*di - 1, r, rt) = s(2, 1, di, r - 2, 2, rt)
                  cv(l + 1, 2*di, r, rt) = s(2, 2, di, r - 2, 2, rt)
               end do
            end do
         end do
      end do
   end subroutine flat_coefficients


   !> K u and the predictor at the end node (i, j) of a grid row, column type ct and row type
   !> rt, bounds checked.
   subroutine end_node(nx, ny, s, i, j, ct, rt, u, v, f, minv, c1, c2, w)
      integer, intent(in) :: nx, ny, i, j, ct, rt
      real(wp), intent(in) :: s(2, 2, -1:1, -1:1, 3, 3)
      real(wp), intent(in) :: u(2, 0:nx, 0:ny), v(2, 0:nx, 0:ny), minv(2, 0:nx, 0:ny)
      real(wp), intent(inout) :: f(2, 0:nx, 0:ny), w(2, 0:nx, 0:ny)
      real(wp), intent(in) :: c1, c2
      integer :: di, dj, ii, jj
      real(wp) :: gx, gy
      gx = 0
      gy = 0
      do dj = -1, 1
         jj = j + dj
         if (jj < 0 .or. jj > ny) cycle
         do di = -1, 1
            ii = i + di
            if (ii < 0 .or. ii > nx) cycle
            gx = gx + s(1, 1, di, dj, ct, rt)*u(1, ii, jj) + s(1, 2, di, dj, ct, rt)*u(2, ii, jj)
            gy = gy + s(2, 1, di, dj, ct, rt)*u(1, ii, jj) + s(2, 2, di, dj, ct, rt)*u(2, ii, jj)
         end do
      end do
      f(1, i, j) = gx
      f(2, i, j) = gy
      w(1, i, j) = u(1, i, j) + c1*v(1, i, j) - c2*minv(1, i, j)*gx
      w(2, i, j) = u(2, i, j) + c1*v(2, i, j) - c2*minv(2, i, j)*gy
   end subroutine end_node

   !> General meshes: the block-CSR rows, chunk by chunk.
   subroutine sweep_rows(stiff, u, uold, v, f, minv, mass, c1, c2, rdt, pending, w, partial)
      type(stiffness_t), intent(in) :: stiff
      real(wp), intent(in) :: u(:, :), uold(:, :), minv(:), mass(:), c1, c2, rdt
      real(wp), intent(inout) :: v(:, :), f(:, :), w(:, :), partial(:, :)
      logical, intent(in) :: pending
      integer :: c, r, k, m, n
      real(wp) :: fx, fy, vx, vy, ek, ed, es, ea
      !$omp parallel do schedule(dynamic) if(stiff%nnode >= omp_min_nodes) &
      !$omp private(r, k, m, n, fx, fy, vx, vy, ek, ed, es, ea)
      do c = 1, size(partial, 2)
         ek = 0
         ed = 0
         es = 0
         ea = 0
         do r = (c - 1)*chunk_rows + 1, min(c*chunk_rows, size(stiff%row_node))
            n = stiff%row_node(r)
            if (pending) then
               vx = (u(1, n) - uold(1, n))*rdt
               vy = (u(2, n) - uold(2, n))*rdt
               ek = ek + mass(n)*(vx*vx + vy*vy)
               ed = ed + mass(n)*((0.5_wp*(vx + v(1, n)))**2 + (0.5_wp*(vy + v(2, n)))**2)
               es = es + u(1, n)*f(1, n) + u(2, n)*f(2, n)
               ea = ea + mass(n)*((vx - v(1, n))**2 + (vy - v(2, n))**2)
               v(1, n) = vx
               v(2, n) = vy
            else
               vx = v(1, n)
               vy = v(2, n)
            end if
            fx = 0
            fy = 0
            do k = stiff%row_start(r), stiff%row_start(r + 1) - 1
               m = stiff%blk_col(k)
               fx = fx + stiff%blk(1, 1, k)*u(1, m) + stiff%blk(1, 2, k)*u(2, m)
               fy = fy + stiff%blk(2, 1, k)*u(1, m) + stiff%blk(2, 2, k)*u(2, m)
            end do
            f(1, n) = fx
            f(2, n) = fy
            w(1, n) = u(1, n) + c1*vx - c2*minv(n)*fx
            w(2, n) = u(2, n) + c1*vy - c2*minv(n)*fy
         end do
         partial(:, c) = [ek, ed, es, ea]
      end do
      !$omp end parallel do
   end subroutine sweep_rows
end module contact2d_sweep
