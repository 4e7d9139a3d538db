/* src/core/solvers/network/network_regularized.c - the existence scheme (PCn) on a network: every element's damper graph A
 * replaced by its Yosida approximation A_(1/n) (Pražák & Rajagopal 2016, (17)), every graph spring likewise, so that
 *
 *     x' = v,   M v' = f(t) - K x - C v + sum_e c_e v_b,e b_e - sum_e b_e [S_1/n(u_e) + A_1/n(z_e - v_b) - gamma(z_e - v_b)]
 *
 * is an ODE in R^2n, integrated by GSL odeiv2 with its analytic Jacobian (dense: at most
 * DP_NETWORK_MAX_MATRIX_NODES nodes). It is the exact stepping's independent check: as n grows its solution
 * converges to the network's (at rate 1/n, as for one mass). Rows carry no phase: nothing sticks exactly.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include "dashpot/regularized.h"
#include "base/band.h"
#include "solvers/network/network_run.h"
#include "solvers/regularized.h"

struct dp_network_regularized {
    struct dp_network_run *nr;
    gsl_odeiv2_system sys;
    gsl_odeiv2_driver *drv;
    double lam;            /* 1/n */
    double *Minv;          /* n x n, dense */
    double *y, *F, *acc, *D;   /* state (2n), forces (n), M^-1 F (n), per-element slopes (ne) */
    double t;
    unsigned long long fevals;
};

/* An element's regularized force at elongation u and rate z, and (slopes) its derivatives in u and z. */
static double element_force(const struct dp_network_run *nr, size_t i, double u, double z, double lam, double *du,
                            double *dz)
{
    const dp_element *e = &nr->net->el[i];
    double f = 0, s = 0, vb = e->has_damper ? e->damper.belt_velocity : 0;
    *du = *dz = 0;
    if (e->has_spring && !dp_spring_linear(&e->spring))
        f += dp_graph_yosida_slope(&e->spring.graph, lam, u, du);
    if (e->has_contact && u < e->contact.distance) {   /* compliant (rigid ones are refused) */
        f += network_run_compliant_force(&e->contact, u);
        *du += e->contact.compliance;
    }
    if (e->has_damper) {
        f += dp_graph_yosida_slope(&e->damper.graph, lam, z - vb, &s);
        *dz += s;
        if (e->damper.relaxation.kind != DP_RELAX_NONE) {
            f -= dp_relaxation_eval(&e->damper.relaxation, z - vb);
            *dz -= dp_relaxation_slope(&e->damper.relaxation, z - vb);
        }
    }
    return f;
}

/* F = f(t) - K x - C v + belt terms - sum_e b_e (nonlinear force); acc = M^-1 F. */
static void forces(struct dp_network_regularized *g, double t, const double y[])
{
    struct dp_network_run *nr = g->nr;
    size_t n = nr->n;
    const double *x = y, *v = y + n;
    dp_band_symv(nr->K, n, nr->p, x, g->F);
    dp_band_symv(nr->C, n, nr->p, v, g->acc);
    for (size_t i = 0; i < n; i++)
        g->F[i] = -g->F[i] - g->acc[i];
    for (size_t i = 0; i < nr->net->nforce; i++)
        g->F[nr->net->force[i].node] += dp_forcing_eval(&nr->net->force[i].f, t);
    for (size_t i = 0; i < nr->nel; i++) {
        const dp_element *e = &nr->net->el[i];
        double du, dz, vb = e->has_damper ? e->damper.belt_velocity : 0;
        double f = nr->c[i] * -vb + element_force(nr, i, network_run_rel(e->a, e->b, x), network_run_rel(e->a, e->b, v), g->lam,
                                                  &du, &dz);
        if (e->b >= 0)
            g->F[e->b] -= f;
        if (e->a >= 0)
            g->F[e->a] += f;
    }
    for (size_t i = 0; i < n; i++) {
        double s = 0;
        for (size_t j = 0; j < n; j++)
            s += g->Minv[i * n + j] * g->F[j];
        g->acc[i] = s;
    }
}

static int rhs(double t, const double y[], double f[], void *p)
{
    struct dp_network_regularized *g = p;
    size_t n = g->nr->n;
    g->fevals++;
    forces(g, t, y);
    memcpy(f, y + n, n * sizeof *f);
    memcpy(f + n, g->acc, n * sizeof *f);
    for (size_t i = 0; i < 2 * n; i++)
        if (!isfinite(f[i]))
            return GSL_EBADFUNC;
    return GSL_SUCCESS;
}

/* A += w b b^T (dense n x n) for an element's incidence vector. */
static void add_bbT(double *A, size_t n, long a, long b, double w)
{
    if (a >= 0)
        A[(size_t)a * n + (size_t)a] += w;
    if (b >= 0)
        A[(size_t)b * n + (size_t)b] += w;
    if (a >= 0 && b >= 0) {
        A[(size_t)a * n + (size_t)b] -= w;
        A[(size_t)b * n + (size_t)a] -= w;
    }
}

