!> Command line: contact2d DECK [-o OUT.h5] [--force] [--static] [--set group:variable=value ...]
!> Also the text of --help and --version.
module contact2d_cli
   use, intrinsic :: iso_fortran_env, only: output_unit, compiler_version
   use contact2d_strings, only: str
   use contact2d_version, only: program_name, program_version
   use contact2d_build_config, only: sweep_lanes, build_flags
   implicit none
   private
   public :: cli_t, cli_parse, usage, cli_print_help, cli_print_version

   integer, parameter :: arg_len = 4096

   !> Parsed command line.
   type :: cli_t
      character(len=:), allocatable :: deck      !< deck path
      character(len=:), allocatable :: output    !< output path ('' = <deck stem>.h5)
      logical :: force = .false.                 !< overwrite an existing output file
      logical :: help = .false.
      logical :: version = .false.
      logical :: quiet = .false.                 !< no deck echo
      character(len=arg_len), allocatable :: sets(:)
   end type cli_t

   character(len=*), parameter :: usage = &
      'usage: contact2d DECK [-o OUT.h5] [--force] [--static] [--set group:variable=value ...] [--quiet]'// &
      new_line('a')//'       contact2d --help | --version'

contains

   !> Parse the command line. stat /= 0 with a message on a bad argument.
   subroutine cli_parse(cli, stat, errmsg)
      type(cli_t), intent(out) :: cli
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      character(len=:), allocatable :: arg
      integer :: i, n, nset

      stat = 1
      n = command_argument_count()
      allocate (cli%sets(n))
      cli%deck = ''
      cli%output = ''
      nset = 0
      i = 1
      do while (i <= n)
         arg = argument(i)
         select case (arg)
         case ('-h', '--help')
            cli%help = .true.
         case ('--version')
            cli%version = .true.
         case ('--force')
            cli%force = .true.
         case ('-q', '--quiet')
            cli%quiet = .true.
         case ('--static')
            ! the static engine (docs/static.md): the same as --set solver:method='static'
            nset = nset + 1
            cli%sets(nset) = "solver:method='static'"
         case ('-o', '--output')
            if (i == n) then
               errmsg = trim(arg)//' needs a file name'
               return
            end if
            i = i + 1
            cli%output = argument(i)   ! in full, whatever its length
            if (len(cli%output) == 0) then
               errmsg = trim(arg)//': the output file name is empty'
               return
            end if
         case ('--set')
            if (i == n) then
               errmsg = '--set needs group:variable=value'
               return
            end if
            i = i + 1
            nset = nset + 1
            arg = argument(i)
            if (len(arg) > arg_len) then
               errmsg = '--set argument '//arg(1:40)//'... is longer than the '//str(arg_len)// &
                        ' characters accepted'
               return
            end if
            cli%sets(nset) = arg
         case default
            if (index(arg, '-') == 1) then
               errmsg = "unknown option '"//trim(arg)//"'"
               return
            end if
            if (len(cli%deck) > 0) then
               errmsg = "more than one deck given ('"//cli%deck//"' and '"//trim(arg)//"')"
               return
            end if
            cli%deck = arg
         end select
         i = i + 1
      end do
      cli%sets = cli%sets(1:nset)
      if (len(cli%deck) == 0 .and. .not. (cli%help .or. cli%version)) then
         errmsg = 'no deck given'
         return
      end if
      if (len(cli%output) == 0 .and. len(cli%deck) > 0) cli%output = stem(cli%deck)//'.h5'
      stat = 0
      errmsg = ''
   end subroutine cli_parse

   !> --help: the usage and the options, on stdout.
   subroutine cli_print_help()
      write (output_unit, '(a)') usage
      write (output_unit, '(a)') 'Runs the deck and writes its HDF5 file (default: <deck stem>.h5 here).'
      write (output_unit, '(a)') '  -o, --output FILE   output file'
      write (output_unit, '(a)') '  --force             overwrite an existing output file'
      write (output_unit, '(a)') '  --set G:V=X         override deck variable V of group G (G#i for the i-th'
      write (output_unit, '(a)') '                      &dirichlet or &traction); repeatable; validated as the deck'
      write (output_unit, '(a)') '  -q, --quiet         do not echo the effective deck'
      write (output_unit, '(a)') '  --static            solve the static problem directly (solver:method = ''static'','
      write (output_unit, '(a)') '                      docs/static.md) instead of the explicit march'
      write (output_unit, '(a)') 'Deck reference: docs/deck.md. Output layout: docs/output.md.'
   end subroutine cli_print_help

   !> --version: the program's version and the build, so that a timing can be told apart from
   !> another build's (docs/deck.md).
   subroutine cli_print_version()
      write (output_unit, '(a)') program_name//' '//program_version
      write (output_unit, '(a)') 'built with '//compiler_version()//', '//build_flags// &
         '; the sweep''s inside rows use '//str(sweep_lanes)//' lanes'
   end subroutine cli_print_version

   !> Command argument i in full (deferred length: never cut).
   function argument(i) result(a)
      integer, intent(in) :: i
      character(len=:), allocatable :: a
      integer :: l
      call get_command_argument(i, length=l)
      allocate (character(len=l) :: a)
      if (l > 0) call get_command_argument(i, a)
   end function argument

   !> File name without directory and extension.
   function stem(path) result(s)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: s
      integer :: slash, dot
      slash = index(path, '/', back=.true.)
      s = path(slash + 1:)
      dot = index(s, '.', back=.true.)
      if (dot > 1) s = s(1:dot - 1)
   end function stem
end module contact2d_cli
