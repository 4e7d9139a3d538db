/* src/core/solvers/right_hand_run.c - right-hand solutions (Matrosov & Finogenko 1995, §3: D+q = q', D+q' = G(t, q, q')) of the
 * friction models of right_hand.h, as a dp_run of rows.
 *
 * A smooth phase keeps every coordinate's mode (stick, slip +/-, free) and is integrated by GSL odeiv2
 * rk8pd with the acceleration problem of that mode solved at every evaluation. A phase ends at a located
 * event: a sliding velocity reaching zero, a stuck coordinate's force leaving its cone, the mode's problem
 * losing its unique solution, the rod's N turning negative. Each is found by bisection on the length of one
 * step from the step's start (the step is the one the error control accepted, so its local error holds).
 * At the event the full enumeration (dp_right_hand_solve) picks the next mode: accelerations may jump there. When
 * it finds no solution or several, the run stops with the time, state and candidates in its error:
 * Painlevé's inconsistency or indeterminacy, never guessed.
 *
 * The rod leaves the floor when the enumeration's only motion is the free flight (lift-off): it flies in
 * closed form (right_hand/rod_flight.c) until an end lands, located by safe advances on the end's height;
 * the impact there (Stronge's energetic restitution with Coulomb friction) ends in a bounce (flight again)
 * or with the end on the floor, where the enumeration picks stick, slip or lift-off as at any event.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include <gsl/gsl_odeiv2.h>

#include "dashpot/right_hand.h"
#include "record/row_queue.h"
#include "record/sink.h"
#include "rules/rules.h"
#include "solvers/run_types.h"

#define MAX_WIDTH 16
#define QCAP0 64
/* Bisection on a step's length stops at this relative width of the time (root-finding to rounding). */
#define LOCATE_REL 1e-13
/* Steps this short (relative to the time) may fall back on a Taylor step when rk8pd's stages fail. */
#define TAYLOR_MAX 1e-7
/* evolve_apply halves a step whose stages fail until one passes: a step below this (relative) that does not
 * reach its target means the phase ends just ahead, and the boundary is located. */
#define COLLAPSE 1e-12
/* A run locating more events than this is taken for an accumulation of events (Zeno): it stops. */
#define MAX_EVENTS 100000
/* Integrator steps one dp_run_next call may take before it hands control back (as the other solvers do, so
 * that a front end's deadline and cancellation are checked between calls): the segment resumes next call. */
#define CALL_STEPS 100000
/* A rebound whose accumulation of further bounces (2 v/(a (1 - e)) for the end's fall acceleration a, exact for
 * a point under constant a) would end within this fraction of dt, or whose height v^2/(2a) is below this
 * fraction of the rod's length (the heights' rounding is ~1e-16 of it: a landing there is located by
 * rounding noise), is made plastic: the bounces left are below what location resolves (Zeno), as for the
 * contacts of a network (docs/contact.md). */
#define ZENO_REL 1e-9
#define HOP_REL 1e-12

struct dp_right_hand_run {
    dp_right_hand_model m;
    double t, y[4];                 /* q0, q1, q0', q1' */
    double ya[2];                   /* the rod: the end A's height and its rate (0, 0 on the floor) */
    int flight;                     /* the rod is off the floor, moving as fl says */
    dp_right_hand_flight fl;
    dp_right_hand_mode mode[2];
    dp_right_hand_sol sol;                  /* the mode's solution at (t, y): the right-hand derivative */
    gsl_odeiv2_system sys;
    gsl_odeiv2_step *st;
    gsl_odeiv2_control *ctl;
    gsl_odeiv2_evolve *ev;
    double h, h0;
    unsigned long long k;           /* samples emitted; the next is at k dt */
    dp_columns cols;
    size_t nN, nmargin;
    dp_row_queue queue;             /* records not yet handed out (an event and a row may fall due together) */
    dp_row_slots slots;             /* row slots of the block being produced */
    double final_row[MAX_WIDTH];
    int ended;                      /* no more records will be produced */
    int fail;                       /* stop with `why` once the FIFO is drained */
    char why[256];
    unsigned long events;
    unsigned long call_steps;       /* integrator steps in the current dp_run_next call */
};

