!> cfe2d: reads a keyword deck, runs its steps and writes the listing.
program cfe2d
  use kinds, only: program_version
  use model, only: model_t
  use deck_parser, only: read_model
  use tie_constraints, only: tie_surfaces
  use listing, only: listing_t, open_listing, write_header
  use analysis, only: run_analysis
  use analysis_events, only: observer_ref_t, run_timing_t, wall_time
  use results_gmsh, only: result_file_t, open_result_file
  use results_vtu, only: vtu_series_t, open_vtu_series
  use results_frd, only: frd_file_t, open_frd_file
  use results_dat, only: dat_file_t, open_dat_file
  use results_sta, only: status_files_t, open_status_files
  use progress, only: progress_t
  use messages, only: fatal, terminate, warn
  use directories, only: make_directories
  use solver_codes, only: solver_code, solver_in_build, solver_skyline, solver_mumps, order_rcm, order_amd, &
                          contact_solve_condensed, solver_cholmod
  use strings, only: to_upper, itoa
  use mpi_session, only: session_start, session_serve
  implicit none
  character(len=4096) :: arg
  character(len=:), allocatable :: deck, outdir, job, base, why
  type(model_t) :: m
  type(listing_t), target :: lst
  type(result_file_t), target :: res
  type(progress_t), target :: prog
  type(vtu_series_t), target :: vtu
  type(frd_file_t), target :: frd
  type(dat_file_t), target :: dat
  type(status_files_t), target :: sta
  type(observer_ref_t), allocatable :: observers(:)
  type(run_timing_t) :: timing
  logical :: quiet, want_vtu, made, worker, exists
  integer :: i, k, ios, digits, nobs, solver, ranks

  ! Under mpirun the ranks other than 0 only join the solver's jobs.
  call session_start(worker, ranks)
  if (ranks == 0) call fatal('MPI could not be started (MPI_Init failed)')
  if (worker) then
    call session_serve()
    call terminate(0)
  end if
  timing%started = wall_time()
  solver = 0
  deck = ''
  outdir = ''
  quiet = .false.
  want_vtu = .false.
  digits = 7
  i = 1
  do while (i <= command_argument_count())
    call get_command_argument(i, arg)
    select case (trim(arg))
    case ('-h', '--help')
      call usage()
      call terminate(0)
    case ('-v', '--version')
      print '(a)', 'cfe2d ' // program_version
      call terminate(0)
    case ('-version')
      ! ccx's spelling; tools that drive ccx (pycalculix) read the layout
      ! version of the result files from the last number
      print '(a)', 'cfe2d ' // program_version // ', result files as CalculiX Version 2.20'
      call terminate(0)
    case ('-q', '--quiet')
      quiet = .true.
    case ('--vtu')
      want_vtu = .true.
    case ('-d', '--digits')
      i = i + 1
      if (i > command_argument_count()) call fatal('--digits needs a number')
      call get_command_argument(i, arg)
      read(arg, *, iostat=ios) digits
      if (ios /= 0 .or. digits < 3 .or. digits > 17) call fatal('--digits needs a number from 3 to 17')
    case ('-s', '--solver')
      i = i + 1
      if (i > command_argument_count()) call fatal('--solver needs a name (CHOLMOD, UMFPACK, SKYLINE, MUMPS)')
      call get_command_argument(i, arg)
      solver = solver_code(to_upper(trim(arg)))
      if (solver == 0) call fatal('--solver ' // trim(arg) // ': not a solver (CHOLMOD, UMFPACK, SKYLINE, MUMPS)')
      if (.not. solver_in_build(solver)) call fatal('--solver MUMPS: this cfe2d was built without MUMPS ' // &
                                                    '(no MPI or libmumps-dev where it was built; see README)')
    case ('-i')
      ! CalculiX's command line: ccx -i job (job.inp)
      i = i + 1
      if (i > command_argument_count()) call fatal('-i needs a job name (job.inp is read)')
      call get_command_argument(i, arg)
      if (len(deck) > 0) call fatal('only one deck per run')
      deck = trim(arg)
    case ('-o', '--output-dir')
      i = i + 1
      if (i > command_argument_count()) call fatal('--output-dir needs a directory')
      call get_command_argument(i, arg)
      outdir = trim(arg)
    case default
      if (arg(1:1) == '-') call fatal('unknown option "' // trim(arg) // '" (see cfe2d --help)')
      if (len(deck) > 0) call fatal('only one deck per run')
      deck = trim(arg)
    end select
    i = i + 1
  end do
  if (len(deck) == 0) then
    call usage()
    call fatal('no deck given')
  end if

  ! As ccx: a job name without extension names job.inp.
  inquire(file=deck, exist=exists)
  if (.not. exists) then
    inquire(file=deck // '.inp', exist=exists)
    if (exists) deck = deck // '.inp'
  end if
  ! Job name: the deck without its directory and .inp extension.
  k = index(deck, '/', back=.true.)
  base = deck(k + 1:)
  if (len(base) > 4) then
    if (base(len(base) - 3:) == '.inp' .or. base(len(base) - 3:) == '.INP') base = base(1:len(base) - 4)
  end if
  if (len(outdir) > 0) then
    job = outdir // '/' // base
  else
    job = deck(1:k) // base
  end if

  call read_model(deck, m)
  if (solver /= 0) call choose_solver(m, solver)
  if (ranks > 1 .and. m%solver /= solver_mumps) call warn(itoa(ranks) // ' MPI ranks, but the solver is not MUMPS: ' // &
    'rank 0 runs alone and the others wait (--solver MUMPS or *SOLVER, TYPE=MUMPS to share the work)')
  ! *TIE needs the projection onto faces, which the contact layer owns.
  call tie_surfaces(m)
  timing%read = wall_time() - timing%started
  ! The output directory is made (with its parents) only once the deck has
  ! been read, so that a deck with errors leaves no empty folders behind.
  if (len(outdir) > 0) then
    call make_directories(outdir, made, why)
    if (.not. made) call fatal('cannot create output directory "' // outdir // '" (' // why // ')')
  end if
  if (size(m%pairs) > 0) then
    call open_listing(job // '.out', job // '_contact.csv', digits, lst)
  else
    call open_listing(job // '.out', '', digits, lst)
  end if
  call write_header(lst, m)
  ! The writers that observe the analysis; a new output format is one more line here.
  allocate(observers(7))
  nobs = 1
  observers(1)%o => lst
  ! CalculiX's print and status files, as ccx writes them for every run
  call open_dat_file(job // '.dat', dat)
  call open_status_files(job, sta)
  observers(2)%o => dat
  observers(3)%o => sta
  nobs = 3
  if (any_file_request(m)) then
    call open_result_file(job // '.msh', m, res)
    nobs = nobs + 1
    observers(nobs)%o => res
    ! CalculiX's result file beside the gmsh one, for cgx, ccx2paraview, pycalculix
    call open_frd_file(job // '.frd', m, frd)
    nobs = nobs + 1
    observers(nobs)%o => frd
  end if
  if (want_vtu .or. m%vtu) then
    call open_vtu_series(job, vtu)
    nobs = nobs + 1
    observers(nobs)%o => vtu
  end if
  if (.not. quiet) then
    nobs = nobs + 1
    observers(nobs)%o => prog
  end if
  timing%output = wall_time() - timing%started - timing%read
  call run_analysis(m, observers(1:nobs), timing)
  call terminate(0)

contains

  !> The solver of --solver in place of the deck's (its ordering kept
  !> where the new solver has it, otherwise that solver's default).
  subroutine choose_solver(m, solver)
    type(model_t), intent(inout) :: m
    integer, intent(in) :: solver
    if ((solver == solver_skyline) .neqv. (m%solver == solver_skyline)) &
      m%ordering = merge(order_rcm, order_amd, solver == solver_skyline)
    m%solver = solver
    if (m%contact_solve == contact_solve_condensed .and. solver /= solver_cholmod .and. solver /= solver_mumps) &
      call fatal('--solver: the deck asks for CONTACT SOLVE=CONDENSED, which needs CHOLMOD or MUMPS')
  end subroutine choose_solver

  logical function any_file_request(m)
    type(model_t), intent(in) :: m
    integer :: s
    any_file_request = .false.
    do s = 1, size(m%steps)
      if (any(m%steps(s)%requests%to_file)) any_file_request = .true.
    end do
  end function any_file_request

  subroutine usage()
    print '(a)', 'usage: cfe2d [options] deck.inp'
    print '(a)', '       cfe2d [options] -i job      (as ccx: reads job.inp; so does cfe2d job)'
    print '(a)', ''
    print '(a)', 'Runs the keyword deck and writes <job>.out (listing), CalculiX''s <job>.dat'
    print '(a)', '(*NODE PRINT, *EL PRINT, *CONTACT PRINT), <job>.sta and <job>.cvg, with'
    print '(a)', 'contact <job>_contact.csv, and with *NODE FILE or *EL FILE the gmsh result'
    print '(a)', 'file <job>.msh and CalculiX''s <job>.frd, next to the deck or in'
    print '(a)', '--output-dir. With --vtu (or FORMAT=VTU on *NODE FILE or *EL FILE) also'
    print '(a)', 'ParaView files: <job>_NNNN.vtu per increment and'
    print '(a)', 'the time series <job>.pvd.'
    print '(a)', ''
    print '(a)', '  -o, --output-dir DIR   write the results into DIR (made, with its parents, if missing)'
    print '(a)', '  -d, --digits N         significant digits of reals in the listing (default 7)'
    print '(a)', '  -q, --quiet            no progress lines'
    print '(a)', '  -s, --solver NAME      CHOLMOD, UMFPACK, SKYLINE or MUMPS, in place of the deck''s *SOLVER'
    print '(a)', '                         (MUMPS over MPI: mpirun -np N cfe2d --solver mumps deck.inp)'
    print '(a)', '      --vtu              also write ParaView files (<job>_NNNN.vtu, <job>.pvd)'
    print '(a)', '  -h, --help             this text'
    print '(a)', '  -v, --version          program version'
  end subroutine usage
end program cfe2d
