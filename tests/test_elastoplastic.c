/* tests/test_elastoplastic.c - the Jenkins element (docs/systems.md §3; Höschl 003 §15) against closed forms:
 * its return mapping under monotonic loading, a full strain cycle whose loop area is the plastic work,
 * shakedown under small cycles; a mass on a Jenkins spring under a constant load thrown fast enough to
 * yield (elastic swing, one plastic excursion, elastic oscillation about the new offset), one mass and a
 * one-node network alike, with the orders measured at theta = 1/2 and theta = 1; bad input. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "dashpot/wellposedness.h"
#include "trajectory.h"

static const dp_spring jenkins = { .law = DP_SPRING_ELASTOPLASTIC, .k = 2, .yield = 3 };

/* Monotonic loading: F = min(k u, F_y), p = max(0, u - F_y/k), flow only past yield. */
static void test_monotonic_loading(void **state)
{
    (void)state;
    double p = 0;
    int flow;
    for (int i = 1; i <= 300; i++) {
        double u = 0.01 * i, F = dp_elastoplastic_return(&jenkins, u, &p, &flow);
        double F_ref = fmin(2 * u, 3), p_ref = fmax(0, u - 1.5);
        assert_true(fabs(F - F_ref) <= 1e-12);
        assert_true(fabs(p - p_ref) <= 1e-12);
        assert_int_equal(flow, u > 1.5 + 1e-12 ? 1 : 0);
    }
}

/* u along 0 -> U -> -U -> U in steps of du: the loop's area (trapezoids; the kinks fall on grid points) and
 * the plastic work F_y sum |dp| over the cycle both equal the parallelogram's 4 F_y (U - F_y/k). */
static void test_cycle_area_is_plastic_work(void **state)
{
    (void)state;
    const double U = 4, du = 0.001;
    double p = 0, u = 0, F = 0, area = 0, work = 0;
    int flow;
    double legs[3][2] = { { 0, U }, { U, -U }, { -U, U } };
    for (int leg = 0; leg < 3; leg++) {
        int n = (int)lround(fabs(legs[leg][1] - legs[leg][0]) / du);
        double dir = legs[leg][1] > legs[leg][0] ? 1 : -1;
        for (int i = 1; i <= n; i++) {
            double u1 = legs[leg][0] + dir * du * i, p0 = p;
            double F1 = dp_elastoplastic_return(&jenkins, u1, &p, &flow);
            if (leg > 0) {   /* the closed cycle: from U back to U */
                area += 0.5 * (F + F1) * (u1 - u);
                work += jenkins.yield * fabs(p - p0);
            }
            u = u1, F = F1;
        }
    }
    double ref = 4 * jenkins.yield * (U - jenkins.yield / jenkins.k);
    assert_true(fabs(area - ref) <= 1e-9 * ref);
    assert_true(fabs(work - ref) <= 1e-9 * ref);
}

/* After yielding to U, cycles of amplitude below 2 F_y/k stay elastic: p stays put, no loop, no flow. */
static void test_shakedown(void **state)
{
    (void)state;
    double p = 0, area = 0, F = 0, u = 0;
    int flow;
    for (int i = 1; i <= 4000; i++)   /* to U = 4 */
        F = dp_elastoplastic_return(&jenkins, u = 0.001 * i, &p, &flow);
    double p_shaken = p;
    assert_true(fabs(p_shaken - 2.5) <= 1e-12);
    for (int i = 1; i <= 20000; i++) {
        double u1 = 4 - 1.4 * (1 - cos(2 * M_PI * i / 1000.0)) ;   /* between 4 and 1.2: amplitude 2.8 < 3 */
        double F1 = dp_elastoplastic_return(&jenkins, u1, &p, &flow);
        assert_int_equal(flow, 0);
        area += 0.5 * (F + F1) * (u1 - u);
        u = u1, F = F1;
    }
    assert_true(p == p_shaken);
    assert_true(fabs(area) <= 1e-9);
}

/* ---- a mass on a Jenkins spring ------------------------------------------------------------------------ */

