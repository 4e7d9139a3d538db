/* src/core/newmark.c - Newmark's method in Höschl's incremental tangent-stiffness form (seed 003 §15,
 * Ex. 40; include/dashpot/newmark.h): the coefficients, the stability limit, the solver's rules, one step
 * over band matrices, and the one-mass run.
 *
 * Why incremental: this is how Höschl integrates his elastic-plastic example by hand (each step one linear
 * solve with the tangent stiffness of the springs' current state); for linear systems it is the standard
 * Newmark method exactly, which test_newmark.c checks step for step against the textbook form.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>

#include "dashpot/newmark.h"
#include "network/newmark_step.h"
#include "record/run_internal.h"

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

/* ---- the rules ---------------------------------------------------------------------------------------- */

static void check_laws(const dp_spring *sp, int has_spring, const dp_damper *d, int has_damper, const char *at,
                       dp_errors *e)
{
    char p[DP_POINTER_MAX];
    if (has_spring && !dp_spring_linear(sp) && !dp_spring_plastic(sp)) {
        snprintf(p, sizeof p, "%s/spring/law", at);
        dp_errors_add(e, p, "the newmark solver takes linear and elastoplastic springs; a %s spring is stepped by "
                      "the stick-slip solver", dp_spring_law_name(sp->law));
    }
    if (has_damper && !dp_damper_linear(d)) {
        snprintf(p, sizeof p, "%s/damper/law", at);
        dp_errors_add(e, p, "the newmark solver takes linear dampers only: a %s damper is set-valued (it can "
                      "stick), which only the stick-slip solver steps exactly: use \"kind\": \"stick-slip\"",
                      dp_damper_law_name(d->law));
    } else if (has_damper && d->relaxation.kind != DP_RELAX_NONE) {
        snprintf(p, sizeof p, "%s/damper/relaxation", at);
        dp_errors_add(e, p, "the newmark solver takes linear dampers without relaxation: use the stick-slip "
                      "solver");
    }
}

void dp_newmark_check(const dp_spec *s, dp_errors *e)
{
    const dp_solver_spec *sv = &s->solver;
    if (!(sv->beta > 0 && sv->beta <= 0.5))
        dp_errors_add(e, "/solver/beta", "must be in (0, 0.5], got %g", sv->beta);
    if (!(sv->gamma >= 0.5 && sv->gamma <= 1))
        dp_errors_add(e, "/solver/gamma", "must be in [0.5, 1], got %g", sv->gamma);
    if (s->net == NULL) {
        check_laws(&s->model.spring, 1, &s->model.damper, 1, "/model", e);
        return;
    }
    if (s->net->n > DP_NETWORK_MAX_MATRIX_NODES)
        dp_errors_add(e, "/model/masses", "the newmark solver reports the stability limit of the highest mode from "
                      "a dense eigenproblem: at most %d nodes, got %zu", DP_NETWORK_MAX_MATRIX_NODES, s->net->n);
    for (size_t i = 0; i < s->net->nel; i++) {
        char at[64];
        const dp_element *el = &s->net->el[i];
        snprintf(at, sizeof at, "/model/elements/%zu", i);
        check_laws(&el->spring, el->has_spring, &el->damper, el->has_damper, at, e);
    }
}

/* ---- the stability limit ------------------------------------------------------------------------------ */

/* The highest omega^2 of K phi = omega^2 M phi with every spring's elastic stiffness. */
static int omega2_max(const dp_spec *s, double *w2)
{
    if (s->net == NULL) {
        const dp_spring *sp = &s->model.spring;
        *w2 = sp->k / s->model.mass;
        return DP_OK;
    }
    const dp_network *net = s->net;
    size_t n = net->n;
    gsl_matrix *M = gsl_matrix_calloc(n, n), *K = gsl_matrix_calloc(n, n);
    gsl_vector *ev = gsl_vector_alloc(n);
    gsl_eigen_gensymm_workspace *ws = gsl_eigen_gensymm_alloc(n);
    int st = DP_ENOMEM;
    if (M && K && ev && ws) {
        dp_network_linear_parts(net, M->data, K->data, NULL);
        for (size_t i = 0; i < net->nel; i++) {
            const dp_element *el = &net->el[i];
            if (!el->has_spring || !dp_spring_plastic(&el->spring))
                continue;
            long a = el->a, b = el->b;
            double k = el->spring.k;
            if (a >= 0)
                *gsl_matrix_ptr(K, (size_t)a, (size_t)a) += k;
            if (b >= 0)
                *gsl_matrix_ptr(K, (size_t)b, (size_t)b) += k;
            if (a >= 0 && b >= 0)
                *gsl_matrix_ptr(K, (size_t)a, (size_t)b) -= k, *gsl_matrix_ptr(K, (size_t)b, (size_t)a) -= k;
        }
        st = gsl_eigen_gensymm(K, M, ev, ws) == 0 ? DP_OK : DP_ESOLVE;
        *w2 = 0;
        for (size_t i = 0; st == DP_OK && i < n; i++)
            *w2 = fmax(*w2, gsl_vector_get(ev, i));
    }
    gsl_eigen_gensymm_free(ws);
    gsl_vector_free(ev);
    gsl_matrix_free(M);
    gsl_matrix_free(K);
    return st;
}

