/* tests/test_network_smooth.c - spring graphs of finite slope on networks (network_smooth.c): a compliant
 * contact and a "graph" spring without a vertical piece are stepped by the theta-rule on their force and
 * their vertices are located inside the step. Checked against a closed form (a ball bouncing on a compliant
 * floor: free flight and a half turn of a linear oscillator, alternately), against the same network at
 * dt/64, and by the rules and the meta line; theta = 1/2 stays second order through the touch and the
 * separation (errors fall by about 4 per halving of dt; with events "none" they wander). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "dashpot/run.h"
#include "rows.h"

#define G 9.81



/* ---- a ball on a compliant floor: the closed form -------------------------------------------------- */

/* A unit mass dropped from x = 1 at rest onto a floor of compliance k at x = 0 under gravity g: it falls
 * for t1 = sqrt(2/g), arrives at v1 = sqrt(2 g), then x'' + w^2 x = -g (w^2 = k) for a contact time
 * Tc = (pi + 2 atan(g / (w v1))) / w, leaves at v1 (the force is elastic) and flies back to x = 1: the
 * motion is periodic with period 2 t1 + Tc. */
static double ball_x(double t, double k)
{
    double w = sqrt(k), t1 = sqrt(2 / G), v1 = sqrt(2 * G), Tc = (M_PI + 2 * atan(G / (w * v1))) / w;
    t = fmod(t, 2 * t1 + Tc);
    if (t <= t1)
        return 1 - 0.5 * G * t * t;
    if (t <= t1 + Tc) {
        double s = t - t1;
        return G / k * (cos(w * s) - 1) - v1 / w * sin(w * s);
    }
    double s = t - t1 - Tc;
    return v1 * s - 0.5 * G * s * s;
}

static void ball_doc(char *json, size_t len, double dt, double k, const char *events)
{
    snprintf(json, len, "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"contact\":"
             "{\"distance\":0,\"compliance\":%.17g}}],\"forcing\":[{\"node\":0,\"kind\":\"constant\",\"value\":-%g}]},"
             "\"initial\":{\"x\":[1],\"v\":[0]},\"solver\":{\"kind\":\"stick-slip\",\"dt\":%.17g,\"t_end\":1.2,"
             "\"theta\":0.5,\"events\":\"%s\"},\"output\":{\"every\":%ld}}", k, G, dt, events, lround(0.05 / dt));
}

/* The largest error of x over the samples (every 0.05) against the closed form. */
static double ball_error(double dt, double k, const char *events, rows *r)
{
    char json[1024];
    ball_doc(json, sizeof json, dt, k, events);
    assert_int_equal(rows_collect(json, 128, r), DP_DONE);
    double worst = 0;
    for (size_t i = 0; i < r->n; i++) {
        const double *row = r->d + i * r->width;
        worst = fmax(worst, fabs(row[1] - ball_x(row[0], k)));
    }
    return worst;
}

static void test_compliant_ball_is_second_order(void **state)
{
    (void)state;
    char json[1024];
    ball_doc(json, sizeof json, 1e-3, 1e4, "locate");
    rows_assert_events_mode(json, "locate");
    for (int stiff = 0; stiff < 2; stiff++) {
        double k = stiff ? 1e6 : 1e4, e[5], f[5];
        for (int i = 0; i < 5; i++) {
            rows r;
            e[i] = ball_error(1e-3 / (1 << i), k, "locate", &r);
            free(r.d);
            f[i] = ball_error(1e-3 / (1 << i), k, "none", &r);
            free(r.d);
        }
        int wandering = 0;
        for (int i = 0; i + 1 < 5; i++) {
            fprintf(stderr, "  k %g dt %g: located %.3e ratio %.3f; events none %.3e ratio %.3f\n", k,
                    1e-3 / (1 << i), e[i], e[i] / e[i + 1], f[i], f[i] / f[i + 1]);
            /* k = 1e6 at dt = 1e-3: w dt = 1, the first halving is not yet asymptotic */
            if (!(stiff && i == 0))
                assert_true(e[i] / e[i + 1] > 3.7 && e[i] / e[i + 1] < 4.3);
            wandering |= f[i] / f[i + 1] < 3 || f[i] / f[i + 1] > 5;
        }
        assert_true(wandering);
        assert_true(e[4] < (stiff ? 5e-6 : 5e-7));
    }
}

/* The touch and the separation are events of the contact's element at the closed form's instants (the
 * root's tolerance); events "none" writes them at the ends of their steps. */
