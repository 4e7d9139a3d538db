/* tests/test_contact.c - unilateral contacts and impacts (systems.md §4) against closed forms:
 * the bouncing ball's impact times, rebound speeds, impulses, energies and accumulation time t_inf for
 * e = 0.9, 0.5, 0 (theta = 1/2 integrates a constant force exactly, so located impacts are exact to rounding);
 * a block carried by a belt into a stop (its impacts, its slip, its rest pressed on the stop, no penetration,
 * no creep); e = 1 between two masses (energy conserved through every impact); unconnected systems that do
 * not disturb each other; plain Moreau-Jean (events "none") within a step of the closed form; and a compliant
 * contact through the regularized solver against the linear-spring closed form, converging to e = 1. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "dashpot/json.h"
#include "dashpot/run.h"

#define G 9.81
#define MAX_EV 8192

/* Every row flattened as t, then the row's numbers; events kept. */
typedef struct run_out {
    double *d;
    size_t n, cap, width;
    size_t nn, ne;          /* nodes and elements written */
    dp_event ev[MAX_EV];
    size_t nev;
    int status;
} run_out;

static void push_row(run_out *o, const dp_row *w)
{
    if (o->n == o->cap) {
        o->cap = o->cap ? 2 * o->cap : 1024;
        o->d = realloc(o->d, o->cap * o->width * sizeof *o->d);
        assert_non_null(o->d);
    }
    double *p = o->d + o->n++ * o->width;
    p[0] = w->t;
    memcpy(p + 1, w->val, (o->width - 1) * sizeof *p);
}

static void run_doc(const char *json, run_out *o)
{
    memset(o, 0, sizeof *o);
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(json, strlen(json), 0, &spec, &errs);
    if (s != DP_OK && errs.n)
        fprintf(stderr, "spec error %s: %s\n", errs.item[0].pointer, errs.item[0].message);
    assert_int_equal(s, DP_OK);
    dp_run *run = dp_run_alloc(&spec, 0, &errs, &s);
    if (run == NULL && errs.n)
        fprintf(stderr, "run error %s: %s\n", errs.item[0].pointer, errs.item[0].message);
    dp_spec_clear(&spec);
    assert_non_null(run);
    const dp_columns *c = dp_run_columns(run);
    assert_non_null(c);
    o->nn = c->nodes, o->ne = c->elements, o->width = 1 + c->width;
    dp_record buf[64];
    size_t n;
    do {
        s = dp_run_next(run, buf, 64, &n);
        for (size_t i = 0; i < n; i++) {
            if (buf[i].type == DP_RECORD_ROW)
                push_row(o, &buf[i].u.row);
            else if (o->nev < MAX_EV)
                o->ev[o->nev++] = buf[i].u.event;
        }
    } while (s == DP_MORE);
    o->status = s;
    if (s != DP_DONE)
        fprintf(stderr, "run failed: %s\n", dp_run_error(run));
    dp_run_free(run);
    assert_int_equal(s, DP_DONE);
}

/* Row i's x of node j, v of node j, Fn of element j. */
static double X(const run_out *o, size_t i, size_t j) { return o->d[i * o->width + 1 + j]; }
static double V(const run_out *o, size_t i, size_t j) { return o->d[i * o->width + 1 + o->nn + j]; }
static double FN(const run_out *o, size_t i, size_t j)
{
    return o->d[i * o->width + 1 + 2 * o->nn + 3 * o->ne + j];
}

static void ball_doc(char *buf, size_t cap, double e, double dt, double t_end, const char *events)
{
    snprintf(buf, cap, "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],"
             "\"contact\":{\"distance\":0,\"restitution\":%.17g}}],\"forcing\":[{\"node\":0,\"kind\":\"constant\","
             "\"value\":%.17g}]},\"initial\":{\"x\":[1],\"v\":[0]},\"solver\":{\"kind\":\"stick-slip\",\"dt\":%g,"
             "\"t_end\":%g,\"theta\":0.5,\"events\":\"%s\"},\"output\":{\"every\":1}}", e, -G, dt, t_end, events);
}

/* The ball from height 1 at rest: impacts at t_k with speed e^k v1 (v1 = sqrt(2g)), each taking the impulse
 * (1 + e) times the speed, leaving kinetic energy (e^k v1)^2 / 2; the impacts accumulate at
 * t_inf = t1 + 2 e v1 / (g (1 - e)), after which the ball lies on the table with the force m g on it. */
