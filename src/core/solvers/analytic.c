/* src/core/solvers/analytic.c - the `analytic` solver: samples of the closed-form Coulomb oscillator
 * (Babováková 2012, (4.14)-(4.15); analysis/coulomb_closed_form.c) on the output grid, turning points passed
 * one by one and stick events where the motion comes to rest. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dashpot/analytic.h"
#include "record/sink.h"
#include "rules/rules.h"
#include "solvers/run_types.h"
#include "solvers/stick_slip_step.h"

/* The run's state: the constant load and the arc the motion is on. */
typedef struct analytic_run {
    double F0;
    dp_coulomb_arc arc;
} analytic_run;

static void analytic_free(void *state)
{
    free(state);
}

static dp_coulomb_problem problem_of(const dp_run *r)
{
    const dp_model *m = &r->spec.model;
    dp_coulomb_problem p = { .m = m->mass, .k = m->spring.k, .F0 = ((const analytic_run *)r->state)->F0, .x0 = r->spec.x0, .v0 = r->spec.v0 };
    p.phi0 = dp_damper_kinetic(&m->damper);   /* a coulomb damper's phi0, or none (check_analytic) */
    return p;
}

/* The sample at time t on arc a. */
static void sample_on(const dp_coulomb_problem *p, const dp_coulomb_arc *a, double t, dp_sample *s)
{
    s->t = t;
    dp_coulomb_arc_eval(p, a, t, &s->x, &s->v);
    s->Fs = p->k * s->x;
    s->Fc = a->dir != 0 ? a->dir * p->phi0 : p->F0 - s->Fs;
    s->Fd = s->Fc;
    s->phase = p->phi0 == 0 ? DP_PHASE_NONE : a->dir == 0 ? DP_PHASE_STICK : DP_PHASE_SLIP;
}

static int sample_finite(const dp_sample *s)
{
    return isfinite(s->x) && isfinite(s->v) && isfinite(s->Fs) && isfinite(s->Fd) && isfinite(s->Fc);
}

static int analytic_init(dp_run *r)
{
    analytic_run *an = r->state = calloc(1, sizeof *an);
    if (an == NULL)
        return DP_ENOMEM;
    dp_forcing_is_constant(&r->spec.model.forcing, &an->F0);
    dp_coulomb_problem p = problem_of(r);
    r->law.tau = p.phi0; /* kept for reports */
    dp_coulomb_arc a = dp_coulomb_arc_from(&p, 0, p.x0, p.v0);
    sample_on(&p, &a, 0, &r->cur);
    an->arc = a;
    if (!sample_finite(&r->cur)) {
        snprintf(r->error_pointer, sizeof r->error_pointer, "/model");
        return dp_run_fail(r, DP_ESOLVE, "the closed form's arc at the initial state overflows double precision: "
                           "the model's numbers are too large or too small for it");
    }
    dp_run_emit_state(r); /* the initial state: queued, no block yet */
    return DP_OK;
}

static int analytic_advance(dp_run *r)
{
    analytic_run *an = r->state;
    dp_coulomb_problem p = problem_of(r);
    while (dp_run_room(r)) {
        if (dp_run_stopped(r, dp_run_work(r)))
            return r->status;
        r->n++;
        double t = r->n < r->nsteps ? (double)r->n * r->h : r->spec.solver.t_end;
        while (an->arc.dir != 0 && an->arc.t1 <= t) { /* pass the turning points up to t */
            dp_coulomb_arc next = dp_coulomb_arc_from(&p, an->arc.t1, an->arc.x1, 0);
            r->sum.iterations++;
            if (next.dir == 0 && p.phi0 > 0)
                dp_run_emit_event(r, DP_EVENT_STICK, next.t0, next.x0, 0);
            an->arc = next;
        }
        if (an->arc.dir == 0)
            r->sum.stick_time += t - fmax(r->cur.t, an->arc.t0);
        double x = r->cur.x, v = r->cur.v;
        sample_on(&p, &an->arc, t, &r->cur);
        if (!sample_finite(&r->cur)) {
            char msg[DP_MESSAGE_MAX];
            snprintf(msg, sizeof msg, "the solution diverged at t = %.17g", t);
            return dp_one_mass_nonfinite(r, msg, t, x, v);
        }
        r->sum.steps = r->n;
        if (r->n >= r->nsteps)
            r->finished = 1;
        dp_run_emit_state(r);
    }
    return DP_OK;
}

const dp_run_type dp_run_analytic = {
    .name = "analytic", .variant = "closed-form", .events_mode = dp_one_mass_events_mode,
    .check = dp_rules_analytic, .init = analytic_init, .advance = analytic_advance,
    .free = analytic_free,
};
