!> Fortran side of the CHOLMOD shim (contact2d_cholmod_shim.c): a sparse SPD matrix factorised
!> once with its last `nlast` dofs eliminated last, solves with it, and the dense factor L22 of
!> the Schur complement on those dofs (docs/static.md).
module contact2d_cholmod
   use, intrinsic :: iso_c_binding, only: c_int, c_long, c_double, c_ptr, c_null_ptr, c_associated, c_loc, &
                                          c_char
   use contact2d_kinds, only: wp
   implicit none
   private
   public :: cholmod_t, dense_lauum, dense_potrf, dense_potrs, dense_gesv, blas_openmp

   !> A factorised matrix.
   type :: cholmod_t
      type(c_ptr) :: handle = c_null_ptr
      integer :: n = 0                 !< order of the matrix
      integer :: nlast = 0             !< trailing dofs eliminated last
      real(wp) :: pivot_ratio = 0      !< min_j L_jj^2 / K_jj
      real(wp) :: lnz = 0              !< nonzeros of L
      real(wp) :: flops = 0            !< floating-point operations of the factorisation
      integer :: blas_threads = 0      !< OpenBLAS threads of the factorisation: the OpenMP team with
                                       !< OpenBLAS's OpenMP build, else 1 (docs/static.md "Threads")
   contains
      procedure :: factor => cholmod_factor
      procedure :: trailing => cholmod_trailing
      procedure :: solve => cholmod_solve
      procedure :: free => cholmod_free
   end type cholmod_t

   interface
      integer(c_int) function c2d_chol_factor(n, nnz, ti, tj, tx, nlast, group, xy, handle, pivot_ratio) &
         bind(c, name='c2d_chol_factor')
         import :: c_int, c_long, c_double, c_ptr
         integer(c_int), value :: n, nlast
         integer(c_long), value :: nnz
         integer(c_int), intent(in) :: ti(*), tj(*), group(*)
         real(c_double), intent(in) :: tx(*)
         type(c_ptr), value :: xy   !< 2 coordinates per dof, or null (METIS)
         type(c_ptr), intent(out) :: handle
         real(c_double), intent(out) :: pivot_ratio
      end function c2d_chol_factor
      integer(c_int) function c2d_chol_trailing(handle, l22, order) bind(c, name='c2d_chol_trailing')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: handle
         real(c_double), intent(out) :: l22(*)
         integer(c_int), intent(out) :: order(*)
      end function c2d_chol_trailing
      integer(c_int) function c2d_chol_solve(handle, b, x) bind(c, name='c2d_chol_solve')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: handle
         real(c_double), intent(in) :: b(*)
         real(c_double), intent(out) :: x(*)
      end function c2d_chol_solve
      real(c_double) function c2d_chol_lnz(handle) bind(c, name='c2d_chol_lnz')
         import :: c_double, c_ptr
         type(c_ptr), value :: handle
      end function c2d_chol_lnz
      real(c_double) function c2d_chol_flops(handle) bind(c, name='c2d_chol_flops')
         import :: c_double, c_ptr
         type(c_ptr), value :: handle
      end function c2d_chol_flops
      integer(c_int) function c2d_chol_blas_threads(handle) bind(c, name='c2d_chol_blas_threads')
         import :: c_int, c_ptr
         type(c_ptr), value :: handle
      end function c2d_chol_blas_threads
      integer(c_int) function c2d_blas_openmp() bind(c, name='c2d_blas_openmp')
         import :: c_int
      end function c2d_blas_openmp
      subroutine c2d_chol_free(handle) bind(c, name='c2d_chol_free')
         import :: c_ptr
         type(c_ptr), intent(inout) :: handle
      end subroutine c2d_chol_free
      ! dense LAPACK, dispatched by the shim (docs/static.md "BLAS")
      subroutine dense_lauum(uplo, n, a, lda, info) bind(c, name='c2d_dlauum')
         import :: c_int, c_double, c_char
         character(kind=c_char), intent(in) :: uplo
         integer(c_int), intent(in) :: n, lda
         real(c_double), intent(inout) :: a(lda, *)
         integer(c_int), intent(out) :: info
      end subroutine dense_lauum
      subroutine dense_potrf(uplo, n, a, lda, info) bind(c, name='c2d_dpotrf')
         import :: c_int, c_double, c_char
         character(kind=c_char), intent(in) :: uplo
         integer(c_int), intent(in) :: n, lda
         real(c_double), intent(inout) :: a(lda, *)
         integer(c_int), intent(out) :: info
      end subroutine dense_potrf
      subroutine dense_potrs(uplo, n, nrhs, a, lda, b, ldb, info) bind(c, name='c2d_dpotrs')
         import :: c_int, c_double, c_char
         character(kind=c_char), intent(in) :: uplo
         integer(c_int), intent(in) :: n, nrhs, lda, ldb
         real(c_double), intent(in) :: a(lda, *)
         real(c_double), intent(inout) :: b(ldb, *)
         integer(c_int), intent(out) :: info
      end subroutine dense_potrs
      subroutine dense_gesv(n, nrhs, a, lda, ipiv, b, ldb, info) bind(c, name='c2d_dgesv')
         import :: c_int, c_double
         integer(c_int), intent(in) :: n, nrhs, lda, ldb
         real(c_double), intent(inout) :: a(lda, *), b(ldb, *)
         integer(c_int), intent(out) :: ipiv(*), info
      end subroutine dense_gesv
   end interface

