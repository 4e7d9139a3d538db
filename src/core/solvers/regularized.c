/* src/core/solvers/regularized.c - the regularized existence schemes (PCn) and (PIk) as solvers (docs/mathematics.md §3).
 *
 *   (PCn), Pražák & Rajagopal 2016, (17)-(18):  m x'' + F_s(x) + F_c - gamma(u) = F(t),  u = x' - v_b,
 *                               F_c = c u + g_n(u),  g_n = A_(1/n) (yosida.c),
 *                               F_s = k x for a linear spring, S_(1/n)(x) for a graph spring (rope, points);
 *   (PIk), Babováková 2012, ch. 2:      x'' = F - f_k^-1(x) - g_k^-1(x'),  f_k^-1 = S_(1/k),  g_k^-1 = (A + c I)_(1/k),
 *                               the whole law regularized, as (FIk) does; no relaxation (the thesis has none).
 * The ODE's Lipschitz constant grows like n/m, so it is stiff: GSL odeiv2 with the analytic Jacobian
 * (piecewise constant: the slopes of the Yosida pieces, yosida.c) and an implicit stepper by default.
 * Note: GSL 2.7's gsl_linalg_LU_decomp allocates its pivot vector on every call, so the implicit steppers
 * allocate (and free) once per Newton-matrix factorization; dashpot's own step path allocates nothing.
 *
 * Samples fall on the output grid t_j = j dt whatever the internal steps. msbdf (and the explicit rkf45, rkck)
 * step freely towards t_end, which the last step lands on exactly; a sample inside an accepted step is
 * interpolated (dense.c), from data computed only for steps that hold a sample: the quintic Hermite
 * interpolant of y, y' = f and y'' = J f + df/dt at the step's ends, except in a stiff msbdf step (h |J| > 4)
 * where f(y) carries the step's error times |J|, and the polynomial through msbdf's last order + 1 values
 * (its own interpolant) is used. rk4imp, bsimp and rk8pd land on every sample instead (dp_regularized_init).
 * Landing on every sample cost msbdf a clipped step before each one and the order drop after it. On the bench
 * problem (bench/regularized.sh: Coulomb, t in [0, 30], 301 samples, tol 1e-10, n = 10..1e5) it took
 * 921-1074 steps, 0.32-0.38 ms: 10.1-10.5x faster than SciPy's LSODA at n >= 1e4 (10.0-10.9x with the
 * core busy). Stepping freely: 566-798 steps, 0.22-0.31 ms, 13.6-16.3x at n >= 1e4 (13.8-16.4x with the
 * core or both cores busy; 25x at n = 10), ~80% of it inside GSL's steps (docs/regularized.md, "Cost").
 * A regularized solution never sticks exactly, so every sample has phase NONE and F_c = g_n(u).
 * The workspace is allocated once per run; the step path allocates nothing. Every GSL return is checked:
 * a right-hand side that leaves the finite numbers is DP_ENONFINITE, any other failure DP_ESOLVE.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "dashpot/regularized.h"
#include "base/dense.h"
#include "record/sink.h"
#include "rules/rules.h"
#include "solvers/regularized.h"
#include "solvers/run_types.h"
#include "solvers/stick_slip_step.h"

/* Integrator steps taken per dp_run_next call at most, so that a front end can cancel a hard run between
 * blocks (~10 ms of msbdf work); the run resumes where it stopped. */
#define REG_STEPS_PER_CALL 100000ULL

/* A step with h rho > REG_STIFF, rho the spectral radius of the Jacobian at an end, is stiff: y' = f(y) and
 * y'' = J f + f_t there carry the step's error times rho and rho^2, which the Hermite interpolant weighs by
 * 0.15 h and 0.017 h^2 (dense.h): 0.9 times the error of y itself at h rho = 4, 170 times at h rho = 100. */
#define REG_STIFF 4.0
/* msbdf's own interpolant for stiff steps needs its last order + 1 <= 6 accepted values. */
#define REG_HISTORY 6

