!> The deck variables of Coulomb friction (contact2d_friction_coulomb, docs/friction.md section
!> 1): `friction_coefficient` of &contact, with its default, its namelist read, its checks, its
!> echo, and the making of the law. A member of the input side of the friction-law seam
!> (contact2d_friction_input): a new parameter of the law touches this file and the law's own
!> (and its row in docs/deck.md) only.
module contact2d_friction_coulomb_input
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_checks, only: check_finite
   use contact2d_deck_syntax, only: read_failed, kv
   use contact2d_friction, only: friction_law_t
   use contact2d_friction_coulomb, only: coulomb_law_t
   use contact2d_friction_input, only: friction_input_t
   implicit none
   private
   public :: coulomb_input_t, coulomb_names

   !> The &contact variables of the law (blank-separated).
   character(len=*), parameter :: coulomb_names = 'friction_coefficient'

   !> Coulomb's deck variables.
   type, extends(friction_input_t) :: coulomb_input_t
      real(wp) :: friction_coefficient = 0   !< mu [-], >= 0 (docs/friction.md)
   contains
      procedure :: name => coulomb_input_name
      procedure :: variables => coulomb_input_variables
      procedure :: read => coulomb_input_read
      procedure :: not_finite => coulomb_input_not_finite
      procedure :: unused => coulomb_input_unused
      procedure :: validate => coulomb_input_validate
      procedure :: echo => coulomb_input_echo
      procedure :: make => coulomb_input_make
   end type coulomb_input_t

contains

   function coulomb_input_name(this) result(text)
      class(coulomb_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = 'coulomb'
   end function coulomb_input_name

   function coulomb_input_variables(this) result(text)
      class(coulomb_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = coulomb_names
   end function coulomb_input_variables

   !> Read one assignment (namelist records '&contact', text, '/'); variables: every &contact
   !> variable, for the did-you-mean of read_failed; where: the message's prefix.
   subroutine coulomb_input_read(this, records, where, variables, stat, errmsg)
      class(coulomb_input_t), intent(inout) :: this
      character(len=*), intent(in) :: records(:), where, variables
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: friction_coefficient
      integer :: ios
      character(len=256) :: msg
      namelist /contact/ friction_coefficient
      friction_coefficient = this%friction_coefficient
      read (records, nml=contact, iostat=ios, iomsg=msg)
      if (read_failed(ios, msg, variables, where, stat, errmsg)) return
      this%friction_coefficient = friction_coefficient
   end subroutine coulomb_input_read

   !> check_finite on every real of the law; true if one is bad.
   logical function coulomb_input_not_finite(this, errmsg) result(bad)
      class(coulomb_input_t), intent(in) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = check_finite('contact:friction_coefficient', this%friction_coefficient, errmsg)
   end function coulomb_input_not_finite

   !> A variable of the law given while friction is another law: true, with the message. A zero
   !> mu is no friction law of its own, so it goes with any law (a --set cannot remove a
   !> variable: `--set contact:friction='tresca'` switches a Coulomb deck with mu = 0 given).
   logical function coulomb_input_unused(this, friction, errmsg) result(bad)
      class(coulomb_input_t), intent(inout) :: this
      character(len=*), intent(in) :: friction
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = friction /= 'coulomb' .and. this%friction_coefficient /= 0
      if (bad) errmsg = "contact:friction_coefficient is set but friction = '"//trim(friction)// &
                        "'; use friction = 'coulomb'"
   end function coulomb_input_unused

   !> A finite mu >= 0 (whatever the law: the default 0 passes); true if refused.
   logical function coulomb_input_validate(this, friction, errmsg) result(bad)
      class(coulomb_input_t), intent(inout) :: this
      character(len=*), intent(in) :: friction
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .not. (this%friction_coefficient >= 0 .and. this%friction_coefficient <= huge(1.0_wp))
      if (bad) errmsg = 'contact:friction_coefficient = '//str(this%friction_coefficient)//' must be finite and >= 0'
   end function coulomb_input_validate

   !> The law's echo lines (when it is the chosen law).
   function coulomb_input_echo(this) result(text)
      class(coulomb_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = kv('friction_coefficient', str(this%friction_coefficient))
   end function coulomb_input_echo

   !> limit_i = mu F_n,i, mu_i = 0 where the tangential dof is prescribed (docs/friction.md).
   subroutine coulomb_input_make(this, abscissa, weight, slides, law)
      class(coulomb_input_t), intent(in) :: this
      real(wp), intent(in) :: abscissa(:), weight(:)
      logical, intent(in) :: slides(:)
      class(friction_law_t), allocatable, intent(out) :: law
      type(coulomb_law_t) :: coulomb
      call coulomb%init(this%friction_coefficient, slides)
      allocate (law, source=coulomb)
   end subroutine coulomb_input_make
end module contact2d_friction_coulomb_input
