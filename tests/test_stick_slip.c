/* tests/test_stick_slip.c - the stick-slip solver against the closed form (Babováková 2012 (4.14)-(4.15)), the
 * thesis algorithm 4.1, hand-computed steps and second methods (graph laws against their named twins).
 *
 * Reference problem (thesis ch. 4): m = k = phi0 = 1, F = 0, x(0) = x0, x'(0) = 0. Arcs are half circles
 * about -/+ phi0/k; turning points shrink by 2 phi0/k; the mass rests at the first |x_j| <= phi0/k.
 * x0 = 5: turns at -3 (t = pi), rests at 1 from t = 2 pi.  x0 = 4.5: -2.5 at pi, rest at 0.5 from 2 pi.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "dashpot/analytic.h"
#include "trajectory.h"

#define COULOMB_MODEL "{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":1}}"

/* Exact x at time t from the arcs. */
static double exact_x(const dp_coulomb_problem *p, const dp_coulomb_arc *a, size_t n, double t, double *v)
{
    size_t i = 0;
    while (i + 1 < n && a[i + 1].t0 <= t)
        i++;
    double x, vv;
    dp_coulomb_arc_eval(p, &a[i], t, &x, &vv);
    if (v)
        *v = vv;
    return x;
}

/* Max |x - x_exact| over the samples of a free Coulomb decay from x0 with step dt. */
static double decay_error(double x0, double dt, double theta, const char *events)
{
    char spec[512];
    traj t;
    SPEC(spec, "{\"model\":" COULOMB_MODEL ",\"initial\":{\"x\":%.17g},"
         "\"solver\":{\"dt\":%.17g,\"t_end\":10,\"theta\":%.17g,\"events\":\"%s\"}}", x0, dt, theta, events);
    assert_int_equal(traj_run(spec, &t), DP_OK);
    assert_int_equal(t.status, DP_DONE);
    dp_coulomb_problem p = { .m = 1, .k = 1, .phi0 = 1, .x0 = x0 };
    dp_coulomb_arc arcs[64];
    size_t na;
    assert_int_equal(dp_coulomb_arcs(&p, 10, arcs, 64, &na), 0);
    double err = 0;
    for (size_t i = 0; i < t.n; i++)
        err = fmax(err, fabs(t.s[i].x - exact_x(&p, arcs, na, t.s[i].t, NULL)));
    traj_free(&t);
    return err;
}

static void test_closed_form_arcs(void **state)
{
    (void)state;
    dp_coulomb_problem p = { .m = 1, .k = 1, .phi0 = 1, .x0 = 5 };
    dp_coulomb_arc a[16];
    size_t n;
    assert_int_equal(dp_coulomb_arcs(&p, 10, a, 16, &n), 0);
    assert_int_equal(n, 3); /* left, right, rest */
    assert_true(fabs(a[0].t1 - M_PI) < 1e-14 && fabs(a[0].x1 + 3) < 1e-14);
    assert_true(fabs(a[1].t1 - 2 * M_PI) < 1e-14 && fabs(a[1].x1 - 1) < 1e-14);
    assert_int_equal(a[2].dir, 0);
    double x, v;
    dp_coulomb_arc_eval(&p, &a[0], M_PI / 2, &x, &v); /* quarter way: at the centre +1, speed -R */
    assert_true(fabs(x - 1) < 1e-14 && fabs(v + 4) < 1e-14);
}