struct dp_regularized {
    double m, c, k, vb;         /* c: viscous part kept exact (PC); k: linear spring kept exact (PC) */
    int spring_exact;
    double ls, ld;              /* Yosida parameters: 1/n (PC) or 1/k (PI) */
    const dp_graph *S, *D;      /* spring and damper graphs that are regularized */
    dp_graph DI;                /* PI: the damper graph with its viscous part, A + c I (owned) */
    const dp_relaxation *gamma;
    const dp_forcing *F;
    gsl_odeiv2_system sys;
    gsl_odeiv2_driver *drv;
    double h;                   /* the control's step-size proposal */
    double h_floor;             /* an accepted (unclipped) step below it means the tolerances cannot be met */
    /* The last accepted step runs from a to b; b is the integrator's state. dy, d2y hold y' and y'' and rho the
     * Jacobian's spectral radius once they were asked for (jet = 1); b's carry over to a with the next step. */
    struct reg_end { double t, y[2], dy[2], d2y[2], rho; int jet; } a, b;
    int bdf;                    /* msbdf: stiff steps interpolate its history (ht, hy: a ring of hn values) */
    int land;                   /* rk4imp, bsimp, rk8pd: land on every sample (dp_regularized_init) */
    unsigned order;             /* msbdf's order on the last step */
    double ht[REG_HISTORY], hy[REG_HISTORY][2];
    size_t hn, hlast;           /* values held, index of the newest */
    unsigned long long fevals, jevals;  /* the integrator's evaluations (the interpolant's are not counted) */
};

/* ---- the law ------------------------------------------------------------------------------------------- */

/* gamma'(u); power relaxation is rejected by dp_regularized_check (unbounded slope at 0). */
static struct dp_regularized *reg_of(const dp_run *r)
{
    return r->state;
}

static double relaxation_rate(const dp_relaxation *r, double u)
{
    if (r->kind == DP_RELAX_RATIONAL) {
        double d = r->b + fabs(u);
        return r->a * r->b / (d * d);
    }
    return r->kind == DP_RELAX_LINEAR ? r->L : 0;
}

/* Spring force at x and (slope != NULL) its derivative. */
static double spring_force(const struct dp_regularized *g, double x, double *slope)
{
    if (g->spring_exact) {
        if (slope)
            *slope = g->k;
        return g->k * x;
    }
    return dp_graph_yosida_slope(g->S, g->ls, x, slope);
}

/* F_c = c u + D_l(u) at relative velocity u and (slope != NULL) d(F_c - gamma)/du. */
static double damper_force(const struct dp_regularized *g, double u, double *slope)
{
    double fc = g->c * u + dp_graph_yosida_slope(g->D, g->ld, u, slope);
    if (slope)
        *slope += g->c - relaxation_rate(g->gamma, u);
    return fc;
}

/* x'' = (F(t) - F_s(x) - F_d(u)) / m. */
static double acceleration(const struct dp_regularized *g, double t, const double y[])
{
    double u = y[1] - g->vb;
    double fs = spring_force(g, y[0], NULL);
    double fd = damper_force(g, u, NULL) - dp_relaxation_eval(g->gamma, u);
    return (dp_forcing_eval(g->F, t) - fs - fd) / g->m;
}

static int rhs(double t, const double y[], double f[], void *p)
{
    struct dp_regularized *g = p;
    g->fevals++;
    f[0] = y[1];
    f[1] = acceleration(g, t, y);
    return isfinite(f[0]) && isfinite(f[1]) ? GSL_SUCCESS : GSL_EBADFUNC;
}

/* d(x, v)'/d(x, v) = [0 1; -F_s'(x)/m -F_d'(u)/m], row-major; dfdt = (0, F'(t)/m). */
static int jacobian(double t, const double y[], double *dfdy, double dfdt[], void *p)
{
    struct dp_regularized *g = p;
    double ks, kd;
    spring_force(g, y[0], &ks);
    damper_force(g, y[1] - g->vb, &kd);
    g->jevals++;
    dfdy[0] = 0, dfdy[1] = 1, dfdy[2] = -ks / g->m, dfdy[3] = -kd / g->m;
    dfdt[0] = 0, dfdt[1] = dp_forcing_rate(g->F, t) / g->m;
    return isfinite(dfdy[2]) && isfinite(dfdy[3]) && isfinite(dfdt[1]) ? GSL_SUCCESS : GSL_EBADFUNC;
}

