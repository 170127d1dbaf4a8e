!> The Gmsh C API (gmshc.h of Gmsh 4.8.4) bound with iso_c_binding: the functions contact2d uses,
!> as procedure pointers bound when the library is loaded at run time (dlopen), and the C-string
!> helpers. Only contact2d_gmsh uses it (docs/geometry.md).
module contact2d_gmsh_api
   use, intrinsic :: iso_c_binding, only: c_int, c_size_t, c_double, c_char, c_ptr, c_null_ptr, &
                                          c_null_char, c_f_pointer, c_associated, c_funptr, &
                                          c_f_procpointer, c_long_long
   use contact2d_gmsh_config, only: gmsh_library_path
   implicit none
   private
   public :: load_gmsh, last_error, c_string, cstr
   public :: c2d_gmsh_guard_begin, c2d_gmsh_guard_end, c2d_gmsh_guard_lines
   public :: gmshInitialize, gmshFinalize, gmshOpen, gmshOptionSetNumber, gmshOptionGetNumber, &
             gmshModelMeshGenerate, gmshModelMeshRefine, gmshModelMeshGetNodes, &
             gmshModelMeshGetElementTypes, gmshModelMeshGetElementsByType, &
             gmshModelMeshGetElementProperties, gmshModelGetPhysicalGroups, &
             gmshModelGetEntitiesForPhysicalGroup, gmshModelGetPhysicalName, &
             gmshLoggerGetLastError, gmshFree

   !> The Gmsh C API functions used here (gmshc.h of Gmsh 4.8.4), as abstract interfaces: the
   !> library is loaded at run time (dlopen) only when a deck names a Gmsh file, so that runs
   !> on the built-in mesh do not pay for loading libgmsh and its dependencies.
   abstract interface
      subroutine gmshInitialize_i(argc, argv, readConfigFiles, ierr) bind(C)
         import :: c_int, c_ptr
         integer(c_int), value :: argc
         type(c_ptr), value :: argv
         integer(c_int), value :: readConfigFiles
         integer(c_int), intent(out) :: ierr
      end subroutine gmshInitialize_i
      subroutine gmshFinalize_i(ierr) bind(C)
         import :: c_int
         integer(c_int), intent(out) :: ierr
      end subroutine gmshFinalize_i
      subroutine gmshOpen_i(fileName, ierr) bind(C)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: fileName(*)
         integer(c_int), intent(out) :: ierr
      end subroutine gmshOpen_i
      subroutine gmshOptionSetNumber_i(name, value, ierr) bind(C)
         import :: c_int, c_char, c_double
         character(kind=c_char), intent(in) :: name(*)
         real(c_double), value :: value
         integer(c_int), intent(out) :: ierr
      end subroutine gmshOptionSetNumber_i
      subroutine gmshOptionGetNumber_i(name, value, ierr) bind(C)
         import :: c_int, c_char, c_double
         character(kind=c_char), intent(in) :: name(*)
         real(c_double), intent(out) :: value
         integer(c_int), intent(out) :: ierr
      end subroutine gmshOptionGetNumber_i
      subroutine gmshModelMeshGenerate_i(dim, ierr) bind(C)
         import :: c_int
         integer(c_int), value :: dim
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGenerate_i
      subroutine gmshModelMeshRefine_i(ierr) bind(C)
         import :: c_int
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshRefine_i
      subroutine gmshModelMeshGetNodes_i(nodeTags, nodeTags_n, coord, coord_n, pcoord, pcoord_n, dim, tag, &
                                       includeBoundary, returnParametricCoord, ierr) bind(C)
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: nodeTags, coord, pcoord
         integer(c_size_t), intent(out) :: nodeTags_n, coord_n, pcoord_n
         integer(c_int), value :: dim, tag, includeBoundary, returnParametricCoord
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetNodes_i
      subroutine gmshModelMeshGetElementTypes_i(elementTypes, elementTypes_n, dim, tag, ierr) &
         bind(C)
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: elementTypes
         integer(c_size_t), intent(out) :: elementTypes_n
         integer(c_int), value :: dim, tag
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetElementTypes_i
      subroutine gmshModelMeshGetElementsByType_i(elementType, elementTags, elementTags_n, nodeTags, nodeTags_n, &
                                                tag, task, numTasks, ierr) bind(C)
         import :: c_int, c_ptr, c_size_t
         integer(c_int), value :: elementType
         type(c_ptr), intent(out) :: elementTags, nodeTags
         integer(c_size_t), intent(out) :: elementTags_n, nodeTags_n
         integer(c_int), value :: tag
         integer(c_size_t), value :: task, numTasks
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetElementsByType_i
      subroutine gmshModelMeshGetElementProperties_i(elementType, elementName, dim, order, numNodes, &
                                                   localNodeCoord, localNodeCoord_n, numPrimaryNodes, ierr) &
         bind(C)
         import :: c_int, c_ptr, c_size_t
         integer(c_int), value :: elementType
         type(c_ptr), intent(out) :: elementName
         integer(c_int), intent(out) :: dim, order, numNodes
         type(c_ptr), intent(out) :: localNodeCoord
         integer(c_size_t), intent(out) :: localNodeCoord_n
         integer(c_int), intent(out) :: numPrimaryNodes
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelMeshGetElementProperties_i
      subroutine gmshModelGetPhysicalGroups_i(dimTags, dimTags_n, dim, ierr) bind(C)
         import :: c_int, c_ptr, c_size_t
         type(c_ptr), intent(out) :: dimTags
         integer(c_size_t), intent(out) :: dimTags_n
         integer(c_int), value :: dim
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetPhysicalGroups_i
      subroutine gmshModelGetEntitiesForPhysicalGroup_i(dim, tag, tags, tags_n, ierr) &
         bind(C)
         import :: c_int, c_ptr, c_size_t
         integer(c_int), value :: dim, tag
         type(c_ptr), intent(out) :: tags
         integer(c_size_t), intent(out) :: tags_n
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetEntitiesForPhysicalGroup_i
      subroutine gmshModelGetPhysicalName_i(dim, tag, name, ierr) bind(C)
         import :: c_int, c_ptr
         integer(c_int), value :: dim, tag
         type(c_ptr), intent(out) :: name
         integer(c_int), intent(out) :: ierr
      end subroutine gmshModelGetPhysicalName_i
      subroutine gmshLoggerGetLastError_i(error, ierr) bind(C)
         import :: c_int, c_ptr
         type(c_ptr), intent(out) :: error
         integer(c_int), intent(out) :: ierr
      end subroutine gmshLoggerGetLastError_i
      subroutine gmshFree_i(p) bind(C)
         import :: c_ptr
         type(c_ptr), value :: p
      end subroutine gmshFree_i
   end interface

   !> Symbols of the loaded library (set once by load_gmsh; the library stays loaded).
   procedure(gmshInitialize_i), pointer :: gmshInitialize => null()
   procedure(gmshFinalize_i), pointer :: gmshFinalize => null()
   procedure(gmshOpen_i), pointer :: gmshOpen => null()
   procedure(gmshOptionSetNumber_i), pointer :: gmshOptionSetNumber => null()
   procedure(gmshOptionGetNumber_i), pointer :: gmshOptionGetNumber => null()
   procedure(gmshModelMeshGenerate_i), pointer :: gmshModelMeshGenerate => null()
   procedure(gmshModelMeshRefine_i), pointer :: gmshModelMeshRefine => null()
   procedure(gmshModelMeshGetNodes_i), pointer :: gmshModelMeshGetNodes => null()
   procedure(gmshModelMeshGetElementTypes_i), pointer :: gmshModelMeshGetElementTypes => null()
   procedure(gmshModelMeshGetElementsByType_i), pointer :: gmshModelMeshGetElementsByType => null()
   procedure(gmshModelMeshGetElementProperties_i), pointer :: gmshModelMeshGetElementProperties => null()
   procedure(gmshModelGetPhysicalGroups_i), pointer :: gmshModelGetPhysicalGroups => null()
   procedure(gmshModelGetEntitiesForPhysicalGroup_i), pointer :: gmshModelGetEntitiesForPhysicalGroup => null()
   procedure(gmshModelGetPhysicalName_i), pointer :: gmshModelGetPhysicalName => null()
   procedure(gmshLoggerGetLastError_i), pointer :: gmshLoggerGetLastError => null()
   procedure(gmshFree_i), pointer :: gmshFree => null()

   interface
      function c_dlopen(filename, flag) bind(C, name='dlopen') result(handle)
         import :: c_ptr, c_char, c_int
         character(kind=c_char), intent(in) :: filename(*)
         integer(c_int), value :: flag
         type(c_ptr) :: handle
      end function c_dlopen
      function c_dlsym(handle, symbol) bind(C, name='dlsym') result(fun)
         import :: c_ptr, c_char, c_funptr
         type(c_ptr), value :: handle
         character(kind=c_char), intent(in) :: symbol(*)
         type(c_funptr) :: fun
      end function c_dlsym
      function c_dlerror() bind(C, name='dlerror') result(msg)
         import :: c_ptr
         type(c_ptr) :: msg
      end function c_dlerror
      !> the guard around Gmsh's calls (contact2d_gmsh_guard.c)
      subroutine c2d_gmsh_guard_begin() bind(C, name='c2d_gmsh_guard_begin')
      end subroutine c2d_gmsh_guard_begin
      subroutine c2d_gmsh_guard_end() bind(C, name='c2d_gmsh_guard_end')
      end subroutine c2d_gmsh_guard_end
      subroutine c2d_gmsh_guard_lines(crash, crash_n, quit, quit_n) bind(C, name='c2d_gmsh_guard_lines')
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: crash(*), quit(*)
         integer(c_int), value :: crash_n, quit_n
      end subroutine c2d_gmsh_guard_lines
      function c_strlen(s) bind(C, name='strlen') result(n)
         import :: c_ptr, c_size_t
         type(c_ptr), value :: s
         integer(c_size_t) :: n
      end function c_strlen
   end interface

   !> RTLD_NOW | RTLD_GLOBAL (glibc values)
   integer(c_int), parameter :: rtld_flags = int(z'102', c_int)
   !> library names tried in turn: the one CMake found, then its usual sonames
   character(len=*), parameter :: library_names(3) = [character(len=256) :: gmsh_library_path, &
                                                      'libgmsh.so.4.8', 'libgmsh.so']
   type(c_ptr), save :: handle = c_null_ptr

