/* src/core/solvers/network/network_events.c - located events on networks: a step whose exact solution changes some
 * element's assignment is split at the earliest instant where the step's starting assignment, held over a
 * shorter step, stops being consistent (a bracketed root of the candidates' smallest margin); the elements
 * that fail there switch (a stick, a release, or a reversal through the belt speed without a stick) and the
 * rest of the step goes on from that instant. So theta = 1/2 stays second order through stick-slip, as the
 * one-mass solver's event location keeps it. A contact that is not armed joins as one more margin, its gap,
 * and its impact is taken at the next sub-step's start (network_contact.c).
 *
 * A static threshold (generalized Coulomb, phi1 > phi0; Pražák & Rajagopal 2016 §4) is located the same way
 * with the graph its phase gives it: a sticking element is held on its static interval [-phi1, phi1], so its
 * margin is its force against phi1 and it breaks away onto the kinetic graph (+-phi0); a slipping one is on
 * its kinetic graph, its margin its relative velocity, and where that reaches zero it sticks if the static
 * interval holds it just after, else it reverses (the one-mass rest branch, stick_slip.c).
 *
 * An elastoplastic (Jenkins) spring (Höschl 1983 §15) is located as the one-mass solver locates it
 * (event_location.c): held elastic, its margin is F_y - |k(u+ - p)| at the held step's end (yield); held
 * sliding in direction d, it is d z+, the slider's rate (unload). At the root the state is taken there, the
 * return mapping puts the force on the yield surface (yield) or stops the slider (unload), the graph is
 * redrawn at the new offset and the assignment renewed by a billionth of a step, as after an impact. A
 * spring whose damper sticks is held exactly by the held step (its z is pinned), and its yield is reported
 * at the end of the sub-step. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "solvers/network/network_run.h"
#include "base/root.h"

/* The part of what is left of a step over which a slider's assignment is renewed once its graph moved: long
 * enough that a slider still sliding at a crawl moves its elongation past rounding there (a billionth, as
 * elsewhere, leaves one stopping a ten-thousandth of a step on on the wrong piece by rounding), short enough
 * that the phase it finds is the one the sub-step starts in. */
#define EP_PROBE 1e-6

typedef struct held_ctx {
    dp_run *r;
    double t;
    const unsigned char *cand;   /* the elements whose held assignment fails by the step's end */
} held_ctx;

/* Element k's damper graph: the static one (phi1) if `stick`, else the kinetic one; the step's factors are
 * renewed when it changes. */
static void static_graph(struct dp_network_run *nr, size_t k, int stick)
{
    const dp_graph *g = stick ? &nr->static_A[k] : &nr->net->el[nr->act_el[k]].damper.graph;
    if (nr->static_A[k].n == 0 || nr->act[k].A == g)
        return;
    nr->act[k].A = g;
    dp_network_step_W_changed(nr->ws);
}

/* The graphs of the assignment at a sub-step's start: static for the elements sticking there (`phase`). */
static void static_graphs(struct dp_network_run *nr, const unsigned char *phase)
{
    for (size_t k = 0; nr->has_static && k < nr->nact; k++)
        static_graph(nr, k, phase[nr->act_el[k]] == DP_PHASE_STICK);
}

/* Whether active element k is an elastoplastic spring (a graph spring of finite slope is theta-weighted too,
 * network_smooth.c, but its graph does not move). */
static int ep_entry(const struct dp_network_run *nr, size_t k)
{
    return k < nr->nact_el && nr->act[k].ep_theta > 0 && nr->ep_graph[nr->act_el[k]] != NULL;
}

/* Whether active element k is an elastoplastic spring free in the held assignment (its own margin applies). */
static int ep_free(const struct dp_network_run *nr, size_t k)
{
    return ep_entry(nr, k) && !dp_network_step_fixed(nr->ws, k);
}

/* An elastoplastic spring's margin at the end of a held step of length s (nr->u and nr->force from it),
 * in the phase the sub-step started in (ep_flow: 0 elastic, +-1 sliding that way): the elastic one
 * F_y - |k(u+ - p)| with u+ = u + s (1 - theta) z + s theta z+, the sliding one d z+. */