/* Thesis Figs. 4.2-4.5 without relaxation: turning points, rest positions and stick times to O(dt). */
static void test_thesis_figures_closed_form(void **state)
{
    (void)state;
    for (int x0 = 0; x0 <= 5; x0++) {
        char spec[512];
        traj t;
        SPEC(spec, "{\"model\":" COULOMB_MODEL ",\"initial\":{\"x\":%d},"
             "\"solver\":{\"dt\":1e-3,\"t_end\":10,\"variant\":\"thesis\"}}", x0);
        assert_int_equal(traj_run(spec, &t), DP_OK);
        dp_coulomb_problem p = { .m = 1, .k = 1, .phi0 = 1, .x0 = x0 };
        dp_coulomb_arc a[16];
        size_t na;
        dp_coulomb_arcs(&p, 10, a, 16, &na);
        double rest_x = a[na - 1].x0, rest_t = a[na - 1].t0;
        printf("x0=%d: rest %.6f (exact %.6f) stick time %.6f (exact %.6f)\n", x0, t.sum.final.x, rest_x,
               t.sum.stick_time, 10 - rest_t);
        /* O(dt): backward Euler loses ~ 2 pi dt phi0 per arc; 10 dt bounds it for the <= 3 arcs here. */
        assert_true(fabs(t.sum.final.x - rest_x) < 10e-3);
        assert_true(fabs(t.sum.stick_time - (10 - rest_t)) < 3e-3);
        /* Turning points: the samples where v changes sign match the arcs' ends. */
        size_t j = 0;
        for (size_t i = 1; i < t.n && j + 1 < na; i++) {
            if (t.s[i - 1].v * t.s[i].v < 0 || (t.s[i].v == 0 && t.s[i - 1].v != 0)) {
                assert_true(fabs(t.s[i].x - a[j].x1) < 10e-3);
                assert_true(fabs(t.s[i].t - a[j].t1) < 3e-3);
                j++;
            }
        }
        assert_int_equal(j, na - 1);
        traj_free(&t);
    }
}

static void test_convergence_orders(void **state)
{
    (void)state;
    const double dts[3] = { 1e-2, 1e-3, 1e-4 };
    const double thetas[2] = { 1, 0.5 };
    for (int k = 0; k < 2; k++) {
        double e[3];
        for (int i = 0; i < 3; i++)
            e[i] = decay_error(4.5, dts[i], thetas[k], "locate");
        double o1 = log10(e[0] / e[1]), o2 = log10(e[1] / e[2]);
        printf("theta=%.1f errors %.3e %.3e %.3e orders %.3f %.3f\n", thetas[k], e[0], e[1], e[2], o1, o2);
        double want = thetas[k] == 1 ? 1 : 2;
        assert_true(fabs(o1 - want) < 0.25 && fabs(o2 - want) < 0.25);
    }
}

/* Runs spec text, asserting it completes. */
static void run_ok(const char *spec, traj *t)
{
    assert_int_equal(traj_run(spec, t), DP_OK);
    if (t->status != DP_DONE)
        fprintf(stderr, "run failed: %s\n", t->error);
    assert_int_equal(t->status, DP_DONE);
}

static double max_diff_x(const traj *a, const traj *b, double *dv)
{
    assert_int_equal(a->n, b->n);
    double e = 0, ev = 0;
    for (size_t i = 0; i < a->n; i++) {
        assert_true(a->s[i].t == b->s[i].t);
        e = fmax(e, fabs(a->s[i].x - b->s[i].x));
        ev = fmax(ev, fabs(a->s[i].v - b->s[i].v));
    }
    if (dv)
        *dv = ev;
    return e;
}

/* Max |x| and |v| difference between algorithm 4.1 with stopping tolerance eps and the exact inclusion. */
static double thesis_vs_exact(int x0, double eps, double *dv)
{
    char a[600], b[600];
    const char *model = "{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\","
                        "\"phi0\":1,\"relaxation\":{\"kind\":\"rational\",\"a\":0.5,\"b\":1}}}";
    traj t1, t2;
    run_ok(SPEC(a, "{\"model\":%s,\"initial\":{\"x\":%d},\"solver\":{\"dt\":1e-3,\"variant\":\"thesis\","
                "\"Z\":100,\"eps\":%.17g}}", model, x0, eps), &t1);
    run_ok(SPEC(b, "{\"model\":%s,\"initial\":{\"x\":%d},\"solver\":{\"dt\":1e-3,\"variant\":\"exact\","
                "\"events\":\"none\",\"theta\":1}}",
                model, x0), &t2);
    double dx = max_diff_x(&t1, &t2, dv);
    assert_int_equal(t1.ne, t2.ne);
    traj_free(&t1);
    traj_free(&t2);
    return dx;
}

/* With gamma = 0.5 v/(1+|v|) (thesis Figs. 4.2-4.5): algorithm 4.1 and the exact inclusion with events
 * "none" (no step split at transitions, as the thesis steps) solve the same step, so they differ only by the fixed-point stopping rule |v_i - v_{i+1}| < eps. With the thesis' own
 * eps = 1e-4 the iteration stops after its second pass, leaving ~alpha * 1e-6 per step (alpha = 5e-4):
 * a few 1e-6 after 10^4 steps. With eps = 1e-6 they agree to 1e-6; with 1e-12, to rounding. */
