/* src/core/lemke.c - Lemke's complementary pivoting for w = Mz + q, 0 <= z ⊥ w >= 0 (seed 002 (1.10);
 * Cottle, Pang & Stone, The Linear Complementarity Problem, §4.4), with the lexicographic ratio test.
 *
 * The tableau holds w - M z - e z0 = q in m rows of 2m + 2 columns: w (0..m), z (m..2m), z0 (2m), rhs
 * (2m + 1). Its w columns are the basis inverse, so the lexicographic rule compares rows of [rhs, B^-1]
 * divided by the pivot column: each row stays lexicographically positive, no basis repeats, and a degenerate
 * problem cannot cycle. The problem is scaled by 1/max|M_ij| first (z is unchanged, w scales), so the pivot
 * tolerances below are relative. The solution is read from the final basis and recomputed from its linear
 * system M_aa z_a = -q_a by LU with one step of refinement, so it is exact to rounding whatever the pivots did.
 * The problem is copied once into plain arrays: the loops read contiguous memory, not GSL accessors.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/lcp.h"
#include "dashpot/status.h"

/* A pivot entry must exceed this fraction of its column's largest entry (plus an absolute floor on the
 * scaled problem, where entries are O(1)): smaller ones are rounding noise of entries that are exactly zero. */
#define PIVOT_REL 1e-11
#define PIVOT_ABS 1e-13
/* Two ratios are a tie when they agree to this relative tolerance; the next column then decides. */
#define TIE_REL 1e-12

struct dp_lcp {
    size_t m, cols;
    double *T;           /* m x cols, row-major */
    size_t *basis;       /* basis[r] = the column basic in row r */
    double *a, *b, *x, *res; /* m x m LU scratch, rhs, solution, residual */
    double *z1, *w1;     /* the refined candidate */
    double *M, *q;       /* the problem, row-major */
    size_t *idx;         /* the basic z's */
    char *isbasic;       /* per column of w, z, z0 */
    char *zbasic;        /* per z: basic at the end */
    size_t *cols_live;   /* the columns a pivot changes */
    size_t *perm;
};

dp_lcp *dp_lcp_alloc(size_t m)
{
    if (m == 0 || m > DP_LCP_MAX)
        return NULL;
    dp_lcp *w = calloc(1, sizeof *w);
    if (w == NULL)
        return NULL;
    w->m = m;
    w->cols = 2 * m + 2;
    w->T = malloc(m * w->cols * sizeof *w->T);
    w->basis = malloc(m * sizeof *w->basis);
    w->a = malloc(m * m * sizeof *w->a);
    w->b = malloc(m * sizeof *w->b);
    w->x = malloc(m * sizeof *w->x);
    w->res = malloc(m * sizeof *w->res);
    w->perm = malloc(m * sizeof *w->perm);
    w->z1 = malloc(m * sizeof *w->z1);
    w->w1 = malloc(m * sizeof *w->w1);
    w->M = malloc(m * m * sizeof *w->M);
    w->q = malloc(m * sizeof *w->q);
    w->idx = malloc(m * sizeof *w->idx);
    w->isbasic = malloc(2 * m + 1);
    w->zbasic = malloc(m);
    w->cols_live = malloc((2 * m + 2) * sizeof *w->cols_live);
    if (!w->isbasic || !w->zbasic || !w->cols_live ||
        !w->T || !w->basis || !w->a || !w->b || !w->x || !w->res || !w->perm || !w->z1 || !w->w1 || !w->M || !w->q ||
        !w->idx) {
        dp_lcp_free(w);
        return NULL;
    }
    return w;
}

void dp_lcp_free(dp_lcp *w)
{
    if (w == NULL)
        return;
    free(w->T);
    free(w->basis);
    free(w->a);
    free(w->b);
    free(w->x);
    free(w->res);
    free(w->perm);
    free(w->z1);
    free(w->w1);
    free(w->M);
    free(w->q);
    free(w->idx);
    free(w->isbasic);
    free(w->zbasic);
    free(w->cols_live);
    free(w);
}

/* The problem as plain row-major arrays (M may be a view with a row stride): one copy, O(m^2), then every
 * loop below reads contiguous memory. 0 when an entry is not finite. */