/* The stiffness and damping the linear parts and the regularized laws present at y, dense. */
static void tangents(const struct dp_network_regularized *g, const double y[], double *Kt, double *Ct)
{
    const struct dp_network_run *nr = g->nr;
    size_t n = nr->n, p1 = nr->p + 1;
    memset(Kt, 0, n * n * sizeof *Kt);
    memset(Ct, 0, n * n * sizeof *Ct);
    for (size_t i = 0; i < n; i++)
        for (size_t d = 0; d < p1 && i + d < n; d++) {
            Kt[(i + d) * n + i] = Kt[i * n + i + d] = nr->K[i * p1 + d];
            Ct[(i + d) * n + i] = Ct[i * n + i + d] = nr->C[i * p1 + d];
        }
    for (size_t i = 0; i < nr->nel; i++) {
        const dp_element *e = &nr->net->el[i];
        double du, dz;
        element_force(nr, i, network_run_rel(e->a, e->b, y), network_run_rel(e->a, e->b, y + n), g->lam, &du, &dz);
        add_bbT(Kt, n, e->a, e->b, du);
        add_bbT(Ct, n, e->a, e->b, dz);
    }
}

static int jacobian(double t, const double y[], double *dfdy, double dfdt[], void *p)
{
    struct dp_network_regularized *g = p;
    const struct dp_network_run *nr = g->nr;
    size_t n = nr->n, m = 2 * n;
    double *Kt = malloc(2 * n * n * sizeof *Kt), *Ct = Kt ? Kt + n * n : NULL;
    if (Kt == NULL)
        return GSL_ENOMEM;
    tangents(g, y, Kt, Ct);
    memset(dfdy, 0, m * m * sizeof *dfdy);
    for (size_t i = 0; i < n; i++) {
        dfdy[i * m + n + i] = 1;
        for (size_t j = 0; j < n; j++) {
            double sk = 0, sc = 0;
            for (size_t k = 0; k < n; k++)
                sk += g->Minv[i * n + k] * Kt[k * n + j], sc += g->Minv[i * n + k] * Ct[k * n + j];
            dfdy[(n + i) * m + j] = -sk;
            dfdy[(n + i) * m + n + j] = -sc;
        }
    }
    free(Kt);
    for (size_t i = 0; i < n; i++)
        dfdt[i] = 0, g->F[i] = 0;
    for (size_t i = 0; i < nr->net->nforce; i++)
        g->F[nr->net->force[i].node] += dp_forcing_rate(&nr->net->force[i].f, t);
    for (size_t i = 0; i < n; i++) {
        double s = 0;
        for (size_t j = 0; j < n; j++)
            s += g->Minv[i * n + j] * g->F[j];
        dfdt[n + i] = s;
    }
    return GSL_SUCCESS;
}

/* The row's forces at the integrator's state: Fs = k u + S_1/n(u), Fd = c (z - v_b) + A_1/n(z - v_b) - gamma. */
static void row_forces(struct dp_network_regularized *g)
{
    struct dp_network_run *nr = g->nr;
    for (size_t i = 0; i < nr->nel; i++) {
        const dp_element *e = &nr->net->el[i];
        double u = network_run_rel(e->a, e->b, nr->x), z = network_run_rel(e->a, e->b, nr->v), du, dz, s = 0, d = 0, vb = 0;
        if (e->has_spring && !dp_spring_linear(&e->spring))
            s = dp_graph_yosida_slope(&e->spring.graph, g->lam, u, &du);
        if (e->has_damper) {
            vb = e->damper.belt_velocity;
            d = element_force(nr, i, u, z, g->lam, &du, &dz) - s - (e->has_contact ? network_run_compliant_force(&e->contact, u) : 0);
        }
        nr->Fs[i] = nr->k[i] * u + s;
        nr->Fd[i] = nr->c[i] * (z - vb) + d;
        nr->phase[i] = DP_PHASE_NONE;
    }
    network_run_contacts_forces(nr, 0);
}

/* M^-1, dense: the inverse masses, or the mass matrix inverted through its Cholesky factor. */
static int invert_mass(struct dp_network_regularized *g)
{
    const dp_network *net = g->nr->net;
    size_t n = net->n;
    if (net->mass) {
        for (size_t i = 0; i < n; i++)
            g->Minv[i * n + i] = 1 / net->mass[i];
        return DP_OK;
    }
    memcpy(g->Minv, net->M, n * n * sizeof *g->Minv);
    gsl_matrix_view v = gsl_matrix_view_array(g->Minv, n, n);
    if (gsl_linalg_cholesky_decomp1(&v.matrix) != 0 || gsl_linalg_cholesky_invert(&v.matrix) != 0)
        return DP_EINVAL;
    return DP_OK;
}