static void test_compliant_touch_events(void **state)
{
    (void)state;
    double k = 1e4, w = sqrt(k), t1 = sqrt(2 / G), v1 = sqrt(2 * G), Tc = (M_PI + 2 * atan(G / (w * v1))) / w;
    double when[2] = { t1, t1 + Tc };    /* the next touch, 3 t1 + Tc, is after t_end */
    rows r;
    ball_error(1e-3, k, "locate", &r);
    assert_int_equal(r.events, 2);
    for (size_t i = 0; i < 2; i++) {
        assert_int_equal(r.ev[i].kind, i == 1 ? DP_EVENT_SEPARATE : DP_EVENT_TOUCH);
        assert_int_equal(r.ev[i].element, 0);
        /* the touch ends free flight, exact for the trapezoidal rule; the separation carries the contact
         * phase's error, (w dt)^2 / 12 of the contact time Tc (2.7e-5 here) */
        double tol = i == 0 ? 1e-12 : 1.2 * w * w * 1e-6 / 12 * Tc;
        if (fabs(r.ev[i].t - when[i]) > tol)
            fprintf(stderr, "event %zu at %.17g, closed form %.17g\n", i, r.ev[i].t, when[i]);
        assert_true(fabs(r.ev[i].t - when[i]) <= tol);
        assert_true(fabs(r.ev[i].x) <= 1e-12);             /* at the floor */
        assert_true(i == 1 ? r.ev[i].v > 0 : r.ev[i].v < 0);
    }
    free(r.d);
    /* theta = 1 (backward Euler: the instants first order) locates them too, at the floor */
    char json[1024];
    ball_doc(json, sizeof json, 1e-3, k, "locate");
    char *th = strstr(json, "\"theta\":0.5");
    assert_non_null(th);
    memcpy(th, "\"theta\":1  ", 11);
    assert_int_equal(rows_collect(json, 128, &r), DP_DONE);
    assert_int_equal(r.events, 2);
    for (size_t i = 0; i < 2; i++) {
        double steps = r.ev[i].t / 1e-3;
        assert_true(fabs(r.ev[i].x) <= 1e-12 && fabs(steps - round(steps)) > 1e-3);
        assert_true(fabs(r.ev[i].t - when[i]) < 2e-3);
    }
    free(r.d);
    ball_error(1e-3, k, "none", &r);
    assert_int_equal(r.events, 2);
    for (size_t i = 0; i < 2; i++) {
        double steps = r.ev[i].t / 1e-3;
        assert_true(fabs(steps - round(steps)) < 1e-6);   /* a step's end */
        assert_true(r.ev[i].t >= when[i] && r.ev[i].t < when[i] + 1e-3 + 1e-12);
    }
    free(r.d);
}

/* ---- one node on a bilinear spring: the closed form -------------------------------------------------- */

/* A unit mass on the graph spring F = u (u >= 0), 2u (u < 0), from x = 1 at rest: a quarter turn at w = 1 to
 * x = 0 at speed 1, half a turn at w = sqrt 2 below (amplitude 1/sqrt 2), a quarter turn back to x = 1: the
 * period is pi + pi / sqrt 2. (A one-node network of such a spring below theta = 1 steps on the network
 * solver, network_check.c, whose theta-rule is the one-mass solver's missing half.) */
static double bilinear_x(double t)
{
    double r2 = sqrt(2.0), T = M_PI + M_PI / r2;
    t = fmod(t, T);
    if (t <= M_PI / 2)
        return cos(t);
    if (t <= M_PI / 2 + M_PI / r2)
        return -sin(r2 * (t - M_PI / 2)) / r2;
    return -cos(t - M_PI / r2);      /* cos of the phase past the lower half turn, from -pi/2 */
}

static double bilinear_error(double dt, const char *events)
{
    char json[1024];
    snprintf(json, sizeof json, "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":"
             "{\"law\":\"graph\",\"points\":[[-1,-2],[0,0],[1,1]]}}]},\"initial\":{\"x\":[1],\"v\":[0]},"
             "\"solver\":{\"dt\":%.17g,\"t_end\":10,\"theta\":0.5,\"events\":\"%s\"},\"output\":{\"every\":%ld}}",
             dt, events, lround(0.5 / dt));
    if (strcmp(events, "locate") == 0)
        rows_assert_events_mode(json, "locate");
    rows r;
    assert_int_equal(rows_collect(json, 128, &r), DP_DONE);
    double worst = 0;
    for (size_t i = 0; i < r.n; i++)
        worst = fmax(worst, fabs(r.d[i * r.width + 1] - bilinear_x(r.d[i * r.width])));
    free(r.d);
    return worst;
}