static double ep_margin(const struct dp_network_run *nr, size_t k, double s)
{
    size_t i = nr->act_el[k];
    const dp_spring *sp = &nr->net->el[i].spring;
    double z = nr->force[k].z;
    int d = nr->ep_flow[i];
    if (d != 0)
        return d * z;
    return sp->yield - fabs(sp->k * (nr->u[k] + s * nr->theta * z - nr->ep_p[i]));
}

/* The candidates' held margins on a chain, each from the blocks of nodes it needs (network_step.h): 1 with
 * their smallest in *m (NAN when the stop hook said stop), 0 when the whole step must be solved. */
static int held_margin_blocks(held_ctx *c, double s, double *m)
{
    struct dp_network_run *nr = c->r->state;
    if (nr->couple == NULL)   /* not a chain whose held solves the blocks hold (network_run.c) */
        return 0;
    size_t nb = dp_network_step_blocks(nr->ws, c->cand, nr->couple, nr->blk, nr->blk_cap / 2);
    if (nb == 0)
        return 0;
    for (size_t b = 0, off = 0; b < nb; b++) {
        size_t lo = nr->blk[2 * b], hi = nr->blk[2 * b + 1];
        network_run_block_rows(nr, c->t, s, lo, hi, nr->blk_W + 2 * (off + b), nr->blk_rhs + off);
        off += hi - lo + 1;
    }
    int done = dp_network_step_solve_blocks(nr->ws, s, nr->blk, nb, nr->blk_W, nr->blk_rhs, nr->u, c->cand,
                                            nr->margin);
    *m = done < 0 ? NAN : INFINITY;
    for (size_t k = 0; done > 0 && k < nr->nact; k++)
        if (c->cand[k])
            *m = fmin(*m, nr->margin[k]);
    return done != 0;
}

/* The smallest margin among the candidates after a step of length s with the sub-step's starting
 * assignment held (nr->margin gets every element's, or on a chain the candidates' alone). */
static double held_margin(void *vctx, double s)
{
    held_ctx *c = vctx;
    struct dp_network_run *nr = c->r->state;
    dp_network_step_pattern_restore(nr->ws, nr->pattern);
    double mb;
    if (c->cand != NULL && held_margin_blocks(c, s, &mb))
        return mb;
    network_run_step_rhs(nr, c->t, s);
    dp_network_step_relaxation_start(nr->ws, nr->v);
    if (dp_network_step_solve_frozen(nr->ws, s, nr->rhs, nr->u, nr->v1, nr->force, nr->margin) != DP_OK)
        return NAN;
    network_run_contacts_margins(nr, s);
    for (size_t k = 0; nr->has_ep && k < nr->nact_el; k++)
        if (ep_free(nr, k))
            nr->margin[k] = fmin(nr->margin[k], ep_margin(nr, k, s));
    double m = INFINITY;
    for (size_t k = 0; k < nr->nact; k++)
        if (c->cand == NULL || c->cand[k])
            m = fmin(m, nr->margin[k]);
    return m;
}

/* The root in (s0, s1] of the smallest margin among the candidates `cand`, the margins there in nr->margin. */
static double held_root(dp_run *r, double t, double s0, double s1, const unsigned char *cand)
{
    held_ctx c = { r, t, cand };
    double g0 = held_margin(&c, s0), g1 = held_margin(&c, s1);
    double at = dp_root_bracket(held_margin, &c, s0, s1, g0, g1, 1e-15 * s1, &r->sum.iterations);
    held_margin(&c, at);
    return at;
}

/* The earliest instant in (0, h] where the starting assignment stops being consistent, in `fails` the
 * elements that fail there (identical blocks fail together). A free element fails where its relative
 * velocity at the held step's end reaches a vertex: at t + s. A fixed one fails where its force leaves its
 * interval; a held step of length s measures the force at t + theta s (the theta-point), so its failure is
 * sought over s in (0, h / theta] and happens at t + theta s*, as the one-mass solver's holding test, which
 * reads the force at the instant itself. Returns h when nothing fails in the step, 0 when something fails at
 * once. */