static int load(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q)
{
    size_t m = w->m;
    for (size_t i = 0; i < m; i++) {
        const double *row = M->data + i * M->tda;
        double *dst = w->M + i * m;
        for (size_t j = 0; j < m; j++) {
            if (!isfinite(row[j]))
                return 0;
            dst[j] = row[j];
        }
        w->q[i] = q->data[i * q->stride];
        if (!isfinite(w->q[i]))
            return 0;
    }
    return 1;
}

/* Gauss-Jordan pivot on (r, e): column e becomes the unit vector e_r. Only the columns that change are
 * touched: the non-basic ones, the leaving variable's (a unit vector until now) and the right-hand side; the
 * other basic columns are unit vectors with a zero in row r, which the pivot leaves as they are. That is
 * m + 3 columns of the 2m + 2, half the work of a full tableau pivot. */
static void pivot(dp_lcp *w, size_t r, size_t e)
{
    size_t m = w->m, c = w->cols, n = 0, leave = w->basis[r], *J = w->cols_live;
    for (size_t j = 0; j <= 2 * m; j++)
        if ((!w->isbasic[j] || j == leave) && j != e)
            J[n++] = j;
    J[n++] = c - 1;
    double *pr = w->T + r * c, inv = 1.0 / pr[e];
    for (size_t k = 0; k < n; k++)
        pr[J[k]] *= inv;
    for (size_t i = 0; i < m; i++) {
        double *pi = w->T + i * c, f = pi[e];
        if (i == r || f == 0.0)
            continue;
        for (size_t k = 0; k < n; k++)
            pi[J[k]] -= f * pr[J[k]];
        pi[e] = 0.0;
    }
    pr[e] = 1.0;
    w->isbasic[leave] = 0;
    w->isbasic[e] = 1;
    w->basis[r] = e;
}

static int tie(double x, double y)
{
    return fabs(x - y) <= TIE_REL * (1.0 + fmax(fabs(x), fabs(y)));
}

/* Is row i's [rhs, B^-1] / sign-scale lexicographically smaller than row k's? (da, db the divisors.) */
static int lex_less(const dp_lcp *w, size_t i, double da, size_t k, double db)
{
    const double *pi = w->T + i * w->cols, *pk = w->T + k * w->cols;
    double x = pi[w->cols - 1] / da, y = pk[w->cols - 1] / db;
    if (!tie(x, y))
        return x < y;
    for (size_t j = 0; j < w->m; j++) {
        x = pi[j] / da;
        y = pk[j] / db;
        if (!tie(x, y))
            return x < y;
    }
    return i < k; /* identical rows cannot happen (B^-1 is regular); a stable choice anyway */
}

/* The lexicographic minimum ratio row for entering column e, or m when the column gives a ray. */
static size_t ratio_test(const dp_lcp *w, size_t e)
{
    size_t m = w->m, c = w->cols, best = m;
    double colmax = 0;
    for (size_t i = 0; i < m; i++)
        if (w->T[i * c + e] > colmax)
            colmax = w->T[i * c + e];
    double tol = PIVOT_REL * colmax > PIVOT_ABS ? PIVOT_REL * colmax : PIVOT_ABS;
    for (size_t i = 0; i < m; i++) {
        double a = w->T[i * c + e];
        if (a > tol && (best == m || lex_less(w, i, a, best, w->T[best * c + e])))
            best = i;
    }
    return best;
}

static void fill_tableau(dp_lcp *w, double scale)
{
    size_t m = w->m, c = w->cols;
    memset(w->T, 0, m * c * sizeof *w->T);
    for (size_t i = 0; i < m; i++) {
        double *p = w->T + i * c;
        const double *Mi = w->M + i * m;
        p[i] = 1.0;
        for (size_t j = 0; j < m; j++)
            p[m + j] = -Mi[j] / scale;
        p[2 * m] = -1.0;
        p[c - 1] = w->q[i] / scale;
        w->basis[i] = i;
    }
    for (size_t j = 0; j <= 2 * m; j++)
        w->isbasic[j] = j < m;
}

/* The residual of (z, wv) as a solution, in the units of the problem. */
static double residual(const dp_lcp *w, const double *z, const double *wv)
{
    size_t m = w->m;
    double r = 0;
    for (size_t i = 0; i < m; i++) {
        const double *Mi = w->M + i * m;
        double s = w->q[i];
        for (size_t j = 0; j < m; j++)
            s += Mi[j] * z[j];
        r = fmax(r, fabs(s - wv[i]));
        r = fmax(r, fmax(-z[i], -wv[i]));
        r = fmax(r, fabs(fmin(z[i], wv[i])));
    }
    return r;
}