/* m x'' + c x' + F_J(x) = F0 from x = 0, v = V, with m = k = F_y = 1, |F0| < F_y and 0 <= c < 2, in closed
 * form. An elastic phase is a damped harmonic swing about p + F0, u = x - p - F0 = e^(-c s/2) (A cos w s +
 * B sin w s), w = sqrt(1 - c^2/4); it yields at the first s > 0 where k (x - p) = +-F_y with x' pointing out
 * (a transversal crossing of that closed-form curve, bracketed on a fine grid and bisected to rounding). A
 * plastic phase in direction d is m x'' + c x' = F0 - d F_y: x' = v_inf + (v0 - v_inf) e^(-c s), v_inf =
 * (F0 - d)/c (uniformly accelerated for c = 0), and unloads at x' = 0, s = ln((v0 - v_inf)/(-v_inf))/c,
 * with p = x - d. The event times and the state at T. */
typedef struct closed { double x, v, p, t[8]; int kind[8], n; } closed;
typedef struct swing { double F0, c, A, B, w; } swing;

static double swing_u(const swing *e, double s)
{
    return exp(-0.5 * e->c * s) * (e->A * cos(e->w * s) + e->B * sin(e->w * s));
}

static double swing_du(const swing *e, double s)
{
    double sg = 0.5 * e->c, ca = cos(e->w * s), sa = sin(e->w * s);
    return exp(-sg * s) * ((e->B * e->w - sg * e->A) * ca - (e->A * e->w + sg * e->B) * sa);
}

/* The first s in (0, T - t] where F0 + u(s) leaves [-1, 1] (INFINITY if none); *d its side. */
static double swing_first_yield(const swing *e, double span, int *d)
{
    const double ds = 1e-3;
    double s0 = 0, g0 = fabs(e->F0 + swing_u(e, 0)) - 1;
    for (double s1 = ds; s0 < span; s0 = s1, s1 += ds) {
        double g1 = fabs(e->F0 + swing_u(e, s1)) - 1;
        if (g1 > 0 && !(g0 > 0)) {   /* a crossing in (s0, s1]: bisect it to rounding */
            double a = s0, b = s1;
            for (int k = 0; k < 200 && b - a > 0; k++) {
                double m = 0.5 * (a + b);
                if (m == a || m == b)
                    break;
                if (fabs(e->F0 + swing_u(e, m)) - 1 > 0)
                    b = m;
                else
                    a = m;
            }
            *d = e->F0 + swing_u(e, b) > 0 ? 1 : -1;
            return b;
        }
        g0 = g1;
    }
    return INFINITY;
}

static closed jenkins_closed_form(double F0, double c, double V, double T)
{
    closed o = { .n = 0 };
    double t = 0, x = 0, v = V, p = 0;
    int flow = 0;
    for (;;) {
        if (flow == 0) {
            double w = sqrt(1 - 0.25 * c * c), A = x - p - F0;
            swing e = { F0, c, A, (v + 0.5 * c * A) / w, w };
            int d = 0;
            double s = swing_first_yield(&e, T - t, &d);
            if (t + s >= T) {
                o.x = p + F0 + swing_u(&e, T - t), o.v = swing_du(&e, T - t), o.p = p;
                return o;
            }
            t += s, x = p + d, v = swing_du(&e, s), flow = d;
            o.t[o.n] = t, o.kind[o.n++] = DP_EVENT_YIELD;
        } else {
            double a = F0 - flow, vinf = c > 0 ? a / c : 0;
            double dur = c > 0 ? log((v - vinf) / -vinf) / c : -v / a;
            double s = fmin(dur, T - t);
            double xs = c > 0 ? x + vinf * s + (v - vinf) * -expm1(-c * s) / c : x + v * s + 0.5 * a * s * s;
            double vs = c > 0 ? vinf + (v - vinf) * exp(-c * s) : v + a * s;
            if (t + dur >= T) {
                o.x = xs, o.v = vs, o.p = xs - flow;
                return o;
            }
            t += dur, x = xs, v = 0, p = x - flow, flow = 0;
            o.t[o.n] = t, o.kind[o.n++] = DP_EVENT_UNLOAD;
        }
    }
}

/* F0 = -1/4, V = 2: yield at k x = 1, slide, unload, swing back past -F_y (undamped, the swing's amplitude
 * 5/4 about F0 reaches -3/2), yield in reverse, slide, unload, then an elastic swing about p + F0 of
 * amplitude at most 3/4 that stays inside: four events before T = 8, with or without the damper c = 0.1. */