static void test_bilinear_node_is_second_order(void **state)
{
    (void)state;
    double e[4], f[4];
    for (int i = 0; i < 4; i++) {
        e[i] = bilinear_error(0.02 / (1 << i), "locate");
        f[i] = bilinear_error(0.02 / (1 << i), "none");
    }
    for (int i = 0; i + 1 < 4; i++) {
        fprintf(stderr, "  dt %g: located %.3e ratio %.3f; events none %.3e ratio %.3f\n", 0.02 / (1 << i), e[i],
                e[i] / e[i + 1], f[i], f[i] / f[i + 1]);
        assert_true(e[i] / e[i + 1] > 3.8 && e[i] / e[i + 1] < 4.2);
    }
    assert_true(e[0] < 1e-3);
}

/* The same spring as a one-mass document at theta = 1/2 is the one-node network it is (the one-mass solver
 * takes backward Euler only): the same rows, bit for bit; so is a rope with events located. A graph with a
 * vertical piece or a rope, with events "none", is still refused at /solver/theta. */
static void test_one_mass_document_is_the_network(void **state)
{
    (void)state;
    const char *net = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":"
                      "\"graph\",\"points\":[[-1,-2],[0,0],[1,1]]},\"damper\":{\"law\":\"coulomb\",\"phi0\":0.2}}]},"
                      "\"initial\":{\"x\":[1],\"v\":[0]},\"solver\":{\"dt\":0.01,\"t_end\":5,\"theta\":0.5}}";
    const char *one = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"graph\",\"points\":[[-1,-2],[0,0],[1,1]]},"
                      "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.2}},\"initial\":{\"x\":1,\"v\":0},"
                      "\"solver\":{\"dt\":0.01,\"t_end\":5,\"theta\":0.5}}";
    rows a, b;
    assert_int_equal(rows_collect(net, 128, &a), DP_DONE);
    assert_int_equal(rows_collect(one, 128, &b), DP_DONE);
    assert_int_equal(a.n, 501);
    assert_int_equal(a.n, b.n);
    assert_int_equal(a.width, b.width);
    assert_memory_equal(a.d, b.d, a.n * a.width * sizeof *a.d);
    assert_int_equal(a.events, b.events);
    free(a.d), free(b.d);
    /* a rope with events located likewise (a linear spring and the contact u <= L on the network) */
    const char *rope_net = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":"
                           "{\"law\":\"rope\",\"k\":1,\"length\":1},\"damper\":{\"law\":\"none\"}}]},\"initial\":"
                           "{\"x\":[0],\"v\":[2]},\"solver\":{\"dt\":0.01,\"t_end\":3,\"theta\":0.5}}";
    const char *rope_one = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"rope\",\"k\":1,\"length\":1},\"damper\":"
                           "{\"law\":\"none\"}},\"initial\":{\"x\":0,\"v\":2},\"solver\":{\"dt\":0.01,\"t_end\":3,"
                           "\"theta\":0.5}}";
    assert_int_equal(rows_collect(rope_net, 128, &a), DP_DONE);
    assert_int_equal(rows_collect(rope_one, 128, &b), DP_DONE);
    assert_int_equal(a.n, 301);
    assert_int_equal(a.n, b.n);
    assert_int_equal(a.width, b.width);
    assert_memory_equal(a.d, b.d, a.n * a.width * sizeof *a.d);
    assert_int_equal(a.events, 1);     /* taut at pi/6, to the trapezoidal rule's phase error */
    assert_int_equal(b.ev[0].kind, DP_EVENT_IMPACT);
    assert_true(fabs(b.ev[0].t - M_PI / 6) < 1e-5);
    free(a.d), free(b.d);
    char ptr[DP_POINTER_MAX] = "";
    assert_int_not_equal(rows_verdict("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"rope\",\"k\":1,\"length\":2},"
                                   "\"damper\":{\"law\":\"none\"}},\"initial\":{\"x\":1,\"v\":0},\"solver\":{\"dt\":0.01,"
                                   "\"t_end\":1,\"theta\":0.5,\"events\":\"none\"}}", ptr, sizeof ptr), DP_OK);
    assert_string_equal(ptr, "/solver/theta");
    assert_int_not_equal(rows_verdict("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"graph\",\"points\":[[-1,-1],[0,0],"
                                   "[0,1],[1,2]]},\"damper\":{\"law\":\"none\"}},\"initial\":{\"x\":1,\"v\":0},\"solver\":"
                                   "{\"dt\":0.01,\"t_end\":1,\"theta\":0.5,\"events\":\"none\"}}", ptr, sizeof ptr), DP_OK);
    assert_string_equal(ptr, "/solver/theta");
}

