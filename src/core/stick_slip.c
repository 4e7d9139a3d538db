/* src/core/stick_slip.c - exact stick-slip time stepping: the theta-method (Moreau-Jean, as Siconos'
 * EulerMoreauOSI) for m x'' + c (x' - v_b) + k x + r - gamma = F(t), r in A(x' - v_b) (mathematics.md §4).
 *
 * Each step is one scalar monotone inclusion in v+. For a linear spring, a threshold damper (Coulomb,
 * Bingham, linear, generalized Coulomb) and no relaxation it is the soft threshold
 *     u = v_free - v_b,  v+ = v_b + sgn(u) max(|u| - h tau / W, 0),  W = m + h theta c + h^2 theta^2 k,
 * (Moreau's catching-up scheme: exact sticking, no creep). Otherwise it goes to dp_inclusion_solve, which
 * handles any maximal monotone damper graph, monotone spring graph and relaxation.
 *
 * With events "locate" a step is split at the instant the relative velocity reaches zero (found to rounding
 * on the step's own trajectory) and at the instant the stick force leaves its interval, so the nonsmooth
 * instants cost no order: theta = 1/2 stays second order. The closed form does it with its own formulas;
 * the general inclusion with the same two conditions evaluated on dp_inclusion (any damper graph that can
 * stick, relaxation, graph springs).
 */
#include <math.h>
#include <string.h>

#include "inclusion.h"
#include "root.h"
#include "run_internal.h"

static double sgn(double x)
{
    return (x > 0) - (x < 0);
}

/* ---- the closed form ------------------------------------------------------------------------------ */

/* F(t), without the call for the usual constant load. */
static inline double load(const dp_ss_law *L, double t)
{
    return L->F_const ? L->F0 : dp_forcing_eval(L->F, t);
}

/* The affine map (v, x, F) -> u of a step of length h, folded once per step length:
 * u = [m v - h(1-theta) c v + h c v_b - h k (x + h theta (1-theta) v) + h F] / W - v_b. */
void dp_ss_coef_init(const dp_ss_law *L, double h, dp_ss_coef *c)
{
    double th = L->theta;
    c->W = L->m + h * th * L->c + h * h * th * th * L->k;
    double iW = 1 / c->W;
    c->cv = (L->m - h * (1 - th) * L->c - h * h * L->k * th * (1 - th)) * iW;
    c->cx = -h * L->k * iW;
    c->cf = h * iW;
    c->c0 = h * L->c * L->vb * iW - L->vb;
    c->thr = h * L->tau * iW;
    c->thr_s = h * L->tau_s * iW;
}

/* Relative free velocity u of a step of length h from (t, x, v), with the step's coefficients in *c. */
static inline double free_velocity(const dp_ss_law *L, double t, double h, double x, double v, dp_ss_coef *c)
{
    if (h != L->h)
        dp_ss_coef_init(L, h, c);
    else
        *c = L->nominal;
    return c->cv * v + c->cx * x + c->cf * load(L, t + L->theta * h) + c->c0;
}

typedef struct step_state { double t, x, v; dp_phase phase; } step_state;

/* Advances s by a step of length h whose free velocity u and coefficients c are known, with the Moreau
 * rule; returns the friction's mean force over the step. */
static inline double moreau_from(const dp_ss_law *L, step_state *s, double h, double u, const dp_ss_coef *c)
{
    double dir = sgn(s->v - L->vb), w, r;
    if (dir != 0 && u * dir > c->thr) {
        w = u - c->thr * dir;               /* slip goes on */
        r = L->tau * dir;
    } else if (L->can_stick && fabs(u) <= c->thr_s) {
        w = 0;                              /* stick: exactly at the belt's speed */
        r = u * c->W / h;
    } else {
        w = u - c->thr * sgn(u);            /* slip from rest or reversal */
        r = L->tau * sgn(u);
    }
    double v1 = L->vb + w;
    s->x += h * ((1 - L->theta) * s->v + L->theta * v1);
    s->v = v1;
    s->t += h;
    s->phase = !L->can_stick ? DP_PHASE_NONE : w == 0 ? DP_PHASE_STICK : DP_PHASE_SLIP;
    return r;
}

static double moreau(const dp_ss_law *L, step_state *s, double h)
{
    dp_ss_coef c;
    double u = free_velocity(L, s->t, h, s->x, s->v, &c);
    return moreau_from(L, s, h, u, &c);
}