static double earliest_event(dp_run *r, double t, double h, unsigned char *fails)
{
    struct dp_network_run *nr = r->state;
    size_t m = nr->nact;
    held_ctx c = { r, t, NULL };
    double th = nr->theta, s0 = 1e-9 * h, *start = nr->roots, *scale = nr->scale, *end = nr->end_margin;
    unsigned char *fixed = nr->fixed, *cand = nr->cand, *failing = nr->fails_at;
    memset(fails, 0, m ? m : 1);
    memset(failing, 0, m ? m : 1);
    int any_fixed = 0, any_free = 0, any = 0;
    dp_network_step_pattern_restore(nr->ws, nr->pattern);   /* the held assignment's fixed elements */
    for (size_t k = 0; k < m; k++)
        fixed[k] = (unsigned char)dp_network_step_fixed(nr->ws, k);
    for (int pass = 0; pass < 2; pass++) {   /* free elements over h, fixed ones over h / theta */
        double g = held_margin(&c, pass ? h / th : h);   /* once: each evaluation is a held solve */
        if (!(g == g))
            return h;
        for (size_t k = 0; k < m; k++)
            if (fixed[k] == pass && nr->margin[k] < 0)
                failing[k] = (unsigned char)(pass + 1), end[k] = nr->margin[k], any = 1;
    }
    /* just after the start the assignment holds, or fails at once: the failing ones' margins there (on a
     * chain from their blocks alone) */
    if (any) {
        c.cand = failing;
        held_margin(&c, s0);
        for (size_t k = 0; k < m; k++)
            start[k] = failing[k] ? nr->margin[k] : 0;
        c.cand = NULL;
    }
    for (int pass = 0; pass < 2; pass++) {
        for (size_t k = 0; k < m; k++) {
            if (failing[k] != pass + 1)
                continue;
            if (!(start[k] >= 0)) {
                fails[k] = 1;
                return 0;
            }
            cand[k] = (unsigned char)(pass + 1);
            scale[k] = fabs(start[k]) + fabs(end[k]);
            pass ? (any_fixed = 1) : (any_free = 1);
        }
    }
    double best = h;
    int found = 0;
    for (int pass = 0; pass < 2; pass++) {
        if (!(pass ? any_fixed : any_free))
            continue;
        for (size_t k = 0; k < m; k++)
            fails[k] = cand[k] == pass + 1;
        double s = held_root(r, t, s0, pass ? h / th : h, fails), at = pass ? th * s : s;
        if (found && at >= best)
            continue;
        /* the ones failing at this instant: the smallest margin whatever its last digits, and any other
         * within the root's tolerance of zero */
        size_t first = (size_t)-1;
        for (size_t k = 0; k < m; k++)
            if (fails[k] && (first == (size_t)-1 || nr->margin[k] < nr->margin[first]))
                first = k;
        for (size_t k = 0; k < m; k++)
            nr->fails_at[k] = fails[k] && (k == first || nr->margin[k] <= 1e-9 * scale[k]);
        best = at, found = 1;
    }
    for (size_t k = 0; k < m; k++)
        fails[k] = found ? nr->fails_at[k] : 0, cand[k] = 0;
    return best;
}

/* Element k's assignment failed at time t (the state is there, the held assignment in the workspace): a
 * fixed element is freed towards its force; a free one that reached a vertex is fixed there if the vertex's
 * interval holds it just after (a stick), else freed beyond it (a reversal through the belt speed, a kink:
 * no stick, as for one mass). Returns the element's phase after. */
