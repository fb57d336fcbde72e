/* The thread policy of the run (blas_info.f90 calls it).
 *
 * cfe2d's element loops (tangents, internal forces, stresses: assembly.f90)
 * run on a team of OpenMP threads: OMP_NUM_THREADS of them when the
 * variable is set, one otherwise (today's behaviour, and the bench's
 * one-thread rows). Their results do not depend on the count: each
 * element's arrays go to storage of their own and the sums are made in
 * element order afterwards.
 *
 * CHOLMOD 3 runs OpenMP loops of its own, asking for a fixed team of 4
 * threads whatever the cores, while the pthread OpenBLAS it calls keeps a
 * team of its own: on a small machine the two spin against each other
 * (system time as large as user time). So outside the element loops no
 * OpenMP level is active (CHOLMOD's loops run on one thread) unless
 * OMP_MAX_ACTIVE_LEVELS or OMP_THREAD_LIMIT says otherwise, and the BLAS
 * runs on one thread unless OPENBLAS_NUM_THREADS or GOTO_NUM_THREADS says
 * otherwise (OMP_NUM_THREADS is the element team's, no longer the BLAS's).
 * An element loop opens one level for its team (cfe_team_open) and closes
 * it when done (cfe_team_close).
 *
 * libgomp's waiting threads spin at every barrier before they sleep: on
 * two cores shared with other work (load 6) a 2-thread run of the default
 * flagship took 16.7 s against 2.3 s on one thread, and 2.3 s with
 * OMP_WAIT_POLICY=PASSIVE. libgomp reads that variable before main, so it
 * is the user's to set (README, docs/benchmark.md); the program does not
 * change its own environment.
 *
 * The entry points are looked up at run time: libgomp comes in with
 * -fopenmp and as CHOLMOD's dependency, and another BLAS may lack
 * openblas_set_num_threads; what is absent is left alone. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdlib.h>

typedef void (*set_int_fn)(int);
typedef int (*get_int_fn)(void);

static int levels_closed = 0;   /* the policy set max-active-levels to 0 */
static int team = 1;            /* threads of the element loops */
static set_int_fn set_levels = NULL;

static void *entry(const char *name)
{
    return dlsym(RTLD_DEFAULT, name);
}

static int set_if_present(const char *name, int value)
{
    set_int_fn f;
    *(void **) &f = entry(name);   /* POSIX's way to a function */
    if (f == NULL) return 0;
    f(value);
    return 1;
}

static int any_set(const char *const *names)
{
    for (; *names != NULL; names++) {
        const char *v = getenv(*names);
        if (v != NULL && *v != '\0') return 1;
    }
    return 0;
}

/* Applies the policy once per process. */
static void apply_policy(void)
{
    static int done = 0;
    static const char *const team_vars[] = {"OMP_NUM_THREADS", NULL};
    static const char *const level_vars[] = {"OMP_MAX_ACTIVE_LEVELS", "OMP_THREAD_LIMIT", NULL};
    static const char *const blas_vars[] = {"OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", NULL};
    get_int_fn max_threads;
    if (done) return;
    done = 1;
    if (any_set(team_vars)) {
        /* libgomp has read OMP_NUM_THREADS (its first value of a list) */
        *(void **) &max_threads = entry("omp_get_max_threads");
        if (max_threads != NULL && max_threads() > 1) team = max_threads();
    }
    *(void **) &set_levels = entry("omp_set_max_active_levels");
    /* no active parallel level: every OpenMP region runs on one thread,
     * whatever num_threads clause it carries */
    if (!any_set(level_vars) && set_levels != NULL) {
        set_levels(0);
        levels_closed = 1;
    }
    if (!any_set(blas_vars)) set_if_present("openblas_set_num_threads", 1);
}

/* Returns the BLAS thread count after the policy, or -1 if the BLAS does
 * not say. */
int cfe_solver_threads(void)
{
    get_int_fn get;
    apply_policy();
    *(void **) &get = entry("openblas_get_num_threads");
    return get != NULL ? get() : -1;
}

/* The element loops' team: OMP_NUM_THREADS if set, else 1. */
int cfe_element_threads(void)
{
    apply_policy();
    return team;
}

/* An element loop's team starts: one active level (if the policy closed
 * them), so that its parallel region runs on the team. */
void cfe_team_open(void)
{
    apply_policy();
    if (levels_closed && team > 1) set_levels(1);
}

/* ... and ends: no active level again, for CHOLMOD's loops. */
void cfe_team_close(void)
{
    if (levels_closed && team > 1) set_levels(0);
}