typedef struct event_ctx { const dp_ss_law *L; step_state s; double dir; } event_ctx;

/* Relative velocity at the end of a step of length eta with the friction held at tau * dir. */
static double slip_velocity(void *p, double eta)
{
    event_ctx *e = p;
    if (eta == 0)
        return e->s.v - e->L->vb;
    dp_ss_coef c;
    double u = free_velocity(e->L, e->s.t, eta, e->s.x, e->s.v, &c);
    return u - c.thr * e->dir;
}

/* Distance of the force needed to hold the mass at the belt's speed from the static interval. */
static double hold_margin(void *p, double eta)
{
    event_ctx *e = p;
    double x = e->s.x + eta * e->L->vb;
    return fabs(dp_forcing_eval(e->L->F, e->s.t + eta) - e->L->k * x) - e->L->tau_s;
}

/* Breakaway from stick inside a step: hold until the needed force leaves [-tau_s, tau_s] (found to
 * rounding), then slide for the rest of the step in that force's direction. Returns the time held. */
static double breakaway(dp_run *r, step_state *s, double h, double *force)
{
    const dp_ss_law *L = &r->law;
    event_ctx e = { .L = L, .s = *s, .dir = 0 };
    double tol = 4 * 2.220446049250313e-16 * (s->t + h);
    double m0 = hold_margin(&e, 0), m1 = hold_margin(&e, h), eta = 0;
    if (m0 < 0 && m1 > 0)
        eta = dp_root_bracket(hold_margin, &e, 0, h, m0, m1, tol, &r->sum.iterations);
    s->x += eta * L->vb;
    s->t += eta;
    dp_run_emit_event(r, DP_EVENT_SLIP, s->t, s->x, s->v);
    double rest = h - eta, dir = sgn(dp_forcing_eval(L->F, s->t) - L->k * s->x);
    if (rest > 0) {
        dp_ss_coef c;
        double u = free_velocity(L, s->t, rest, s->x, s->v, &c);
        double w = u - c.thr * dir;
        w = w * dir > 0 ? w : 0; /* starts from zero acceleration: never backwards */
        double v1 = L->vb + w;
        s->x += rest * ((1 - L->theta) * s->v + L->theta * v1);
        s->v = v1;
        s->t += rest;
        *force = L->tau * dir;
    }
    s->phase = DP_PHASE_SLIP;
    return eta;
}

/* One located step from s over h; emits the events it finds; returns the time spent sticking. */
static double located_step(dp_run *r, step_state *s, double h, double *force)
{
    const dp_ss_law *L = &r->law;
    event_ctx e = { .L = L, .s = *s, .dir = sgn(s->v - L->vb) };
    if (e.dir != 0) {
        dp_ss_coef c;
        double u = free_velocity(L, s->t, h, s->x, s->v, &c);
        if (u * e.dir > c.thr) {
            *force = moreau_from(L, s, h, u, &c);
            return 0;
        }
        /* The relative velocity reaches zero inside the step: stop there, then go on from rest. */
        double tol = 4 * 2.220446049250313e-16 * (s->t + h);
        double g1 = u - c.thr * e.dir;
        double eta = dp_root_bracket(slip_velocity, &e, 0, h, s->v - L->vb, g1, tol, &r->sum.iterations);
        s->x += eta * ((1 - L->theta) * s->v + L->theta * L->vb);
        s->v = L->vb;
        s->t += eta;
        double rest = h - eta;
        step_state probe = *s;
        if (rest > 0)
            *force = moreau(L, &probe, rest);
        int sticks = rest > 0 ? probe.phase == DP_PHASE_STICK : hold_margin(&e, eta) <= 0;
        if (sticks && L->can_stick) {
            dp_run_emit_event(r, DP_EVENT_STICK, s->t, s->x, s->v);
            if (rest > 0)
                *s = probe;
            s->phase = DP_PHASE_STICK;
            return rest;
        }
        if (rest > 0)
            *s = probe;
        s->phase = DP_PHASE_SLIP;
        return 0;
    }
    if (s->phase == DP_PHASE_STICK) {
        /* Held at the belt's speed the mass has no acceleration, so the force that holds it is known in
         * closed form; Moreau's test would see it leave the interval up to a step late. */
        if (hold_margin(&e, h) > 0)
            return breakaway(r, s, h, force);
        s->x += h * L->vb;
        s->t += h;
        *force = dp_forcing_eval(L->F, s->t) - L->k * s->x;
        return h;
    }
    step_state probe = *s;
    *force = moreau(L, &probe, h);
    if (s->phase == DP_PHASE_SLIP && probe.phase == DP_PHASE_STICK)
        dp_run_emit_event(r, DP_EVENT_STICK, s->t, s->x, s->v);
    *s = probe;
    return probe.phase == DP_PHASE_STICK ? h : 0;
}

