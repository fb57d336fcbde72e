/* MUMPS (the distributed multifrontal solver, through its C interface
 * dmumps_c) and the MPI session it runs in, for mumps_binding.f90.
 *
 * Rank 0 runs cfe2d; every other rank waits in cfe_mpi_worker_loop for a
 * command broadcast by rank 0 (make an instance, run a MUMPS job on it,
 * free it, quit) and joins the collective dmumps_c call. The matrix, the
 * right-hand sides and the Schur complement live on rank 0 only (MUMPS'
 * centralised input, PAR=1: the host works too).
 *
 * MPI is started only when the program was launched by an MPI launcher
 * (its environment says so) or when a MUMPS instance is first asked for;
 * a plain run that never chooses MUMPS does not touch MPI. At exit rank 0
 * frees every instance with the workers and tells them to quit (atexit),
 * so that an error stop on rank 0 ends the whole job cleanly.
 *
 * Without CFE_HAVE_MUMPS (no MUMPS or MPI on the build machine) the same
 * entry points exist: one rank, and cfe_mumps_available() says 0. */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define CFE_MAX_INSTANCES 8

#ifdef CFE_HAVE_MUMPS
#include <sys/resource.h>
#include <mpi.h>
#include <dmumps_c.h>

/* Commands from rank 0 to the workers: {command, instance, argument}. */
enum { CMD_QUIT = 0, CMD_NEW = 1, CMD_JOB = 2, CMD_FREE = 3 };

static DMUMPS_STRUC_C inst[CFE_MAX_INSTANCES];
static int live[CFE_MAX_INSTANCES];
static int started = 0, rank = 0, nranks = 1;

