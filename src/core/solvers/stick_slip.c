/* src/core/solvers/stick_slip.c - exact stick-slip time stepping: the theta-method (Moreau-Jean, as Siconos'
 * EulerMoreauOSI) for m x'' + c (x' - v_b) + k x + r - gamma = F(t), r in A(x' - v_b) (docs/mathematics.md §4).
 *
 * Each step is one scalar monotone inclusion in v+. For a linear spring, a damper whose law-table entry has
 * closed_form (a stick interval [-tau, tau] and a viscous c: Coulomb, Bingham, linear, generalized Coulomb)
 * and no relaxation it is the soft threshold
 *     u = v_free - v_b,  v+ = v_b + sgn(u) max(|u| - h tau / W, 0),  W = m + h theta c + h^2 theta^2 k,
 * (Moreau's catching-up scheme: exact sticking, no creep). Otherwise it goes to dp_inclusion_solve, which
 * handles any maximal monotone damper graph, monotone spring graph and relaxation. With events "locate"
 * the steps that hold a phase change are split there (event_location.c); long stretches of slip or stick
 * in the closed form run in the hot loops glide and hold.
 *
 * An elastoplastic spring (Jenkins: docs/systems.md §3) takes the general inclusion with its step graph at the
 * current plastic offset, weighted like a linear spring: (1-theta) F + theta F+, F+ = S(x + h (1-theta) v
 * + h theta v+) the return mapping at the position update's own x+; p moves after the step. With events
 * "locate" its steps are split at its yield and unload as at the damper's stick and slip (event_location.c);
 * with "none" the spring's phase changes are reported at the end of the step that made them.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rules/rules.h"
#include "solvers/run_types.h"
#include "solvers/stick_slip_step.h"

/* No finite bracket for the step: either the state has already run away (report divergence), or the
 * document's own scale overflows the step (report that), or the inclusion really has no solution at this
 * state. */
static int step_failed(dp_run *r, const step_state *s)
{
    char msg[DP_MESSAGE_MAX];
    int huge = !(fabs(s->x) < 1e100 && fabs(s->v) < 1e100);
    if (!huge && !(fabs(log10(fabs(dp_one_mass_extreme(&r->spec)))) >= DP_ONE_MASS_EXTREME_DECADES))
        return dp_run_fail(r, DP_ESOLVE, "the implicit step at t = %.17g has no solution", s->t);
    if (isfinite(s->x) && isfinite(s->v))
        snprintf(msg, sizeof msg, "the solution diverged at t = %.17g (|x| = %.3g, |v| = %.3g)", s->t, fabs(s->x),
                 fabs(s->v));
    else
        snprintf(msg, sizeof msg, "the solution diverged at t = %.17g", s->t);
    return dp_one_mass_nonfinite(r, msg, s->t, s->x, s->v);
}

/* A step from (t, x, v) that ended outside the finite numbers. */
static int step_nonfinite(dp_run *r, double t_end_of_step, double t, double x, double v)
{
    char msg[DP_MESSAGE_MAX];
    snprintf(msg, sizeof msg, "the solution diverged at t = %.17g", t_end_of_step);
    return dp_one_mass_nonfinite(r, msg, t, x, v);
}

/* ---- the run ---------------------------------------------------------------------------------------- */

static void set_forces(dp_run *r, double fc_graph, double fs_graph)
{
    const dp_ss_law *L = &r->law;
    dp_sample *c = &r->cur;
    c->Fs = r->ep ? r->ep_F : L->S ? fs_graph : L->k * c->x;
    c->plastic = r->ep, c->p = r->ep ? r->ep_p : 0;
    c->Fc = fc_graph + L->c * (c->v - L->vb);
    c->Fd = L->gamma->kind == DP_RELAX_NONE ? c->Fc : c->Fc - dp_relaxation_eval(L->gamma, c->v - L->vb);
}

/* Events "none": the elastoplastic spring's return mapping at the step's new position, its graph moved with
 * p, and a yield or unload event when its slider started or stopped sliding in the step. */