int dp_newmark_limit_of(const dp_spec *s, dp_newmark_limit *out)
{
    double w2, beta = s->solver.beta, gamma = s->solver.gamma;
    int st = omega2_max(s, &w2);
    if (st != DP_OK)
        return st;
    out->omega_max = sqrt(w2);
    out->T_min = w2 > 0 ? 2 * M_PI / out->omega_max : INFINITY;
    out->ratio = s->solver.dt / out->T_min;
    out->ratio_limit = 2 * beta >= gamma ? INFINITY : 1 / sqrt(gamma / 2 - beta) / (2 * M_PI);
    out->inside = out->ratio <= out->ratio_limit;
    return DP_OK;
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

/* y += s A x for a symmetric band A. */
static void band_axpy(const double *A, size_t n, size_t p, double s, const double *x, double *y)
{
    for (size_t i = 0; i < n; i++) {
        y[i] += s * A[i * (p + 1)] * x[i];
        for (size_t d = 1; d <= p && i + d < n; d++) {
            double a = s * A[i * (p + 1) + d];
            y[i] += a * x[i + d];
            y[i + d] += a * x[i];
        }
    }
}

static void band_add_element(double *B, size_t p, long a, long b, double k)
{
    if (a >= 0)
        B[(size_t)a * (p + 1)] += k;
    if (b >= 0)
        B[(size_t)b * (p + 1)] += k;
    if (a >= 0 && b >= 0) {
        size_t lo = (size_t)(a < b ? a : b), d = (size_t)labs(a - b);
        B[lo * (p + 1) + d] -= k;
    }
}

static int band_solve(double *F, size_t n, size_t p, double *x)
{
    gsl_matrix_view Fv = gsl_matrix_view_array(F, n, p + 1);
    gsl_vector_view xv = gsl_vector_view_array(x, n);
    return gsl_linalg_cholesky_band_svx(&Fv.matrix, &xv.vector) == 0 ? DP_OK : DP_ESOLVE;
}

static int band_factor(double *F, size_t n, size_t p)
{
    gsl_matrix_view Fv = gsl_matrix_view_array(F, n, p + 1);
    return gsl_linalg_cholesky_band_decomp(&Fv.matrix) == 0 ? DP_OK : DP_ESOLVE;
}

void dp_nm_accel(dp_nm *w, const double *x, const double *v, const double *P, const double *Fep)
{
    size_t n = w->n;
    memcpy(w->a, P, n * sizeof *w->a);
    band_axpy(w->C, n, w->p, -1, v, w->a);
    band_axpy(w->K, n, w->p, -1, x, w->a);
    for (size_t i = 0; i < w->nep; i++) {   /* the force F acts as -F on b, +F on a */
        if (w->eb[i] >= 0)
            w->a[w->eb[i]] -= Fep[i];
        if (w->ea[i] >= 0)
            w->a[w->ea[i]] += Fep[i];
    }
    band_solve(w->Mfac, n, w->p, w->a);   /* M was factored by dp_nm_start */
    memcpy(w->Pold, P, n * sizeof *P);
}

int dp_nm_start(dp_nm *w, const double *x, const double *v, const double *P, const double *Fep)
{
    memcpy(w->Mfac, w->M, w->n * (w->p + 1) * sizeof *w->Mfac);
    if (band_factor(w->Mfac, w->n, w->p) != DP_OK)
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
            band_add_element(w->Khat, w->p, w->ea[i], w->eb[i], w->ek[i]);
    }
    w->factored = band_factor(w->Khat, w->n, w->p) == DP_OK;
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
    band_axpy(w->M, n, w->p, 1, w->tmp, w->r);
    for (size_t i = 0; i < n; i++)
        w->tmp[i] = c.pCv * v[i] + c.pCa * w->a[i];
    band_axpy(w->C, n, w->p, 1, w->tmp, w->r);
    if (band_solve(w->Khat, n, w->p, w->r) != DP_OK)
        return DP_ESOLVE;
    for (size_t i = 0; i < n; i++) {
        x[i] += w->r[i];
        v[i] += c.vx * w->r[i] + c.vv * v[i] + c.va * w->a[i];
    }
    return DP_OK;
}