/* The spectral radius of [0 1; -p -q]: the largest |root| of l^2 + q l + p, without overflow. */
static double spectral_radius(double p, double q)
{
    double a = 0.5 * fabs(q), r = sqrt(fabs(p));
    if (p < 0)
        return a + hypot(a, r);
    return a >= r ? a + sqrt((a - r) * (a + r)) : r;
}

/* y' = f, y'' = J f + df/dt and rho, the spectral radius of J, at one end of a step: the same law and slopes
 * as rhs and jacobian (the slope from the right at a kink). Computed once per end, uncounted; GSL_EBADFUNC
 * if f is not finite (y'' may be, past 1e308, in a step too stiff to use it). */
static int jet(const struct dp_regularized *g, struct reg_end *e)
{
    if (e->jet)
        return GSL_SUCCESS;
    double ks, kd, v = e->y[1];
    spring_force(g, e->y[0], &ks);
    damper_force(g, v - g->vb, &kd);
    double acc = acceleration(g, e->t, e->y);
    e->dy[0] = v, e->dy[1] = acc;
    e->d2y[0] = acc, e->d2y[1] = (dp_forcing_rate(g->F, e->t) - ks * v - kd * acc) / g->m;
    e->rho = spectral_radius(ks / g->m, kd / g->m);
    e->jet = isfinite(acc);
    return e->jet ? GSL_SUCCESS : GSL_EBADFUNC;
}

/* The graph A + c I: the same vertices lifted by c y, the rays by c dy. */
static int add_viscosity(dp_graph *dst, const dp_graph *A, double c)
{
    int s = dp_graph_copy(dst, A);
    if (s != DP_OK)
        return s;
    for (size_t i = 0; i < dst->n; i++)
        dst->f[i] += c * dst->y[i];
    dst->left[1] += c * dst->left[0];
    dst->right[1] += c * dst->right[0];
    return DP_OK;
}

static int set_law(struct dp_regularized *g, const dp_spec *spec)
{
    const dp_model *m = &spec->model;
    const dp_damper *d = &m->damper;
    double n = spec->solver.n_list[0];
    double c = dp_damper_viscous(d);
    g->m = m->mass;
    g->vb = d->belt_velocity;
    g->gamma = &d->relaxation;
    g->F = &m->forcing;
    g->ls = g->ld = 1 / n;
    g->S = &m->spring.graph;
    if (spec->solver.scheme == DP_SCHEME_PI) {
        g->D = &g->DI;
        return add_viscosity(&g->DI, &d->graph, c);
    }
    g->D = &d->graph;
    g->c = c;
    g->spring_exact = dp_spring_linear(&m->spring);
    g->k = m->spring.k;
    return DP_OK;
}

/* ---- the run ------------------------------------------------------------------------------------------- */

const gsl_odeiv2_step_type *dp_regularized_step_type(dp_stepper s)
{
    switch (s) {
    case DP_STEPPER_RK4IMP: return gsl_odeiv2_step_rk4imp;
    case DP_STEPPER_BSIMP: return gsl_odeiv2_step_bsimp;
    case DP_STEPPER_RKF45: return gsl_odeiv2_step_rkf45;
    case DP_STEPPER_RKCK: return gsl_odeiv2_step_rkck;
    case DP_STEPPER_RK8PD: return gsl_odeiv2_step_rk8pd;
    default: return gsl_odeiv2_step_msbdf;
    }
}

/* The state (x, v) at time t as the current sample: forces from the regularized laws, no phase. */
static void set_sample(dp_run *r, double t, const double y[])
{
    const struct dp_regularized *g = r->state;
    dp_sample *c = &r->cur;
    double u = y[1] - g->vb;
    c->t = t, c->x = y[0], c->v = y[1];
    c->Fs = spring_force(g, c->x, NULL);
    c->Fc = damper_force(g, u, NULL);
    c->Fd = c->Fc - dp_relaxation_eval(g->gamma, u);
    c->phase = DP_PHASE_NONE;
}