static int rhs(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    struct dp_right_hand_run *rr = params;
    dp_right_hand_result res;
    dp_right_hand_solve(&rr->m, y, y + 2, rr->mode, &res);
    if (res.n != 1 || res.continuum || !isfinite(res.sol[0].qdd[0]) || !isfinite(res.sol[0].qdd[1]))
        return GSL_EDOM; /* the mode's acceleration problem has no unique solution here */
    dydt[0] = y[2], dydt[1] = y[3];
    dydt[2] = res.sol[0].qdd[0], dydt[3] = res.sol[0].qdd[1];
    return GSL_SUCCESS;
}

/* Whether the state y lies inside the current phase: its mode solvable uniquely, sliding velocities on
 * their side, stick forces within their cones, the rod on the floor. */
static int in_phase(struct dp_right_hand_run *rr, const double y[4], dp_right_hand_sol *out)
{
    dp_right_hand_result res;
    dp_right_hand_solve(&rr->m, y, y + 2, rr->mode, &res);
    if (res.n != 1 || res.continuum)
        return 0;
    const dp_right_hand_sol *s = &res.sol[0];
    if (out)
        *out = *s;
    dp_right_hand_frame fr;
    dp_right_hand_frame_at(&rr->m, y, y + 2, &fr);
    double tol = dp_right_hand_force_tol(&fr);
    for (int k = 0; k < 2; k++) {
        if (rr->mode[k] == DP_RIGHT_HAND_SLIP_POS && y[2 + k] < 0)
            return 0;
        if (rr->mode[k] == DP_RIGHT_HAND_SLIP_NEG && y[2 + k] > 0)
            return 0;
        if (rr->mode[k] == DP_RIGHT_HAND_STICK && fabs(s->Q[k]) > fr.f[k] * fabs(s->N[k]) + tol)
            return 0;
    }
    /* the rod's floor: the same tolerance as the acceptance of a contact solution (right_hand.c) */
    return !(rr->m.kind == DP_RIGHT_HAND_ROD && (s->N[0] < -tol || !(y[1] > 0 && y[1] < M_PI)));
}

/* Coordinates stuck in the current mode (the summary's stick time counts each). */
static int stuck(const struct dp_right_hand_run *rr)
{
    return (rr->mode[0] == DP_RIGHT_HAND_STICK) + (rr->mode[1] == DP_RIGHT_HAND_STICK);
}

/* The second-order Taylor step y0 + h y0' + h^2/2 y0'' with y0'' of the current mode at y0 (0: none). */
static int taylor(struct dp_right_hand_run *rr, const double y0[4], double h, double y[4])
{
    dp_right_hand_sol s;
    if (!in_phase(rr, y0, &s))
        return 0;
    for (int k = 0; k < 2; k++) {
        y[k] = y0[k] + h * y0[2 + k] + 0.5 * h * h * s.qdd[k];
        y[2 + k] = y0[2 + k] + h * s.qdd[k];
    }
    return 1;
}

/* One rk8pd step of length h from (t0, y0) into y: 1 inside the phase, 0 outside, -1 the step failed. A
 * step shorter than TAYLOR_MAX whose inner stages leave the phase (its problem has no unique solution there)
 * is taken by the Taylor step instead, so that a phase boundary is located at the state where it lies rather
 * than at the stages that cross it (error O(h^3) ~ 1e-21 there). */
static int step_to(struct dp_right_hand_run *rr, double t0, const double y0[4], double h, double y[4])
{
    double yerr[4];
    memcpy(y, y0, 4 * sizeof *y);
    gsl_odeiv2_step_reset(rr->st);
    int ok = gsl_odeiv2_step_apply(rr->st, t0, h, y, yerr, NULL, NULL, &rr->sys) == GSL_SUCCESS;
    for (int i = 0; i < 4 && ok; i++)
        ok = isfinite(y[i]);
    if (!ok && !(h <= TAYLOR_MAX * fmax(1, fabs(t0)) && taylor(rr, y0, h, y)))
        return -1;
    return in_phase(rr, y, NULL);
}

