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

/* m x'' + F_J(x) = F0 from x = 0, v = V (m = k = F_y = 1, F0 = 1/4, V = 2): elastic about F0/k until k x
 * = F_y at t1; then m x'' = F0 - F_y until v = 0 at t2 (offset p = x2 - F_y/k); then the elastic
 * oscillation about p + F0/k of amplitude (F_y - F0)/k, which never reaches -F_y. */
typedef struct jenkins_ref { double t1, t2, x2, p; } jenkins_ref;

static const double F0 = 0.25, V0 = 2;

static jenkins_ref reference(void)
{
    jenkins_ref r;
    double R = hypot(F0, V0), phi = atan2(F0, V0);
    r.t1 = phi + asin((1 - F0) / R);
    double v1 = R * cos(r.t1 - phi), a = 1 - F0;
    r.t2 = r.t1 + v1 / a;
    r.x2 = 1 + v1 * v1 / (2 * a);
    r.p = r.x2 - 1;
    return r;
}

static void exact_state(double t, double *x, double *v)
{
    jenkins_ref r = reference();
    double R = hypot(F0, V0), phi = atan2(F0, V0), a = 1 - F0, A = 1 - F0;
    if (t <= r.t1) {
        *x = F0 + R * sin(t - phi), *v = R * cos(t - phi);
    } else if (t <= r.t2) {
        double v1 = R * cos(r.t1 - phi), s = t - r.t1;
        *x = 1 + v1 * s - 0.5 * a * s * s, *v = v1 - a * s;
    } else {
        *x = r.p + F0 + A * cos(t - r.t2), *v = -A * sin(t - r.t2);
    }
}

static const char *one_mass_doc = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1},"
    "\"damper\":{\"law\":\"none\"},\"forcing\":{\"kind\":\"constant\",\"value\":0.25}},\"initial\":{\"x\":0,\"v\":2},"
    "\"solver\":{\"kind\":\"stick-slip\",\"dt\":%.17g,\"t_end\":6,\"theta\":%g},\"output\":{\"every\":1000000}}";

static const char *network_doc = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],"
    "\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1}}],\"forcing\":[{\"node\":0,\"kind\":\"constant\","
    "\"value\":0.25}]},\"initial\":{\"x\":[0],\"v\":[2]},\"solver\":{\"kind\":\"stick-slip\",\"dt\":%.17g,"
    "\"t_end\":6,\"theta\":%g},\"output\":{\"every\":1000000}}";

typedef struct end_state { double x, v, p, Fs; size_t events; dp_event ev[8]; } end_state;

static end_state run_one_mass(double dt, double theta)
{
    char doc[1024];
    snprintf(doc, sizeof doc, one_mass_doc, dt, theta);
    traj t;
    assert_int_equal(traj_run(doc, &t), DP_OK);
    assert_int_equal(t.status, DP_DONE);
    end_state e = { t.sum.final.x, t.sum.final.v, t.sum.final.p, t.sum.final.Fs, t.ne, { { 0 } } };
    assert_true(t.sum.final.plastic);
    for (size_t i = 0; i < t.ne && i < 8; i++)
        e.ev[i] = t.e[i];
    traj_free(&t);
    return e;
}

static end_state run_network(double dt, double theta)
{
    char doc[1024];
    snprintf(doc, sizeof doc, network_doc, dt, theta);
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(doc, strlen(doc), 0, &spec, &errs);
    assert_int_equal(s, DP_OK);
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
    end_state e = { 0 };
    do {
        s = dp_run_next(run, buf, 64, &n);
        for (size_t i = 0; i < n; i++)
            if (buf[i].type == DP_RECORD_EVENT && e.events < 8)
                e.ev[e.events++] = buf[i].u.event;
    } while (s == DP_MORE);
    assert_int_equal(s, DP_DONE);
    const double *row = dp_run_summary(run)->final_row.val;
    e.x = row[0], e.v = row[1], e.Fs = row[2], e.p = row[5];
    dp_run_free(run);
    return e;
}

static double error_of(const end_state *e)
{
    double x, v;
    exact_state(6, &x, &v);
    return fmax(fabs(e->x - x), fabs(e->v - v));
}

/* Elastic swing, one yield, one unload, the offset and the final oscillation against the closed form; the
 * order is the least-squares slope of log error against log dt over eight steps from 0.01 down by 0.8 (the
 * unlocated yield costs theta = 1/2 an O(dt^2) error whose constant depends on where t1 falls in its step,
 * so pairs of halvings scatter); one mass and the one-node network take the same steps. */