static void ball_closed_form(double e)
{
    static char doc[1024];
    run_out o;
    double v1 = sqrt(2 * G), t = sqrt(2 / G), speed = v1, t_inf = t + 2 * e * v1 / (G * (1 - e));
    ball_doc(doc, sizeof doc, e, 1e-3, ceil(t_inf) + 1, "locate");
    run_doc(doc, &o);
    size_t k = 0;
    for (size_t i = 0; i < o.nev; i++) {
        const dp_event *ev = &o.ev[i];
        assert_int_equal(ev->kind, DP_EVENT_IMPACT);
        if (speed > 1e-6) {        /* the first impacts, each against the closed form */
            assert_true(fabs(ev->t - t) <= 1e-9 * (1 + t));
            assert_true(fabs(ev->v + speed) <= 1e-9 * v1);
            assert_true(fabs(ev->v_after - e * speed) <= 1e-9 * v1);
            assert_true(fabs(ev->impulse - (1 + e) * speed) <= 1e-9 * v1);
            assert_true(fabs(0.5 * ev->v_after * ev->v_after - 0.5 * e * e * speed * speed) <= 1e-8 * G);
            assert_true(fabs(ev->x) <= 1e-12);
        }
        t += 2 * e * speed / G, speed *= e, k++;
    }
    assert_true(k >= 1);
    /* finitely many, the last at the accumulation point (to a billionth of a step and rounding) */
    assert_true(o.nev < (e > 0 ? (size_t)(log(1e-13) / log(e)) + 20 : 2));
    assert_true(fabs(o.ev[o.nev - 1].t - t_inf) <= 1e-9);
    for (size_t i = 0; i < o.n; i++) {
        assert_true(X(&o, i, 0) >= -1e-12);                       /* never below the table */
        if (o.d[i * o.width] > t_inf + 1e-3) {                    /* at rest on it, pressed by m g */
            assert_true(fabs(X(&o, i, 0)) <= 1e-12 && V(&o, i, 0) == 0);
            assert_true(fabs(FN(&o, i, 0) + G) <= 1e-9);
        }
    }
    free(o.d);
}

static void test_ball_e09(void **state) { (void)state; ball_closed_form(0.9); }
static void test_ball_e05(void **state) { (void)state; ball_closed_form(0.5); }
static void test_ball_e0(void **state) { (void)state; ball_closed_form(0); }

/* Plain Moreau-Jean (events "none", Siconos' rule): the first impact is reported at the end of the step
 * that closed the contact (armed once the gap predicted half a step on has closed), within two steps of t1; the ball ends at rest with a penetration of at most a
 * step's travel. */
static void test_ball_moreau_jean(void **state)
{
    (void)state;
    static char doc[1024];
    run_out o;
    double h = 1e-3, t1 = sqrt(2 / G), v1 = sqrt(2 * G);
    ball_doc(doc, sizeof doc, 0.5, h, 3, "none");
    run_doc(doc, &o);
    assert_true(o.nev >= 3);
    assert_int_equal(o.ev[0].kind, DP_EVENT_IMPACT);
    assert_true(o.ev[0].t >= t1 && o.ev[0].t <= t1 + 2 * h + 1e-12);
    assert_true(fabs(o.ev[0].v + v1) <= G * h);
    assert_true(fabs(o.ev[0].v_after + 0.5 * o.ev[0].v) <= 1e-12);    /* Newton's law on the step's end */
    double last = o.n - 1;
    assert_true(fabs(X(&o, (size_t)last, 0)) <= v1 * h && V(&o, (size_t)last, 0) == 0);
    free(o.d);
}

/* A block carried by a belt (Coulomb, phi0 = 1, belt speed 0.5) into a stop at x = 0.3 (contact on
 * [0, ground] at distance -0.3, e = 1/2): it sticks at t = 0.5 (x = 1/8), hits the stop at 0.85 at the belt's
 * speed, rebounds at 1/4 and slips, and friction brings it back: impacts every 1/2, 1/4, ... after 0.85,
 * accumulating at 1.85; from there it rests on the stop, pressed by the friction force 1, exactly at 0.3. */
