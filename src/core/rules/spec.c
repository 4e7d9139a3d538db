/* src/core/rules/spec.c - spec defaults, lifetime and the cross-field rules a schema cannot state.
 *
 * The rules come from the mathematics: the thesis algorithm needs the contraction (4.10) and the bound
 * (4.8); the exact step is uniquely solvable only while m + h theta c + h^2 theta^2 k > h theta L_gamma
 * (its left side must stay strictly increasing, docs/mathematics.md §4); theta-weighting is defined only for
 * linear springs; the analytic solver exists only where the closed form (4.14) does.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/newmark.h"
#include "dashpot/right_hand.h"
#include "dashpot/spec.h"
#include "dashpot/lcs.h"
#include "rules/rules.h"

void dp_spec_init(dp_spec *s)
{
    memset(s, 0, sizeof *s);
    s->model.mass = 1;
    s->solver.kind = DP_SOLVER_STICK_SLIP;
    s->solver.dt = 1e-3;
    s->solver.t_end = 10;
    s->solver.theta = 1;
    s->solver.variant = DP_VARIANT_EXACT;
    s->solver.Z = 100;
    s->solver.eps = 1e-4;
    s->solver.events = DP_EVENTS_LOCATE;
    s->solver.scheme = DP_SCHEME_PC;
    s->solver.n_list[0] = 1000;
    s->solver.n_count = 1;
    s->solver.rtol = 1e-8;
    s->solver.atol = 1e-10;
    s->solver.stepper = DP_STEPPER_MSBDF;
    s->solver.beta = 0.25;
    s->solver.gamma = 0.5;
    s->output.every = 1;
    s->output.samples = 1;
    s->output.events = 1;
}

int dp_spec_is_network(const dp_spec *s) { return s->net != NULL; }
int dp_spec_is_lcs(const dp_spec *s) { return s->lcs != NULL; }
int dp_spec_is_right_hand_model(const dp_spec *s) { return s->rh != NULL; }
size_t dp_spec_network_nodes(const dp_spec *s) { return s->net->n; }
/* q and q' (the rod adds its end's height and upward rate: 0 and 0 on the floor) */
size_t dp_spec_right_hand_coordinates(const dp_spec *s) { return s->rh->kind == DP_RIGHT_HAND_ROD ? 3 : 2; }

dp_family dp_spec_family(const dp_spec *s)
{
    return s->lcs ? DP_FAMILY_LCS : s->rh ? DP_FAMILY_RIGHT_HAND : s->net ? DP_FAMILY_NETWORK : DP_FAMILY_ONE_MASS;
}

static void *dup_array(const void *src, size_t n, size_t size, int *fail)
{
    if (src == NULL || n == 0)
        return NULL;
    void *d = malloc(n * size);
    if (d == NULL)
        *fail = 1;
    else
        memcpy(d, src, n * size);
    return d;
}

/* The model families beside the one-mass model, each its own member of dp_spec: one row each, so that
 * copying and clearing a spec names no family. (Which solver runs a family is the run-type table's, in
 * runs/run_table.c.) The initial state x0v, v0v of a model with several coordinates is the spec's own. */
static int network_copy(dp_spec *dst, const dp_spec *src)
{
    return (dst->net = dp_network_copy(src->net)) == NULL ? DP_ENOMEM : DP_OK;
}

static void network_clear(dp_spec *s)
{
    dp_network_free(s->net);
    s->net = NULL;
}

static int lcs_copy(dp_spec *dst, const dp_spec *src)
{
    return (dst->lcs = dp_lcs_model_copy(src->lcs)) == NULL ? DP_ENOMEM : DP_OK;
}

static void lcs_clear(dp_spec *s)
{
    dp_lcs_model_free(s->lcs);
    s->lcs = NULL;
}

static int right_hand_copy(dp_spec *dst, const dp_spec *src)
{
    dst->rh = malloc(sizeof *dst->rh);
    if (dst->rh == NULL)
        return DP_ENOMEM;
    *dst->rh = *src->rh;
    return DP_OK;
}

static void right_hand_clear(dp_spec *s)
{
    free(s->rh);
    s->rh = NULL;
}