typedef struct jcase { double F0, c, V, T; } jcase;
static const jcase undamped = { -0.25, 0, 2, 8 }, damped = { -0.25, 0.1, 2, 8 };

typedef struct run_end { double x, v, p, Fs; size_t ne; dp_event ev[8]; } run_end;

static run_end run_jenkins(const jcase *k, const char *solver)
{
    char doc[1024];
    snprintf(doc, sizeof doc, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1},"
             "\"damper\":{\"law\":\"linear\",\"c\":%.17g},\"forcing\":{\"kind\":\"constant\",\"value\":%.17g}},"
             "\"initial\":{\"x\":0,\"v\":%.17g},\"solver\":%s,\"output\":{\"every\":1000000}}", k->c, k->F0, k->V,
             solver);
    traj t;
    assert_int_equal(traj_run(doc, &t), DP_OK);
    assert_int_equal(t.status, DP_DONE);
    assert_true(t.sum.final.plastic && fabs(t.sum.final.t - k->T) <= 1e-12);
    run_end e = { t.sum.final.x, t.sum.final.v, t.sum.final.p, t.sum.final.Fs, t.ne, { { 0 } } };
    for (size_t i = 0; i < t.ne && i < 8; i++)
        e.ev[i] = t.e[i];
    traj_free(&t);
    return e;
}

/* A solver for the ratio checks: stick-slip with theta (par) and events, or newmark with beta (par). */
typedef struct method { const jcase *k; int newmark; double par; const char *events; } method;

static run_end run_method(const method *m, double dt)
{
    char solver[256];
    if (m->newmark)
        snprintf(solver, sizeof solver, "{\"kind\":\"newmark\",\"dt\":%.17g,\"t_end\":%g,\"beta\":%.17g,"
                 "\"gamma\":0.5}", dt, m->k->T, m->par);
    else
        snprintf(solver, sizeof solver, "{\"kind\":\"stick-slip\",\"dt\":%.17g,\"t_end\":%g,\"theta\":%g,"
                 "\"events\":\"%s\"}", dt, m->k->T, m->par, m->events);
    return run_jenkins(m->k, solver);
}

/* The run's events are the closed form's, in kind and order; returns the largest time error. */
static double event_error(const run_end *e, const closed *ref)
{
    assert_int_equal(e->ne, (size_t)ref->n);
    double worst = 0;
    for (int i = 0; i < ref->n; i++) {
        assert_int_equal(e->ev[i].kind, ref->kind[i]);
        worst = fmax(worst, fabs(e->ev[i].t - ref->t[i]));
    }
    return worst;
}

/* Errors of x and p at T for dt, dt/2, dt/4, dt/8 (dt = 0.02) through the four events: each halving must
 * divide them by ratio_lo..ratio_hi; p is checked so only where it carries an error (with no damper the
 * theta = 1/2 step keeps the elastic energy exactly, so a located yield has the exact speed and p is exact
 * to rounding: asserted instead). Returns the largest event-time error over dt^order. */
static double check_ratios(const method *m, double ratio_lo, double ratio_hi, const char *what)
{
    closed ref = jenkins_closed_form(m->k->F0, m->k->c, m->k->V, m->k->T);
    assert_int_equal(ref.n, 4);
    int order = ratio_lo > 3 ? 2 : 1;
    double ex[4], ep[4], ev_scaled = 0, dt = 0.02;
    for (int i = 0; i < 4; i++, dt /= 2) {
        run_end e = run_method(m, dt);
        ex[i] = fabs(e.x - ref.x), ep[i] = fabs(e.p - ref.p);
        ev_scaled = fmax(ev_scaled, event_error(&e, &ref) / pow(dt, order));
        /* the final state is elastic: F = k (x - p) inside the yield interval */
        assert_true(fabs(e.Fs - (e.x - e.p)) <= 1e-12 && fabs(e.Fs) < 1);
    }
    int p_exact = m->k->c == 0 && order == 2;
    for (int i = 0; i < 3; i++) {
        printf("%s: dt/%d: |x - x*| %.3e -> %.3e (ratio %.3f), |p - p*| %.3e -> %.3e (ratio %.3f)\n", what,
               1 << i, ex[i], ex[i + 1], ex[i] / ex[i + 1], ep[i], ep[i + 1], ep[i] / ep[i + 1]);
        assert_true(ex[i] / ex[i + 1] >= ratio_lo && ex[i] / ex[i + 1] <= ratio_hi);
        if (p_exact)
            assert_true(ep[i] <= 1e-12 && ep[i + 1] <= 1e-12);
        else
            assert_true(ep[i] / ep[i + 1] >= ratio_lo && ep[i] / ep[i + 1] <= ratio_hi);
    }
    printf("%s: event times within %.3g dt^%d\n", what, ev_scaled, order);
    return ev_scaled;
}

