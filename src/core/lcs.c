/* src/core/lcs.c - the θ-step of a linear complementarity system (seed 002 (1.10); systems.md §5):
 * x+ = x + h (A (θ x+ + (1-θ) x) + B u+ + p), w+ = C x+ + D u+ + q, (u+, w+) in the laws, so
 * x+ = x^ + h W B u+ with W = (I - hθA)^-1, x^ = W ((I + h(1-θ)A) x + h p), and u+ solves one LCP
 * w+ = (D + h C W B) u+ + (C x^ + q) per step, by Lemke's method.
 *
 * An interval law u ∈ [lo, hi], w ∈ -N_[lo,hi](u) becomes two complementarity rows: z1 = u - lo ⊥ w + z2 and
 * z2 ⊥ (hi - lo) - z1, z2 = max(-w, 0) (u strictly inside forces z2 = 0 and w = 0; u = hi lets w = -z2 <= 0;
 * u = lo keeps w + z2 >= 0 with z2 = 0). The augmented matrix [[M, J], [-Jᵀ, 0]] adds a skew block, so a
 * positive (semi)definite M stays so and Lemke still decides.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_blas.h>
#include <gsl/gsl_linalg.h>

#include "dashpot/lcs.h"
#include "dashpot/status.h"

struct dp_lcs_stepper {
    size_t n, m, ma;            /* states, components, LCP size (m + interval components) */
    gsl_matrix *E, *WB, *C, *D, *M, *Ma, *W;
    double h;
    gsl_vector *Whp, *q, *lo, *hi;
    size_t *slot;               /* interval component i's second row, or 0 for complementarity */
    gsl_vector *xh, *r, *qa, *za, *wa, *u;
    dp_lcp *lcp;
};

void dp_lcs_stepper_free(dp_lcs_stepper *st)
{
    if (st == NULL)
        return;
    gsl_matrix *mats[] = { st->E, st->WB, st->C, st->D, st->M, st->Ma, st->W };
    gsl_vector *vecs[] = { st->Whp, st->q, st->lo, st->hi, st->xh, st->r, st->qa, st->za, st->wa, st->u };
    for (size_t i = 0; i < sizeof mats / sizeof mats[0]; i++)
        gsl_matrix_free(mats[i]);
    for (size_t i = 0; i < sizeof vecs / sizeof vecs[0]; i++)
        gsl_vector_free(vecs[i]);
    free(st->slot);
    dp_lcp_free(st->lcp);
    free(st);
}

static int finite_all(const double *a, size_t k)
{
    for (size_t i = 0; i < k; i++)
        if (!isfinite(a[i]))
            return 0;
    return 1;
}

static int valid(const dp_lcs *s, double h, double theta)
{
    if (s->n == 0 || s->m == 0 || s->m > DP_LCP_MAX / 2 || s->n > 4096 || !(h >= 0) || !isfinite(h) ||
        !(theta >= 0 && theta <= 1))
        return 0;
    size_t n = s->n, m = s->m;
    if (!finite_all(s->A, n * n) || !finite_all(s->B, n * m) || !finite_all(s->C, m * n) ||
        !finite_all(s->D, m * m) || !finite_all(s->p, n) || !finite_all(s->q, m))
        return 0;
    for (size_t i = 0; i < m; i++)
        if (s->law[i].kind == DP_LCS_INTERVAL &&
            !(isfinite(s->law[i].lo) && isfinite(s->law[i].hi) && s->law[i].lo <= s->law[i].hi))
            return 0;
    return 1;
}