static const struct family {
    int (*present)(const dp_spec *s);
    size_t (*coordinates)(const dp_spec *s);   /* the length of x0v and v0v */
    int (*copy)(dp_spec *dst, const dp_spec *src);
    void (*clear)(dp_spec *s);
} families[] = {
    { dp_spec_is_network, dp_spec_network_nodes, network_copy, network_clear },
    { dp_spec_is_lcs, NULL, lcs_copy, lcs_clear },
    { dp_spec_is_right_hand_model, dp_spec_right_hand_coordinates, right_hand_copy, right_hand_clear },
};
#define NFAMILIES (sizeof families / sizeof *families)

void dp_spec_clear(dp_spec *s)
{
    if (s == NULL)
        return;
    dp_model_clear(&s->model);
    for (size_t i = 0; i < NFAMILIES; i++)
        families[i].clear(s);
    free(s->x0v);
    free(s->v0v);
    free(s->output.nodes);
    free(s->output.elements);
    s->x0v = s->v0v = NULL, s->output.nodes = s->output.elements = NULL;
}

int dp_spec_copy(dp_spec *dst, const dp_spec *src)
{
    *dst = *src;
    dst->net = NULL, dst->rh = NULL, dst->lcs = NULL;
    dst->x0v = dst->v0v = NULL, dst->output.nodes = dst->output.elements = NULL;
    if (dp_model_copy(&dst->model, &src->model) != DP_OK) {
        memset(&dst->model, 0, sizeof dst->model);
        return DP_ENOMEM;
    }
    int fail = 0;
    for (size_t i = 0; i < NFAMILIES && !fail; i++) {
        const struct family *f = &families[i];
        if (!f->present(src))
            continue;
        fail = f->copy(dst, src) != DP_OK;
        size_t n = f->coordinates ? f->coordinates(src) : 0;
        dst->x0v = dup_array(src->x0v, n, sizeof(double), &fail);
        dst->v0v = dup_array(src->v0v, n, sizeof(double), &fail);
    }
    dst->output.nodes = dup_array(src->output.nodes, src->output.nnodes, sizeof(size_t), &fail);
    dst->output.elements = dup_array(src->output.elements, src->output.nelements, sizeof(size_t), &fail);
    if (fail) {
        dp_spec_clear(dst);
        return DP_ENOMEM;
    }
    return DP_OK;
}

/* Whether theta < 1 is allowed for the exact step of a one-mass model: a linear or plastic spring (others are
 * stepped by backward Euler) and a uniquely solvable step, m + h theta c + h^2 theta^2 k > h theta L_gamma
 * (check_exact). */
static int one_mass_takes_theta(const dp_spec *s, double th)
{
    const dp_model *m = &s->model;
    if (!dp_spring_linear(&m->spring) && !dp_spring_plastic(&m->spring))
        return 0;
    double h = s->solver.dt, k = dp_spring_stiffness(&m->spring), c = dp_damper_viscous(&m->damper);
    double L = dp_relaxation_lipschitz(&m->damper.relaxation);
    return !isfinite(L) || m->mass + h * th * c + h * h * th * th * k > h * th * L;
}

/* The same for a network: every spring linear, plastic, a graph of finite slope (which the network
 * theta-steps, network_smooth.c; a compliant contact is such a graph) or a rope with events located
 * (network_check.c). */
static int network_takes_theta(const dp_network *net, int located)
{
    for (size_t i = 0; i < net->nel; i++) {
        const dp_element *el = &net->el[i];
        int rope = located && el->has_spring && dp_spring_is_split(&el->spring);
        if (el->has_spring && !dp_spring_linear(&el->spring) && !dp_spring_plastic(&el->spring) && !rope &&
            !dp_spring_sloped_graph(&el->spring))
            return 0;
    }
    return 1;
}

double dp_spec_default_theta(const dp_spec *s)
{
    if (s->solver.kind != DP_SOLVER_STICK_SLIP || s->solver.variant != DP_VARIANT_EXACT || s->rh)
        return 1;
    if (s->lcs)
        return 0.5;
    if (s->net)
        return network_takes_theta(s->net, s->solver.events == DP_EVENTS_LOCATE) ? 0.5 : 1;
    return one_mass_takes_theta(s, 0.5) ? 0.5 : 1;
}

long dp_spec_every_for(const dp_spec *s, double samples)
{
    if (!(s->solver.dt > 0 && isfinite(s->solver.t_end) && s->solver.t_end > 0 && samples >= 2))
        return 1;
    double every = ceil(dp_spec_steps(s) / (samples - 1));
    return every < 1 ? 1 : every > 9007199254740992.0 ? 9007199254740992L : (long)every;
}

