!> The driver: the run as a short story (docs/architecture.md, "One run"): command line ->
!> deck -> output names -> model -> the engine's run (contact2d_run_explicit or
!> contact2d_run_static: state, integrate or solve, write, summary). Only the driver and those
!> run routines stop the program (contact2d_run_exit; exit 1: bad input or usage, exit 2: the
!> run failed).
module contact2d_driver
   use contact2d_kinds, only: wp, i8
   use contact2d_strings, only: str
   use contact2d_cli, only: cli_t, cli_parse, cli_print_help, cli_print_version
   use contact2d_deck, only: deck_t, deck_read, deck_blame
   use contact2d_model, only: model_t, model_build, beside
   use contact2d_threads, only: thread_tuner_t
   use contact2d_report, only: report_header
   use contact2d_run_explicit, only: run_explicit
   use contact2d_run_static, only: run_static
   use contact2d_run_exit, only: opath, fail
   use contact2d_comm, only: comm_init, comm_end, comm_rank, comm_size, comm_barrier
   implicit none
   private
   public :: driver_main

contains

   !> The whole program: read the input, build the model, run the engine the deck names.
   subroutine driver_main()
      type(cli_t) :: cli
      type(deck_t) :: deck
      type(model_t) :: model
      type(thread_tuner_t) :: tuner
      integer(i8) :: clock0, rate
      integer :: stat
      character(len=:), allocatable :: errmsg

      call system_clock(clock0, rate)
      ! the processes of mpirun -np N (one without it); the ranks but 0 print nothing and write
      ! no file: every rank runs the same story on the same data (docs/mpi.md)
      call comm_init()
      if (comm_rank() /= 0) call quiet_rank()
      call tuner%begin()  ! the set-up window of the thread tuner (contact2d_threads)
      call cli_parse(cli, stat, errmsg)
      if (stat /= 0) call fail(1, errmsg//' (usage: contact2d --help)')
      if (cli%help) then
         call cli_print_help()
         call comm_end()
         stop
      end if
      if (cli%version) then
         call cli_print_version()
         call comm_end()
         stop
      end if
      call read_input(cli, deck)
      call model_build(deck, model, stat, errmsg)
      if (stat /= 0) call fail(1, errmsg//deck_blame(deck, errmsg))
      call report_header(cli%deck, cli%output, cli%quiet, deck, model)
      if (deck%solver%method == 'static') then
         ! (several processes share the explicit engine's rows only)
         if (comm_size() > 1) call fail(1, "solver:method = 'static' runs as one process (without mpirun)")
         call run_static(deck, model, clock0)
      else
         call run_explicit(cli%output, deck, model, clock0, rate, tuner)
      end if
      call comm_end()
   end subroutine driver_main

   !> A rank other than 0: its standard output and error go nowhere (rank 0 prints the run's
   !> lines, which every rank would print alike), and it neither takes the output's lock nor
   !> writes the file (contact2d_outpath, contact2d_output: writer off).
   subroutine quiet_rank()
      use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
      open (output_unit, file='/dev/null', action='write')
      open (error_unit, file='/dev/null', action='write')
      opath%writer = .false.
   end subroutine quiet_rank

   !> The deck (read, validated, --set applied), the output names checked before any set-up
   !> (contact2d_outpath) and the memory the mesh needs.
   subroutine read_input(cli, deck)
      type(cli_t), intent(in) :: cli
      type(deck_t), intent(out) :: deck
      integer :: stat
      character(len=:), allocatable :: errmsg, mesh_file
      call deck_read(cli%deck, cli%sets, deck, stat, errmsg)
      if (stat /= 0) call fail(1, errmsg)
      mesh_file = ''   ! an input the output must not be, as the deck
      if (len_trim(deck%mesh%file) > 0) mesh_file = beside(cli%deck, trim(deck%mesh%file))
      call opath%check(cli%output, cli%deck, mesh_file, cli%force, deck%output%xdmf, stat, errmsg)
      if (stat /= 0) call fail(1, errmsg)
      ! every rank has checked the names before rank 0 takes the lock (several processes)
      call comm_barrier()
      call memory_check(deck, stat, errmsg)
      if (stat /= 0) call fail(1, errmsg//deck_blame(deck, errmsg))
   end subroutine read_input

   !> Refuse a mesh whose arrays do not fit in the memory this process may use: one line naming
   !> the mesh and the bytes asked for, before any output. The probe is an allocation of the
   !> estimated size (not touched), so a limit on the address space (ulimit -v) is honoured;
   !> memory overcommitted by the system cannot be detected this way.
   subroutine memory_check(deck, stat, errmsg)
      type(deck_t), intent(in) :: deck
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      real(wp) :: nel, nnode, bytes
      real(wp), allocatable :: probe(:)
      integer :: ios
      stat = 0
      errmsg = ''
      ! a Gmsh mesh's size is known only once Gmsh has read it (nx, ny are unset): no probe
      if (len_trim(deck%mesh%file) > 0) return
      nel = real(deck%mesh%nx, wp)*real(deck%mesh%ny, wp)*4.0_wp**deck%mesh%level
      nnode = (real(deck%mesh%nx, wp)*2.0_wp**deck%mesh%level + 1)*(real(deck%mesh%ny, wp)*2.0_wp**deck%mesh%level + 1)
      ! nodal arrays of the model, the integrator and the output (about 40 reals per node),
      ! connectivity, element shape index and stress (about 12 words per element)
      bytes = 8*(40*nnode + 12*nel)
      allocate (probe(int(bytes/8, i8)), stat=ios)
      if (ios /= 0) then
         stat = 1
         errmsg = 'mesh '//str(nint(nel, i8))//' elements, '//str(nint(nnode, i8))//' nodes: cannot allocate the '// &
                  str(nint(bytes/2.0_wp**20, i8))//' MiB it needs (allocation failed)'
         return
      end if
      deallocate (probe)
   end subroutine memory_check
end module contact2d_driver