static void test_belt_into_stop(void **state)
{
    (void)state;
    const char *doc = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"damper\":{\"law\":"
                      "\"coulomb\",\"phi0\":1,\"belt_velocity\":0.5}},{\"between\":[0,\"ground\"],\"contact\":"
                      "{\"distance\":-0.3,\"restitution\":0.5}}]},\"initial\":{\"x\":[0],\"v\":[0]},\"solver\":"
                      "{\"kind\":\"stick-slip\",\"dt\":0.01,\"t_end\":2.5,\"theta\":0.5},\"output\":{\"every\":1}}";
    run_out o;
    run_doc(doc, &o);
    assert_true(o.nev >= 4);
    assert_int_equal(o.ev[0].kind, DP_EVENT_STICK);
    assert_true(fabs(o.ev[0].t - 0.5) <= 1e-12 && fabs(o.ev[0].x - 0.125) <= 1e-12);
    assert_int_equal(o.ev[1].kind, DP_EVENT_IMPACT);                  /* the impact, then the slip it makes */
    assert_int_equal(o.ev[1].element, 1);
    assert_true(fabs(o.ev[1].t - 0.85) <= 1e-12);
    assert_true(fabs(o.ev[1].v + 0.5) <= 1e-12 && fabs(o.ev[1].v_after - 0.25) <= 1e-12);
    assert_true(fabs(o.ev[1].impulse - 0.75) <= 1e-12);
    assert_int_equal(o.ev[2].kind, DP_EVENT_SLIP);
    assert_true(o.ev[2].t == o.ev[1].t);
    double t = 0.85, dt = 0.5;
    size_t impacts = 0;
    for (size_t i = 1; i < o.nev; i++) {
        if (o.ev[i].kind != DP_EVENT_IMPACT)
            continue;
        if (dt > 1e-6)
            assert_true(fabs(o.ev[i].t - t) <= 1e-9);
        t += dt, dt /= 2, impacts++;
    }
    assert_true(impacts > 10 && impacts < 80);
    assert_true(fabs(o.ev[o.nev - 1].t - 1.85) <= 1e-9);
    for (size_t i = 0; i < o.n; i++) {
        assert_true(X(&o, i, 0) <= 0.3 + 1e-12);                      /* no penetration */
        if (o.d[i * o.width] > 1.86) {                                 /* no creep */
            assert_true(X(&o, i, 0) == X(&o, o.n - 1, 0) && fabs(X(&o, i, 0) - 0.3) <= 1e-12);
            assert_true(V(&o, i, 0) == 0 && fabs(FN(&o, i, 1) + 1) <= 1e-12);
        }
    }
    free(o.d);
}

/* Two masses on a spring (k = 50), the lower one above the table, e = 1, falling from rest: theta = 1/2 is the
 * implicit midpoint rule on the linear flight, which conserves the energy (kinetic + spring + gravity)
 * exactly, and a perfectly elastic impact keeps the kinetic energy, so the energy stays put to rounding. */
static void test_two_masses_elastic(void **state)
{
    (void)state;
    const char *doc = "{\"model\":{\"masses\":[1,0.5],\"elements\":[{\"between\":[\"ground\",0],\"contact\":"
                      "{\"distance\":0,\"restitution\":1}},{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":50}}],"
                      "\"forcing\":[{\"node\":0,\"kind\":\"constant\",\"value\":-9.81},{\"node\":1,\"kind\":"
                      "\"constant\",\"value\":-4.905}]},\"initial\":{\"x\":[0.5,1.2],\"v\":[0,0]},\"solver\":{\"kind\":"
                      "\"stick-slip\",\"dt\":0.001,\"t_end\":4,\"theta\":0.5},\"output\":{\"every\":1}}";
    run_out o;
    run_doc(doc, &o);
    size_t impacts = 0;
    for (size_t i = 0; i < o.nev; i++)
        impacts += o.ev[i].kind == DP_EVENT_IMPACT;
    assert_true(impacts >= 3);
    double E0 = 0;
    for (size_t i = 0; i < o.n; i++) {
        double x0 = X(&o, i, 0), x1 = X(&o, i, 1), v0 = V(&o, i, 0), v1 = V(&o, i, 1);
        double E = 0.5 * v0 * v0 + 0.25 * v1 * v1 + 25 * (x1 - x0 - 0) * (x1 - x0) + G * x0 + 0.5 * G * x1;
        if (i == 0)
            E0 = E;
        assert_true(fabs(E - E0) <= 1e-9 * fabs(E0));
        assert_true(x0 >= -1e-12);
    }
    free(o.d);
}

/* The ball and the belt block as one network of two unconnected parts: each one's impacts split the other's
 * steps, which must change nothing (constant and linear forces between events are integrated exactly). */