/* An element with a rope and a compliant contact: its contact's touch and separation are written once each
 * (the rope's constraint on the same element was taken for a second compliant contact: four events). */
static void test_compliant_contact_beside_a_rope(void **state)
{
    (void)state;
    const char *json = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":"
                       "\"rope\",\"k\":1,\"length\":2},\"contact\":{\"distance\":0,\"compliance\":1e4}}],\"forcing\":"
                       "[{\"node\":0,\"kind\":\"constant\",\"value\":-9.81}]},\"initial\":{\"x\":[1],\"v\":[0]},"
                       "\"solver\":{\"dt\":0.001,\"t_end\":0.6},\"output\":{\"every\":1000}}";
    rows r;
    assert_int_equal(rows_collect(json, 128, &r), DP_DONE);
    assert_int_equal(r.events, 2);
    assert_int_equal(r.ev[0].kind, DP_EVENT_TOUCH);
    assert_int_equal(r.ev[1].kind, DP_EVENT_SEPARATE);
    free(r.d);
}

/* ---- a chain with a kinked graph spring against itself at dt/64 ------------------------------------- */

/* Two blocks: a stiffening graph spring (slope 1, then 4 past |u| = 0.3) with Coulomb friction on a belt
 * (phi0 = 1.5, at 0.1) on [ground, 0] (so that element has a damper vertex and spring vertices both), a linear spring between
 * them, and a compliant stop the second block hits (u of [ground, 1] kept >= -0.6); a harmonic load (3 sin 0.9 t)
 * on node 1, to t = 10, sampled every 0.5. */
static void chain_doc(char *json, size_t len, double dt, const char *events)
{
    snprintf(json, len, "{\"model\":{\"masses\":[1,1.5],\"elements\":["
             "{\"between\":[\"ground\",0],\"spring\":{\"law\":\"graph\",\"points\":[[-1,-2.4],[-0.3,-0.3],[0.3,0.3],"
             "[1,3.1]]},\"damper\":{\"law\":\"coulomb\",\"phi0\":1.5,\"belt_velocity\":0.1}},"
             "{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":2}},"
             "{\"between\":[\"ground\",1],\"contact\":{\"distance\":-0.6,\"compliance\":200}}],"
             "\"forcing\":[{\"node\":1,\"kind\":\"harmonic\",\"amplitude\":3,\"omega\":0.9}]},"
             "\"initial\":{\"x\":[0.5,-0.2]},\"solver\":{\"dt\":%.17g,\"t_end\":10,\"theta\":0.5,"
             "\"events\":\"%s\"},\"output\":{\"every\":%ld}}", dt, events, lround(0.5 / dt));
}

static double chain_error(double dt, const char *events, const rows *ref)
{
    char json[2048];
    chain_doc(json, sizeof json, dt, events);
    rows r;
    assert_int_equal(rows_collect(json, 128, &r), DP_DONE);
    double worst = rows_max_difference(&r, ref, 1, 5);
    free(r.d);
    return worst;
}

static void test_graph_spring_chain_is_second_order(void **state)
{
    (void)state;
    char json[2048];
    chain_doc(json, sizeof json, 0.0025 / 64, "locate");
    rows_assert_events_mode(json, "locate");
    rows ref;
    assert_int_equal(rows_collect(json, 128, &ref), DP_DONE);
    size_t kinds[11] = { 0 };
    for (size_t i = 0; i < ref.events; i++)
        kinds[ref.ev[i].kind]++;
    fprintf(stderr, "  reference: %zu stick, %zu slip, %zu touch, %zu separate\n", kinds[DP_EVENT_STICK],
            kinds[DP_EVENT_SLIP], kinds[DP_EVENT_TOUCH], kinds[DP_EVENT_SEPARATE]);
    assert_true(kinds[DP_EVENT_STICK] >= 2 && kinds[DP_EVENT_TOUCH] >= 1 && kinds[DP_EVENT_SEPARATE] >= 1);
    /* the spring crosses its kinks at 0.3 and -0.3 in the reference */
    int above = 0, below = 0;
    for (size_t i = 0; i < ref.n; i++)
        above |= ref.d[i * ref.width + 1] > 0.35, below |= ref.d[i * ref.width + 1] < -0.35;
    assert_true(above && below);
    double e[4], f[4];
    for (int i = 0; i < 4; i++) {
        e[i] = chain_error(0.02 / (1 << i), "locate", &ref);
        f[i] = chain_error(0.02 / (1 << i), "none", &ref);
    }
    for (int i = 0; i + 1 < 4; i++) {
        fprintf(stderr, "  dt %g: located %.3e ratio %.3f; events none %.3e ratio %.3f\n", 0.02 / (1 << i), e[i],
                e[i] / e[i + 1], f[i], f[i] / f[i + 1]);
        assert_true(e[i] / e[i + 1] > 3.5 && e[i] / e[i + 1] < 4.5);
    }
    assert_true(f[0] / f[3] < 0.5 * e[0] / e[3]);
    free(ref.d);
}