void dp_spec_choose(dp_spec *s, unsigned which)
{
    if (s->solver.kind != DP_SOLVER_STICK_SLIP || s->rh)
        which &= ~DP_CHOSEN_THETA;      /* only the theta-method has a theta to choose */
    if (which & DP_CHOSEN_THETA)
        s->solver.theta = dp_spec_default_theta(s);
    if (which & DP_CHOSEN_EVERY)
        s->output.every = dp_spec_every_for(s, DP_SPEC_SAMPLE_BUDGET);
    s->chosen |= which;
}

double dp_spec_steps(const dp_spec *s)
{
    /* t_end/dt is usually meant to be a whole number; forgive the last bits of rounding in the quotient. */
    double r = s->solver.t_end / s->solver.dt;
    double n = ceil(r * (1 - 1e-12));
    return n < 1 ? 1 : n;
}

static void check_analytic(const dp_spec *s, dp_errors *e)
{
    const dp_model *m = &s->model;
    double F0;
    const dp_damper_law_info *DL = dp_damper_law_info_of(m->damper.law);
    if (!dp_spring_linear(&m->spring) || !(m->spring.k > 0))
        dp_errors_add(e, "/model/spring", "the analytic solver needs a linear spring with k > 0");
    if (!(DL && DL->analytic))
        dp_errors_add(e, "/model/damper/law", "the analytic solver needs a coulomb (or no) damper, got %s",
                      dp_damper_law_name(m->damper.law));
    if (m->damper.relaxation.kind != DP_RELAX_NONE)
        dp_errors_add(e, "/model/damper/relaxation", "the analytic solver has no closed form with relaxation");
    if (m->damper.belt_velocity != 0)
        dp_errors_add(e, "/model/damper/belt_velocity", "the analytic solver needs belt_velocity 0");
    if (!dp_forcing_is_constant(&m->forcing, &F0))
        dp_errors_add(e, "/model/forcing", "the analytic solver needs a constant forcing");
}

/* An upper bound on the turning points the analytic solver passes up to t_end: one per half-period
 * pi sqrt(m/k), and with Coulomb friction no more than it takes to come to rest, each half-cycle bringing
 * the amplitude about the arc's centre down by 2 phi0 / k. The solver passes them one by one, so a bound
 * over the step limit is a run that never ends in practice; from k ~ 1e40 on, the half-period is even
 * below the rounding of t and the clock stops for good (found by tests/fuzz/fuzz_spec.c). */
static double analytic_arcs(const dp_spec *s)
{
    const dp_model *m = &s->model;
    double k = m->spring.k, om = sqrt(k / m->mass), F0 = 0;
    double phi0 = dp_damper_kinetic(&m->damper);   /* coulomb's phi0, or no damper (check_analytic) */
    dp_forcing_is_constant(&m->forcing, &F0);
    double by_time = s->solver.t_end * om / M_PI + 2;
    if (!(phi0 > 0))
        return by_time;
    double amplitude = hypot(s->x0 - F0 / k, s->v0 / om) + phi0 / k;
    return fmin(by_time, amplitude * k / (2 * phi0) + 2);
}

static void check_thesis(const dp_spec *s, dp_errors *e)
{
    const dp_model *m = &s->model;
    const dp_damper *d = &m->damper;
    const dp_damper_law_info *DL = dp_damper_law_info_of(d->law);
    int thesis = DL && DL->thesis;
    if (!dp_spring_linear(&m->spring) || !(m->spring.k > 0))
        dp_errors_add(e, "/model/spring", "variant \"thesis\" (algorithm 4.1) needs a linear spring with k > 0");
    if (!thesis)
        dp_errors_add(e, "/model/damper/law", "variant \"thesis\" needs a coulomb damper, got %s",
                      dp_damper_law_name(d->law));
    if (d->belt_velocity != 0)
        dp_errors_add(e, "/model/damper/belt_velocity", "variant \"thesis\" has no belt; use variant \"exact\"");
    if (s->solver.theta != 1)
        dp_errors_add(e, "/solver/theta", "variant \"thesis\" is the backward Euler scheme: theta must be 1");
    double A = dp_relaxation_bound(&d->relaxation);
    if (thesis && d->relaxation.kind != DP_RELAX_NONE && !(A < dp_damper_kinetic(d)))
        dp_errors_add(e, "/model/damper/relaxation",
                      "variant \"thesis\" needs |gamma| <= A < phi0 (thesis (4.8)) for its sign rule (4.12); "
                      "sup|gamma| = %g, phi0 = %g", A, dp_damper_kinetic(d));
    double K = m->mass / s->solver.dt + s->solver.dt * m->spring.k;
    double L = dp_relaxation_lipschitz(&d->relaxation);
    if (!(L < K))
        dp_errors_add(e, "/solver/dt",
                      "the fixed-point iteration (4.13) does not contract: alpha = L_gamma/(m/dt + dt k) = %g/%g "
                      ">= 1 (thesis (4.10)); choose a smaller dt", L, K);
}

