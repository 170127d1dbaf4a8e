/* contact2d: a small C shim over CHOLMOD (SuiteSparse, Debian libsuitesparse-dev) for the static
 * engine (docs/static.md). CHOLMOD's C API passes structs; these functions take and return plain
 * arrays so that Fortran binds them with iso_c_binding (src/solvers/contact2d_cholmod.f90).
 *
 * The matrix is symmetric positive definite, given as lower-triangle triplets (0-based, duplicates
 * summed). Its last `nlast` rows and columns (the contact dofs) are kept last in the elimination
 * order: the leading block is ordered on its node graph, by nested dissection on the node
 * coordinates when they are given, else by METIS (AMD if METIS fails); the trailing block follows
 * in its given order, no postordering. The supernodal factor L = [L11 0; L21 L22] then holds in L22
 * the Cholesky factor of the Schur complement S = K22 - K21 K11^-1 K12 (S = L22 L22^T).
 */
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <suitesparse/cholmod.h>
#include <dlfcn.h>
#include <stddef.h>

/* OpenBLAS, when contact2d is linked against it (CMakeLists.txt, docs/static.md "BLAS" and
 * "Threads"): weak, so that the reference BLAS (no such symbol) links too. libgomp's entry points
 * are weak as well (this file is compiled without -fopenmp; the Fortran side links libgomp). */
extern void openblas_set_num_threads(int) __attribute__((weak));
extern int openblas_get_num_threads(void) __attribute__((weak));
extern int openblas_get_parallel(void) __attribute__((weak));
extern int omp_get_max_threads(void) __attribute__((weak));
extern void omp_set_num_threads(int) __attribute__((weak));
extern int omp_in_parallel(void) __attribute__((weak));

/* BLAS threads around each call into CHOLMOD or LAPACK (docs/static.md "Threads"). The static
 * engine calls them from the main thread with no OpenMP kernel running, so the BLAS gets the run's
 * OpenMP team (omp_get_max_threads: OMP_NUM_THREADS, or the run's own choice) for the call and
 * one thread after, so that a threaded OpenBLAS never runs threads beside the OpenMP kernels.
 * OpenBLAS's OpenMP build runs its threads as libgomp's team (no second pool), and its
 * openblas_set_num_threads also sets the calling thread's OpenMP team (omp_set_num_threads in
 * its goto_set_num_threads): the run's team is put back after each change. Inside an OpenMP
 * parallel region (not the case today) the BLAS is left on one thread. Returns the run's team. */
static int blas_team_begin(void)
{
    int team = omp_get_max_threads ? omp_get_max_threads() : 1;
    if (!openblas_set_num_threads) return team;
    openblas_set_num_threads(omp_in_parallel && omp_in_parallel() ? 1 : team);
    if (omp_set_num_threads) omp_set_num_threads(team);
    return team;
}

static void blas_team_end(int team)
{
    if (!openblas_set_num_threads) return;
    openblas_set_num_threads(1);
    if (omp_set_num_threads) omp_set_num_threads(team);
}

typedef struct {
    cholmod_common common;
    cholmod_factor *L;
    int n;
    int nlast;
    int blas_threads;   /* OpenBLAS threads during the factorisation (1 without OpenBLAS) */
} c2d_chol_t;

/* Nested dissection by coordinates (docs/static.md "Ordering"): split a set of groups at the median
 * of its longer coordinate extent (groups with the same coordinate on one side, so that on a
 * structured mesh the cut is one grid line), take as separator the groups of the lower side that
 * have a neighbour on the upper side, order the two sides recursively, the separator last.
 * Pieces of at most ND_LEAF groups keep their order. adjp/adji: the group graph (CSR, both
 * directions); xy: 2 coordinates per group; out: the group order. O(n log n) (a quickselect per
 * piece). Returns 1 on success. */
