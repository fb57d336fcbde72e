/* CHOLMOD behind an opaque handle for the Fortran side (cholmod_binding).
 *
 * Fortran never sees a CHOLMOD struct: the layouts of cholmod_common,
 * cholmod_sparse, cholmod_dense and cholmod_factor differ between CHOLMOD
 * versions, and only a C compiler reading the installed cholmod.h gets
 * them right. The shim uses the int-index, double-precision public API of
 * cholmod.h only, which CHOLMOD 3 and later provide alike.
 *
 * Matrices come in as 0-based compressed columns of the upper triangle of
 * a symmetric matrix; column indices handed back are 0-based in the
 * caller's numbering. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>
#include <cholmod.h>

/* Return codes of cfe_cholmod_factor (cholmod_binding mirrors them). */
enum { CFE_OK = 0, CFE_NOT_POSDEF = 1, CFE_FAILED = -1 };

typedef struct {
    cholmod_common c;
    cholmod_factor *L;
    int nlast;                 /* trailing equations kept last (condensed solve) */
    cholmod_dense *X, *Y, *E;  /* cholmod_solve2's workspace, kept between solves */
} cfe_cholmod;

/* A cholmod_sparse header over the caller's arrays (nothing copied). */
static cholmod_sparse upper_view(int n, int *ap, int *ai, double *ax)
{
    cholmod_sparse a;
    memset(&a, 0, sizeof a);
    a.nrow = (size_t) n;
    a.ncol = (size_t) n;
    a.nzmax = (size_t) ap[n];
    a.p = ap;
    a.i = ai;
    a.x = ax;
    a.stype = 1;
    a.itype = CHOLMOD_INT;
    a.xtype = CHOLMOD_REAL;
    a.dtype = CHOLMOD_DOUBLE;
    a.sorted = 1;
    a.packed = 1;
    return a;
}

/* Library version at run time (major, minor, patch). */
void cfe_cholmod_version(int v[3])
{
    cholmod_version(v);
}

/* Version of the cholmod.h this shim was compiled against. */
void cfe_cholmod_header_version(int v[3])
{
    v[0] = CHOLMOD_MAIN_VERSION;
    v[1] = CHOLMOD_SUB_VERSION;
    v[2] = CHOLMOD_SUBSUB_VERSION;
}

/* A new CHOLMOD workspace, or NULL. Always the supernodal LL'
 * factorisation: it stops at a pivot that is not positive, whereas the
 * simplicial LDL' would factor an indefinite matrix silently. */
void *cfe_cholmod_start(void)
{
    cfe_cholmod *h = calloc(1, sizeof *h);
    if (h == NULL) return NULL;
    if (!cholmod_start(&h->c)) {
        free(h);
        return NULL;
    }
    h->c.print = 0;
    h->c.supernodal = CHOLMOD_SUPERNODAL;
    h->c.quick_return_if_not_posdef = 1;
    h->L = NULL;
    return h;
}

void cfe_cholmod_finish(void *handle)
{
    cfe_cholmod *h = handle;
    if (h == NULL) return;
    if (h->L != NULL) cholmod_free_factor(&h->L, &h->c);
    if (h->X != NULL) cholmod_free_dense(&h->X, &h->c);
    if (h->Y != NULL) cholmod_free_dense(&h->Y, &h->c);
    if (h->E != NULL) cholmod_free_dense(&h->E, &h->c);
    cholmod_finish(&h->c);
    free(h);
}

/* Fill-reducing ordering and symbolic factorisation: AMD, or the given
 * 0-based permutation perm (perm[new] = old) when perm is not NULL.
 * lnz: entries of L. Returns 0, or the (negative) CHOLMOD status. */
int cfe_cholmod_analyse(void *handle, int n, int *ap, int *ai, double *ax, int *perm, double *lnz)
{
    cfe_cholmod *h = handle;
    cholmod_sparse a = upper_view(n, ap, ai, ax);
    if (h->L != NULL) cholmod_free_factor(&h->L, &h->c);
    h->nlast = 0;
    h->c.nmethods = 1;
    h->c.postorder = 1;
    h->c.method[0].ordering = perm != NULL ? CHOLMOD_GIVEN : CHOLMOD_AMD;
    h->L = perm != NULL ? cholmod_analyze_p(&a, perm, NULL, 0, &h->c) : cholmod_analyze(&a, &h->c);
    if (h->L == NULL || h->c.status < CHOLMOD_OK) return h->c.status < 0 ? h->c.status : CFE_FAILED;
    *lnz = h->c.lnz;
    return CFE_OK;
}