static void check_theta(double theta, double order_lo, double order_hi)
{
    jenkins_ref ref = reference();
    double dt = 0.01, sx = 0, sy = 0, sxx = 0, sxy = 0;
    const int N = 8;
    for (int i = 0; i < N; i++, dt *= 0.8) {
        end_state a = run_one_mass(dt, theta), b = run_network(dt, theta);
        double err = error_of(&a), lx = log(dt), ly = log(err);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
        assert_true(fabs(a.x - b.x) <= 1e-9 && fabs(a.v - b.v) <= 1e-9 && fabs(a.p - b.p) <= 1e-9);
        assert_int_equal(a.events, 2);
        assert_int_equal(b.events, 2);
        assert_int_equal(a.ev[0].kind, DP_EVENT_YIELD);
        assert_int_equal(a.ev[1].kind, DP_EVENT_UNLOAD);
        assert_int_equal(b.ev[0].kind, DP_EVENT_YIELD);
        assert_int_equal(b.ev[1].kind, DP_EVENT_UNLOAD);
        /* reported at the end of the step that made them */
        assert_true(a.ev[0].t >= ref.t1 - 1e-12 && a.ev[0].t <= ref.t1 + dt + 1e-12);
        assert_true(fabs(a.ev[1].t - ref.t2) <= 2 * dt);
        assert_true(fabs(a.p - ref.p) <= (theta == 1 ? 5 : 0.5) * dt);
        /* the final state is elastic: F = k (x - p) inside the yield interval */
        assert_true(fabs(a.Fs - (a.x - a.p)) <= 1e-12 && fabs(a.Fs) < 1);
        assert_true(fabs(b.Fs - (b.x - b.p)) <= 1e-12);
        /* and the error is small in absolute terms, not only of the right order */
        assert_true(err <= (theta == 1 ? 2 * dt : dt * dt));
    }
    double order = (N * sxy - sx * sy) / (N * sxx - sx * sx);
    printf("theta %g: measured order %.3f\n", theta, order);
    assert_true(order > order_lo && order < order_hi);
}

static void test_mass_on_jenkins_theta_one(void **state)
{
    (void)state;
    check_theta(1, 0.85, 1.2);
}

static void test_mass_on_jenkins_theta_half(void **state)
{
    (void)state;
    check_theta(0.5, 1.7, 2.5);
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

/* Höschl's incremental Newmark (beta = 1/6 and 1/4) on the same mass: the tangent stiffness is the last
 * step's (k, or 0 while the slider slides), so the step that crosses yield overshoots and the error's
 * constant depends on where t1 falls in its step: it converges, at least at first order in dt, to the same
 * closed form, with one yield and one unload. */
static void test_newmark_on_jenkins(void **state)
{
    (void)state;
    const double betas[2] = { 1.0 / 6, 0.25 };
    for (int k = 0; k < 2; k++) {
        double dt = 0.01, sx = 0, sy = 0, sxx = 0, sxy = 0;
        const int N = 8;
        for (int i = 0; i < N; i++, dt *= 0.8) {
            char doc[1024];
            snprintf(doc, sizeof doc, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,"
                     "\"yield\":1},\"damper\":{\"law\":\"none\"},\"forcing\":{\"kind\":\"constant\",\"value\":0.25}},"
                     "\"initial\":{\"x\":0,\"v\":2},\"solver\":{\"kind\":\"newmark\",\"dt\":%.17g,\"t_end\":6,"
                     "\"beta\":%.17g,\"gamma\":0.5},\"output\":{\"every\":1000000}}", dt, betas[k]);
            traj t;
            assert_int_equal(traj_run(doc, &t), DP_OK);
            assert_int_equal(t.status, DP_DONE);
            end_state e = { t.sum.final.x, t.sum.final.v, t.sum.final.p, t.sum.final.Fs, t.ne, { { 0 } } };
            assert_int_equal(t.ne, 2);
            assert_int_equal(t.e[0].kind, DP_EVENT_YIELD);
            assert_int_equal(t.e[1].kind, DP_EVENT_UNLOAD);
            traj_free(&t);
            double err = error_of(&e), lx = log(dt), ly = log(err);
            assert_true(err <= 0.02 * dt);
            assert_true(fabs(e.p - reference().p) <= 0.02 * dt);
            sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
        }
        double order = (N * sxy - sx * sy) / (N * sxx - sx * sx);
        printf("newmark beta %.4f on the Jenkins spring: measured order %.3f\n", betas[k], order);
        assert_true(order > 0.9);
    }
}

/* A Jenkins spring beside a Coulomb damper under a slow harmonic load: the mass sticks at reversals while the
 * slider yields and unloads. The one-mass inclusion solver and the network's active-set solver are separate
 * codes for the same step; they agree on the whole path and on every event. */
static void test_yielding_beside_sticking(void **state)
{
    (void)state;
    const char *one = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1},"
        "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5},\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":1.6,"
        "\"omega\":0.3,\"phase\":0}},\"initial\":{\"x\":0,\"v\":0},\"solver\":{\"kind\":\"stick-slip\","
        "\"dt\":0.01,\"t_end\":30,\"theta\":0.5},\"output\":{\"every\":100}}";
    const char *net = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":"
        "\"elastoplastic\",\"k\":1,\"yield\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5}}],\"forcing\":"
        "[{\"node\":0,\"kind\":\"harmonic\",\"amplitude\":1.6,\"omega\":0.3,\"phase\":0}]},\"initial\":{\"x\":[0],"
        "\"v\":[0]},\"solver\":{\"kind\":\"stick-slip\",\"dt\":0.01,\"t_end\":30,\"theta\":0.5},"
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
        cmocka_unit_test(test_mass_on_jenkins_theta_one),
        cmocka_unit_test(test_mass_on_jenkins_theta_half),
        cmocka_unit_test(test_newmark_on_jenkins),
        cmocka_unit_test(test_yielding_beside_sticking),
        cmocka_unit_test(test_wellposedness_entry),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