#define ND_LEAF 16
/* The k-th smallest key[s[.]] of s[0..len-1] (quickselect, median-of-three pivot; s is permuted). */
static double nd_select(int *s, int len, int k, const double *key)
{
    int lo = 0, hi = len - 1;
    while (hi > lo) {
        int mid = lo + (hi - lo) / 2, i = lo, j = hi;
        double a = key[s[lo]], b = key[s[mid]], c = key[s[hi]];
        double pivot = a < b ? (b < c ? b : (a < c ? c : a)) : (a < c ? a : (b < c ? c : b));
        while (i <= j) {
            while (key[s[i]] < pivot) i++;
            while (key[s[j]] > pivot) j--;
            if (i <= j) {
                int t = s[i]; s[i] = s[j]; s[j] = t;
                i++; j--;
            }
        }
        if (k <= j) hi = j;
        else if (k >= i) lo = i;
        else break;
    }
    return key[s[k]];
}

static int nd_order(int ng, const int *adjp, const int *adji, const double *xy, int *out)
{
    /* an explicit stack of (start, length, stage) ranges of the work array `set`; a range is
     * first split (stage 0), its separator saved at its end, then emitted after its children */
    int *set = malloc(sizeof(int) * (ng > 0 ? ng : 1)), *side = malloc(sizeof(int) * (ng > 0 ? ng : 1));
    int *stack = malloc(sizeof(int) * 3 * (2 * ng + 8)), *tmp = malloc(sizeof(int) * (ng > 0 ? ng : 1));
    double *key = malloc(sizeof(double) * (ng > 0 ? ng : 1));
    int sp = 0, nout = 0, k, ok = 0;
    if (!set || !side || !stack || !tmp || !key) goto out;
    for (k = 0; k < ng; k++) {
        set[k] = k;
        side[k] = -1;
    }
    if (ng > 0) {
        stack[sp++] = 0; stack[sp++] = ng; stack[sp++] = 0;
    }
    while (sp > 0) {
        int stage = stack[--sp], len = stack[--sp], start = stack[--sp];
        int *s = set + start, i, cut, nlow, nsep, nhigh;
        double xmin, xmax, ymin, ymax;
        if (stage == 1) {
            /* children done: emit the separator, kept at the end of the range */
            int nsep1 = len;
            for (i = 0; i < nsep1; i++) out[nout++] = s[i];
            continue;
        }
        if (len <= ND_LEAF) {
            for (i = 0; i < len; i++) out[nout++] = s[i];
            continue;
        }
        xmin = xmax = xy[2 * s[0]];
        ymin = ymax = xy[2 * s[0] + 1];
        for (i = 1; i < len; i++) {
            double x = xy[2 * s[i]], y = xy[2 * s[i] + 1];
            if (x < xmin) xmin = x;
            if (x > xmax) xmax = x;
            if (y < ymin) ymin = y;
            if (y > ymax) ymax = y;
        }
        {
            int axis = (xmax - xmin >= ymax - ymin) ? 0 : 1;
            for (i = 0; i < len; i++) key[s[i]] = xy[2 * s[i] + axis];
        }
        /* the median coordinate (quickselect), then three-way: below | equal | above it */
        {
            double m = nd_select(s, len, len / 2, key);
            int lt = 0, gt = len, q = 0;
            while (q < gt) {
                double kq = key[s[q]];
                if (kq < m) {
                    int t = s[q]; s[q] = s[lt]; s[lt] = t;
                    lt++; q++;
                } else if (kq > m) {
                    int t = s[q]; s[q] = s[--gt]; s[gt] = t;
                } else {
                    q++;
                }
            }
            /* lower side: below and equal (one grid line stays whole), unless nothing is above */
            cut = gt < len ? gt - 1 : lt - 1;
        }
        for (i = 0; i < len; i++) side[s[i]] = i <= cut ? 0 : 1;
        /* separator: lower-side groups with an upper-side neighbour (within this range) */
        nlow = nsep = 0;
        for (i = 0; i <= cut; i++) {
            int g = s[i], p, is_sep = 0;
            for (p = adjp[g]; p < adjp[g + 1]; p++)
                if (side[adji[p]] == 1) {
                    is_sep = 1;
                    break;
                }
            if (is_sep) tmp[len - 1 - nsep++] = g;   /* separators fill tmp from the end */
            else tmp[nlow++] = g;
        }
        nhigh = len - 1 - cut;
        for (i = 0; i < nhigh; i++) tmp[nlow + i] = s[cut + 1 + i];
        /* tmp = [low | high | separator (reversed)] */
        for (i = 0; i < len; i++) {
            side[s[i]] = -1;
        }
        memcpy(s, tmp, sizeof(int) * len);
        /* the separator is emitted after both children: push it first (stage 1), then the children */
        stack[sp++] = start + nlow + nhigh; stack[sp++] = nsep; stack[sp++] = 1;
        stack[sp++] = start + nlow; stack[sp++] = nhigh; stack[sp++] = 0;
        stack[sp++] = start; stack[sp++] = nlow; stack[sp++] = 0;
    }
    ok = nout == ng;
out:
    free(set);
    free(side);
    free(stack);
    free(tmp);
    free(key);
    return ok;
}