/* The phase ends in (t0, t0 + hi] (a step of hi leaves it): bisection to LOCATE_REL, then t and y just
 * past the end (or just before it when the step past it cannot be taken). */
static void locate(struct dp_right_hand_run *rr, double t0, const double y0[4], double hi)
{
    double lo = 0, y[4];
    while (hi - lo > LOCATE_REL * fmax(1, fabs(t0) + hi)) {
        double mid = 0.5 * (lo + hi);
        if (step_to(rr, t0, y0, mid, y) == 1)
            lo = mid;
        else
            hi = mid;
    }
    if (step_to(rr, t0, y0, hi, y) < 0 && step_to(rr, t0, y0, lo, y) < 0)
        memcpy(y, y0, sizeof y);
    rr->t = t0 + hi;
    memcpy(rr->y, y, sizeof y);
    for (int k = 0; k < 2; k++) /* a sliding velocity that reached zero is zero: the coordinate rests */
        if ((rr->mode[k] == DP_RIGHT_HAND_SLIP_POS && rr->y[2 + k] <= 0) ||
            (rr->mode[k] == DP_RIGHT_HAND_SLIP_NEG && rr->y[2 + k] >= 0))
            rr->y[2 + k] = 0;
}

static double phase_code(dp_right_hand_mode m)
{
    return m == DP_RIGHT_HAND_STICK ? DP_PHASE_STICK : m == DP_RIGHT_HAND_FREE ? DP_PHASE_NONE : DP_PHASE_SLIP;
}

/* q, q', q'', N, mode, margins of the current state into row. */
static void fill_row(const struct dp_right_hand_run *rr, double *row)
{
    dp_right_hand_conditions c;
    dp_right_hand_conditions_at(&rr->m, rr->y, rr->y + 2, &rr->sol, &c);
    size_t i = 0;
    for (int k = 0; k < 2; k++)
        row[i++] = rr->y[k];
    for (int k = 0; k < 2; k++)
        row[i++] = rr->y[2 + k];
    for (int k = 0; k < 2; k++)
        row[i++] = rr->sol.qdd[k];
    for (size_t k = 0; k < rr->nN; k++)
        row[i++] = rr->sol.N[k];
    for (int k = 0; k < 2; k++)
        row[i++] = phase_code(rr->mode[k]);
    row[i++] = c.c12, row[i++] = c.c23;
    if (rr->m.kind == DP_RIGHT_HAND_PISTON_HINGE)
        row[i++] = c.c62, row[i++] = c.c64;
    else
        row[i++] = rr->ya[0], row[i++] = rr->ya[1];
}