static void check_exact(const dp_spec *s, dp_errors *e)
{
    const dp_model *m = &s->model;
    /* a dt past t_end is one step of t_end (dp_spec_steps) */
    double h = fmin(s->solver.dt, s->solver.t_end), th = s->solver.theta;
    if (th != 1 && !dp_spring_linear(&m->spring) && !dp_spring_plastic(&m->spring))
        dp_errors_add(e, "/solver/theta", "theta < 1 needs a linear spring, a graph spring of finite slope or a "
                      "rope with events located (the %s spring has a vertical piece, stepped by backward Euler): "
                      "use theta = 1", dp_spring_law_name(m->spring.law));
    double k = dp_spring_stiffness(&m->spring);
    double c = dp_damper_viscous(&m->damper);
    double W = m->mass + h * th * c + h * h * th * th * k;
    double L = dp_relaxation_lipschitz(&m->damper.relaxation);
    if (isfinite(L) && !(W > h * th * L))
        dp_errors_add(e, "/solver/dt", "the implicit step is not uniquely solvable: m + h theta c + h^2 theta^2 k "
                      "= %g must exceed h theta L_gamma = %g; choose a smaller dt", W, h * th * L);
}

/* ---- the document's scale: what a step forms from it is finite ------------------------------------- */

/* A member of the document and its value, one factor of a quantity a step forms. */
typedef struct factor { const char *ptr; double v; } factor;

static double decades(double v)
{
    return v == 0 || !isfinite(v) ? 0 : fabs(log10(fabs(v)));
}

/* Unless q is finite (and, with `divides`, 1/q too), an error at the factor farthest from 1 in decades, the
 * member to change, naming every factor with its value (all finite: the parser took only finite numbers). */
static int formed(dp_errors *e, double q, int divides, const char *what, const factor *f, size_t n)
{
    if (isfinite(q) && (!divides || (q != 0 && isfinite(1 / q))))
        return 1;
    char list[DP_MESSAGE_MAX] = "";
    size_t used = 0, worst = 0;
    for (size_t i = 0; i < n; i++) {
        if (decades(f[i].v) > decades(f[worst].v))
            worst = i;
        if (used < sizeof list)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%s = %g", i ? ", " : "", f[i].ptr, f[i].v);
    }
    dp_errors_add(e, f[worst].ptr, "%s %s double precision (%s): the document's scale is too large or too small "
                  "for the step", what, divides ? "leaves" : "overflows", list);
    return 0;
}

#define FORMED(e, q, divides, what, ...)                                                                        \
    formed(e, q, divides, what, (const factor[]){ __VA_ARGS__ },                                                  \
           sizeof((const factor[]){ __VA_ARGS__ }) / sizeof(factor))

/* The largest |F| the forcing takes, and each harmonic term's phase omega t_end + phase and rate
 * amplitude omega, each table's pieces: finite, or an error at the term's member. */