/* W = (I - hθA)^-1, E = W (I + h(1-θ)A), WB = h W B, Whp = h W p. 0 when I - hθA is singular. */
static int discretize(dp_lcs_stepper *st, const dp_lcs *s, double h, double theta)
{
    size_t n = s->n, m = s->m;
    gsl_matrix *L = gsl_matrix_alloc(n, n), *R = gsl_matrix_alloc(n, n);
    gsl_permutation *p = gsl_permutation_alloc(n);
    int ok = L && R && p, sign;
    for (size_t i = 0; ok && i < n; i++)
        for (size_t j = 0; j < n; j++) {
            double a = s->A[i * n + j], d = i == j;
            gsl_matrix_set(L, i, j, d - h * theta * a);
            gsl_matrix_set(R, i, j, d + h * (1 - theta) * a);
        }
    ok = ok && gsl_linalg_LU_decomp(L, p, &sign) == GSL_SUCCESS && gsl_linalg_LU_det(L, sign) != 0;
    ok = ok && gsl_linalg_LU_invert(L, p, st->W) == GSL_SUCCESS;
    for (size_t j = 0; ok && j < n; j++) {
        gsl_vector_view col = gsl_matrix_column(R, j), out = gsl_matrix_column(st->E, j);
        ok = gsl_linalg_LU_solve(L, p, &col.vector, &out.vector) == GSL_SUCCESS;
    }
    for (size_t j = 0; ok && j < m; j++) {
        gsl_vector_view out = gsl_matrix_column(st->WB, j);
        for (size_t i = 0; i < n; i++)
            gsl_vector_set(st->xh, i, h * s->B[i * m + j]);
        ok = gsl_linalg_LU_solve(L, p, st->xh, &out.vector) == GSL_SUCCESS;
    }
    for (size_t i = 0; ok && i < n; i++)
        gsl_vector_set(st->xh, i, h * s->p[i]);
    ok = ok && gsl_linalg_LU_solve(L, p, st->xh, st->Whp) == GSL_SUCCESS;
    gsl_matrix_free(L);
    gsl_matrix_free(R);
    gsl_permutation_free(p);
    return ok;
}

/* M = D + C WB, and the augmented matrix with each interval's pair of rows. */
static void assemble(dp_lcs_stepper *st, const dp_lcs *s)
{
    size_t m = s->m, k = m;
    gsl_matrix_memcpy(st->M, st->D);
    gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, st->C, st->WB, 1.0, st->M);
    gsl_matrix_set_zero(st->Ma);
    for (size_t i = 0; i < m; i++)
        for (size_t j = 0; j < m; j++)
            gsl_matrix_set(st->Ma, i, j, gsl_matrix_get(st->M, i, j));
    for (size_t i = 0; i < m; i++) {
        int interval = s->law[i].kind == DP_LCS_INTERVAL;
        gsl_vector_set(st->lo, i, interval ? s->law[i].lo : 0.0);
        gsl_vector_set(st->hi, i, interval ? s->law[i].hi : INFINITY);
        st->slot[i] = interval ? k : 0;
        if (interval) {
            gsl_matrix_set(st->Ma, i, k, 1.0);
            gsl_matrix_set(st->Ma, k, i, -1.0);
            k++;
        }
    }
}

dp_lcs_stepper *dp_lcs_stepper_alloc(const dp_lcs *s, double h, double theta, int *status)
{
    *status = DP_EINVAL;
    if (!valid(s, h, theta))
        return NULL;
    *status = DP_ENOMEM;
    dp_lcs_stepper *st = calloc(1, sizeof *st);
    if (st == NULL)
        return NULL;
    size_t n = s->n, m = s->m, ma = m;
    for (size_t i = 0; i < m; i++)
        ma += s->law[i].kind == DP_LCS_INTERVAL;
    st->n = n, st->m = m, st->ma = ma;
    st->E = gsl_matrix_alloc(n, n), st->WB = gsl_matrix_alloc(n, m), st->C = gsl_matrix_alloc(m, n);
    st->D = gsl_matrix_alloc(m, m), st->M = gsl_matrix_alloc(m, m), st->Ma = gsl_matrix_alloc(ma, ma);
    st->W = gsl_matrix_alloc(n, n), st->h = h;
    st->Whp = gsl_vector_alloc(n), st->q = gsl_vector_alloc(m), st->lo = gsl_vector_alloc(m);
    st->hi = gsl_vector_alloc(m), st->xh = gsl_vector_alloc(n), st->r = gsl_vector_alloc(m);
    st->qa = gsl_vector_alloc(ma), st->za = gsl_vector_alloc(ma), st->wa = gsl_vector_alloc(ma);
    st->u = gsl_vector_alloc(m), st->slot = calloc(m, sizeof *st->slot), st->lcp = dp_lcp_alloc(ma);
    if (!st->E || !st->WB || !st->W || !st->C || !st->D || !st->M || !st->Ma || !st->Whp || !st->q || !st->lo || !st->hi ||
        !st->xh || !st->r || !st->qa || !st->za || !st->wa || !st->u || !st->slot || !st->lcp) {
        dp_lcs_stepper_free(st);
        return NULL;
    }
    memcpy(st->C->data, s->C, m * n * sizeof(double));
    memcpy(st->D->data, s->D, m * m * sizeof(double));
    memcpy(st->q->data, s->q, m * sizeof(double));
    if (!discretize(st, s, h, theta)) {
        *status = DP_EINVAL;
        dp_lcs_stepper_free(st);
        return NULL;
    }
    assemble(st, s);
    *status = DP_OK;
    return st;
}

