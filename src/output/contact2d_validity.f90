!> The validity range of a small-strain linear run, checked once on its end state
!> (docs/output.md, "Validity warnings").
!>
!> contact2d is linear elasticity with small strains and small displacements against the contact
!> geometry of the initial configuration (SPEC sections 2 and 3, docs/geometry.md). A run can
!> leave that range without failing: a load of the wrong sign or a Young's modulus in GPa instead
!> of MPa gives strains of tens of per cent, or sends the body far beyond its own size, and the
!> linear answer is then nonsense that still converges (or merely does not). So the end state is
!> measured after the step loop (never inside it):
!>   - the largest principal strain magnitude |(e_xx + e_yy)/2| + sqrt(((e_xx - e_yy)/2)^2 + e_xy^2)
!>     over the elements, e the element's mean strain (the mean of its 2 x 2 Gauss points, as
!>     /final/stress is the mean stress) of the Q1 field e = sym(grad u); a warning above
!>     strain_limit. The element mean, not the Gauss-point values: at a singular point (the ends
!>     of the paper scene's Gamma_u, a jump of the prescribed displacement) the strain grows
!>     without bound under refinement, and its Gauss-point value at the shipped level 4 is
!>     already 5.1 % (3.4 % as element mean; 5.03 % at level 5, 7.4 % at level 6: the warning
!>     then names that corner);
!>   - the largest displacement max |u_i| against the diagonal of the mesh's bounding box (the
!>     body's own size); a warning when it is larger.
module contact2d_validity
   use, intrinsic :: iso_fortran_env, only: error_unit
   use contact2d_kinds, only: wp
   use contact2d_version, only: program_name
   use contact2d_h5, only: h5file_t
   use contact2d_mesh, only: mesh_t
   use contact2d_q1, only: q1_gradients
   use contact2d_strings, only: sci, fixed, str
   implicit none
   private
   public :: validity_t, strain_limit

   !> Largest strain of the small-strain range: linear kinematics err by about the strain itself
   !> (the Green-Lagrange strain adds (grad u)^T grad u / 2), so 5 % is already a few per cent off.
   real(wp), parameter :: strain_limit = 0.05_wp

   !> What the end state says about the validity range.
   type :: validity_t
      real(wp) :: strain_max = 0           !< largest principal magnitude of an element's mean strain [1]
      real(wp) :: displacement_max = 0     !< largest |u_i| [mm]
      real(wp) :: size = 0                 !< diagonal of the mesh's bounding box [mm]
      real(wp) :: strain_at(2) = 0         !< centre of the element where strain_max is reached [mm]
   contains
      procedure :: measure => validity_measure
      procedure :: strain_warning => validity_strain_warning
      procedure :: displacement_warning => validity_displacement_warning
      procedure :: write => validity_write
      procedure :: report => validity_report
   end type validity_t

contains

   !> Strain and displacement maxima of the displacement u (2, nnode) on mesh.
   subroutine validity_measure(this, mesh, u)
      class(validity_t), intent(out) :: this
      type(mesh_t), intent(in) :: mesh
      real(wp), intent(in) :: u(:, :)   !< [mm]
      real(wp), parameter :: g = 1/sqrt(3.0_wp)
      real(wp), parameter :: gxi(4) = [-g, g, g, -g], geta(4) = [-g, -g, g, g]
      real(wp) :: xe(2, 4), ue(2, 4), n(4), dndx(2, 4), detj, grad(2, 2), exx, eyy, exy, e
      integer :: el, q
      this%size = norm2(mesh%bbox(2, :) - mesh%bbox(1, :))
      this%displacement_max = sqrt(maxval(u(1, :)**2 + u(2, :)**2))
      do el = 1, mesh%nel
         xe = mesh%element_coordinates(el)
         ue = u(:, mesh%conn(:, el))
         ! the mean displacement gradient over the Gauss points, grad(i, j) = d u_i / d x_j
         grad = 0
         do q = 1, 4
            call q1_gradients(xe, gxi(q), geta(q), n, dndx, detj)
            grad = grad + 0.25_wp*matmul(ue, transpose(dndx))
         end do
         exx = grad(1, 1)
         eyy = grad(2, 2)
         exy = 0.5_wp*(grad(1, 2) + grad(2, 1))
         e = abs(0.5_wp*(exx + eyy)) + sqrt((0.5_wp*(exx - eyy))**2 + exy**2)
         if (e > this%strain_max) then
            this%strain_max = e
            this%strain_at = 0.25_wp*sum(xe, dim=2)
         end if
      end do
   end subroutine validity_measure

   !> The warning line when the largest strain exceeds strain_limit, else ''.
   function validity_strain_warning(this) result(msg)
      class(validity_t), intent(in) :: this
      character(len=:), allocatable :: msg
      msg = ''
      if (.not. this%strain_max > strain_limit) return
      msg = 'the largest strain of the end state is '//fixed(100*this%strain_max, 1)//' % (element mean, '// &
            'at x = '//sci(this%strain_at(1))//', y = '//sci(this%strain_at(2))//' mm), over '// &
            str(nint(100*strain_limit))//' %, the small-strain range of this linear code: the result is '// &
            'outside its model there; check the load''s sign and size and the units (material:young in MPa)'
   end function validity_strain_warning

   !> The warning line when the body moved further than its own size, else ''.
   function validity_displacement_warning(this) result(msg)
      class(validity_t), intent(in) :: this
      character(len=:), allocatable :: msg
      msg = ''
      if (.not. this%displacement_max > this%size) return
      msg = 'the largest displacement of the end state, '//sci(this%displacement_max)//' mm, exceeds the '// &
            'body''s own size (the diagonal of its bounding box, '//sci(this%size)//' mm): small '// &
            'displacements are assumed; check the load''s sign and the supports (a rigid-body motion?)'
   end function validity_displacement_warning

   !> Root attributes of the output: strain_max [1], displacement_max [mm] and, when there are
   !> warnings, validity_warnings (their lines, newline-separated).
   subroutine validity_write(this, file)
      class(validity_t), intent(in) :: this
      type(h5file_t), intent(inout) :: file
      character(len=:), allocatable :: a, b
      call file%attr(file%id, 'strain_max', this%strain_max)
      call file%attr(file%id, 'displacement_max', this%displacement_max)
      a = this%strain_warning()
      b = this%displacement_warning()
      if (len(a) > 0 .and. len(b) > 0) a = a//new_line('a')
      if (len(a) + len(b) > 0) call file%attr(file%id, 'validity_warnings', a//b)
   end subroutine validity_write

   !> One stderr warning line per warning (none when all is in range).
   subroutine validity_report(this)
      class(validity_t), intent(in) :: this
      character(len=:), allocatable :: msg
      msg = this%strain_warning()
      if (len(msg) > 0) write (error_unit, '(a)') program_name//': warning: '//msg
      msg = this%displacement_warning()
      if (len(msg) > 0) write (error_unit, '(a)') program_name//': warning: '//msg
   end subroutine validity_report
end module contact2d_validity
