!> The deck variables of Tresca friction (contact2d_friction_tresca, docs/friction.md): the
!> uniform `threshold` or the piecewise-linear profile `threshold_abscissa`/`threshold_values`,
!> and `tresca_scope`, with their defaults, their namelist read, their checks, their echo and the
!> making of the law. A member of the input side of the friction-law seam
!> (contact2d_friction_input): a new parameter of the law touches this file and the law's own
!> (and its row in docs/deck.md) only.
module contact2d_friction_tresca_input
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str, lower
   use contact2d_checks, only: check_finite
   use contact2d_deck_syntax, only: unset, max_points, line_len, read_failed, too_long, kv, quoted, reals
   use contact2d_friction, only: friction_law_t
   use contact2d_friction_tresca, only: tresca_law_t
   use contact2d_friction_input, only: friction_input_t
   implicit none
   private
   public :: tresca_input_t, tresca_names, scope_len

   !> The &contact variables of the law (blank-separated).
   character(len=*), parameter :: tresca_names = 'threshold threshold_abscissa threshold_values tresca_scope'
   !> Longest accepted tresca_scope.
   integer, parameter :: scope_len = 8

   !> Tresca's deck variables. tresca_scope is held at line_len characters while the deck is
   !> read, so that an over-long value is refused (tresca_input_too_long), never cut.
   type, extends(friction_input_t) :: tresca_input_t
      real(wp) :: threshold = 0                    !< uniform threshold s [MPa], >= 0
      real(wp) :: threshold_abscissa(max_points) = unset  !< abscissae of a piecewise-linear s [mm]
      real(wp) :: threshold_values(max_points) = unset    !< s at those abscissae [MPa]
      integer :: npoints = 0                       !< derived: points of the s profile (0: uniform)
      character(len=line_len) :: tresca_scope = 'all'  !< 'all' (as in the paper) | 'contact'
   contains
      procedure :: name => tresca_input_name
      procedure :: variables => tresca_input_variables
      procedure :: read => tresca_input_read
      procedure :: too_long => tresca_input_too_long
      procedure :: not_finite => tresca_input_not_finite
      procedure :: derive => tresca_input_count
      procedure :: unused => tresca_input_unused
      procedure :: validate => tresca_input_validate
      procedure :: echo => tresca_input_echo
      procedure :: echo_always => tresca_scope_echo
      procedure :: make => tresca_input_make
   end type tresca_input_t