/* ---- the general inclusion ------------------------------------------------------------------------- */

/* The inclusion of a step of length h from s (mathematics.md §4, "Exact form of the step"). */
static dp_inclusion step_inclusion(const dp_ss_law *L, const step_state *s, double h)
{
    double th = L->theta;
    return (dp_inclusion){
        .W = L->m + h * th * L->c + h * h * th * th * L->k,
        .b = L->m * s->v - h * (1 - th) * L->c * s->v + h * L->c * L->vb
           - h * L->k * (s->x + h * th * (1 - th) * s->v) + h * dp_forcing_eval(L->F, s->t + th * h),
        .h = h, .A = L->A, .a_shift = L->vb, .S = L->S, .s_x = s->x, .s_h = h,
        .gamma = L->gamma, .g_theta = th, .g_shift = (1 - th) * s->v - L->vb,
    };
}

/* One step through dp_inclusion_solve; returns DP_OK or DP_ESOLVE. */
static int inclusion_step(dp_run *r, step_state *s, double h, double *fc, double *fs)
{
    const dp_ss_law *L = &r->law;
    double th = L->theta;
    dp_inclusion p = step_inclusion(L, s, h);
    double w, a, sp;
    if (dp_inclusion_solve(&p, &w, &a, &sp, &r->sum.iterations) != DP_OK)
        return DP_ESOLVE;
    double dir = sgn(s->v - L->vb);
    /* Motion branch: where rest solves the step but a motion in the direction of the free push does too
     * (non-Lipschitz gamma), follow the motion. */
    double push = sgn(p.b - p.W * L->vb);
    if (L->motion && w == L->vb && dir == 0 && push != 0)
        dp_inclusion_solve_side(&p, push, &w, &a, &sp, &r->sum.iterations);
    /* Generalized Coulomb (rest branch): where the motion stops or would start, the static interval
     * [-phi1, phi1] decides whether the mass stays at the belt's speed. */
    if (L->tau_s > L->tau && w != L->vb && (dir == 0 || sgn(w - L->vb) != dir)
        && dp_inclusion_holds_with(&p, L->vb, -L->tau_s, L->tau_s)) {
        double R = (p.b - p.W * L->vb + h * dp_relaxation_eval(L->gamma, th * L->vb + p.g_shift)) / h, lo, hi;
        sp = 0;
        if (L->S) {
            dp_graph_force(L->S, s->x + h * L->vb, &lo, &hi);
            sp = lo;
        }
        w = L->vb;
        a = R - sp;
    }
    s->x += h * ((1 - th) * s->v + th * w);
    s->v = w;
    s->t += h;
    s->phase = !L->can_stick ? DP_PHASE_NONE : w == L->vb ? DP_PHASE_STICK : DP_PHASE_SLIP;
    *fc = a;
    *fs = sp;
    return DP_OK;
}

/* No finite bracket for the step: either the state has already run away (report divergence) or the
 * inclusion really has no solution at this state. */
static int step_failed(dp_run *r, const step_state *s)
{
    if (!(fabs(s->x) < 1e100 && fabs(s->v) < 1e100))
        return dp_run_fail(r, DP_ENONFINITE, "the solution diverged at t = %.17g (|x| = %.3g, |v| = %.3g)",
                           s->t, fabs(s->x), fabs(s->v));
    return dp_run_fail(r, DP_ESOLVE, "the implicit step at t = %.17g has no solution", s->t);
}

/* ---- events of the general inclusion ---------------------------------------------------------------- */

/* The same two instants as located_step and breakaway, for any maximal monotone damper graph, spring graph
 * and relaxation: where the relative velocity reaches zero, and where the force that holds the mass at the
 * belt's speed leaves the stick interval. */

