/* src/core/lcp/lemke.c - Lemke's complementary pivoting for w = Mz + q, 0 <= z ⊥ w >= 0 (Cibulka 2014, (1.10);
 * Cottle, Pang & Stone, The Linear Complementarity Problem, §4.4), with the lexicographic ratio test.
 *
 * The system w - M z - e z0 = q has 2m + 1 variables: w (0..m), z (m..2m), z0 (2m). The tableau is stored
 * compactly (Tucker's form): m rows, one per basic variable, of m + 1 columns for the non-basic variables
 * (slots) and the right-hand side, x_B + T x_N = rhs. A pivot swaps one basic and one non-basic variable in
 * place and is one contiguous rank-one update of the whole tableau: no index lists, no unit columns. The
 * basis inverse, which the lexicographic rule compares row by row ([rhs, B^-1] divided by the pivot column),
 * is the original w columns: a basic w_j's column is a unit vector, a non-basic one's is its slot. Each row
 * stays lexicographically positive, no basis repeats, and a degenerate problem cannot cycle. The problem is
 * scaled by the power of two at or above max|M_ij| first (exact: z is unchanged, w scales), so the pivot
 * tolerances below are relative.
 *
 * The answer is read from the final tableau after one step of iterative refinement that uses the basis
 * inverse the tableau already holds (O(m^2), no factorization: it takes the pivots' accumulated rounding out)
 * and checked: w = Mz + q recomputed, complementarity and signs (res->residual). The problem is copied once
 * into plain arrays: the loops read contiguous memory, not GSL accessors. The workspace is allocated once
 * per size and reused: a solve does not allocate.
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
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

/* Two doubles of a tableau row: the pivot's loops work on these (one SSE2 operation on baseline x86-64;
 * the compiler does not vectorize the plain loop at -O2). Rows start on 32-byte boundaries (aligned_alloc,
 * the stride a multiple of 4), so the loops below run over whole pairs, two at a time, with no tail. */
typedef double pair __attribute__((vector_size(16), may_alias));

struct dp_lcp {
    size_t m, cols, rhs; /* cols: the row stride, m + 2 (m + 1 slots, the right-hand side at rhs = m + 1)
                          * rounded up to a multiple of 4 with zero columns, so a row's loop has no tail */
    double *T;           /* m x cols, row-major */
    size_t *basis;       /* basis[r] = the variable basic in row r */
    size_t *slot;        /* slot[s] = the variable non-basic in column s */
    size_t *where;       /* per variable: its row when basic, its slot when not */
    char *isbasic;       /* per variable */
    double *ratio;       /* the ratio test's quotients */
    double *rho;         /* the refinement's residual */
    double *saved;       /* the right-hand side before refinement */
    double *z1, *w1;     /* the answer read from the refined tableau */
    double *z2, *w2;     /* the unrefined one, when the first fails its check */
    double mmax;         /* max |M_ij| of the problem being solved */
    double *M, *q;       /* the problem, row-major */
    char *zbasic;        /* per z: basic at the end */
};

dp_lcp *dp_lcp_alloc(size_t m)
{
    if (m == 0 || m > DP_LCP_MAX)
        return NULL;
    dp_lcp *w = calloc(1, sizeof *w);
    if (w == NULL)
        return NULL;
    w->m = m;
    w->rhs = m + 1;
    w->cols = (m + 2 + 3) / 4 * 4;
    w->T = aligned_alloc(32, m * w->cols * sizeof *w->T); /* a multiple of 32 bytes, as it must be */
    w->basis = malloc(m * sizeof *w->basis);
    w->slot = malloc((m + 1) * sizeof *w->slot);
    w->where = malloc((2 * m + 1) * sizeof *w->where);
    w->isbasic = malloc(2 * m + 1);
    double **vec[] = { &w->ratio, &w->rho, &w->saved, &w->z1, &w->w1, &w->z2, &w->w2, &w->q };
    int ok = 1;
    for (size_t k = 0; k < sizeof vec / sizeof *vec; k++)
        ok &= (*vec[k] = malloc(m * sizeof(double))) != NULL;
    w->M = malloc(m * m * sizeof *w->M);
    w->zbasic = malloc(m);
    if (!ok || !w->T || !w->basis || !w->slot || !w->where || !w->isbasic || !w->M || !w->zbasic) {
        dp_lcp_free(w);
        return NULL;
    }
    return w;
}