/* ---- a graph spring whose domain ends in a stop ------------------------------------------------------------ */

/* One node on `spring` (and `extra` elements) under a harmonic load, theta = 1/2, events located. */
static void stop_run(const char *spring, const char *extra, double v0, double dt, rows *r)
{
    char json[1536];
    snprintf(json, sizeof json, "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":%s}"
             "%s],\"forcing\":[{\"node\":0,\"kind\":\"harmonic\",\"amplitude\":1.5,\"omega\":1.3}]},\"initial\":"
             "{\"x\":[0],\"v\":[%g]},\"solver\":{\"dt\":%.17g,\"t_end\":6,\"theta\":0.5},\"output\":{\"every\":%ld}}",
             spring, extra, v0, dt, lround(0.25 / dt));
    rows_assert_events_mode(json, "locate");
    assert_int_equal(rows_collect(json, 128, r), DP_DONE);
}

/* Two runs that must agree to the discretization's error at dt = 0.01 (the graph's sloped part is
 * theta-stepped with its vertices located, the linear spring is not split there: 1e-7 apart): every sample's
 * x and v, every event's kind, time and impulse. */
static void assert_stop_runs_agree(const rows *a, const rows *b)
{
    assert_true(rows_max_difference(a, b, 1, 3) < 1e-6);
    assert_int_equal(a->events, b->events);
    for (size_t i = 0; i < a->events; i++) {
        assert_int_equal(a->ev[i].kind, DP_EVENT_IMPACT);
        assert_int_equal(b->ev[i].kind, DP_EVENT_IMPACT);
        assert_true(fabs(a->ev[i].t - b->ev[i].t) < 1e-6 && fabs(a->ev[i].impulse - b->ev[i].impulse) < 1e-6);
    }
}

/* The graph [[0, 0], [1, 1], [1, 2]] (slope 1, a vertical end at u = 1) is the rope of k = 1, L = 1; the graph
 * [[-0.5, -3], [-0.5, -0.5], [1, 1]] (a vertical start at u = -0.5) is a linear spring k = 1 with a plastic
 * rigid stop u >= -0.5, whose force the graph's Fs carries (the stop's own Fn with the contact). */
static void test_bounded_graph_is_a_rope_and_a_stop(void **state)
{
    (void)state;
    rows a, b;
    stop_run("{\"law\":\"graph\",\"points\":[[0,0],[1,1],[1,2]]}", "", 2, 0.01, &a);
    stop_run("{\"law\":\"rope\",\"k\":1,\"length\":1}", "", 2, 0.01, &b);
    assert_true(a.events >= 2);
    assert_stop_runs_agree(&a, &b);
    free(a.d), free(b.d);
    stop_run("{\"law\":\"graph\",\"points\":[[-0.5,-3],[-0.5,-0.5],[1,1]]}", "", -2, 0.01, &a);
    stop_run("{\"law\":\"linear\",\"k\":1}", ",{\"between\":[\"ground\",0],\"contact\":{\"distance\":-0.5,"
             "\"restitution\":0}}", -2, 0.01, &b);
    assert_true(a.events >= 2);
    assert_stop_runs_agree(&a, &b);
    /* rows: a t x v Fs Fd phase; b t x v Fs[2] Fd[2] phase[2] Fn[2] */
    for (size_t i = 0; i < a.n; i++) {
        const double *ra = a.d + i * a.width, *rb = b.d + i * b.width;
        assert_true(fabs(ra[3] - (rb[3] + rb[10])) < 1e-5);
    }
    free(a.d), free(b.d);
}

/* Both stops and a curved inside, thrown out: theta = 1/2 stays second order through every stop reached
 * (errors against dt/64 fall by about 4 per halving). */