typedef struct arrival_ctx { const dp_ss_law *L; step_state s; double dir, a; } arrival_ctx;

/* dir Phi(v_b) of a step of length eta with the damper force held at its slip-side limit a (A(0) is
 * [A(0-), A(0+)] for a maximal monotone graph): negative while that step would still end slipping in
 * direction dir, >= 0 once it reaches the belt's speed. At eta = 0 it is -m |v - v_b|. */
static double arrival(void *p, double eta)
{
    const arrival_ctx *e = p;
    dp_inclusion q = step_inclusion(e->L, &e->s, eta);
    double lo, hi;
    dp_inclusion_phi_with(&q, e->L->vb, e->a, e->a, &lo, &hi);
    return e->dir > 0 ? hi : -lo;
}

/* The interval the damper force may take at rest: the static one of a generalized Coulomb law, else A(0). */
static void stick_interval(const dp_ss_law *L, double *lo, double *hi)
{
    if (L->tau_s > L->tau) {
        *lo = -L->tau_s, *hi = L->tau_s;
        return;
    }
    dp_graph_force(L->A, 0, lo, hi);
}

typedef struct hold_ctx { const dp_ss_law *L; step_state s; double slo, shi; } hold_ctx;

/* [*lo, *hi]: the damper forces r that hold the mass at the belt's speed at s.t + eta, from
 * m x'' = 0 = F - F_s - r + gamma(0) (a vertical spring piece widens it). */
static void hold_force(const hold_ctx *e, double eta, double *lo, double *hi)
{
    const dp_ss_law *L = e->L;
    double x = e->s.x + eta * L->vb, flo, fhi;
    if (L->S)
        dp_graph_force(L->S, x, &flo, &fhi);
    else
        flo = fhi = L->k * x;
    double load_g = dp_forcing_eval(L->F, e->s.t + eta) + dp_relaxation_eval(L->gamma, 0);
    *lo = load_g - fhi, *hi = load_g - flo;
}

/* Distance of the holding forces from the stick interval: > 0 when the mass must break away. */
static double hold_gap(void *p, double eta)
{
    const hold_ctx *e = p;
    double lo, hi;
    hold_force(e, eta, &lo, &hi);
    double gap = fmax(lo - e->shi, e->slo - hi);
    return fmin(fmax(gap, -1e300), 1e300); /* finite for the root search: a rigid stop makes it -inf */
}

/* Held over the whole step: the damper takes the holding force of least magnitude. */
static double hold_step(const hold_ctx *e, step_state *s, double h, double *fc, double *fs)
{
    double lo, hi;
    hold_force(e, h, &lo, &hi);
    lo = fmax(lo, e->slo), hi = fmin(hi, e->shi);
    s->x += h * e->L->vb;
    s->t += h;
    s->v = e->L->vb;
    s->phase = DP_PHASE_STICK;
    *fc = fmin(fmax(0.0, lo), hi);
    *fs = e->L->S ? dp_forcing_eval(e->L->F, s->t) + dp_relaxation_eval(e->L->gamma, 0) - *fc : 0;
    return h;
}

/* Breakaway from stick inside a step (general form of breakaway). Returns the time held or -1. */
static double breakaway_general(dp_run *r, hold_ctx *e, step_state *s, double h, double *fc, double *fs)
{
    double g0 = hold_gap(e, 0), g1 = hold_gap(e, h), eta = 0;
    if (g0 < 0)
        eta = dp_root_bracket(hold_gap, e, 0, h, g0, g1, 4 * 2.220446049250313e-16 * (s->t + h),
                              &r->sum.iterations);
    double lo, hi;
    hold_force(e, eta, &lo, &hi);
    *fc = lo > e->shi ? e->shi : e->slo; /* the bound it leaves by, if the step ends here */
    *fs = 0;
    s->x += eta * r->law.vb;
    s->t += eta;
    dp_run_emit_event(r, DP_EVENT_SLIP, s->t, s->x, s->v);
    if (h - eta > 0 && inclusion_step(r, s, h - eta, fc, fs) != DP_OK)
        return -1;
    s->phase = DP_PHASE_SLIP; /* even if the first stretch of slip rounds to the belt's speed */
    return eta;
}

/* One located step of the general inclusion from s over h; emits the events it finds; returns the time
 * spent sticking, or -1 if a step has no solution. */
