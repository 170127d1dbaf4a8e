!> Deck -> model: the mesh, material, element matrices, boundary data, contact and time step
!> built from a validated deck. Every cross-group check that needs the model lives here.
module contact2d_model
   use contact2d_kinds, only: wp
   use contact2d_version, only: program_name
   use contact2d_strings, only: str
   use contact2d_checks, only: check_positive
   use contact2d_messages, only: messages_t
   use contact2d_deck, only: deck_t, edge_load_cfg_t, edge_id, unset
   use contact2d_mesh, only: mesh_t
   use contact2d_material, only: material_t, material_init
   use contact2d_stiffness, only: stiffness_t
   use contact2d_mass_scaling, only: mass_scale
   use contact2d_loading, only: loading_t
   use contact2d_contact, only: contact_t, contact_config_t
   use contact2d_gmsh, only: gmsh_read
   use contact2d_explicit, only: damping_none, damping_given, damping_auto
   use contact2d_initial, only: initial_velocity_warning
   use contact2d_body, only: body_t, body_init
   use contact2d_pair, only: contact_pair_t, pair_init
   use contact2d_timestep, only: timestep_critical, timestep_choose, timestep_power, timestep_guarded
   implicit none
   private
   public :: model_t, model_build, beside

   !> Everything the deck and the mesh define: built once by model_build, read-only (intent(in))
   !> from then on. What changes during a run is in the state (contact2d_state).
   type :: model_t
      type(mesh_t) :: mesh
      !> the bodies (contact2d_body): one today, the whole mesh
      type(body_t), allocatable :: bodies(:)
      !> the contact pairs (contact2d_pair): none, or one (the deck's &contact) today
      type(contact_pair_t), allocatable :: pairs(:)
      type(stiffness_t) :: stiff
      type(loading_t) :: load
      !> the contact operator as built and validated; each run's state works on a copy of it
      type(contact_t) :: contact
      real(wp) :: dt = 0             !< initial time step (contact2d_timestep) [s]
      real(wp) :: dt_critical = 0    !< critical step: element bound, mass scaling, penalty [s]
      real(wp) :: omega2_power = 0   !< power-iteration estimate of omega_max^2 (0: none) [1/s^2]
      logical :: dt_guarded = .false.   !< dt from the power estimate: watch for a growing mode
      integer :: damping = damping_auto
      ! mass scaling (solver:mass_scaling > 0)
      real(wp) :: added_mass = 0     !< total fictitious mass [t]
      real(wp) :: body_mass = 0      !< physical mass of the body [t]
      integer :: scaled_nodes = 0    !< nodes that got mass
      type(messages_t) :: warnings
   end type model_t

contains

   !> Build the model. stat /= 0 with a one-line message naming the problem. The model is not
   !> changed after this (every later use is intent(in)); its warnings are all collected here.
   subroutine model_build(deck, model, stat, errmsg)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(out) :: model
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer :: i, nx, ny, nflip
      type(material_t) :: material
      !> outward normals of the sides bottom, right, top, left
      real(wp), parameter :: outward(2, 4) = reshape([0.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
                                                      -1.0_wp, 0.0_wp], [2, 4])
      real(wp) :: dt_scaled

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
      ! the one body: every element, the deck's material; the element matrices and masses are
      ! formed with the body's material (contact2d_stiffness)
      call material_init(material, deck%material%young, deck%material%poisson, &
                         deck%material%density, stat, errmsg)
      if (stat /= 0) return
      allocate (model%bodies(1))
      call body_init(model%bodies(1), 'body', [(i, i=1, model%mesh%nel)], material)
      call model%stiff%init(model%mesh, model%bodies(1)%material, stat, errmsg)
      if (stat /= 0) return
      allocate (model%pairs(0))
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

      if (deck%contact%present) then
         call build_contact()
         if (stat /= 0) return
      end if

      ! the time step (contact2d_timestep): the critical step, dt from the deck, and for the
      ! explicit engine the power-iteration estimate (solver:dt_limit = 'power')
      model%dt_critical = timestep_critical(model%stiff, model%contact, dt_scaled)
      stat = 1
      if (check_positive(deck%path//': dt_critical (from material:young, density and the mesh size)', &
                         model%dt_critical, errmsg)) return
      call timestep_choose(deck, model%dt_critical, model%contact%penalty, model%dt, model%warnings, stat, errmsg)
      if (stat /= 0) return
      if (deck%solver%method /= 'static') then
         call timestep_power(deck, model%stiff, model%load%free, model%contact, model%dt, model%omega2_power)
         model%dt_guarded = timestep_guarded(deck, model%dt, model%dt_critical)
      end if
      select case (trim(deck%solver%damping))
      case ('none'); model%damping = damping_none
      case ('given'); model%damping = damping_given
      case default; model%damping = damping_auto
      end select
      ! the last warning: an initial velocity on prescribed dofs (contact2d_initial)
      errmsg = initial_velocity_warning(model%load%free, deck%initial%velocity)
      if (len(errmsg) > 0) call model%warnings%add(errmsg)
      stat = 0
      errmsg = ''
   contains
      subroutine build_contact()
         integer, allocatable :: nodes(:)
         type(contact_config_t) :: cfg
         character(len=:), allocatable :: obstacle, warning
         integer :: g
         real(wp) :: d1, d2
         associate (c => deck%contact)
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
            call c%shape%make(cfg%obstacle)
            ! the obstacle's prescribed motion and where the step takes its geometry from
            call c%motion%apply(cfg%obstacle)
            cfg%current = c%motion%current()
            cfg%origin = c%origin
            cfg%multiplier = c%multiplier
            if (allocated(c%law)) allocate (cfg%friction, source=c%law)
            cfg%method = c%method
            cfg%penalty_stiffness = c%penalty_stiffness
            cfg%file_id = model%mesh%file_id([(g, g=1, model%mesh%nnode)])
            obstacle = cfg%obstacle%describe()
            call model%contact%init(cfg, nodes, model%mesh%x, model%load%free, model%stiff%mass, &
                                    model%warnings, stat, errmsg)
            ! an obstacle that the built-in edge can never touch (the shape's own test): warn
            if (stat == 0 .and. len_trim(c%boundary) == 0) then
               warning = c%shape%edge_warning(trim(c%edge), outward(:, edge_id(c%edge)))
               if (len(warning) > 0) call model%warnings%add(warning)
            end if
         end associate
         if (stat /= 0) then
            errmsg = deck%path//': '//errmsg
            return
         end if
         ! the one pair: the contact nodes kept by contact%init against the obstacle
         if (model%contact%active) then
            deallocate (model%pairs)
            allocate (model%pairs(1))
            call pair_init(model%pairs(1), 1, model%contact%node, obstacle)
         end if
      end subroutine build_contact

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