/* x = A^-1 b for the k x k matrix in w->a (overwritten by its LU factors, partial pivoting), b in w->b.
 * 0 when a pivot is below 1e-13 of the largest: singular to working precision. */
static int lu_solve(dp_lcp *w, size_t k)
{
    double *A = w->a, *x = w->x, amax = 0;
    memcpy(x, w->b, k * sizeof *x);
    for (size_t i = 0; i < k * k; i++)
        amax = fmax(amax, fabs(A[i]));
    for (size_t c = 0; c < k; c++) {
        size_t p = c;
        for (size_t i = c + 1; i < k; i++)
            if (fabs(A[i * k + c]) > fabs(A[p * k + c]))
                p = i;
        if (!(fabs(A[p * k + c]) > 1e-13 * amax))
            return 0;
        w->perm[c] = p;
        if (p != c) {
            for (size_t j = 0; j < k; j++) {
                double t = A[c * k + j];
                A[c * k + j] = A[p * k + j], A[p * k + j] = t;
            }
        }
        for (size_t i = c + 1; i < k; i++) {
            double f = A[i * k + c] /= A[c * k + c];
            for (size_t j = c + 1; j < k; j++)
                A[i * k + j] -= f * A[c * k + j];
        }
    }
    return 1;
}

/* Solves with the factors of lu_solve: v = A^-1 v in place. */
static void lu_apply(const dp_lcp *w, size_t k, double *v)
{
    const double *A = w->a;
    for (size_t c = 0; c < k; c++) {
        size_t p = w->perm[c];
        if (p != c) {
            double t = v[c];
            v[c] = v[p], v[p] = t;
        }
        for (size_t i = c + 1; i < k; i++)
            v[i] -= A[i * k + c] * v[c];
    }
    for (size_t c = k; c-- > 0;) {
        for (size_t j = c + 1; j < k; j++)
            v[c] -= A[c * k + j] * v[j];
        v[c] /= A[c * k + c];
    }
}

/* z from the final basis: z_a solves M_aa z_a = -q_a (a = the z's that are basic), with one refinement step
 * against the original entries; w = M z + q, w_a = 0. 0 when M_aa is singular to working precision. */
static int basis_solve(dp_lcp *w, const char *zbasic, double *z, double *wv)
{
    size_t m = w->m, k = 0, *idx = w->idx;
    for (size_t i = 0; i < m; i++)
        if (zbasic[i])
            idx[k++] = i;
    memset(z, 0, m * sizeof *z);
    if (k > 0) {
        for (size_t i = 0; i < k; i++) {
            w->b[i] = -w->q[idx[i]];
            for (size_t j = 0; j < k; j++)
                w->a[i * k + j] = w->M[idx[i] * m + idx[j]];
        }
        if (!lu_solve(w, k))
            return 0;
        lu_apply(w, k, w->x);
        for (size_t i = 0; i < k; i++) {
            double s = -w->b[i];
            for (size_t j = 0; j < k; j++)
                s += w->M[idx[i] * m + idx[j]] * w->x[j];
            w->res[i] = s;
        }
        lu_apply(w, k, w->res);
        for (size_t i = 0; i < k; i++)
            z[idx[i]] = w->x[i] - w->res[i];
    }
    for (size_t i = 0; i < m; i++) {
        const double *Mi = w->M + i * m;
        double s = w->q[i];
        for (size_t j = 0; j < m; j++)
            s += Mi[j] * z[j];
        wv[i] = zbasic[i] ? 0.0 : s;
    }
    return 1;
}

/* The tableau's own values of z and w (used when the basis system is singular). */
static void tableau_values(const dp_lcp *w, double scale, double *z, double *wv)
{
    size_t m = w->m, c = w->cols;
    memset(z, 0, m * sizeof *z);
    memset(wv, 0, m * sizeof *wv);
    for (size_t r = 0; r < m; r++) {
        double v = fmax(w->T[r * c + c - 1], 0.0);
        if (w->basis[r] < m)
            wv[w->basis[r]] = v * scale;
        else if (w->basis[r] < 2 * m)
            z[w->basis[r] - m] = v;
    }
}