contains

   !> Load libgmsh and its symbols once (dlopen/dlsym). stat /= 0 with a message if it is missing.
   subroutine load_gmsh(stat, errmsg)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      integer :: k
      type(c_funptr) :: fun
      stat = 0
      errmsg = ''
      if (c_associated(handle)) return
      do k = 1, size(library_names)
         handle = c_dlopen(cstr(trim(library_names(k))), rtld_flags)
         if (c_associated(handle)) exit
      end do
      stat = 1
      if (.not. c_associated(handle)) then
         errmsg = "mesh:file needs Gmsh's library, which cannot be loaded ("//c_string(c_dlerror())// &
                  '); install libgmsh-dev (Debian: apt-get install libgmsh-dev)'
         return
      end if
      call bind_symbol('gmshInitialize')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshInitialize)
      call bind_symbol('gmshFinalize')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshFinalize)
      call bind_symbol('gmshOpen')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshOpen)
      call bind_symbol('gmshOptionSetNumber')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshOptionSetNumber)
      call bind_symbol('gmshOptionGetNumber')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshOptionGetNumber)
      call bind_symbol('gmshModelMeshGenerate')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshModelMeshGenerate)
      call bind_symbol('gmshModelMeshRefine')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshModelMeshRefine)
      call bind_symbol('gmshModelMeshGetNodes')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshModelMeshGetNodes)
      call bind_symbol('gmshModelMeshGetElementTypes')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshModelMeshGetElementTypes)
      call bind_symbol('gmshModelMeshGetElementsByType')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshModelMeshGetElementsByType)
      call bind_symbol('gmshModelMeshGetElementProperties')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshModelMeshGetElementProperties)
      call bind_symbol('gmshModelGetPhysicalGroups')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshModelGetPhysicalGroups)
      call bind_symbol('gmshModelGetEntitiesForPhysicalGroup')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshModelGetEntitiesForPhysicalGroup)
      call bind_symbol('gmshModelGetPhysicalName')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshModelGetPhysicalName)
      call bind_symbol('gmshLoggerGetLastError')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshLoggerGetLastError)
      call bind_symbol('gmshFree')
      if (stat /= 0) return
      call c_f_procpointer(fun, gmshFree)
      stat = 0
   contains
      subroutine bind_symbol(name)
         character(len=*), intent(in) :: name
         fun = c_dlsym(handle, cstr(name))
         if (.not. c_associated(fun)) then
            stat = 1
            errmsg = "Gmsh's library has no symbol "//name//' (an incompatible version?)'
            handle = c_null_ptr
         else
            stat = 0
         end if
      end subroutine bind_symbol
   end subroutine load_gmsh

   !> ': <Gmsh's last error>' or ''.
   function last_error() result(s)
      character(len=:), allocatable :: s
      type(c_ptr) :: p
      integer(c_int) :: ierr
      s = ''
      call gmshLoggerGetLastError(p, ierr)
      if (ierr /= 0) return
      if (.not. c_associated(p)) return
      s = c_string(p)
      call gmshFree(p)
      if (len(s) > 0) s = ' ('//s//')'
   end function last_error

   !> A copy of a NUL-terminated C string.
   function c_string(p) result(s)
      type(c_ptr), intent(in) :: p
      character(len=:), allocatable :: s
      character(kind=c_char), pointer :: chars(:)
      integer :: i, n
      if (.not. c_associated(p)) then
         s = ''
         return
      end if
      n = int(c_strlen(p))
      call c_f_pointer(p, chars, [n])
      allocate (character(len=n) :: s)
      do i = 1, n
         s(i:i) = chars(i)
      end do
   end function c_string

   !> A Fortran string as a NUL-terminated C string.
   pure function cstr(s) result(c)
      character(len=*), intent(in) :: s
      character(kind=c_char, len=1) :: c(len_trim(s) + 1)
      integer :: i
      do i = 1, len_trim(s)
         c(i) = s(i:i)
      end do
      c(len_trim(s) + 1) = c_null_char
   end function cstr
end module contact2d_gmsh_api
