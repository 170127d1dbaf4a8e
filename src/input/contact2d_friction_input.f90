!> The input side of the friction-law seam (docs/friction.md section 2): an abstract friction
!> law input holds one law's &contact variables, reads, checks and echoes them, and makes the
!> law (contact2d_friction) from them and the contact nodes' geometry. Members: one
!> contact2d_friction_<law>_input module per law; the registry of contact2d_deck_contact lists
!> them, so that a law's parameters touch its own two files only.
module contact2d_friction_input
   use contact2d_kinds, only: wp
   use contact2d_friction, only: friction_law_t
   implicit none
   private
   public :: friction_input_t, friction_input_box_t

   !> One friction law's deck variables and the making of the law.
   type, abstract :: friction_input_t
   contains
      !> The deck's name of the law (contact:friction).
      procedure(input_text), deferred :: name
      !> The &contact variables of the law, blank-separated ('' for none).
      procedure(input_text), deferred :: variables
      !> name (lower case, no subscript) is a variable of this law.
      procedure, non_overridable :: claims => friction_input_claims
      !> Read one assignment (namelist records '&contact', text, '/'); variables: every &contact
      !> variable, for the did-you-mean; where: the message's prefix.
      procedure :: read => friction_input_read
      !> A string longer than its field is refused; true if so.
      procedure :: too_long => friction_input_too_long
      !> check_finite on every real of the law; true if one is bad.
      procedure :: not_finite => friction_input_no_message
      !> Derived values of the law's variables (such as a profile's number of points), before the
      !> checks below; true if refused.
      procedure :: derive => friction_input_derive
      !> A variable of this law given while friction (the chosen law) is another: true, with the
      !> message.
      procedure :: unused => friction_input_check
      !> The law's own checks, friction being the chosen law; true if refused.
      procedure :: validate => friction_input_check
      !> The echo lines of the law's variables when it is the chosen law.
      procedure :: echo => friction_input_echo
      !> Echo lines written whatever the chosen law ('' unless a law says otherwise).
      procedure :: echo_always => friction_input_echo
      !> Make the law for contact nodes with these abscissae [mm], weights w_i [mm] and free
      !> tangential dofs (slides); law is left unallocated for a law that is no friction.
      procedure(input_make), deferred :: make
   end type friction_input_t

   !> One entry of a list of law inputs (a polymorphic element).
   type :: friction_input_box_t
      class(friction_input_t), allocatable :: input
   end type friction_input_box_t

   abstract interface
      function input_text(this) result(text)
         import :: friction_input_t
         class(friction_input_t), intent(in) :: this
         character(len=:), allocatable :: text
      end function input_text

      subroutine input_make(this, abscissa, weight, slides, law)
         import :: friction_input_t, friction_law_t, wp
         class(friction_input_t), intent(in) :: this
         real(wp), intent(in) :: abscissa(:), weight(:)
         logical, intent(in) :: slides(:)
         class(friction_law_t), allocatable, intent(out) :: law
      end subroutine input_make
   end interface

contains

   logical function friction_input_claims(this, name) result(claims)
      class(friction_input_t), intent(in) :: this
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: names
      names = this%variables()
      claims = len(names) > 0 .and. index(' '//names//' ', ' '//name//' ') > 0
   end function friction_input_claims

   !> A law without variables claims no name, so is never asked to read.
   subroutine friction_input_read(this, records, where, variables, stat, errmsg)
      class(friction_input_t), intent(inout) :: this
      character(len=*), intent(in) :: records(:), where, variables
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
   end subroutine friction_input_read

   logical function friction_input_too_long(this, where, stat, errmsg) result(bad)
      class(friction_input_t), intent(in) :: this
      character(len=*), intent(in) :: where
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .false.
   end function friction_input_too_long

   logical function friction_input_no_message(this, errmsg) result(bad)
      class(friction_input_t), intent(in) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .false.
   end function friction_input_no_message

   logical function friction_input_derive(this, errmsg) result(bad)
      class(friction_input_t), intent(inout) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .false.
   end function friction_input_derive

   logical function friction_input_check(this, friction, errmsg) result(bad)
      class(friction_input_t), intent(inout) :: this
      character(len=*), intent(in) :: friction
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .false.
   end function friction_input_check

   function friction_input_echo(this) result(text)
      class(friction_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = ''
   end function friction_input_echo
end module contact2d_friction_input