static void test_bounded_graph_is_second_order(void **state)
{
    (void)state;
    const char *g = "{\"law\":\"graph\",\"points\":[[-0.6,-5],[-0.6,-1],[0,0],[0.4,0.2],[0.8,1.2],[0.8,4]]}";
    rows ref;
    stop_run(g, "", 2, 0.003125 / 64, &ref);
    size_t ends[2] = { 0, 0 };
    for (size_t i = 0; i < ref.events; i++)
        ends[ref.ev[i].x > 0]++;
    fprintf(stderr, "  reference: %zu impacts at the lower stop, %zu at the upper\n", ends[0], ends[1]);
    assert_true(ends[0] >= 1 && ends[1] >= 1);
    double e[4];
    for (int k = 0; k < 4; k++) {
        rows r;
        stop_run(g, "", 2, 0.025 / (1 << k), &r);
        e[k] = rows_max_difference(&r, &ref, 1, 3);
        free(r.d);
    }
    for (int k = 0; k + 1 < 4; k++) {
        fprintf(stderr, "  dt %g: error %.3e ratio %.3f\n", 0.025 / (1 << k), e[k], e[k] / e[k + 1]);
        assert_true(e[k] / e[k + 1] > 3.5 && e[k] / e[k + 1] < 4.5);
    }
    free(ref.d);
}

/* ---- a graph spring with a jump (a preload) ------------------------------------------------------------------ */

/* The preloaded spring F = u + 0.5 sgn u ([[-1, -1.5], [0, -0.5], [0, 0.5], [1, 1.5]]: a jump of 1 at u = 0) on
 * a unit mass from x = 2 at rest: x = -0.5 + 2.5 cos t to x = 0 at t1 = acos 0.2, then the mirror image up to
 * x = -2 at 2 t1, and the half period again with the sign changed (period 4 t1; the energy
 * v^2/2 + x^2/2 + |x|/2 = 3 is kept). */
static double preload_x(double t)
{
    double t1 = acos(0.2), half = 2 * t1;
    double s = fmod(t, 2 * half), sign = s < half ? 1 : -1;
    s = s < half ? s : s - half;
    return sign * (s <= t1 ? -0.5 + 2.5 * cos(s) : 0.5 - 2.5 * cos(half - s));
}

static void preload_doc(char *json, size_t len, double dt, double x0, const char *load, double t_end)
{
    snprintf(json, len, "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":"
             "\"graph\",\"points\":[[-1,-1.5],[0,-0.5],[0,0.5],[1,1.5]]}}]%s},\"initial\":{\"x\":[%g],\"v\":[0]},"
             "\"solver\":{\"dt\":%.17g,\"t_end\":%g,\"theta\":0.5},\"output\":{\"every\":%ld}}", load, x0, dt, t_end,
             lround(0.25 / dt));
}

/* Against the closed form the error falls by about 4 per halving of dt through the jump's crossings (the
 * jump an entry of its own, its crossing located, network_run.c), and the energy is kept. */
static void test_preloaded_spring_is_second_order(void **state)
{
    (void)state;
    char json[1024];
    double e[4];
    for (int k = 0; k < 4; k++) {
        preload_doc(json, sizeof json, 0.02 / (1 << k), 2, "", 10);
        rows_assert_events_mode(json, "locate");
        rows r;
        assert_int_equal(rows_collect(json, 128, &r), DP_DONE);
        e[k] = 0;
        for (size_t i = 0; i < r.n; i++) {
            const double *row = r.d + i * r.width;
            e[k] = fmax(e[k], fabs(row[1] - preload_x(row[0])));
            if (k == 3)   /* the energy, to the scheme's error */
                assert_true(fabs(row[2] * row[2] / 2 + row[1] * row[1] / 2 + fabs(row[1]) / 2 - 3) < 1e-4);
        }
        free(r.d);
    }
    for (int k = 0; k + 1 < 4; k++) {
        fprintf(stderr, "  dt %g: error %.3e ratio %.3f\n", 0.02 / (1 << k), e[k], e[k] / e[k + 1]);
        assert_true(e[k] / e[k + 1] > 3.5 && e[k] / e[k + 1] < 4.5);
    }
}

/* At the jump at rest under a load inside its interval (0.3 < 0.5) the mass stays at x = 0 to the bit, the
 * spring's force the load's; a load past it (0.8) moves it at once, x = 0.3 (1 - cos t) (the closed form). */