static unsigned char switch_element(dp_run *r, double t, double left, size_t k)
{
    struct dp_network_run *nr = r->state;
    double s0 = 1e-9 * (left > 0 ? left : 1);
    if (dp_network_step_fixed(nr->ws, k)) {
        int dir = dp_network_step_violation(nr->ws, k, s0, nr->u);
        static_graph(nr, k, 0);    /* broken away: on to the kinetic graph */
        dp_network_step_slip(nr->ws, k, s0, nr->u, dir >= 0 ? 1 : -1);
    } else {
        dp_network_step_fix_end(nr->ws, k, nr->v);
        static_graph(nr, k, 1);    /* at rest the static interval holds it */
        if (!dp_network_step_at_rest(nr->ws, k))
            static_graph(nr, k, 0);
        dp_network_step_pattern_save(nr->ws, nr->pattern);
        unsigned char *only = calloc(nr->nact, 1);
        if (only == NULL)
            return nr->phase[nr->act_el[k]];
        only[k] = 1;
        double m = left > 0 ? held_margin(&(held_ctx){ r, t, only }, s0) : 0;
        free(only);
        if (m < 0) {
            int dir = dp_network_step_violation(nr->ws, k, s0, nr->u);
            static_graph(nr, k, 0);
            dp_network_step_slip(nr->ws, k, s0, nr->u, dir >= 0 ? 1 : -1);
        }
    }
    if (!nr->can_stick[nr->act_el[k]])
        return DP_PHASE_NONE;
    return dp_network_step_at_rest(nr->ws, k) ? DP_PHASE_STICK : DP_PHASE_SLIP;
}

/* Whether a fixed element's force leaves its interval inside a step that the exact solution keeps it
 * fixed over: the step's multiplier is the force at its theta-point, so below theta = 1 the held step is
 * looked at up to h / theta to see the force at the step's end. (One held solve per step with something
 * fixed; the assignment is left as it was.) */
static int breaks_away(dp_run *r, double t, double h)
{
    struct dp_network_run *nr = r->state;
    if (nr->theta == 1)
        return 0;
    int any = 0;
    dp_network_step_pattern_restore(nr->ws, nr->pattern);
    for (size_t k = 0; k < nr->nact && !any; k++)
        any = dp_network_step_fixed(nr->ws, k);
    if (!any)
        return 0;
    static_graphs(nr, nr->phase_prev);
    held_margin(&(held_ctx){ r, t, NULL }, h / nr->theta);
    for (size_t k = 0; k < nr->nact; k++)
        if (dp_network_step_fixed(nr->ws, k) && nr->margin[k] < 0)
            return 1;
    return 0;
}

/* The elastoplastic springs whose own margin fails at the located instant at (the held state there, before
 * it is taken): nr->cand[k] 1 for a yield (it was elastic), 2 for an unload (it was sliding). */
static size_t ep_events_at(struct dp_network_run *nr, double at)
{
    size_t n = 0;
    for (size_t k = 0; nr->has_ep && k < nr->nact_el; k++) {
        if (!nr->fails[k] || !ep_free(nr, k))
            continue;
        double m = ep_margin(nr, k, at);
        if (!(m <= nr->margin[k] || m <= 1e-9 * nr->scale[k]))
            continue;      /* its damper's event, not the spring's */
        nr->cand[k] = nr->ep_flow[nr->act_el[k]] ? 2 : 1;
        n++;
    }
    return n;
}

/* The yields and unloads of ep_events_at, the state taken to their instant (the return mapping done): a
 * yield's force exactly on the yield surface, its offset and graph there; an unload's slider stopped. */
static void ep_switch(struct dp_network_run *nr)
{
    for (size_t k = 0; nr->has_ep && k < nr->nact_el; k++) {
        if (!nr->cand[k])
            continue;
        size_t i = nr->act_el[k];
        const dp_element *e = &nr->net->el[i];
        if (nr->cand[k] == 1) {
            double u = network_run_rel(e->a, e->b, nr->x);
            int d = nr->ep_flow[i] ? nr->ep_flow[i] : u >= nr->ep_p[i] ? 1 : -1;
            nr->ep_flow[i] = (signed char)d;
            nr->ep_F[i] = d * e->spring.yield;
            nr->ep_p[i] = u - d * e->spring.yield / e->spring.k;
            dp_elastoplastic_graph(&e->spring, nr->ep_p[i], 1, nr->ep_graph[i]);
        } else {
            nr->ep_flow[i] = 0;
        }
        nr->cand[k] = 0;
    }
}

/* Whether a step's solution turns a sliding slider back (its end rate against its flow): its piece may be
 * the same at both ends, the slider stopped inside the step all the same. */
static int ep_turns(const struct dp_network_run *nr)
{
    for (size_t k = 0; nr->has_ep && k < nr->nact_el; k++)
        if (ep_entry(nr, k) && nr->ep_flow[nr->act_el[k]] * nr->force[k].z < 0)
            return 1;
    return 0;
}

