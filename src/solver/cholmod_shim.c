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
#include <stdlib.h>
#include <string.h>
#include <cholmod.h>

/* Return codes of cfe_cholmod_factor (cholmod_binding mirrors them). */
enum { CFE_OK = 0, CFE_NOT_POSDEF = 1, CFE_FAILED = -1 };

typedef struct {
    cholmod_common c;
    cholmod_factor *L;
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
    h->c.nmethods = 1;
    h->c.method[0].ordering = perm != NULL ? CHOLMOD_GIVEN : CHOLMOD_AMD;
    h->L = perm != NULL ? cholmod_analyze_p(&a, perm, NULL, 0, &h->c) : cholmod_analyze(&a, &h->c);
    if (h->L == NULL || h->c.status < CHOLMOD_OK) return h->c.status < 0 ? h->c.status : CFE_FAILED;
    *lnz = h->c.lnz;
    return CFE_OK;
}

/* Diagonal entry k (permuted numbering) of a numerically factored L. */
static double diag_of_l(const cholmod_factor *L, size_t k)
{
    const double *x = L->x;
    if (L->is_super) {
        const int *super = L->super, *pi = L->pi, *px = L->px;
        size_t s;
        /* supernodes hold consecutive columns: find the one holding k */
        size_t lo = 0, hi = L->nsuper;
        while (hi - lo > 1) {
            size_t mid = (lo + hi) / 2;
            if ((size_t) super[mid] <= k) lo = mid; else hi = mid;
        }
        s = lo;
        size_t nsrow = (size_t) (pi[s + 1] - pi[s]), j = k - (size_t) super[s];
        return x[(size_t) px[s] + j + j * nsrow];
    }
    return x[((const int *) L->p)[k]];
}

/* Numeric factorisation of the analysed pattern with values ax.
 * On CFE_NOT_POSDEF, *col is the column (caller's numbering) of the pivot
 * that was not positive. On CFE_OK, *ratio is the smallest pivot L(k,k)^2
 * relative to the matrix's own diagonal entry (the share of that entry's
 * stiffness left after elimination; round-off sized for a free mode) and
 * *col its column. Returns CFE_OK, CFE_NOT_POSDEF or a negative status. */
int cfe_cholmod_factor(void *handle, int n, int *ap, int *ai, double *ax, double *ratio, int *col)
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
    for (size_t k = 0; k < L->n; k++) {
        int j = perm != NULL ? perm[k] : (int) k;
        /* sorted columns: the diagonal is the last entry of column j */
        double ajj = ap[j + 1] > ap[j] && ai[ap[j + 1] - 1] == j ? ax[ap[j + 1] - 1] : 0.0;
        double d = diag_of_l(L, k);
        double pivot = L->is_ll ? d * d : d;   /* LL' or LDL' */
        double r = ajj > 0.0 ? pivot / ajj : 0.0;
        if (r < *ratio || *col < 0) {
            *ratio = r;
            *col = j;
        }
    }
    return CFE_OK;
}

/* min(diag(L)) / max(diag(L)) of the last factorisation. */
double cfe_cholmod_rcond(void *handle)
{
    cfe_cholmod *h = handle;
    return h->L != NULL ? cholmod_rcond(h->L, &h->c) : 0.0;
}

/* Solves A X = B in place for nrhs columns of length n stored one after
 * the other in b. Returns 0, or the (negative) CHOLMOD status. */
int cfe_cholmod_solve(void *handle, int n, int nrhs, double *b)
{
    cfe_cholmod *h = handle;
    cholmod_dense rhs, *x;
    memset(&rhs, 0, sizeof rhs);
    rhs.nrow = (size_t) n;
    rhs.ncol = (size_t) nrhs;
    rhs.nzmax = (size_t) n * (size_t) nrhs;
    rhs.d = (size_t) n;
    rhs.x = b;
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    x = cholmod_solve(CHOLMOD_A, h->L, &rhs, &h->c);
    if (x == NULL) return h->c.status < 0 ? h->c.status : CFE_FAILED;
    memcpy(b, x->x, rhs.nzmax * sizeof(double));
    cholmod_free_dense(&x, &h->c);
    return CFE_OK;
}
