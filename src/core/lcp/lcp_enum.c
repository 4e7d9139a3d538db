/* src/core/lcp/lcp_enum.c - every solution of a small LCP w = Mz + q, 0 <= z ⊥ w >= 0, by its 2^m complementary
 * bases, and the uniqueness theory of M (Cibulka 2014, Lemma 2.5, Theorem 2.3, Examples 2.4, 2.6, 2.11).
 *
 * A solution has a set a of indices with w_a = 0 and z_rest = 0 (for a degenerate solution several sets), so
 * trying every a with a regular M_aa finds every isolated solution; a singular M_aa is counted, since a
 * continuum of solutions can pass through it. The enumeration is the reference the tests hold Lemke to, and
 * the route's way of reporting several solutions. P-matrix: every principal minor > 0, which is exactly
 * "one solution for every q" (Samelson-Thrall-Wesler); the determinants come from the same LU factors.
 * Both work on the problem equilibrated by powers of two and accept a basic solution by the relative test of
 * lcp_scale.h, so no decision depends on the problem's units; the enumeration asks its stop hook every 256
 * bases.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>

#include "dashpot/lcp.h"
#include "dashpot/status.h"
#include "lcp/lcp_scale.h"

/* A principal minor counts as positive (resp. the submatrix regular) above this fraction of Hadamard's bound
 * on |det| (the product of its rows' norms), compared in logarithms on the equilibrated matrix: below it the
 * sign is rounding. */
#define MINOR_REL 1e-12
/* Two basic solutions are one (a degenerate solution reached from several bases) when their scaled z agree to
 * this fraction of the larger's largest entry. */
#define SAME_REL 1e-9
/* Bases between two polls of the stop hook: 256 LU factorizations of at most 12 x 12, well under a millisecond. */
#define POLL_BASES 256u

typedef struct sub {
    size_t k, idx[DP_LCP_ENUM_MAX], perm[DP_LCP_ENUM_MAX];
    double a[DP_LCP_ENUM_MAX * DP_LCP_ENUM_MAX];
    int sign;            /* the determinant's sign (0: a zero pivot) */
    double logdet;       /* log |det|, -inf when a pivot is 0 */
    double loghad;       /* log of Hadamard's bound, -inf when a row is 0 */
} sub;

/* The equilibrated problem of size m <= DP_LCP_ENUM_MAX (lcp_scale.h). */
typedef struct scaled {
    size_t m;
    double M[DP_LCP_ENUM_MAX * DP_LCP_ENUM_MAX], q[DP_LCP_ENUM_MAX];
    int r[DP_LCP_ENUM_MAX], c[DP_LCP_ENUM_MAX];
    lcp_scaling sc;
} scaled;

static int scale_problem(const gsl_matrix *M, const gsl_vector *q, scaled *p)
{
    p->m = M->size1;
    p->sc = (lcp_scaling){ p->r, p->c, 0 };
    return lcp_equilibrate(M, q, p->M, p->q, &p->sc);
}

/* The Euclidean norm of k numbers without overflow or underflow in the squares. */
static double norm_of(const double *x, size_t k)
{
    double big = 0, sum = 0;
    for (size_t j = 0; j < k; j++)
        big = fmax(big, fabs(x[j]));
    if (big == 0)
        return 0;
    for (size_t j = 0; j < k; j++)
        sum += (x[j] / big) * (x[j] / big);
    return big * sqrt(sum);
}

/* LU of the scaled M_aa for the index set `mask`: its sign, log |det| and log of Hadamard's bound. */
static void factor(const scaled *p, unsigned mask, sub *s)
{
    s->k = 0;
    for (size_t i = 0; i < p->m; i++)
        if (mask & (1u << i))
            s->idx[s->k++] = i;
    size_t k = s->k;
    s->loghad = s->logdet = 0;
    s->sign = 1;
    if (k == 0)
        return; /* the empty basis: z = 0, det 1 */
    for (size_t i = 0; i < k; i++) {
        for (size_t j = 0; j < k; j++)
            s->a[i * k + j] = p->M[s->idx[i] * p->m + s->idx[j]];
        s->loghad += log(norm_of(s->a + i * k, k)); /* -inf for a zero row */
    }
    gsl_matrix_view A = gsl_matrix_view_array(s->a, k, k);
    gsl_permutation perm = { k, s->perm };
    int sign = 1;
    gsl_linalg_LU_decomp(&A.matrix, &perm, &sign); /* partial pivoting; a zero pivot shows in U */
    s->logdet = 0;
    for (size_t i = 0; i < k; i++) {
        double u = s->a[i * k + i];
        sign = u > 0 ? sign : u < 0 ? -sign : 0;
        s->logdet += log(fabs(u));
    }
    s->sign = sign;
}

static int regular(const sub *s)
{
    return s->sign != 0 && s->logdet - s->loghad > log(MINOR_REL);
}

/* det(M_aa) in the problem's units, 2^-(Σ_a r_i + c_i) times the scaled one, formed as mantissa and exponent:
 * NaN when beyond the doubles, 0 when singular to rounding. */