/* Appends the integrator's state b to msbdf's history (a ring: the oldest value goes). */
static void remember(struct dp_regularized *g)
{
    size_t i = g->hlast = (g->hlast + 1) % REG_HISTORY;
    g->ht[i] = g->b.t, g->hy[i][0] = g->b.y[0], g->hy[i][1] = g->b.y[1];
    if (g->hn < REG_HISTORY)
        g->hn++;
}

/* y at ts from msbdf's history: the polynomial through its last order + 1 values, as a BDF step of that
 * order is built on. */
static void bdf_interp(const struct dp_regularized *g, double ts, double y[])
{
    size_t n = g->order + 1 < g->hn ? g->order + 1 : g->hn;
    double t[REG_HISTORY], v[REG_HISTORY][2];
    for (size_t k = 0; k < n; k++) {
        size_t i = (g->hlast + REG_HISTORY - k) % REG_HISTORY;
        t[k] = g->ht[i], v[k][0] = g->hy[i][0], v[k][1] = g->hy[i][1];
    }
    dp_poly_interp(t, v[0], n, 2, ts, y);
}

static int regularized_init(dp_run *r)
{
    struct dp_regularized *g = calloc(1, sizeof *g);
    if (g == NULL)
        return DP_ENOMEM;
    r->state = g; /* from here on dp_run_free releases whatever was built */
    if (set_law(g, &r->spec) != DP_OK)
        return dp_run_fail(r, DP_ENOMEM, "out of memory building the regularized damper graph");
    const dp_solver_spec *sv = &r->spec.solver;
    g->sys = (gsl_odeiv2_system){ rhs, jacobian, 2, g };
    /* A first step far below any time scale of the ODE (the fastest is ~ m/n): the control grows it by up to
     * 5x per accepted step, so the few steps this costs are cheaper than rejections from too large a guess.
     * The output grid plays no part: the steps are the same whatever dt and output.every. */
    g->h = 1e-3 * g->m / (sv->n_list[0] + 1);
    /* The fastest time scale is m / L, L <= n + k + c + L_gamma (the Yosida pieces are at most n steep).
     * Sound runs never step below ~1e-6 of it (measured down to rtol = 1e-12, n = 1e7); an error control
     * asking for 1e-12 of it is asking for more digits than doubles hold (atol = 1e-300 would otherwise
     * crawl through 10^9 steps near t = 0 before the step limit stops it). */
    double L = sv->n_list[0] + g->k + g->c + dp_relaxation_lipschitz(g->gamma);
    g->h_floor = 1e-12 * g->m / L;
    g->drv = gsl_odeiv2_driver_alloc_y_new(&g->sys, dp_regularized_step_type(sv->stepper), g->h, sv->atol, sv->rtol);
    if (g->drv == NULL)
        return dp_run_fail(r, DP_ENOMEM, "out of memory allocating the %s integrator",
                           dp_stepper_name(sv->stepper));
    /* msbdf and the explicit rkf45, rkck step freely and the samples are interpolated (sample_at); explicit
     * steps stay inside their stability region, h rho <= ~6 (measured), so their derivatives serve Hermite.
     * The others land on every sample as dashpot always did: rk8pd's and bsimp's (orders 8, 12) long steps
     * outrun a quintic; rk4imp's and bsimp's steps, allowed to grow long, jump across the stick band
     * |u| < phi0/n (measured at n = 1e4, 1e5: bsimp's x(30) off by 2e-2, rk4imp's v by 5e-3 at the stop). */
    g->bdf = sv->stepper == DP_STEPPER_MSBDF;
    g->land = sv->stepper == DP_STEPPER_RK4IMP || sv->stepper == DP_STEPPER_BSIMP || sv->stepper == DP_STEPPER_RK8PD;
    g->b.t = 0, g->b.y[0] = r->spec.x0, g->b.y[1] = r->spec.v0;
    g->hlast = REG_HISTORY - 1;
    remember(g);
    set_sample(r, g->b.t, g->b.y);
    if (!isfinite(r->cur.Fs) || !isfinite(r->cur.Fc)) {
        snprintf(r->error_pointer, sizeof r->error_pointer, "/initial");
        return dp_one_mass_nonfinite(r, "the regularized forces are not finite at the initial state", 0,
                                     r->spec.x0, r->spec.v0);
    }
    dp_run_emit_state(r); /* the initial state: queued, no block yet */
    return DP_OK;
}