/* Whether a slider slid in the last (sub-)step: its graph was redrawn at the new offset, and the assignment
 * the workspace keeps names the old graph's vertex. */
static int ep_redrawn(const struct dp_network_run *nr)
{
    for (size_t k = 0; nr->has_ep && k < nr->nact_el; k++)
        if (ep_entry(nr, k) && nr->ep_flow[nr->act_el[k]] != 0)
            return 1;
    return 0;
}

/* Whether the network has contacts and something other than a closing contact fails at the start of the
 * held step (nr->fails): an element's assignment or a resting contact's release. */
static int switches_at_once(const struct dp_network_run *nr)
{
    for (size_t j = 0; nr->nc && j < nr->nact; j++)
        if (nr->fails[j] && (j < nr->nact_el || nr->ct_on[j - nr->nact_el]))
            return 1;
    return 0;
}

/* The rest of a step taken whole from t (no instant to split it at): contacts the solution carries through
 * their stops are armed and it is solved again; after too many impacts in the step (chatter) every contact
 * is armed by Moreau-Jean's rule instead. */
static int finish_step(dp_run *r, double t, double left)
{
    struct dp_network_run *nr = r->state;
    dp_network_step_pattern_restore(nr->ws, nr->pattern);
    if (network_run_contacts_chattering(nr))
        network_run_contacts_arm_mj(nr, left);
    int s = network_run_net_step_keep(r, t, left);
    if (s == DP_OK && network_run_contacts_arm_closing(nr, left))
        s = network_run_net_step_keep(r, t, left);
    if (s != DP_OK)
        return s;
    network_run_take_velocity(nr, left);
    network_run_element_forces(nr, 1);
    network_run_step_events(r, nr->phase_prev, t + left);
    network_run_plastic_events(r, t + left);
    network_run_stick_time(r, nr->phase, left);
    if (nr->nc)
        network_run_contacts_mj_events(r, t, left);
    return DP_OK;
}

/* Contacts at a sub-step's start t: impacts there; after a velocity jump the assignment is renewed by a
 * billionth of a step (as at the run's start) and the phase changes it made are events at t. */
static int contacts_at(dp_run *r, double t, double left)
{
    struct dp_network_run *nr = r->state;
    int jumped = network_run_contacts_instant(r, t, r->h);
    if (jumped < 0)
        return -jumped;
    if (jumped == 0)
        return DP_OK;
    int s = network_run_net_step_keep(r, t, 1e-9 * left);
    if (s != DP_OK)
        return s;
    network_run_element_forces(nr, 1);
    network_run_step_events(r, nr->phase_prev, t);
    memcpy(nr->phase_prev, nr->phase, nr->nel);
    return DP_OK;
}

/* A step split at its phase changes: while the exact step over what is left changes some element's phase,
 * the starting assignment is held up to the earliest instant where it fails, the step is taken to there,
 * the element switches (stick at its belt speed, or slip towards its force) and its event is emitted at
 * that instant; so theta = 1/2 stays second order through stick-slip, as for one mass. Contacts: impacts
 * at each sub-step's start (contacts_at), a closing gap is one more margin to split at. */
