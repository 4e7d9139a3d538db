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
 * equilibrated first, rows and columns by powers of two (lcp_scale.h: exact, and z, w scale back exactly), so
 * that the pivot tolerances below, which compare entries of one column, mean the same whatever the units of
 * each row and of q: a problem scaled by 1e-200 pivots as the same problem scaled by 1.
 *
 * The answer is read from the final tableau after one step of iterative refinement that uses the basis
 * inverse the tableau already holds (O(m^2), no factorization: it takes the pivots' accumulated rounding out)
 * and checked on the scaled problem: w = Mz + q recomputed, signs and complementarity relative to the size
 * of each row's terms (lcp_settle, res->residual); an answer that fails the check is reported as such, never
 * as a solution. A secondary ray is checked too: its direction must solve the homogeneous equations. The
 * problem is copied once into plain arrays: the loops read contiguous memory, not GSL accessors. The
 * workspace is allocated once per size and reused: a solve does not allocate. The stop hook is asked every
 * POLL_WORK multiply-adds of pivoting (a few milliseconds).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/lcp.h"
#include "dashpot/status.h"
#include "lcp/lcp_scale.h"

/* A pivot entry must exceed this fraction of its column's largest entry (plus an absolute floor on the
 * scaled problem, where entries are O(1)): smaller ones are rounding noise of entries that are exactly zero. */
#define PIVOT_REL 1e-11
#define PIVOT_ABS 1e-13
/* Two ratios are a tie when they agree to this relative tolerance; the next column then decides. */
#define TIE_REL 1e-12
/* Multiply-adds of pivoting between two polls of the stop hook: about a millisecond of work. */
#define POLL_WORK (1u << 21)
/* One entry compared by the lexicographic rule, in multiply-adds: two loads through the basis, two divisions,
 * a comparison, none vectorized (measured: Murty's matrix spends 75 % of its time there). */
#define LEX_WEIGHT 8

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
    long double *lscratch; /* the acceptance test's (LCP_SETTLE_SCRATCH) */
    double *M, *q;       /* the equilibrated problem, row-major (lcp_scale.h) */
    int *r, *c;          /* its row and column exponents */
    lcp_scaling sc;
    double qscale;       /* max |q_i| of the equilibrated problem */
    unsigned long long lexwork; /* entries the lexicographic rule compared (scalar, with divisions: they
                                   count towards the stop hook's work as a pivot's multiply-adds do) */
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
    w->lscratch = malloc(LCP_SETTLE_SCRATCH(m) * sizeof *w->lscratch);
    w->M = malloc(m * m * sizeof *w->M);
    w->r = malloc(m * sizeof *w->r), w->c = malloc(m * sizeof *w->c);
    w->sc = (lcp_scaling){ w->r, w->c, 0 };
    if (!ok || !w->T || !w->basis || !w->slot || !w->where || !w->isbasic || !w->M || !w->lscratch || !w->r ||
        !w->c) {
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
                    w->z1, w->w1, w->z2, w->w2, w->q, w->M, w->lscratch, w->r, w->c };
    for (size_t k = 0; k < sizeof all / sizeof *all; k++)
        free(all[k]);
    free(w);
}