static int gsl_failure(dp_run *r, int s, double t)
{
    if (s == GSL_EBADFUNC) {
        char msg[DP_MESSAGE_MAX];
        snprintf(msg, sizeof msg, "the solution diverged at t = %.17g (non-finite right-hand side)", t);
        return dp_one_mass_nonfinite(r, msg, t, r->cur.x, r->cur.v);
    }
    return dp_run_fail(r, DP_ESOLVE, "the %s integrator failed at t = %.17g: %s",
                       dp_stepper_name(r->spec.solver.stepper), t, gsl_strerror(s));
}

/* One accepted step of the integrator from b towards t1 (landing there exactly if it can reach it): a becomes
 * the old b, b the new state. DP_OK or the run's error. */
static int step_to(dp_run *r, double t1)
{
    struct dp_regularized *g = r->state;
    gsl_odeiv2_driver *d = g->drv;
    /* The front end's step limit bounds the integrator's own steps too: a stiff enough model (k ~ 1e97
     * from the fuzzer) would otherwise integrate for hours. */
    if ((double)d->e->count >= r->max_steps)
        return dp_run_fail(r, DP_ELIMIT, "more than %.0f integrator steps by t = %.17g (the step limit): "
                           "choose an implicit stepper, a smaller n or a less stiff model", r->max_steps, g->b.t);
    /* A stepper that lands splits what is left to the sample into equal steps no longer than the proposal: a
     * short remainder step before each sample would make msbdf see a step-size drop and lower its order (its
     * stability heuristic). The free steppers only clip their last step at t_end (gsl_odeiv2_evolve_apply
     * does): on the bench that and an equal split are within 5% of each other's step counts, and then a run
     * to T takes the steps of a run to any later t_end, up to the one that holds T. */
    double t = g->b.t, rem = t1 - t, h = g->land && g->h < rem ? rem / ceil(rem / g->h) : g->h;
    double y[2] = { g->b.y[0], g->b.y[1] };
    unsigned order = gsl_odeiv2_step_order(d->s);
    int s = gsl_odeiv2_evolve_apply(d->e, d->c, d->s, &g->sys, &t, t1, &h, y);
    if (s != GSL_SUCCESS)
        return gsl_failure(r, s, g->b.t);
    if (!isfinite(y[0]) || !isfinite(y[1]))
        return gsl_failure(r, GSL_EBADFUNC, t);
    if (t < t1 && d->e->last_step < g->h_floor)
        return dp_run_fail(r, DP_ESOLVE, "the %s integrator's step fell to %.3g at t = %.17g: rtol = %g, "
                           "atol = %g cannot be met in double precision", dp_stepper_name(r->spec.solver.stepper),
                           d->e->last_step, t, r->spec.solver.rtol, r->spec.solver.atol);
    if (t < t1)
        g->h = h; /* the control's proposal; a final (clipped) step leaves it as it was */
    /* The order this step used: msbdf reports the next step's, which differs by one at most. */
    unsigned next = gsl_odeiv2_step_order(d->s);
    g->order = next < order ? next : order;
    g->a = g->b;
    g->b = (struct reg_end){ .t = t, .y = { y[0], y[1] } };
    if (g->bdf)
        remember(g);
    return DP_OK;
}

/* Whether the last step was stiff (its ends' jets computed): its derivatives do not serve Hermite. */
static int stiff_step(const struct dp_regularized *g)
{
    return (g->b.t - g->a.t) * fmax(g->a.rho, g->b.rho) > REG_STIFF;
}