void dp_lcp_free(dp_lcp *w)
{
    if (w == NULL)
        return;
    void *all[] = { w->T, w->basis, w->slot, w->where, w->isbasic, w->ratio, w->rho, w->saved,
                    w->z1, w->w1, w->z2, w->w2, w->q, w->M, w->zbasic };
    for (size_t k = 0; k < sizeof all / sizeof *all; k++)
        free(all[k]);
    free(w);
}

/* max of two finite numbers: fmax's NaN rules cost a library call per use in the loops below. */
static inline double maxd(double a, double b)
{
    return b > a ? b : a; /* a when equal: maxd(0.0, -0.0) is +0 */
}

/* The problem as plain row-major arrays (M may be a view with a row stride): one copy, O(m^2), then every
 * loop below reads contiguous memory. Also max|M_ij| in *mmax. 0 when an entry is not finite. */
static int load(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, double *mmax)
{
    size_t m = w->m;
    double big = 0, nan_if_any = 0; /* x - x is NaN exactly when x is not finite: no branch per entry */
    for (size_t i = 0; i < m; i++) {
        const double *row = M->data + i * M->tda;
        double *dst = w->M + i * m;
        for (size_t j = 0; j < m; j++) {
            double x = row[j];
            dst[j] = x;
            nan_if_any += x - x;
            big = maxd(big, fabs(x));
        }
        w->q[i] = q->data[i * q->stride];
        nan_if_any += w->q[i] - w->q[i];
    }
    *mmax = big;
    return nan_if_any == 0.0;
}

/* The power of two at or above x > 0 (scaling by it is exact). */
static double power_of_two_above(double x)
{
    if (!(x >= DBL_MIN)) {
        int e;
        return ldexp(1.0, (frexp(x, &e), e));
    }
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    bits &= 0x7ff0000000000000u; /* the exponent alone: 2^floor(log2 x) */
    double p;
    memcpy(&p, &bits, sizeof p);
    return p == x ? p : 2 * p;
}

/* Tucker's exchange on (row r, slot s): the basic variable of row r and the non-basic one of slot s trade
 * places. Row r is divided by the pivot (its slot entry becoming 1/p); every other row i loses f_i times it,
 * f_i its slot entry, which is first set to 0 so that the same contiguous loop leaves -f_i / p there. */
