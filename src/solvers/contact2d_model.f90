!> Deck -> model: the mesh, material, element matrices, boundary data, contact and time step
!> built from a validated deck. Every cross-group check that needs the model lives here.
module contact2d_model
   use contact2d_kinds, only: wp
   use contact2d_version, only: program_name
   use contact2d_strings, only: str
   use contact2d_checks, only: check_positive
   use contact2d_messages, only: messages_t
   use contact2d_deck, only: deck_t, edge_load_cfg_t, edge_id, unset
   use contact2d_mesh, only: mesh_t, node_elements
   use contact2d_material, only: material_t, material_init
   use contact2d_stiffness, only: stiffness_t
   use contact2d_mass_scaling, only: mass_scale
   use contact2d_loading, only: loading_t
   use contact2d_contact, only: contact_t, contact_config_t
   use contact2d_gmsh, only: gmsh_read
   use contact2d_explicit, only: damping_none, damping_given, damping_auto
   use contact2d_initial, only: initial_velocity_warning
   use contact2d_body, only: body_t, body_init
   use contact2d_pair, only: contact_pair_t, pair_init, master_body
   use contact2d_rigid, only: rigid_t, rigid_free_motions, rigid_describe, rigid_drive
   use contact2d_timestep, only: timestep_critical, timestep_choose, timestep_power, timestep_guarded
   implicit none
   private
   public :: model_t, model_build, beside

   !> Everything the deck and the mesh define: built once by model_build, read-only (intent(in))
   !> from then on. What changes during a run is in the state (contact2d_state).
   type :: model_t
      type(mesh_t) :: mesh
      !> the bodies (contact2d_body): the deck's &body groups, or one, the whole mesh
      type(body_t), allocatable :: bodies(:)
      !> the body of each element (nel), an index into bodies
      integer, allocatable :: body_of(:)
      !> the contact pairs (contact2d_pair): one per &contact group of the deck, in its order
      type(contact_pair_t), allocatable :: pairs(:)
      type(stiffness_t) :: stiff
      type(loading_t) :: load
      !> the contact operator of each pair (contacts(k) of pairs(k)) as built and validated; each
      !> run's state works on a copy of them. Their slave node sets are disjoint (model_build), so
      !> each node's forward-increment multipliers belong to one operator (SPEC section 4)
      type(contact_t), allocatable :: contacts(:)
      real(wp) :: dt = 0             !< initial time step (contact2d_timestep) [s]
      !> initial velocity of each node (2, nnode) [mm/s]: initial:velocity, or its body's
      !> &body velocity (a node shared by bodies: the last body's)
      real(wp), allocatable :: velocity0(:, :)
      real(wp) :: dt_critical = 0    !< critical step: element bound, mass scaling, penalty [s]
      real(wp) :: omega2_power = 0   !< power-iteration estimate of omega_max^2 (0: none) [1/s^2]
      logical :: dt_guarded = .false.   !< dt from the power estimate: watch for a growing mode
      integer :: damping = damping_auto
      ! mass scaling (solver:mass_scaling > 0)
      real(wp) :: added_mass = 0     !< total fictitious mass [t]
      real(wp) :: body_mass = 0      !< physical mass of the body [t]
      integer :: scaled_nodes = 0    !< nodes that got mass
      type(messages_t) :: warnings
      !> the body's rigid motions that no support stops (contact2d_rigid): nfree > 0 only for a
      !> body held by contact alone; the static engine regularises them (docs/static.md)
      type(rigid_t) :: unsupported
   end type model_t

contains

   !> Build the model. stat /= 0 with a one-line message naming the problem. The model is not
   !> changed after this (every later use is intent(in)); its warnings are all collected here.
   subroutine model_build(deck, model, stat, errmsg)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(out) :: model
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer :: i, nx, ny, nflip, e, k
      type(material_t) :: material
      type(material_t), allocatable :: mats(:)
      !> outward normals of the sides bottom, right, top, left
      real(wp), parameter :: outward(2, 4) = reshape([0.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
                                                      -1.0_wp, 0.0_wp], [2, 4])
      real(wp) :: dt_scaled
      type(contact_t) :: nocontact   !< no pair: no penalty springs in the time step

      if (len_trim(deck%mesh%file) > 0) then
         ! a Gmsh mesh (docs/geometry.md): quads only, oriented, Jacobians checked
         ! (a crash or an exit() inside Gmsh is reported by gmsh_read itself in the driver's form)
         call gmsh_read(beside(deck%path, trim(deck%mesh%file)), deck%mesh%level, model%mesh, stat, errmsg, &
                        context=program_name//': error: '//deck%path//': ')
         if (stat /= 0) then
            errmsg = deck%path//': '//errmsg
            return
         end if
         call model%mesh%orient(nflip, stat, errmsg)
         if (stat /= 0) then
            errmsg = deck%path//": mesh:file = '"//trim(deck%mesh%file)//"': "//errmsg
            return
         end if
         if (nflip > 0) call model%warnings%add('mesh: '//str(nflip)//' clockwise element(s) of '// &
                                                trim(deck%mesh%file)//' reoriented counter-clockwise')
      else
         nx = deck%mesh%nx*2**deck%mesh%level
         ny = deck%mesh%ny*2**deck%mesh%level
         call model%mesh%init_rectangle(deck%mesh%lx, deck%mesh%ly, nx, ny)
      end if
      if (size(deck%body) == 0) then
         ! the one body: every element, the deck's material; the element matrices and masses are
         ! formed with the body's material (contact2d_stiffness)
         call material_init(material, deck%material%young, deck%material%poisson, &
                            deck%material%density, stat, errmsg)
         if (stat /= 0) return
         allocate (model%bodies(1))
         call body_init(model%bodies(1), 'body', [(i, i=1, model%mesh%nel)], material)
         call model%stiff%init(model%mesh, model%bodies(1)%material, stat, errmsg)
         allocate (model%body_of(model%mesh%nel))
         model%body_of = 1
      else
         ! the deck's bodies: each the elements of one physical surface, every element in exactly
         ! one body; the element matrices and masses of each element with its body's material
         call build_bodies()
         if (stat /= 0) return
         allocate (mats(size(model%bodies)))
         do i = 1, size(model%bodies)
            mats(i) = model%bodies(i)%material
         end do
         call model%stiff%init_bodies(model%mesh, mats, model%body_of, stat, errmsg)
      end if
      if (stat /= 0) return
      allocate (model%pairs(0), model%contacts(0))
      ! derived quantities checked before use, naming what they come from (contact2d_checks)
      stat = 1
      if (check_positive(deck%path//': smallest lumped nodal mass (material:density, mesh:lx, ly, nx, ny, level)', &
                         minval(model%stiff%mass), errmsg)) return
      if (check_positive(deck%path//': largest element frequency squared (material:young, density, mesh size)', &
                         model%stiff%omega2_element, errmsg)) return
      stat = 0
      model%body_mass = sum(model%stiff%mass)
      dt_scaled = 0
      if (deck%solver%mass_scaling > 0 .and. deck%solver%method == 'static') then
         ! the static engine solves K u = f: no mass to scale (docs/static.md); said, not applied, so
         ! that --static runs a deck made for the explicit engine
         call model%warnings%add('solver:mass_scaling = '//str(deck%solver%mass_scaling)// &
                                 ' s is not used by the static engine (no mass, no time step)')
      else if (deck%solver%mass_scaling > 0) then
         call mass_scale(model%stiff, deck%solver%mass_scaling, model%added_mass, model%scaled_nodes, dt_scaled)
      end if

      call model%load%init(model%mesh%nnode)
      do i = 1, size(deck%dirichlet)
         call add_edge_load(deck%dirichlet(i), 'dirichlet', i)
         if (stat /= 0) return
      end do
      do i = 1, size(deck%traction)
         call add_edge_load(deck%traction(i), 'traction', i)
         if (stat /= 0) return
      end do
      call model%load%finalize()

      if (size(deck%contacts) > 0) then
         deallocate (model%pairs, model%contacts)
         allocate (model%pairs(size(deck%contacts)), model%contacts(size(deck%contacts)))
      end if
      do i = 1, size(deck%contacts)
         call build_contact(i)
         if (stat /= 0) return
      end do
      call slave_overlap()
      if (stat /= 0) return
      call rigid_check()
      if (stat /= 0) return

      ! the time step (contact2d_timestep): the critical step, dt from the deck, and for the
      ! explicit engine the power-iteration estimate (solver:dt_limit = 'power')
      ! (each pair's penalty springs sit on its own nodes: the smallest of the pairs' bounds)
      if (size(model%contacts) == 0) then
         model%dt_critical = timestep_critical(model%stiff, nocontact, dt_scaled)
      else
         model%dt_critical = timestep_critical(model%stiff, model%contacts(1), dt_scaled)
         do i = 2, size(model%contacts)
            model%dt_critical = min(model%dt_critical, timestep_critical(model%stiff, model%contacts(i), dt_scaled))
         end do
      end if
      stat = 1
      if (check_positive(deck%path//': dt_critical (from material:young, density and the mesh size)', &
                         model%dt_critical, errmsg)) return
      call timestep_choose(deck, model%dt_critical, any(model%contacts%penalty), model%dt, model%warnings, stat, errmsg)
      if (stat /= 0) return
      if (deck%solver%method /= 'static') then
         call timestep_power(deck, model%stiff, model%load%free, model%contacts, model%dt, model%omega2_power)
         model%dt_guarded = timestep_guarded(deck, model%dt, model%dt_critical)
      end if
      select case (trim(deck%solver%damping))
      case ('none'); model%damping = damping_none
      case ('given'); model%damping = damping_given
      case default; model%damping = damping_auto
      end select
      ! the initial velocity of each node: uniform, or its body's own (&body velocity)
      allocate (model%velocity0(2, model%mesh%nnode))
      model%velocity0(1, :) = deck%initial%velocity(1)
      model%velocity0(2, :) = deck%initial%velocity(2)
      do i = 1, size(deck%body)
         if (any(deck%body(i)%velocity == unset)) cycle
         do e = 1, model%mesh%nel
            if (model%body_of(e) /= i) cycle
            do k = 1, 4
               model%velocity0(:, model%mesh%conn(k, e)) = deck%body(i)%velocity
            end do
         end do
      end do
      ! the last warning: an initial velocity on prescribed dofs (contact2d_initial)
      errmsg = initial_velocity_warning(model%load%free, deck%initial%velocity)
      if (len(errmsg) > 0) call model%warnings%add(errmsg)
      stat = 0
      errmsg = ''
   contains
      !> model%bodies and model%body_of from the deck's &body groups; refused: a surface the mesh
      !> lacks (its names listed), an element in two bodies, an element in none.
      subroutine build_bodies()
         integer :: b, k, e, sidx
         type(material_t) :: mat
         character(len=:), allocatable :: where
         allocate (model%bodies(size(deck%body)), model%body_of(model%mesh%nel))
         model%body_of = 0
         do b = 1, size(deck%body)
            associate (c => deck%body(b))
               where = deck%path//':'//str(c%line)//": &body (#"//str(b)//") '"//trim(c%name)//"': "
               sidx = model%mesh%surface_index(c%surface)
               if (sidx == 0) then
                  stat = 1
                  errmsg = where//"surface = '"//trim(c%surface)//"' is not a physical surface of "// &
                           trim(deck%mesh%file)//'; it has '//model%mesh%surface_list()
                  return
               end if
               do k = model%mesh%sstart(sidx), model%mesh%sstart(sidx + 1) - 1
                  e = model%mesh%selem(k)
                  if (model%body_of(e) /= 0 .and. model%body_of(e) /= b) then
                     stat = 1
                     errmsg = where//'element '//str(model%mesh%id_of(e))//' of surface '''//trim(c%surface)// &
                              ''' is also in body '''//trim(deck%body(model%body_of(e))%name)// &
                              '''; an element belongs to one body'
                     return
                  end if
                  model%body_of(e) = b
               end do
               call material_init(mat, c%young, c%poisson, c%density, stat, errmsg)
               if (stat /= 0) then
                  errmsg = where//errmsg
                  return
               end if
               call body_init(model%bodies(b), trim(c%name), pack([(e, e=1, model%mesh%nel)], model%body_of == b), mat)
            end associate
         end do
         e = findloc(model%body_of, 0, dim=1)
         if (e > 0) then
            stat = 1
            errmsg = deck%path//': element '//str(model%mesh%id_of(e))//' of '//trim(deck%mesh%file)//' is in no body ('// &
                     str(count(model%body_of == 0))//' element(s) are): give every element a &body (surfaces: '// &
                     model%mesh%surface_list()//')'
            return
         end if
         do b = 1, size(model%bodies)
            if (size(model%bodies(b)%elements) == 0) then
               stat = 1
               errmsg = deck%path//':'//str(deck%body(b)%line)//": &body (#"//str(b)//") '"//trim(deck%body(b)%name)// &
                        "': surface = '"//trim(deck%body(b)%surface)//"' holds no quadrilateral"
               return
            end if
         end do
         stat = 0
      end subroutine build_bodies

      !> The contact operator and pair record of the deck's ip-th &contact group.
      subroutine build_contact(ip)
         integer, intent(in) :: ip
         integer, allocatable :: nodes(:)
         type(contact_config_t) :: cfg
         character(len=:), allocatable :: obstacle, warning
         integer :: g, slave, master, nwarn, k
         real(wp) :: d1, d2
         associate (c => deck%contacts(ip))
            if (len_trim(c%boundary) > 0) then
               ! Gamma_c: the chain of boundary edges of the named group (docs/geometry.md)
               g = model%mesh%group_index(c%boundary)
               if (g == 0) then
                  stat = 1
                  errmsg = deck%path//": contact:boundary = '"//trim(c%boundary)//"' is not a physical curve of "// &
                           trim(deck%mesh%file)//'; it has '//model%mesh%group_list()
                  return
               end if
               call model%mesh%group_chain(g, [c%xmin, c%xmax, c%ymin, c%ymax], c%direction == 'cw', nodes, &
                                           stat, errmsg)
               if (stat /= 0) then
                  errmsg = deck%path//": contact:boundary = '"//trim(c%boundary)//"' "//errmsg
                  return
               end if
               ! with an origin, the chain starts at its end nearer to O
               if (all(c%origin /= unset)) then
                  d1 = norm2(model%mesh%x(:, nodes(1)) - c%origin)
                  d2 = norm2(model%mesh%x(:, nodes(size(nodes))) - c%origin)
                  if (d2 < d1) nodes = nodes(size(nodes):1:-1)
               end if
            else
               call model%mesh%select_nodes(edge_id(c%edge), [c%xmin, c%xmax, c%ymin, c%ymax], nodes)
               if (c%direction == 'cw') nodes = nodes(size(nodes):1:-1)
            end if
            ! the slave body: every edge of Gamma_c in one body (docs/deck.md &body)
            call chain_body(nodes, slave, "boundary = '"//trim(c%boundary)//"'")
            if (stat /= 0) return
            if (len_trim(c%master) > 0) then
               ! another body's boundary as the master side (docs/geometry.md "Two bodies")
               call build_master(ip, slave, cfg, master)
               if (stat /= 0) return
               obstacle = "boundary '"//trim(c%master)//"' of body '"//model%bodies(master)%name//"'"
            else
               call c%shape%make(cfg%obstacle)
               ! the obstacle's prescribed motion and where the step takes its geometry from
               call c%motion%apply(cfg%obstacle)
               cfg%current = c%motion%current()
               obstacle = cfg%obstacle%describe()
            end if
            cfg%origin = c%origin
            cfg%multiplier = c%multiplier
            if (allocated(c%law)) allocate (cfg%friction, source=c%law)
            cfg%method = c%method
            cfg%penalty_stiffness = c%penalty_stiffness
            cfg%file_id = model%mesh%file_id([(g, g=1, model%mesh%nnode)])
            nwarn = model%warnings%n
            call model%contacts(ip)%init(cfg, nodes, model%mesh%x, model%load%free, model%stiff%mass, &
                                    model%warnings, stat, errmsg)
            ! the k-th group's warnings say contact#k (the first's, contact, as before)
            if (ip > 1) then
               do k = nwarn + 1, model%warnings%n
                  if (index(model%warnings%items(k), 'contact:') == 1) &
                     model%warnings%items(k) = 'contact#'//str(ip)//trim(model%warnings%items(k)(8:))
               end do
            end if
            ! an obstacle that the built-in edge can never touch (the shape's own test): warn
            if (stat == 0 .and. len_trim(c%boundary) == 0 .and. len_trim(c%master) == 0) then
               warning = c%shape%edge_warning(trim(c%edge), outward(:, edge_id(c%edge)))
               if (len(warning) > 0) call model%warnings%add(warning)
            end if
         end associate
         if (stat /= 0) then
            ! the k-th group's messages say contact#k (the first's, contact, as before)
            if (ip > 1 .and. index(errmsg, 'contact:') == 1) errmsg = 'contact#'//str(ip)//errmsg(8:)
            errmsg = deck%path//': '//errmsg
            return
         end if
         ! the pair: the contact nodes kept by contact%init against the obstacle or the master body
         call pair_init(model%pairs(ip), trim(deck%contacts(ip)%name), slave, model%contacts(ip)%node, obstacle)
         if (model%contacts(ip)%body) then
            model%pairs(ip)%master_kind = master_body
            model%pairs(ip)%master_body = master
         end if
      end subroutine build_contact

      !> The master chain of the ip-th &contact group (contact:master, a physical curve, all of it,
      !> counter-clockwise: its body on the left), its body (refused: not a curve of the mesh, on
      !> several bodies, on the slave's body), a point inside that body by its first edge, the
      !> overlap tolerance.
      subroutine build_master(ip, slave, cfg, master)
         integer, intent(in) :: ip
         integer, intent(in) :: slave
         type(contact_config_t), intent(inout) :: cfg
         integer, intent(out) :: master
         integer :: gm
         real(wp) :: t(2), hmin
         integer :: k
         associate (c => deck%contacts(ip))
            gm = model%mesh%group_index(c%master)
            if (gm == 0) then
               stat = 1
               errmsg = deck%path//": contact:master = '"//trim(c%master)//"' is not a physical curve of "// &
                        trim(deck%mesh%file)//'; it has '//model%mesh%group_list()
               return
            end if
            call model%mesh%group_chain(gm, [-unset, unset, -unset, unset], .false., cfg%master_nodes, stat, errmsg)
            if (stat /= 0) then
               errmsg = deck%path//": contact:master = '"//trim(c%master)//"' "//errmsg
               return
            end if
            call chain_body(cfg%master_nodes, master, "master = '"//trim(c%master)//"'")
            if (stat /= 0) return
            if (master == slave) then
               stat = 1
               errmsg = deck%path//": contact:master = '"//trim(c%master)//"' and boundary = '"// &
                        trim(c%boundary)//"' are both on body '"//model%bodies(master)%name// &
                        "'; contact pairs the boundaries of two different bodies"
               return
            end if
            associate (xm => model%mesh%x(:, cfg%master_nodes))
               t = xm(:, 2) - xm(:, 1)
               cfg%master_inside = 0.5_wp*(xm(:, 1) + xm(:, 2)) + 0.1_wp*[-t(2), t(1)]
               hmin = huge(1.0_wp)
               do k = 1, size(cfg%master_nodes) - 1
                  hmin = min(hmin, norm2(xm(:, k + 1) - xm(:, k)))
               end do
            end associate
            ! the overlap the meshes' round-off may leave: 1e-6 of the shortest master edge
            cfg%overlap_tol = 1.0e-6_wp*hmin
         end associate
      end subroutine build_master

      !> A node in the slave sets of two pairs is refused: the forward-increment multipliers of
      !> two pairs on one node would need one joint solve (SPEC section 4), which the engines,
      !> solving pair by pair, do not do.
      subroutine slave_overlap()
         integer, allocatable :: owner(:)
         integer :: k, i, n
         allocate (owner(model%mesh%nnode))
         owner = 0
         do k = 1, size(model%contacts)
            do i = 1, model%contacts(k)%nc
               n = model%contacts(k)%node(i)
               if (owner(n) /= 0) then
                  stat = 1
                  errmsg = deck%path//': node '//str(model%mesh%file_id(n))//' ('//str(model%mesh%x(1, n))//', '// &
                           str(model%mesh%x(2, n))//") is a contact node of pairs '"// &
                           trim(deck%contacts(owner(n))%name)//"' and '"//trim(deck%contacts(k)%name)// &
                           "'; a node belongs to one pair (two pairs' multipliers on one node need one joint solve)"
                  return
               end if
               owner(n) = k
            end do
         end do
      end subroutine slave_overlap

      !> The rigid motions of each connected part of the mesh (a body, or bodies bonded where they
      !> share nodes; docs/static.md "Bodies held by contact"): those its supports leave free are
      !> noted (model%unsupported: the static engine then takes its proximal path); one that
      !> contact cannot stop either (no normal, nor a tangent where the law carries friction, does
      !> work on it) is a mechanism: refused when a load drives it or the static engine runs
      !> (K u = f has no unique solution), a warning for the explicit engine otherwise (nothing
      !> moves the part along it).
      subroutine rigid_check()
         integer, allocatable :: root(:), nodes(:), tsel(:)
         integer :: k, e, r, ra, rb
         logical, allocatable :: seen(:)

         ! connected parts: union of the nodes of every element (each root the smallest node)
         allocate (root(model%mesh%nnode))
         root = [(k, k=1, model%mesh%nnode)]
         do e = 1, model%mesh%nel
            do k = 2, 4
               ra = find(root, model%mesh%conn(1, e))
               rb = find(root, model%mesh%conn(k, e))
               root(max(ra, rb)) = min(ra, rb)
            end do
         end do
         do k = 1, model%mesh%nnode
            root(k) = find(root, k)
         end do
         allocate (seen(model%mesh%nnode))
         seen = .false.
         do e = 1, model%mesh%nel
            r = root(model%mesh%conn(1, e))
            if (seen(r)) cycle
            seen(r) = .true.
            nodes = pack([(k, k=1, model%mesh%nnode)], root == r)
            tsel = pack([(k, k=1, size(model%load%tnode))], root(model%load%tnode) == r)
            call part_check(nodes, model%body_of(e), tsel)
            if (stat /= 0) return
         end do
      end subroutine rigid_check

      !> The root of node i's part (rigid_check), halving the path on the way.
      integer function find(root, i) result(f)
         integer, intent(inout) :: root(:)
         integer, intent(in) :: i
         f = i
         do while (root(f) /= f)
            root(f) = root(root(f))
            f = root(f)
         end do
      end function find

      !> rigid_check for one connected part: its nodes, the body that names it, its load entries.
      subroutine part_check(nodes, body, tsel)
         integer, intent(in) :: nodes(:), body, tsel(:)
         type(rigid_t) :: mech, mech_friction, unsupported
         integer, allocatable :: cnode(:)
         real(wp), allocatable :: cn(:, :), ctan(:, :), unit_fn(:), lim(:)
         logical, allocatable :: carries(:), inpart(:), pcarries(:)
         integer, allocatable :: sel(:)
         integer :: ip
         real(wp) :: none(2, 0)
         character(len=:), allocatable :: what, remedy
         logical :: drives
         integer :: k

         ! the supports alone
         call rigid_free_motions(model%mesh%x, nodes, model%load%free, [integer ::], none, none, [logical ::], &
                                 unsupported, stat)
         if (stat /= 0) then
            errmsg = deck%path//": LAPACK dsyev failed on the rigid motions of body '"//model%bodies(body)%name//"'"
            return
         end if
         if (unsupported%nfree == 0) return
         if (model%unsupported%nfree == 0) model%unsupported = unsupported
         ! the supports and contact: normals, and tangents where the law carries a tangential
         ! force under a unit normal force (the contact nodes of this part only)
         allocate (inpart(model%mesh%nnode))
         inpart = .false.
         inpart(nodes) = .true.
         ! every pair's contact nodes in this part, in pair order
         allocate (cnode(0), cn(2, 0), ctan(2, 0), carries(0))
         do ip = 1, size(model%contacts)
            associate (ct => model%contacts(ip))
               sel = pack([(k, k=1, ct%nc)], inpart(ct%node))
               cnode = [cnode, ct%node(sel)]
               cn = reshape([cn, ct%normal(:, sel)], [2, size(cnode)])
               ctan = reshape([ctan, ct%tangent(:, sel)], [2, size(cnode)])
               pcarries = [(.false., k=1, size(sel))]
               if (ct%friction .and. size(sel) > 0) then
                  if (allocated(lim)) deallocate (lim, unit_fn)
                  allocate (lim(ct%nc), unit_fn(ct%nc))
                  unit_fn = 1
                  call ct%law%limits(unit_fn, unit_fn, lim)
                  pcarries = lim(sel) > 0
               end if
               carries = [carries, pcarries]
               ! two bodies: the pair holds its master body too, along its nodal normals
               if (ct%body) then
                  associate (mb => ct%master)
                     cnode = [cnode, pack(mb%mnode, inpart(mb%mnode))]
                     cn = reshape([cn, pack(mb%nodal, spread(inpart(mb%mnode), 1, 2))], [2, size(cnode)])
                     ctan = reshape([ctan, pack(reshape([-mb%nodal(2, :), mb%nodal(1, :)], [2, mb%nm], order=[2, 1]), &
                                                spread(inpart(mb%mnode), 1, 2))], [2, size(cnode)])
                     carries = [carries, spread(.false., 1, count(inpart(mb%mnode)))]
                  end associate
               end if
            end associate
         end do
         call rigid_free_motions(model%mesh%x, nodes, model%load%free, cnode, cn, ctan, carries, mech, stat)
         if (stat /= 0) then
            errmsg = deck%path//": LAPACK dsyev failed on the rigid motions of body '"//model%bodies(body)%name//"'"
            return
         end if
         if (mech%nfree == 0) return
         ! would friction everywhere stop the first motion? then say so
         call rigid_free_motions(model%mesh%x, nodes, model%load%free, cnode, cn, ctan, [(.true., k=1, size(cnode))], &
                                 mech_friction, stat)
         remedy = 'add a &dirichlet'
         if (stat == 0 .and. size(cnode) > 0) then
            if (mech_friction%nfree == 0) then
               remedy = remedy//' or friction'
            else if (norm2(matmul(transpose(mech_friction%motion), mech%motion(:, 1))) < 1 - 1.0e-6_wp) then
               remedy = remedy//' or friction'
            end if
         end if
         stat = 0
         what = "body '"//model%bodies(body)%name//"' is free to "//rigid_describe(mech, mech%motion(:, 1))
         drives = .false.
         do k = 1, mech%nfree
            drives = drives .or. rigid_drive(mech, mech%motion(:, k), model%mesh%x, model%load%tnode(tsel), &
                                             model%load%tcomp(tsel), model%load%tcurve(tsel), model%load%tweight(tsel))
         end do
         if (drives .or. deck%solver%method == 'static' .or. deck%solver%compare_static) then
            stat = 1
            errmsg = deck%path//': '//what//': no support and no contact stops it; '//remedy
         else
            call model%warnings%add(what//' (no support and no contact stops it); no load drives it, so the '// &
                                    'explicit engine runs it, the static engine would refuse it; '//remedy)
         end if
      end subroutine part_check

      !> The body of the chain `nodes` (consecutive nodes are the ends of one element edge): the
      !> body of the elements holding its edges; stat = 1 when they are of several bodies.
      subroutine chain_body(nodes, slave, what)
         integer, intent(in) :: nodes(:)
         integer, intent(out) :: slave
         character(len=*), intent(in) :: what   !< the deck's variable and value, for the message
         integer, allocatable :: adj_start(:), adj_elem(:)
         integer :: i, k, e, b
         slave = 1
         stat = 0
         if (size(model%bodies) == 1) return
         call node_elements(model%mesh%conn, model%mesh%nnode, adj_start, adj_elem)
         slave = 0
         do i = 1, size(nodes) - 1
            do k = adj_start(nodes(i)), adj_start(nodes(i) + 1) - 1
               e = adj_elem(k)
               if (.not. any(model%mesh%conn(:, e) == nodes(i + 1))) cycle
               b = model%body_of(e)
               if (slave == 0) slave = b
               if (b /= slave) then
                  stat = 1
                  errmsg = deck%path//": contact:"//what//" lies on bodies '"// &
                           model%bodies(slave)%name//"' and '"//model%bodies(b)%name// &
                           "'; a contact boundary lies on one body"
                  return
               end if
            end do
         end do
         ! a chain of one node (no edge): the lowest body of that node's elements
         if (slave == 0 .and. size(nodes) > 0) &
            slave = minval(model%body_of(adj_elem(adj_start(nodes(1)):adj_start(nodes(1) + 1) - 1)))
         if (slave == 0) slave = 1
      end subroutine chain_body

      subroutine add_edge_load(cfg, group, k)
         type(edge_load_cfg_t), intent(in) :: cfg
         character(len=*), intent(in) :: group
         integer, intent(in) :: k
         integer, allocatable :: nodes(:), seg(:, :)
         integer :: id, comp, conflict, g, interior
         character(len=:), allocatable :: where

         where = deck%path//':'//str(cfg%line)//': &'//group//' (#'//str(k)//'): '
         interior = 0
         if (len_trim(cfg%boundary) > 0) then
            g = model%mesh%group_index(cfg%boundary)
            if (g == 0) then
               stat = 1
               errmsg = where//"boundary = '"//trim(cfg%boundary)//"' is not a physical curve of "// &
                        trim(deck%mesh%file)//'; it has '//model%mesh%group_list()
               return
            end if
            call model%mesh%select_group(g, [cfg%xmin, cfg%xmax, cfg%ymin, cfg%ymax], nodes, seg, interior)
            if (size(nodes) == 0) then
               stat = 1
               errmsg = where//"the selection (boundary = '"//trim(cfg%boundary)//"' and its range) holds no node"
               return
            end if
         else
            call model%mesh%select_nodes(edge_id(cfg%edge), [cfg%xmin, cfg%xmax, cfg%ymin, cfg%ymax], nodes)
            if (size(nodes) == 0) then
               stat = 1
               errmsg = where//"the selection (edge = '"//trim(cfg%edge)//"' and its range) holds no node"
               return
            end if
         end if
         comp = merge(1, 2, cfg%component == 'x')
         id = model%load%add_curve(cfg%times(1:cfg%nstage), cfg%values(1:cfg%nstage))
         if (group == 'dirichlet') then
            call model%load%prescribe(nodes, comp, id, conflict)
            if (conflict /= 0) then
               stat = 1
               errmsg = where//'node '//str(model%mesh%file_id(conflict))//' ('//str(model%mesh%x(1, conflict))//', '// &
                        str(model%mesh%x(2, conflict))//') component '//trim(cfg%component)// &
                        ' is already prescribed with another load curve'
               return
            end if
         else
            if (len_trim(cfg%boundary) == 0) call model%mesh%select_segments(nodes, seg)
            if (size(seg, 2) == 0) then
               stat = 1
               errmsg = where//'the selection holds no element edge (a single node cannot carry a traction)'
               return
            end if
            if (cfg%component == 'normal' .or. cfg%component == 'tangential') then
               if (interior > 0) then
                  stat = 1
                  errmsg = where//"boundary = '"//trim(cfg%boundary)//"': "//str(interior)//' of its edges lie '// &
                           'inside the mesh; a normal or tangential traction needs boundary edges'
                  return
               end if
               call model%load%add_traction_rotated(model%mesh%x, seg, cfg%component == 'tangential', id)
            else
               call model%load%add_traction(model%mesh%x, seg, comp, id)
            end if
         end if
      end subroutine add_edge_load
   end subroutine model_build

   !> A relative file name is taken relative to the deck's directory (docs/geometry.md).
   function beside(deck_path, file) result(path)
      character(len=*), intent(in) :: deck_path, file
      character(len=:), allocatable :: path
      integer :: slash
      slash = index(deck_path, '/', back=.true.)
      if (file(1:1) == '/' .or. slash == 0) then
         path = file
      else
         path = deck_path(1:slash)//file
      end if
   end function beside
end module contact2d_model