/* Was this process started by an MPI launcher (Open MPI, MPICH/Hydra, PMIx)? */
static int launched_by_mpi(void)
{
  static const char *vars[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS", 0};
  for (int k = 0; vars[k]; k++)
    if (getenv(vars[k])) return 1;
  return 0;
}

/* Rank 0's side of wait_command (a non-blocking broadcast must meet a
 * non-blocking one). */
static void broadcast(int cmd, int h, int arg)
{
  int msg[3] = {cmd, h, arg};
  MPI_Request req;
  MPI_Ibcast(msg, 3, MPI_INT, 0, MPI_COMM_WORLD, &req);
  MPI_Wait(&req, MPI_STATUS_IGNORE);
}

/* The job on instance h, every rank together; icntl and cntl are rank 0's. */
static void run_job(int h, int job)
{
  MPI_Bcast(inst[h].icntl, 60, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Bcast(inst[h].cntl, 15, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  inst[h].job = job;
  dmumps_c(&inst[h]);
}

static void new_instance(int h, int sym)
{
  memset(&inst[h], 0, sizeof(inst[h]));
  inst[h].comm_fortran = (MUMPS_INT)MPI_Comm_c2f(MPI_COMM_WORLD);
  inst[h].par = 1;
  inst[h].sym = sym;
  inst[h].job = -1;
  dmumps_c(&inst[h]);
  live[h] = 1;
}

static void free_instance(int h)
{
  inst[h].job = -2;
  dmumps_c(&inst[h]);
  live[h] = 0;
}

/* Rank 0 at exit: the instances freed with the workers, then quit. */
static void finish_session(void)
{
  int fin = 0;
  if (!started || rank != 0) return;
  MPI_Finalized(&fin);
  if (fin) return;
  for (int h = 0; h < CFE_MAX_INSTANCES; h++)
    if (live[h]) {
      broadcast(CMD_FREE, h, 0);
      free_instance(h);
    }
  broadcast(CMD_QUIT, 0, 0);
  MPI_Finalize();
}

int cfe_mumps_available(void) { return 1; }

/* MUMPS keeps large arrays on the stack: rank 0 of a 2-rank run of 805 000
 * equations (a 50 000-point contact surface) overflowed the usual 8 MiB
 * (a segmentation fault in the analysis). The soft limit is raised to
 * 1 GiB (or the hard limit); Linux lets the main thread's stack grow to the
 * limit in force when it grows, so this holds for the rest of the run. */
static void raise_stack_limit(void)
{
  struct rlimit rl;
  rlim_t want = (rlim_t)1 << 30;
  if (getrlimit(RLIMIT_STACK, &rl) != 0 || rl.rlim_cur == RLIM_INFINITY || rl.rlim_cur >= want) return;
  if (rl.rlim_max != RLIM_INFINITY && rl.rlim_max < want) want = rl.rlim_max;
  rl.rlim_cur = want;
  setrlimit(RLIMIT_STACK, &rl);
}

/* Starts MPI if the launcher says so, or always when force is set.
 * Returns the number of ranks (1 without MPI). */
int cfe_mpi_start(int force)
{
  int init = 0;
  if (started) return nranks;
  if (!force && !launched_by_mpi()) return 1;
  raise_stack_limit();
  MPI_Initialized(&init);
  if (!init && MPI_Init(NULL, NULL) != MPI_SUCCESS) return -1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);
  started = 1;
  if (rank == 0) atexit(finish_session);
  return nranks;
}

int cfe_mpi_rank(void) { return rank; }

/* The next command from rank 0. A blocking MPI_Bcast would spin (Open MPI
 * polls) for the whole time rank 0 reads, assembles and writes, taking a
 * core from it on a machine with as many ranks as cores; the worker polls
 * a non-blocking broadcast instead and sleeps between polls (50 us, up to
 * 2 ms while nothing comes). */
static void wait_command(int *msg)
{
  MPI_Request req;
  int done = 0;
  long ns = 50000;
  MPI_Ibcast(msg, 3, MPI_INT, 0, MPI_COMM_WORLD, &req);
  for (;;) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (done) return;
    struct timespec ts = {0, ns};
    nanosleep(&ts, 0);
    if (ns < 2000000) ns *= 2;
  }
}

/* A worker rank: obeys rank 0 until it says quit, then leaves MPI. */
void cfe_mpi_worker_loop(void)
{
  int msg[3];
  if (!started || rank == 0) return;
  for (;;) {
    wait_command(msg);
    if (msg[0] == CMD_QUIT) break;
    switch (msg[0]) {
    case CMD_NEW: new_instance(msg[1], msg[2]); break;
    case CMD_JOB: run_job(msg[1], msg[2]); break;
    case CMD_FREE: free_instance(msg[1]); break;
    default: break;
    }
  }
  MPI_Finalize();
}

/* A new instance (sym: 0 unsymmetric, 1 positive definite, 2 symmetric),
 * silent; returns its handle (0-based) or -1 when all are taken. */
int cfe_mumps_new(int sym)
{
  int h;
  if (!started && cfe_mpi_start(1) < 0) return -1;
  for (h = 0; h < CFE_MAX_INSTANCES; h++)
    if (!live[h]) break;
  if (h == CFE_MAX_INSTANCES) return -1;
  broadcast(CMD_NEW, h, sym);
  new_instance(h, sym);
  inst[h].icntl[0] = -1;   /* ICNTL(1..4): no messages; cfe2d reports the errors */
  inst[h].icntl[1] = -1;
  inst[h].icntl[2] = -1;
  inst[h].icntl[3] = 0;
  return h;
}

void cfe_mumps_free(int h)
{
  if (h < 0 || h >= CFE_MAX_INSTANCES || !live[h]) return;
  broadcast(CMD_FREE, h, 0);
  free_instance(h);
}

/* ICNTL(k) = icntl[k-1] (k = 1..60) and CNTL(k) = cntl[k-1] (k = 1..15). */
void cfe_mumps_get_control(int h, int *icntl, double *cntl)
{
  memcpy(icntl, inst[h].icntl, 60 * sizeof(int));
  memcpy(cntl, inst[h].cntl, 15 * sizeof(double));
}

void cfe_mumps_set_control(int h, const int *icntl, const double *cntl)
{
  memcpy(inst[h].icntl, icntl, 60 * sizeof(int));
  memcpy(inst[h].cntl, cntl, 15 * sizeof(double));
}

/* Runs job (1 analysis, 2 factorisation, 3 solve) on every rank. The
 * matrix is n equations, nnz entries at (irn, jcn) 1-based with values a
 * (a may be null for the analysis); nschur > 0 keeps the equations
 * schur_list (1-based) as a Schur block returned into schur (nschur^2,
 * rank 0); rhs (n x nrhs) is replaced by the solutions. Returns INFOG(1);
 * infog[80], info[80] and rinfog[40] receive MUMPS' statistics. */
int cfe_mumps_job(int h, int job, int n, long long nnz, int *irn, int *jcn, double *a, int nschur,
                  int *schur_list, double *schur, int nrhs, double *rhs, int *infog, int *info, double *rinfog)
{
  DMUMPS_STRUC_C *id = &inst[h];
  id->n = n;
  id->nnz = (MUMPS_INT8)nnz;
  id->nz = nnz <= 2147483647LL ? (MUMPS_INT)nnz : 0;
  id->irn = irn;
  id->jcn = jcn;
  id->a = a;
  id->size_schur = nschur;
  id->listvar_schur = nschur > 0 ? schur_list : 0;
  id->schur = nschur > 0 ? schur : 0;
  id->schur_lld = nschur;
  id->nrhs = nrhs;
  id->lrhs = n;
  id->rhs = rhs;
  broadcast(CMD_JOB, h, job);
  run_job(h, job);
  memcpy(infog, id->infog, 80 * sizeof(int));
  memcpy(info, id->info, 80 * sizeof(int));
  memcpy(rinfog, id->rinfog, 40 * sizeof(double));
  return id->infog[0];
}

/* The equations (1-based) of the null pivots of the last factorisation,
 * at most max of them; returns how many MUMPS found (INFOG(28)). */
int cfe_mumps_null_pivots(int h, int *list, int max)
{
  int k, cnt = inst[h].infog[27];
  for (k = 0; k < cnt && k < max; k++) list[k] = inst[h].pivnul_list[k];
  return cnt;
}

#else /* no MUMPS in this build: one rank, no instance */

int cfe_mumps_available(void) { return 0; }
int cfe_mpi_start(int force) { (void)force; return 1; }
int cfe_mpi_rank(void) { return 0; }
void cfe_mpi_worker_loop(void) {}
int cfe_mumps_new(int sym) { (void)sym; return -1; }
void cfe_mumps_free(int h) { (void)h; }
void cfe_mumps_get_control(int h, int *icntl, double *cntl)
{
  (void)h;
  memset(icntl, 0, 60 * sizeof(int));
  memset(cntl, 0, 15 * sizeof(double));
}
void cfe_mumps_set_control(int h, const int *icntl, const double *cntl) { (void)h; (void)icntl; (void)cntl; }
int cfe_mumps_job(int h, int job, int n, long long nnz, int *irn, int *jcn, double *a, int nschur,
                  int *schur_list, double *schur, int nrhs, double *rhs, int *infog, int *info, double *rinfog)
{
  (void)h; (void)job; (void)n; (void)nnz; (void)irn; (void)jcn; (void)a; (void)nschur;
  (void)schur_list; (void)schur; (void)nrhs; (void)rhs;
  memset(infog, 0, 80 * sizeof(int));
  memset(info, 0, 80 * sizeof(int));
  memset(rinfog, 0, 40 * sizeof(double));
  infog[0] = -999;
  return -999;
}
int cfe_mumps_null_pivots(int h, int *list, int max) { (void)h; (void)list; (void)max; return 0; }

#endif