/* max of two finite numbers: fmax's NaN rules cost a library call per use in the loops below. */
static inline double maxd(double a, double b)
{
    return b > a ? b : a; /* a when equal: maxd(0.0, -0.0) is +0 */
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

/* Two numbers of size `scale` (or larger) tie when they agree to TIE_REL of it. */
static int tie_at(double scale, double x, double y)
{
    return fabs(x - y) <= TIE_REL * (scale + maxd(fabs(x), fabs(y)));
}

/* Ratios are values of the entering variable, of the size of q's entries on the equilibrated problem (qscale,
 * its largest): a tie is relative to that and to the ratios themselves, whatever the problem's units. */
static int tie(const dp_lcp *w, double x, double y)
{
    return tie_at(w->qscale, x, y);
}

/* Row i's entry of B^-1's column j: w_j's column of the full tableau, a unit vector while w_j is basic. */
static double binv(const dp_lcp *w, size_t i, size_t j)
{
    if (w->isbasic[j])
        return w->where[j] == i ? 1.0 : 0.0;
    return w->T[i * w->cols + w->where[j]];
}

/* Is row i's [rhs, B^-1] / da lexicographically smaller than row k's / db? */
static int lex_less(dp_lcp *w, size_t i, double da, size_t k, double db)
{
    size_t rhs = w->rhs;
    double x = w->T[i * w->cols + rhs] / da, y = w->T[k * w->cols + rhs] / db;
    if (!tie(w, x, y))
        return x < y;
    for (size_t j = 0; j < w->m; j++) {
        x = binv(w, i, j) / da; /* B^-1 of the equilibrated problem: entries of size 1 */
        y = binv(w, k, j) / db;
        if (!tie_at(1.0, x, y)) {
            w->lexwork += j + 1;
            return x < y;
        }
    }
    w->lexwork += w->m;
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
        if (i != first && col[i * c] > tol && tie(w, ratio[i], theta) &&
            lex_less(w, i, col[i * c], best, col[best * c]))
            best = i;
    return best;
}

/* The starting tableau of the equilibrated problem: w basic (row i holds w_i), z_j in slot j, z0 in slot m. */
static void fill_tableau(dp_lcp *w)
{
    size_t m = w->m, c = w->cols;
    for (size_t i = 0; i < m; i++) {
        double *p = w->T + i * c;
        const double *Mi = w->M + i * m;
        for (size_t j = 0; j < m; j++)
            p[j] = -Mi[j];
        p[m] = -1.0;
        p[m + 1] = w->q[i];
        for (size_t j = m + 2; j < c; j++)
            p[j] = 0.0;
        w->basis[i] = i, w->where[i] = i, w->isbasic[i] = 1;
    }
    for (size_t j = 0; j <= m; j++)
        w->slot[j] = m + j, w->where[m + j] = j, w->isbasic[m + j] = 0;
}

/* The tableau's own values of z (basic ones below zero, rounding, set to 0). */
static void tableau_z(const dp_lcp *w, double *z)
{
    size_t m = w->m, c = w->cols;
    memset(z, 0, m * sizeof *z);
    for (size_t r = 0; r < m; r++)
        if (w->basis[r] >= m && w->basis[r] < 2 * m)
            z[w->basis[r] - m] = maxd(w->T[r * c + w->rhs], 0.0);
}

static void store(const double *src, gsl_vector *dst)
{
    for (size_t i = 0; i < dst->size; i++)
        dst->data[i * dst->stride] = src[i];
}

/* One step of iterative refinement of the basic variables' values (the rhs column, overwritten), with the
 * basis inverse the tableau already holds: rho = q - B x_B against the original columns (w_j: e_j,
 * z_j: -M e_j), then x_B += B^-1 rho, B^-1's column j being w_j's (a unit vector while w_j is basic).
 * O(m^2) and no factorization: it takes the pivots' accumulated rounding out of the answer. */
static void refine_values(dp_lcp *w)
{
    size_t m = w->m, c = w->cols;
    double *rho = w->rho, *T = w->T, *rhs = w->T + w->rhs;
    for (size_t i = 0; i < m; i++)
        rho[i] = w->q[i];
    for (size_t r = 0; r < m; r++) {
        size_t v = w->basis[r];
        double x = rhs[r * c];
        if (v < m) {
            rho[v] -= x;
        } else if (v < 2 * m) {
            const double *Mj = w->M + (v - m);
            for (size_t i = 0; i < m; i++)
                rho[i] += Mj[i * m] * x;
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

/* The tableau's z in the problem's units into z, and w = Mz + q into wv, settled and checked (lcp_settle):
 * its relative residual; *finite = 0 when z or w is beyond the doubles. */
static double tableau_answer(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, double *z, double *wv,
                             int *finite)
{
    tableau_z(w, w->rho);
    *finite = lcp_unscale(w->m, &w->sc, w->rho, NULL, z, NULL);
    if (!*finite)
        return INFINITY;
    return lcp_settle(M, q, &w->sc, z, wv, w->lscratch, finite);
}

/* The answer from the final basis: the tableau's values after one step of refinement, checked. Should the
 * check fail (an ill-conditioned basis, where the refinement's own basis inverse is poor), the unrefined
 * values are tried as well and the better of the two is kept, in w->z1, w->w1. Returns its residual. */
static double finish(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, int *finite)
{
    size_t m = w->m, c = w->cols;
    for (size_t r = 0; r < m; r++)
        w->saved[r] = w->T[r * c + w->rhs];
    refine_values(w);
    double r1 = tableau_answer(w, M, q, w->z1, w->w1, finite);
    if (r1 <= LCP_ACCEPT || !*finite)
        return r1;
    for (size_t r = 0; r < m; r++)
        w->T[r * c + w->rhs] = w->saved[r];
    int finite2;
    double r2 = tableau_answer(w, M, q, w->z2, w->w2, &finite2);
    if (!finite2 || !(r2 < r1))
        return r1;
    memcpy(w->z1, w->z2, m * sizeof *w->z1);
    memcpy(w->w1, w->w2, m * sizeof *w->w1);
    return r2;
}

/* The secondary ray's direction, the entering variable (slot s) rising by 1 and each basic one falling by its
 * column entry, must solve the homogeneous equations dw - M dz - e dz0 = 0: its largest relative residual
 * (each row against the size of its terms). A failed check means the rounding of the pivots made the ray. */
static double ray_residual(dp_lcp *w, size_t s)
{
    size_t m = w->m, c = w->cols, enter = w->slot[s];
    double *dz = w->z1, *dw = w->w1, dz0 = enter == 2 * m ? 1.0 : 0.0, worst = 0;
    memset(dz, 0, m * sizeof *dz);
    memset(dw, 0, m * sizeof *dw);
    if (enter < m)
        dw[enter] = 1.0;
    else if (enter < 2 * m)
        dz[enter - m] = 1.0;
    for (size_t r = 0; r < m; r++) {
        size_t v = w->basis[r];
        double d = -w->T[r * c + s];
        if (v < m)
            dw[v] = d;
        else if (v < 2 * m)
            dz[v - m] = d;
        else
            dz0 = d;
    }
    for (size_t i = 0; i < m; i++) {
        const double *Mi = w->M + i * m;
        double acc = dw[i] - dz0, size = fabs(dw[i]) + fabs(dz0);
        for (size_t j = 0; j < m; j++)
            acc -= Mi[j] * dz[j], size += fabs(Mi[j] * dz[j]);
        if (size > 0)
            worst = maxd(worst, fabs(acc) / size);
    }
    return worst;
}

/* The problem equilibrated into the workspace; 0 when an entry is not finite. */
static int load(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q)
{
    if (!lcp_equilibrate(M, q, w->M, w->q, &w->sc))
        return 0;
    w->qscale = 0;
    for (size_t i = 0; i < w->m; i++)
        w->qscale = maxd(w->qscale, fabs(w->q[i]));
    return 1;
}

/* The pivots from the first one on, until z0 leaves (DP_OK), a ray (DP_OK, outcome RAY or INACCURATE), the
 * pivot limit (DP_ELIMIT) or the stop hook (DP_ECANCEL). */
static int pivot_loop(dp_lcp *w, size_t r, const dp_stop *stop, dp_lcp_result *res)
{
    size_t m = w->m, z0 = 2 * m, leaving = w->basis[r];
    pivot(w, r, m); /* z0's slot */
    res->pivots = 1;
    size_t limit = dp_lcp_pivot_limit(m);
    unsigned long long work = 0, per = (unsigned long long)m * w->cols;
    while (leaving != z0) {
        size_t entering = leaving < m ? leaving + m : leaving - m, s = w->where[entering];
        r = ratio_test(w, s);
        if (r == m) {
            res->residual = ray_residual(w, s);
            res->outcome = res->residual <= LCP_ACCEPT ? DP_LCP_RAY : DP_LCP_INACCURATE;
            return DP_OK;
        }
        if (res->pivots >= limit)
            return DP_ELIMIT;
        leaving = w->basis[r];
        pivot(w, r, s);
        res->pivots++;
        work += per + LEX_WEIGHT * w->lexwork; /* a degenerate problem's ties cost as much as its pivots */
        w->lexwork = 0;
        if (work >= POLL_WORK) {
            work = 0;
            if (dp_stop_now(stop))
                return DP_ECANCEL;
        }
    }
    return DP_OK;
}

size_t dp_lcp_pivot_limit(size_t m)
{
    return 1000 + 200 * m;
}

int dp_lcp_lemke(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, gsl_vector *z, gsl_vector *wv,
                 dp_lcp_result *res)
{
    return dp_lcp_lemke_until(w, M, q, z, wv, res, NULL);
}

int dp_lcp_lemke_until(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, gsl_vector *z, gsl_vector *wv,
                       dp_lcp_result *res, const dp_stop *stop)
{
    size_t m = w->m;
    *res = (dp_lcp_result){ DP_LCP_SOLVED, 0, 0.0 };
    if (M->size1 != m || M->size2 != m || q->size != m || z->size != m || wv->size != m)
        return DP_EINVAL;
    if (!load(w, M, q))
        return DP_EINVAL;
    size_t r = 0;
    for (size_t i = 1; i < m; i++)
        if (w->q[i] < w->q[r])
            r = i;
    if (w->q[r] >= 0) { /* z = 0, w = q exactly */
        memset(w->z1, 0, m * sizeof *w->z1);
        for (size_t i = 0; i < m; i++)
            w->w1[i] = q->data[i * q->stride];
    } else {
        fill_tableau(w);
        /* First pivot: z0 enters at the lexicographically smallest row of [q, I] (all its column entries are
         * -1, so after it every row is lexicographically positive). */
        const double *rhs = w->T + w->rhs;
        for (size_t i = 0; i < m; i++)
            if (i != r && tie(w, rhs[i * w->cols], rhs[r * w->cols]) && lex_less(w, i, 1.0, r, 1.0))
                r = i;
        int s = pivot_loop(w, r, stop, res);
        if (s != DP_OK || res->outcome != DP_LCP_SOLVED)
            return s;
        int finite;
        res->residual = finish(w, M, q, &finite);
        if (!finite)
            return DP_ENONFINITE;
        if (res->residual > LCP_ACCEPT)
            res->outcome = DP_LCP_INACCURATE;
    }
    store(w->z1, z);
    store(w->w1, wv);
    return DP_OK;
}