static double minor_value(const scaled *p, const sub *s)
{
    if (!regular(s))
        return 0.0;
    double mant = s->sign;
    int e = 0, ek;
    for (size_t i = 0; i < s->k; i++) {
        mant *= frexp(fabs(s->a[i * s->k + i]), &ek);
        e += ek;
        mant = frexp(mant, &ek);
        e += ek;
        e -= p->r[s->idx[i]] + p->c[s->idx[i]];
    }
    double v = ldexp(mant, e);
    return isfinite(v) ? v : NAN;
}

static int push(dp_lcp_solutions *out, const double *z, const double *w, const double *zs)
{
    size_t m = out->m;
    for (size_t k = 0; k < out->n; k++) {
        const double *zk = out->z + (out->cap * m) + k * m; /* the scaled copies, after the answers */
        double d = 0, n = 0;
        for (size_t i = 0; i < m; i++) {
            d = fmax(d, fabs(zk[i] - zs[i]));
            n = fmax(n, fmax(fabs(zk[i]), fabs(zs[i])));
        }
        if (d <= SAME_REL * n)
            return DP_OK; /* the same (degenerate) solution from another basis */
    }
    if (out->n == out->cap) {
        size_t cap = out->cap ? 2 * out->cap : 4;
        double *pz = malloc(2 * cap * m * sizeof *pz), *pw = realloc(out->w, cap * m * sizeof *pw);
        if (pz == NULL || pw == NULL) {
            free(pz);
            if (pw)
                out->w = pw;
            return DP_ENOMEM;
        }
        if (out->z) { /* answers first, then the scaled copies */
            memcpy(pz, out->z, out->n * m * sizeof *pz);
            memcpy(pz + cap * m, out->z + out->cap * m, out->n * m * sizeof *pz);
        }
        free(out->z);
        out->z = pz, out->w = pw, out->cap = cap;
    }
    memcpy(out->z + out->n * m, z, m * sizeof *z);
    memcpy(out->w + out->n * m, w, m * sizeof *w);
    memcpy(out->z + out->cap * m + out->n * m, zs, m * sizeof *zs);
    out->n++;
    return DP_OK;
}

static int valid(const gsl_matrix *M, const gsl_vector *q)
{
    return M->size1 == M->size2 && q->size == M->size1 && q->size > 0;
}

/* The basic solution of the factored basis s in scaled units into zs (0 when the solve fails). */
static int basic_z(const scaled *p, const sub *s, double *zs)
{
    double b[DP_LCP_ENUM_MAX];
    memset(zs, 0, p->m * sizeof *zs);
    if (s->k == 0)
        return 1;
    gsl_matrix_const_view A = gsl_matrix_const_view_array(s->a, s->k, s->k);
    gsl_permutation perm = { s->k, (size_t *)s->perm };
    gsl_vector_view bv = gsl_vector_view_array(b, s->k);
    for (size_t i = 0; i < s->k; i++)
        b[i] = -p->q[s->idx[i]];
    if (gsl_linalg_LU_svx(&A.matrix, &perm, &bv.vector) != GSL_SUCCESS)
        return 0;
    for (size_t i = 0; i < s->k; i++)
        zs[s->idx[i]] = b[i];
    return 1;
}

/* Whether basis s gives a solution: z, w in the problem's units written, 1; 0 not one; DP_ENONFINITE as -1
 * when it is one (by the scaled problem's test) but beyond the doubles. */
static int basic_solution(const gsl_matrix *M, const gsl_vector *q, const scaled *p, const sub *s, double *zs,
                          double *z, double *w)
{
    long double scratch[LCP_SETTLE_SCRATCH(DP_LCP_ENUM_MAX)];
    int finite;
    if (!basic_z(p, s, zs))
        return 0;
    if (lcp_unscale(p->m, &p->sc, zs, NULL, z, NULL)) {
        double r = lcp_settle(M, q, &p->sc, z, w, scratch, &finite);
        if (r > LCP_ACCEPT)
            return 0;
        return finite ? 1 : -1;
    }
    gsl_matrix_const_view Ms = gsl_matrix_const_view_array(p->M, p->m, p->m);
    gsl_vector_const_view qs = gsl_vector_const_view_array(p->q, p->m);
    double zc[DP_LCP_ENUM_MAX], wc[DP_LCP_ENUM_MAX];
    int none[DP_LCP_ENUM_MAX] = { 0 };
    const lcp_scaling unit = { none, none, 0 }; /* the scaled problem is its own equilibration */
    memcpy(zc, zs, p->m * sizeof *zc);
    return lcp_settle(&Ms.matrix, &qs.vector, &unit, zc, wc, scratch, &finite) > LCP_ACCEPT ? 0 : -1;
}

int dp_lcp_enumerate(const gsl_matrix *M, const gsl_vector *q, dp_lcp_solutions *out)
{
    return dp_lcp_enumerate_until(M, q, out, NULL);
}

