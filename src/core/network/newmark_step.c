/* src/core/network/newmark_step.c - Newmark's method in Höschl's incremental tangent-stiffness form
 * (Höschl 1983, §15, Ex. 40; include/dashpot/newmark.h): the coefficients and one step over band matrices,
 * shared by the one-mass and the network Newmark runs.
 *
 * Why incremental: this is how Höschl integrates his elastic-plastic example by hand (each step one linear
 * solve with the tangent stiffness of the springs' current state); for linear systems it is the standard
 * Newmark method exactly, which test_newmark.c checks step for step against the textbook form.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>

#include "dashpot/newmark.h"
#include "base/band.h"
#include "network/newmark_step.h"

void dp_newmark_coef_init(double beta, double gamma, double h, dp_newmark_coef *c)
{
    c->kM = 1 / (beta * h * h);
    c->kC = gamma / (beta * h);
    c->pMv = 1 / (beta * h);
    c->pMa = 1 / (2 * beta);
    c->pCv = gamma / beta;
    c->pCa = h * (gamma / (2 * beta) - 1);
    c->vx = gamma / (beta * h);
    c->vv = -gamma / beta;
    c->va = h * (1 - gamma / (2 * beta));
}

/* ---- one step over band matrices ---------------------------------------------------------------------- */

dp_nm *dp_nm_alloc(size_t n, size_t p, size_t nep)
{
    dp_nm *w = calloc(1, sizeof *w);
    if (w == NULL)
        return NULL;
    size_t band = n * (p + 1);
    w->n = n, w->p = p, w->nep = nep;
    w->a = calloc(n, sizeof *w->a);
    w->Khat = calloc(band, sizeof *w->Khat);
    w->Mfac = calloc(band, sizeof *w->Mfac);
    w->r = calloc(n, sizeof *w->r);
    w->tmp = calloc(n, sizeof *w->tmp);
    w->Pold = calloc(n, sizeof *w->Pold);
    w->tan = calloc(nep ? nep : 1, 1);
    if (!w->a || !w->Khat || !w->Mfac || !w->r || !w->tmp || !w->Pold || !w->tan) {
        dp_nm_free(w);
        return NULL;
    }
    return w;
}

void dp_nm_free(dp_nm *w)
{
    if (w == NULL)
        return;
    free(w->a), free(w->Khat), free(w->Mfac), free(w->r), free(w->tmp), free(w->Pold), free(w->tan);
    free(w);
}

void dp_nm_accel(dp_nm *w, const double *x, const double *v, const double *P, const double *Fep)
{
    size_t n = w->n;
    memcpy(w->a, P, n * sizeof *w->a);
    dp_band_axpy(w->C, n, w->p, -1, v, w->a);
    dp_band_axpy(w->K, n, w->p, -1, x, w->a);
    for (size_t i = 0; i < w->nep; i++) {   /* the force F acts as -F on b, +F on a */
        if (w->eb[i] >= 0)
            w->a[w->eb[i]] -= Fep[i];
        if (w->ea[i] >= 0)
            w->a[w->ea[i]] += Fep[i];
    }
    dp_band_cholesky_solve(w->Mfac, n, w->p, w->a);   /* M was factored by dp_nm_start */
    memcpy(w->Pold, P, n * sizeof *P);
}

int dp_nm_start(dp_nm *w, const double *x, const double *v, const double *P, const double *Fep)
{
    memcpy(w->Mfac, w->M, w->n * (w->p + 1) * sizeof *w->Mfac);
    if (dp_band_cholesky(w->Mfac, w->n, w->p) != DP_OK)
        return DP_ESOLVE;
    dp_nm_accel(w, x, v, P, Fep);
    return DP_OK;
}

/* K^ for step h and the tangent pattern `flow`, refactored only when either changed. */
static int khat(dp_nm *w, double h, const dp_newmark_coef *c, const signed char *flow)
{
    int same = w->factored && h == w->h_fac;
    for (size_t i = 0; same && i < w->nep; i++)
        same = w->tan[i] == (flow[i] == 0);
    if (same)
        return DP_OK;
    size_t len = w->n * (w->p + 1);
    for (size_t i = 0; i < len; i++)
        w->Khat[i] = w->K[i] + c->kC * w->C[i] + c->kM * w->M[i];
    for (size_t i = 0; i < w->nep; i++) {
        w->tan[i] = flow[i] == 0;
        if (w->tan[i])
            dp_band_add_incidence(w->Khat, w->p, w->ea[i], w->eb[i], w->ek[i]);
    }
    w->factored = dp_band_cholesky(w->Khat, w->n, w->p) == DP_OK;
    w->h_fac = h;
    return w->factored ? DP_OK : DP_ESOLVE;
}

int dp_nm_step(dp_nm *w, double h, const double *Pnew, const signed char *flow, double *x, double *v)
{
    size_t n = w->n;
    dp_newmark_coef c;
    dp_newmark_coef_init(w->beta, w->gamma, h, &c);
    if (khat(w, h, &c, flow) != DP_OK)
        return DP_ESOLVE;
    for (size_t i = 0; i < n; i++) {
        w->r[i] = Pnew[i] - w->Pold[i];
        w->tmp[i] = c.pMv * v[i] + c.pMa * w->a[i];
    }
    dp_band_axpy(w->M, n, w->p, 1, w->tmp, w->r);
    for (size_t i = 0; i < n; i++)
        w->tmp[i] = c.pCv * v[i] + c.pCa * w->a[i];
    dp_band_axpy(w->C, n, w->p, 1, w->tmp, w->r);
    if (dp_band_cholesky_solve(w->Khat, n, w->p, w->r) != DP_OK)
        return DP_ESOLVE;
    for (size_t i = 0; i < n; i++) {
        x[i] += w->r[i];
        v[i] += c.vx * w->r[i] + c.vv * v[i] + c.va * w->a[i];
    }
    return DP_OK;
}
