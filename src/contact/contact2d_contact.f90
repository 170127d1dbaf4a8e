!> Contact of the body with a rigid straight obstacle: forward-increment Lagrange multipliers
!> (Carpenter, Taylor & Katona 1991) with P1 or P0 multipliers and Tresca or Coulomb friction
!> (SPEC sections 3, 4, 6; the paper's (10)-(13) and (17); Coulomb and the friction-law seam:
!> docs/friction.md), or a penalty for comparison.
!>
!> Geometry (docs/geometry.md): contact nodes x_0..x_N ordered by abscissa; per node the gap
!> g_i and the body's outward normal n_i = -nu_i from the node's closest point on the obstacle,
!> t_i = (-n2, n1). With geometry 'initial' (a fixed obstacle, small deformation) they are
!> found once, in the initial configuration; with 'current' (finite sliding, a moving obstacle)
!> each step projects the predicted position x + u~ onto the obstacle at t_(n+1) and refreshes
!> them (update_geometry), and friction acts on the slip relative to the obstacle's surface;
!> weights w_i = integral of phi_i, the friction law made from them (its limits: Tresca s_i w_i),
!> and for P0 the coupling D (tridiagonal) and the LCP matrix D M^-1 D^T (five bands). Forces: F_n, F_t per node; the force on the body
!> is -F_n n_i - F_t t_i. With 'initial' the step reads these per-node arrays only, never the
!> obstacle's shape; with 'current' update_geometry refills them from the obstacle first.
module contact2d_contact
   use contact2d_kinds, only: wp, i8
   use contact2d_strings, only: str
   use contact2d_messages, only: messages_t
   use contact2d_lcp, only: lcp_t
   use contact2d_friction, only: friction_law_t
   use contact2d_friction_input, only: friction_input_t
   use contact2d_obstacle, only: obstacle_t
   use contact2d_master_body, only: master_body_t
   implicit none
   private
   public :: contact_t, contact_config_t, status_separated, status_stick, status_slip

   integer, parameter :: status_separated = 0, status_stick = 1, status_slip = 2
   integer, parameter :: multiplier_p1 = 1, multiplier_p0 = 0
   !> |F_t| >= (1 - slip_tol) s_i w_i counts as slip in the status (SPEC section 3).
   real(wp), parameter :: slip_tol = 1.0e-8_wp
   !> rows of contact_t%rec
   integer, parameter :: rec_nx = 1, rec_ny = 2, rec_tx = 3, rec_ty = 4, rec_gap = 5, rec_mass = 6, &
                         rec_cmass = 7, rec_free0 = 8, nrec = 8

   !> Settings of the contact set-up (one object instead of a long positional list).
   type :: contact_config_t
      class(obstacle_t), allocatable :: obstacle   !< the rigid obstacle
      !> point O of the abscissa (huge() components: the first node) [mm]
      real(wp) :: origin(2) = huge(1.0_wp)
      !> node numbers as the user's mesh file has them, for messages (not allocated: the
      !> solver's own numbers)
      integer, allocatable :: file_id(:)
      character(len=4) :: multiplier = 'P1'        !< 'P1' | 'P0'
      !> the friction law's input (the deck's contact:friction and its variables), which makes
      !> the law on the contact nodes (docs/friction.md section 2); none: frictionless
      class(friction_input_t), allocatable :: friction
      character(len=8) :: method = 'lagrange'      !< 'lagrange' | 'penalty'
      real(wp) :: penalty_stiffness = 0            !< k_p [MPa/mm]
      !> gaps and normals in the current configuration, refreshed each step (docs/geometry.md);
      !> else in the initial one, fixed (a moving obstacle needs .true.: the deck's check)
      logical :: current = .false.
      !> the master side as another body's boundary (instead of the obstacle; docs/geometry.md
      !> "Two bodies"): its chain of mesh nodes in order, and a point inside that body next to
      !> the chain's first edge (it orients the master's normals)
      integer, allocatable :: master_nodes(:)
      real(wp) :: master_inside(2) = 0
      !> the most a slave node may start inside the master body [mm] (round-off of the meshes)
      real(wp) :: overlap_tol = 0
   end type contact_config_t

   !> A candidate contact boundary and the multipliers of the last step.
   type :: contact_t
      logical :: active = .false.           !< the model has contact
      integer :: nc = 0                     !< number of contact nodes
      integer :: multiplier = multiplier_p1 !< P1 or P0
      logical :: penalty = .false.          !< method = 'penalty' (normal force k_p w_i max(d_i, 0))
      real(wp) :: penalty_stiffness = 0     !< k_p [MPa/mm]
      logical :: friction = .false.         !< Tresca or Coulomb friction (law allocated)
      class(friction_law_t), allocatable :: law   !< the friction law (docs/friction.md section 2)
      !> the tangential limits never change (no friction, or law%fixed): slip_limit is
      !> set once and P1 finds F_n in the same pass as the rest of the step
      logical :: limits_fixed = .false.
      !> the law makes a node with F_n,i > 0 carry friction (law%depends_on_fn: Coulomb with
      !> mu > 0), so with P0 it counts as touching even where its own dual cell is open
      logical :: fn_touches = .false.
      real(wp), allocatable :: normal(:, :)   !< n_i, outward normal of the body (2, nc)
      real(wp), allocatable :: tangent(:, :)  !< t_i = (-n2, n1) (2, nc)
      integer, allocatable :: node(:)       !< mesh node of each contact node (nc)
      real(wp), allocatable :: abscissa(:)  !< curvilinear abscissa from O [mm]
      real(wp), allocatable :: h(:)         !< segment lengths h_i = |x_(i+1) - x_i| (nc-1) [mm]
      real(wp), allocatable :: weight(:)    !< w_i = integral of phi_i over Gamma_c [mm]
      real(wp), allocatable :: gap(:)       !< initial gap g_i [mm]
      real(wp), allocatable :: threshold(:) !< the law's per-node threshold s_i [MPa] (law%node_thresholds)
      real(wp), allocatable :: slip_limit(:)  !< tangential limit of the last step [N] (the law's)
      real(wp), allocatable :: mass(:)      !< lumped mass m_i [t]
      logical, allocatable :: slides(:)     !< tangential dof free (friction applies)
      ! P0: D (tridiagonal: dl(i) = D(i+1, i) = D(i, i+1), dd(i) = D(i, i)) and the LCP
      real(wp), allocatable :: dd(:), dl(:)
      type(lcp_t) :: lcp
      ! state of the last step
      real(wp), allocatable :: fn(:), ft(:)   !< nodal normal and tangential forces [N]
      real(wp), allocatable :: mu(:)          !< P0 normal multiplier per dual cell [MPa]
      real(wp), allocatable :: dtil(:), b(:)  !< work: trial gaps, LCP right-hand side
      logical, allocatable :: stuck(:)        !< the node stuck in the last step
      !> largest |tangential increment| of a stuck node since the last reset [mm] (should be 0)
      real(wp) :: stick_increment_max = 0
      !> status changes (separated/stick/slip) summed over nodes and steps since the last reset
      integer(i8) :: status_changes = 0
      !> largest penetration since the last reset [mm]: per node (P1, penalty), per dual cell
      !> as max((D d)_i, 0)/w_i (P0)
      real(wp) :: penetration_max = 0
      integer, allocatable :: last_status(:), cur_status(:)
      real(wp) :: friction_dissipation = 0  !< [mJ]
      real(wp) :: normal_work = 0           !< sum F_n,i Delta d_i [mJ]
      real(wp) :: normal_total = 0          !< sum of F_n [N]
      real(wp) :: tangential_total = 0      !< sum of F_t [N]
      !> work done on the body by the contact forces through the obstacle's motion [mJ]:
      !> sum F_c,i . Delta s_i, Delta s_i the centred displacement of the obstacle's surface
      !> point under node i (0 for a fixed obstacle)
      real(wp) :: obstacle_work = 0
      !> geometry 'current': the gaps, normals and tangents are refreshed each step
      logical :: current = .false.
      !> the obstacle (geometry 'current' only: the step projects onto it)
      class(obstacle_t), allocatable :: obstacle
      real(wp), allocatable :: xref(:, :)   !< initial positions of the contact nodes (2, nc) [mm]
      !> the obstacle's surface motion under each node in this step (3, nc) [mm]: its tangential
      !> part over [t_n, t_(n+1)], then the centred displacement (s(t_(n+1)) - s(t_(n-1)))/2;
      !> zeros for a fixed obstacle
      real(wp), allocatable :: ds(:, :)
      integer(i8) :: clock_ticks = 0        !< time spent in enforce (system_clock ticks)
      !> per-node constants side by side for the step's loop: rec(rec_*, i) = n_i, t_i, g_i, m_i,
      !> c/m_i (of the step coefficient c_last), 1 where a zero tangential limit means slip
      real(wp), allocatable :: rec(:, :)
      real(wp) :: c_last = -1               !< the c that rec(rec_cmass, :) belongs to
      integer :: stat = 0                   !< /= 0 after a failed LCP solve
      character(len=:), allocatable :: errmsg
      !> the master side is another body's boundary (node to segment, contact2d_master_body):
      !> the step is master%step; the per-node arrays above describe the slave nodes
      logical :: body = .false.
      type(master_body_t) :: master
   contains
      procedure :: init => contact_init
      procedure :: enforce => contact_enforce
      procedure :: status => contact_status
      procedure :: fields => contact_fields
      procedure :: multiplier_name => contact_multiplier_name
      procedure :: penetration => contact_penetration
   end type contact_t

contains

   !> Set up the contact boundary. nodes: candidate nodes ordered by abscissa; free(2, nnode):
   !> 1 on free dofs. Nodes with a prescribed normal dof are dropped (warned); a candidate
   !> boundary touching a Dirichlet boundary is accepted with a warning (inf-sup lost).
   subroutine contact_init(this, cfg, candidates, x, free, mass, warnings, stat, errmsg)
      class(contact_t), intent(out) :: this
      type(contact_config_t), intent(in) :: cfg
      integer, intent(in) :: candidates(:)
      real(wp), intent(in) :: x(:, :), free(:, :), mass(:)
      type(messages_t), intent(inout) :: warnings
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      logical, allocatable :: keep(:)
      real(wp), allocatable :: cand_gap(:), cand_nu(:, :)
      real(wp) :: tol, lmax
      integer :: i

      stat = 1
      this%active = .true.
      this%errmsg = ''
      allocate (cand_gap(size(candidates)), cand_nu(2, size(candidates)))
      if (allocated(cfg%master_nodes)) then
         ! another body's boundary: gaps and master normals from the closest master segments
         ! (contact2d_master_body), refreshed every step
         call body_init(this, cfg, candidates, x, free, mass, cand_gap, cand_nu, stat, errmsg)
         if (stat /= 0) return
         stat = 1
      else
         ! gap and normal of every candidate from its closest obstacle point, in the initial
         ! configuration, fixed for the run (small deformation: docs/geometry.md, SPEC section 3)
         do i = 1, size(candidates)
            call cfg%obstacle%project(x(:, candidates(i)), cand_gap(i), cand_nu(:, i))
         end do
      end if
      if (size(candidates) == 0) then
         errmsg = 'contact: the candidate boundary (edge and range) holds no node'
         return
      end if
      lmax = maxval(maxval(x, dim=2) - minval(x, dim=2))
      tol = 1.0e-12_wp*lmax

      call init_nodes(this, cfg, candidates, free, cand_nu, keep, warnings, stat, errmsg)
      if (stat /= 0) return
      call init_geometry(this, cfg, x, free, mass, cand_gap, keep, tol, stat, errmsg)
      if (stat /= 0) return

      this%current = cfg%current
      if (this%current) allocate (this%obstacle, source=cfg%obstacle)
      this%xref = x(:, this%node)
      allocate (this%ds(3, this%nc))
      this%ds = 0
      allocate (this%rec(nrec, this%nc))
      this%rec(rec_nx:rec_ny, :) = this%normal
      this%rec(rec_tx:rec_ty, :) = this%tangent
      this%rec(rec_gap, :) = this%gap
      this%rec(rec_mass, :) = this%mass
      this%rec(rec_cmass, :) = 0

      call init_friction(this, cfg, stat, errmsg)
      if (stat /= 0) return
      if (this%body) then
         ! the master's set-up on the kept slave nodes (the gaps of the output's first frame)
         call this%master%init(this%node, cfg%master_nodes, x, free, mass, cfg%master_inside, &
                               cand_gap(1:this%nc), cand_nu(:, 1:this%nc), stat, errmsg)
         if (stat /= 0) return
      end if

      this%penalty = cfg%method == 'penalty'
      this%penalty_stiffness = cfg%penalty_stiffness
      if (cfg%multiplier == 'P0') then
         this%multiplier = multiplier_p0
         call setup_p0(this)
      else
         this%multiplier = multiplier_p1
      end if
      stat = 0
      errmsg = ''
   end subroutine contact_init

   !> Another body's boundary as the master side: the candidates' initial gaps and the master's
   !> normals at their projections (off the master: a large gap, the normal of the nearest
   !> segment); refused when a slave node starts inside the master body by more than
   !> cfg%overlap_tol (the worst named, with its penetration) or a node is on both sides.
   subroutine body_init(this, cfg, candidates, x, free, mass, cand_gap, cand_nu, stat, errmsg)
      type(contact_t), intent(inout) :: this
      type(contact_config_t), intent(in) :: cfg
      integer, intent(in) :: candidates(:)
      real(wp), intent(in) :: x(:, :), free(:, :), mass(:)
      real(wp), intent(out) :: cand_gap(:), cand_nu(:, :)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer :: i, w
      stat = 1
      this%body = .true.
      do i = 1, size(candidates)
         if (any(cfg%master_nodes == candidates(i))) then
            errmsg = 'contact: node '//str(user_id(cfg, candidates(i)))//' is on both the slave boundary and '// &
                     'the master boundary; the two sides must be different bodies, not bonded there'
            return
         end if
      end do
      if (size(candidates) == 0) then
         stat = 0
         return
      end if
      call this%master%init(candidates, cfg%master_nodes, x, free, mass, cfg%master_inside, cand_gap, cand_nu, &
                            stat, errmsg)
      if (stat /= 0) return
      w = minloc(cand_gap, dim=1)
      if (cand_gap(w) < -cfg%overlap_tol) then
         stat = 1
         errmsg = 'contact: the bodies overlap at the start: slave node '//str(user_id(cfg, candidates(w)))// &
                  ' at ('//str(x(1, candidates(w)))//', '//str(x(2, candidates(w)))//') is '// &
                  str(-cand_gap(w))//' mm inside the master boundary (tolerance '//str(cfg%overlap_tol)//' mm)'
         return
      end if
      ! round-off below the tolerance counts as touching; off the master: far
      cand_gap = max(cand_gap, 0.0_wp)
      where (cand_gap > 1.0e30_wp) cand_gap = 1.0e30_wp
      stat = 0
   end subroutine body_init

   !> The contact nodes: the candidates less those whose normal displacement is prescribed
   !> (warned: their reaction is a Dirichlet one), with their normals n_i = -nu_i and tangents
   !> t_i = (-n2, n1); a warning when the candidates touch the Dirichlet boundary (the paper's
   !> inf-sup condition is lost). stat 1: no node left, or a dropped node inside the chain.
   subroutine init_nodes(this, cfg, candidates, free, cand_nu, keep, warnings, stat, errmsg)
      type(contact_t), intent(inout) :: this
      type(contact_config_t), intent(in) :: cfg
      integer, intent(in) :: candidates(:)
      real(wp), intent(in) :: free(:, :), cand_nu(:, :)
      logical, allocatable, intent(out) :: keep(:)
      type(messages_t), intent(inout) :: warnings
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer :: i, k, nd, ntouch
      character(len=:), allocatable :: ids

      stat = 1
      ! drop nodes whose normal displacement is prescribed; detect contact with Gamma_u
      allocate (keep(size(candidates)))
      ntouch = 0
      ids = ''
      do i = 1, size(candidates)
         k = candidates(i)
         keep(i) = .true.
         if (any(free(:, k) == 0)) ntouch = ntouch + 1
         if (any(free(:, k) == 0 .and. abs(cand_nu(:, i)) > 1.0e-12_wp)) then
            keep(i) = .false.
            if (len(ids) > 0) ids = ids//', '
            ids = ids//str(user_id(cfg, k))
         end if
      end do
      nd = count(.not. keep)
      if (nd > 0) then
         call warnings%add('contact: '//str(nd)//' candidate node(s) dropped from Gamma_c because their '// &
                           'normal displacement is prescribed (node '//ids//'); their reaction is a Dirichlet reaction')
      end if
      if (ntouch > 0) then
         call warnings%add('contact: the candidate boundary touches the Dirichlet boundary at '//str(ntouch)// &
                           ' node(s): closure(Gamma_u) and closure(Gamma_c) meet, the inf-sup condition of the '// &
                           'paper is lost and the multipliers may oscillate')
      end if
      this%node = pack(candidates, keep)
      this%nc = size(this%node)
      allocate (this%normal(2, this%nc), this%tangent(2, this%nc))
      this%normal(1, :) = -pack(cand_nu(1, :), keep)
      this%normal(2, :) = -pack(cand_nu(2, :), keep)
      this%tangent(1, :) = -this%normal(2, :)
      this%tangent(2, :) = this%normal(1, :)
      if (this%nc == 0) then
         errmsg = 'contact: every candidate node has a prescribed normal displacement; Gamma_c is empty'
         return
      end if
      ! the kept nodes must still form one chain of element edges
      do i = 1, size(candidates) - 1
         if (.not. keep(i) .and. any(keep(:i - 1)) .and. any(keep(i + 1:))) then
            errmsg = 'contact: node '//str(user_id(cfg, candidates(i)))// &
                     ' inside the candidate boundary has a prescribed '// &
                     'normal displacement; split the boundary or free that node'
            return
         end if
      end do
      stat = 0
   end subroutine init_nodes

   !> The chain's geometry (SPEC section 3): gaps g_i (a node more than tol inside the obstacle
   !> is refused, round-off below it is set to 0), segment lengths h_i, weights w_i, abscissae
   !> from O, masses m_i, which nodes slide; the step's state arrays allocated and zeroed.
   !> stat 1: a single-node chain or a node that starts inside the obstacle.
   subroutine init_geometry(this, cfg, x, free, mass, cand_gap, keep, tol, stat, errmsg)
      type(contact_t), intent(inout) :: this
      type(contact_config_t), intent(in) :: cfg
      real(wp), intent(in) :: x(:, :), free(:, :), mass(:), cand_gap(:), tol
      logical, intent(in) :: keep(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp) :: e(2)
      integer :: i, k

      stat = 1
      associate (nc => this%nc)
         this%gap = pack(cand_gap, keep)
         allocate (this%abscissa(nc), this%h(max(nc - 1, 0)), this%weight(nc), &
                   this%threshold(nc), this%mass(nc), this%slides(nc), &
                   this%fn(nc), this%ft(nc), this%mu(nc), this%dtil(nc), this%b(nc), this%stuck(nc), &
                   this%last_status(nc), this%cur_status(nc))
         this%stuck = .false.
         this%last_status = status_separated
         this%fn = 0
         this%ft = 0
         this%mu = 0
         do i = 1, nc - 1
            this%h(i) = norm2(x(:, this%node(i + 1)) - x(:, this%node(i)))
         end do
         ! weights: half of each adjacent segment (SPEC section 3)
         this%weight = 0
         do i = 1, nc - 1
            this%weight(i) = this%weight(i) + 0.5_wp*this%h(i)
            this%weight(i + 1) = this%weight(i + 1) + 0.5_wp*this%h(i)
         end do
         if (nc == 1) then
            errmsg = 'contact: Gamma_c has a single node; it needs at least one element edge'
            return
         end if
         ! abscissa from O along the chain
         e = (x(:, this%node(2)) - x(:, this%node(1)))/this%h(1)
         if (all(cfg%origin < huge(1.0_wp))) then
            this%abscissa(1) = dot_product(x(:, this%node(1)) - cfg%origin, e)
         else
            this%abscissa(1) = 0
         end if
         do i = 2, nc
            this%abscissa(i) = this%abscissa(i - 1) + this%h(i - 1)
         end do
         do i = 1, nc
            k = this%node(i)
            this%mass(i) = mass(k)
            this%slides(i) = all(free(:, k) == 1 .or. abs(this%tangent(:, i)) <= 1.0e-12_wp)
            if (this%gap(i) < -tol) then
               errmsg = 'contact: node '//str(user_id(cfg, k))//' at ('//str(x(1, k))//', '//str(x(2, k))// &
                        ') starts inside the obstacle (gap '//str(this%gap(i))//' mm)'
               return
            end if
            this%gap(i) = max(this%gap(i), 0.0_wp)
         end do
      end associate
      stat = 0
   end subroutine init_geometry

   !> The friction: the law made by its input (friction_input_t%make, docs/friction.md section 2)
   !> from the contact nodes' abscissae, weights and free tangential dofs, its first limits and
   !> its per-node thresholds for the output, and the step's rec_free0 column.
   subroutine init_friction(this, cfg, stat, errmsg)
      type(contact_t), intent(inout) :: this
      type(contact_config_t), intent(in) :: cfg
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg

      errmsg = ''
      if (allocated(cfg%friction)) call cfg%friction%make(this%abscissa, this%weight, this%slides, this%law)
      this%friction = allocated(this%law)
      allocate (this%slip_limit(this%nc))
      if (this%friction) call this%law%limits(this%fn, this%fn, this%slip_limit)
      if (.not. this%friction) this%slip_limit = 0
      ! the law's thresholds s_i, written as /contact/threshold (zeros without friction)
      this%threshold = 0
      if (this%friction) call this%law%node_thresholds(this%threshold)
      this%limits_fixed = .not. this%friction
      if (this%friction) this%limits_fixed = this%law%fixed
      if (this%friction) this%fn_touches = this%law%depends_on_fn()
      ! a zero limit means slip where there is no friction or the tangential dof is free
      this%rec(rec_free0, :) = merge(1.0_wp, 0.0_wp, this%slides .or. .not. this%friction)
      stat = 0
   end subroutine init_friction

   !> Node k as the user's mesh file numbers it (the messages name nodes so).
   integer function user_id(cfg, k)
      type(contact_config_t), intent(in) :: cfg
      integer, intent(in) :: k
      user_id = k
      if (allocated(cfg%file_id)) user_id = cfg%file_id(k)
   end function user_id

   !> D_ij = integral over dual cell i of phi_j (SPEC section 3) and the LCP matrix D M^-1 D^T.
   subroutine setup_p0(this)
      type(contact_t), intent(inout) :: this
      real(wp), allocatable :: ab(:, :)
      integer :: i, j, k, nc
      nc = this%nc
      allocate (this%dd(nc), this%dl(nc - 1))
      this%dd = 0
      do i = 1, nc - 1
         this%dd(i) = this%dd(i) + 3*this%h(i)/8
         this%dd(i + 1) = this%dd(i + 1) + 3*this%h(i)/8
         this%dl(i) = this%h(i)/8
      end do
      ! (D M^-1 D^T)(i, j) = sum_k D(i, k) D(j, k) / m_k, five bands; upper band storage, kd = 2
      allocate (ab(3, nc))
      ab = 0
      do j = 1, nc
         do i = max(1, j - 2), j
            do k = max(1, j - 1), min(nc, i + 1)
               ab(3 + i - j, j) = ab(3 + i - j, j) + d_entry(this, i, k)*d_entry(this, j, k)/this%mass(k)
            end do
         end do
      end do
      call this%lcp%init(ab, 2)
   end subroutine setup_p0

   pure real(wp) function d_entry(this, i, j)
      type(contact_t), intent(in) :: this
      integer, intent(in) :: i, j
      if (i == j) then
         d_entry = this%dd(i)
      else if (abs(i - j) == 1) then
         d_entry = this%dl(min(i, j))
      else
         d_entry = 0
      end if
   end function d_entry

   !> y = D x (D symmetric tridiagonal).
   pure subroutine d_apply(this, x, y)
      type(contact_t), intent(in) :: this
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      integer :: i, nc
      nc = this%nc
      y = this%dd*x
      ! row by row, each row's terms in the order of the edge loop it replaces (y(i) gets the
      ! edge (i-1, i) before the edge (i, i+1)), so the sums are the same
      if (nc < 2) return
      y(1) = y(1) + this%dl(1)*x(2)
      do i = 2, nc - 1
         y(i) = y(i) + this%dl(i - 1)*x(i - 1)
         y(i) = y(i) + this%dl(i)*x(i + 1)
      end do
      y(nc) = y(nc) + this%dl(nc - 1)*x(nc - 1)
   end subroutine d_apply

   !> The contact step (SPEC section 4, step 3). u^n, v^(n-1/2) and the trial u~ (unew) in;
   !> unew becomes u^(n+1) = u~ + c M^-1 F_c at the contact nodes and fc(:, node) = F_c.
   !> Energies use the centred increment (u^(n+1) - u^(n-1))/2 (SPEC section 6).
   !> Two passes over the contact nodes: the normal forces (node by node for P1 and penalty, the
   !> LCP for P0), then, after the friction law's limits, one pass for the tangential forces, the
   !> update, energies, diagnostics and status (docs/performance.md, "The contact step").
   subroutine contact_enforce(this, u, v, unew, c, dt, fc, time)
      class(contact_t), intent(inout) :: this
      real(wp), intent(in) :: u(:, :)      !< u^n [mm]
      real(wp), intent(in) :: v(:, :)      !< v^(n-1/2) [mm/s]
      real(wp), intent(inout) :: unew(:, :)  !< u~ in, u^(n+1) out [mm]
      real(wp), intent(in) :: c            !< dt^2 / (1 + alpha dt / 2) [s^2]
      real(wp), intent(in) :: dt           !< [s]
      real(wp), intent(inout) :: fc(:, :)  !< contact force on the body [N]
      real(wp), intent(in), optional :: time  !< t_n [s] (geometry 'current'; absent: 0)
      integer(i8) :: t0, t1
      real(wp) :: rc, tn
      logical :: cells

 
      call system_clock(t0)
      if (this%body) then
         ! another body's boundary: node to segment in the current configuration
         call this%master%step(u, v, unew, c, dt, fc, this%fn, this%normal, this%tangent, this%gap, &
                               this%normal_work, this%penetration_max, this%stat, this%errmsg)
         call body_status(this)
         this%c_last = c
         call system_clock(t1)
         this%clock_ticks = this%clock_ticks + (t1 - t0)
         return
      end if
      rc = 1/c
      cells = this%multiplier == multiplier_p0 .and. .not. this%penalty
      ! geometry 'current': gaps, normals and the obstacle's surface motion of this step, from
      ! x + u~ at t_(n+1) (the penalty's force is explicit: from x + u^n at t_n)
      if (this%current) then
         tn = 0
         if (present(time)) tn = time
         if (this%penalty) then
            call update_geometry(this, u, tn, tn + dt, dt)
         else
            call update_geometry(this, unew, tn + dt, tn + dt, dt)
         end if
      end if
      ! c/m_i changes only with c (the damping coefficient): kept between steps
      if (c /= this%c_last) then
         this%rec(rec_cmass, :) = c/this%mass
         this%c_last = c
      end if
      ! normal forces
      if (this%penalty) then
         ! explicit penalty on the gap at t_n: F_n = k_p w_i max(d_i^n, 0)
         call normal_penalty(this%nc, this%node, this%normal, this%gap, this%weight, this%penalty_stiffness, u, this%fn)
      else if (this%multiplier == multiplier_p1) then
         ! P1: Lambda_n,i = max(0, m_i d~_i / c), node by node (in finish_pass when the limits
         ! are fixed)
         if (.not. this%limits_fixed) &
            call normal_p1(this%nc, this%node, this%normal, this%gap, this%mass, rc, unew, this%fn)
      else
         ! P0: mu >= 0, (D M^-1 D^T) mu - D d~ / c >= 0, complementary; F_n = D mu
         call trial_gaps(this%nc, this%node, this%normal, this%gap, rc, unew, this%dtil)
         call d_apply(this, this%dtil, this%b)
         if (this%stat == 0) call this%lcp%solve(this%b, this%mu, this%stat, this%errmsg)
         call d_apply(this, this%mu, this%fn)
      end if
      ! the law's limits from this step's normal forces (one call on plain arrays); contact
      ! judged like the status (SPEC section 3): P1 by F_n, P0 on the node's own dual cell
      if (this%friction .and. .not. this%limits_fixed) then
         if (cells) then
            call this%law%limits(this%fn, this%mu, this%slip_limit)
         else
            call this%law%limits(this%fn, this%fn, this%slip_limit)
         end if
      end if
      call finish_pass(this, u, v, unew, fc, dt, rc, cells)
      if (cells) then
         call d_apply(this, this%dtil, this%b)
         this%b = this%b/this%weight
         this%penetration_max = max(this%penetration_max, maxval(this%b))
      end if
      call system_clock(t1)
      this%clock_ticks = this%clock_ticks + (t1 - t0)
   end subroutine contact_enforce

   !> P1 normal forces Lambda_n,i = max(0, m_i d~_i / c) (the paper's (12)).
   pure subroutine normal_p1(nc, node, normal, gap, mass, rc, unew, fn)
      integer, intent(in) :: nc, node(nc)
      real(wp), intent(in) :: normal(2, nc), gap(nc), mass(nc), rc, unew(2, *)
      real(wp), intent(out) :: fn(nc)
      integer :: i, k
      real(wp) :: nx, ny
      do i = 1, nc
         k = node(i)
         nx = normal(1, i)
         ny = normal(2, i)
         fn(i) = max(0.0_wp, mass(i)*(unew(1, k)*nx + unew(2, k)*ny - gap(i))*rc)
      end do
   end subroutine normal_p1

   !> Penalty normal forces k_p w_i max(d_i^n, 0) from the gap at t_n.
   pure subroutine normal_penalty(nc, node, normal, gap, weight, kp, u, fn)
      integer, intent(in) :: nc, node(nc)
      real(wp), intent(in) :: normal(2, nc), gap(nc), weight(nc), kp, u(2, *)
      real(wp), intent(out) :: fn(nc)
      integer :: i, k
      real(wp) :: nx, ny
      do i = 1, nc
         k = node(i)
         nx = normal(1, i)
         ny = normal(2, i)
         fn(i) = kp*weight(i)*max(u(1, k)*nx + u(2, k)*ny - gap(i), 0.0_wp)
      end do
   end subroutine normal_penalty

   !> P0 trial gaps over c, d~_i / c.
   pure subroutine trial_gaps(nc, node, normal, gap, rc, unew, dtil)
      integer, intent(in) :: nc, node(nc)
      real(wp), intent(in) :: normal(2, nc), gap(nc), rc, unew(2, *)
      real(wp), intent(out) :: dtil(nc)
      integer :: i, k
      real(wp) :: nx, ny
      do i = 1, nc
         k = node(i)
         nx = normal(1, i)
         ny = normal(2, i)
         dtil(i) = (unew(1, k)*nx + unew(2, k)*ny - gap(i))*rc
      end do
   end subroutine trial_gaps

   !> After the normal forces and the law's limits, one pass over the contact nodes: tangential
   !> forces (trial stick, else slip at the limit: docs/friction.md section 1), u^(n+1) and F_c,
   !> work on the centred increment (u^(n+1) - u^(n-1))/2, the diagnostics of u^(n+1) and the
   !> status (the rule of node_status, evaluated here on the values at hand).
   subroutine finish_pass(this, u, v, unew, fc, dt, rc, cells)
      type(contact_t), intent(inout) :: this
      real(wp), intent(in) :: u(2, *), v(2, *)
      real(wp), intent(inout) :: unew(2, *), fc(2, *)
      real(wp), intent(in) :: dt, rc
      logical, intent(in) :: cells
      call finish_nodes(this%nc, this%node, this%rec, this%fn, this%slip_limit, this%mu, this%ft, this%stuck, &
                        this%dtil, this%last_status, this%friction, this%fn_touches, cells, &
                        this%limits_fixed .and. this%multiplier == multiplier_p1 .and. .not. this%penalty, &
                        this%ds, u, v, unew, fc, dt, rc, this%stick_increment_max, this%penetration_max, &
                        this%status_changes, this%normal_work, this%friction_dissipation, this%obstacle_work, &
                        this%normal_total, this%tangential_total)
   end subroutine finish_pass

   !> The loop of finish_pass on plain arrays. rec(:, i): the per-node constants (rec_* indices).
   !> ds(:, i): the obstacle's surface motion under node i (contact_t%ds): stick keeps the node
   !> on the surface point, friction dissipates on the slip relative to it, and the contact
   !> force's work through it is the obstacle's work on the body (docs/geometry.md).
   subroutine finish_nodes(nc, node, rec, fnv, limv, mu, ftv, stuckv, dtil, last_status, friction, fn_touches, cells, &
                           p1_here, ds, u, v, unew, fc, dt, rc, sim_max, pen_max, status_changes, normal_work, &
                           friction_dissipation, obstacle_work, &
                           normal_total, tangential_total)
      integer, intent(in) :: nc, node(nc)
      real(wp), intent(in) :: rec(nrec, nc), limv(nc), mu(nc), ds(3, nc)
      real(wp), intent(inout) :: fnv(nc)
      real(wp), intent(inout) :: ftv(nc)
      logical, intent(inout) :: stuckv(nc)
      real(wp), intent(inout) :: dtil(nc)
      integer, intent(inout) :: last_status(nc)
      logical, intent(in) :: friction, cells
      logical, intent(in) :: fn_touches   !< contact_t%fn_touches
      logical, intent(in) :: p1_here   !< find the P1 normal force here (normal_p1's expression)
      real(wp), intent(in) :: u(2, *), v(2, *)
      real(wp), intent(inout) :: unew(2, *), fc(2, *)
      real(wp), intent(in) :: dt, rc
      real(wp), intent(inout) :: sim_max, pen_max, normal_work, friction_dissipation, obstacle_work
      integer(i8), intent(inout) :: status_changes
      real(wp), intent(out) :: normal_total, tangential_total
      integer :: i, k, st
      real(wp) :: nx, ny, tx, ty, trial, lim, fn, ft, fx, fy, dx, dy, cm, d, fnsum, ftsum, wn, wf, wo, sim, pen
      integer(i8) :: changes
      logical :: stuck, touching

      sim = sim_max
      pen = pen_max
      changes = 0
      fnsum = 0
      ftsum = 0
      wn = 0
      wf = 0
      wo = 0
      do i = 1, nc
         k = node(i)
         nx = rec(rec_nx, i)
         ny = rec(rec_ny, i)
         tx = rec(rec_tx, i)
         ty = rec(rec_ty, i)
         if (p1_here) then
            fn = max(0.0_wp, rec(rec_mass, i)*(unew(1, k)*nx + unew(2, k)*ny - rec(rec_gap, i))*rc)
            fnv(i) = fn
         else
            fn = fnv(i)
         end if
         lim = limv(i)
         if (friction) then
            trial = rec(rec_mass, i)*(((unew(1, k) - u(1, k))*tx + (unew(2, k) - u(2, k))*ty) - ds(1, i))*rc
            ! sign(min(|trial|, lim), trial), written so that no spilled value is reloaded wider
            stuck = abs(trial) < lim
            ft = merge(trial, sign(lim, trial), stuck)
            ftv(i) = ft
            stuckv(i) = stuck
         else
            ft = ftv(i)
            stuck = stuckv(i)
         end if
         fx = -fn*nx - ft*tx
         fy = -fn*ny - ft*ty
         cm = rec(rec_cmass, i)
         unew(1, k) = unew(1, k) + cm*fx
         unew(2, k) = unew(2, k) + cm*fy
         fc(1, k) = fx
         fc(2, k) = fy
         dx = unew(1, k) - u(1, k)
         dy = unew(2, k) - u(2, k)
         if (stuck) sim = max(sim, abs((dx*tx + dy*ty) - ds(1, i)))
         wo = wo + (fx*ds(2, i) + fy*ds(3, i))
         dx = 0.5_wp*(dx + dt*v(1, k)) - ds(2, i)
         dy = 0.5_wp*(dy + dt*v(2, k)) - ds(3, i)
         wn = wn + fn*(dx*nx + dy*ny)
         wf = wf + ft*(dx*tx + dy*ty)
         fnsum = fnsum + fn
         ftsum = ftsum + ft
         d = unew(1, k)*nx + unew(2, k)*ny - rec(rec_gap, i)
         ! status (node_status, same outcome): with P0 the normal part is judged on the node's
         ! dual cell; a zero limit is slip where rec_free0 says the node slides freely
         if (cells) then
            dtil(i) = d
            touching = mu(i) > 0 .or. (fn_touches .and. fn > 0)
         else
            pen = max(pen, d)
            touching = fn > 0
         end if
         st = status_rule(touching, lim, ft, rec(rec_free0, i) > 0)
         changes = changes + merge(1, 0, st /= last_status(i))
         last_status(i) = st
      end do
      normal_work = normal_work + wn
      friction_dissipation = friction_dissipation + wf
      obstacle_work = obstacle_work + wo
      normal_total = fnsum
      tangential_total = ftsum
      sim_max = sim
      pen_max = pen
      status_changes = status_changes + changes
   end subroutine finish_nodes

   !> Geometry 'current' (docs/geometry.md): each contact node's position x_i + w_i (w = u~ at
   !> tp = t_(n+1), or u^n at tp = t_n for the explicit penalty) projected onto the obstacle at tp:
   !> gap g_i, normal n_i = -nu_i, tangent t_i; the stored gap becomes w_i . n_i + g_i, so that
   !> the step's d_i = w_i . n_i - gap_i = -g_i and, linearised about x + w, u^(n+1) . n_i - gap_i
   !> is the penetration at t_(n+1) (the kernels of the fixed geometry unchanged). The obstacle's
   !> surface motion under each node (ds): its tangential part over the step [t - dt, t]
   !> (t = t_(n+1)) for the stick trial, and the centred displacement (s(t) - s(t - 2 dt))/2 for
   !> the work sums, of the obstacle point at the node's closest point x + w - g nu (carried to t
   !> by the translation when tp < t). No allocation.
   subroutine update_geometry(this, w, tp, t, dt)
      type(contact_t), intent(inout) :: this
      real(wp), intent(in) :: w(:, :)
      real(wp), intent(in) :: tp, t, dt
      real(wp) :: d0(2), d1(2), d2(2), dp(2), a0, a1, a2, x(2), g, nu(2), n(2), tg(2), xs(2), s1(2), s2(2)
      integer :: i, k
      dp = this%obstacle%displacement(tp)
      d2 = this%obstacle%displacement(t)
      d1 = this%obstacle%displacement(t - dt)
      d0 = this%obstacle%displacement(t - 2*dt)
      a2 = this%obstacle%angle(t)
      a1 = this%obstacle%angle(t - dt)
      a0 = this%obstacle%angle(t - 2*dt)
      do i = 1, this%nc
         k = this%node(i)
         x = this%xref(:, i) + w(:, k)
         call this%obstacle%project_at(dp, x, g, nu)
         n = -nu
         tg = [-n(2), n(1)]
         this%normal(:, i) = n
         this%tangent(:, i) = tg
         this%gap(i) = (w(1, k)*n(1) + w(2, k)*n(2)) + g
         this%rec(rec_nx:rec_ny, i) = n
         this%rec(rec_tx:rec_ty, i) = tg
         this%rec(rec_gap, i) = this%gap(i)
         if (this%obstacle%moving) then
            xs = x - g*nu + (d2 - dp)
            s1 = this%obstacle%surface_displacement(d1, d2, a2 - a1, xs)
            s2 = this%obstacle%surface_displacement(d0, d2, a2 - a0, xs)
            this%ds(1, i) = s1(1)*tg(1) + s1(2)*tg(2)
            this%ds(2:3, i) = 0.5_wp*s2
         end if
      end do
   end subroutine update_geometry

   !> Two bodies: the sums and the status of the step from the normal forces (frictionless:
   !> a touching node slides), the status changes counted.
   subroutine body_status(this)
      type(contact_t), intent(inout) :: this
      integer :: i, st
      this%normal_total = sum(this%fn)
      this%tangential_total = 0
      do i = 1, this%nc
         st = merge(status_slip, status_separated, this%fn(i) > 0)
         if (st /= this%last_status(i)) this%status_changes = this%status_changes + 1
         this%last_status(i) = st
         this%rec(rec_nx:rec_ny, i) = this%normal(:, i)
         this%rec(rec_tx:rec_ty, i) = this%tangent(:, i)
      end do
   end subroutine body_status

   !> Status per contact node (SPEC section 3): 0 separated, 1 stick, 2 slip.
   subroutine contact_status(this, status)
      class(contact_t), intent(in) :: this
      integer, intent(out) :: status(:)
      integer :: i
      do i = 1, this%nc
         status(i) = node_status(this, i)
      end do
   end subroutine contact_status

   !> Status of contact node i; with P0 the normal part is judged on the node's dual cell.
   pure integer function node_status(this, i) result(status)
      type(contact_t), intent(in) :: this
      integer, intent(in) :: i
      logical :: touching
      if (this%multiplier == multiplier_p0 .and. .not. this%penalty) then
         ! a law driven by F_n (Coulomb, mu > 0) acts on the nodal F_n,i = (D^T mu_n)_i, which a
         ! neighbouring closed cell makes positive at a node whose own cell is open: such a node
         ! carries friction and is reported touching (docs/friction.md section 1)
         touching = this%mu(i) > 0 .or. (this%fn_touches .and. this%fn(i) > 0)
      else
         touching = this%fn(i) > 0
      end if
      status = status_rule(touching, this%slip_limit(i), this%ft(i), this%rec(rec_free0, i) > 0)
   end function node_status

   !> The status of a node from its contact state, this step's tangential limit lim and force ft:
   !> separated if not touching; else slip if |ft| >= (1 - slip_tol) lim > 0, or if lim = 0 where
   !> a zero limit means sliding freely (free0: no friction law, or the tangential dof is free, as
   !> with Tresca s_i = 0 or Coulomb mu = 0; docs/output.md); else stick. Without branches (the
   !> step's pass uses it too).
   pure elemental integer function status_rule(touching, lim, ft, free0) result(status)
      logical, intent(in) :: touching, free0
      real(wp), intent(in) :: lim, ft
      logical :: slip
      slip = merge(free0, abs(ft) >= (1 - slip_tol)*lim, lim <= 0)
      status = merge(merge(status_slip, status_stick, slip), status_separated, touching)
   end function status_rule

   !> Multiplier fields (SPEC section 3): P1 (and penalty) per node, lambda = M_c^-1 F (consistent
   !> 1D mass of Gamma_c, LAPACK dptsv); P0 per dual cell, mu_n and mu_t = D^-1 F_t.
   subroutine contact_fields(this, pressure, shear, stat)
      class(contact_t), intent(in) :: this
      real(wp), intent(out) :: pressure(:), shear(:)
      integer, intent(out) :: stat
      real(wp) :: diag(this%nc), off(max(this%nc - 1, 1)), rhs(this%nc, 2)
      integer :: i, nc
      external :: dptsv
      nc = this%nc
      if (this%multiplier == multiplier_p0 .and. .not. this%penalty) then
         diag = this%dd
         off(1:nc - 1) = this%dl
         rhs(:, 1) = this%ft
         call dptsv(nc, 1, diag, off, rhs, nc, stat)
         pressure = this%mu
         shear = rhs(:, 1)
      else
         diag = 0
         do i = 1, nc - 1
            diag(i) = diag(i) + this%h(i)/3
            diag(i + 1) = diag(i + 1) + this%h(i)/3
            off(i) = this%h(i)/6
         end do
         rhs(:, 1) = this%fn
         rhs(:, 2) = this%ft
         call dptsv(nc, 2, diag, off, rhs, nc, stat)
         pressure = rhs(:, 1)
         shear = rhs(:, 2)
      end if
   end subroutine contact_fields

   !> 'P1', 'P0' or 'penalty'.
   function contact_multiplier_name(this) result(name)
      class(contact_t), intent(in) :: this
      character(len=:), allocatable :: name
      if (this%penalty) then
         name = 'penalty'
      else if (this%multiplier == multiplier_p0) then
         name = 'P0'
      else
         name = 'P1'
      end if
   end function contact_multiplier_name

   !> Largest penetration: per node for P1 and penalty, max((D d)_i, 0) per dual cell for P0 [mm].
   real(wp) function contact_penetration(this, u) result(pen)
      class(contact_t), intent(in) :: this
      real(wp), intent(in) :: u(:, :)
      real(wp) :: d(this%nc), dd(this%nc)
      integer :: i
      if (this%body) then
         ! two bodies: the gap of the last step after its correction (c max(-w, 0))
         pen = 0
         if (allocated(this%master%lcp%w)) pen = max(0.0_wp, -this%c_last*minval(this%master%lcp%w))
         return
      end if
      do i = 1, this%nc
         d(i) = dot_product(u(:, this%node(i)), this%normal(:, i)) - this%gap(i)
      end do
      if (this%multiplier == multiplier_p0 .and. .not. this%penalty) then
         call d_apply(this, d, dd)
         pen = max(maxval(dd/this%weight), 0.0_wp)   ! per unit cell length: a mean gap [mm]
      else
         pen = max(maxval(d), 0.0_wp)
      end if
   end function contact_penetration
end module contact2d_contact
