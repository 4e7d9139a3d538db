/* src/core/analytic.c - closed-form Coulomb oscillator (seed 000 (4.14)-(4.15)) and the `analytic` solver.
 *
 * In the plane (y, w) = (x - xc, v/omega) an arc is a clockwise rotation at rate omega = sqrt(k/m) about
 * the arc's centre, so the time to the next turning point is an angle divided by omega: no root finding,
 * and turning points and rest positions come out to rounding (|x_{j+1} - xc| = |x_j - xc| by symmetry).
 */
#include <math.h>

#include "dashpot/analytic.h"
#include "record/run_internal.h"

dp_coulomb_arc dp_coulomb_arc_from(const dp_coulomb_problem *p, double t0, double x0, double v0)
{
    dp_coulomb_arc a = { .t0 = t0, .x0 = x0, .v0 = v0, .t1 = INFINITY, .x1 = x0 };
    double need = p->F0 - p->k * x0;
    if (v0 == 0 && fabs(need) <= p->phi0) {
        a.xc = x0; /* rest: dir 0 */
        return a;
    }
    a.dir = v0 != 0 ? (v0 > 0 ? 1 : -1) : (need > 0 ? 1 : -1);
    a.xc = (p->F0 - a.dir * p->phi0) / p->k;
    if (p->phi0 == 0)
        return a; /* undamped: one endless harmonic arc */
    double om = sqrt(p->k / p->m);
    double y = x0 - a.xc, w = v0 != 0 ? v0 / om : copysign(0.0, a.dir);
    double ang = atan2(w, y); /* in (0, pi] moving right, [-pi, 0) moving left */
    a.t1 = t0 + (a.dir > 0 ? ang : ang + M_PI) / om;
    a.x1 = a.xc + a.dir * hypot(y, w);
    return a;
}

void dp_coulomb_arc_eval(const dp_coulomb_problem *p, const dp_coulomb_arc *a, double t, double *x, double *v)
{
    if (a->dir == 0) {
        *x = a->x0, *v = 0;
        return;
    }
    double om = sqrt(p->k / p->m), s = om * (t - a->t0);
    double y = a->x0 - a->xc, w = a->v0 / om, c = cos(s), sn = sin(s);
    *x = a->xc + y * c + w * sn;
    *v = om * (w * c - y * sn);
}

int dp_coulomb_arcs(const dp_coulomb_problem *p, double t_end, dp_coulomb_arc *arcs, size_t cap, size_t *n)
{
    *n = 0;
    dp_coulomb_arc a = dp_coulomb_arc_from(p, 0, p->x0, p->v0);
    for (;;) {
        if (*n == cap)
            return -1;
        arcs[(*n)++] = a;
        if (a.dir == 0 || !(a.t1 < t_end))
            return 0;
        a = dp_coulomb_arc_from(p, a.t1, a.x1, 0);
    }
}

/* ---- the solver --------------------------------------------------------------------------------------- */

static dp_coulomb_problem problem_of(const dp_run *r)
{
    const dp_model *m = &r->spec.model;
    dp_coulomb_problem p = { .m = m->mass, .k = m->spring.k, .F0 = r->an_F0, .x0 = r->spec.x0, .v0 = r->spec.v0 };
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

int dp_analytic_init(dp_run *r)
{
    dp_forcing_is_constant(&r->spec.model.forcing, &r->an_F0);
    dp_coulomb_problem p = problem_of(r);
    r->law.tau = p.phi0; /* kept for reports */
    dp_coulomb_arc a = dp_coulomb_arc_from(&p, 0, p.x0, p.v0);
    sample_on(&p, &a, 0, &r->cur);
    r->an_arc = a;
    return DP_OK;
}

int dp_analytic_advance(dp_run *r)
{
    dp_coulomb_problem p = problem_of(r);
    while (dp_run_room(r)) {
        if (dp_run_stopped(r, dp_run_work(r)))
            return r->status;
        r->n++;
        double t = r->n < r->nsteps ? (double)r->n * r->h : r->spec.solver.t_end;
        while (r->an_arc.dir != 0 && r->an_arc.t1 <= t) { /* pass the turning points up to t */
            dp_coulomb_arc next = dp_coulomb_arc_from(&p, r->an_arc.t1, r->an_arc.x1, 0);
            r->sum.iterations++;
            if (next.dir == 0 && p.phi0 > 0)
                dp_run_emit_event(r, DP_EVENT_STICK, next.t0, next.x0, 0);
            r->an_arc = next;
        }
        if (r->an_arc.dir == 0)
            r->sum.stick_time += t - fmax(r->cur.t, r->an_arc.t0);
        sample_on(&p, &r->an_arc, t, &r->cur);
        r->sum.steps = r->n;
        if (r->n >= r->nsteps)
            r->finished = 1;
        dp_run_emit_state(r);
    }
    return DP_OK;
}