static void store(const double *src, gsl_vector *dst)
{
    for (size_t i = 0; i < dst->size; i++)
        dst->data[i * dst->stride] = src[i];
}

/* Reads the solution from the final basis, refines it and clears rounding-size negatives. */
static void finish(dp_lcp *w, double scale, gsl_vector *z, gsl_vector *wv, dp_lcp_result *res)
{
    size_t m = w->m;
    char *zbasic = w->zbasic;
    memset(zbasic, 0, m);
    for (size_t r = 0; r < m; r++)
        if (w->basis[r] >= m && w->basis[r] < 2 * m)
            zbasic[w->basis[r] - m] = 1;
    double *z1 = w->z1, *w1 = w->w1;
    if (basis_solve(w, zbasic, z1, w1)) {
        /* Degenerate bases give basic variables at zero: their rounding noise below zero is cleared. */
        double qmax = 0, zmax = 0;
        for (size_t i = 0; i < m; i++)
            qmax = fmax(qmax, fabs(w->q[i])), zmax = fmax(zmax, z1[i]);
        double tol = 64 * DBL_EPSILON * (qmax + scale * zmax);
        for (size_t i = 0; i < m; i++) {
            if (z1[i] < 0 && z1[i] >= -tol)
                z1[i] = 0.0;
            if (w1[i] < 0 && w1[i] >= -tol)
                w1[i] = 0.0;
        }
        res->residual = residual(w, z1, w1);
        /* The basis' own solution is exact to rounding unless M_aa is badly conditioned: then the
         * tableau's values may be better, and the better of the two is kept. */
        if (res->residual > 1e-12 * (qmax + scale * zmax + 1)) {
            double *z0 = w->b, *w0 = w->res; /* free again after basis_solve */
            tableau_values(w, scale, z0, w0);
            double r0 = residual(w, z0, w0);
            if (r0 < res->residual)
                z1 = z0, w1 = w0, res->residual = r0;
        }
    } else {
        tableau_values(w, scale, z1, w1);
        res->residual = residual(w, z1, w1);
    }
    store(z1, z);
    store(w1, wv);
}

int dp_lcp_lemke(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, gsl_vector *z, gsl_vector *wv,
                 dp_lcp_result *res)
{
    size_t m = w->m;
    if (M->size1 != m || M->size2 != m || q->size != m || z->size != m || wv->size != m)
        return DP_EINVAL;
    if (!load(w, M, q))
        return DP_EINVAL;
    *res = (dp_lcp_result){ DP_LCP_SOLVED, 0, 0.0 };
    size_t r = 0;
    for (size_t i = 1; i < m; i++)
        if (w->q[i] < w->q[r])
            r = i;
    if (w->q[r] >= 0) {
        memset(w->z1, 0, m * sizeof *w->z1);
        store(w->z1, z);
        store(w->q, wv);
        return DP_OK;
    }
    double scale = 0;
    for (size_t i = 0; i < m * m; i++)
        scale = fmax(scale, fabs(w->M[i]));
    if (!(scale > 0))
        scale = 1.0;
    fill_tableau(w, scale);
    /* First pivot: z0 enters at the lexicographically smallest row of [q, I] (all its column entries are -1,
     * so after it every row is lexicographically positive). */
    for (size_t i = 0; i < m; i++)
        if (i != r && lex_less(w, i, 1.0, r, 1.0))
            r = i;
    size_t z0 = 2 * m, entering;
    size_t leaving = w->basis[r];
    pivot(w, r, z0);
    res->pivots = 1;
    /* A lexicographic run visits each basis at most once; this guard only bounds a pathological input. */
    size_t limit = 1000 + 200 * m;
    while (leaving != z0) {
        entering = leaving < m ? leaving + m : leaving - m;
        r = ratio_test(w, entering);
        if (r == m) {
            res->outcome = DP_LCP_RAY;
            tableau_values(w, scale, w->z1, w->w1);
            store(w->z1, z);
            store(w->w1, wv);
            return DP_OK;
        }
        leaving = w->basis[r];
        pivot(w, r, entering);
        if (++res->pivots > limit)
            return DP_ELIMIT;
    }
    finish(w, scale, z, wv, res);
    return DP_OK;
}