static void test_unconnected_parts(void **state)
{
    (void)state;
    const char *both = "{\"model\":{\"masses\":[1,1],\"elements\":[{\"between\":[\"ground\",0],\"contact\":"
                       "{\"distance\":0,\"restitution\":0.5}},{\"between\":[\"ground\",1],\"damper\":{\"law\":\"coulomb\","
                       "\"phi0\":1,\"belt_velocity\":0.5}},{\"between\":[1,\"ground\"],\"contact\":{\"distance\":-0.3,"
                       "\"restitution\":0.5}}],\"forcing\":[{\"node\":0,\"kind\":\"constant\",\"value\":-9.81}]},"
                       "\"initial\":{\"x\":[1,0],\"v\":[0,0]},\"solver\":{\"kind\":\"stick-slip\",\"dt\":0.01,"
                       "\"t_end\":2.5,\"theta\":0.5},\"output\":{\"every\":1}}";
    static char ball[1024];
    ball_doc(ball, sizeof ball, 0.5, 0.01, 2.5, "locate");
    const char *belt = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"damper\":{\"law\":"
                       "\"coulomb\",\"phi0\":1,\"belt_velocity\":0.5}},{\"between\":[0,\"ground\"],\"contact\":"
                       "{\"distance\":-0.3,\"restitution\":0.5}}]},\"initial\":{\"x\":[0],\"v\":[0]},\"solver\":"
                       "{\"kind\":\"stick-slip\",\"dt\":0.01,\"t_end\":2.5,\"theta\":0.5},\"output\":{\"every\":1}}";
    run_out a, b, c;
    run_doc(both, &a);
    run_doc(ball, &b);
    run_doc(belt, &c);
    assert_int_equal(a.n, b.n);
    assert_int_equal(a.n, c.n);
    for (size_t i = 0; i < a.n; i++) {
        assert_true(fabs(X(&a, i, 0) - X(&b, i, 0)) <= 1e-9 && fabs(V(&a, i, 0) - V(&b, i, 0)) <= 1e-9);
        assert_true(fabs(X(&a, i, 1) - X(&c, i, 0)) <= 1e-9 && fabs(V(&a, i, 1) - V(&c, i, 0)) <= 1e-9);
    }
    assert_int_equal(a.nev, b.nev + c.nev);
    free(a.d), free(b.d), free(c.d);
}

/* A compliant contact (force k max(-x, 0)) through the regularized solver: in contact the ball is a linear
 * oscillator about -g/k, so its deepest penetration is g/k + sqrt((g/k)^2 + v1^2/k) and it leaves at the
 * speed it came (e = 1). As k grows the motion converges to the rigid e = 1 bounce: the delay, half a
 * contact time, shrinks like 1/sqrt(k), so each tenfold k cuts the error at t = 1.2 by about sqrt(10). */
static double compliant_error(double k, double *pen_err)
{
    static char doc[1024];
    snprintf(doc, sizeof doc, "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"contact\":"
             "{\"distance\":0,\"compliance\":%g}}],\"forcing\":[{\"node\":0,\"kind\":\"constant\",\"value\":-9.81}]},"
             "\"initial\":{\"x\":[1],\"v\":[0]},\"solver\":{\"kind\":\"regularized\",\"n\":1,\"dt\":1e-5,"
             "\"t_end\":1.2,\"rtol\":1e-10,\"atol\":1e-12},\"output\":{\"every\":1}}", k);
    run_out o;
    run_doc(doc, &o);
    double v1 = sqrt(2 * G), xs = G / k, pen = xs + sqrt(xs * xs + v1 * v1 / k), lowest = 0;
    for (size_t i = 0; i < o.n; i++)
        lowest = fmin(lowest, X(&o, i, 0));
    *pen_err = fabs(-lowest - pen) / pen;
    double s = 1.2 - sqrt(2 / G), rigid = v1 * s - 0.5 * G * s * s;
    double err = fabs(X(&o, o.n - 1, 0) - rigid);
    free(o.d);
    return err;
}

static void test_compliance_converges(void **state)
{
    (void)state;
    double pe, e3 = compliant_error(1e3, &pe);
    assert_true(pe <= 1e-4);
    double e4 = compliant_error(1e4, &pe);
    assert_true(pe <= 1e-3);
    double e5 = compliant_error(1e5, &pe);
    assert_true(pe <= 1e-2);        /* the deepest sample of a 1e-5 grid over a contact of 1e-2 */
    assert_true(e3 / e4 > 2.5 && e3 / e4 < 4 && e4 / e5 > 2.5 && e4 / e5 < 4);
    assert_true(e5 < 0.05);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ball_e09),
        cmocka_unit_test(test_ball_e05),
        cmocka_unit_test(test_ball_e0),
        cmocka_unit_test(test_ball_moreau_jean),
        cmocka_unit_test(test_belt_into_stop),
        cmocka_unit_test(test_two_masses_elastic),
        cmocka_unit_test(test_unconnected_parts),
        cmocka_unit_test(test_compliance_converges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