static double forcing_bound(const dp_forcing *f, const char *ptr, double t_end, dp_errors *e, int *ok)
{
    char p[DP_POINTER_MAX], q[DP_POINTER_MAX];
    double b = 0;
    switch (f->kind) {
    case DP_FORCING_CONSTANT:
        return fabs(f->value);
    case DP_FORCING_HARMONIC:
        snprintf(p, sizeof p, "%s/omega", ptr);
        snprintf(q, sizeof q, "%s/amplitude", ptr);
        *ok &= FORMED(e, f->omega * t_end + f->phase, 0, "the phase omega t_end + phase", { p, f->omega },
                      { "/solver/t_end", t_end });
        *ok &= FORMED(e, f->amplitude * f->omega, 0, "the load's rate amplitude omega", { q, f->amplitude },
                      { p, f->omega });
        return fabs(f->amplitude);
    case DP_FORCING_TABLE:
        for (size_t i = 0; i < f->n; i++) {
            snprintf(p, sizeof p, "%s/points/%zu", ptr, i);
            b = fmax(b, fabs(f->F[i]));
            if (i > 0)
                *ok &= FORMED(e, f->F[i] - f->F[i - 1], 0, "the table's step F[i] - F[i-1]", { p, f->F[i] });
        }
        return b;
    case DP_FORCING_SUM:
        for (size_t i = 0; i < f->nterms; i++) {
            snprintf(p, sizeof p, "%s/terms/%zu", ptr, i);
            b += forcing_bound(&f->terms[i], p, t_end, e, ok);
        }
        if (!isfinite(b)) {
            dp_errors_add(e, ptr, "the terms' magnitudes add up past double precision");
            *ok = 0;
            return 0;
        }
        return b;
    default:
        return 0;
    }
}

/* The step of length h (a pointer to the member that sets it) of the theta-method, formed as the solvers
 * form it (stick_slip_step.c: W, the closed form's coefficients, the step's right side b at the start). */
static int step_finite(const dp_spec *s, double h, const char *hp, double th, double Fmax, dp_errors *e)
{
    const dp_model *m = &s->model;
    double k = dp_spring_stiffness(&m->spring), c = dp_damper_viscous(&m->damper), vb = m->damper.belt_velocity;
    double tau = fmax(dp_damper_kinetic(&m->damper), dp_damper_static(&m->damper));
    const factor M = { "/model/mass", m->mass }, H = { hp, h }, K = { "/model/spring/k", k },
                 C = { "/model/damper/c", c }, VB = { "/model/damper/belt_velocity", vb },
                 X = { "/initial/x", s->x0 }, V = { "/initial/v", s->v0 }, F = { "/model/forcing", Fmax };
    int ok = FORMED(e, h * th, 1, "the step's h theta", H);
    double W = m->mass + h * th * c + h * h * th * th * k;
    ok = ok && FORMED(e, W, 1, "the step's m + h theta c + h^2 theta^2 k", M, H, C, K);
    ok = ok && FORMED(e, h * k / W + (m->mass - h * (1 - th) * c - h * h * k * th * (1 - th)) / W, 0,
                      "the step's coefficients", M, H, C, K);
    ok = ok && FORMED(e, h * (c * vb + tau + Fmax) / W, 0, "the step's load h (c v_b + tau + F) / W", M, H, C,
                      VB, F, { "/model/damper", tau });
    ok = ok && FORMED(e, s->x0 + h * s->v0, 0, "the position update x + h v", X, V, H);
    ok = ok && FORMED(e, m->mass * s->v0 - h * (1 - th) * c * s->v0 - h * k * (s->x0 + h * th * (1 - th) * s->v0)
                      + h * (c * vb + Fmax), 0, "the step's right side m v - h k x + h F", M, V, X, H, C, K, VB, F);
    ok = ok && FORMED(e, s->v0 - vb, 0, "the relative velocity v - v_b", V, VB);
    return ok;
}

/* Newmark's step of length h (Höschl 1983, §15; network/newmark_step.c): the effective stiffness
 * K + gamma/(beta h) C + M/(beta h^2) and its inverse, and the starting acceleration (F - C v - K x)/M. */