static int all_finite(const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

/* The stop record of a state or a candidate outside the finite numbers: an overflow of the model's own
 * scale (its numbers' products leave double precision), said so, never as physics and never with a NaN. */
static void overflow(struct dp_right_hand_run *rr, const char *what)
{
    int n = snprintf(rr->why, sizeof rr->why, "the %s overflows double precision at t=%.10g", what, rr->t);
    if (all_finite(rr->y, 4) && n > 0 && (size_t)n < sizeof rr->why)
        snprintf(rr->why + n, sizeof rr->why - (size_t)n, ", q=[%.9g,%.9g], qd=[%.9g,%.9g]", rr->y[0], rr->y[1],
                 rr->y[2], rr->y[3]);
    rr->fail = 1;
}

static int emit_row(dp_run *r)
{
    struct dp_right_hand_run *rr = r->state;
    double row[MAX_WIDTH];
    fill_row(rr, row);
    if (!all_finite(row, rr->cols.width)) {
        overflow(rr, "state or its forces");
        return DP_OK;
    }
    memcpy(rr->final_row, row, sizeof row);
    r->sum.final_row = (dp_row){ .t = rr->t, .val = rr->final_row };
    /* output.every decimates the grid k dt (the first and the last sample always written) */
    int due = rr->k % (unsigned long long)r->spec.output.every == 0 || rr->k >= r->nsteps;
    if (!r->spec.output.samples || !due)
        return DP_OK;
    r->sum.samples++;
    dp_record rec = { .type = DP_RECORD_ROW, .u.row = { .t = rr->t, .val = NULL } };
    return dp_row_queue_push(&rr->queue, &rec, row);
}

static const char *mode_name(dp_right_hand_mode m)
{
    static const char *const names[] = { "free", "stick", "slip+", "slip-" };
    return names[m];
}

/* The stop record: time, state, which paradox, the candidate accelerations. */
static void paradox(struct dp_right_hand_run *rr, const dp_right_hand_result *res)
{
    char *p = rr->why, *end = rr->why + sizeof rr->why;
    char what[48];
    for (int i = 0; i < res->n && i < DP_RIGHT_HAND_MAX_SOL; i++)
        if (!all_finite(res->sol[i].qdd, 2) || !all_finite(res->sol[i].N, 2)) {
            overflow(rr, "acceleration problem (a candidate's q'' or N)");
            return;
        }
    if (res->n == 0 && !res->continuum)
        snprintf(what, sizeof what, "inconsistency (no acceleration)");
    else
        snprintf(what, sizeof what, "indeterminacy (%d accelerations%s)", res->n, res->continuum ? " and more" : "");
    p += snprintf(p, (size_t)(end - p), "Painleve %s at t=%.10g, q=[%.9g,%.9g], qd=[%.9g,%.9g]: ", what, rr->t,
                  rr->y[0], rr->y[1], rr->y[2], rr->y[3]);
    if (res->n == 0 && p < end)
        snprintf(p, (size_t)(end - p), "no candidates");
    for (int i = 0; i < res->n && i < DP_RIGHT_HAND_MAX_SOL && p < end; i++)
        p += snprintf(p, (size_t)(end - p), "%sqdd=[%.6g,%.6g] N=[%.6g,%.6g] (%s,%s)", i ? "; " : "",
                      res->sol[i].qdd[0], res->sol[i].qdd[1], res->sol[i].N[0], res->sol[i].N[1],
                      res->sol[i].liftoff ? "lift-off" : mode_name(res->sol[i].mode[0]),
                      mode_name(res->sol[i].mode[1]));
    rr->fail = 1;
}

/* The rod's planar state from the run's: q, q' on the floor's coordinates, the end A's height apart. */
static dp_right_hand_rod_state rod_state(const struct dp_right_hand_run *rr)
{
    return (dp_right_hand_rod_state){ .x = rr->y[0], .y = rr->ya[0], .theta = rr->y[1], .xd = rr->y[2], .yd = rr->ya[1],
                                      .thetad = rr->y[3] };
}

static void set_rod_state(struct dp_right_hand_run *rr, const dp_right_hand_rod_state *s)
{
    rr->y[0] = s->x, rr->y[1] = s->theta, rr->y[2] = s->xd, rr->y[3] = s->thetad;
    rr->ya[0] = s->y, rr->ya[1] = s->yd;
}

/* In flight a row's accelerations are the free rod's (theta'' = 0), its reaction 0, no mode. */
static void flight_sol(struct dp_right_hand_run *rr, double xdd)
{
    rr->sol = (dp_right_hand_sol){ .qdd = { xdd, 0 }, .mode = { DP_RIGHT_HAND_FREE, DP_RIGHT_HAND_FREE }, .liftoff = 1 };
    rr->mode[0] = rr->mode[1] = DP_RIGHT_HAND_FREE;
}

/* One event into the stream (counted whether written or not); 0 out of memory. */
static int event(dp_run *r, dp_event ev)
{
    struct dp_right_hand_run *rr = r->state;
    r->sum.events++;
    dp_record rec = { .type = DP_RECORD_EVENT, .u.event = ev };
    if (r->spec.output.events && dp_row_queue_push(&rr->queue, &rec, NULL) != DP_OK)
        return dp_run_fail(r, DP_ENOMEM, "out of memory for the events"), 0;
    return 1;
}

/* The rod leaves the floor at the current state: a free flight from here, announced by a lift-off event
 * (the end's height and upward rate: 0 and 0 from sliding or sticking, the rebound after a bounce). */
static int take_off(dp_run *r, int announce)
{
    struct dp_right_hand_run *rr = r->state;
    dp_right_hand_rod_state s = rod_state(rr);
    double xdd;
    rr->flight = 1;
    dp_right_hand_flight_start(&rr->m, rr->t, &s, &rr->fl);
    dp_right_hand_flight_at(&rr->m, &rr->fl, rr->t, &s, &xdd);
    flight_sol(rr, xdd);
    if (!announce)
        return 1;
    return event(r, (dp_event){ .kind = DP_EVENT_LIFTOFF, .t = rr->t, .x = rr->ya[0], .v = rr->ya[1], .element = 0 });
}

/* The full acceleration problem at the current state picks the mode (events for the coordinates whose
 * stick/slip changed); 0 when the run must stop (a paradox, the rod lifting off). */
static int classify(dp_run *r, int initial)
{
    struct dp_right_hand_run *rr = r->state;
    if (!all_finite(rr->y, 4)) {
        overflow(rr, "state");
        return 0;
    }
    if (rr->m.kind == DP_RIGHT_HAND_ROD && !(rr->y[1] > 0 && rr->y[1] < M_PI)) {
        snprintf(rr->why, sizeof rr->why, "the rod reaches the floor at t=%.10g, q=[%.9g,%.9g], qd=[%.9g,%.9g]: "
                 "it lies flat, both ends on the floor, a contact this model (one end on the floor, 0 < theta < pi) "
                 "does not follow", rr->t, rr->y[0], rr->y[1], rr->y[2], rr->y[3]);
        rr->fail = 1;
        return 0;
    }
    dp_right_hand_result res;
    dp_right_hand_solve(&rr->m, rr->y, rr->y + 2, NULL, &res);
    if (res.n != 1 || res.continuum) {
        paradox(rr, &res);
        return 0;
    }
    const dp_right_hand_sol *s = &res.sol[0];
    if (!all_finite(s->qdd, 2) || !all_finite(s->N, 2) || !all_finite(s->Q, 2)) {
        overflow(rr, "acceleration problem (q'', N or Q)");
        return 0;
    }
    if (s->liftoff)
        return take_off(r, !initial);
    for (int k = 0; k < 2 && !initial; k++) {
        int now = s->mode[k] == DP_RIGHT_HAND_STICK;
        if (rr->mode[k] == s->mode[k] || s->mode[k] == DP_RIGHT_HAND_FREE)
            continue;                    /* a reversal slip+ -> slip- is a new slip phase */
        r->sum.events++;
        rr->events++;
        dp_record rec = { .type = DP_RECORD_EVENT };
        rec.u.event = (dp_event){ .kind = now ? DP_EVENT_STICK : DP_EVENT_SLIP, .t = rr->t, .x = rr->y[k],
                                  .v = rr->y[2 + k], .element = (size_t)k };
        if (r->spec.output.events && dp_row_queue_push(&rr->queue, &rec, NULL) != DP_OK)
            return dp_run_fail(r, DP_ENOMEM, "out of memory for the events"), 0;
    }
    memcpy(rr->mode, s->mode, sizeof rr->mode);
    rr->sol = *s;
    return 1;
}

/* The impact of the end A, on the floor in state s with s->yd <= 0: the impulse, an impact event (the end's
 * height 0, its upward rate before and after, the normal impulse), then a bounce (lift-off) or the end on the
 * floor, where the enumeration chooses stick, slip or lift-off (classify). 0 when the run stops. */
static int impact_at(dp_run *r, dp_right_hand_rod_state *s)
{
    struct dp_right_hand_run *rr = r->state;
    dp_right_hand_impact im;
    double e = rr->m.e, l = rr->m.length / 2;
    for (int pass = 0; pass < 2; pass++) {
        if (!dp_right_hand_rod_impact(&rr->m, s->theta, s->xd, s->yd, s->thetad, e, &im)) {
            snprintf(rr->why, sizeof rr->why, "the impact at t=%.10g, q=[%.9g,%.9g], qd=[%.9g,%.9g] does not end",
                     rr->t, s->x, s->theta, s->xd, s->thetad);
            rr->fail = 1;
            return 0;
        }
        double fall = rr->m.g - l * sin(s->theta) * im.thetad * im.thetad; /* the end's fall acceleration */
        if (!(im.vn > 0 && e < 1 && fall > 0 &&
              (2 * im.vn < ZENO_REL * r->h * fall * (1 - e) || im.vn * im.vn < 2 * fall * HOP_REL * rr->m.length)))
            break;
        e = 0;                                   /* the bounces left accumulate within location's reach */
    }
    double out[5] = { im.vt, im.vn, im.thetad, im.Pt, im.Pn };
    if (!all_finite(out, 5)) {
        overflow(rr, "impact");
        return 0;
    }
    r->sum.impacts++;
    if (!event(r, (dp_event){ .kind = DP_EVENT_IMPACT, .t = rr->t, .x = 0, .v = s->yd, .v_after = im.vn,
                              .impulse = im.Pn, .element = 0 }))
        return 0;
    s->y = 0, s->xd = im.vt, s->yd = im.vn, s->thetad = im.thetad;
    set_rod_state(rr, s);
    if (im.vn > 0)
        return take_off(r, 1);
    rr->flight = 0;
    rr->ya[0] = rr->ya[1] = 0;
    rr->mode[0] = rr->mode[1] = DP_RIGHT_HAND_FREE;   /* the mode on the floor is an event: stick or slip */
    gsl_odeiv2_evolve_reset(rr->ev);
    rr->h = rr->h0;
    return classify(r, 0);
}

/* The state at a landing of end `end` (1: B, which becomes A: the rod's ends are alike), theta taken back
 * into (-pi, pi]; 0 when the rod lands flat (both ends at once: the run stops). */
static int landing_state(struct dp_right_hand_run *rr, int end, dp_right_hand_rod_state *s)
{
    double xdd, l = rr->m.length / 2;
    dp_right_hand_flight_at(&rr->m, &rr->fl, rr->t, s, &xdd);
    if (end == 1) {
        double sn = sin(s->theta), cs = cos(s->theta);
        s->x += 2 * l * cs, s->xd -= 2 * l * sn * s->thetad, s->yd += 2 * l * cs * s->thetad;
        s->theta += M_PI;
    }
    s->theta = remainder(s->theta, 2 * M_PI);
    s->y = 0;
    if (s->theta > 0 && s->theta < M_PI)
        return 1;
    snprintf(rr->why, sizeof rr->why, "the rod lands flat at t=%.10g, x_A=%.9g, qd=[%.9g,%.9g]: an impact at both ends "
             "at once, which this model (one end on the floor) does not follow", rr->t, s->x, s->xd, s->thetad);
    rr->fail = 1;
    return 0;
}

/* The free flight up to t1: the landing located (rod_flight.c), the impact there; the advances count as the
 * integrator's steps. */
static int fly(dp_run *r, double t1)
{
    struct dp_right_hand_run *rr = r->state;
    while (rr->flight && rr->t < t1) {
        if (rr->call_steps >= CALL_STEPS)
            return DP_MORE;
        unsigned long used = 0;
        double t = rr->t, xdd;
        int end = 0, s = dp_right_hand_flight_landing(&rr->m, &rr->fl, &t, t1, CALL_STEPS - rr->call_steps, &used, &end);
        rr->call_steps += used;
        r->sum.steps += used;
        if ((double)r->sum.steps > r->max_steps)
            return dp_run_fail(r, DP_ELIMIT, "the integrator took more than %.6g steps", r->max_steps);
        if (s == DP_FLIGHT_OVERFLOW) {
            overflow(rr, "flight");
            return DP_OK;
        }
        rr->t = t;
        dp_right_hand_rod_state st;
        dp_right_hand_flight_at(&rr->m, &rr->fl, t, &st, &xdd);
        set_rod_state(rr, &st);
        flight_sol(rr, xdd);
        if (s == DP_FLIGHT_BUDGET)
            return DP_MORE;
        if (s != DP_FLIGHT_LANDS)
            continue;
        if (++rr->events > MAX_EVENTS)
            return dp_run_fail(r, DP_ESOLVE, "more than %d located events (t=%.10g): an accumulation of "
                               "events (Zeno) this solver does not cross", MAX_EVENTS, rr->t);
        if (!landing_state(rr, end, &st) || !impact_at(r, &st))
            return DP_OK;
    }
    return DP_OK;
}

/* The first of 4^k LOCATE_REL-scaled lengths (up to 1e-3) at which a step from (t0, y0) leaves the phase,
 * or 0 when none does. */
static double ahead(struct dp_right_hand_run *rr, double t0, const double y0[4])
{
    double y[4];
    for (double h = LOCATE_REL * fmax(1, fabs(t0)); h < 1e-3; h *= 4)
        if (step_to(rr, t0, y0, h, y) != 1)
            return h;
    return 0;
}

/* Integrates the phases up to t1 (the next sample), locating and crossing the events on the way. */
static int segment(dp_run *r, double t1)
{
    struct dp_right_hand_run *rr = r->state;
    while (rr->t < t1) {
        if (rr->flight) {
            int s = fly(r, t1);
            if (s != DP_OK || rr->fail || r->status != DP_OK)
                return s;
            continue;
        }
        double t0 = rr->t, y0[4], hb = fmin(rr->h, t1 - t0), hi;
        memcpy(y0, rr->y, sizeof y0);
        if ((double)++r->sum.steps > r->max_steps)
            return dp_run_fail(r, DP_ELIMIT, "the integrator took more than %.6g steps", r->max_steps);
        if (++rr->call_steps > CALL_STEPS)
            return DP_MORE; /* resumed by the next call, toward the same t1 */
        int s = gsl_odeiv2_evolve_apply(rr->ev, rr->ctl, rr->st, &rr->sys, &rr->t, t1, &rr->h, rr->y);
        if (s != GSL_SUCCESS) {
            rr->t = t0, hi = hb;
            memcpy(rr->y, y0, sizeof y0);
        } else if (!in_phase(rr, rr->y, &rr->sol)) {
            hi = rr->t - t0;
        } else if (rr->t < t1 && rr->t - t0 < COLLAPSE * fmax(1, fabs(t0)) && (hi = ahead(rr, t0, y0)) > 0) {
            ;                   /* the step collapsed before a boundary: hi is past it */
        } else {
            r->sum.stick_time += (rr->t - t0) * stuck(rr);
            continue;
        }
        if (!(hi > 0))
            hi = fmax(fabs(t0), 1) * LOCATE_REL;
        locate(rr, t0, y0, hi);
        r->sum.stick_time += (rr->t - t0) * stuck(rr);
        gsl_odeiv2_evolve_reset(rr->ev);
        rr->h = rr->h0;
        if (++rr->events > MAX_EVENTS)
            return dp_run_fail(r, DP_ESOLVE, "more than %d located events (t=%.10g): an accumulation of "
                               "events (Zeno) this solver does not cross", MAX_EVENTS, rr->t);
        if (!classify(r, 0))
            return DP_OK;
    }
    rr->t = t1; /* evolve_apply lands on t1 exactly */
    return DP_OK;
}

static int rh_run_advance(dp_run *r)
{
    struct dp_right_hand_run *rr = r->state;
    if (dp_row_slots_reserve(&rr->slots, r->out_cap) != DP_OK)   /* rows are narrow: one per record */
        return dp_run_fail(r, DP_ENOMEM, "out of memory for a block's rows");
    rr->call_steps = 0;
    dp_row_queue_flush(&rr->queue, r, &rr->slots);
    while (r->out_n < r->out_cap && !dp_row_queue_waiting(&rr->queue) && !rr->ended && r->status == DP_OK) {
        if (rr->fail) {
            rr->ended = 1;
            break;
        }
        if (rr->k > 0) {
            double t1 = rr->k < r->nsteps ? (double)rr->k * r->h : r->spec.solver.t_end;
            int s = segment(r, t1);
            if (s == DP_MORE)
                break;
            if (s != DP_OK)
                return r->status;
            if (rr->fail)
                continue;
        }
        if (emit_row(r) != DP_OK)
            return dp_run_fail(r, DP_ENOMEM, "out of memory for the rows");
        r->n = rr->k;
        if (rr->k++ >= r->nsteps)
            rr->ended = 1;
        dp_row_queue_flush(&rr->queue, r, &rr->slots);
    }
    dp_row_queue_flush(&rr->queue, r, &rr->slots);
    if (rr->ended && !dp_row_queue_waiting(&rr->queue)) {
        if (rr->fail && r->out_n > 0)
            return DP_OK;      /* the rows before the stop go out first; the next call fails with the record */
        if (rr->fail)
            return dp_run_fail(r, DP_ESOLVE, "%s", rr->why);
        r->finished = 1;
    }
    return DP_OK;
}

static int rh_run_pending(const dp_run *r)
{
    const struct dp_right_hand_run *rr = r->state;
    return dp_row_queue_waiting(&rr->queue);
}

static void setup_columns(struct dp_right_hand_run *rr)
{
    static const char *const names[] = { "q", "qd", "qdd", "N", "mode", "margin", "gap" };
    int rod = rr->m.kind == DP_RIGHT_HAND_ROD;
    rr->nN = rod ? 1 : 2;
    rr->nmargin = rod ? 2 : 4;
    size_t n[] = { 2, 2, 2, rr->nN, 2, rr->nmargin, 2 };
    rr->cols.ngroups = rod ? 7 : 6;           /* the rod's gap: the end A's height and rate */
    rr->cols.width = 0;
    for (size_t g = 0; g < rr->cols.ngroups; g++) {
        rr->cols.group[g] = (dp_column_group){ .name = names[g], .n = n[g], .index = NULL, .phase = g == 4 };
        rr->cols.width += n[g];
    }
}

static int rh_run_init(dp_run *r)
{
    struct dp_right_hand_run *rr = calloc(1, sizeof *rr);
    if (rr == NULL)
        return DP_ENOMEM;
    r->state = rr;
    rr->m = *r->spec.rh;
    memcpy(rr->y, r->spec.x0v, 2 * sizeof *rr->y);
    memcpy(rr->y + 2, r->spec.v0v, 2 * sizeof *rr->y);
    setup_columns(rr);
    r->cols = &rr->cols;
    rr->slots.width = rr->cols.width;
    if (dp_row_queue_init(&rr->queue, rr->cols.width, QCAP0) != DP_OK)
        return DP_ENOMEM;
    double rtol = r->spec.solver.rtol > 0 ? r->spec.solver.rtol : 1e-10;
    double atol = r->spec.solver.atol > 0 ? r->spec.solver.atol : rtol * 1e-2;
    rr->sys = (gsl_odeiv2_system){ rhs, NULL, 4, rr };
    rr->st = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 4);
    rr->ctl = gsl_odeiv2_control_y_new(atol, rtol);
    rr->ev = gsl_odeiv2_evolve_alloc(4);
    if (rr->st == NULL || rr->ctl == NULL || rr->ev == NULL)
        return DP_ENOMEM;
    rr->h0 = rr->h = fmin(r->h, 1e-3);
    if (rr->m.kind == DP_RIGHT_HAND_ROD)
        rr->ya[0] = r->spec.x0v[2], rr->ya[1] = r->spec.v0v[2];
    dp_right_hand_rod_state s = rod_state(rr);
    if (rr->ya[0] > 0 || rr->ya[1] > 0)
        take_off(r, 0);   /* the rod starts in the air */
    else if (rr->ya[1] < 0)
        impact_at(r, &s); /* ...or hitting the floor */
    else
        classify(r, 1); /* a paradox at t = 0 stops the run in its first block, with its record */
    return DP_OK;
}

static void rh_run_free(void *state)
{
    struct dp_right_hand_run *rr = state;
    if (rr == NULL)
        return;
    if (rr->ev)
        gsl_odeiv2_evolve_free(rr->ev);
    if (rr->ctl)
        gsl_odeiv2_control_free(rr->ctl);
    if (rr->st)
        gsl_odeiv2_step_free(rr->st);
    dp_row_queue_clear(&rr->queue);
    free(rr->slots.data);
    free(rr);
}

const dp_run_type dp_run_right_hand = {
    .name = "right-hand", .check = dp_rules_right_hand, .init = rh_run_init, .advance = rh_run_advance,
    .pending = rh_run_pending, .free = rh_run_free,
};