/* theta = 1/2 with yield and unload located: second order through four events, the event times too. */
static void test_located_events_second_order(void **state)
{
    (void)state;
    method a = { &undamped, 0, 0.5, "locate" }, b = { &damped, 0, 0.5, "locate" };
    assert_true(check_ratios(&a, 3.5, 4.5, "stick-slip theta 1/2") <= 1);   /* event times within dt^2 */
    assert_true(check_ratios(&b, 3.5, 4.5, "stick-slip theta 1/2, c = 0.1") <= 1);
}

/* theta = 1 with the events located: first order, consistently (every halving halves the error). */
static void test_located_events_theta_one(void **state)
{
    (void)state;
    method a = { &undamped, 0, 1, "locate" }, b = { &damped, 0, 1, "locate" };
    assert_true(check_ratios(&a, 1.8, 2.2, "stick-slip theta 1") <= 2);      /* event times within 2 dt */
    assert_true(check_ratios(&b, 1.8, 2.2, "stick-slip theta 1, c = 0.1") <= 2);
}

/* Newmark's average acceleration (beta = 1/4, gamma = 1/2) split at yield and unload, each stretch with its
 * phase's tangent stiffness: second order through the four events; Höschl's linear acceleration
 * (beta = 1/6, not energy-conserving: p carries an O(dt^2) error even undamped) too. */
static void test_newmark_located_second_order(void **state)
{
    (void)state;
    method a = { &undamped, 1, 0.25, NULL }, b = { &damped, 1, 0.25, NULL }, c = { &damped, 1, 1.0 / 6, NULL };
    assert_true(check_ratios(&a, 3.5, 4.5, "newmark beta 1/4") <= 1);
    assert_true(check_ratios(&b, 3.5, 4.5, "newmark beta 1/4, c = 0.1") <= 1);
    assert_true(check_ratios(&c, 3.5, 4.5, "newmark beta 1/6, c = 0.1") <= 1);
}

/* Where the event falls in its step does not matter: at every step from 0.01 down by 0.8 (t1 anywhere in
 * its step) the error at T stays under C dt^2 with one C, and the events are at the closed form's times. */
static void test_located_events_any_phase_of_the_step(void **state)
{
    (void)state;
    method m = { &damped, 0, 0.5, "locate" };
    closed ref = jenkins_closed_form(damped.F0, damped.c, damped.V, damped.T);
    double worst = 0;
    for (double n = 800; n <= 3200; n *= 1.25) {   /* dt = T/n: t_end on the grid */
        double dt = damped.T / round(n);
        run_end e = run_method(&m, dt);
        worst = fmax(worst, fmax(fabs(e.x - ref.x), fabs(e.p - ref.p)) / (dt * dt));
        assert_true(event_error(&e, &ref) <= dt * dt);
    }
    printf("theta 1/2, dt from 0.01 by 0.8: error at T within %.3f dt^2\n", worst);
    assert_true(worst <= 1);
}

/* Events "none" keeps the unlocated step (a yield or unload reported at the end of its step): the one-mass
 * inclusion step and the network's active-set step, separate codes for the same step, agree to rounding;
 * the network unlocated too (its meta line "none"; networks locate them by default, test_network_events.c). */
static const char *network_doc = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],"
    "\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1},\"damper\":{\"law\":\"linear\",\"c\":%.17g}}],"
    "\"forcing\":[{\"node\":0,\"kind\":\"constant\",\"value\":%.17g}]},\"initial\":{\"x\":[0],\"v\":[%.17g]},"
    "\"solver\":{\"kind\":\"stick-slip\",\"dt\":%.17g,\"t_end\":%g,\"theta\":%g,\"events\":\"none\"},"
    "\"output\":{\"every\":1000000}}";

