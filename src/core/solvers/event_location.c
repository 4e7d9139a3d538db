/* src/core/solvers/event_location.c - splitting a stick-slip step at the instants where its phase changes.
 *
 * A step that reaches the belt's speed or breaks away from it is split at that instant, found to rounding,
 * so the nonsmooth instants cost the theta-method no order (theta = 1/2 stays second order). Two conditions,
 * on the step's own trajectory: where the step with the damper held at its slip-side limit ends at the
 * belt's speed, and where the force that holds the mass at rest leaves the stick interval. The closed form
 * has them as formulas; the general inclusion evaluates them on dp_inclusion (any damper graph that can
 * stick, relaxation, graph springs).
 */
#include <math.h>

#include "base/root.h"
#include "solvers/stick_slip_step.h"

/* How close to its root an event instant inside a step of length h from t is found: a few ulps of the time. */
static double instant_tol(double t, double h)
{
    return 4 * 2.220446049250313e-16 * (t + h);
}

/* An event found inside a step: emitted at once, or kept in *ev when the caller asks for it. */
static void note(dp_run *r, dp_ss_events *ev, dp_event_kind kind, double t, double x, double v)
{
    if (ev == NULL) {
        dp_run_emit_event(r, kind, t, x, v);
        return;
    }
    if (ev->n < DP_SS_EVENTS_MAX)
        ev->e[ev->n++] = (dp_event){ .kind = kind, .t = t, .x = x, .v = v };
}

void dp_ss_events_emit(dp_run *r, const dp_ss_events *ev)
{
    for (size_t i = 0; i < ev->n; i++)
        dp_run_emit_event(r, ev->e[i].kind, ev->e[i].t, ev->e[i].x, ev->e[i].v);
}