static int newmark_finite(const dp_spec *s, double h, const char *hp, double Fmax, dp_errors *e)
{
    const dp_model *m = &s->model;
    double M = m->mass, C = dp_damper_viscous(&m->damper), K = m->spring.k, b = s->solver.beta, g = s->solver.gamma;
    const factor FM = { "/model/mass", M }, FH = { hp, h }, FK = { "/model/spring/k", K },
                 FC = { "/model/damper/c", C }, FB = { "/solver/beta", b }, FX = { "/initial/x", s->x0 },
                 FV = { "/initial/v", s->v0 }, FF = { "/model/forcing", Fmax },
                 FVB = { "/model/damper/belt_velocity", m->damper.belt_velocity };
    double khat = K + g / (b * h) * C + M / (b * h * h);
    int ok = FORMED(e, b * h * h, 1, "Newmark's beta h^2", FB, FH);
    ok = ok && FORMED(e, khat, 1, "Newmark's effective stiffness K + gamma C/(beta h) + M/(beta h^2)", FM, FC, FK,
                      FB, FH);
    double a0 = (Fmax + fabs(C * (s->v0 - m->damper.belt_velocity)) + fabs(K * s->x0)) / M;
    ok = ok && FORMED(e, a0, 0, "the starting acceleration (F - c v - k x)/m", FM, FC, FK, FX, FV, FVB, FF);
    ok = ok && FORMED(e, (fabs(s->v0) / (b * h) + a0 / (2 * b)) * (M + C * h) + khat * fabs(s->x0), 0,
                      "Newmark's step load", FM, FC, FK, FB, FH, FX, FV);
    return ok;
}

/* The regularized schemes (regularized.c): each approximation's Yosida parameter 1/n and its forces at the
 * initial state n |v - v_b|, n |x|, and the integrator's first step 1e-3 m/(n + 1) and floor 1e-12 m/L, L
 * the ODE's fastest rate n + k + c + L_gamma: normal numbers, or GSL gets a step of 0. */
static int regularized_finite(const dp_spec *s, dp_errors *e)
{
    const dp_model *m = &s->model;
    const dp_solver_spec *sv = &s->solver;
    int ok = 1;
    for (size_t i = 0; i < sv->n_count && i < DP_SPEC_MAX_NLIST && ok; i++) {
        char p[32];
        snprintf(p, sizeof p, "/solver/%s/%zu", sv->scheme == DP_SCHEME_PI ? "k" : "n", i);
        if (sv->n_count == 1)   /* a number, or an array of one whose own pointer the member's also names */
            snprintf(p, sizeof p, "/solver/%s", sv->scheme == DP_SCHEME_PI ? "k" : "n");
        double lg = dp_relaxation_lipschitz(&m->damper.relaxation);   /* power's is infinite: refused apart */
        double n = sv->n_list[i], L = n + m->spring.k + dp_damper_viscous(&m->damper) + (isfinite(lg) ? lg : 0);
        const factor N = { p, n }, M = { "/model/mass", m->mass }, X = { "/initial/x", s->x0 },
                     V = { "/initial/v", s->v0 }, VB = { "/model/damper/belt_velocity", m->damper.belt_velocity };
        ok = FORMED(e, n, 1, "the approximation's 1/n", N)
             && FORMED(e, n * (fabs(s->v0 - m->damper.belt_velocity) + fabs(s->x0)), 0,
                       "the approximation's forces n |v - v_b|, n |x|", N, X, V, VB)
             && FORMED(e, 1e-3 * m->mass / (n + 1), 1, "the integrator's first step 1e-3 m/(n + 1)", M, N)
             && FORMED(e, 1e-12 * m->mass / L, 1, "the integrator's smallest step 1e-12 m/(n + k + c + L_gamma)", M,
                       N, { "/model/spring/k", m->spring.k }, { "/model/damper/c", dp_damper_viscous(&m->damper) });
    }
    return ok;
}

/* The laws' own quantities at the initial state: a rope's force at its length, an elastoplastic spring's
 * vertices p -/+ F_y/k and trial force, the relaxation's slope and value. */
static int laws_finite(const dp_spec *s, double h, double th, dp_errors *e)
{
    const dp_spring *sp = &s->model.spring;
    const dp_relaxation *r = &s->model.damper.relaxation;
    const factor K = { "/model/spring/k", sp->k }, X = { "/initial/x", s->x0 };
    int ok = 1;
    if (sp->law == DP_SPRING_LINEAR)
        ok &= FORMED(e, sp->k * s->x0, 0, "the spring force k x", K, X);
    if (sp->law == DP_SPRING_ROPE)
        ok &= FORMED(e, sp->k * sp->length, 0, "the rope's force k L", K, { "/model/spring/length", sp->length });
    if (dp_spring_plastic(sp)) {
        const factor Y = { "/model/spring/yield", sp->yield }, P = { "/model/spring/offset", sp->offset };
        double d = sp->yield / sp->k;
        ok &= FORMED(e, 2 * d, 0, "the elastic range 2 F_y / k", Y, K);
        ok = ok && FORMED(e, fabs(sp->offset) + d, 0, "the yield points p -/+ F_y / k", Y, K, P);
        ok = ok && FORMED(e, sp->k * (s->x0 - sp->offset), 0, "the trial force k (x - p)", K, X, P);
    }
    if (r->kind == DP_RELAX_RATIONAL || r->kind == DP_RELAX_LINEAR) {
        const factor A = { "/model/damper/relaxation/a", r->a }, B = { "/model/damper/relaxation/b", r->b },
                     L = { "/model/damper/relaxation/L", r->L }, H = { "/solver/dt", h };
        double lip = dp_relaxation_lipschitz(r);
        ok &= r->kind == DP_RELAX_LINEAR ? FORMED(e, h * th * lip, 0, "the relaxation's h theta L", L, H)
                                         : FORMED(e, h * th * lip, 0, "the relaxation's h theta a / b", A, B, H);
    }
    return ok;
}

