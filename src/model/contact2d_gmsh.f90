!> Quadrilateral meshes from Gmsh through its own library (the C API of libgmsh, gmshc.h, bound
!> with iso_c_binding; docs/geometry.md, the extension of SPEC sections 2 and 8).
!>
!> A .geo file is meshed here (2D, then refined `level` times by Gmsh: each quad split in four,
!> new boundary nodes on the geometry); a .msh file (any version Gmsh reads) is taken as it is,
!> then refined the same way. Only 4-node quadrilaterals are accepted. Physical curves become
!> named boundary groups of 2-node edges, physical surfaces named groups of elements (the bodies
!> of a deck with &body groups). Nodes are renumbered 1..n in increasing Gmsh tag,
!> keeping only the nodes of the quadrilaterals (a circle's centre point carries no mass).
module contact2d_gmsh
   use, intrinsic :: iso_c_binding, only: c_int, c_size_t, c_double, c_char, c_ptr, c_null_ptr, &
                                          c_f_pointer, c_associated, c_long_long
   use, intrinsic :: ieee_exceptions, only: ieee_get_halting_mode, ieee_set_halting_mode, ieee_set_flag, &
                                            ieee_all, ieee_usual
   use omp_lib, only: omp_get_max_threads, omp_set_num_threads
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use contact2d_gmsh_api
   use contact2d_kinds, only: wp, i8
   use contact2d_strings, only: str
   use contact2d_sys, only: sys_path_info, sys_strerror, kind_file, kind_missing, kind_names
   use contact2d_mesh, only: mesh_t, mesh_max_elements
   use contact2d_renumber, only: rcm_order, group_order
   implicit none
   private
   public :: gmsh_read

   !> Gmsh element types used here (Gmsh's numbering).
   integer(c_int), parameter :: type_line2 = 1, type_quad4 = 3

contains

   !> Read (and for a .geo, mesh) `path`, refine it `level` times and fill `mesh` with its quads
   !> (orientation not yet checked: mesh%orient does that) and named boundary groups.
   !> context: put before the one line written when Gmsh crashes or ends the program while it
   !> works (the caller's error prefix, e.g. 'contact2d: error: deck.nml: ').
   subroutine gmsh_read(path, level, mesh, stat, errmsg, context)
      character(len=*), intent(in) :: path
      integer, intent(in) :: level
      type(mesh_t), intent(inout) :: mesh
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      character(len=*), intent(in), optional :: context
      logical :: halting(size(ieee_usual))
      integer :: threads
      ! Gmsh's own arithmetic may raise IEEE flags (e.g. a 0/0 it handles itself): no floating-
      ! point traps while it runs (the Debug build traps invalid, zero and overflow), restored after
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      ! Gmsh sets the OpenMP thread count to its General.NumThreads (1) in gmshInitialize: the
      ! run's own count (OMP_NUM_THREADS, or all cores) is put back after it
      threads = omp_get_max_threads()
      if (present(context)) then
         call read_untrapped(path, level, mesh, stat, errmsg, context)
      else
         call read_untrapped(path, level, mesh, stat, errmsg, '')
      end if
      call omp_set_num_threads(threads)
      call ieee_set_flag(ieee_all, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
   end subroutine gmsh_read

   subroutine read_untrapped(path, level, mesh, stat, errmsg, context)
      character(len=*), intent(in) :: path
      integer, intent(in) :: level
      type(mesh_t), intent(inout) :: mesh
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      character(len=*), intent(in) :: context
      integer(c_int) :: ierr
      integer(c_long_long) :: dev, ino, bytes
      integer :: k, kind, err
      real(wp) :: n2, n1, nfinal
      character(len=:), allocatable :: head
      character(len=*), parameter :: stage_collect = 'passing its mesh to contact2d'

      stat = 1
      call sys_path_info(path, kind, dev, ino, bytes, err)
      if (err /= 0) then
         ! the system's reason: a link loop (ELOOP), a name too long, a folder not searchable
         errmsg = "mesh:file = '"//path//"': "//sys_strerror(err)
         return
      else if (kind == kind_missing) then
         errmsg = "mesh:file = '"//path//"': no such file"
         return
      else if (kind /= kind_file) then
         errmsg = "mesh:file = '"//path//"' is a "//trim(kind_names(kind))//', not a regular file'
         return
      end if
      call load_gmsh(stat, errmsg)
      if (stat /= 0) return
      stat = 1
      head = "mesh:file = '"//path//"'"
      ! From here on Gmsh's ways of ending the process (a crash, an uncaught C++ exception, exit()
      ! called by a .geo's Exit statement) end it with one line and status 1 (contact2d_gmsh_guard.c)
      call stage('initialising the Gmsh library')
      call c2d_gmsh_guard_begin()
      call gmshInitialize(0_c_int, c_null_ptr, 0_c_int, ierr)
      if (ierr /= 0) then
         call give_up('mesh: the Gmsh library failed to initialise (ierr = '//str(int(ierr))//')')
         return
      end if
      ! quiet: Gmsh's own log stays off the terminal; its last error is quoted instead
      call gmshOptionSetNumber(cstr('General.Terminal'), 0.0_c_double, ierr)
      if (ierr == 0) call gmshOptionSetNumber(cstr('General.Verbosity'), 1.0_c_double, ierr)
      call stage('reading it')
      if (ierr == 0) call gmshOpen(cstr(path), ierr)
      if (ierr /= 0) then
         call give_up(head//': Gmsh cannot read it'//last_error())
         return
      end if
      if (ends_with(path, '.geo')) then
         ! Gmsh 4.8 (Debian 12) crashes in its quad algorithm 8: refused before meshing
         if (crashing_algorithm()) then
            call give_up(head//' sets Mesh.Algorithm = 8, which crashes (segfault) the Gmsh '// &
                         'library older than 4.9 (Debian 12 has 4.8.4); use Mesh.Algorithm = 6 with Mesh.RecombineAll = 1 '// &
                         '(docs/geometry.md)')
            return
         end if
         ! The size before the surfaces are meshed (Gmsh 4.8 has no element-count limit): the
         ! curves first. A square whose boundary carries n1 segments of size h holds (n1/4)^2
         ! quadrilaterals of side h; a surface meshed at the size of its boundary holds about as
         ! many (a disk 4/pi times more, a thin strip far fewer): refused above the cap
         call stage('meshing its curves')
         call gmshModelMeshGenerate(1_c_int, ierr)
         if (ierr /= 0) then
            call give_up(head//': Gmsh failed to mesh it'//last_error())
            return
         end if
         n1 = count_option('Mesh.NbNodes')
         if ((n1/4)**2 > mesh_max_elements) then
            call give_up(head//': its curves are meshed with '//str(n1)//' nodes; a square with that '// &
                         'boundary holds (n/4)^2 = '//str(real(nint((n1/4)**2, i8), wp))//' quadrilaterals, more than '// &
                         'this program is meant for ('//str(mesh_max_elements)//'): coarsen the mesh '// &
                         '(larger characteristic lengths, fewer nodes or layers; docs/geometry.md)')
            return
         end if
         call stage('meshing it')
         call gmshModelMeshGenerate(2_c_int, ierr)
         if (ierr /= 0) then
            call give_up(head//': Gmsh failed to mesh it'//last_error())
            return
         end if
      end if
      ! the size after refinement is known before refining: each level splits a 2D element in four
      n2 = count_option('Mesh.NbQuadrangles') + count_option('Mesh.NbTriangles')
      nfinal = n2*4.0_wp**level
      if (nfinal > mesh_max_elements) then
         call give_up(head//' has '//str(n2)//' 2D elements; refined level = '//str(level)//' times that is '// &
                      str(n2)//'*4**'//str(level)//' = '//str(nfinal)//' elements, more than this program '// &
                      'is meant for ('//str(mesh_max_elements)//')')
         return
      end if
      do k = 1, level
         call stage('refining it (refinement '//str(k)//' of '//str(level)//')')
         call gmshModelMeshRefine(ierr)
         if (ierr /= 0) then
            call give_up(head//': Gmsh refinement '//str(k)//' failed'//last_error())
            return
         end if
      end do
      call stage(stage_collect)
      call collect(path, mesh, stat, errmsg)
      if (stat /= 0) then
         call give_up(errmsg)
         return
      end if
      call stage('finalising the Gmsh library')
      call gmshFinalize(ierr)
      call c2d_gmsh_guard_end()
      if (ierr /= 0) then
         stat = 1
         errmsg = 'mesh: gmshFinalize failed (ierr = '//str(int(ierr))//')'
      end if
   contains
      !> Name the stage in the line the guard writes if Gmsh crashes or exits during it.
      subroutine stage(what)
         character(len=*), intent(in) :: what
         character(len=:), allocatable :: crash, quit
         crash = context//head//': the Gmsh library crashed while '//what
         quit = context//head//': Gmsh ended the program while '//what//' (exit() called by Gmsh: an Exit '// &
                'statement in the .geo, or a fatal Gmsh error); contact2d needs the mesh: remove the Exit '// &
                '(a .geo is a program Gmsh runs, docs/geometry.md)'
         if (index(what, 'refining') == 1) then
            ! refining a mesh already read runs no .geo statement: an exit() there is Gmsh's own
            ! fatal error, seen when the refined mesh does not fit in memory
            quit = context//head//': Gmsh ended the program while '//what//' (exit() called by Gmsh: a '// &
                   'fatal Gmsh error, such as running out of memory: the refined mesh may not fit in the '// &
                   'memory this process may use; try a lower mesh:level)'
         end if
         if (what == stage_collect) then
            ! Fortran's own run-time errors (a failed allocation) end the program too, their
            ! message discarded with Gmsh's stderr
            crash = context//head//': crashed while '//what
            quit = context//head//': the program ended while '//what//' (a failed allocation: the mesh '// &
                   'may not fit in the memory this process may use)'
         end if
         call c2d_gmsh_guard_lines(crash, int(len(crash), c_int), quit, int(len(quit), c_int))
      end subroutine stage
      !> Stop reading with errmsg = msg and finalise the library. After a Gmsh failure (out of
      !> memory, say) gmshFinalize was seen to crash: should it, the guard writes msg itself,
      !> naming the crash, so that the one line still says why the mesh was refused.
      subroutine give_up(msg)
         character(len=*), intent(in) :: msg
         character(len=:), allocatable :: crash, quit
         integer(c_int) :: ierr2
         errmsg = msg
         stat = 1
         crash = context//msg//'; then the Gmsh library crashed while finalising'
         quit = context//msg//'; then Gmsh ended the program while finalising'
         call c2d_gmsh_guard_lines(crash, int(len(crash), c_int), quit, int(len(quit), c_int))
         call gmshFinalize(ierr2)
         call c2d_gmsh_guard_end()
      end subroutine give_up
      !> A read-only Gmsh statistic (Mesh.NbNodes, Mesh.NbQuadrangles, ...) of the current mesh.
      real(wp) function count_option(name)
         character(len=*), intent(in) :: name
         real(c_double) :: v
         integer(c_int) :: e
         call gmshOptionGetNumber(cstr(name), v, e)
         count_option = 0
         if (e == 0) count_option = real(v, wp)
      end function count_option
      !> Mesh.Algorithm = 8 with a Gmsh older than 4.9 (4.8 has no General.MajorVersion option:
      !> a library that does not say its version counts as old).
      logical function crashing_algorithm()
         real(c_double) :: algorithm, major, minor
         integer(c_int) :: e1, e2, e3
         call gmshOptionGetNumber(cstr('Mesh.Algorithm'), algorithm, e1)
         call gmshOptionGetNumber(cstr('General.MajorVersion'), major, e2)
         call gmshOptionGetNumber(cstr('General.MinorVersion'), minor, e3)
         crashing_algorithm = .false.
         if (e1 /= 0) return
         if (nint(algorithm) /= 8) return
         crashing_algorithm = .true.
         if (e2 /= 0 .or. e3 /= 0) return
         crashing_algorithm = nint(major) < 4 .or. (nint(major) == 4 .and. nint(minor) < 9)
      end function crashing_algorithm
   end subroutine read_untrapped


   !> Nodes, quadrilaterals and physical curves of the current Gmsh model, in that order of
   !> steps, then the nodes renumbered for the sweep.
   subroutine collect(path, mesh, stat, errmsg)
      character(len=*), intent(in) :: path
      type(mesh_t), intent(inout) :: mesh
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer, allocatable :: local(:), conn(:, :), seg(:, :), gstart(:), elem_id(:), perm(:)
      real(wp), allocatable :: x(:, :)
      character(len=64), allocatable :: names(:)
      integer :: nseg

      stat = 1
      call collect_quads(path, conn, elem_id, stat, errmsg)
      if (stat /= 0) return
      call collect_nodes(path, conn, local, x, stat, errmsg)
      if (stat /= 0) return
      call collect_groups(path, local, names, gstart, seg, nseg, stat, errmsg)
      if (stat /= 0) return
      call mesh%init_arrays(x, conn)
      mesh%elem_id = elem_id
      call mesh%set_groups(names, gstart, seg(:, 1:nseg))
      call collect_surfaces(path, elem_id, mesh%surface_name, mesh%sstart, mesh%selem, stat, errmsg)
      if (stat /= 0) return
      ! nodes in reverse Cuthill-McKee order for the sweep's locality, an element's nodes together
      ! for its groups of rows (outputs keep the file's)
      call rcm_order(mesh%conn, mesh%nnode, perm)
      call group_order(mesh%conn, mesh%nnode, perm)
      call mesh%renumber(perm)
      stat = 0
      errmsg = ''
   end subroutine collect

   !> The quadrilaterals: the model's 2D elements must all be 4-node quadrilaterals of four
   !> distinct nodes; conn holds their Gmsh node tags, elem_id their Gmsh element tags.
   subroutine collect_quads(path, conn, elem_id, stat, errmsg)
      character(len=*), intent(in) :: path
      integer, allocatable, intent(out) :: conn(:, :), elem_id(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(c_ptr) :: p_types, p_etags, p_enodes
      integer(c_size_t) :: n_types, n_etags, n_enodes
      integer(c_int) :: ierr
      integer(c_int), pointer :: types(:)
      integer(c_size_t), pointer :: etags(:), enodes(:)
      integer :: i, j, nel

      stat = 1
      ! 2D element types: quadrilaterals only
      call gmshModelMeshGetElementTypes(p_types, n_types, 2_c_int, -1_c_int, ierr)
      if (ierr /= 0) then
         errmsg = "mesh:file = '"//path//"': Gmsh cannot list its elements"//last_error()
         return
      end if
      call c_f_pointer(p_types, types, [n_types])
      do i = 1, int(n_types)
         if (types(i) /= type_quad4) then
            errmsg = "mesh:file = '"//path//"' holds "//type_name(types(i))//' elements; contact2d takes '// &
                     '4-node quadrilaterals only: add Mesh.RecombineAll = 1; Mesh.SubdivisionAlgorithm = 1; '// &
                     '(with Mesh.Algorithm = 6, not 8) or use transfinite surfaces with Recombine'
            call gmshFree(p_types)
            return
         end if
      end do
      call gmshFree(p_types)
      if (n_types == 0) then
         errmsg = "mesh:file = '"//path//"' holds no 2D element (is there a Plane Surface, and was it meshed? "// &
                  "A .msh saved from a .geo with physical groups holds only their elements: add a Physical Surface)"
         return
      end if

      ! quadrilaterals
      call gmshModelMeshGetElementsByType(type_quad4, p_etags, n_etags, p_enodes, n_enodes, -1_c_int, &
                                          0_c_size_t, 1_c_size_t, ierr)
      if (ierr /= 0) then
         errmsg = "mesh:file = '"//path//"': Gmsh cannot give its quadrilaterals"//last_error()
         return
      end if
      call c_f_pointer(p_etags, etags, [n_etags])
      call c_f_pointer(p_enodes, enodes, [n_enodes])
      nel = int(n_etags)
      allocate (conn(4, nel), elem_id(nel))
      elem_id = int(etags)
      conn = reshape(int(enodes), [4, nel])
      call gmshFree(p_etags)
      call gmshFree(p_enodes)
      ! a quadrilateral with a node twice (collapsed to a triangle) is refused: the element rows,
      ! the node grouping and the Q1 element all take four distinct nodes
      do i = 1, nel
         do j = 2, 4
            if (any(conn(1:j - 1, i) == conn(j, i))) then
               errmsg = "mesh:file = '"//path//"': element "//str(elem_id(i))//' has node '//str(conn(j, i))// &
                        ' twice (a degenerate quadrilateral); contact2d takes 4-node quadrilaterals of four distinct nodes'
               return
            end if
         end do
      end do
      stat = 0
   end subroutine collect_quads

   !> The nodes: only those of the quadrilaterals are kept (a circle's centre point carries no
   !> mass), numbered 1..n in increasing Gmsh tag (local maps a tag to that number, 0 when not
   !> kept); x gets their finite coordinates and conn is rewritten in the new numbers.
   subroutine collect_nodes(path, conn, local, x, stat, errmsg)
      character(len=*), intent(in) :: path
      integer, intent(inout) :: conn(:, :)
      integer, allocatable, intent(out) :: local(:)
      real(wp), allocatable, intent(out) :: x(:, :)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(c_ptr) :: p_tags, p_coord, p_pc
      integer(c_size_t) :: n_tags, n_coord, n_pc
      integer(c_int) :: ierr
      integer(c_size_t), pointer :: tags(:)
      real(c_double), pointer :: coord(:)
      integer, allocatable :: used(:)
      integer(c_size_t) :: maxtag
      integer :: i, j, nel, nnode, bad

      stat = 1
      nel = size(conn, 2)
      ! all nodes; keep those of the quadrilaterals, numbered in increasing tag
      call gmshModelMeshGetNodes(p_tags, n_tags, p_coord, n_coord, p_pc, n_pc, -1_c_int, -1_c_int, &
                                 0_c_int, 0_c_int, ierr)
      if (ierr /= 0) then
         errmsg = "mesh:file = '"//path//"': Gmsh cannot give its nodes"//last_error()
         return
      end if
      call c_f_pointer(p_tags, tags, [n_tags])
      call c_f_pointer(p_coord, coord, [n_coord])
      maxtag = max(maxval(tags), int(maxval(conn), c_size_t))
      allocate (local(maxtag), used(maxtag))
      used = 0
      used(pack(conn, .true.)) = 1
      local = 0
      nnode = 0
      ! increasing tag order
      do j = 1, int(maxtag)
         if (used(j) == 1) then
            nnode = nnode + 1
            local(j) = nnode
         end if
      end do
      ! coordinates are finite: a NaN or Infinity (a .msh file is text anyone can edit) would
      ! otherwise surface as a non-positive Jacobian, or trap in the Debug build's area test
      bad = 0
      do i = 1, int(n_tags)
         j = int(tags(i))
         if (j > size(local)) cycle
         if (local(j) == 0) cycle
         if (.not. (ieee_is_finite(coord(3*i - 2)) .and. ieee_is_finite(coord(3*i - 1)))) then
            bad = j
            exit
         end if
      end do
      if (bad > 0) then
         call gmshFree(p_tags)
         call gmshFree(p_coord)
         if (c_associated(p_pc)) call gmshFree(p_pc)
         errmsg = "mesh:file = '"//path//"': node "//str(bad)//' has a coordinate that is not finite (NaN or Infinity)'
         return
      end if
      allocate (x(2, nnode))
      x = 0
      used = 0
      do i = 1, int(n_tags)
         j = int(tags(i))
         if (local(j) > 0) then
            x(1, local(j)) = coord(3*i - 2)
            x(2, local(j)) = coord(3*i - 1)
            used(j) = 1
         end if
      end do
      call gmshFree(p_tags)
      call gmshFree(p_coord)
      if (c_associated(p_pc)) call gmshFree(p_pc)
      if (any(local > 0 .and. used == 0)) then
         errmsg = "mesh:file = '"//path//"': an element refers to a node without coordinates"
         return
      end if
      conn = reshape(local(pack(conn, .true.)), [4, nel])
      stat = 0
   end subroutine collect_nodes

   !> The physical groups: each physical curve becomes a named boundary group of 2-node edges
   !> (its name, or its tag when it has none), in local node numbers; group g is
   !> seg(:, gstart(g):gstart(g+1)-1).
   subroutine collect_groups(path, local, names, gstart, seg, nseg, stat, errmsg)
      character(len=*), intent(in) :: path
      integer, intent(in) :: local(:)
      character(len=64), allocatable, intent(out) :: names(:)
      integer, allocatable, intent(out) :: gstart(:), seg(:, :)
      integer, intent(out) :: nseg
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(c_ptr) :: p_dimtags, p_ents
      integer(c_size_t) :: n_dimtags, n_ents
      integer(c_int) :: ierr
      integer(c_int), pointer :: dimtags(:), ents(:)
      integer :: i, g, ngroup
      character(len=:), allocatable :: name

      stat = 1
      nseg = 0
      ! physical curves -> named groups of 2-node edges
      call gmshModelGetPhysicalGroups(p_dimtags, n_dimtags, 1_c_int, ierr)
      if (ierr /= 0) then
         errmsg = "mesh:file = '"//path//"': Gmsh cannot list its physical groups"//last_error()
         return
      end if
      ngroup = int(n_dimtags)/2
      allocate (names(ngroup), gstart(ngroup + 1), seg(2, 0))
      if (ngroup > 0) then
         call c_f_pointer(p_dimtags, dimtags, [n_dimtags])
      end if
      nseg = 0
      do g = 1, ngroup
         gstart(g) = nseg + 1
         call physical_name(1_c_int, dimtags(2*g), name, ierr)
         if (ierr /= 0) exit
         names(g) = name
         call gmshModelGetEntitiesForPhysicalGroup(1_c_int, dimtags(2*g), p_ents, n_ents, ierr)
         if (ierr /= 0) exit
         call c_f_pointer(p_ents, ents, [n_ents])
         do i = 1, int(n_ents)
            call curve_edges(ents(i), seg, nseg, local, stat, errmsg)
            if (stat /= 0) then
               errmsg = "mesh:file = '"//path//"': physical curve '"//trim(names(g))//"' "//errmsg
               call gmshFree(p_ents)
               call gmshFree(p_dimtags)
               return
            end if
            stat = 1
         end do
         call gmshFree(p_ents)
      end do
      if (c_associated(p_dimtags)) call gmshFree(p_dimtags)
      if (ierr /= 0) then
         errmsg = "mesh:file = '"//path//"': Gmsh cannot read a physical group"//last_error()
         return
      end if
      gstart(ngroup + 1) = nseg + 1
      stat = 0
   end subroutine collect_groups

   !> The physical surfaces: each becomes a named group of elements (its name, or its tag when it
   !> has none), as indices into the quadrilaterals of collect_quads (elem_id: their Gmsh tags);
   !> surface s is selem(sstart(s):sstart(s+1)-1). An element of two surfaces is listed in both
   !> (the model refuses it when both are bodies).
   subroutine collect_surfaces(path, elem_id, names, sstart, selem, stat, errmsg)
      character(len=*), intent(in) :: path
      integer, intent(in) :: elem_id(:)
      character(len=64), allocatable, intent(out) :: names(:)
      integer, allocatable, intent(out) :: sstart(:), selem(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(c_ptr) :: p_dimtags, p_ents, p_etags, p_enodes
      integer(c_size_t) :: n_dimtags, n_ents, n_etags, n_enodes
      integer(c_int) :: ierr
      integer(c_int), pointer :: dimtags(:), ents(:)
      integer(c_size_t), pointer :: etags(:)
      integer, allocatable :: index_of(:), add(:)
      integer :: i, j, g, ngroup, n, m, tag
      character(len=:), allocatable :: name

      stat = 1
      ! Gmsh element tag -> element index (the tags of the quadrilaterals, positive)
      allocate (index_of(0:max(0, maxval(elem_id))))
      index_of = 0
      do i = 1, size(elem_id)
         index_of(elem_id(i)) = i
      end do
      call gmshModelGetPhysicalGroups(p_dimtags, n_dimtags, 2_c_int, ierr)
      if (ierr /= 0) then
         errmsg = "mesh:file = '"//path//"': Gmsh cannot list its physical surfaces"//last_error()
         return
      end if
      ngroup = int(n_dimtags)/2
      allocate (names(ngroup), sstart(ngroup + 1), selem(0))
      if (ngroup > 0) call c_f_pointer(p_dimtags, dimtags, [n_dimtags])
      n = 0
      do g = 1, ngroup
         sstart(g) = n + 1
         call physical_name(2_c_int, dimtags(2*g), name, ierr)
         if (ierr /= 0) exit
         names(g) = name
         call gmshModelGetEntitiesForPhysicalGroup(2_c_int, dimtags(2*g), p_ents, n_ents, ierr)
         if (ierr /= 0) exit
         call c_f_pointer(p_ents, ents, [n_ents])
         do i = 1, int(n_ents)
            call gmshModelMeshGetElementsByType(type_quad4, p_etags, n_etags, p_enodes, n_enodes, ents(i), &
                                                0_c_size_t, 1_c_size_t, ierr)
            if (ierr /= 0) exit
            call c_f_pointer(p_etags, etags, [n_etags])
            allocate (add(n_etags))
            m = 0
            do j = 1, int(n_etags)
               tag = int(etags(j))
               if (tag < 1 .or. tag > ubound(index_of, 1)) cycle
               if (index_of(tag) == 0) cycle
               m = m + 1
               add(m) = index_of(tag)
            end do
            selem = [selem, add(1:m)]   ! one reallocation per surface entity
            n = n + m
            deallocate (add)
            call gmshFree(p_etags)
            call gmshFree(p_enodes)
         end do
         call gmshFree(p_ents)
         if (ierr /= 0) exit
      end do
      if (c_associated(p_dimtags)) call gmshFree(p_dimtags)
      if (ierr /= 0) then
         errmsg = "mesh:file = '"//path//"': Gmsh cannot read a physical surface"//last_error()
         return
      end if
      sstart(ngroup + 1) = n + 1
      stat = 0
      errmsg = ''
   end subroutine collect_surfaces

   !> Append the 2-node line elements of curve `tag` to seg.
   subroutine curve_edges(tag, seg, nseg, local, stat, errmsg)
      integer(c_int), intent(in) :: tag
      integer, allocatable, intent(inout) :: seg(:, :)
      integer, intent(inout) :: nseg
      integer, intent(in) :: local(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      type(c_ptr) :: p_types, p_etags, p_enodes
      integer(c_size_t) :: n_types, n_etags, n_enodes
      integer(c_int), pointer :: types(:)
      integer(c_size_t), pointer :: enodes(:)
      integer(c_int) :: ierr
      integer, allocatable :: tmp(:, :)
      integer :: i, n, a, b

      stat = 1
      call gmshModelMeshGetElementTypes(p_types, n_types, 1_c_int, tag, ierr)
      if (ierr /= 0) then
         errmsg = 'cannot be read'//last_error()
         return
      end if
      call c_f_pointer(p_types, types, [n_types])
      do i = 1, int(n_types)
         if (types(i) /= type_line2) then
            errmsg = 'holds '//type_name(types(i))//' elements; only 2-node lines (first-order meshes) are taken'
            call gmshFree(p_types)
            return
         end if
      end do
      call gmshFree(p_types)
      if (n_types == 0) then
         stat = 0
         return
      end if
      call gmshModelMeshGetElementsByType(type_line2, p_etags, n_etags, p_enodes, n_enodes, tag, &
                                          0_c_size_t, 1_c_size_t, ierr)
      if (ierr /= 0) then
         errmsg = 'cannot be read'//last_error()
         return
      end if
      call c_f_pointer(p_enodes, enodes, [n_enodes])
      n = int(n_etags)
      if (nseg + n > size(seg, 2)) then
         allocate (tmp(2, max(2*size(seg, 2), nseg + n)))
         tmp(:, 1:nseg) = seg(:, 1:nseg)
         call move_alloc(tmp, seg)
      end if
      do i = 1, n
         a = int(enodes(2*i - 1))
         b = int(enodes(2*i))
         if (a > size(local) .or. b > size(local)) then
            errmsg = 'has an edge whose nodes belong to no quadrilateral'
            call gmshFree(p_etags)
            call gmshFree(p_enodes)
            return
         end if
         if (local(a) == 0 .or. local(b) == 0) then
            errmsg = 'has an edge whose nodes belong to no quadrilateral'
            call gmshFree(p_etags)
            call gmshFree(p_enodes)
            return
         end if
         nseg = nseg + 1
         seg(:, nseg) = [local(a), local(b)]
      end do
      call gmshFree(p_etags)
      call gmshFree(p_enodes)
      stat = 0
      errmsg = ''
   end subroutine curve_edges

   !> Gmsh's name of an element type, e.g. 'Triangle 3' (the type number if Gmsh does not say).
   !> The name of physical group `tag` of dimension `dim` (unnamed: its tag as text).
   subroutine physical_name(dim, tag, name, ierr)
      integer(c_int), intent(in) :: dim, tag
      character(len=:), allocatable, intent(out) :: name
      integer(c_int), intent(out) :: ierr
      type(c_ptr) :: p_name
      call gmshModelGetPhysicalName(dim, tag, p_name, ierr)
      if (ierr /= 0) return
      name = c_string(p_name)
      call gmshFree(p_name)
      if (len(name) == 0) name = str(int(tag))
   end subroutine physical_name

   function type_name(etype) result(name)
      integer(c_int), intent(in) :: etype
      character(len=:), allocatable :: name
      type(c_ptr) :: p_name, p_local
      integer(c_int) :: dim, order, nn, npn, ierr
      integer(c_size_t) :: n_local
      call gmshModelMeshGetElementProperties(etype, p_name, dim, order, nn, p_local, n_local, npn, ierr)
      if (ierr /= 0) then
         name = 'type-'//str(int(etype))
         return
      end if
      name = "'"//c_string(p_name)//"' (Gmsh type "//str(int(etype))//')'
      call gmshFree(p_name)
      if (c_associated(p_local)) call gmshFree(p_local)
   end function type_name


   pure logical function ends_with(s, tail)
      character(len=*), intent(in) :: s, tail
      integer :: n
      n = len_trim(s)
      ends_with = .false.
      if (n >= len(tail)) ends_with = s(n - len(tail) + 1:n) == tail
   end function ends_with
end module contact2d_gmsh