/* Order the leading block on the graph of its groups (the mesh nodes: their dofs are consecutive
 * and share one group id), which is 2x smaller with 4x fewer edges than the dof graph and keeps
 * each node's dofs together. With coordinates (xy: 2 per dof), nested dissection by coordinates
 * (nd_order); without, METIS (AMD if METIS fails). perm11 gets the dof permutation. Returns 1 on
 * success. */
static int order_groups(int nfirst, long nnz, const int *ti, const int *tj, const int *group,
                        const double *xy, int *perm11, cholmod_common *c)
{
    int *gid = malloc(sizeof(int) * (nfirst > 0 ? nfirst : 1)), *gstart = malloc(sizeof(int) * (nfirst + 1));
    int *gperm = NULL, *adjp = NULL, *adji = NULL, *fill = NULL;
    double *gxy = NULL;
    int ng = 0, k, ok = 0;
    long m = 0, e;
    cholmod_triplet *T = NULL;
    cholmod_sparse *G = NULL;
    if (!gid || !gstart) goto out;
    for (k = 0; k < nfirst; k++) {
        if (k == 0 || group[k] != group[k - 1]) gstart[ng++] = k;
        gid[k] = ng - 1;
    }
    gstart[ng] = nfirst;
    gperm = malloc(sizeof(int) * (ng > 0 ? ng : 1));
    if (!gperm) goto out;
    if (xy) {
        /* the group graph in both directions from the entries between the first dofs of two
         * groups (one per group pair and element; repeats are harmless) */
        adjp = calloc(ng + 1, sizeof(int));
        fill = malloc(sizeof(int) * (ng > 0 ? ng : 1));
        gxy = malloc(sizeof(double) * 2 * (ng > 0 ? ng : 1));
        if (!adjp || !fill || !gxy) goto out;
        for (e = 0; e < nnz; e++) {
            int a = ti[e], b = tj[e];
            if (a < nfirst && b < nfirst && a == gstart[gid[a]] && b == gstart[gid[b]] && gid[a] != gid[b]) {
                adjp[gid[a] + 1]++;
                adjp[gid[b] + 1]++;
            }
        }
        for (k = 0; k < ng; k++) adjp[k + 1] += adjp[k];
        adji = malloc(sizeof(int) * (adjp[ng] > 0 ? adjp[ng] : 1));
        if (!adji) goto out;
        memcpy(fill, adjp, sizeof(int) * ng);
        for (e = 0; e < nnz; e++) {
            int a = ti[e], b = tj[e];
            if (a < nfirst && b < nfirst && a == gstart[gid[a]] && b == gstart[gid[b]] && gid[a] != gid[b]) {
                adji[fill[gid[a]]++] = gid[b];
                adji[fill[gid[b]]++] = gid[a];
            }
        }
        for (k = 0; k < ng; k++) {
            gxy[2 * k] = xy[2 * gstart[k]];
            gxy[2 * k + 1] = xy[2 * gstart[k] + 1];
        }
        ok = nd_order(ng, adjp, adji, gxy, gperm);
    } else {
        for (e = 0; e < nnz; e++)
            if (ti[e] < nfirst && tj[e] < nfirst && gid[ti[e]] != gid[tj[e]]) m++;
        T = cholmod_allocate_triplet(ng, ng, m > 0 ? m : 1, -1, CHOLMOD_PATTERN, c);
        if (!T) goto out;
        m = 0;
        for (e = 0; e < nnz; e++) {
            if (ti[e] < nfirst && tj[e] < nfirst) {
                int a = gid[ti[e]], b = gid[tj[e]];
                if (a == b) continue;
                ((int *)T->i)[m] = a > b ? a : b;
                ((int *)T->j)[m] = a > b ? b : a;
                m++;
            }
        }
        T->nnz = m;
        G = cholmod_triplet_to_sparse(T, m, c);
        if (!G) goto out;
        ok = cholmod_metis(G, NULL, 0, 1, gperm, c);
        if (!ok) {
            c->status = CHOLMOD_OK;
            ok = cholmod_amd(G, NULL, 0, gperm, c);
        }
    }
    if (ok) {
        int p = 0, q;
        for (k = 0; k < ng; k++)
            for (q = gstart[gperm[k]]; q < gstart[gperm[k] + 1]; q++) perm11[p++] = q;
    }
out:
    free(gid);
    free(gstart);
    free(gperm);
    free(adjp);
    free(adji);
    free(fill);
    free(gxy);
    if (T) cholmod_free_triplet(&T, c);
    if (G) cholmod_free_sparse(&G, c);
    return ok;
}

