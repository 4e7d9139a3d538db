/* src/core/lemke.c - Lemke's complementary pivoting for w = Mz + q, 0 <= z ⊥ w >= 0 (seed 002 (1.10);
 * Cottle, Pang & Stone, The Linear Complementarity Problem, §4.4), with the lexicographic ratio test.
 *
 * The tableau holds w - M z - e z0 = q in m rows of 2m + 2 columns: w (0..m), z (m..2m), z0 (2m), rhs
 * (2m + 1). Its w columns are the basis inverse, so the lexicographic rule compares rows of [rhs, B^-1]
 * divided by the pivot column: each row stays lexicographically positive, no basis repeats, and a degenerate
 * problem cannot cycle. The problem is scaled by 1/max|M_ij| first (z is unchanged, w scales), so the pivot
 * tolerances below are relative. The solution is read from the final basis and recomputed from its linear
 * system M_aa z_a = -q_a by LU with one step of refinement, so it is exact to rounding whatever the pivots did.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_permutation.h>

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
    if (!w->T || !w->basis || !w->a || !w->b || !w->x || !w->res || !w->perm || !w->z1 || !w->w1) {
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
    free(w);
}

static double max_abs_matrix(const gsl_matrix *M)
{
    double s = 0;
    for (size_t i = 0; i < M->size1; i++)
        for (size_t j = 0; j < M->size2; j++)
            s = fmax(s, fabs(gsl_matrix_get(M, i, j)));
    return s;
}

static int finite_data(const gsl_matrix *M, const gsl_vector *q)
{
    for (size_t i = 0; i < q->size; i++) {
        if (!isfinite(gsl_vector_get(q, i)))
            return 0;
        for (size_t j = 0; j < q->size; j++)
            if (!isfinite(gsl_matrix_get(M, i, j)))
                return 0;
    }
    return 1;
}

/* Gauss-Jordan pivot on (r, e): column e becomes the unit vector e_r. */
static void pivot(dp_lcp *w, size_t r, size_t e)
{
    size_t m = w->m, c = w->cols;
    double *pr = w->T + r * c, inv = 1.0 / pr[e];
    for (size_t j = 0; j < c; j++)
        pr[j] *= inv;
    pr[e] = 1.0;
    for (size_t i = 0; i < m; i++) {
        if (i == r)
            continue;
        double *pi = w->T + i * c, f = pi[e];
        if (f == 0.0)
            continue;
        for (size_t j = 0; j < c; j++)
            pi[j] -= f * pr[j];
        pi[e] = 0.0;
    }
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
        colmax = fmax(colmax, w->T[i * c + e]);
    double tol = fmax(PIVOT_REL * colmax, PIVOT_ABS);
    for (size_t i = 0; i < m; i++) {
        double a = w->T[i * c + e];
        if (a > tol && (best == m || lex_less(w, i, a, best, w->T[best * c + e])))
            best = i;
    }
    return best;
}

static void fill_tableau(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, double scale)
{
    size_t m = w->m, c = w->cols;
    memset(w->T, 0, m * c * sizeof *w->T);
    for (size_t i = 0; i < m; i++) {
        double *p = w->T + i * c;
        p[i] = 1.0;
        for (size_t j = 0; j < m; j++)
            p[m + j] = -gsl_matrix_get(M, i, j) / scale;
        p[2 * m] = -1.0;
        p[c - 1] = gsl_vector_get(q, i) / scale;
        w->basis[i] = i;
    }
}

/* The residual of (z, wv) as a solution, in the units of the problem. */
static double residual(const gsl_matrix *M, const gsl_vector *q, const gsl_vector *z, const gsl_vector *wv)
{
    size_t m = q->size;
    double r = 0;
    for (size_t i = 0; i < m; i++) {
        double s = gsl_vector_get(q, i), zi = gsl_vector_get(z, i), wi = gsl_vector_get(wv, i);
        for (size_t j = 0; j < m; j++)
            s += gsl_matrix_get(M, i, j) * gsl_vector_get(z, j);
        r = fmax(r, fabs(s - wi));
        r = fmax(r, fmax(-zi, -wi));
        r = fmax(r, fabs(fmin(zi, wi)));
    }
    return r;
}

/* z from the final basis: z_a solves M_aa z_a = -q_a (a = the z's that are basic), w = M z + q, w_a = 0.
 * Returns 0 when M_aa is singular to working precision (the caller keeps the tableau's values). */
