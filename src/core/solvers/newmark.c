/* src/core/solvers/newmark.c - the one-mass Newmark run (Höschl 1983, §15, Ex. 40): the mass as a 1 x 1 band
 * system stepped by network/newmark_step.c, an elastoplastic spring's return map after each step.
 *
 * With events "locate" a step in which the spring yields or unloads is split there: the instant is the root
 * of the spring's margin (dp_plastic_margin) at the end of a Newmark stretch with the tangent of the phase it
 * starts in, as a function of the stretch's length; the stretch to it is taken, the acceleration renewed from
 * the equation of motion at the event, and the rest of the step goes on with the new phase's tangent (k
 * elastic, 0 sliding). So each stretch has its right tangent stiffness and the kink costs the method no
 * order (beta = 1/4, gamma = 1/2 stays second order), where Höschl's hand computation keeps the tangent of
 * the step's start and corrects the force after it. With "none" the step keeps its starting tangent and the
 * events are reported at its end. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dashpot/newmark.h"
#include "base/root.h"
#include "network/newmark_step.h"
#include "record/sink.h"
#include "rules/rules.h"
#include "solvers/run_types.h"
#include "solvers/stick_slip_step.h"

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

/* The run's state: the stepper and its 1 x 1 band matrices. */
typedef struct newmark_run {
    dp_nm *w;
    double M, C, K;
} newmark_run;

static void newmark_free(void *state)
{
    newmark_run *nm = state;
    if (nm == NULL)
        return;
    dp_nm_free(nm->w);
    free(nm);
}

static int newmark_init(dp_run *r)
{
    dp_model *m = &r->spec.model;
    int ep = dp_spring_plastic(&m->spring);
    newmark_run *nm = r->state = calloc(1, sizeof *nm);
    if (nm == NULL)
        return DP_ENOMEM;
    dp_nm *w = nm->w = dp_nm_alloc(1, 0, ep ? 1 : 0);
    if (w == NULL)
        return DP_ENOMEM;
    static const long ground = -1, node = 0;
    nm->M = m->mass;
    nm->C = dp_damper_viscous(&m->damper);
    nm->K = ep ? 0 : m->spring.k;
    w->M = &nm->M, w->C = &nm->C, w->K = &nm->K;
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
    dp_run_emit_state(r); /* the initial state: queued, no block yet */
    return DP_OK;
}

/* The step to t from (x0, v0) left the finite numbers (or came within 1e300 of leaving them). */
static int diverged(dp_run *r, double t, double x0, double v0)
{
    char msg[DP_MESSAGE_MAX];
    snprintf(msg, sizeof msg, "the solution diverged at t = %.17g", t);
    return dp_one_mass_nonfinite(r, msg, r->cur.t, x0, v0);
}

/* ---- yield and unload located inside a step -------------------------------------------------------- */

/* Spring events one step may split at; past them the rest of the step keeps its tangent. */
#define NEWMARK_SPLITS_MAX 6

/* A stretch from (t, x, v), the acceleration and load at t in the stepper, to t_end with the spring held in
 * its phase; failed set if the stretch has no solution. */
typedef struct stretch { dp_run *r; dp_nm *w; double t, x, v, t_end, h; int failed; } stretch;

/* The stretch's end for length eta (the whole rest ends exactly at t_end) into (*x, *v). */
static int stretch_to(stretch *c, double eta, double *x, double *v)
{
    *x = c->x, *v = c->v;
    if (eta == 0)
        return DP_OK;
    double P = one_mass_load(c->r, eta == c->h ? c->t_end : c->t + eta);
    signed char flow = (signed char)c->r->ep_flow;
    return dp_nm_step(c->w, eta, &P, &flow, x, v);
}

static double stretch_margin(void *p, double eta)
{
    stretch *c = p;
    double x, v;
    if (stretch_to(c, eta, &x, &v) != DP_OK)
        c->failed = 1;
    return dp_plastic_margin(&c->r->spec.model.spring, c->r->ep_p, c->r->ep_flow, x, v);
}

/* One step from (r->cur.t, *x, *v) of length h to t_end, split at the spring's yield and unload, events
 * emitted; the return mapping done at the end (the caller renews the acceleration). DP_OK or DP_ESOLVE. */