static double located_inclusion_step(dp_run *r, step_state *s, double h, double *fc, double *fs)
{
    const dp_ss_law *L = &r->law;
    hold_ctx hc = { .L = L, .s = *s };
    stick_interval(L, &hc.slo, &hc.shi);
    double dir = sgn(s->v - L->vb);
    if (dir == 0 && s->phase == DP_PHASE_STICK)
        return hold_gap(&hc, h) <= 0 ? hold_step(&hc, s, h, fc, fs) : breakaway_general(r, &hc, s, h, fc, fs);
    step_state probe = *s;
    if (inclusion_step(r, &probe, h, fc, fs) != DP_OK)
        return -1;
    if (dir == 0 || sgn(probe.v - L->vb) == dir) {
        if (s->phase == DP_PHASE_SLIP && probe.phase == DP_PHASE_STICK)
            dp_run_emit_event(r, DP_EVENT_STICK, s->t, s->x, s->v);
        *s = probe;
        return s->phase == DP_PHASE_STICK ? h : 0;
    }
    /* The relative velocity reaches zero inside the step: stop there, then go on from rest. */
    double alo, ahi;
    dp_graph_force(L->A, 0, &alo, &ahi);
    arrival_ctx ac = { .L = L, .s = *s, .dir = dir, .a = dir > 0 ? ahi : alo };
    double g0 = arrival(&ac, 0), g1 = arrival(&ac, h);
    if (!(g0 < 0 && g1 >= 0)) { /* no sign change to bracket (rounding at the end of the step) */
        *s = probe;
        return s->phase == DP_PHASE_STICK ? h : 0;
    }
    double eta = dp_root_bracket(arrival, &ac, 0, h, g0, g1, 4 * 2.220446049250313e-16 * (s->t + h),
                                 &r->sum.iterations);
    s->x += eta * ((1 - L->theta) * s->v + L->theta * L->vb);
    s->v = L->vb;
    s->t += eta;
    s->phase = DP_PHASE_SLIP;
    double rest = h - eta;
    hc.s = *s;
    probe = *s;
    if (rest > 0 && inclusion_step(r, &probe, rest, fc, fs) != DP_OK)
        return -1;
    int sticks = rest > 0 ? probe.phase == DP_PHASE_STICK : hold_gap(&hc, 0) <= 0;
    if (sticks) {
        dp_run_emit_event(r, DP_EVENT_STICK, s->t, s->x, s->v);
        if (rest == 0)
            return hold_step(&hc, s, 0, fc, fs);
        *s = probe;
        return rest;
    }
    if (rest == 0) { /* arrived at the end of the step, about to reverse: the slip-side forces */
        double flo = 0, fhi = 0;
        if (L->S)
            dp_graph_force(L->S, s->x, &flo, &fhi);
        *fc = ac.a, *fs = flo;
        return 0;
    }
    *s = probe;
    s->phase = DP_PHASE_SLIP;
    return 0;
}

/* ---- the run ---------------------------------------------------------------------------------------- */

static void set_forces(dp_run *r, double fc_graph, double fs_graph)
{
    const dp_ss_law *L = &r->law;
    dp_sample *c = &r->cur;
    c->Fs = L->S ? fs_graph : L->k * c->x;
    c->Fc = fc_graph + L->c * (c->v - L->vb);
    c->Fd = L->gamma->kind == DP_RELAX_NONE ? c->Fc : c->Fc - dp_relaxation_eval(L->gamma, c->v - L->vb);
}

static void phase_event(dp_run *r, dp_phase before)
{
    dp_phase now = r->cur.phase;
    if (before == now || now == DP_PHASE_NONE)
        return;
    dp_run_emit_event(r, now == DP_PHASE_STICK ? DP_EVENT_STICK : DP_EVENT_SLIP, r->cur.t, r->cur.x, r->cur.v);
}

/* The hot loops below take nominal steps of the closed form up to (not including) the next step that
 * emits a sample or is the last; this is where they must stop. */
static unsigned long long fast_stop(const dp_run *r)
{
    unsigned long long stop = r->nsteps - 1;
    if (r->spec.output.samples && r->n + (unsigned long long)r->countdown - 1 < stop)
        stop = r->n + (unsigned long long)r->countdown - 1;
    return stop;
}