contains

   function tresca_input_name(this) result(text)
      class(tresca_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = 'tresca'
   end function tresca_input_name

   function tresca_input_variables(this) result(text)
      class(tresca_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = tresca_names
   end function tresca_input_variables

   !> Read one assignment (namelist records '&contact', text, '/'); variables: every &contact
   !> variable, for the did-you-mean of read_failed; where: the message's prefix.
   subroutine tresca_input_read(this, records, where, variables, stat, errmsg)
      class(tresca_input_t), intent(inout) :: this
      character(len=*), intent(in) :: records(:), where, variables
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      real(wp) :: threshold, threshold_abscissa(max_points), threshold_values(max_points)
      character(len=line_len) :: tresca_scope
      integer :: ios
      character(len=256) :: msg
      namelist /contact/ threshold, threshold_abscissa, threshold_values, tresca_scope
      threshold = this%threshold; threshold_abscissa = this%threshold_abscissa
      threshold_values = this%threshold_values; tresca_scope = this%tresca_scope
      read (records, nml=contact, iostat=ios, iomsg=msg)
      if (read_failed(ios, msg, variables, where, stat, errmsg)) return
      this%threshold = threshold; this%threshold_abscissa = threshold_abscissa
      this%threshold_values = threshold_values; this%tresca_scope = tresca_scope
   end subroutine tresca_input_read

   !> A string longer than its field (scope_len) is refused; true if so.
   logical function tresca_input_too_long(this, where, stat, errmsg) result(bad)
      class(tresca_input_t), intent(in) :: this
      character(len=*), intent(in) :: where
      integer, intent(inout) :: stat
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = too_long(where, 'tresca_scope', this%tresca_scope, scope_len, stat, errmsg)
   end function tresca_input_too_long

   !> check_finite on every real of the law; true if one is bad.
   logical function tresca_input_not_finite(this, errmsg) result(bad)
      class(tresca_input_t), intent(in) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = .true.
      if (check_finite('contact:threshold', this%threshold, errmsg)) return
      if (check_finite('contact:threshold_abscissa', this%threshold_abscissa, errmsg)) return
      if (check_finite('contact:threshold_values', this%threshold_values, errmsg)) return
      bad = .false.
   end function tresca_input_not_finite

   !> The points of the profile (npoints); true if abscissae and values differ in number.
   logical function tresca_input_count(this, errmsg) result(bad)
      class(tresca_input_t), intent(inout) :: this
      character(len=:), allocatable, intent(inout) :: errmsg
      this%npoints = count(this%threshold_abscissa /= unset)
      bad = count(this%threshold_values /= unset) /= this%npoints
      if (bad) errmsg = 'contact: threshold_abscissa and threshold_values need the same number of entries'
   end function tresca_input_count

   !> A threshold given while friction is another law: true, with the message. A zero
   !> threshold is no friction law of its own, so it goes with any law: `--set
   !> contact:friction='coulomb' --set contact:threshold=0` switches a Tresca deck to Coulomb.
   logical function tresca_input_unused(this, friction, errmsg) result(bad)
      class(tresca_input_t), intent(inout) :: this
      character(len=*), intent(in) :: friction
      character(len=:), allocatable, intent(inout) :: errmsg
      bad = friction /= 'tresca' .and. (this%threshold /= 0 .or. this%npoints > 0)
      if (bad) errmsg = "contact: a threshold is given but friction = '"//trim(friction)//"'; use friction = 'tresca'"
   end function tresca_input_unused

   !> The threshold (uniform or profile) and tresca_scope (lower-cased); friction: the chosen
   !> law (Coulomb acts where F_n > 0 and takes no other scope). True if refused.
   logical function tresca_input_validate(this, friction, errmsg) result(bad)
      class(tresca_input_t), intent(inout) :: this
      character(len=*), intent(in) :: friction
      character(len=:), allocatable, intent(inout) :: errmsg
      integer :: i
      bad = .true.
      if (this%npoints > 0 .and. this%threshold /= 0) then
         errmsg = 'contact: give either threshold or threshold_abscissa/threshold_values, not both'
         return
      end if
      if (.not. this%threshold >= 0) then
         errmsg = 'contact:threshold = '//str(this%threshold)//' must be >= 0 (MPa)'
         return
      end if
      if (this%npoints > 0) then
         if (any(this%threshold_abscissa(this%npoints + 1:) /= unset) .or. &
             any(this%threshold_values(this%npoints + 1:) /= unset)) then
            errmsg = 'contact: threshold_abscissa/threshold_values must be given from the first entry on'
            return
         end if
         if (any(this%threshold_values(1:this%npoints) < 0)) then
            errmsg = 'contact:threshold_values must all be >= 0 (MPa)'
            return
         end if
         do i = 2, this%npoints
            if (.not. this%threshold_abscissa(i) > this%threshold_abscissa(i - 1)) then
               errmsg = 'contact:threshold_abscissa must increase strictly (entry '//str(i)//')'
               return
            end if
         end do
      end if
      this%tresca_scope = lower(this%tresca_scope)
      if (.not. any(this%tresca_scope == [character(len=scope_len) :: 'all', 'contact'])) then
         errmsg = "contact:tresca_scope = '"//trim(this%tresca_scope)//"' is not one of 'all', 'contact'"
         return
      end if
      if (friction == 'coulomb' .and. this%tresca_scope /= 'all') then
         errmsg = "contact:tresca_scope = '"//trim(this%tresca_scope)//"' applies to Tresca only; "// &
                  "Coulomb friction acts where F_n > 0"
         return
      end if
      bad = .false.
   end function tresca_input_validate

   !> The law's threshold echo lines (when it is the chosen law).
   function tresca_input_echo(this) result(text)
      class(tresca_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      if (this%npoints > 0) then
         text = kv('threshold_abscissa', reals(this%threshold_abscissa(1:this%npoints)))// &
                kv('threshold_values', reals(this%threshold_values(1:this%npoints)))
      else
         text = kv('threshold', str(this%threshold))
      end if
   end function tresca_input_echo

   !> The echo line of tresca_scope (written whatever the law: a frictionless deck may carry it).
   function tresca_scope_echo(this) result(text)
      class(tresca_input_t), intent(in) :: this
      character(len=:), allocatable :: text
      text = kv('tresca_scope', quoted(this%tresca_scope))
   end function tresca_scope_echo

   !> Tresca's law on the contact nodes (SPEC section 3): s_i from the uniform threshold or the
   !> profile at their abscissae, limits s_i w_i where the tangential dof is free.
   subroutine tresca_input_make(this, abscissa, weight, slides, law)
      class(tresca_input_t), intent(in) :: this
      real(wp), intent(in) :: abscissa(:), weight(:)
      logical, intent(in) :: slides(:)
      class(friction_law_t), allocatable, intent(out) :: law
      type(tresca_law_t) :: tresca
      call tresca%init(abscissa, weight, slides, this%threshold, this%threshold_abscissa(1:this%npoints), &
                       this%threshold_values(1:this%npoints), trim(this%tresca_scope) == 'contact')
      allocate (law, source=tresca)
   end subroutine tresca_input_make
end module contact2d_friction_tresca_input