/* d[k] = L(k,k), the diagonal of a numerically factored L (factor order),
 * read supernode by supernode (or column by column when simplicial). */
static void diagonal_of_l(const cholmod_factor *L, double *d)
{
    const double *x = L->x;
    if (L->is_super) {
        const int *super = L->super, *pi = L->pi, *px = L->px;
        for (size_t s = 0; s < L->nsuper; s++) {
            size_t nsrow = (size_t) (pi[s + 1] - pi[s]);
            for (size_t k = (size_t) super[s]; k < (size_t) super[s + 1]; k++) {
                size_t j = k - (size_t) super[s];
                d[k] = x[(size_t) px[s] + j + j * nsrow];
            }
        }
    } else {
        const int *p = L->p;
        for (size_t k = 0; k < L->n; k++) d[k] = x[p[k]];
    }
}

/* Numeric factorisation of the analysed pattern with values ax.
 * On CFE_NOT_POSDEF, *col is the column (caller's numbering) of the pivot
 * that was not positive. On CFE_OK, *ratio is the smallest pivot L(k,k)^2
 * relative to the matrix's own diagonal entry (the share of that entry's
 * stiffness left after elimination; round-off sized for a free mode) and
 * *col its column. The last nskip pivots are not judged: a condensed
 * solve judges the trailing block itself (it factors a Schur complement
 * of its own). Returns CFE_OK, CFE_NOT_POSDEF or a negative status. */
int cfe_cholmod_factor(void *handle, int n, int *ap, int *ai, double *ax, int nskip, double *ratio, int *col)
{
    cfe_cholmod *h = handle;
    cholmod_sparse a = upper_view(n, ap, ai, ax);
    cholmod_factor *L = h->L;
    const int *perm;
    *ratio = 1.0;
    *col = -1;
    if (L == NULL) return CFE_FAILED;
    cholmod_factorize(&a, L, &h->c);
    perm = L->Perm;
    if (h->c.status == CHOLMOD_NOT_POSDEF) {
        if (L->minor < L->n && perm != NULL) *col = perm[L->minor];
        return CFE_NOT_POSDEF;
    }
    if (h->c.status < CHOLMOD_OK) return h->c.status;
    double *diag = malloc(L->n * sizeof *diag);
    if (diag == NULL) return CFE_FAILED;
    diagonal_of_l(L, diag);
    for (size_t k = 0; k + (size_t) nskip < L->n; k++) {
        int j = perm != NULL ? perm[k] : (int) k;
        /* sorted columns: the diagonal is the last entry of column j */
        double ajj = ap[j + 1] > ap[j] && ai[ap[j + 1] - 1] == j ? ax[ap[j + 1] - 1] : 0.0;
        double pivot = L->is_ll ? diag[k] * diag[k] : diag[k];   /* LL' or LDL' */
        double r = ajj > 0.0 ? pivot / ajj : 0.0;
        if (r < *ratio || *col < 0) {
            *ratio = r;
            *col = j;
        }
    }
    free(diag);
    /* the workspace in Common (n-sized integer arrays) is made again by
     * the next factorisation; the solves do without it */
    cholmod_free_work(&h->c);
    return CFE_OK;
}

/* min(diag(L)) / max(diag(L)) of the last factorisation. */
double cfe_cholmod_rcond(void *handle)
{
    cfe_cholmod *h = handle;
    return h->L != NULL ? cholmod_rcond(h->L, &h->c) : 0.0;
}

/* A dense header over the caller's n x nrhs column-major array. */
static cholmod_dense dense_view(int n, int nrhs, double *b)
{
    cholmod_dense d;
    memset(&d, 0, sizeof d);
    d.nrow = (size_t) n;
    d.ncol = (size_t) nrhs;
    d.nzmax = (size_t) n * (size_t) nrhs;
    d.d = (size_t) n;
    d.x = b;
    d.xtype = CHOLMOD_REAL;
    d.dtype = CHOLMOD_DOUBLE;
    return d;
}