/* Assemble, order and factorise. Returns 0 on success; 1 allocation/ordering failure, 2 not
 * positive definite (CHOLMOD found a non-positive pivot). pivot_ratio: min_j L_jj^2 / K_jj over
 * all columns (a rigid-body mode shows as a ratio near machine epsilon). */
int c2d_chol_factor(int n, long nnz, const int *ti, const int *tj, const double *tx, int nlast,
                    const int *group, const double *xy, void **handle, double *pivot_ratio)
{
    c2d_chol_t *h = calloc(1, sizeof(c2d_chol_t));
    cholmod_triplet *T = NULL;
    cholmod_sparse *A = NULL;
    int *perm = NULL, nfirst = n - nlast, status = 1, team;
    long k;
    double *diag = NULL;

    *handle = NULL;
    *pivot_ratio = 0.0;
    if (!h) return 1;
    h->n = n;
    h->nlast = nlast;
    team = blas_team_begin();
    h->blas_threads = openblas_get_num_threads ? openblas_get_num_threads() : 1;
    cholmod_start(&h->common);
    h->common.print = 0;
    h->common.supernodal = CHOLMOD_SUPERNODAL;
    h->common.final_ll = 1;

    T = cholmod_allocate_triplet(n, n, nnz, -1, CHOLMOD_REAL, &h->common);
    if (!T) goto done;
    for (k = 0; k < nnz; k++) {
        int i = ti[k], j = tj[k];
        /* lower triangle: row >= column */
        ((int *)T->i)[k] = i > j ? i : j;
        ((int *)T->j)[k] = i > j ? j : i;
        ((double *)T->x)[k] = tx[k];
    }
    T->nnz = nnz;
    A = cholmod_triplet_to_sparse(T, nnz, &h->common);
    if (!A) goto done;

    perm = malloc(sizeof(int) * (n > 0 ? n : 1));
    if (!perm) goto done;
    if (nfirst > 0) {
        if (!order_groups(nfirst, nnz, ti, tj, group, xy, perm, &h->common)) goto done;
    }
    for (k = 0; k < nlast; k++) perm[nfirst + k] = nfirst + (int)k;
    h->common.nmethods = 1;
    h->common.method[0].ordering = CHOLMOD_GIVEN;
    h->common.postorder = 0;
    h->L = cholmod_analyze_p(A, perm, NULL, 0, &h->common);
    if (!h->L) goto done;
    cholmod_factorize(A, h->L, &h->common);
    if (h->common.status == CHOLMOD_NOT_POSDEF) {
        status = 2;
        goto done;
    }
    if (h->common.status != CHOLMOD_OK || !h->L->is_super) goto done;
    /* the trailing dofs must have stayed last (in any order) */
    {
        const int *Lperm = h->L->Perm;
        for (k = 0; k < nlast; k++)
            if (Lperm[nfirst + k] < nfirst) goto done;
    }

    /* smallest pivot relative to the matrix diagonal (both in the permuted order) */
    diag = calloc(n > 0 ? n : 1, sizeof(double));
    if (!diag) goto done;
    {
        const int *Ap = A->p, *Ai = A->i;
        const double *Ax = A->x;
        int j, p;
        for (j = 0; j < n; j++)
            for (p = Ap[j]; p < Ap[j + 1]; p++)
                if (Ai[p] == j) diag[j] += Ax[p];
    }
    {
        const int *super = h->L->super, *pi = h->L->pi, *px = h->L->px, *Lperm = h->L->Perm;
        const double *Lx = h->L->x;
        double ratio = INFINITY;
        size_t s;
        for (s = 0; s < h->L->nsuper; s++) {
            int k1 = super[s], k2 = super[s + 1], nsrow = pi[s + 1] - pi[s], j;
            for (j = k1; j < k2; j++) {
                double ljj = Lx[px[s] + (size_t)(j - k1) * nsrow + (j - k1)];
                double kjj = diag[Lperm[j]];
                double r = kjj > 0 ? ljj * ljj / kjj : 0.0;
                if (r < ratio) ratio = r;
            }
        }
        *pivot_ratio = n > 0 ? ratio : 1.0;
    }
    status = 0;

done:
    blas_team_end(team);
    free(diag);
    free(perm);
    if (T) cholmod_free_triplet(&T, &h->common);
    if (A) cholmod_free_sparse(&A, &h->common);
    if (status != 0) {
        if (h->L) cholmod_free_factor(&h->L, &h->common);
        cholmod_finish(&h->common);
        free(h);
        return status;
    }
    *handle = h;
    return 0;
}

