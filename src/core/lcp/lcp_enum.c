/* src/core/lcp/lcp_enum.c - every solution of a small LCP w = Mz + q, 0 <= z ⊥ w >= 0, by its 2^m complementary
 * bases, and the uniqueness theory of M (Cibulka 2014, Lemma 2.5, Theorem 2.3, Examples 2.4, 2.6, 2.11).
 *
 * A solution has a set a of indices with w_a = 0 and z_rest = 0 (for a degenerate solution several sets), so
 * trying every a with a regular M_aa finds every isolated solution; a singular M_aa is counted, since a
 * continuum of solutions can pass through it. The enumeration is the reference the tests hold Lemke to, and
 * the route's way of reporting several solutions. P-matrix: every principal minor > 0, which is exactly
 * "one solution for every q" (Samelson-Thrall-Wesler); the determinants come from the same LU factors.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>

#include "dashpot/lcp.h"
#include "dashpot/status.h"

/* Acceptance of a basic solution: z_a >= -ACCEPT * scale, w >= -ACCEPT * scale, scale the size of the data;
 * a computed zero misses by rounding (~1e-16 scale) and a real violation by far more. */
#define ACCEPT 1e-10
/* A principal minor counts as positive (resp. the submatrix regular) above this fraction of the product of
 * its rows' norms (Hadamard's bound on |det|): below it the sign is rounding. */
#define MINOR_REL 1e-12

typedef struct sub {
    size_t k, idx[DP_LCP_ENUM_MAX], perm[DP_LCP_ENUM_MAX];
    double a[DP_LCP_ENUM_MAX * DP_LCP_ENUM_MAX];
    double det, hadamard;
} sub;

/* LU of M_aa for the index set `mask`; 0 if the LU failed. */
static int factor(const gsl_matrix *M, unsigned mask, sub *s)
{
    s->k = 0;
    for (size_t i = 0; i < M->size1; i++)
        if (mask & (1u << i))
            s->idx[s->k++] = i;
    size_t k = s->k;
    s->hadamard = 1.0;
    for (size_t i = 0; i < k; i++) {
        double n2 = 0;
        for (size_t j = 0; j < k; j++) {
            double v = gsl_matrix_get(M, s->idx[i], s->idx[j]);
            s->a[i * k + j] = v;
            n2 += v * v;
        }
        s->hadamard *= sqrt(n2);
    }
    gsl_matrix_view A = gsl_matrix_view_array(s->a, k, k);
    gsl_permutation p = { k, s->perm };
    int sign;
    if (gsl_linalg_LU_decomp(&A.matrix, &p, &sign) != GSL_SUCCESS)
        return 0;
    s->det = gsl_linalg_LU_det(&A.matrix, sign);
    return 1;
}

static int regular(const sub *s)
{
    return fabs(s->det) > MINOR_REL * s->hadamard && s->hadamard > 0;
}

static int push(dp_lcp_solutions *out, const double *z)
{
    size_t m = out->m;
    for (size_t k = 0; k < out->n; k++) {
        double d = 0, n = 1;
        for (size_t i = 0; i < m; i++) {
            d = fmax(d, fabs(out->z[k * m + i] - z[i]));
            n = fmax(n, fabs(z[i]));
        }
        if (d <= 1e-9 * n)
            return DP_OK; /* the same (degenerate) solution from another basis */
    }
    if (out->n == out->cap) {
        size_t cap = out->cap ? 2 * out->cap : 4;
        double *p = realloc(out->z, cap * m * sizeof *p);
        if (p == NULL)
            return DP_ENOMEM;
        out->z = p;
        out->cap = cap;
    }
    memcpy(out->z + out->n * m, z, m * sizeof *z);
    out->n++;
    return DP_OK;
}

static double data_scale(const gsl_matrix *M, const gsl_vector *q)
{
    double s = 1.0;
    for (size_t i = 0; i < q->size; i++) {
        s = fmax(s, fabs(gsl_vector_get(q, i)));
        for (size_t j = 0; j < q->size; j++)
            s = fmax(s, fabs(gsl_matrix_get(M, i, j)));
    }
    return s;
}

static int valid(const gsl_matrix *M, const gsl_vector *q)
{
    if (M->size1 != M->size2 || q->size != M->size1 || q->size == 0)
        return 0;
    for (size_t i = 0; i < q->size; i++) {
        if (!isfinite(gsl_vector_get(q, i)))
            return 0;
        for (size_t j = 0; j < q->size; j++)
            if (!isfinite(gsl_matrix_get(M, i, j)))
                return 0;
    }
    return 1;
}