static run_end run_network(const jcase *k, double dt, double theta)
{
    char doc[1024];
    snprintf(doc, sizeof doc, network_doc, k->c, k->F0, k->V, dt, k->T, theta);
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(doc, strlen(doc), 0, &spec, &errs);
    assert_int_equal(s, DP_OK);
    assert_string_equal(dp_spec_events_mode(&spec), "none");
    dp_run *run = dp_run_alloc(&spec, 0, &errs, &s);
    dp_spec_clear(&spec);
    assert_non_null(run);
    const dp_columns *c = dp_run_columns(run);
    /* x, v, Fs, Fd, phase and the plastic offsets "p" of the one elastoplastic element */
    assert_int_equal(c->ngroups, 6);
    assert_string_equal(c->group[5].name, "p");
    assert_int_equal(c->width, 6);
    dp_record buf[64];
    size_t n;
    run_end e = { 0 };
    do {
        s = dp_run_next(run, buf, 64, &n);
        for (size_t i = 0; i < n; i++)
            if (buf[i].type == DP_RECORD_EVENT && e.ne < 8)
                e.ev[e.ne++] = buf[i].u.event;
    } while (s == DP_MORE);
    assert_int_equal(s, DP_DONE);
    const double *row = dp_run_summary(run)->final_row.val;
    e.x = row[0], e.v = row[1], e.Fs = row[2], e.p = row[5];
    dp_run_free(run);
    return e;
}

static void test_unlocated_one_mass_is_the_network(void **state)
{
    (void)state;
    closed ref = jenkins_closed_form(damped.F0, damped.c, damped.V, damped.T);
    const double thetas[2] = { 0.5, 1 };
    for (int k = 0; k < 2; k++) {
        for (double dt = 0.01; dt > 0.002; dt /= 2) {
            method m = { &damped, 0, thetas[k], "none" };
            run_end a = run_method(&m, dt), b = run_network(&damped, dt, thetas[k]);
            assert_true(fabs(a.x - b.x) <= 1e-9 && fabs(a.v - b.v) <= 1e-9 && fabs(a.p - b.p) <= 1e-9);
            assert_int_equal(a.ne, 4);
            assert_int_equal(b.ne, 4);
            for (int i = 0; i < 4; i++) {
                assert_int_equal(a.ev[i].kind, ref.kind[i]);
                assert_int_equal(b.ev[i].kind, ref.kind[i]);
                /* at the end of the step that made them: on the grid, within two steps of the closed form's */
                assert_true(fabs(a.ev[i].t - b.ev[i].t) <= 1e-9);
                assert_true(fabs(a.ev[i].t / dt - round(a.ev[i].t / dt)) <= 1e-6);
                assert_true(fabs(a.ev[i].t - ref.t[i]) <= 2 * dt);
            }
        }
    }
}

/* Before yield the Jenkins spring is the linear spring's theta-scheme: the same samples to rounding. */
static void test_elastic_swing_is_the_linear_spring(void **state)
{
    (void)state;
    const char *fmt = "{\"model\":{\"mass\":1,\"spring\":%s,\"damper\":{\"law\":\"none\"},\"forcing\":{\"kind\":"
                      "\"constant\",\"value\":0.25}},\"initial\":{\"x\":0,\"v\":2},\"solver\":{\"kind\":\"stick-slip\","
                      "\"dt\":0.01,\"t_end\":0.5,\"theta\":0.5}}";
    char a[512], b[512];
    snprintf(a, sizeof a, fmt, "{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1}");
    snprintf(b, sizeof b, fmt, "{\"law\":\"linear\",\"k\":1}");
    traj ta, tb;
    assert_int_equal(traj_run(a, &ta), DP_OK);
    assert_int_equal(traj_run(b, &tb), DP_OK);
    assert_int_equal(ta.n, tb.n);
    for (size_t i = 0; i < ta.n; i++) {
        assert_true(fabs(ta.s[i].x - tb.s[i].x) <= 1e-13 && fabs(ta.s[i].v - tb.s[i].v) <= 1e-13);
        assert_true(fabs(ta.s[i].Fs - tb.s[i].Fs) <= 1e-13);
        assert_true(ta.s[i].plastic && ta.s[i].p == 0 && !tb.s[i].plastic);
    }
    assert_int_equal(ta.ne, 0);
    traj_free(&ta);
    traj_free(&tb);
}