/* ---- the closed form ------------------------------------------------------------------------------ */

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
    double tol = instant_tol(s->t, h);
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
double dp_ss_located_step(dp_run *r, step_state *s, double h, double *force)
{
    const dp_ss_law *L = &r->law;
    event_ctx e = { .L = L, .s = *s, .dir = sgn(s->v - L->vb) };
    if (e.dir != 0) {
        dp_ss_coef c;
        double u = free_velocity(L, s->t, h, s->x, s->v, &c);
        if (u * e.dir > c.thr) {
            *force = dp_ss_moreau_from(L, s, h, u, &c);
            return 0;
        }
        /* The relative velocity reaches zero inside the step: stop there, then go on from rest. */
        double tol = instant_tol(s->t, h);
        double g1 = u - c.thr * e.dir;
        double eta = dp_root_bracket(slip_velocity, &e, 0, h, s->v - L->vb, g1, tol, &r->sum.iterations);
        s->x += eta * ((1 - L->theta) * s->v + L->theta * L->vb);
        s->v = L->vb;
        s->t += eta;
        double rest = h - eta;
        step_state probe = *s;
        if (rest > 0)
            *force = dp_ss_moreau(L, &probe, rest);
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
    *force = dp_ss_moreau(L, &probe, h);
    if (s->phase == DP_PHASE_SLIP && probe.phase == DP_PHASE_STICK)
        dp_run_emit_event(r, DP_EVENT_STICK, s->t, s->x, s->v);
    *s = probe;
    return probe.phase == DP_PHASE_STICK ? h : 0;
}


/* ---- the general inclusion ------------------------------------------------------------------------- */

/* The same two instants as located_step and breakaway, for any maximal monotone damper graph, spring graph
 * and relaxation: where the relative velocity reaches zero, and where the force that holds the mass at the
 * belt's speed leaves the stick interval. */

typedef struct arrival_ctx { const dp_run *r; const dp_ss_law *L; step_state s; double dir, a; } arrival_ctx;

/* dir Phi(v_b) of a step of length eta with the damper force held at its slip-side limit a (A(0) is
 * [A(0-), A(0+)] for a maximal monotone graph): negative while that step would still end slipping in
 * direction dir, >= 0 once it reaches the belt's speed. At eta = 0 it is -m |v - v_b|. */
static double arrival(void *p, double eta)
{
    const arrival_ctx *e = p;
    dp_inclusion q = dp_ss_run_inclusion(e->r, &e->s, eta);
    double lo, hi;
    dp_inclusion_phi_with(&q, e->L->vb, e->a, e->a, &lo, &hi);
    return e->dir > 0 ? hi : -lo;
}

/* The interval the damper force may take at rest: the static one of a generalized Coulomb law, else A(0). */
void dp_ss_stick_interval(const dp_ss_law *L, double *lo, double *hi)
{
    if (L->tau_s > L->tau) {
        *lo = -L->tau_s, *hi = L->tau_s;
        return;
    }
    dp_graph_force(L->A, 0, lo, hi);
}

/* ep: an elastoplastic spring (its force at rest is its return mapping from the offset ep_p, not the
 * theta-weighted step graph L->S), else NULL. */
typedef struct hold_ctx { const dp_ss_law *L; step_state s; double slo, shi; const dp_spring *ep; double ep_p; } hold_ctx;

/* [*lo, *hi]: the damper forces r that hold the mass at the belt's speed at s.t + eta, from
 * m x'' = 0 = F - F_s - r + gamma(0) (a vertical spring piece widens it); returns F + gamma(0) = F_s + r. */
static double hold_force(const hold_ctx *e, double eta, double *lo, double *hi)
{
    const dp_ss_law *L = e->L;
    double x = e->s.x + eta * L->vb, flo, fhi;
    if (e->ep) {
        double p = e->ep_p;
        int flow;
        flo = fhi = dp_elastoplastic_return(e->ep, x, &p, &flow);
    } else if (L->S)
        dp_graph_force(L->S, x, &flo, &fhi);
    else
        flo = fhi = L->k * x;
    double load_g = dp_forcing_eval(L->F, e->s.t + eta) + dp_relaxation_eval(L->gamma, 0);
    *lo = load_g - fhi, *hi = load_g - flo;
    return load_g;
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
    double lo, hi, load_g = hold_force(e, h, &lo, &hi);
    lo = fmax(lo, e->slo), hi = fmin(hi, e->shi);
    s->x += h * e->L->vb;
    s->t += h;
    s->v = e->L->vb;
    s->phase = DP_PHASE_STICK;
    *fc = fmin(fmax(0.0, lo), hi);
    *fs = e->L->S ? load_g - *fc : 0;
    return h;
}

/* Breakaway from stick inside a step (general form of breakaway). Returns the time held or -1. */
static double breakaway_general(dp_run *r, hold_ctx *e, step_state *s, double h, double *fc, double *fs,
                                dp_ss_events *ev)
{
    double g0 = hold_gap(e, 0), g1 = hold_gap(e, h), eta = 0;
    if (g0 < 0)
        eta = dp_root_bracket(hold_gap, e, 0, h, g0, g1, instant_tol(s->t, h), &r->sum.iterations);
    double lo, hi, load_g = hold_force(e, eta, &lo, &hi);
    *fc = lo > e->shi ? e->shi : e->slo; /* the bound it leaves by, if the step ends here */
    *fs = r->law.S ? load_g - *fc : 0;   /* and the spring graph's share of the balance at rest */
    s->x += eta * r->law.vb;
    s->t += eta;
    note(r, ev, DP_EVENT_SLIP, s->t, s->x, s->v);
    if (h - eta > 0 && dp_ss_inclusion_step(r, s, h - eta, fc, fs) != DP_OK)
        return -1;
    s->phase = DP_PHASE_SLIP; /* even if the first stretch of slip rounds to the belt's speed */
    return eta;
}

/* One located step of the general inclusion from s over h; emits the events it finds; returns the time
 * spent sticking, or -1 if a step has no solution. */
double dp_ss_located_inclusion_step(dp_run *r, step_state *s, double h, double *fc, double *fs, dp_ss_events *ev)
{
    const dp_ss_law *L = &r->law;
    hold_ctx hc = { .L = L, .s = *s, .ep = r->ep ? &r->spec.model.spring : NULL, .ep_p = r->ep_p };
    dp_ss_stick_interval(L, &hc.slo, &hc.shi);
    double dir = sgn(s->v - L->vb);
    if (dir == 0 && s->phase == DP_PHASE_STICK)
        return hold_gap(&hc, h) <= 0 ? hold_step(&hc, s, h, fc, fs) : breakaway_general(r, &hc, s, h, fc, fs, ev);
    step_state probe = *s;
    if (dp_ss_inclusion_step(r, &probe, h, fc, fs) != DP_OK)
        return -1;
    if (dir == 0 || sgn(probe.v - L->vb) == dir) {
        if (s->phase == DP_PHASE_SLIP && probe.phase == DP_PHASE_STICK)
            note(r, ev, DP_EVENT_STICK, s->t, s->x, s->v);
        *s = probe;
        return s->phase == DP_PHASE_STICK ? h : 0;
    }
    /* The relative velocity reaches zero inside the step: stop there, then go on from rest. */
    double alo, ahi;
    dp_graph_force(L->A, 0, &alo, &ahi);
    arrival_ctx ac = { .r = r, .L = L, .s = *s, .dir = dir, .a = dir > 0 ? ahi : alo };
    double g0 = arrival(&ac, 0), g1 = arrival(&ac, h);
    if (!(g0 < 0 && g1 >= 0)) { /* no sign change to bracket (rounding at the end of the step) */
        *s = probe;
        return s->phase == DP_PHASE_STICK ? h : 0;
    }
    double eta = dp_root_bracket(arrival, &ac, 0, h, g0, g1, instant_tol(s->t, h), &r->sum.iterations);
    s->x += eta * ((1 - L->theta) * s->v + L->theta * L->vb);
    s->v = L->vb;
    s->t += eta;
    s->phase = DP_PHASE_SLIP;
    double rest = h - eta;
    hc.s = *s;
    probe = *s;
    if (rest > 0 && dp_ss_inclusion_step(r, &probe, rest, fc, fs) != DP_OK)
        return -1;
    int sticks = rest > 0 ? probe.phase == DP_PHASE_STICK : hold_gap(&hc, 0) <= 0;
    if (sticks) {
        note(r, ev, DP_EVENT_STICK, s->t, s->x, s->v);
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


/* ---- an elastoplastic spring's yield and unload ------------------------------------------------------ */

/* The Jenkins element (Höschl 1983, §15) changes phase where its slider starts sliding (yield: the trial
 * force k (x - p) of the elastic stretch reaches +-F_y) and where it stops (unload: the elongation rate x'
 * of the sliding stretch reaches zero, after which the force leaves the yield surface). Each is a root of a
 * margin on the step's own trajectory held in the current phase, as a function of the stretch's length,
 * exactly as the damper's arrival and breakaway are; the step is split there and goes on in the new phase,
 * so the kink costs theta = 1/2 no order. The held trajectory is the step with the spring's graph at the
 * current offset (its clamp agrees with the held phase up to the root) and the damper's own events located
 * inside it, so whichever comes first, spring or damper, is met first. */

/* Spring events one step may split at; past them the step ends as an unlocated one (a step long enough to
 * yield, unload and yield again several times resolves nothing anyway). */
#define PLASTIC_SPLITS_MAX 6

/* A stretch of length h from s with the spring held in its phase: the damper's events located (if it can
 * stick) into *ev, not emitted. Returns the time held at the belt's speed, or -1 (no solution). */
static double held_stretch(dp_run *r, step_state *s, double h, double *fc, double *fs, dp_ss_events *ev)
{
    if (r->law.locate)
        return dp_ss_located_inclusion_step(r, s, h, fc, fs, ev);
    if (dp_ss_inclusion_step(r, s, h, fc, fs) != DP_OK)
        return -1;
    return s->phase == DP_PHASE_STICK ? h : 0;
}

static double plastic_margin_at(const dp_run *r, const step_state *e)
{
    return dp_plastic_margin(&r->spec.model.spring, r->ep_p, r->ep_flow, e->x, e->v);
}

typedef struct plastic_ctx { dp_run *r; step_state s; int failed; } plastic_ctx;

static double plastic_margin(void *p, double eta)
{
    plastic_ctx *c = p;
    step_state e = c->s;
    dp_ss_events ev = { 0 };
    double fc, fs;
    if (eta > 0 && held_stretch(c->r, &e, eta, &fc, &fs, &ev) < 0)
        c->failed = 1;
    return plastic_margin_at(c->r, &e);
}

/* The spring at the end of a stretch in one phase: the return mapping there (p follows a sliding slider),
 * the step graph moved with p; returns whether the slider slid (+1, -1) or not (0). */
static int plastic_follow(dp_run *r, const step_state *s)
{
    dp_spring *sp = &r->spec.model.spring;
    int flow;
    r->ep_F = dp_elastoplastic_return(sp, s->x, &r->ep_p, &flow);
    if (flow)
        dp_elastoplastic_graph(sp, r->ep_p, r->law.theta, &sp->graph);
    return flow;
}

/* The phase change at the end s of a stretch, after plastic_follow (dp_plastic_switch); the step graph moved
 * with a new offset. */
static void plastic_switch(dp_run *r, const step_state *s)
{
    dp_spring *sp = &r->spec.model.spring;
    dp_event_kind kind = dp_plastic_switch(sp, s->x, &r->ep_p, &r->ep_F, &r->ep_flow);
    if (kind == DP_EVENT_YIELD)
        dp_elastoplastic_graph(sp, r->ep_p, r->law.theta, &sp->graph);
    dp_run_emit_event(r, kind, s->t, s->x, s->v);
}

/* One step of a one-mass model on an elastoplastic spring, split at the spring's yield and unload and at
 * the damper's stick and slip, whichever come first; events emitted in order. Returns the time spent
 * sticking, or -1 (a stretch has no solution). */
double dp_ss_located_plastic_step(dp_run *r, step_state *s, double h, double *fc, double *fs)
{
    double held = 0, rem = h;
    for (int split = 0; rem > 0; split++) {
        step_state e = *s;
        dp_ss_events ev = { 0 };
        double hd = held_stretch(r, &e, rem, fc, fs, &ev);
        if (hd < 0)
            return -1;
        plastic_ctx c = { .r = r, .s = *s };
        double g0 = plastic_margin_at(r, s), g1 = plastic_margin_at(r, &e);
        if (!(g1 > 0) || split == PLASTIC_SPLITS_MAX) {   /* the phase holds to the step's end */
            dp_ss_events_emit(r, &ev);
            *s = e;
            int flow = plastic_follow(r, s);
            if (split == PLASTIC_SPLITS_MAX && flow != r->ep_flow) {   /* too many: reported at the end */
                r->ep_flow = flow;
                dp_run_emit_event(r, flow ? DP_EVENT_YIELD : DP_EVENT_UNLOAD, s->t, s->x, s->v);
            }
            return held + hd;
        }
        double eta = 0;
        if (g0 < 0)
            eta = dp_root_bracket(plastic_margin, &c, 0, rem, g0, g1, instant_tol(s->t, rem), &r->sum.iterations);
        if (c.failed)
            return -1;
        if (eta > 0) {
            ev.n = 0;
            hd = held_stretch(r, s, eta, fc, fs, &ev);
            if (hd < 0)
                return -1;
            dp_ss_events_emit(r, &ev);
            held += hd;
            plastic_follow(r, s);
        }
        plastic_switch(r, s);
        rem = eta < rem ? rem - eta : 0;
    }
    return held;
}