static void test_thesis_matches_exact_with_relaxation(void **state)
{
    (void)state;
    for (int x0 = 0; x0 <= 5; x0++) {
        double dv4, dv6, dv12;
        double dx4 = thesis_vs_exact(x0, 1e-4, &dv4);
        double dx6 = thesis_vs_exact(x0, 1e-6, &dv6);
        double dx12 = thesis_vs_exact(x0, 1e-12, &dv12);
        printf("x0=%d thesis vs exact: eps 1e-4 |dx| %.2e |dv| %.2e; eps 1e-6 %.2e %.2e; eps 1e-12 %.2e %.2e\n",
               x0, dx4, dv4, dx6, dv6, dx12, dv12);
        assert_true(dx4 < 1e-5 && dv4 < 1e-5);
        assert_true(dx6 < 1e-6 && dv6 < 1e-6);
        assert_true(dx12 < 1e-11 && dv12 < 1e-11);
    }
}

/* Once at rest with |k x| < phi0 and no load, x stays bitwise constant (no creep). */
static void test_exact_sticking(void **state)
{
    (void)state;
    char spec[512];
    traj t;
    run_ok(SPEC(spec, "{\"model\":" COULOMB_MODEL ",\"initial\":{\"x\":4.5},\"solver\":{\"dt\":1e-3,"
                "\"t_end\":20,\"theta\":0.5},\"output\":{\"every\":1}}"), &t);
    size_t first = 0;
    while (first < t.n && t.s[first].phase != DP_PHASE_STICK)
        first++;
    assert_true(first < t.n && t.s[first].t < 2 * M_PI + 1e-3);
    for (size_t i = first; i < t.n; i++) {
        assert_true(t.s[i].x == t.s[first].x);
        assert_true(t.s[i].v == 0);
    }
    assert_true(fabs(t.s[first].x - 0.5) < 1e-6);
    assert_int_equal(t.ne, 1);
    assert_int_equal(t.e[0].kind, DP_EVENT_STICK);
    assert_true(fabs(t.e[0].t - 2 * M_PI) < 1e-6); /* located to O(dt^2) */
    assert_true(fabs(t.sum.stick_time - (20 - 2 * M_PI)) < 1e-6);
    traj_free(&t);
}

/* A user graph with the Coulomb shape goes through the general inclusion solver: same answer. */
static void test_graph_damper_equals_coulomb(void **state)
{
    (void)state;
    char a[600], b[600];
    traj t1, t2;
    const char *solver = "\"solver\":{\"dt\":1e-3,\"events\":\"none\",\"theta\":1}";
    run_ok(SPEC(a, "{\"model\":" COULOMB_MODEL ",\"initial\":{\"x\":5},%s}", solver), &t1);
    run_ok(SPEC(b, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"graph\",\"points\":[[-1,-1],[1,1]]},"
                "\"damper\":{\"law\":\"graph\",\"points\":[[-1,-1],[0,-1],[0,1],[1,1]]}},"
                "\"initial\":{\"x\":5},%s}", solver), &t2);
    double dv, dx = max_diff_x(&t1, &t2, &dv);
    printf("graph vs coulomb: |dx| %.3e |dv| %.3e\n", dx, dv);
    assert_true(dx < 1e-12 && dv < 1e-12);
    for (size_t i = 0; i < t1.n; i++)
        assert_int_equal(t1.s[i].phase, t2.s[i].phase);
    assert_int_equal(t1.ne, t2.ne);
    traj_free(&t1);
    traj_free(&t2);
}

/* The analytic solver samples the closed form; the exact solver at theta = 1/2 agrees with it to O(dt^2),
 * also under a constant load (arcs about (F0 -/+ phi0)/k) and from a moving start. */