/* The next step: towards t_end, or to the sample ts for the steppers that land on every sample. */
static int step(dp_run *r, double ts)
{
    return step_to(r, reg_of(r)->land ? ts : r->spec.solver.t_end);
}

/* Steps until the last accepted step holds ts (b.t >= ts). DP_OK, DP_MORE when *budget ran out first, or the
 * run's error. */
static int integrate_past(dp_run *r, double ts, unsigned long long *budget)
{
    while (reg_of(r)->b.t < ts) {
        if (*budget == 0)
            return DP_MORE;
        (*budget)--;
        if (dp_run_stopped(r, r->n + reg_of(r)->fevals + reg_of(r)->jevals))
            return r->status == DP_OK ? DP_MORE : r->status; /* a yield: as if the budget ran out */
        int s = step(r, ts);
        if (s != DP_OK)
            return s;
    }
    return DP_OK;
}

/* The sample at ts inside the last step (a.t < ts <= b.t): the state itself at b.t (t_end always); in a stiff
 * msbdf step the polynomial through its last order + 1 values (BDF's own interpolant); else the quintic
 * Hermite interpolant, its end derivatives evaluated once per step. */
static int sample_at(dp_run *r, double ts)
{
    struct dp_regularized *g = r->state;
    if (ts == g->b.t) {
        set_sample(r, ts, g->b.y);
        return DP_OK;
    }
    if (jet(g, &g->a) != GSL_SUCCESS || jet(g, &g->b) != GSL_SUCCESS)
        return gsl_failure(r, GSL_EBADFUNC, g->a.t);
    double y[2];
    if (g->bdf && stiff_step(g)) {
        bdf_interp(g, ts, y);
    } else {
        dp_hermite_end a = { g->a.t, g->a.y, g->a.dy, g->a.d2y }, b = { g->b.t, g->b.y, g->b.dy, g->b.d2y };
        dp_hermite5(&a, &b, 2, ts, y);
    }
    if (!isfinite(y[0]) || !isfinite(y[1]))
        return gsl_failure(r, GSL_EBADFUNC, ts);
    set_sample(r, ts, y);
    return DP_OK;
}

static void update_summary(dp_run *r)
{
    const struct dp_regularized *g = r->state;
    r->sum.steps = g->drv->e->count;
    r->sum.rejected = g->drv->e->failed_steps;
    r->sum.fevals = g->fevals;
    r->sum.iterations = g->jevals;
}

static int regularized_advance(dp_run *r)
{
    unsigned long long budget = REG_STEPS_PER_CALL, every = (unsigned long long)r->spec.output.every;
    double t_end = r->spec.solver.t_end;
    while (dp_run_room(r)) {
        if (dp_run_stopped(r, r->n + reg_of(r)->fevals + reg_of(r)->jevals)) /* samples count as work too */
            return r->status;
        /* The next sample that is kept: decimated grid points are never computed. */
        unsigned long long next = r->nsteps - r->n > every ? r->n + every : r->nsteps;
        double ts = next < r->nsteps ? fmin((double)next * r->h, t_end) : t_end;
        int s = integrate_past(r, ts, &budget);
        if (s == DP_OK)
            s = sample_at(r, ts);
        update_summary(r);
        if (s == DP_MORE)
            return DP_OK;
        if (s != DP_OK)
            return s;
        r->n = next;
        r->countdown = 1;
        if (r->n >= r->nsteps)
            r->finished = 1;
        dp_run_emit_state(r);
    }
    return DP_OK;
}

static void regularized_free(void *state)
{
    struct dp_regularized *g = state;
    if (g == NULL)
        return;
    if (g->drv != NULL)
        gsl_odeiv2_driver_free(g->drv);
    dp_graph_clear(&g->DI);
    free(g);
}

const dp_run_type dp_run_regularized = {
    .name = "regularized", .check = dp_rules_regularized, .init = regularized_init, .advance = regularized_advance,
    .free = regularized_free,
};