static int basis_solve(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, const char *zbasic, gsl_vector *z,
                       gsl_vector *wv)
{
    size_t m = w->m, k = 0, idx[DP_LCP_MAX];
    for (size_t i = 0; i < m; i++)
        if (zbasic[i])
            idx[k++] = i;
    gsl_vector_set_zero(z);
    if (k > 0) {
        gsl_matrix_view A = gsl_matrix_view_array(w->a, k, k);
        gsl_vector_view b = gsl_vector_view_array(w->b, k), x = gsl_vector_view_array(w->x, k),
                        r = gsl_vector_view_array(w->res, k);
        for (size_t i = 0; i < k; i++) {
            w->b[i] = -gsl_vector_get(q, idx[i]);
            for (size_t j = 0; j < k; j++)
                gsl_matrix_set(&A.matrix, i, j, gsl_matrix_get(M, idx[i], idx[j]));
        }
        gsl_permutation p = { k, w->perm };
        int sign;
        if (gsl_linalg_LU_decomp(&A.matrix, &p, &sign) != GSL_SUCCESS)
            return 0;
        double umax = 0, umin = INFINITY;
        for (size_t i = 0; i < k; i++) {
            umax = fmax(umax, fabs(w->a[i * k + i]));
            umin = fmin(umin, fabs(w->a[i * k + i]));
        }
        if (!(umin > 1e-13 * umax))
            return 0;
        if (gsl_linalg_LU_solve(&A.matrix, &p, &b.vector, &x.vector) != GSL_SUCCESS)
            return 0;
        /* One refinement step against the original entries: r = M_aa x - b, x -= LU \ r. */
        for (size_t i = 0; i < k; i++) {
            double s = -w->b[i];
            for (size_t j = 0; j < k; j++)
                s += gsl_matrix_get(M, idx[i], idx[j]) * w->x[j];
            w->res[i] = s;
        }
        gsl_linalg_LU_svx(&A.matrix, &p, &r.vector);
        for (size_t i = 0; i < k; i++)
            gsl_vector_set(z, idx[i], w->x[i] - w->res[i]);
    }
    for (size_t i = 0; i < m; i++) {
        double s = gsl_vector_get(q, i);
        for (size_t j = 0; j < m; j++)
            s += gsl_matrix_get(M, i, j) * gsl_vector_get(z, j);
        gsl_vector_set(wv, i, zbasic[i] ? 0.0 : s);
    }
    return 1;
}

/* The tableau's own values of z and w (used when the basis system is singular). */
static void tableau_values(const dp_lcp *w, double scale, gsl_vector *z, gsl_vector *wv)
{
    size_t m = w->m, c = w->cols;
    gsl_vector_set_zero(z);
    gsl_vector_set_zero(wv);
    for (size_t r = 0; r < m; r++) {
        double v = fmax(w->T[r * c + c - 1], 0.0);
        if (w->basis[r] < m)
            gsl_vector_set(wv, w->basis[r], v * scale);
        else if (w->basis[r] < 2 * m)
            gsl_vector_set(z, w->basis[r] - m, v);
    }
}

/* Reads the solution from the final basis, refines it and clears rounding-size negatives. */
static void finish(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, double scale, gsl_vector *z,
                   gsl_vector *wv, dp_lcp_result *res)
{
    size_t m = w->m;
    char zbasic[DP_LCP_MAX] = { 0 };
    for (size_t r = 0; r < m; r++)
        if (w->basis[r] >= m && w->basis[r] < 2 * m)
            zbasic[w->basis[r] - m] = 1;
    tableau_values(w, scale, z, wv);
    double r0 = residual(M, q, z, wv);
    gsl_vector_view zv = gsl_vector_view_array(w->z1, m), wvv = gsl_vector_view_array(w->w1, m);
    gsl_vector *z1 = &zv.vector, *w1 = &wvv.vector;
    if (basis_solve(w, M, q, zbasic, z1, w1)) {
        /* Degenerate bases give basic variables at zero: their rounding noise of either sign is cleared. */
        double qmax = 0;
        for (size_t i = 0; i < m; i++)
            qmax = fmax(qmax, fabs(gsl_vector_get(q, i)));
        double zmax = gsl_vector_max(z1) > 0 ? gsl_vector_max(z1) : 0;
        double tol = 64 * DBL_EPSILON * (qmax + scale * zmax);
        for (size_t i = 0; i < m; i++) {
            if (fabs(gsl_vector_get(z1, i)) <= tol && gsl_vector_get(z1, i) < 0)
                gsl_vector_set(z1, i, 0.0);
            if (fabs(gsl_vector_get(w1, i)) <= tol && gsl_vector_get(w1, i) < 0)
                gsl_vector_set(w1, i, 0.0);
        }
        double r1 = residual(M, q, z1, w1);
        if (r1 <= r0) {
            gsl_vector_memcpy(z, z1);
            gsl_vector_memcpy(wv, w1);
            r0 = r1;
        }
    }
    res->residual = r0;
}

int dp_lcp_lemke(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, gsl_vector *z, gsl_vector *wv,
                 dp_lcp_result *res)
{
    size_t m = w->m;
    if (M->size1 != m || M->size2 != m || q->size != m || z->size != m || wv->size != m)
        return DP_EINVAL;
    if (!finite_data(M, q))
        return DP_EINVAL;
    *res = (dp_lcp_result){ DP_LCP_SOLVED, 0, 0.0 };
    size_t r = 0;
    for (size_t i = 1; i < m; i++)
        if (gsl_vector_get(q, i) < gsl_vector_get(q, r))
            r = i;
    if (gsl_vector_get(q, r) >= 0) {
        gsl_vector_set_zero(z);
        gsl_vector_memcpy(wv, q);
        return DP_OK;
    }
    double scale = max_abs_matrix(M);
    if (!(scale > 0))
        scale = 1.0;
    fill_tableau(w, M, q, scale);
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
            tableau_values(w, scale, z, wv);
            return DP_OK;
        }
        leaving = w->basis[r];
        pivot(w, r, entering);
        if (++res->pivots > limit)
            return DP_ELIMIT;
    }
    finish(w, M, q, scale, z, wv, res);
    return DP_OK;
}