/* One cholmod_solve2 of system sys on b (n x nrhs) in place; the result
 * and workspace stay allocated in the handle, so repeated solves do not
 * allocate (and the kernel does not clear fresh pages each time). */
static int solve_in_place(cfe_cholmod *h, int sys, int n, int nrhs, double *b)
{
    cholmod_dense rhs = dense_view(n, nrhs, b);
    if (!cholmod_solve2(sys, h->L, &rhs, NULL, &h->X, NULL, &h->Y, &h->E, &h->c))
        return h->c.status < 0 ? h->c.status : CFE_FAILED;
    memcpy(b, h->X->x, rhs.nzmax * sizeof(double));
    return CFE_OK;
}

/* Solves A X = B in place for nrhs columns of length n stored one after
 * the other in b. Returns 0, or the (negative) CHOLMOD status. */
int cfe_cholmod_solve(void *handle, int n, int nrhs, double *b)
{
    return solve_in_place(handle, CHOLMOD_A, n, nrhs, b);
}

/* Ordering with the last nlast equations kept last, and symbolic
 * analysis. perm (0-based, perm[new] = old, size n) is used when not NULL
 * and must already end with the last block; otherwise CAMD orders the
 * leading equations with the last block as a second constraint set.
 * CHOLMOD's postordering may move columns across the blocks, so the final
 * permutation is checked, and the analysis repeated without postordering
 * if the block did not stay last. lnz: entries of L; flops: its
 * factorisation's floating-point operations. Returns 0, CFE_FAILED if the
 * block cannot be kept last, or the (negative) CHOLMOD status. */
int cfe_cholmod_analyse_last(void *handle, int n, int *ap, int *ai, double *ax, int nlast, int *perm,
                             double *lnz, double *flops)
{
    cfe_cholmod *h = handle;
    cholmod_sparse a = upper_view(n, ap, ai, ax);
    int *p = perm, *cmember = NULL, ok = 0;
    if (h->L != NULL) cholmod_free_factor(&h->L, &h->c);
    h->nlast = 0;
    if (p == NULL) {
        p = malloc((size_t) n * sizeof *p);
        cmember = malloc((size_t) n * sizeof *cmember);
        if (p == NULL || cmember == NULL) {
            free(p);
            free(cmember);
            return CFE_FAILED;
        }
        for (int i = 0; i < n; i++) cmember[i] = i >= n - nlast;
        if (!cholmod_camd(&a, NULL, 0, cmember, p, &h->c)) {
            free(p);
            free(cmember);
            return h->c.status < 0 ? h->c.status : CFE_FAILED;
        }
    }
    h->c.nmethods = 1;
    h->c.method[0].ordering = CHOLMOD_GIVEN;
    for (int post = 1; post >= 0 && !ok; post--) {
        h->c.postorder = post;
        if (h->L != NULL) cholmod_free_factor(&h->L, &h->c);
        h->L = cholmod_analyze_p(&a, p, NULL, 0, &h->c);
        if (h->L == NULL || h->c.status < CHOLMOD_OK) break;
        ok = 1;
        for (int k = n - nlast; k < n && ok; k++) ok = ((const int *) h->L->Perm)[k] >= n - nlast;
    }
    h->c.postorder = 1;
    if (cmember != NULL) {
        free(p);
        free(cmember);
    }
    if (h->L == NULL || h->c.status < CHOLMOD_OK) return h->c.status < 0 ? h->c.status : CFE_FAILED;
    if (!ok) return CFE_FAILED;
    h->nlast = nlast;
    *lnz = h->c.lnz;
    *flops = h->c.fl;
    return CFE_OK;
}

/* tperm[k] (0-based) = the trailing equation (0-based within the last
 * block) at trailing position k of the factor. */
void cfe_cholmod_trailing_order(void *handle, int *tperm)
{
    cfe_cholmod *h = handle;
    int n = (int) h->L->n, m = h->nlast;
    const int *perm = h->L->Perm;
    for (int k = 0; k < m; k++) tperm[k] = perm[n - m + k] - (n - m);
}

/* The trailing m x m block L22 of the numerically factored L (column-major,
 * lower triangle, zero above), read from the factor's own layout. Then
 * L22 L22' is the Schur complement of the leading block. Returns CFE_OK
 * or CFE_FAILED (not factored, or not LL'). */