static void plastic_step(dp_run *r)
{
    dp_spring *sp = &r->spec.model.spring;
    int before = r->ep_flow;
    r->ep_F = dp_elastoplastic_return(sp, r->cur.x, &r->ep_p, &r->ep_flow);
    if (r->ep_flow)
        dp_elastoplastic_graph(sp, r->ep_p, r->law.theta, &sp->graph);
    if (r->ep_flow != before)
        dp_run_emit_event(r, r->ep_flow ? DP_EVENT_YIELD : DP_EVENT_UNLOAD, r->cur.t, r->cur.x, r->cur.v);
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
    if (r->n + DP_RUN_POLL_WORK < stop) /* back to the advance loop's stop poll now and then */
        stop = r->n + DP_RUN_POLL_WORK;
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
    double t = r->cur.t, x = r->cur.x, v = r->cur.v;
    if (r->cur.phase == DP_PHASE_SLIP && r->cur.v != L->vb)
        glide(r);
    else if (r->cur.phase == DP_PHASE_STICK && r->cur.v == L->vb)
        hold(r);
    else
        return DP_OK;
    if (!isfinite(r->cur.x) || !isfinite(r->cur.v))
        return step_nonfinite(r, r->cur.t, t, x, v);
    return DP_OK;
}

int dp_stick_slip_advance(dp_run *r)
{
    const dp_ss_law *L = &r->law;
    int located_plastic = r->ep && r->spec.solver.events == DP_EVENTS_LOCATE;
    while (dp_run_room(r)) {
        if (dp_run_stopped(r, dp_run_work(r)))
            return r->status;
        if (L->closed && fast_steps(r) != DP_OK)
            return r->status;
        double h = dp_run_step_length(r), fc = 0, fs = 0;
        step_state s = { r->cur.t, r->cur.x, r->cur.v, r->cur.phase };
        dp_phase before = s.phase;
        if (located_plastic) {
            double held = dp_ss_located_plastic_step(r, &s, h, &fc, &fs);
            if (held < 0)
                return step_failed(r, &s);
            r->sum.stick_time += held;
        } else if (L->closed && L->locate) {
            r->sum.stick_time += dp_ss_located_step(r, &s, h, &fc);
        } else if (L->locate) {
            double held = dp_ss_located_inclusion_step(r, &s, h, &fc, &fs, NULL);
            if (held < 0)
                return step_failed(r, &s);
            r->sum.stick_time += held;
        } else {
            if (L->closed)
                fc = dp_ss_moreau(L, &s, h);
            else if (dp_ss_inclusion_step(r, &s, h, &fc, &fs) != DP_OK)
                return step_failed(r, &s);
            if (s.phase == DP_PHASE_STICK)
                r->sum.stick_time += h;
        }
        r->n++;
        s.t = r->n < r->nsteps ? (double)r->n * r->h : r->spec.solver.t_end;
        if (!isfinite(s.x) || !isfinite(s.v) || !isfinite(fc) || !isfinite(fs))
            return step_nonfinite(r, s.t, r->cur.t, r->cur.x, r->cur.v);
        r->cur.t = s.t, r->cur.x = s.x, r->cur.v = s.v, r->cur.phase = s.phase;
        if (r->ep && !located_plastic)
            plastic_step(r);
        if (dp_run_sample_due(r)) { /* forces are only read in samples and the summary (the last step) */
            set_forces(r, fc, fs);
            if (!isfinite(r->cur.Fs) || !isfinite(r->cur.Fd) || !isfinite(r->cur.Fc) || !isfinite(r->cur.p))
                return step_nonfinite(r, s.t, s.t, s.x, s.v);
        }
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
    double Fs = r->ep ? r->ep_F : L->S ? slo : L->k * c->x;
    dp_graph_force(L->A, c->v - L->vb, &lo, &hi);
    double need = dp_forcing_eval(L->F, 0) - Fs, fc = fmin(fmax(need, lo), hi);
    c->phase = DP_PHASE_NONE;
    if (L->can_stick && c->v == L->vb) { /* held if the stick interval has the force; else it slips off */
        double rlo, rhi;
        dp_ss_stick_interval(L, &rlo, &rhi);
        int holds = rlo <= need && need <= rhi;
        c->phase = holds ? DP_PHASE_STICK : DP_PHASE_SLIP;
        /* slipping off: the bound it slips past (not the sign of the need: an interval need not hold 0) */
        fc = holds ? need : need > rhi ? hi : lo;
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
    const dp_spring_law_info *SL = dp_spring_law_info_of(m->spring.law);
    const dp_damper_law_info *DL = dp_damper_law_info_of(d->law);
    if (SL == NULL || DL == NULL)
        return DP_EINVAL;
    int linear_spring = SL->linear;
    double lo, hi;
    L->m = m->mass;
    L->k = dp_spring_stiffness(&m->spring);
    L->c = dp_damper_viscous(d);
    L->tau = dp_damper_kinetic(d);
    L->motion = r->spec.solver.branch == DP_BRANCH_MOTION;
    /* The motion branch leaves rest as soon as kinetic friction allows: the static threshold drops out. */
    L->tau_s = !L->motion ? dp_damper_static(d) : L->tau;
    L->vb = d->belt_velocity;
    L->theta = r->spec.solver.theta;
    L->A = &d->graph;
    L->kink_hint = r->kink_hint;
    L->S = linear_spring ? NULL : &m->spring.graph;
    L->gamma = &d->relaxation;
    L->F = &m->forcing;
    dp_graph_force(L->A, 0, &lo, &hi);
    /* A stick interval at rest: a static threshold (which may exceed the graph's, generalized Coulomb) or a
     * vertical piece of the graph at zero. */
    L->can_stick = L->tau_s > 0 || lo < hi;
    /* Only an entry that says so takes the closed form, which reads tau and c and never the graph. */
    L->closed = linear_spring && DL->closed_form && d->relaxation.kind == DP_RELAX_NONE;
    /* Only a stick interval makes the dynamics nonsmooth; smooth reversals need no splitting. */
    L->h = r->h;
    if (SL->plastic) {   /* its state at x0 and its step graph there */
        dp_spring *sp = &r->spec.model.spring;
        r->ep = 1, r->ep_p = sp->offset;
        r->ep_F = dp_elastoplastic_return(sp, r->spec.x0, &r->ep_p, &r->ep_flow);
        r->ep_flow = 0;
        dp_elastoplastic_graph(sp, r->ep_p, L->theta, &sp->graph);
    }
    L->F_const = m->forcing.kind == DP_FORCING_NONE || m->forcing.kind == DP_FORCING_CONSTANT;
    L->F0 = dp_forcing_eval(&m->forcing, 0);
    dp_ss_coef_init(L, L->h, &L->nominal);
    /* Events are located where the damper can stick; the motion branch leaves rest on its own terms. */
    L->locate = r->spec.solver.events == DP_EVENTS_LOCATE && (L->closed ? L->tau > 0 : L->can_stick && !L->motion)
                && SL->locate && DL->locate;
    initial_state(r);
    if (!isfinite(r->cur.Fs) || !isfinite(r->cur.Fd) || !isfinite(r->cur.Fc)) {
        snprintf(r->error_pointer, sizeof r->error_pointer, "/initial");
        return dp_run_fail(r, DP_ESOLVE, "the forces at the initial state overflow double precision (a graph's "
                           "piece or a law too steep for it there)");
    }
    dp_run_emit_state(r); /* the initial state: queued, no block yet */
    return DP_OK;
}

const char *dp_one_mass_events_mode(const dp_spec *s)
{
    const dp_spring_law_info *SL = dp_spring_law_info_of(s->model.spring.law);
    const dp_damper_law_info *DL = dp_damper_law_info_of(s->model.damper.law);
    int step = !(SL && SL->locate && DL && DL->locate);
    return s->solver.events == DP_EVENTS_NONE ? "none" : step ? "step" : "locate";
}

const dp_run_type dp_run_stick_slip = {
    .name = "stick-slip", .variant = "exact", .events_mode = dp_one_mass_events_mode,
    .check = dp_rules_stick_slip, .init = dp_stick_slip_init,
    .advance = dp_stick_slip_advance,
};