static void fast_done(dp_run *r, unsigned long long n, double x, double v)
{
    r->countdown -= (long)(n - r->n);
    r->n = n;
    r->cur.x = x, r->cur.v = v, r->cur.t = (double)n * r->h;
}

/* Glide: the slip goes on in one direction. The same arithmetic as free_velocity and moreau_from's first
 * branch, so the result is bit for bit the general path's; it leaves out only what a continuing slip
 * cannot need (events, forces, the bracket). */
static void glide(dp_run *r)
{
    const dp_ss_law *L = &r->law;
    const dp_ss_coef *c = &L->nominal;
    unsigned long long n = r->n, stop = fast_stop(r);
    double x = r->cur.x, v = r->cur.v, dir = sgn(v - L->vb), h = L->h, th = L->theta;
    for (; n < stop; n++) {
        double u = c->cv * v + c->cx * x + c->cf * load(L, (double)n * h + th * h) + c->c0;
        if (!(u * dir > c->thr))
            break;
        double v1 = L->vb + (u - c->thr * dir);
        x += h * ((1 - th) * v + th * v1);
        v = v1;
    }
    fast_done(r, n, x, v);
}

/* Hold: the mass sits at the belt's speed and the holding force stays inside the static interval (tested
 * as the located step tests it, or as Moreau's rule does with events "none"). Same arithmetic as
 * located_step's stick branch and moreau_from's stick branch. */
static void hold(dp_run *r)
{
    const dp_ss_law *L = &r->law;
    const dp_ss_coef *c = &L->nominal;
    unsigned long long n = r->n, stop = fast_stop(r);
    double x = r->cur.x, vb = L->vb, h = L->h, th = L->theta;
    for (; n < stop; n++) {
        double t = (double)n * h;
        if (L->locate) {
            if (fabs(dp_forcing_eval(L->F, t + h) - L->k * (x + h * vb)) - L->tau_s > 0)
                break;
            x += h * vb;
        } else {
            if (!(fabs(c->cv * vb + c->cx * x + c->cf * load(L, t + th * h) + c->c0) <= c->thr_s))
                break;
            x += h * ((1 - th) * vb + th * vb);
        }
        r->sum.stick_time += h;
    }
    fast_done(r, n, x, vb);
}

/* Runs the hot loop that fits the current phase, if any; DP_OK or DP_ENONFINITE. */
static int fast_steps(dp_run *r)
{
    const dp_ss_law *L = &r->law;
    if (r->cur.phase == DP_PHASE_SLIP && r->cur.v != L->vb)
        glide(r);
    else if (r->cur.phase == DP_PHASE_STICK && r->cur.v == L->vb)
        hold(r);
    else
        return DP_OK;
    if (!isfinite(r->cur.x) || !isfinite(r->cur.v))
        return dp_run_fail(r, DP_ENONFINITE, "the solution diverged at t = %.17g", r->cur.t);
    return DP_OK;
}

int dp_stick_slip_advance(dp_run *r)
{
    const dp_ss_law *L = &r->law;
    while (dp_run_room(r)) {
        if (L->closed && fast_steps(r) != DP_OK)
            return r->status;
        double h = dp_run_step_length(r), fc = 0, fs = 0;
        step_state s = { r->cur.t, r->cur.x, r->cur.v, r->cur.phase };
        dp_phase before = s.phase;
        if (L->closed && L->locate) {
            r->sum.stick_time += located_step(r, &s, h, &fc);
        } else if (L->locate) {
            double held = located_inclusion_step(r, &s, h, &fc, &fs);
            if (held < 0)
                return step_failed(r, &s);
            r->sum.stick_time += held;
        } else {
            if (L->closed)
                fc = moreau(L, &s, h);
            else if (inclusion_step(r, &s, h, &fc, &fs) != DP_OK)
                return step_failed(r, &s);
            if (s.phase == DP_PHASE_STICK)
                r->sum.stick_time += h;
        }
        r->n++;
        s.t = r->n < r->nsteps ? (double)r->n * r->h : r->spec.solver.t_end;
        if (!isfinite(s.x) || !isfinite(s.v) || !isfinite(fc) || !isfinite(fs))
            return dp_run_fail(r, DP_ENONFINITE, "the solution diverged at t = %.17g", s.t);
        r->cur.t = s.t, r->cur.x = s.x, r->cur.v = s.v, r->cur.phase = s.phase;
        if (dp_run_sample_due(r)) /* forces are only read in samples and the summary (the last step) */
            set_forces(r, fc, fs);
        if (!L->locate)
            phase_event(r, before);
        r->sum.steps = r->n;
        if (r->n >= r->nsteps)
            r->finished = 1;
        dp_run_emit_state(r);
    }
    return DP_OK;
}