static void test_analytic_solver_matches_stick_slip(void **state)
{
    (void)state;
    const char *model = "{\"mass\":2,\"spring\":{\"law\":\"linear\",\"k\":3},\"damper\":{\"law\":\"coulomb\","
                        "\"phi0\":0.4},\"forcing\":{\"kind\":\"constant\",\"value\":0.3}}";
    char a[600], b[600];
    traj an, ss;
    run_ok(SPEC(a, "{\"model\":%s,\"initial\":{\"x\":-2,\"v\":1.5},\"solver\":{\"kind\":\"analytic\",\"dt\":1e-3,"
                "\"t_end\":40}}", model), &an);
    run_ok(SPEC(b, "{\"model\":%s,\"initial\":{\"x\":-2,\"v\":1.5},\"solver\":{\"dt\":1e-3,\"t_end\":40,"
                "\"theta\":0.5}}", model), &ss);
    double dv, dx = max_diff_x(&an, &ss, &dv);
    printf("analytic vs theta=1/2: |dx| %.3e |dv| %.3e, rest %.9f, events %zu/%zu\n", dx, dv, an.sum.final.x,
           an.ne, ss.ne);
    assert_true(dx < 1e-5 && dv < 1e-5);
    assert_int_equal(an.ne, 1);
    assert_int_equal(ss.ne, 1);
    assert_true(fabs(an.e[0].t - ss.e[0].t) < 1e-5);
    /* at rest the spring and the load balance within the stick interval */
    assert_true(fabs(0.3 - 3 * an.sum.final.x) <= 0.4);
    assert_true(fabs(an.sum.stick_time - ss.sum.stick_time) < 1e-5);
    traj_free(&an);
    traj_free(&ss);
}

/* Decimation changes what is written, never the trajectory: with every = 7 the fast slip loop runs between
 * samples, with every = 1 it never does; the common samples agree bit for bit (also with harmonic load and
 * theta = 1, and a belt). */
static void test_decimation_is_exact(void **state)
{
    (void)state;
    /* the third case, a load on a belt, once caught the fast loop summing F and the belt term in another
     * order than the general path */
    const char *loads[3] = { "{\"kind\":\"constant\",\"value\":0.2}",
                             "{\"kind\":\"harmonic\",\"amplitude\":1,\"omega\":0.7}",
                             "{\"kind\":\"constant\",\"value\":0.3},\"damper\":{\"law\":\"coulomb\","
                             "\"phi0\":0.3,\"belt_velocity\":0.5}" };
    for (int k = 0; k < 3; k++) {
        char a[600], b[600];
        traj all, dec;
        const char *fmt = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"forcing\":%s%s},"
                          "\"initial\":{\"x\":3},\"solver\":{\"dt\":1e-3,\"t_end\":50,\"theta\":%s,\"events\":\"%s\"},"
                          "\"output\":{\"every\":%d}}";
        const char *damper = k == 2 ? "" : ",\"damper\":{\"law\":\"coulomb\",\"phi0\":0.3}";
        const char *theta = k == 1 ? "1" : "0.5", *events = k == 2 ? "none" : "locate";
        run_ok(SPEC(a, fmt, loads[k], damper, theta, events, 1), &all);
        run_ok(SPEC(b, fmt, loads[k], damper, theta, events, 7), &dec);
        assert_int_equal(dec.n, (all.n - 1 + 6) / 7 + 1);
        for (size_t i = 0; i + 1 < dec.n; i++) {
            const dp_sample *p = &all.s[7 * i], *q = &dec.s[i];
            assert_true(p->t == q->t && p->x == q->x && p->v == q->v && p->Fc == q->Fc && p->phase == q->phase);
        }
        const dp_sample *p = &all.s[all.n - 1], *q = &dec.s[dec.n - 1];
        assert_true(p->t == q->t && p->x == q->x && p->v == q->v);
        assert_int_equal(all.ne, dec.ne);
        assert_true(all.sum.stick_time == dec.sum.stick_time);
        traj_free(&all);
        traj_free(&dec);
    }
}

/* Samples at the times of `coarse` (every `stride`-th of `fine`): max |x| and |v| difference. */
static double strided_diff(const traj *coarse, const traj *fine, size_t stride, double *dv)
{
    double dx = 0;
    *dv = 0;
    for (size_t i = 0; i < coarse->n && i * stride < fine->n; i++) {
        const dp_sample *p = &coarse->s[i], *q = &fine->s[i * stride];
        assert_true(fabs(p->t - q->t) < 1e-12);
        dx = fmax(dx, fabs(p->x - q->x));
        *dv = fmax(*dv, fabs(p->v - q->v));
    }
    return dx;
}

