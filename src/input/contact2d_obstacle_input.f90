!> The input side of the obstacle seam (docs/geometry.md): an abstract obstacle input holds one
!> shape's &contact variables, reads, checks and echoes them, and makes the obstacle
!> (contact2d_obstacle) from them. Members: one contact2d_obstacle_<shape>_input module per
!> shape; the registry of contact2d_deck_contact lists them, so that a shape's parameters touch
!> its own two files only.
module contact2d_obstacle_input
   use contact2d_kinds, only: wp
   use contact2d_obstacle, only: obstacle_t
   implicit none
   private
   public :: obstacle_input_t, obstacle_input_box_t

   !> One obstacle shape's deck variables and the making of the obstacle.
   type, abstract :: obstacle_input_t
   contains
      !> The deck's name of the shape (contact:obstacle).
      procedure(input_text), deferred :: name
      !> The &contact variables of the shape, blank-separated.
      procedure(input_text), deferred :: variables
      !> name (lower case, no subscript) is a variable of this shape.
      procedure, non_overridable :: claims => obstacle_input_claims
      !> Read one assignment (namelist records '&contact', text, '/'); variables: every &contact
      !> variable, for the did-you-mean; where: the message's prefix.
      procedure(input_read), deferred :: read
      !> A string longer than its field is refused; true if so.
      procedure :: too_long => obstacle_input_too_long
      !> check_finite on every real of the shape; true if one is bad.
      procedure :: not_finite => obstacle_input_message
      !> Checks of a choice of the shape made whatever the chosen shape (its text values
      !> lower-cased), before the others; true if refused.
      procedure :: prepare => obstacle_input_message_inout
      !> The shape's own checks when it is the chosen one; true if refused.
      procedure :: validate_chosen => obstacle_input_message_inout
      !> A variable of this shape given while obstacle (the chosen shape) is another: true,
      !> with the message.
      procedure :: unused => obstacle_input_unused
      !> Fill the defaults of the variables not given (checking that a vector is given whole);
      !> true if refused.
      procedure :: complete => obstacle_input_message_inout
      !> Checks made whatever the chosen shape, after complete; true if refused.
      procedure :: validate_always => obstacle_input_message_inout
      !> The echo lines of the shape's variables when it is the chosen one.
      procedure(input_text), deferred :: echo
      !> Make the obstacle.
      procedure(input_make), deferred :: make
      !> A warning ('' for none) when the obstacle can never be touched by the built-in edge
      !> named edge, whose outward normal is outward (a plane whose normal points along it).
      procedure :: edge_warning => obstacle_input_edge_warning
   end type obstacle_input_t

   !> One entry of a list of shape inputs (a polymorphic element).
   type :: obstacle_input_box_t
      class(obstacle_input_t), allocatable :: input
   end type obstacle_input_box_t

   abstract interface
      function input_text(this) result(text)
         import :: obstacle_input_t
         class(obstacle_input_t), intent(in) :: this
         character(len=:), allocatable :: text
      end function input_text

      subroutine input_read(this, records, where, variables, stat, errmsg)
         import :: obstacle_input_t
         class(obstacle_input_t), intent(inout) :: this
         character(len=*), intent(in) :: records(:), where, variables
         integer, intent(inout) :: stat
         character(len=:), allocatable, intent(inout) :: errmsg
      end subroutine input_read

      subroutine input_make(this, obstacle)
         import :: obstacle_input_t, obstacle_t
         class(obstacle_input_t), intent(in) :: this
         class(obstacle_t), allocatable, intent(out) :: obstacle
      end subroutine input_make
   end interface

contains

   logical function obstacle_input_claims(this, name) result(claims)
      class(obstacle_input_t), intent(in) :: this
      character(len=*), intent(in) :: name
      claims = index(' '//this%variables()//' ', ' '//name//' ') > 0
   end function obstacle_input_claims

   logical function obstacle_input_too_long(this, where, stat, errmsg) result(bad)
      class(obstacle_input_t), intent(in) :: this
      character(len=*), intent(in) :: where
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .false.
   end function obstacle_input_too_long

   logical function obstacle_input_message(this, errmsg) result(bad)
      class(obstacle_input_t), intent(in) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .false.
   end function obstacle_input_message

   logical function obstacle_input_message_inout(this, errmsg) result(bad)
      class(obstacle_input_t), intent(inout) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .false.
   end function obstacle_input_message_inout

   logical function obstacle_input_unused(this, obstacle, errmsg) result(bad)
      class(obstacle_input_t), intent(in) :: this
      character(len=*), intent(in) :: obstacle
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .false.
   end function obstacle_input_unused

   function obstacle_input_edge_warning(this, edge, outward) result(text)
      class(obstacle_input_t), intent(in) :: this
      character(len=*), intent(in) :: edge
      real(wp), intent(in) :: outward(2)
      character(len=:), allocatable :: text
      text = ''
   end function obstacle_input_edge_warning
end module contact2d_obstacle_input