/* The trailing nlast x nlast block L22 of the factor, dense column-major (upper part zero), in
 * the elimination order; order[k] (0-based) is the trailing dof of its k-th row and column. */
int c2d_chol_trailing(void *handle, double *l22, int *order)
{
    c2d_chol_t *h = handle;
    const int *super = h->L->super, *pi = h->L->pi, *px = h->L->px, *Ls = h->L->s;
    const double *Lx = h->L->x;
    int nfirst = h->n - h->nlast, nl = h->nlast, j;
    size_t s;
    memset(l22, 0, sizeof(double) * (size_t)nl * nl);
    for (j = 0; j < nl; j++) order[j] = ((const int *)h->L->Perm)[nfirst + j] - nfirst;
    for (s = 0; s < h->L->nsuper; s++) {
        int k1 = super[s], k2 = super[s + 1], nsrow = pi[s + 1] - pi[s], r;
        if (k2 <= nfirst) continue;
        for (j = k1 > nfirst ? k1 : nfirst; j < k2; j++) {
            for (r = j - k1; r < nsrow; r++) {
                int row = Ls[pi[s] + r];
                l22[(size_t)(j - nfirst) * nl + (row - nfirst)] = Lx[px[s] + (size_t)(j - k1) * nsrow + r];
            }
        }
    }
    return 0;
}

/* x = K^-1 b (length n). Returns 0 on success. */
int c2d_chol_solve(void *handle, const double *b, double *x)
{
    c2d_chol_t *h = handle;
    cholmod_dense *B, *X;
    int team;
    B = cholmod_allocate_dense(h->n, 1, h->n, CHOLMOD_REAL, &h->common);
    if (!B) return 1;
    memcpy(B->x, b, sizeof(double) * h->n);
    team = blas_team_begin();
    X = cholmod_solve(CHOLMOD_A, h->L, B, &h->common);
    blas_team_end(team);
    cholmod_free_dense(&B, &h->common);
    if (!X) return 1;
    memcpy(x, X->x, sizeof(double) * h->n);
    cholmod_free_dense(&X, &h->common);
    return 0;
}

