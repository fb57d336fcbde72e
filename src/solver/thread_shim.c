/* The thread policy of the solvers (blas_info.f90 calls it).
 *
 * CHOLMOD 3 runs its own OpenMP loops, asking for a fixed team of 4
 * threads whatever the cores, while the pthread OpenBLAS it calls keeps a
 * team of its own: on a small machine the two spin against each other
 * (system time as large as user time). Unless the environment says
 * otherwise, the OpenMP loops run on one thread and the BLAS on one.
 *
 * The entry points are looked up at run time: libgomp comes in as
 * CHOLMOD's dependency, not on the link line, and another BLAS may lack
 * openblas_set_num_threads; what is absent is left alone. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdlib.h>

typedef void (*set_int_fn)(int);
typedef int (*get_int_fn)(void);

static int set_if_present(const char *name, int value)
{
    set_int_fn f;
    *(void **) &f = dlsym(RTLD_DEFAULT, name);   /* POSIX's way to a function */
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

/* Applies the policy once per process. Returns the BLAS thread count
 * afterwards, or -1 if the BLAS does not say. */
int cfe_solver_threads(void)
{
    static int done = 0;
    static const char *const omp_vars[] = {"OMP_NUM_THREADS", "OMP_THREAD_LIMIT", "OMP_MAX_ACTIVE_LEVELS", NULL};
    static const char *const blas_vars[] = {"OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS", NULL};
    get_int_fn get;
    if (!done) {
        done = 1;
        /* no active parallel level: every OpenMP region runs on one thread,
         * whatever num_threads clause it carries */
        if (!any_set(omp_vars)) set_if_present("omp_set_max_active_levels", 0);
        if (!any_set(blas_vars)) set_if_present("openblas_set_num_threads", 1);
    }
    *(void **) &get = dlsym(RTLD_DEFAULT, "openblas_get_num_threads");
    return get != NULL ? get() : -1;
}