int network_run_located_step(dp_run *r, double t, double h)
{
    struct dp_network_run *nr = r->state;
    double left = h;
    for (size_t sub = 0; left > 0; sub++) {
        memcpy(nr->phase_prev, nr->phase, nr->nel);
        if (nr->nc && network_run_contacts_chattering(nr)) {
            dp_network_step_pattern_save(nr->ws, nr->pattern);
            return finish_step(r, t, left);
        }
        int s = nr->nc ? contacts_at(r, t, left) : DP_OK;
        if (s != DP_OK)
            return s;
        /* a moved graph: the assignment renewed on it by a billionth of the step, as at the run's start */
        if (ep_redrawn(nr) && (s = network_run_net_step_keep(r, t, EP_PROBE * left)) != DP_OK)
            return s;
        dp_network_step_pattern_save(nr->ws, nr->pattern);
        if ((s = network_run_net_step_keep(r, t, left)) != DP_OK)
            return s;
        network_run_element_forces(nr, 1);
        int same = dp_network_step_pattern_same(nr->ws, nr->pattern) && !network_run_contacts_penetrate(nr, left) &&
                   !ep_turns(nr);
        if (same && nr->theta < 1) {      /* keep the step's solution while the held step looks further */
            memcpy(nr->v1_keep, nr->v1, nr->n * sizeof *nr->v1);
            memcpy(nr->force_keep, nr->force, nr->nact * sizeof *nr->force);
            same = !breaks_away(r, t, left);
            if (network_run_cancelled(r))
                return DP_ECANCEL;
            memcpy(nr->v1, nr->v1_keep, nr->n * sizeof *nr->v1);
            memcpy(nr->force, nr->force_keep, nr->nact * sizeof *nr->force);
        }
        if (same) {
            network_run_take_velocity(nr, left);
            network_run_element_forces(nr, 1);
            network_run_step_events(r, nr->phase_prev, t + left);
            network_run_plastic_events(r, t + left);
            network_run_stick_time(r, nr->phase, left);
            return DP_OK;
        }
        /* impacts add sub-steps of their own (accumulating ones end plastic: network_contact.c) */
        if (sub > 2 * nr->nact + 4 + 2 * nr->impacts_step)
            return finish_step(r, t, left);
        static_graphs(nr, nr->phase_prev);   /* the held assignment's graphs: its phases at t */
        double at = earliest_event(r, t, left, nr->fails);
        if (network_run_cancelled(r))
            return DP_ECANCEL;   /* the stop hook, polled inside the held solves */
        if (at >= left)
            return finish_step(r, t, left);  /* no change the held assignment sees */
        if (!(at > 1e-9 * left)) {
            /* a change at the very start: the whole step is exact for elements, but it would carry contacts
             * through their stops, so with contacts an element or a resting contact switches a billionth of
             * the step on */
            if (!switches_at_once(nr))
                return finish_step(r, t, left);
            at = 1e-9 * left;
        }
        /* a static threshold's event at the step's end to rounding: no sliver of a sub-step after it (a
         * breakaway there would stick again in the sliver's rounding; elsewhere a sliver is harmless) */
        if (nr->has_static && left - at <= 1e-12 * left)
            at = left;
        held_margin(&(held_ctx){ r, t, NULL }, at);  /* the state at the event, assignment held */
        size_t ep_events = ep_events_at(nr, at), kinks = network_run_smooth_kinks_at(nr, at);
        network_run_take_velocity(nr, at);
        ep_switch(nr);
        network_run_element_forces(nr, 1);
        /* every element whose assignment fails at this instant (to the root's tolerance) switches here:
         * identical blocks stick together */
        for (size_t j = 0; j < nr->nact; j++) {
            if (!nr->fails[j] || (ep_entry(nr, j) && ep_events) || network_run_smooth_kink(nr, j))
                continue;      /* with a yield, unload or a spring's vertex the renewal below finds its piece */
            if (j < nr->nact_el && nr->jump && nr->jump[j])
                switch_element(r, t + at, left - at, j);   /* a graph's jump: its element's phase is its damper's */
            else if (j < nr->nact_el)
                nr->phase[nr->act_el[j]] = switch_element(r, t + at, left - at, j);
            else if (nr->ct_on[j - nr->nact_el])
                switch_element(r, t + at, left - at, j);    /* a resting contact let go */
            /* a closing contact takes its impact at the next sub-step's start */
        }
        if (network_run_cancelled(r))
            return DP_ECANCEL;
        /* after a yield or unload (the graph moved) or at a spring's vertex (the next piece) the assignment is
         * renewed over a sliver of what is left */
        int renew = (ep_events || kinks) && left - at > 0;
        if (renew && (s = network_run_net_step_keep(r, t + at, EP_PROBE * (left - at))) != DP_OK)
            return s;
        if (renew)
            network_run_element_forces(nr, 1);
        network_run_stick_time(r, nr->phase_prev, at);
        network_run_step_events(r, nr->phase_prev, t + at);
        network_run_plastic_events(r, t + at);
        t += at, left -= at;
    }
    return DP_OK;
}