void dp_lcs_stepper_set_p(dp_lcs_stepper *st, const double *p)
{
    gsl_vector_const_view pv = gsl_vector_const_view_array(p, st->n);
    gsl_blas_dgemv(CblasNoTrans, st->h, st->W, &pv.vector, 0.0, st->Whp);
}

const gsl_matrix *dp_lcs_step_matrix(const dp_lcs_stepper *st)
{
    return st->M;
}

int dp_lcs_step(dp_lcs_stepper *st, double *x, double *u, double *w, dp_lcp_result *res)
{
    size_t n = st->n, m = st->m;
    gsl_vector_view xv = gsl_vector_view_array(x, n);
    /* x^ = E x + h W p; r = C x^ + q */
    gsl_blas_dgemv(CblasNoTrans, 1.0, st->E, &xv.vector, 0.0, st->xh);
    gsl_vector_add(st->xh, st->Whp);
    gsl_vector_memcpy(st->r, st->q);
    gsl_blas_dgemv(CblasNoTrans, 1.0, st->C, st->xh, 1.0, st->r);
    /* the LCP's q: r + M lo in the rows of u, hi - lo in the second rows of intervals */
    for (size_t i = 0; i < m; i++) {
        double s = gsl_vector_get(st->r, i);
        for (size_t j = 0; j < m; j++)
            s += gsl_matrix_get(st->M, i, j) * gsl_vector_get(st->lo, j);
        gsl_vector_set(st->qa, i, s);
        if (st->slot[i])
            gsl_vector_set(st->qa, st->slot[i], gsl_vector_get(st->hi, i) - gsl_vector_get(st->lo, i));
    }
    int s = dp_lcp_lemke(st->lcp, st->Ma, st->qa, st->za, st->wa, res);
    if (s != DP_OK)
        return s;
    if (res->outcome != DP_LCP_SOLVED)
        return DP_ESOLVE;
    for (size_t i = 0; i < m; i++) {
        double ui = gsl_vector_get(st->za, i) + gsl_vector_get(st->lo, i);
        if (st->slot[i])
            ui = fmin(ui, gsl_vector_get(st->hi, i)); /* rounding past the end of the interval */
        gsl_vector_set(st->u, i, ui);
    }
    /* x+ = x^ + h W B u+, w+ = C x+ + D u+ + q */
    gsl_vector_memcpy(&xv.vector, st->xh);
    gsl_blas_dgemv(CblasNoTrans, 1.0, st->WB, st->u, 1.0, &xv.vector);
    gsl_vector_view wv = gsl_vector_view_array(w, m);
    gsl_vector_memcpy(&wv.vector, st->q);
    gsl_blas_dgemv(CblasNoTrans, 1.0, st->C, &xv.vector, 1.0, &wv.vector);
    gsl_blas_dgemv(CblasNoTrans, 1.0, st->D, st->u, 1.0, &wv.vector);
    memcpy(u, st->u->data, m * sizeof *u);
    return DP_OK;
}