/* Number of nonzeros of L and floating-point operations of the factorisation (CHOLMOD's counts). */
double c2d_chol_lnz(void *handle)
{
    c2d_chol_t *h = handle;
    return h->common.lnz;
}

double c2d_chol_flops(void *handle)
{
    c2d_chol_t *h = handle;
    return h->common.fl;
}

/* OpenBLAS threads the factorisation ran on (docs/static.md "Threads"). */
int c2d_chol_blas_threads(void *handle)
{
    c2d_chol_t *h = handle;
    return h->blas_threads;
}

/* 1 when the BLAS is OpenBLAS's OpenMP build (openblas_get_parallel() == 2), whose threads the
 * static engine's calls get; 0 for a serial or pthreads OpenBLAS or another BLAS (one thread). */
int c2d_blas_openmp(void)
{
    return openblas_get_parallel && openblas_get_parallel() == 2;
}

void c2d_chol_free(void **handle)
{
    c2d_chol_t *h = *handle;
    if (!h) return;
    if (h->L) cholmod_free_factor(&h->L, &h->common);
    cholmod_finish(&h->common);
    free(h);
    *handle = NULL;
}

/* Dense LAPACK for the static engine's own calls (condensation, active-set solves), looked up in
 * the process's global scope (dlsym RTLD_DEFAULT): with OpenBLAS linked (CMakeLists.txt,
 * docs/static.md "BLAS") that is OpenBLAS, because the reference LAPACK/BLAS that the explicit
 * engine uses is linked statically into the program and not exported; without OpenBLAS it is the
 * system's liblapack.so.3. If the lookup fails, the routine linked into the program is called. */
typedef void (*c2d_lauum_t)(const char *, const int *, double *, const int *, int *, size_t);
typedef void (*c2d_potrf_t)(const char *, const int *, double *, const int *, int *, size_t);
typedef void (*c2d_potrs_t)(const char *, const int *, const int *, const double *, const int *, double *,
                            const int *, int *, size_t);
typedef void (*c2d_gesv_t)(const int *, const int *, double *, const int *, int *, double *, const int *, int *);
extern void dlauum_(const char *, const int *, double *, const int *, int *, size_t);
extern void dpotrf_(const char *, const int *, double *, const int *, int *, size_t);
extern void dpotrs_(const char *, const int *, const int *, const double *, const int *, double *, const int *,
                    int *, size_t);
extern void dgesv_(const int *, const int *, double *, const int *, int *, double *, const int *, int *);

static void *c2d_lookup(const char *name, void *fallback)
{
    void *f = dlsym(RTLD_DEFAULT, name);
    return f ? f : fallback;
}

void c2d_dlauum(const char *uplo, const int *n, double *a, const int *lda, int *info)
{
    static c2d_lauum_t f = NULL;
    int team;
    if (!f) f = (c2d_lauum_t)c2d_lookup("dlauum_", (void *)dlauum_);
    team = blas_team_begin();
    f(uplo, n, a, lda, info, 1);
    blas_team_end(team);
}

void c2d_dpotrf(const char *uplo, const int *n, double *a, const int *lda, int *info)
{
    static c2d_potrf_t f = NULL;
    int team;
    if (!f) f = (c2d_potrf_t)c2d_lookup("dpotrf_", (void *)dpotrf_);
    team = blas_team_begin();
    f(uplo, n, a, lda, info, 1);
    blas_team_end(team);
}

void c2d_dpotrs(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda, double *b,
                const int *ldb, int *info)
{
    static c2d_potrs_t f = NULL;
    int team;
    if (!f) f = (c2d_potrs_t)c2d_lookup("dpotrs_", (void *)dpotrs_);
    team = blas_team_begin();
    f(uplo, n, nrhs, a, lda, b, ldb, info, 1);
    blas_team_end(team);
}

void c2d_dgesv(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b, const int *ldb,
               int *info)
{
    static c2d_gesv_t f = NULL;
    int team;
    if (!f) f = (c2d_gesv_t)c2d_lookup("dgesv_", (void *)dgesv_);
    team = blas_team_begin();
    f(n, nrhs, a, lda, ipiv, b, ldb, info);
    blas_team_end(team);
}
