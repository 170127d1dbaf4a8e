!> Thin HDF5 wrapper: one file handle with a sticky error state, attributes with units,
!> whole datasets, and extendible chunked 1D series flushed as a run goes (STYLE: HDF5).
!>
!> Every hdferr is checked. The first failure is kept in the handle (stat, errmsg) and later
!> calls on that handle do nothing, so a caller writes a batch and checks `ok()` once.
module contact2d_h5
   use contact2d_sys, only: sys_h5_reason, sys_h5_register, sys_h5_claim_failed
   use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_char, c_null_char, c_int64_t
   use contact2d_kinds, only: wp
   use hdf5, only: hid_t, hsize_t, h5open_f, h5fcreate_f, h5fclose_f, h5fflush_f, &
                   h5gcreate_f, h5gclose_f, h5screate_f, h5screate_simple_f, h5sclose_f, &
                   h5acreate_f, h5awrite_f, h5aclose_f, h5dcreate_f, h5dwrite_f, h5dclose_f, &
                   h5pcreate_f, h5pset_chunk_f, h5pclose_f, h5dset_extent_f, h5dget_space_f, &
                   h5sselect_hyperslab_f, h5tcopy_f, h5tset_cset_f, h5tclose_f, h5eset_auto_f, h5aexists_f, h5adelete_f, &
                   H5F_ACC_TRUNC_F, H5F_ACC_EXCL_F, H5S_SCALAR_F, H5T_NATIVE_DOUBLE, &
                   H5T_NATIVE_INTEGER, H5T_STRING, H5T_CSET_UTF8_F, H5P_DATASET_CREATE_F, &
                   H5S_UNLIMITED_F, H5S_SELECT_SET_F, H5F_SCOPE_GLOBAL_F
   implicit none
   private
   public :: h5file_t, h5series_t

   !> An open HDF5 file with a sticky error state.
   type :: h5file_t
      integer(hid_t) :: id = -1
      integer :: stat = 0
      character(len=:), allocatable :: errmsg
      character(len=:), allocatable :: path
   contains
      procedure :: create => h5file_create
      procedure :: close => h5file_close
      procedure :: flush => h5file_flush
      procedure :: ok => h5file_ok
      procedure :: group => h5file_group
      procedure :: close_group => h5file_close_group
      procedure, private :: attr_real, attr_real1, attr_int, attr_str
      generic :: attr => attr_real, attr_real1, attr_int, attr_str
      procedure, private :: dset_real1, dset_real2, dset_int1, dset_int2
      generic :: dataset => dset_real1, dset_real2, dset_int1, dset_int2
      procedure :: fail => h5file_fail
   end type h5file_t

   !> An extendible, chunked 1D dataset of reals, appended to in blocks.
   type :: h5series_t
      integer(hid_t) :: id = -1
      integer(hsize_t) :: length = 0
   contains
      procedure :: create => series_create
      procedure :: append => series_append
      procedure :: close => series_close
   end type h5series_t

   logical, save :: library_open = .false.