/* The initial damper force: where the mass is at the belt's speed, the force that holds it (F - F_s),
 * projected on the stick interval; elsewhere the graph's value. */
static void initial_state(dp_run *r)
{
    const dp_ss_law *L = &r->law;
    dp_sample *c = &r->cur;
    double lo, hi, slo = 0, shi = 0;
    c->t = 0, c->x = r->spec.x0, c->v = r->spec.v0;
    if (L->S) {
        dp_graph_force(L->S, c->x, &slo, &shi);
        /* On a vertical piece (a taut rope, a rigid stop) the force is any value of [slo, shi], possibly
         * unbounded both ways: take the one closest to zero, which is finite. */
        slo = fmin(fmax(0.0, slo), shi);
    }
    double Fs = L->S ? slo : L->k * c->x;
    dp_graph_force(L->A, c->v - L->vb, &lo, &hi);
    double need = dp_forcing_eval(L->F, 0) - Fs, fc = fmin(fmax(need, lo), hi);
    c->phase = DP_PHASE_NONE;
    if (L->can_stick && c->v == L->vb) { /* held if the stick interval has the force; else it slips off */
        double rlo, rhi;
        stick_interval(L, &rlo, &rhi);
        int holds = rlo <= need && need <= rhi;
        c->phase = holds ? DP_PHASE_STICK : DP_PHASE_SLIP;
        fc = holds ? need : need > 0 ? hi : lo;
    } else if (L->can_stick) {
        c->phase = DP_PHASE_SLIP;
    }
    set_forces(r, fc, Fs);
}

int dp_stick_slip_init(dp_run *r)
{
    const dp_model *m = &r->spec.model;
    const dp_damper *d = &m->damper;
    dp_ss_law *L = &r->law;
    int linear_spring = m->spring.law == DP_SPRING_LINEAR;
    int threshold = d->law != DP_DAMPER_GRAPH;
    double lo, hi;
    L->m = m->mass;
    L->k = linear_spring ? m->spring.k : 0;
    L->c = (d->law == DP_DAMPER_LINEAR || d->law == DP_DAMPER_BINGHAM) ? d->c : 0;
    L->tau = d->law == DP_DAMPER_BINGHAM ? d->tau : (d->law == DP_DAMPER_COULOMB
             || d->law == DP_DAMPER_GENERALIZED_COULOMB) ? d->phi0 : 0;
    L->motion = r->spec.solver.branch == DP_BRANCH_MOTION;
    /* The motion branch leaves rest as soon as kinetic friction allows: the static threshold drops out. */
    L->tau_s = d->law == DP_DAMPER_GENERALIZED_COULOMB && !L->motion ? d->phi1 : L->tau;
    L->vb = d->belt_velocity;
    L->theta = r->spec.solver.theta;
    L->A = &d->graph;
    L->S = linear_spring ? NULL : &m->spring.graph;
    L->gamma = &d->relaxation;
    L->F = &m->forcing;
    dp_graph_force(L->A, 0, &lo, &hi);
    L->can_stick = threshold ? L->tau_s > 0 : lo < hi;
    L->closed = linear_spring && threshold && d->relaxation.kind == DP_RELAX_NONE;
    /* Only a stick interval makes the dynamics nonsmooth; smooth reversals need no splitting. */
    L->h = r->h;
    L->F_const = m->forcing.kind == DP_FORCING_NONE || m->forcing.kind == DP_FORCING_CONSTANT;
    L->F0 = dp_forcing_eval(&m->forcing, 0);
    dp_ss_coef_init(L, L->h, &L->nominal);
    /* Events are located where the damper can stick; the motion branch leaves rest on its own terms. */
    L->locate = r->spec.solver.events == DP_EVENTS_LOCATE && (L->closed ? L->tau > 0 : L->can_stick && !L->motion);
    initial_state(r);
    return DP_OK;
}