static void test_preloaded_spring_holds_and_lets_go(void **state)
{
    (void)state;
    char json[1024];
    rows r;
    preload_doc(json, sizeof json, 0.01, 0, ",\"forcing\":[{\"node\":0,\"kind\":\"constant\",\"value\":0.3}]", 5);
    assert_int_equal(rows_collect(json, 128, &r), DP_DONE);
    for (size_t i = 0; i < r.n; i++) {
        const double *row = r.d + i * r.width;   /* t x v Fs Fd phase */
        assert_true(row[1] == 0 && row[2] == 0);
        assert_true(i == 0 || fabs(row[3] - 0.3) < 1e-14);
    }
    free(r.d);
    preload_doc(json, sizeof json, 0.01, 0, ",\"forcing\":[{\"node\":0,\"kind\":\"constant\",\"value\":0.8}]", 2);
    assert_int_equal(rows_collect(json, 128, &r), DP_DONE);
    for (size_t i = 0; i < r.n; i++) {
        const double *row = r.d + i * r.width;
        assert_true(fabs(row[1] - 0.3 * (1 - cos(row[0]))) < 1e-5);
    }
    free(r.d);
}

/* ---- no creep -------------------------------------------------------------------------------------------- */

/* A block (node 1) pressed by a compliant contact onto another (node 0) that rings on a compliant floor, held
 * by Coulomb friction to the ground: both contacts start pressed (allowed for a compliant one), the lower
 * block oscillates for ever (the trapezoidal rule does not damp it), and the upper one, once stuck, keeps its
 * position to the last bit while the force through its contact changes every step. */
static void test_stuck_block_on_compliant_contact_does_not_creep(void **state)
{
    (void)state;
    const char *json = "{\"model\":{\"masses\":[1,1],\"elements\":[{\"between\":[\"ground\",0],\"contact\":"
                       "{\"distance\":0,\"compliance\":1e4}},{\"between\":[0,1],\"contact\":{\"distance\":0.5,"
                       "\"compliance\":1e3}},{\"between\":[\"ground\",1],\"damper\":{\"law\":\"coulomb\",\"phi0\":0.3}}],"
                       "\"forcing\":[{\"node\":0,\"kind\":\"constant\",\"value\":-9.81},{\"node\":1,\"kind\":"
                       "\"constant\",\"value\":-9.81}]},\"initial\":{\"x\":[-0.001962,0.49019],\"v\":[0,0]},"
                       "\"solver\":{\"dt\":0.001,\"t_end\":20},\"output\":{\"every\":100}}";
    rows_assert_events_mode(json, "locate");
    rows r;
    assert_int_equal(rows_collect(json, 128, &r), DP_DONE);
    assert_int_equal(r.events, 1);
    assert_int_equal(r.ev[0].kind, DP_EVENT_STICK);
    assert_int_equal(r.ev[0].element, 2);
    size_t after = 0, moved = 0;
    double held = NAN, fn_lo = INFINITY, fn_hi = -INFINITY;
    for (size_t i = 0; i < r.n; i++) {
        const double *row = r.d + i * r.width;   /* t, x0 x1, v0 v1, Fs[3], Fd[3], phase[3], Fn[3] */
        if (row[0] <= r.ev[0].t)
            continue;
        if (after++ == 0)
            held = row[2];
        moved += row[2] != held || row[4] != 0;
        fn_lo = fmin(fn_lo, row[15]), fn_hi = fmax(fn_hi, row[15]);
    }
    assert_true(after > 190);
    assert_int_equal(moved, 0);
    assert_true(fn_hi - fn_lo > 0.1);    /* the contact's force moves while the block does not */
    free(r.d);
}

/* Two networks (from random documents) whose backward-Euler graph springs (events "none") end steps held
 * at a stop: the next step saw the elongation past the stop by rounding, no feasible point, and the run
 * ended "the implicit step has no solution" (network_stepping.c now puts it back at the stop). */
