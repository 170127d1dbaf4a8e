!> The KKT residuals that prove a static solution (docs/static.md "Algorithm" 6): pure arithmetic
!> on plain arrays, so that a hand-solved problem checks it (tests/solvers/test_kkt.pf).
module contact2d_kkt
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: kkt_names, kkt_values, absmax

   !> KKT residual names (summary and HDF5 attributes kkt_<name>), all relative.
   character(len=24), parameter :: kkt_names(4) = [character(len=24) :: &
      'normal_feasibility', 'complementarity', 'friction_feasibility', 'equilibrium']

contains

   !> The four relative KKT residuals (kkt_names, docs/static.md "Algorithm" 6) on plain arrays.
   !> u: the full displacement (2, nnode), for max|u|. Per contact node (P0: per dual cell) e the
   !> normal distance d = u.n - g (P0: (D d)_i / w_i) and lam its multiplier (F_n; P0: mu_n).
   !> Per tangential unknown ft its F_t, lim its friction limit (s w, mu F_n, 0) and psi its
   !> tangential displacement in the increment, (u - u_prev).t. The body receives -F_t t, so
   !> friction opposes the slip when F_t psi = lim |psi|. Per dof (2, nnode): fext, fc (the contact
   !> force on the body), fint = K u, free (.false. on prescribed dofs, whose residual is their
   !> reaction).
   !>   normal feasibility   max(e, 0) / max|u|
   !>   complementarity      max(|lam e| / (max|lam| max|u|), max(-lam, 0) / max|lam|)
   !>   friction             max(|F_t| - lim, 0) / max lim and |lim |psi| - F_t psi| / (max lim max|u|)
   !>   equilibrium          ||fext + fc - fint||_inf on the free dofs / max(reaction, fext, fc)
   !> Without contact (size(e) = 0) the first three are 0.
   pure function kkt_values(u, e, lam, ft, lim, psi, fext, fc, fint, free) result(kkt)
      real(wp), intent(in) :: u(:, :), e(:), lam(:), ft(:), lim(:), psi(:), fext(:, :), fc(:, :), fint(:, :)
      logical, intent(in) :: free(:, :)
      real(wp) :: kkt(4)
      real(wp) :: umax, lmax, r, rfree, scale
      integer :: n, c, k

      kkt = 0
      ! equilibrium first: its force scale also scales the friction residual when no node has a limit
      rfree = 0
      scale = 0
      do n = 1, size(u, 2)
         do c = 1, 2
            r = fext(c, n) + fc(c, n) - fint(c, n)
            if (free(c, n)) then
               rfree = max(rfree, abs(r))
            else
               scale = max(scale, abs(r))
            end if
            scale = max(scale, abs(fext(c, n)), abs(fc(c, n)))
         end do
      end do
      ! (nothing loaded, nothing reacting: the residual is the absolute one, 0/0 never formed)
      kkt(4) = rfree
      if (scale > 0) kkt(4) = rfree/scale
      umax = max(maxval(abs(u)), tiny(1.0_wp))
      if (size(e) > 0) then
         lmax = max(maxval(abs(lam)), tiny(1.0_wp))
         kkt(1) = max(maxval(e), 0.0_wp)/umax
         ! (lmax umax floored: both may be near tiny on the first of many small increments, and
         ! their product would be 0, the ratio 0/0)
         kkt(2) = max(maxval(abs(lam*e))/max(lmax*umax, tiny(1.0_wp)), maxval(-lam)/lmax, 0.0_wp)
         ! no limit anywhere (Coulomb with every node separated, tresca_scope = 'contact' with none
         ! in contact): any F_t is wrong, measured against the problem's forces (F_c holds F_t, so
         ! the ratio is finite), not against a limit of 0
         lmax = absmax(lim)
         if (lmax == 0) lmax = scale
         lmax = max(lmax, tiny(1.0_wp))
         do k = 1, size(ft)
            kkt(3) = max(kkt(3), max(abs(ft(k)) - lim(k), 0.0_wp)/lmax, &
                         abs(lim(k)*abs(psi(k)) - ft(k)*psi(k))/max(lmax*umax, tiny(1.0_wp)))
         end do
      end if
   end function kkt_values

   !> max |x|, 0 for an empty x.
   pure real(wp) function absmax(x)
      real(wp), intent(in) :: x(:)
      absmax = 0
      if (size(x) > 0) absmax = maxval(abs(x))
   end function absmax
end module contact2d_kkt