static int located_step(dp_run *r, dp_nm *w, double h, double t_end, double *x, double *v)
{
    const dp_spring *sp = &r->spec.model.spring;
    stretch c = { .r = r, .w = w, .t = r->cur.t, .x = *x, .v = *v, .t_end = t_end, .h = h };
    for (int split = 0;; split++) {
        double x1, v1;
        if (stretch_to(&c, c.h, &x1, &v1) != DP_OK)
            return DP_ESOLVE;
        double g0 = dp_plastic_margin(sp, r->ep_p, r->ep_flow, c.x, c.v);
        double g1 = dp_plastic_margin(sp, r->ep_p, r->ep_flow, x1, v1);
        if (!(g1 > 0) || split == NEWMARK_SPLITS_MAX) {   /* the phase holds to the step's end */
            int flow;
            *x = x1, *v = v1;
            r->ep_F = dp_elastoplastic_return(sp, x1, &r->ep_p, &flow);
            if (split == NEWMARK_SPLITS_MAX && flow != r->ep_flow) {   /* too many: reported at the end */
                r->ep_flow = flow;
                dp_run_emit_event(r, flow ? DP_EVENT_YIELD : DP_EVENT_UNLOAD, t_end, x1, v1);
            }
            return DP_OK;
        }
        double eta = 0, tol = 4 * 2.220446049250313e-16 * (c.t + c.h);   /* a few ulps of the time */
        if (g0 < 0)
            eta = dp_root_bracket(stretch_margin, &c, 0, c.h, g0, g1, tol, &r->sum.iterations);
        if (c.failed || stretch_to(&c, eta, x, v) != DP_OK)
            return DP_ESOLVE;
        int flow;
        double t = eta == c.h ? t_end : c.t + eta;
        r->ep_F = dp_elastoplastic_return(sp, *x, &r->ep_p, &flow);
        dp_run_emit_event(r, dp_plastic_switch(sp, *x, &r->ep_p, &r->ep_F, &r->ep_flow), t, *x, *v);
        if (eta == c.h)
            return DP_OK;
        double P = one_mass_load(r, t);
        dp_nm_accel(w, x, v, &P, &r->ep_F);   /* the event's acceleration and load start the rest */
        c.t = t, c.x = *x, c.v = *v, c.h -= eta;
    }
}

static int newmark_advance(dp_run *r)
{
    dp_nm *w = ((newmark_run *)r->state)->w;
    const dp_spring *sp = &r->spec.model.spring;
    int located = r->ep && r->spec.solver.events == DP_EVENTS_LOCATE;
    while (dp_run_room(r)) {
        double h = dp_run_step_length(r), x = r->cur.x, v = r->cur.v, x0 = x, v0 = v;
        r->n++;
        double t = r->n < r->nsteps ? (double)r->n * r->h : r->spec.solver.t_end, P = one_mass_load(r, t);
        signed char flow = (signed char)r->ep_flow;
        int st = located ? located_step(r, w, h, t, &x, &v) : dp_nm_step(w, h, &P, &flow, &x, &v);
        if (st != DP_OK)
            return dp_run_fail(r, DP_ESOLVE, "the Newmark step at t = %.17g has no solution", r->cur.t);
        r->cur.t = t, r->cur.x = x, r->cur.v = v;
        if (r->ep && !located) {
            int before = r->ep_flow;
            r->ep_F = dp_elastoplastic_return(sp, x, &r->ep_p, &r->ep_flow);
            if (r->ep_flow != before)
                dp_run_emit_event(r, r->ep_flow ? DP_EVENT_YIELD : DP_EVENT_UNLOAD, t, x, v);
        }
        dp_nm_accel(w, &r->cur.x, &r->cur.v, &P, &r->ep_F);
        if (!(fabs(x) < 1e300 && fabs(v) < 1e300 && isfinite(w->a[0])))
            return diverged(r, t, x0, v0);
        r->sum.steps = r->n;
        if (r->n >= r->nsteps)
            r->finished = 1;
        if (dp_run_sample_due(r)) {
            one_mass_forces(r);
            if (!isfinite(r->cur.Fs) || !isfinite(r->cur.Fc) || !isfinite(r->cur.p))
                return diverged(r, t, x0, v0);
        }
        dp_run_emit_state(r);
    }
    return DP_OK;
}

/* Newmark's run locates an elastoplastic spring's yield and unload with events "locate"; otherwise (events
 * "none", or a linear spring, which has no events) the meta line says "step", as it always has. */
static const char *newmark_events_mode(const dp_spec *s)
{
    int located = dp_spring_plastic(&s->model.spring) && s->solver.events == DP_EVENTS_LOCATE;
    return located ? "locate" : "step";
}

const dp_run_type dp_run_newmark = {
    .name = "newmark", .events_mode = newmark_events_mode, .check = dp_rules_newmark, .init = newmark_init, .advance = newmark_advance,
    .free = newmark_free,
};