/* A Jenkins spring beside a Coulomb damper under a slow harmonic load: the mass sticks at reversals while the
 * slider yields and unloads. With events "none" the one-mass inclusion solver and the network's active-set
 * solver (told not to locate them either) are separate codes for the same step; they agree on the whole
 * path and on every event. */
static void test_yielding_beside_sticking(void **state)
{
    (void)state;
    const char *one = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1},"
        "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5},\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":1.6,"
        "\"omega\":0.3,\"phase\":0}},\"initial\":{\"x\":0,\"v\":0},\"solver\":{\"kind\":\"stick-slip\","
        "\"dt\":0.01,\"t_end\":30,\"theta\":0.5,\"events\":\"none\"},\"output\":{\"every\":100}}";
    const char *net = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":"
        "\"elastoplastic\",\"k\":1,\"yield\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5}}],\"forcing\":"
        "[{\"node\":0,\"kind\":\"harmonic\",\"amplitude\":1.6,\"omega\":0.3,\"phase\":0}]},\"initial\":{\"x\":[0],"
        "\"v\":[0]},\"solver\":{\"kind\":\"stick-slip\",\"dt\":0.01,\"t_end\":30,\"theta\":0.5,\"events\":\"none\"},"
        "\"output\":{\"every\":100}}";
    traj a;
    assert_int_equal(traj_run(one, &a), DP_OK);
    assert_int_equal(a.status, DP_DONE);
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(net, strlen(net), 0, &spec, &errs);
    assert_int_equal(s, DP_OK);
    dp_run *run = dp_run_alloc(&spec, 0, &errs, &s);
    dp_spec_clear(&spec);
    assert_non_null(run);
    dp_record buf[64];
    size_t n, is = 0, ie = 0, kinds[5] = { 0 };
    do {
        s = dp_run_next(run, buf, 64, &n);
        for (size_t i = 0; i < n; i++) {
            if (buf[i].type == DP_RECORD_ROW) {   /* x, v, Fs, Fd, phase, p */
                const double *r = buf[i].u.row.val;
                assert_true(is < a.n);
                const dp_sample *o = &a.s[is++];
                assert_true(fabs(r[0] - o->x) <= 1e-9 && fabs(r[1] - o->v) <= 1e-9);
                assert_true(fabs(r[2] - o->Fs) <= 1e-9 && fabs(r[3] - o->Fd) <= 1e-9 && fabs(r[5] - o->p) <= 1e-9);
                assert_true(fabs(r[2]) <= 1 + 1e-12 && fabs(r[2] - (r[0] - r[5])) <= 1e-12);
            } else {
                const dp_event *e = &buf[i].u.event;
                assert_true(ie < a.ne);
                assert_int_equal(e->kind, a.e[ie].kind);
                assert_true(fabs(e->t - a.e[ie++].t) <= 1e-9);
                kinds[e->kind]++;
            }
        }
    } while (s == DP_MORE);
    assert_int_equal(s, DP_DONE);
    assert_int_equal(is, a.n);
    assert_int_equal(ie, a.ne);
    for (int k = DP_EVENT_STICK; k <= DP_EVENT_UNLOAD; k++)
        assert_true(kinds[k] >= 2);
    dp_run_free(run);
    traj_free(&a);
}

/* The same mass with every event located: the damper's stick and slip and the spring's yield and unload
 * met in time order inside the steps (a mass that stops while its slider slides unloads it at the same
 * instant). No closed form, so the order is measured by halving: the differences of x and p at T between
 * dt and dt/2 shrink by 4 per halving, and the event times move by O(dt^2). */