int dp_lcp_enumerate_until(const gsl_matrix *M, const gsl_vector *q, dp_lcp_solutions *out, const dp_stop *stop)
{
    *out = (dp_lcp_solutions){ q->size, 0, 0, NULL, NULL, 0 };
    if (!valid(M, q) || q->size > DP_LCP_ENUM_MAX)
        return DP_EINVAL;
    scaled p;
    if (!scale_problem(M, q, &p))
        return DP_EINVAL;
    size_t m = q->size;
    double zs[DP_LCP_ENUM_MAX], z[DP_LCP_ENUM_MAX], w[DP_LCP_ENUM_MAX];
    sub s;
    for (unsigned mask = 0; mask < (1u << m); mask++) {
        if (mask % POLL_BASES == POLL_BASES - 1 && dp_stop_now(stop))
            return DP_ECANCEL;
        factor(&p, mask, &s);
        if (mask != 0 && !regular(&s)) {
            out->singular++;
            continue;
        }
        int got = basic_solution(M, q, &p, &s, zs, z, w);
        if (got < 0)
            return DP_ENONFINITE;
        if (got > 0) {
            int st = push(out, z, w, zs);
            if (st != DP_OK)
                return st;
        }
    }
    return DP_OK;
}

void dp_lcp_solutions_clear(dp_lcp_solutions *s)
{
    if (s == NULL)
        return;
    free(s->z);
    free(s->w);
    s->z = s->w = NULL;
    s->n = s->cap = 0;
}

/* µ = λ_min((M + Mᵀ)/2) of M scaled by 2^-e (max |M_ij| in [1, 2)): *mu the scaled one. */
static int symmetric_min_eig(const gsl_matrix *M, int e, double *mu)
{
    size_t m = M->size1;
    gsl_matrix *S = gsl_matrix_alloc(m, m);
    gsl_vector *ev = gsl_vector_alloc(m);
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc(m);
    int st = DP_ENOMEM;
    if (S && ev && ws) {
        for (size_t i = 0; i < m; i++)
            for (size_t j = 0; j < m; j++) /* halves first: no sum of two large entries is formed */
                gsl_matrix_set(S, i, j, ldexp(gsl_matrix_get(M, i, j), -e - 1) + ldexp(gsl_matrix_get(M, j, i), -e - 1));
        st = gsl_eigen_symm(S, ev, ws) == GSL_SUCCESS ? DP_OK : DP_ESOLVE;
        if (st == DP_OK)
            *mu = gsl_vector_min(ev);
    }
    gsl_eigen_symm_free(ws);
    gsl_vector_free(ev);
    gsl_matrix_free(S);
    return st;
}

/* Every principal minor positive, by its sign on the equilibrated matrix? Sets t->p_matrix, and when not the
 * witness: of the minors that are not positive, the most negative relative to Hadamard's bound (a negative
 * one before one singular to rounding), in the problem's units. */
static void p_matrix_test(const gsl_matrix *M, dp_lcp_theory *t)
{
    scaled p;
    sub s;
    scale_problem(M, NULL, &p);
    t->p_matrix = 1;
    t->minor = NAN;
    t->minor_set = 0;
    double worst = INFINITY;
    for (unsigned mask = 1; mask < (1u << p.m); mask++) {
        factor(&p, mask, &s);
        if (regular(&s) && s.sign > 0)
            continue;
        double rel = regular(&s) ? -exp(fmin(s.logdet - s.loghad, 0.0)) : 0.0; /* in [-1, 0] */
        if (t->p_matrix || rel < worst) {
            t->p_matrix = 0;
            worst = rel;
            t->minor_set = mask;
            t->minor = minor_value(&p, &s);
        }
    }
}

int dp_lcp_theory_of(const gsl_matrix *M, dp_lcp_theory *t)
{
    memset(t, 0, sizeof *t);
    size_t m = M->size1;
    if (M->size1 != M->size2 || m == 0)
        return DP_EINVAL;
    double norm = 0;
    for (size_t i = 0; i < m; i++)
        for (size_t j = 0; j < m; j++) {
            double x = gsl_matrix_get(M, i, j);
            if (!isfinite(x))
                return DP_EINVAL;
            norm = fmax(norm, fabs(x));
        }
    int e = norm > 0 ? ilogb(norm) : 0, st;
    double mu;
    if ((st = symmetric_min_eig(M, e, &mu)) != DP_OK)
        return st;
    /* µ is computed to about eps |M|: below that its sign is not known, so "positive" needs more; decided on
     * the scaled matrix, whose largest entry is in [1, 2). */
    double tol = 1e-12 * (double)m;
    t->pd_symmetric = mu > tol;
    t->psd = mu >= -tol;
    t->mu = ldexp(mu, e);
    if (!isfinite(t->mu))
        return DP_ENONFINITE;
    t->lipschitz = t->pd_symmetric ? 1.0 / t->mu : INFINITY; /* +inf too when 1/µ is beyond the doubles */
    t->minor = NAN;
    if (m <= DP_LCP_ENUM_MAX)
        p_matrix_test(M, t);
    else
        t->p_matrix = t->pd_symmetric ? 1 : -1;
    return DP_OK;
}