int dp_network_regularized_init(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    const dp_solver_spec *sv = &r->spec.solver;
    size_t n = nr->n;
    struct dp_network_regularized *g = calloc(1, sizeof *g);
    if (g == NULL)
        return DP_ENOMEM;
    nr->reg = g;
    g->nr = nr;
    g->lam = 1 / sv->n_list[0];
    g->Minv = calloc(n * n, sizeof *g->Minv);
    g->y = calloc(2 * n, sizeof *g->y);
    g->F = calloc(n, sizeof *g->F);
    g->acc = calloc(n, sizeof *g->acc);
    if (!g->Minv || !g->y || !g->F || !g->acc)
        return DP_ENOMEM;
    if (invert_mass(g) != DP_OK)
        return dp_run_fail(r, DP_EINVAL, "the mass matrix could not be inverted");
    g->sys = (gsl_odeiv2_system){ rhs, jacobian, 2 * n, g };
    /* a first step below the fastest time scale, m / (n + stiffness): the error control grows it */
    double h0 = 1e-3 / (sv->n_list[0] + 1);
    g->drv = gsl_odeiv2_driver_alloc_y_new(&g->sys, dp_regularized_step_type(sv->stepper), h0, sv->atol, sv->rtol);
    if (g->drv == NULL)
        return DP_ENOMEM;
    gsl_odeiv2_driver_set_nmax(g->drv, (unsigned long)fmin(r->max_steps, 4e9));
    memcpy(g->y, nr->x, n * sizeof *g->y);
    memcpy(g->y + n, nr->v, n * sizeof *g->y);
    row_forces(g);
    return DP_OK;
}

void dp_network_regularized_free(struct dp_network_regularized *g)
{
    if (g == NULL)
        return;
    if (g->drv)
        gsl_odeiv2_driver_free(g->drv);
    free(g->Minv), free(g->y), free(g->F), free(g->acc);
    free(g);
}

/* Integrates from g->t to t1 one accepted step at a time (the driver's evolve, control and step), asking the
 * run's stop hook between steps with the right-hand side evaluations (n x n work each) as the measure, so a
 * deadline or a hang-up ends even a long stretch without samples. GSL_CONTINUE when the hook said so. */
static int integrate_to(dp_run *r, double t1)
{
    struct dp_network_regularized *g = network_run_of(r)->reg;
    gsl_odeiv2_driver *d = g->drv;
    unsigned long long size = (unsigned long long)(network_run_of(r)->n * network_run_of(r)->n + network_run_of(r)->nel + 1);
    while (g->t < t1) {
        if (dp_run_stopped(r, r->n + g->fevals * size))
            return GSL_CONTINUE;
        if (d->n++ >= d->nmax)
            return GSL_EMAXITER;
        int s = gsl_odeiv2_evolve_apply(d->e, d->c, d->s, d->sys, &g->t, t1, &d->h, g->y);
        if (s != GSL_SUCCESS)
            return s;
    }
    return GSL_SUCCESS;
}

/* Integrates to the next output instant (the next sample due, or t_end), one row there. */
int dp_network_regularized_advance(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    struct dp_network_regularized *g = nr->reg;
    size_t n = nr->n;
    if (network_run_reserve_rows(r) != DP_OK)
        return DP_ENOMEM;
    network_run_flush(r);
    while (r->out_n < r->out_cap && !dp_row_queue_waiting(&nr->queue) && nr->slots.used < nr->slots.cap && !r->finished) {
        unsigned long long next = r->n + (unsigned long long)(r->countdown > 0 ? r->countdown : 1);
        if (next > r->nsteps || !r->spec.output.samples)
            next = r->nsteps;
        double t1 = next < r->nsteps ? (double)next * r->h : r->spec.solver.t_end;
        int s = integrate_to(r, t1);
        if (s == GSL_CONTINUE)
            return r->status;       /* stopped (DP_ECANCEL) or asked to yield between steps */
        r->sum.fevals = g->fevals;
        if (s == GSL_EBADFUNC)
            return dp_run_fail(r, DP_ENONFINITE, "the solution diverged at t = %.17g (non-finite right-hand side)",
                               g->t);
        if (s != GSL_SUCCESS)
            return dp_run_fail(r, DP_ESOLVE, "the %s integrator failed at t = %.17g: %s",
                               dp_stepper_name(r->spec.solver.stepper), g->t, gsl_strerror(s));
        r->countdown -= (long)(next - r->n);
        r->n = next;
        r->cur.t = t1;
        memcpy(nr->x, g->y, n * sizeof *g->y);
        memcpy(nr->v, g->y + n, n * sizeof *g->y);
        row_forces(g);
        if (!network_run_state_finite(nr))
            return dp_run_fail(r, DP_ENONFINITE, "the solution diverged at t = %.17g", t1);
        r->sum.steps = r->n;
        if (r->n >= r->nsteps) {
            r->finished = 1;
            network_run_finalize_summary(r);
        }
        if (r->countdown <= 0 || r->n >= r->nsteps)
            network_run_emit_row(r);
    }
    return DP_OK;
}