static void test_located_beside_sticking(void **state)
{
    (void)state;
    traj t[5];
    for (int i = 0; i < 5; i++) {
        char doc[1024];
        snprintf(doc, sizeof doc, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1},"
                 "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5},\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":1.6,"
                 "\"omega\":0.3,\"phase\":0}},\"initial\":{\"x\":0,\"v\":0},\"solver\":{\"kind\":\"stick-slip\","
                 "\"dt\":%.17g,\"t_end\":30,\"theta\":0.5},\"output\":{\"every\":1000000}}", 0.02 / (1 << i));
        assert_int_equal(traj_run(doc, &t[i]), DP_OK);
        assert_int_equal(t[i].status, DP_DONE);
    }
    size_t kinds[6] = { 0 };
    for (size_t j = 0; j < t[0].ne; j++) {
        kinds[t[0].e[j].kind]++;
        assert_true(j == 0 || t[0].e[j].t >= t[0].e[j - 1].t);
        if (t[0].e[j].kind == DP_EVENT_STICK && j + 1 < t[0].ne && t[0].e[j + 1].kind == DP_EVENT_UNLOAD)
            assert_true(fabs(t[0].e[j + 1].t - t[0].e[j].t) <= 1e-9);   /* stops: stick and unload at once */
    }
    for (int k = DP_EVENT_STICK; k <= DP_EVENT_UNLOAD; k++)
        assert_true(kinds[k] >= 2);
    double dx[4], dp[4];
    for (int i = 0; i < 4; i++) {
        const dp_sample *a = &t[i].sum.final, *b = &t[i + 1].sum.final;
        dx[i] = fabs(a->x - b->x), dp[i] = fabs(a->p - b->p);
        assert_int_equal(t[i].ne, t[0].ne);   /* the same events at every step */
        double dt = 0.02 / (1 << i), worst = 0;
        for (size_t j = 0; j < t[i].ne; j++) {
            assert_int_equal(t[i].e[j].kind, t[i + 1].e[j].kind);
            worst = fmax(worst, fabs(t[i].e[j].t - t[i + 1].e[j].t));
        }
        printf("beside sticking, dt = %g: events move by %.3g dt^2\n", dt, worst / (dt * dt));
        assert_true(worst <= dt * dt);
    }
    for (int i = 0; i < 3; i++) {
        printf("beside sticking: differences of x %.3e -> %.3e (ratio %.3f), of p %.3e -> %.3e (ratio %.3f)\n",
               dx[i], dx[i + 1], dx[i] / dx[i + 1], dp[i], dp[i + 1], dp[i] / dp[i + 1]);
        assert_true(dx[i] / dx[i + 1] >= 3.5 && dx[i] / dx[i + 1] <= 4.5);
        assert_true(dp[i] / dp[i + 1] >= 3.5 && dp[i] / dp[i + 1] <= 4.5);
    }
    for (int i = 0; i < 5; i++)
        traj_free(&t[i]);
}

/* No creep: a mass at rest stays exactly where it is, every step, with no event: held by a Coulomb damper
 * (the spring elastic, or at its yield force), or on the Jenkins spring alone in equilibrium (inside, or
 * exactly on the yield surface with the load at F_y), by stick-slip (theta = 1/2) and by newmark. */
static void test_no_creep(void **state)
{
    (void)state;
    static const struct { const char *spring, *damper; double F, x; int newmark, sticks; } rest[] = {
        { "", "{\"law\":\"coulomb\",\"phi0\":0.5}", 0.3, 0, 0, 1 },
        { ",\"offset\":-1", "{\"law\":\"coulomb\",\"phi0\":0.5}", 1.3, 0, 0, 1 },   /* F_s = F_y, held */
        { "", "{\"law\":\"none\"}", 0.5, 0.5, 0, 0 },
        { "", "{\"law\":\"none\"}", 1, 1, 0, 0 },                                     /* on the surface */
        { "", "{\"law\":\"none\"}", 0.5, 0.5, 1, 0 },
        { "", "{\"law\":\"none\"}", 1, 1, 1, 0 },
    };
    for (size_t c = 0; c < sizeof rest / sizeof *rest; c++) {
        char doc[1024];
        snprintf(doc, sizeof doc, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1%s},"
                 "\"damper\":%s,\"forcing\":{\"kind\":\"constant\",\"value\":%g}},\"initial\":{\"x\":%g,\"v\":0},"
                 "\"solver\":%s,\"output\":{\"every\":1}}", rest[c].spring, rest[c].damper, rest[c].F, rest[c].x,
                 rest[c].newmark ? "{\"kind\":\"newmark\",\"dt\":0.01,\"t_end\":100}"
                                 : "{\"kind\":\"stick-slip\",\"dt\":0.01,\"t_end\":100,\"theta\":0.5}");
        traj t;
        assert_int_equal(traj_run(doc, &t), DP_OK);
        assert_int_equal(t.status, DP_DONE);
        assert_int_equal(t.n, 10001);
        double p0 = t.s[0].p;
        for (size_t i = 0; i < t.n; i++)
            assert_true(t.s[i].x == rest[c].x && t.s[i].v == 0 && t.s[i].p == p0);
        assert_int_equal(t.ne, 0);
        if (rest[c].sticks)
            assert_true(fabs(t.sum.stick_time - 100) <= 1e-9);
        traj_free(&t);
    }
}

