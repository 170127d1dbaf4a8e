!> The deck variables of Coulomb friction (contact2d_friction_coulomb, docs/friction.md section
!> 1): `friction_coefficient` of &contact, with its default, its namelist read, its checks and
!> its echo. The &contact reader (contact2d_deck_contact) routes to this module every assignment
!> of a name it claims (coulomb_claims), so that a new parameter of the law touches this file
!> (and its row in docs/deck.md) only.
module contact2d_friction_coulomb_input
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_checks, only: check_finite
   use contact2d_deck_syntax, only: read_failed, kv
   implicit none
   private
   public :: coulomb_input_t, coulomb_names, coulomb_claims, coulomb_input_read, coulomb_input_not_finite
   public :: coulomb_input_unused, coulomb_input_validate, coulomb_input_echo

   !> The &contact variables of the law (blank-separated).
   character(len=*), parameter :: coulomb_names = 'friction_coefficient'

   !> Coulomb's deck variables.
   type :: coulomb_input_t
      real(wp) :: friction_coefficient = 0   !< mu [-], >= 0 (docs/friction.md)
   end type coulomb_input_t

contains

   !> name (lower case, no subscript) is a variable of this law.
   pure logical function coulomb_claims(name)
      character(len=*), intent(in) :: name
      coulomb_claims = index(' '//coulomb_names//' ', ' '//name//' ') > 0
   end function coulomb_claims

   !> Read one assignment (namelist records '&contact', text, '/'); variables: every &contact
   !> variable, for the did-you-mean of read_failed; where: the message's prefix.
   subroutine coulomb_input_read(records, where, variables, cfg, stat, errmsg)
      character(len=*), intent(in) :: records(:), where, variables
      type(coulomb_input_t), intent(inout) :: cfg
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: friction_coefficient
      integer :: ios
      character(len=256) :: msg
      namelist /contact/ friction_coefficient
      friction_coefficient = cfg%friction_coefficient
      read (records, nml=contact, iostat=ios, iomsg=msg)
      if (read_failed(ios, msg, variables, where, stat, errmsg)) return
      cfg%friction_coefficient = friction_coefficient
   end subroutine coulomb_input_read

   !> check_finite on every real of the law; true if one is bad.
   logical function coulomb_input_not_finite(cfg, errmsg) result(bad)
      type(coulomb_input_t), intent(in) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = check_finite('contact:friction_coefficient', cfg%friction_coefficient, errmsg)
   end function coulomb_input_not_finite

   !> A variable of the law given while friction is another law: true, with the message. A zero
   !> mu is no friction law of its own, so it goes with any law (a --set cannot remove a
   !> variable: `--set contact:friction='tresca'` switches a Coulomb deck with mu = 0 given).
   logical function coulomb_input_unused(cfg, friction, errmsg) result(bad)
      type(coulomb_input_t), intent(in) :: cfg
      character(len=*), intent(in) :: friction
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = friction /= 'coulomb' .and. cfg%friction_coefficient /= 0
      if (bad) errmsg = "contact:friction_coefficient is set but friction = '"//trim(friction)// &
                        "'; use friction = 'coulomb'"
   end function coulomb_input_unused

   !> A finite mu >= 0; true if refused.
   logical function coulomb_input_validate(cfg, errmsg) result(bad)
      type(coulomb_input_t), intent(in) :: cfg
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .not. (cfg%friction_coefficient >= 0 .and. cfg%friction_coefficient <= huge(1.0_wp))
      if (bad) errmsg = 'contact:friction_coefficient = '//str(cfg%friction_coefficient)//' must be finite and >= 0'
   end function coulomb_input_validate

   !> The law's echo lines (when it is the chosen law).
   function coulomb_input_echo(cfg) result(text)
      type(coulomb_input_t), intent(in) :: cfg
      character(len=:), allocatable :: text
      text = kv('friction_coefficient', str(cfg%friction_coefficient))
   end function coulomb_input_echo
end module contact2d_friction_coulomb_input