/* ---- the one-mass run --------------------------------------------------------------------------------- */

/* The load: F(t) and a viscous damper's belt term c v_b. */
static double one_mass_load(const dp_run *r, double t)
{
    const dp_damper *d = &r->spec.model.damper;
    return dp_forcing_eval(&r->spec.model.forcing, t) +
           (dp_damper_has_viscous(d) ? dp_damper_viscous(d) * d->belt_velocity : 0);
}

static void one_mass_forces(dp_run *r)
{
    const dp_model *m = &r->spec.model;
    dp_sample *c = &r->cur;
    double cv = dp_damper_viscous(&m->damper);
    c->Fs = r->ep ? r->ep_F : m->spring.k * c->x;
    c->Fc = c->Fd = cv == 0 ? 0 : cv * (c->v - m->damper.belt_velocity);
    c->phase = DP_PHASE_NONE;
    c->plastic = r->ep, c->p = r->ep ? r->ep_p : 0;
}

int dp_newmark_init(dp_run *r)
{
    dp_model *m = &r->spec.model;
    int ep = dp_spring_plastic(&m->spring);
    dp_nm *w = r->nm = dp_nm_alloc(1, 0, ep ? 1 : 0);
    if (w == NULL)
        return DP_ENOMEM;
    static const long ground = -1, node = 0;
    r->nm_M = m->mass;
    r->nm_C = dp_damper_viscous(&m->damper);
    r->nm_K = ep ? 0 : m->spring.k;
    w->M = &r->nm_M, w->C = &r->nm_C, w->K = &r->nm_K;
    w->ea = &ground, w->eb = &node, w->ek = &m->spring.k;
    w->beta = r->spec.solver.beta, w->gamma = r->spec.solver.gamma;
    r->cur.t = 0, r->cur.x = r->spec.x0, r->cur.v = r->spec.v0;
    if (ep) {
        int flow;
        r->ep = 1, r->ep_p = m->spring.offset;
        r->ep_F = dp_elastoplastic_return(&m->spring, r->cur.x, &r->ep_p, &flow);
        r->ep_flow = 0;
    }
    double P = one_mass_load(r, 0);
    if (dp_nm_start(w, &r->cur.x, &r->cur.v, &P, &r->ep_F) != DP_OK)
        return DP_ESOLVE;
    one_mass_forces(r);
    return DP_OK;
}

int dp_newmark_advance(dp_run *r)
{
    dp_nm *w = r->nm;
    const dp_spring *sp = &r->spec.model.spring;
    while (dp_run_room(r)) {
        double h = dp_run_step_length(r), x = r->cur.x, v = r->cur.v;
        r->n++;
        double t = r->n < r->nsteps ? (double)r->n * r->h : r->spec.solver.t_end, P = one_mass_load(r, t);
        signed char flow = (signed char)r->ep_flow;
        if (dp_nm_step(w, h, &P, &flow, &x, &v) != DP_OK)
            return dp_run_fail(r, DP_ESOLVE, "the Newmark step at t = %.17g has no solution", r->cur.t);
        r->cur.t = t, r->cur.x = x, r->cur.v = v;
        if (r->ep) {
            int before = r->ep_flow;
            r->ep_F = dp_elastoplastic_return(sp, x, &r->ep_p, &r->ep_flow);
            if (r->ep_flow != before)
                dp_run_emit_event(r, r->ep_flow ? DP_EVENT_YIELD : DP_EVENT_UNLOAD, t, x, v);
        }
        dp_nm_accel(w, &r->cur.x, &r->cur.v, &P, &r->ep_F);
        if (!(fabs(x) < 1e300 && fabs(v) < 1e300 && isfinite(w->a[0])))
            return dp_run_fail(r, DP_ENONFINITE, "the solution diverged at t = %.17g", t);
        r->sum.steps = r->n;
        if (r->n >= r->nsteps)
            r->finished = 1;
        if (dp_run_sample_due(r))
            one_mass_forces(r);
        dp_run_emit_state(r);
    }
    return DP_OK;
}