/* The well-posedness report: the Jenkins element is a stop operator, so with a maximal monotone damper the
 * motion exists and is unique (Brezis); a non-monotone damper beside it still fails its check. */
static void test_wellposedness_entry(void **state)
{
    (void)state;
    dp_model m = { .mass = 1, .spring = { .law = DP_SPRING_ELASTOPLASTIC, .k = 2, .yield = 1 },
                   .damper = { .law = DP_DAMPER_COULOMB, .phi0 = 0.3 } };
    assert_int_equal(dp_model_prepare(&m), DP_OK);
    dp_wp_report r;
    dp_wellposedness(&m, &r);
    assert_true(r.existence.guaranteed && r.uniqueness.guaranteed);
    assert_non_null(strstr(r.existence.theorem, "stop operator"));
    assert_non_null(strstr(r.check[0].name, "elastoplastic"));
    assert_true(r.check[0].holds);
    dp_model_clear(&m);
    dp_model g = { .mass = 1, .spring = { .law = DP_SPRING_ELASTOPLASTIC, .k = 2, .yield = 1 },
                   .damper = { .law = DP_DAMPER_GENERALIZED_COULOMB, .phi0 = 0.3, .phi1 = 0.5 } };
    assert_int_equal(dp_model_prepare(&g), DP_OK);
    dp_wellposedness(&g, &r);
    assert_false(r.uniqueness.guaranteed);
    assert_null(r.uniqueness.theorem);
    dp_model_clear(&g);
}

/* ---- bad input ----------------------------------------------------------------------------------------- */

static void expect_error(const char *json, const char *pointer, const char *needle)
{
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(json, strlen(json), 0, &spec, &errs);
    if (s == DP_OK) {
        dp_run *run = dp_run_alloc(&spec, 0, &errs, &s);
        assert_null(run);
    }
    int found = 0;
    for (size_t i = 0; i < errs.n; i++)
        found |= strcmp(errs.item[i].pointer, pointer) == 0 && strstr(errs.item[i].message, needle) != NULL;
    if (!found)
        for (size_t i = 0; i < errs.n; i++)
            fprintf(stderr, "error %s: %s\n", errs.item[i].pointer, errs.item[i].message);
    assert_true(found);
    dp_spec_clear(&spec);
}

static void test_bad_input(void **state)
{
    (void)state;
    expect_error("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":0},\"damper\":{\"law\":\"none\"}}}",
                 "/model/spring/yield", "> 0");
    expect_error("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":-2},\"damper\":{\"law\":\"none\"}}}",
                 "/model/spring/yield", "> 0");
    expect_error("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":0,\"yield\":1},\"damper\":{\"law\":\"none\"}}}",
                 "/model/spring/k", "> 0");
    expect_error("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1},\"damper\":{\"law\":\"none\"}}}",
                 "/model/spring/yield", "missing");
    expect_error("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1},"
                 "\"damper\":{\"law\":\"none\"}},\"solver\":{\"kind\":\"regularized\",\"n\":10}}", "/model/spring/law", "memory");
    expect_error("{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":"
                 "\"elastoplastic\",\"k\":1,\"yield\":1}}]},\"initial\":{\"x\":[0],\"v\":[0]},"
                 "\"solver\":{\"kind\":\"regularized\",\"n\":10}}", "/model/elements/0/spring/law", "memory");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_monotonic_loading),
        cmocka_unit_test(test_cycle_area_is_plastic_work),
        cmocka_unit_test(test_shakedown),
        cmocka_unit_test(test_elastic_swing_is_the_linear_spring),
        cmocka_unit_test(test_located_events_second_order),
        cmocka_unit_test(test_located_events_theta_one),
        cmocka_unit_test(test_newmark_located_second_order),
        cmocka_unit_test(test_located_events_any_phase_of_the_step),
        cmocka_unit_test(test_unlocated_one_mass_is_the_network),
        cmocka_unit_test(test_yielding_beside_sticking),
        cmocka_unit_test(test_located_beside_sticking),
        cmocka_unit_test(test_no_creep),
        cmocka_unit_test(test_wellposedness_entry),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
