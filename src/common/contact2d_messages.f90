!> A list of warnings gathered while a model is set up; the driver prints them and stores them
!> in the output file, tests can inspect them.
module contact2d_messages
   implicit none
   private
   public :: messages_t

   integer, parameter :: msg_len = 512

   !> Growing list of one-line messages.
   type :: messages_t
      integer :: n = 0
      character(len=msg_len), allocatable :: items(:)
   contains
      procedure :: add => messages_add
      procedure :: contains_text => messages_contains_text
   end type messages_t

contains

   subroutine messages_add(this, msg)
      class(messages_t), intent(inout) :: this
      character(len=*), intent(in) :: msg
      character(len=msg_len), allocatable :: tmp(:)
      if (.not. allocated(this%items)) allocate (this%items(4))
      if (this%n == size(this%items)) then
         allocate (tmp(2*this%n))
         tmp(1:this%n) = this%items
         call move_alloc(tmp, this%items)
      end if
      this%n = this%n + 1
      this%items(this%n) = msg
   end subroutine messages_add

   !> True if some message contains the text.
   logical function messages_contains_text(this, text)
      class(messages_t), intent(in) :: this
      character(len=*), intent(in) :: text
      integer :: i
      messages_contains_text = .false.
      do i = 1, this%n
         if (index(this%items(i), text) > 0) messages_contains_text = .true.
      end do
   end function messages_contains_text
end module contact2d_messages