contains

   !> Record the first failure.
   subroutine h5file_fail(this, hdferr, what)
      class(h5file_t), intent(inout) :: this
      integer, intent(in) :: hdferr
      character(len=*), intent(in) :: what
      character(len=:), allocatable :: reason
      if (hdferr >= 0 .or. this%stat /= 0) return
      this%stat = 1
      ! the system's reason (e.g. 'No space left on device') from HDF5's error stack
      reason = sys_h5_reason()
      this%errmsg = 'HDF5 error in '//what//' ('//this%path//')'
      if (len(reason) > 0) this%errmsg = this%errmsg//': '//reason
   end subroutine h5file_fail

   !> True while no HDF5 call has failed on this file.
   logical function h5file_ok(this)
      class(h5file_t), intent(in) :: this
      h5file_ok = this%stat == 0
   end function h5file_ok

   !> Create a file; with overwrite false an existing file is an error (O_EXCL: a link there is
   !> not followed either) and the new file is registered as this process's own (contact2d_sys:
   !> only such files are ever moved into place or removed).
   subroutine h5file_create(this, path, overwrite)
      class(h5file_t), intent(inout) :: this
      character(len=*), intent(in) :: path
      logical, intent(in) :: overwrite
      integer :: hdferr, ios
      this%path = path
      this%stat = 0
      this%errmsg = ''
      if (.not. library_open) then
         call h5open_f(hdferr)
         call this%fail(hdferr, 'h5open')
         if (this%stat /= 0) return
         ! our own messages replace HDF5's error-stack dump
         call h5eset_auto_f(0, hdferr)
         library_open = .true.
      end if
      if (overwrite) then
         call h5fcreate_f(path, H5F_ACC_TRUNC_F, this%id, hdferr)
      else
         call h5fcreate_f(path, H5F_ACC_EXCL_F, this%id, hdferr)
         if (hdferr >= 0) then
            if (sys_h5_register(int(this%id, c_int64_t)) /= 0) hdferr = -1
         else
            ! a create that failed after its exclusive open (a full disk) leaves an empty file:
            ! ours to remove, unless the name was taken (EEXIST)
            ios = sys_h5_claim_failed(path)
         end if
      end if
      call this%fail(hdferr, 'creating the file')
   end subroutine h5file_create

   !> Flush everything written so far to disk (a crash afterwards leaves a readable file).
   subroutine h5file_flush(this)
      class(h5file_t), intent(inout) :: this
      integer :: hdferr
      if (this%stat /= 0) return
      call h5fflush_f(this%id, H5F_SCOPE_GLOBAL_F, hdferr)
      call this%fail(hdferr, 'flush')
   end subroutine h5file_flush

   subroutine h5file_close(this)
      class(h5file_t), intent(inout) :: this
      integer :: hdferr
      if (this%id < 0) return
      call h5fclose_f(this%id, hdferr)
      call this%fail(hdferr, 'closing the file')
      this%id = -1
   end subroutine h5file_close

   !> Create a group (path relative to loc, or absolute); returns its id.
   integer(hid_t) function h5file_group(this, loc, name) result(gid)
      class(h5file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer :: hdferr
      gid = -1
      if (this%stat /= 0) return
      call h5gcreate_f(loc, name, gid, hdferr)
      call this%fail(hdferr, 'creating group '//name)
   end function h5file_group

   subroutine h5file_close_group(this, gid)
      class(h5file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: gid
      integer :: hdferr
      if (gid < 0) return
      call h5gclose_f(gid, hdferr)
      call this%fail(hdferr, 'closing a group')
   end subroutine h5file_close_group

   ! ---- attributes (an existing attribute of the same name is replaced) ----------------------

   subroutine drop_existing(this, loc, name)
      class(h5file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      logical :: exists
      integer :: hdferr
      call h5aexists_f(loc, name, exists, hdferr); call this%fail(hdferr, 'attribute '//name)
      if (exists .and. hdferr >= 0) then
         call h5adelete_f(loc, name, hdferr); call this%fail(hdferr, 'attribute '//name)
      end if
   end subroutine drop_existing

   subroutine attr_real(this, loc, name, value)
      class(h5file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: value
      integer(hid_t) :: sp, at
      integer :: hdferr
      if (this%stat /= 0) return
      call h5screate_f(H5S_SCALAR_F, sp, hdferr); call this%fail(hdferr, 'attribute '//name)
      call drop_existing(this, loc, name)
      call h5acreate_f(loc, name, H5T_NATIVE_DOUBLE, sp, at, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5awrite_f(at, H5T_NATIVE_DOUBLE, value, [1_hsize_t], hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5aclose_f(at, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5sclose_f(sp, hdferr); call this%fail(hdferr, 'attribute '//name)
   end subroutine attr_real

   !> A 1D real attribute (h5py reads it as an array).
   subroutine attr_real1(this, loc, name, value)
      class(h5file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: value(:)
      integer(hsize_t) :: dims(1)
      integer(hid_t) :: sp, at
      integer :: hdferr
      if (this%stat /= 0) return
      dims = shape(value, kind=hsize_t)
      call h5screate_simple_f(1, dims, sp, hdferr); call this%fail(hdferr, 'attribute '//name)
      call drop_existing(this, loc, name)
      call h5acreate_f(loc, name, H5T_NATIVE_DOUBLE, sp, at, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5awrite_f(at, H5T_NATIVE_DOUBLE, value, dims, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5aclose_f(at, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5sclose_f(sp, hdferr); call this%fail(hdferr, 'attribute '//name)
   end subroutine attr_real1

   subroutine attr_int(this, loc, name, value)
      class(h5file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer, intent(in) :: value
      integer(hid_t) :: sp, at
      integer :: hdferr
      if (this%stat /= 0) return
      call h5screate_f(H5S_SCALAR_F, sp, hdferr); call this%fail(hdferr, 'attribute '//name)
      call drop_existing(this, loc, name)
      call h5acreate_f(loc, name, H5T_NATIVE_INTEGER, sp, at, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5awrite_f(at, H5T_NATIVE_INTEGER, value, [1_hsize_t], hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5aclose_f(at, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5sclose_f(sp, hdferr); call this%fail(hdferr, 'attribute '//name)
   end subroutine attr_int

   !> A variable-length UTF-8 string attribute (h5py reads it as str).
   subroutine attr_str(this, loc, name, value)
      class(h5file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      character(len=*), intent(in) :: value
      character(len=:, kind=c_char), allocatable, target :: cstr
      type(c_ptr), target :: ptr(1)
      integer(hid_t) :: sp, at, ty
      integer :: hdferr
      if (this%stat /= 0) return
      cstr = value//c_null_char
      ptr(1) = c_loc(cstr)
      call h5screate_f(H5S_SCALAR_F, sp, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5tcopy_f(H5T_STRING, ty, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5tset_cset_f(ty, H5T_CSET_UTF8_F, hdferr); call this%fail(hdferr, 'attribute '//name)
      call drop_existing(this, loc, name)
      call h5acreate_f(loc, name, ty, sp, at, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5awrite_f(at, ty, c_loc(ptr), hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5aclose_f(at, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5tclose_f(ty, hdferr); call this%fail(hdferr, 'attribute '//name)
      call h5sclose_f(sp, hdferr); call this%fail(hdferr, 'attribute '//name)
   end subroutine attr_str

   ! ---- whole datasets ----------------------------------------------------------------------
   ! Fortran (a, b) arrays appear in h5py as (b, a): u(2, nnode) is read as (nnode, 2).

   subroutine dset_real1(this, loc, name, a, units)
      class(h5file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: a(:)
      character(len=*), intent(in) :: units  !< stored as the attribute 'units'
      integer(hsize_t) :: dims(1)
      integer(hid_t) :: sp, ds
      integer :: hdferr
      if (this%stat /= 0) return
      dims = shape(a, kind=hsize_t)
      call h5screate_simple_f(1, dims, sp, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5dcreate_f(loc, name, H5T_NATIVE_DOUBLE, sp, ds, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5dwrite_f(ds, H5T_NATIVE_DOUBLE, a, dims, hdferr); call this%fail(hdferr, 'dataset '//name)
      call this%attr(ds, 'units', units)
      call h5dclose_f(ds, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5sclose_f(sp, hdferr); call this%fail(hdferr, 'dataset '//name)
   end subroutine dset_real1

   subroutine dset_real2(this, loc, name, a, units)
      class(h5file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: a(:, :)
      character(len=*), intent(in) :: units
      integer(hsize_t) :: dims(2)
      integer(hid_t) :: sp, ds
      integer :: hdferr
      if (this%stat /= 0) return
      dims = shape(a, kind=hsize_t)
      call h5screate_simple_f(2, dims, sp, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5dcreate_f(loc, name, H5T_NATIVE_DOUBLE, sp, ds, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5dwrite_f(ds, H5T_NATIVE_DOUBLE, a, dims, hdferr); call this%fail(hdferr, 'dataset '//name)
      call this%attr(ds, 'units', units)
      call h5dclose_f(ds, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5sclose_f(sp, hdferr); call this%fail(hdferr, 'dataset '//name)
   end subroutine dset_real2

   subroutine dset_int1(this, loc, name, a, units)
      class(h5file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer, intent(in) :: a(:)
      character(len=*), intent(in) :: units
      integer(hsize_t) :: dims(1)
      integer(hid_t) :: sp, ds
      integer :: hdferr
      if (this%stat /= 0) return
      dims = shape(a, kind=hsize_t)
      call h5screate_simple_f(1, dims, sp, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5dcreate_f(loc, name, H5T_NATIVE_INTEGER, sp, ds, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5dwrite_f(ds, H5T_NATIVE_INTEGER, a, dims, hdferr); call this%fail(hdferr, 'dataset '//name)
      call this%attr(ds, 'units', units)
      call h5dclose_f(ds, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5sclose_f(sp, hdferr); call this%fail(hdferr, 'dataset '//name)
   end subroutine dset_int1

   subroutine dset_int2(this, loc, name, a, units)
      class(h5file_t), intent(inout) :: this
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      integer, intent(in) :: a(:, :)
      character(len=*), intent(in) :: units
      integer(hsize_t) :: dims(2)
      integer(hid_t) :: sp, ds
      integer :: hdferr
      if (this%stat /= 0) return
      dims = shape(a, kind=hsize_t)
      call h5screate_simple_f(2, dims, sp, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5dcreate_f(loc, name, H5T_NATIVE_INTEGER, sp, ds, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5dwrite_f(ds, H5T_NATIVE_INTEGER, a, dims, hdferr); call this%fail(hdferr, 'dataset '//name)
      call this%attr(ds, 'units', units)
      call h5dclose_f(ds, hdferr); call this%fail(hdferr, 'dataset '//name)
      call h5sclose_f(sp, hdferr); call this%fail(hdferr, 'dataset '//name)
   end subroutine dset_int2

   ! ---- extendible series -------------------------------------------------------------------

   !> Create an empty, unlimited, chunked 1D dataset of reals with a 'units' attribute.
   subroutine series_create(this, file, loc, name, units, chunk)
      class(h5series_t), intent(inout) :: this
      type(h5file_t), intent(inout) :: file
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name, units
      integer, intent(in) :: chunk
      integer(hid_t) :: sp, pl
      integer :: hdferr
      if (file%stat /= 0) return
      this%length = 0
      call h5screate_simple_f(1, [0_hsize_t], sp, hdferr, [H5S_UNLIMITED_F])
      call file%fail(hdferr, 'series '//name)
      call h5pcreate_f(H5P_DATASET_CREATE_F, pl, hdferr); call file%fail(hdferr, 'series '//name)
      call h5pset_chunk_f(pl, 1, [int(chunk, hsize_t)], hdferr); call file%fail(hdferr, 'series '//name)
      call h5dcreate_f(loc, name, H5T_NATIVE_DOUBLE, sp, this%id, hdferr, pl)
      call file%fail(hdferr, 'series '//name)
      call file%attr(this%id, 'units', units)
      call h5pclose_f(pl, hdferr); call file%fail(hdferr, 'series '//name)
      call h5sclose_f(sp, hdferr); call file%fail(hdferr, 'series '//name)
   end subroutine series_create

   !> Append values at the end of the series.
   subroutine series_append(this, file, values)
      class(h5series_t), intent(inout) :: this
      type(h5file_t), intent(inout) :: file
      real(wp), intent(in) :: values(:)
      integer(hid_t) :: fsp, msp
      integer(hsize_t) :: n(1)
      integer :: hdferr
      if (file%stat /= 0 .or. size(values) == 0) return
      n = size(values, kind=hsize_t)
      call h5dset_extent_f(this%id, [this%length + n(1)], hdferr); call file%fail(hdferr, 'extending a series')
      call h5dget_space_f(this%id, fsp, hdferr); call file%fail(hdferr, 'extending a series')
      call h5sselect_hyperslab_f(fsp, H5S_SELECT_SET_F, [this%length], n, hdferr)
      call file%fail(hdferr, 'extending a series')
      call h5screate_simple_f(1, n, msp, hdferr); call file%fail(hdferr, 'extending a series')
      call h5dwrite_f(this%id, H5T_NATIVE_DOUBLE, values, n, hdferr, msp, fsp)
      call file%fail(hdferr, 'writing a series')
      call h5sclose_f(msp, hdferr); call file%fail(hdferr, 'extending a series')
      call h5sclose_f(fsp, hdferr); call file%fail(hdferr, 'extending a series')
      this%length = this%length + n(1)
   end subroutine series_append

   subroutine series_close(this, file)
      class(h5series_t), intent(inout) :: this
      type(h5file_t), intent(inout) :: file
      integer :: hdferr
      if (this%id < 0) return
      call h5dclose_f(this%id, hdferr)
      call file%fail(hdferr, 'closing a series')
      this%id = -1
   end subroutine series_close
end module contact2d_h5