/* Every quantity the one-mass run types form from the document at its start is finite, or the member that
 * makes one overflow is named (a 422 at validation rather than a run that fails with "overflow" at t = 0).
 * Runs on when they are: the run's own checks stop it later, with the overflow named as such. */
static int check_one_mass_finite(const dp_spec *s, dp_errors *e)
{
    const dp_solver_spec *sv = &s->solver;
    double n = sv->t_end / sv->dt;
    if (!isfinite(n))
        return 1;                /* finish() refuses the step count */
    int ok = 1;
    double th = sv->kind == DP_SOLVER_STICK_SLIP ? sv->theta : 1;
    double Fmax = forcing_bound(&s->model.forcing, "/model/forcing", sv->t_end, e, &ok);
    double steps = dp_spec_steps(s), last = sv->t_end - (steps - 1) * sv->dt;
    if (!ok || sv->kind == DP_SOLVER_ANALYTIC)
        return ok;
    ok &= laws_finite(s, sv->dt, th, e);
    if (sv->kind == DP_SOLVER_REGULARIZED)
        return ok && regularized_finite(s, e);
    if (sv->kind == DP_SOLVER_NEWMARK)
        return ok && (steps <= 1 || newmark_finite(s, sv->dt, "/solver/dt", Fmax, e))
               && newmark_finite(s, last, "/solver/t_end", Fmax, e);
    if (ok && steps > 1)
        ok &= step_finite(s, sv->dt, "/solver/dt", th, Fmax, e);
    if (ok)
        ok &= step_finite(s, last, "/solver/t_end", th, Fmax, e);
    return ok;
}

/* A graph whose end ray is vertical bounds its kinematic variable (a rope bounds x, a velocity limit v);
 * the initial state must lie inside, or the first step has no solution. */
static void check_domain(const dp_graph *g, double y, const char *ptr, const char *name, dp_errors *e)
{
    if (g->n == 0)
        return;
    if (g->right[0] == 0 && y > g->y[g->n - 1])
        dp_errors_add(e, ptr, "the graph allows %s <= %g only (its last piece is vertical), got %g", name,
                      g->y[g->n - 1], y);
    if (g->left[0] == 0 && y < g->y[0])
        dp_errors_add(e, ptr, "the graph allows %s >= %g only (its first piece is vertical), got %g", name,
                      g->y[0], y);
}

/* The one-mass model's domain: the initial state inside the graphs' vertical ends (a rope bounds x). */
static void check_one_mass_domain(const dp_spec *s, dp_errors *e)
{
    const dp_model *m = &s->model;
    const dp_spring_law_info *SL = dp_spring_law_info_of(m->spring.law);
    dp_law_field x_max = SL ? SL->x_max : 0;
    double xm = x_max ? dp_law_field_value(&m->spring, x_max) : 0;
    if (x_max && s->x0 > xm)
        dp_errors_add(e, "/initial/x", "the %s is inextensible: x must be <= %s = %g, got %g", SL->row.name,
                      dp_law_member_key(&SL->row, x_max), xm, s->x0);
    else
        check_domain(&m->spring.graph, s->x0, "/initial/x", "x", e);
    check_domain(&m->damper.graph, s->v0 - m->damper.belt_velocity, "/initial/v", "v - belt_velocity", e);
}

/* What every run type ends its rules with: DP_EINVAL if they added errors, else the step limit (node-steps
 * for a network: a step costs about a unit per node and element). */