int cfe_cholmod_trailing_block(void *handle, int m, double *l22)
{
    cfe_cholmod *h = handle;
    const cholmod_factor *L = h->L;
    size_t n, first;
    if (L == NULL || !L->is_ll || L->x == NULL || m != h->nlast) return CFE_FAILED;
    n = L->n;
    first = n - (size_t) m;
    memset(l22, 0, (size_t) m * (size_t) m * sizeof *l22);
    if (L->is_super) {
        const int *super = L->super, *pi = L->pi, *px = L->px, *ls = L->s;
        const double *x = L->x;
        for (size_t s = 0; s < L->nsuper; s++) {
            size_t k1 = (size_t) super[s], k2 = (size_t) super[s + 1];
            size_t nsrow = (size_t) (pi[s + 1] - pi[s]);
            if (k2 <= first) continue;
            for (size_t j = k1 > first ? k1 : first; j < k2; j++) {
                /* rows of column j: the supernode's rows from its diagonal down */
                for (size_t r = j - k1; r < nsrow; r++) {
                    size_t row = (size_t) ls[pi[s] + r];
                    l22[(row - first) + (j - first) * (size_t) m] = x[(size_t) px[s] + r + (j - k1) * nsrow];
                }
            }
        }
    } else {
        const int *lp = L->p, *li = L->i, *lnz = L->nz;
        const double *x = L->x;
        for (size_t j = first; j < n; j++)
            for (int q = lp[j]; q < lp[j] + lnz[j]; q++)
                l22[((size_t) li[q] - first) + (j - first) * (size_t) m] = x[q];
    }
    return CFE_OK;
}

/* Forward half of a solve in the factor's order: b := L \ (P b). */
int cfe_cholmod_forward(void *handle, int n, double *b)
{
    cfe_cholmod *h = handle;
    int st = solve_in_place(h, CHOLMOD_P, n, 1, b);
    return st == CFE_OK ? solve_in_place(h, CHOLMOD_L, n, 1, b) : st;
}

/* Backward half: b := P' (L' \ b). */
int cfe_cholmod_backward(void *handle, int n, double *b)
{
    cfe_cholmod *h = handle;
    int st = solve_in_place(h, CHOLMOD_Lt, n, 1, b);
    return st == CFE_OK ? solve_in_place(h, CHOLMOD_Pt, n, 1, b) : st;
}

/* CHOLMOD's OpenMP regions under a policy of one thread (thread_shim.c:
 * no active parallel level unless the environment asks for one). libgomp
 * still makes a team of one for every region and, at its end, wakes the
 * team's barrier with a futex system call; CHOLMOD's supernodal
 * factorisation opens several regions per supernode: 895 654 system calls
 * on the 1e6-dof square (strace -c), 47 117 on the flagship, about 0.1 s
 * of system and 0.1 to 0.3 s of user time on the square. GOMP_parallel is
 * the entry gcc compiles a parallel region to, and the libraries bind to
 * the program's definition of it: a region that would run on one thread
 * (asked for one, or no active level allowed) is called here directly, as
 * its team's one thread would run it; any other goes to libgomp's. Inside
 * the region omp_get_num_threads() is 1 and omp_get_thread_num() 0 either
 * way, which is all CHOLMOD asks of OpenMP (nm -D libcholmod.so). */
typedef void (*gomp_parallel_fn)(void (*)(void *), void *, unsigned, unsigned);
typedef int (*omp_int_fn)(void);
static gomp_parallel_fn libgomp_parallel = NULL;
static omp_int_fn max_active_levels = NULL;

/* libgomp's entries, looked up once before main (libgomp, a dependency of
 * CHOLMOD's, is loaded and initialised by then). */
__attribute__((constructor)) static void find_libgomp(void)
{
    *(void **) &libgomp_parallel = dlsym(RTLD_NEXT, "GOMP_parallel");
    *(void **) &max_active_levels = dlsym(RTLD_DEFAULT, "omp_get_max_active_levels");
}

void GOMP_parallel(void (*fn)(void *), void *data, unsigned num_threads, unsigned flags)
{
    if (libgomp_parallel == NULL || num_threads == 1 || (max_active_levels != NULL && max_active_levels() < 1)) {
        fn(data);
        return;
    }
    libgomp_parallel(fn, data, num_threads, flags);
}