/* Row r divided by its pivot, then every other row i minus f_i times it (f_i first set to 0): on pairs. */
static void exchange_rows(double *T, size_t m, size_t c, size_t r, size_t s)
{
    size_t n2 = c / 2;
    pair *pr = (pair *)(T + r * c);
    double inv = 1.0 / T[r * c + s];
    T[r * c + s] = 1.0;
    for (size_t k = 0; k < n2; k += 2) {
        pr[k] *= inv;
        pr[k + 1] *= inv;
    }
    for (size_t i = 0; i < m; i++) {
        double *ti = T + i * c, f = ti[s];
        if (i == r || f == 0.0)
            continue;
        ti[s] = 0.0;
        pair *pi = (pair *)ti;
        for (size_t k = 0; k < n2; k += 2) {
            pi[k] -= f * pr[k];
            pi[k + 1] -= f * pr[k + 1];
        }
    }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
/* The same on four doubles at once where the processor has AVX (chosen at run time; no FMA, so the
 * arithmetic, and the answer, are bit for bit those of the pairs). */
typedef double quad __attribute__((vector_size(32), may_alias));

__attribute__((target("avx"))) static void exchange_rows_avx(double *T, size_t m, size_t c, size_t r, size_t s)
{
    size_t n4 = c / 4;
    quad *pr = (quad *)(T + r * c);
    double inv = 1.0 / T[r * c + s];
    T[r * c + s] = 1.0;
    for (size_t k = 0; k < n4; k++)
        pr[k] *= inv;
    for (size_t i = 0; i < m; i++) {
        double *ti = T + i * c, f = ti[s];
        if (i == r || f == 0.0)
            continue;
        ti[s] = 0.0;
        quad *pi = (quad *)ti;
        for (size_t k = 0; k < n4; k++)
            pi[k] -= f * pr[k];
    }
}
#define HAVE_AVX() __builtin_cpu_supports("avx")
#else
#define exchange_rows_avx exchange_rows
#define HAVE_AVX() 0
#endif

static void pivot(dp_lcp *w, size_t r, size_t s)
{
    if (HAVE_AVX())
        exchange_rows_avx(w->T, w->m, w->cols, r, s);
    else
        exchange_rows(w->T, w->m, w->cols, r, s);
    size_t leave = w->basis[r], enter = w->slot[s];
    w->basis[r] = enter, w->slot[s] = leave;
    w->isbasic[enter] = 1, w->where[enter] = r;
    w->isbasic[leave] = 0, w->where[leave] = s;
}

static int tie(double x, double y)
{
    return fabs(x - y) <= TIE_REL * (1.0 + maxd(fabs(x), fabs(y)));
}

/* Row i's entry of B^-1's column j: w_j's column of the full tableau, a unit vector while w_j is basic. */
static double binv(const dp_lcp *w, size_t i, size_t j)
{
    if (w->isbasic[j])
        return w->where[j] == i ? 1.0 : 0.0;
    return w->T[i * w->cols + w->where[j]];
}

/* Is row i's [rhs, B^-1] / da lexicographically smaller than row k's / db? */
static int lex_less(const dp_lcp *w, size_t i, double da, size_t k, double db)
{
    size_t rhs = w->rhs;
    double x = w->T[i * w->cols + rhs] / da, y = w->T[k * w->cols + rhs] / db;
    if (!tie(x, y))
        return x < y;
    for (size_t j = 0; j < w->m; j++) {
        x = binv(w, i, j) / da;
        y = binv(w, k, j) / db;
        if (!tie(x, y))
            return x < y;
    }
    return i < k; /* identical rows cannot happen (B^-1 is regular); a stable choice anyway */
}

/* The lexicographic minimum ratio row for the variable in slot s, or m when its column gives a ray: the
 * minimum ratio rhs_i / a_i over the rows that block (a_i above the pivot tolerance), and only among rows
 * whose ratios tie with it (a degenerate step) the lexicographic rule. */
static size_t ratio_test(dp_lcp *w, size_t s)
{
    size_t m = w->m, c = w->cols, best = m;
    const double *col = w->T + s, *rhs = w->T + w->rhs;
    double colmax = 0, theta = 0, *ratio = w->ratio;
    for (size_t i = 0; i < m; i++)
        colmax = maxd(colmax, col[i * c]);
    double tol = maxd(PIVOT_REL * colmax, PIVOT_ABS);
    for (size_t i = 0; i < m; i++) {
        double a = col[i * c];
        if (!(a > tol))
            continue;
        ratio[i] = rhs[i * c] / a;
        if (best == m || ratio[i] < theta)
            best = i, theta = ratio[i];
    }
    if (best == m)
        return m;
    size_t first = best;
    for (size_t i = 0; i < m; i++)
        if (i != first && col[i * c] > tol && tie(ratio[i], theta) &&
            lex_less(w, i, col[i * c], best, col[best * c]))
            best = i;
    return best;
}

/* The starting tableau: w basic (row i holds w_i), z_j in slot j, z0 in slot m; scaled by 1/scale. */
static void fill_tableau(dp_lcp *w, double scale)
{
    size_t m = w->m, c = w->cols;
    double inv = 1.0 / scale; /* a power of two: exact */
    for (size_t i = 0; i < m; i++) {
        double *p = w->T + i * c;
        const double *Mi = w->M + i * m;
        for (size_t j = 0; j < m; j++)
            p[j] = -Mi[j] * inv;
        p[m] = -1.0;
        p[m + 1] = w->q[i] * inv;
        for (size_t j = m + 2; j < c; j++)
            p[j] = 0.0;
        w->basis[i] = i, w->where[i] = i, w->isbasic[i] = 1;
    }
    for (size_t j = 0; j <= m; j++)
        w->slot[j] = m + j, w->where[m + j] = j, w->isbasic[m + j] = 0;
}

/* The tableau's own values of z and w, basic ones below zero (rounding) set to 0. */
static void tableau_values(const dp_lcp *w, double scale, double *z, double *wv)
{
    size_t m = w->m, c = w->cols;
    memset(z, 0, m * sizeof *z);
    memset(wv, 0, m * sizeof *wv);
    for (size_t r = 0; r < m; r++) {
        double v = maxd(w->T[r * c + w->rhs], 0.0);
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

/* One step of iterative refinement of the basic variables' values (the rhs column, overwritten), with the
 * basis inverse the tableau already holds: rho = q/scale - B x_B against the original columns (w_j: e_j,
 * z_j: -M e_j / scale), then x_B += B^-1 rho, B^-1's column j being w_j's (a unit vector while w_j is
 * basic). O(m^2) and no factorization: it takes the pivots' accumulated rounding out of the answer. */
static void refine_values(dp_lcp *w, double scale)
{
    size_t m = w->m, c = w->cols;
    double inv = 1.0 / scale, *rho = w->rho, *T = w->T, *rhs = w->T + w->rhs;
    for (size_t i = 0; i < m; i++)
        rho[i] = w->q[i] * inv;
    for (size_t r = 0; r < m; r++) {
        size_t v = w->basis[r];
        double x = rhs[r * c];
        if (v < m) {
            rho[v] -= x;
        } else if (v < 2 * m) {
            const double *Mj = w->M + (v - m);
            for (size_t i = 0; i < m; i++)
                rho[i] += Mj[i * m] * inv * x;
        }
    }
    for (size_t j = 0; j < m; j++) {
        if (w->isbasic[j]) {
            rhs[w->where[j] * c] += rho[j];
            continue;
        }
        const double *col = T + w->where[j];
        for (size_t r = 0; r < m; r++)
            rhs[r * c] += col[r * c] * rho[j];
    }
}

/* The tableau's z (refined first when asked) with w recomputed as Mz + q, 0 where z is basic, into z, wv;
 * its residual (z >= 0 and z ⊥ w hold by construction). *tol: the rounding level, 64 eps (|q| + |M| |z|);
 * w's rounding-size negatives are cleared against it. */
static double tableau_answer(dp_lcp *w, double scale, int refine, double *z, double *wv, double *tol)
{
    size_t m = w->m;
    if (refine)
        refine_values(w, scale);
    tableau_values(w, scale, z, wv);
    double qmax = 0, zmax = 0;
    for (size_t i = 0; i < m; i++)
        qmax = maxd(qmax, fabs(w->q[i])), zmax = maxd(zmax, z[i]);
    *tol = 64 * DBL_EPSILON * (qmax + w->mmax * zmax);
    double r = 0;
    for (size_t i = 0; i < m; i++) {
        const double *Mi = w->M + i * m;
        double s = w->q[i];
        for (size_t j = 0; j < m; j++)
            s += Mi[j] * z[j];
        wv[i] = w->zbasic[i] ? 0.0 : (s < 0 && s >= -*tol ? 0.0 : s);
        r = maxd(r, fabs(s - wv[i]));
        r = maxd(r, -wv[i]);
    }
    return r;
}

/* The answer from the final basis: the tableau's values after one step of refinement, checked. Should the
 * check fail (an ill-conditioned basis, where the refinement's own basis inverse is poor), the unrefined
 * values are tried as well and the better of the two is kept; res->residual says what was reached. */
static void finish(dp_lcp *w, double scale, gsl_vector *z, gsl_vector *wv, dp_lcp_result *res)
{
    size_t m = w->m, c = w->cols;
    memset(w->zbasic, 0, m);
    for (size_t r = 0; r < m; r++) {
        if (w->basis[r] >= m && w->basis[r] < 2 * m)
            w->zbasic[w->basis[r] - m] = 1;
        w->saved[r] = w->T[r * c + w->rhs];
    }
    double tol, *z1 = w->z1, *w1 = w->w1;
    res->residual = tableau_answer(w, scale, 1, z1, w1, &tol);
    if (res->residual > tol) {
        for (size_t r = 0; r < m; r++)
            w->T[r * c + w->rhs] = w->saved[r];
        double r2 = tableau_answer(w, scale, 0, w->z2, w->w2, &tol);
        if (r2 < res->residual)
            z1 = w->z2, w1 = w->w2, res->residual = r2;
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
    double mmax;
    if (!load(w, M, q, &mmax))
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
    w->mmax = mmax;
    double scale = mmax > 0 ? power_of_two_above(mmax) : 1.0; /* exact scaling */
    fill_tableau(w, scale);
    /* First pivot: z0 enters at the lexicographically smallest row of [q, I] (all its column entries are -1,
     * so after it every row is lexicographically positive). */
    const double *rhs = w->T + w->rhs;
    for (size_t i = 0; i < m; i++)
        if (i != r && tie(rhs[i * w->cols], rhs[r * w->cols]) && lex_less(w, i, 1.0, r, 1.0))
            r = i;
    size_t z0 = 2 * m, leaving = w->basis[r];
    pivot(w, r, m); /* z0's slot */
    res->pivots = 1;
    /* A lexicographic run visits each basis at most once; this guard only bounds a pathological input. */
    size_t limit = 1000 + 200 * m;
    while (leaving != z0) {
        size_t entering = leaving < m ? leaving + m : leaving - m, s = w->where[entering];
        r = ratio_test(w, s);
        if (r == m) {
            res->outcome = DP_LCP_RAY;
            tableau_values(w, scale, w->z1, w->w1);
            store(w->z1, z);
            store(w->w1, wv);
            return DP_OK;
        }
        leaving = w->basis[r];
        pivot(w, r, s);
        if (++res->pivots > limit)
            return DP_ELIMIT;
    }
    finish(w, scale, z, wv, res);
    return DP_OK;
}