static int finish(const dp_spec *s, double max_steps, dp_errors *e, size_t before)
{
    if (e->n + e->dropped > before)
        return DP_EINVAL;
    if (max_steps <= 0 || max_steps > DP_SPEC_MAX_STEPS)
        max_steps = DP_SPEC_MAX_STEPS;
    double n = s->solver.t_end / s->solver.dt;
    if (!isfinite(n)) {
        dp_errors_add(e, "/solver/dt", "t_end/dt = %g/%g overflows double precision: at most %.6g steps per run",
                      s->solver.t_end, s->solver.dt, max_steps);
        return DP_ELIMIT;
    }
    if (s->net && !(n * (double)(s->net->n + s->net->nel) <= max_steps)) {
        dp_errors_add(e, "/solver/dt", "t_end/dt = %.6g steps of %zu nodes and %zu elements exceed the limit of "
                      "%.6g node-steps per run", n, s->net->n, s->net->nel, max_steps);
        return DP_ELIMIT;
    }
    if (!(n <= max_steps)) {
        dp_errors_add(e, "/solver/dt", "t_end/dt = %.6g steps exceeds the limit of %.6g steps per run",
                      n, max_steps);
        return DP_ELIMIT;
    }
    return DP_OK;
}

/* One function per run type (solvers/run_types.h), each named in its type. */

int dp_rules_stick_slip(const dp_spec *s, double max_steps, dp_errors *e)
{
    size_t before = e->n + e->dropped;
    check_one_mass_domain(s, e);
    if (check_one_mass_finite(s, e))
        check_exact(s, e);
    return finish(s, max_steps, e, before);
}

int dp_rules_thesis(const dp_spec *s, double max_steps, dp_errors *e)
{
    size_t before = e->n + e->dropped;
    check_one_mass_domain(s, e);
    if (check_one_mass_finite(s, e))
        check_thesis(s, e);
    return finish(s, max_steps, e, before);
}

int dp_rules_analytic(const dp_spec *s, double max_steps, dp_errors *e)
{
    size_t before = e->n + e->dropped;
    check_one_mass_domain(s, e);
    if (check_one_mass_finite(s, e))
        check_analytic(s, e);
    int st = finish(s, max_steps, e, before);
    if (st != DP_OK)
        return st;
    if (max_steps <= 0 || max_steps > DP_SPEC_MAX_STEPS)
        max_steps = DP_SPEC_MAX_STEPS;
    double arcs = analytic_arcs(s);
    if (!(arcs <= max_steps)) {
        dp_errors_add(e, "/model/spring/k", "the closed form passes up to %.3g turning points by t_end, over the "
                      "limit of %.6g per run (the half-period pi sqrt(m/k) is %.3g)", arcs, max_steps,
                      M_PI * sqrt(s->model.mass / s->model.spring.k));
        return DP_ELIMIT;
    }
    return DP_OK;
}

int dp_rules_newmark(const dp_spec *s, double max_steps, dp_errors *e)
{
    size_t before = e->n + e->dropped;
    check_one_mass_domain(s, e);
    if (check_one_mass_finite(s, e))
        dp_newmark_check(s, e);
    return finish(s, max_steps, e, before);
}

int dp_rules_regularized(const dp_spec *s, double max_steps, dp_errors *e)
{
    size_t before = e->n + e->dropped;
    check_one_mass_domain(s, e);
    if (!check_one_mass_finite(s, e))
        ;
    else if (dp_spring_plastic(&s->model.spring))
        dp_errors_add(e, "/model/spring/law", "the %s spring has memory (its plastic offset), which the "
                      "regularized schemes' memoryless laws do not: use the stick-slip or the newmark solver",
                      dp_spring_law_name(s->model.spring.law));
    else
        dp_regularized_check(s, e);
    return finish(s, max_steps, e, before);
}

int dp_rules_network(const dp_spec *s, double max_steps, dp_errors *e)
{
    size_t before = e->n + e->dropped;
    dp_network_check(s, e);
    dp_quakes_check(s, e);
    return finish(s, max_steps, e, before);
}

int dp_rules_right_hand(const dp_spec *s, double max_steps, dp_errors *e)
{
    size_t before = e->n + e->dropped;
    dp_right_hand_check(s, e);
    return finish(s, max_steps, e, before);
}