/* The solution of basis `mask` if it is one (z written, 1), else 0. */
static int basic_solution(const gsl_matrix *M, const gsl_vector *q, const sub *s, double scale, double *z)
{
    size_t m = q->size, k = s->k;
    double b[DP_LCP_ENUM_MAX];
    memset(z, 0, m * sizeof *z);
    if (k > 0) {
        gsl_matrix_const_view A = gsl_matrix_const_view_array(s->a, k, k);
        gsl_permutation p = { k, (size_t *)s->perm };
        gsl_vector_view bv = gsl_vector_view_array(b, k);
        for (size_t i = 0; i < k; i++)
            b[i] = -gsl_vector_get(q, s->idx[i]);
        if (gsl_linalg_LU_svx(&A.matrix, &p, &bv.vector) != GSL_SUCCESS)
            return 0;
        for (size_t i = 0; i < k; i++)
            z[s->idx[i]] = b[i];
    }
    double zmax = 0;
    for (size_t i = 0; i < m; i++)
        zmax = fmax(zmax, fabs(z[i]));
    double tol = ACCEPT * scale * (1.0 + zmax);
    for (size_t i = 0; i < m; i++) {
        double w = gsl_vector_get(q, i);
        for (size_t j = 0; j < m; j++)
            w += gsl_matrix_get(M, i, j) * z[j];
        if (z[i] < -tol || w < -tol)
            return 0;
        if (z[i] < 0)
            z[i] = 0.0;
    }
    return 1;
}

int dp_lcp_enumerate(const gsl_matrix *M, const gsl_vector *q, dp_lcp_solutions *out)
{
    *out = (dp_lcp_solutions){ q->size, 0, 0, NULL, 0 };
    if (!valid(M, q) || q->size > DP_LCP_ENUM_MAX)
        return DP_EINVAL;
    size_t m = q->size;
    double scale = data_scale(M, q), z[DP_LCP_ENUM_MAX];
    sub s;
    for (unsigned mask = 0; mask < (1u << m); mask++) {
        if (mask != 0 && (!factor(M, mask, &s) || !regular(&s))) {
            out->singular++;
            continue;
        }
        if (mask == 0)
            s.k = 0;
        if (basic_solution(M, q, &s, scale, z)) {
            int st = push(out, z);
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
    s->z = NULL;
    s->n = s->cap = 0;
}

/* µ = λ_min((M + Mᵀ)/2). */
static int symmetric_min_eig(const gsl_matrix *M, double *mu)
{
    size_t m = M->size1;
    gsl_matrix *S = gsl_matrix_alloc(m, m);
    gsl_vector *ev = gsl_vector_alloc(m);
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc(m);
    int st = DP_ENOMEM;
    if (S && ev && ws) {
        for (size_t i = 0; i < m; i++)
            for (size_t j = 0; j < m; j++)
                gsl_matrix_set(S, i, j, 0.5 * (gsl_matrix_get(M, i, j) + gsl_matrix_get(M, j, i)));
        st = gsl_eigen_symm(S, ev, ws) == GSL_SUCCESS ? DP_OK : DP_ESOLVE;
        if (st == DP_OK)
            *mu = gsl_vector_min(ev);
    }
    gsl_eigen_symm_free(ws);
    gsl_vector_free(ev);
    gsl_matrix_free(S);
    return st;
}

/* Every principal minor positive? Sets t->p_matrix, and the smallest minor as a witness when not. */
static void p_matrix_test(const gsl_matrix *M, dp_lcp_theory *t)
{
    size_t m = M->size1;
    sub s;
    t->p_matrix = 1;
    t->minor = INFINITY;
    t->minor_set = 0;
    for (unsigned mask = 1; mask < (1u << m); mask++) {
        int ok = factor(M, mask, &s);
        double det = ok ? s.det : 0.0;
        int positive = ok && det > MINOR_REL * s.hadamard;
        if (!positive && (t->p_matrix || det < t->minor)) {
            t->p_matrix = 0;
            t->minor = det;
            t->minor_set = mask;
        }
    }
    if (t->p_matrix)
        t->minor = NAN;
}

int dp_lcp_theory_of(const gsl_matrix *M, dp_lcp_theory *t)
{
    memset(t, 0, sizeof *t);
    if (M->size1 != M->size2 || M->size1 == 0)
        return DP_EINVAL;
    for (size_t i = 0; i < M->size1; i++)
        for (size_t j = 0; j < M->size2; j++)
            if (!isfinite(gsl_matrix_get(M, i, j)))
                return DP_EINVAL;
    int st = symmetric_min_eig(M, &t->mu);
    if (st != DP_OK)
        return st;
    double norm = 0;
    for (size_t i = 0; i < M->size1; i++)
        for (size_t j = 0; j < M->size2; j++)
            norm = fmax(norm, fabs(gsl_matrix_get(M, i, j)));
    /* µ is computed to about eps * |M|: below that its sign is not known, so "positive" needs more. */
    double tol = 1e-12 * norm * (double)M->size1;
    t->pd_symmetric = t->mu > tol;
    t->psd = t->mu >= -tol;
    t->lipschitz = t->pd_symmetric ? 1.0 / t->mu : INFINITY;
    t->minor = NAN;
    if (M->size1 <= DP_LCP_ENUM_MAX)
        p_matrix_test(M, t);
    else
        t->p_matrix = t->pd_symmetric ? 1 : -1;
    return DP_OK;
}