/* Velocity-weakening friction on a belt (gamma = 0.5 u / (1 + |u|)), lightly forced: a stick-slip cycle. */
#define RELAXED_FORCED "{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{%s,\"belt_velocity\":0.5," \
    "\"relaxation\":{\"kind\":\"rational\",\"a\":0.5,\"b\":1}},\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":0.2," \
    "\"omega\":0.7}}"

/* Runs it from rest at x = 0 to t = 16 with samples every 0.02. */
static void relaxed_run(const char *damper, double dt, const char *theta, const char *events, traj *t)
{
    char model[600], spec[900];
    snprintf(model, sizeof model, RELAXED_FORCED, damper);
    run_ok(SPEC(spec, "{\"model\":%s,\"initial\":{\"x\":0},\"solver\":{\"dt\":%.17g,\"t_end\":16,\"theta\":%s,"
                "\"events\":\"%s\"},\"output\":{\"every\":%.0f}}", model, dt, theta, events, 0.02 / dt), t);
}

/* Located events in the general inclusion (relaxation: no closed form): a user graph of the Coulomb shape
 * gives the named law's answer, event for event; theta = 1/2 stays cleanly second order through the
 * stick-slip transitions with "locate", events included (reference: dt = 2e-2 / 512, located); with "none"
 * the error is larger at every dt and its observed order scatters as transitions fall between grid points. */
static void test_located_events_general_inclusion(void **state)
{
    (void)state;
    const char *coulomb = "\"law\":\"coulomb\",\"phi0\":1";
    const char *graph = "\"law\":\"graph\",\"points\":[[-1,-1],[0,-1],[0,1],[1,1]]";
    traj named, user;
    relaxed_run(coulomb, 1e-3, "0.5", "locate", &named);
    relaxed_run(graph, 1e-3, "0.5", "locate", &user);
    double dv, dx = strided_diff(&named, &user, 1, &dv);
    printf("located, relaxed: graph vs coulomb |dx| %.3e |dv| %.3e, events %zu/%zu\n", dx, dv, named.ne, user.ne);
    assert_true(dx < 1e-12 && dv < 1e-12);
    assert_true(named.ne >= 4); /* several stick and slip transitions in the window */
    assert_int_equal(named.ne, user.ne);
    for (size_t i = 0; i < named.ne; i++)
        assert_true(named.e[i].kind == user.e[i].kind && fabs(named.e[i].t - user.e[i].t) < 1e-12);
    traj_free(&user);

    double dts[3] = { 2e-2 / 2, 2e-2 / 4, 2e-2 / 8 }, err[2][3];
    traj ref;
    relaxed_run(coulomb, 2e-2 / 512, "0.5", "locate", &ref);
    for (int m = 0; m < 2; m++) {
        for (int i = 0; i < 3; i++) {
            traj t;
            relaxed_run(coulomb, dts[i], "0.5", m ? "none" : "locate", &t);
            err[m][i] = strided_diff(&t, &ref, 1, &dv);
            if (m == 0) { /* the same events, at times right to O(dt^2) */
                double de = 0;
                assert_int_equal(t.ne, ref.ne);
                for (size_t j = 0; j < t.ne; j++)
                    de = fmax(de, fabs(t.e[j].t - ref.e[j].t));
                printf("dt %.4g: event times within %.2e of the reference\n", dts[i], de);
                assert_true(de < 10 * dts[i] * dts[i]);
            }
            traj_free(&t);
        }
        printf("%s: errors %.3e %.3e %.3e, orders %.2f %.2f\n", m ? "none  " : "locate", err[m][0], err[m][1],
               err[m][2], log2(err[m][0] / err[m][1]), log2(err[m][1] / err[m][2]));
    }
    for (int i = 0; i < 3; i++) {
        if (i < 2) /* second order, located; step-resolved transitions scatter with the grid */
            assert_true(fabs(log2(err[0][i] / err[0][i + 1]) - 2) < 0.1);
        assert_true(err[0][i] < err[1][i]);
    }
    traj_free(&named);
    traj_free(&ref);
}

/* From rest inside the stick interval a user graph of the Coulomb shape starts stuck like the named law (no
 * stick event at t = 0), breaks away at the same located instant, and reverses without a stick event. */