contains

   !> Factorise the n x n SPD matrix given by triplets (1-based, duplicates summed, either
   !> triangle). group(n): the mesh node of each dof (a node's dofs consecutive), for the
   !> ordering of the leading block: nested dissection by coordinates when xy(2, n) (the
   !> coordinates of each dof's node) is given, else METIS (docs/static.md "Ordering").
   !> stat: 0 ok; 1 CHOLMOD failure; 2 not positive definite.
   subroutine cholmod_factor(this, n, ti, tj, tx, nlast, group, stat, errmsg, xy)
      class(cholmod_t), intent(inout) :: this
      integer, intent(in) :: n, nlast
      integer, intent(in) :: ti(:), tj(:), group(:)
      real(wp), intent(in) :: tx(:)
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(c_double), intent(in), optional, target, contiguous :: xy(:, :)
      integer(c_int), allocatable :: i0(:), j0(:)
      real(c_double) :: ratio
      type(c_ptr) :: pxy
      call this%free()
      allocate (i0(size(ti)), j0(size(tj)))
      i0(:) = int(ti - 1, c_int)
      j0(:) = int(tj - 1, c_int)
      pxy = c_null_ptr
      if (present(xy)) pxy = c_loc(xy)
      stat = c2d_chol_factor(int(n, c_int), int(size(tx), c_long), i0, j0, tx, int(nlast, c_int), &
                             int(group, c_int), pxy, this%handle, ratio)
      errmsg = ''
      select case (stat)
      case (0)
         this%n = n
         this%nlast = nlast
         this%pivot_ratio = ratio
         this%lnz = c2d_chol_lnz(this%handle)
         this%flops = c2d_chol_flops(this%handle)
         this%blas_threads = int(c2d_chol_blas_threads(this%handle))
      case (2)
         errmsg = 'CHOLMOD: the stiffness matrix is not positive definite'
      case default
         errmsg = 'CHOLMOD: the sparse factorisation failed (out of memory or ordering failure)'
      end select
   end subroutine cholmod_factor

   !> The dense lower-triangular factor L22 (nlast x nlast) of the Schur complement on the
   !> trailing dofs in their elimination order: S(order, order) = L22 L22^T, order(k) being the
   !> trailing dof (1-based, within the trailing block) eliminated k-th among them.
   subroutine cholmod_trailing(this, l22, order)
      class(cholmod_t), intent(in) :: this
      real(wp), intent(out) :: l22(:, :)
      integer, intent(out) :: order(:)
      integer(c_int) :: info, ord(size(order))
      info = c2d_chol_trailing(this%handle, l22, ord)
      order = ord + 1
   end subroutine cholmod_trailing

   !> x = K^-1 b. stat /= 0 on failure.
   subroutine cholmod_solve(this, b, x, stat)
      class(cholmod_t), intent(in) :: this
      real(wp), intent(in) :: b(:)
      real(wp), intent(out) :: x(:)
      integer, intent(out) :: stat
      stat = c2d_chol_solve(this%handle, b, x)
   end subroutine cholmod_solve

   !> Whether the BLAS is OpenBLAS's OpenMP build, whose threads (the run's OpenMP team) the
   !> factorisation, solves and dense LAPACK calls get; else they run on one thread
   !> (docs/static.md "Threads").
   logical function blas_openmp()
      blas_openmp = c2d_blas_openmp() /= 0
   end function blas_openmp

   subroutine cholmod_free(this)
      class(cholmod_t), intent(inout) :: this
      if (c_associated(this%handle)) call c2d_chol_free(this%handle)
      this%handle = c_null_ptr
   end subroutine cholmod_free
end module contact2d_cholmod