static void test_rounding_past_a_stop_is_put_back(void **state)
{
    (void)state;
    static const char *const docs[] = {   /* ' for " */
        "{'model':{'masses':[0.5,1,1,0.5],'elements':[{'between':['ground',0],'spring':{'law':'graph','points"
        "':[[-0.403,-0.141],[0.158,1.994],[0.672,2.575]]}},{'between':['ground',1],'spring':{'law':'linear','"
        "k':0.5}},{'between':['ground',2],'damper':{'law':'linear','c':0.3}},{'between':['ground',3],'spring'"
        ":{'law':'linear','k':10},'damper':{'law':'coulomb','phi0':0.3,'belt_velocity':0}},{'between':['groun"
        "d',0],'spring':{'law':'graph','points':[[-1.058,-1.132],[-0.392,1.23],[0.545,4.077]]}},{'between':[0"
        ",3],'spring':{'law':'graph','points':[[-0.8,-4],[-0.8,-1.5],[0,0],[0.9,1.2],[0.9,5]]}}],'forcing':[{"
        "'node':2,'kind':'harmonic','amplitude':0.5,'omega':0.7}]},'initial':{'x':[0.242,-0.241,0.122,0.15],'"
        "v':[-0.915,-0.018,0.99,-0.734]},'solver':{'dt':0.003,'t_end':5,'theta':1,'events':'none'},'output':{"
        "'every':100}}",
        "{'model':{'masses':[0.5,2,1,2],'elements':[{'between':['ground',0],'damper':{'law':'coulomb','phi0':"
        "0.8,'belt_velocity':0.1}},{'between':['ground',1],'damper':{'law':'linear','c':0.3}},{'between':['gr"
        "ound',2],'spring':{'law':'graph','points':[[-0.838,-1.066],[-0.038,0.009],[0.309,1.808],[0.345,4.39]"
        "]},'damper':{'law':'coulomb','phi0':0.8,'belt_velocity':0.1}},{'between':['ground',3],'spring':{'law"
        "':'graph','points':[[-0.883,-0.738],[0.888,1.919]]},'damper':{'law':'linear','c':0.05}},{'between':["
        "0,1],'contact':{'distance':-0.325,'compliance':1000.0}},{'between':[3,'ground'],'contact':{'distance"
        "':-1.065,'compliance':10}},{'between':[0,3],'spring':{'law':'rope','k':2,'length':0.8}}],'forcing':["
        "{'node':0,'kind':'harmonic','amplitude':5,'omega':5}]},'initial':{'x':[0.019,0.234,0.06,-0.278],'v':"
        "[-0.524,0.724,-0.277,0.15]},'solver':{'dt':0.01,'t_end':5,'theta':1,'events':'none'},'output':{'ever"
        "y':100}}",
    };
    for (size_t i = 0; i < 2; i++) {
        char *json = strdup(docs[i]);
        assert_non_null(json);
        for (char *c = json; *c; c++)
            *c = *c == '\'' ? '"' : *c;
        rows r;
        assert_int_equal(rows_collect(json, 128, &r), DP_DONE);
        assert_int_equal(r.n, i == 0 ? 18 : 6);
        free(r.d), free(json);
    }
}

/* ---- the rules --------------------------------------------------------------------------------------- */


/* theta = 1/2 is accepted for a compliant contact and a sloped graph spring, and for a graph with a vertical
 * piece with events located (split); without, such a graph needs theta = 1, named at its spring. */
static void test_theta_rule(void **state)
{
    (void)state;
    char json[1024], ptr[DP_POINTER_MAX] = "";
    const char *springs[3] = { "[[-1,-2],[0,0],[1,1]]", "[[-1,-2],[0,0],[0,1],[1,2]]", NULL };
    for (int i = 0; springs[i]; i++) {
        snprintf(json, sizeof json, "{\"model\":{\"masses\":[1,1],\"elements\":[{\"between\":[\"ground\",0],"
                 "\"spring\":{\"law\":\"graph\",\"points\":%s}},{\"between\":[0,1],\"spring\":{\"law\":\"linear\","
                 "\"k\":1},\"contact\":{\"distance\":-1,\"compliance\":10}}]},\"initial\":{\"x\":[0.5,0]},"
                 "\"solver\":{\"dt\":0.01,\"t_end\":1,\"theta\":0.5,\"events\":\"%s\"}}", springs[i],
                 i == 0 ? "locate" : "none");
        ptr[0] = 0;
        int s = rows_verdict(json, ptr, sizeof ptr);
        if (i == 0) {
            assert_int_equal(s, DP_OK);
            rows_assert_events_mode(json, "locate");
        } else {
            assert_int_not_equal(s, DP_OK);
            assert_string_equal(ptr, "/model/elements/0/spring");
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_compliant_ball_is_second_order),
        cmocka_unit_test(test_compliant_touch_events),
        cmocka_unit_test(test_compliant_contact_beside_a_rope),
        cmocka_unit_test(test_bilinear_node_is_second_order),
        cmocka_unit_test(test_one_mass_document_is_the_network),
        cmocka_unit_test(test_graph_spring_chain_is_second_order),
        cmocka_unit_test(test_bounded_graph_is_a_rope_and_a_stop),
        cmocka_unit_test(test_bounded_graph_is_second_order),
        cmocka_unit_test(test_preloaded_spring_is_second_order),
        cmocka_unit_test(test_preloaded_spring_holds_and_lets_go),
        cmocka_unit_test(test_stuck_block_on_compliant_contact_does_not_creep),
        cmocka_unit_test(test_rounding_past_a_stop_is_put_back),
        cmocka_unit_test(test_theta_rule),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