static void test_graph_damper_starts_like_coulomb(void **state)
{
    (void)state;
    const char *fmt = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{%s,\"relaxation\":"
                      "{\"kind\":\"rational\",\"a\":0.5,\"b\":1}},\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":1.2,"
                      "\"omega\":1.5}},\"initial\":{\"x\":2},\"solver\":{\"dt\":1e-3,\"t_end\":13,\"theta\":0.5}}";
    char a[900], b[900];
    traj named, user;
    run_ok(SPEC(a, fmt, "\"law\":\"coulomb\",\"phi0\":1"), &named);
    run_ok(SPEC(b, fmt, "\"law\":\"graph\",\"points\":[[-1,-1],[0,-1],[0,1],[1,1]]"), &user);
    assert_int_equal(named.s[0].phase, DP_PHASE_STICK);
    assert_int_equal(user.s[0].phase, DP_PHASE_STICK);
    assert_true(named.s[0].Fc == user.s[0].Fc);
    assert_int_equal(named.ne, 5); /* slip at 0.39, then the first stick at 9.45: reversals are not sticks */
    assert_int_equal(user.ne, named.ne);
    assert_int_equal(named.e[0].kind, DP_EVENT_SLIP);
    assert_true(named.e[1].t > 9);
    for (size_t i = 0; i < named.ne; i++)
        assert_true(named.e[i].kind == user.e[i].kind && fabs(named.e[i].t - user.e[i].t) < 1e-12);
    double dv, dx = max_diff_x(&named, &user, &dv);
    assert_true(dx < 1e-12 && dv < 1e-12);
    traj_free(&named);
    traj_free(&user);
}

/* A mass carried by a belt (Coulomb, v_b = 0.4) against a rope of length 0.5: it sticks at the same located
 * instant as on a linear spring of the same stiffness (closed form vs general inclusion), rides the belt to
 * x = L exactly, and breaks away there, at t_stick + (L - x_stick) / v_b, when the taut rope stops it. */
static void test_rope_breaks_stick_at_its_length(void **state)
{
    (void)state;
    const char *fmt = "{\"model\":{\"mass\":1,\"spring\":{%s},\"damper\":{\"law\":\"coulomb\",\"phi0\":1,"
                      "\"belt_velocity\":0.4}},\"initial\":{\"x\":0},\"solver\":{\"dt\":1e-2,\"t_end\":3,\"theta\":1}}";
    char a[600], b[600];
    traj rope, lin;
    run_ok(SPEC(a, fmt, "\"law\":\"rope\",\"k\":1,\"length\":0.5"), &rope);
    run_ok(SPEC(b, fmt, "\"law\":\"linear\",\"k\":1"), &lin);
    assert_int_equal(rope.ne, 2);
    assert_int_equal(lin.ne, 2);
    assert_true(rope.e[0].kind == DP_EVENT_STICK && lin.e[0].kind == DP_EVENT_STICK);
    assert_true(fabs(rope.e[0].t - lin.e[0].t) < 1e-12 && fabs(rope.e[0].x - lin.e[0].x) < 1e-12);
    double t_taut = rope.e[0].t + (0.5 - rope.e[0].x) / 0.4;
    printf("rope: stick at %.15f, slip at %.15f (expected %.15f)\n", rope.e[0].t, rope.e[1].t, t_taut);
    assert_true(rope.e[1].kind == DP_EVENT_SLIP && fabs(rope.e[1].t - t_taut) < 1e-12);
    assert_true(fabs(rope.e[1].x - 0.5) < 1e-12);
    for (size_t i = 0; i < rope.n; i++)
        assert_true(rope.s[i].x <= 0.5);
    assert_true(rope.sum.final.x == 0.5 && rope.sum.final.v == 0); /* held by the rope, the belt slides */
    traj_free(&rope);
    traj_free(&lin);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_form_arcs),
        cmocka_unit_test(test_thesis_figures_closed_form),
        cmocka_unit_test(test_convergence_orders),
        cmocka_unit_test(test_thesis_matches_exact_with_relaxation),
        cmocka_unit_test(test_exact_sticking),
        cmocka_unit_test(test_graph_damper_equals_coulomb),
        cmocka_unit_test(test_analytic_solver_matches_stick_slip),
        cmocka_unit_test(test_decimation_is_exact),
        cmocka_unit_test(test_located_events_general_inclusion),
        cmocka_unit_test(test_graph_damper_starts_like_coulomb),
        cmocka_unit_test(test_rope_breaks_stick_at_its_length),
    };
    return cmocka_run_group_tests_name("stick_slip", tests, NULL, NULL);
}
