/* tests/test_wellposedness.c - the well-posedness report over the law catalogue, the seeds' counterexamples
 * and user graphs that break each hypothesis (table-driven), and both solution branches of both
 * counterexamples (Pražák & Rajagopal 2016 §4) against their closed forms. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "dashpot/wellposedness.h"
#include "trajectory.h"

typedef struct row {
    const char *name, *model;
    const char *framework;
    int exists, unique;
    const char *theorem;     /* substring of the existence theorem when guaranteed */
    const char *failing;     /* substring of the uniqueness reason when not guaranteed */
    int counterexample;
} row;

#define LIN "\"spring\":{\"law\":\"linear\",\"k\":1}"
#define GSP "\"spring\":{\"law\":\"graph\",\"points\":[[-1,-2],[1,2]]}"

static const row rows[] = {
    { "coulomb", LIN ",\"damper\":{\"law\":\"coulomb\",\"phi0\":1}", "PC", 1, 1, "Pražák & Rajagopal 2016, Theorem 3", NULL, 0 },
    { "no damper", LIN ",\"damper\":{\"law\":\"none\"}", "PC", 1, 1, "Theorem 3", NULL, 0 },
    { "linear damper", LIN ",\"damper\":{\"law\":\"linear\",\"c\":2}", "PC", 1, 1, "Theorem 3", NULL, 0 },
    { "bingham", LIN ",\"damper\":{\"law\":\"bingham\",\"tau\":1,\"c\":2}", "PC", 1, 1, "Theorem 3", NULL, 0 },
    { "coulomb + rational gamma", LIN ",\"damper\":{\"law\":\"coulomb\",\"phi0\":1,\"relaxation\":{\"kind\":"
      "\"rational\",\"a\":0.5,\"b\":1}}", "PC", 1, 1, "Theorem 3", NULL, 0 },
    { "coulomb + linear gamma", LIN ",\"damper\":{\"law\":\"coulomb\",\"phi0\":1,\"relaxation\":{\"kind\":"
      "\"linear\",\"L\":0.3}}", "PC", 1, 1, "Theorem 3", NULL, 0 },
    { "counterexample 2: coulomb + gamma_N", LIN ",\"damper\":{\"law\":\"coulomb\",\"phi0\":1,\"relaxation\":"
      "{\"kind\":\"power\",\"N\":2}}", "PC", 1, 0, "Theorem 3", "gamma Lipschitz", 1 },
    { "counterexample 1: generalized coulomb", LIN ",\"damper\":{\"law\":\"generalized-coulomb\",\"phi0\":0.5,"
      "\"phi1\":1}", "PC", 0, 0, NULL, "A monotone", 1 },
    { "generalized coulomb, phi1 = phi0", LIN ",\"damper\":{\"law\":\"generalized-coulomb\",\"phi0\":1,"
      "\"phi1\":1}", "PC", 1, 1, "Theorem 3", NULL, 0 },
    { "belt-driven coulomb", LIN ",\"damper\":{\"law\":\"coulomb\",\"phi0\":1,\"belt_velocity\":0.4}", "PC", 1,
      1, "Theorem 3", NULL, 0 },
    { "monotone user graph", LIN ",\"damper\":{\"law\":\"graph\",\"points\":[[-1,-2],[0,-1],[0,1],[1,2]]}",
      "PC", 1, 1, "Theorem 3", NULL, 0 },
    { "non-monotone user graph", LIN ",\"damper\":{\"law\":\"graph\",\"points\":[[-1,0],[0,1],[1,0.5]]}", "PC",
      0, 0, NULL, "A monotone", 0 },
    { "user graph with a gap", LIN ",\"damper\":{\"law\":\"graph\",\"points\":[[-1,-1],[0,-1],null,[0,1],[1,1]]}",
      "PC", 0, 0, NULL, "A maximal", 0 },
    { "non-coercive: vertical end", LIN ",\"damper\":{\"law\":\"graph\",\"points\":[[-1,-1],[0,0],[0,1]]}", "PC",
      0, 0, NULL, "A coercive", 0 },
    { "non-coercive: negative plateau", LIN ",\"damper\":{\"law\":\"graph\",\"points\":[[0,-2],[1,-1],[2,-1]]}",
      "PC", 0, 0, NULL, "A coercive", 0 },
    { "rope + bingham", "\"spring\":{\"law\":\"rope\",\"k\":1,\"length\":2},\"damper\":{\"law\":\"bingham\","
      "\"tau\":1,\"c\":1}", "PI", 0, 0, NULL, "growth of f", 0 },
    { "graph spring + bingham, constant load", GSP ",\"damper\":{\"law\":\"bingham\",\"tau\":1,\"c\":1},"
      "\"forcing\":{\"kind\":\"constant\",\"value\":0.5}", "PI", 1, 1, "Babováková 2012, Theorem 2.1", NULL, 0 },
    { "graph spring + bingham, harmonic load", GSP ",\"damper\":{\"law\":\"bingham\",\"tau\":1,\"c\":1},"
      "\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":1,\"omega\":2}", "PI", 1, 0, "Theorem 2.1",
      "constant load", 0 },
    { "graph spring + coulomb", GSP ",\"damper\":{\"law\":\"coulomb\",\"phi0\":1}", "PI", 0, 0, NULL,
      "x' = g(F_d) a function", 0 },
    { "graph spring + relaxation", GSP ",\"damper\":{\"law\":\"linear\",\"c\":1,\"relaxation\":{\"kind\":"
      "\"rational\",\"a\":0.5,\"b\":1}}", "PI", 0, 0, NULL, "no relaxation", 0 },
    { "graph spring off the origin", "\"spring\":{\"law\":\"graph\",\"points\":[[1,0],[2,1]]},\"damper\":"
      "{\"law\":\"linear\",\"c\":1}", "PI", 0, 0, NULL, "f(0) = 0", 0 },
};

static void test_table(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        const row *r = &rows[i];
        char text[1024];
        snprintf(text, sizeof text, "{\"model\":{\"mass\":1,%s}}", r->model);
        dp_model m = { 0 };
        dp_errors errs;
        dp_errors_init(&errs);
        int s = dp_model_parse_lenient(text, strlen(text), &m, &errs);
        if (s != DP_OK)
            fprintf(stderr, "%s: %s %s\n", r->name, errs.n ? errs.item[0].pointer : "", errs.n ? errs.item[0].message : "");
        assert_int_equal(s, DP_OK);
        dp_wp_report rep;
        dp_wellposedness(&m, &rep);
        printf("%-40s %s existence %d uniqueness %d | %s\n", r->name, rep.framework, rep.existence.guaranteed,
               rep.uniqueness.guaranteed, rep.uniqueness.reason);
        assert_string_equal(rep.framework, r->framework);
        assert_int_equal(rep.existence.guaranteed, r->exists);
        assert_int_equal(rep.uniqueness.guaranteed, r->unique);
        if (r->exists)
            assert_non_null(strstr(rep.existence.theorem, r->theorem));
        else
            assert_null(rep.existence.theorem);
        if (r->failing)
            assert_non_null(strstr(rep.uniqueness.reason, r->failing));
        assert_int_equal(rep.counterexample != NULL, r->counterexample);
        dp_model_clear(&m);
    }
}

/* Witnesses are concrete: the generalized Coulomb pair, the gap's midpoint, gamma_N's unbounded ratio. */
static void test_witnesses(void **state)
{
    (void)state;
    const char *text = "{\"model\":{\"mass\":1," LIN ",\"damper\":{\"law\":\"graph\",\"points\":[[-1,-1],[0,-1],"
                       "null,[0,1],[1,1]]}}}";
    dp_model m = { 0 };
    dp_errors errs;
    dp_errors_init(&errs);
    assert_int_equal(dp_model_parse_lenient(text, strlen(text), &m, &errs), DP_OK);
    dp_wp_report rep;
    dp_wellposedness(&m, &rep);
    assert_non_null(strstr(rep.check[2].detail, "gap between (0, -1) and (0, 1)"));
    dp_model_clear(&m);
    /* the strict parser refuses the same document for a simulation */
    char full[512];
    snprintf(full, sizeof full, "{\"model\":{\"mass\":1," LIN ",\"damper\":{\"law\":\"graph\",\"points\":[[-1,-1],"
             "[0,-1],null,[0,1],[1,1]]}}}");
    traj t;
    assert_int_equal(traj_run(full, &t), DP_EINVAL);
    dp_model g = { .mass = 1, .spring = { .law = DP_SPRING_LINEAR, .k = 1 },
                   .damper = { .law = DP_DAMPER_COULOMB, .phi0 = 1,
                               .relaxation = { .kind = DP_RELAX_POWER, .N = 2 } } };
    assert_int_equal(dp_model_prepare(&g), DP_OK);
    dp_wellposedness(&g, &rep);
    assert_non_null(strstr(rep.check[5].detail, "gamma(u)/u = 2000 at u = 1e-6")); /* 2 u^(1/2) / u */
    dp_model_clear(&g);
}

/* Counterexample 1 (Pražák & Rajagopal 2016 (24)-(25)): m = k = 1, phi0 = 0.5 < phi1 = 1, F = phi1 from rest.
 * Rest: x = 0. Motion: x = (phi1 - phi0)(1 - cos t) on [0, pi], then rest at 2 (phi1 - phi0) = 1. */
static void test_counterexample_generalized_coulomb(void **state)
{
    (void)state;
    const char *m = "{\"mass\":1," LIN ",\"damper\":{\"law\":\"generalized-coulomb\",\"phi0\":0.5,\"phi1\":1},"
                    "\"forcing\":{\"kind\":\"constant\",\"value\":1}}";
    char a[600], b[600];
    traj rest, motion;
    assert_int_equal(traj_run(SPEC(a, "{\"model\":%s,\"solver\":{\"dt\":1e-3,\"t_end\":5,\"theta\":0.5}}", m),
                              &rest), DP_OK);
    assert_int_equal(traj_run(SPEC(b, "{\"model\":%s,\"solver\":{\"dt\":1e-3,\"t_end\":5,\"theta\":0.5,"
                                   "\"branch\":\"motion\"}}", m), &motion), DP_OK);
    assert_int_equal(rest.status, DP_DONE);
    assert_int_equal(motion.status, DP_DONE);
    for (size_t i = 0; i < rest.n; i++)
        assert_true(rest.s[i].x == 0 && rest.s[i].v == 0);
    double err = 0;
    for (size_t i = 0; i < motion.n; i++) {
        double t = motion.s[i].t, x = t <= M_PI ? 0.5 * (1 - cos(t)) : 1;
        err = fmax(err, fabs(motion.s[i].x - x));
    }
    printf("generalized coulomb, motion branch: max |x - 0.5(1 - cos t)| = %.3e\n", err);
    assert_true(err < 1e-5);
    /* it starts slipping at once (no event: |F| = phi1 > phi0 is no rest for the motion branch) and sticks
     * at the turning point t = pi */
    assert_true(motion.ne == 1 && motion.e[0].kind == DP_EVENT_STICK);
    assert_true(fabs(motion.e[0].t - M_PI) < 1e-5);
    traj_free(&rest);
    traj_free(&motion);
}

/* x'' = gamma_N(x') - x with N = 2 on the motion branch (x' > 0). */
static int power_rhs(double t, const double y[], double f[], void *params)
{
    (void)t, (void)params;
    f[0] = y[1];
    f[1] = 2 * sqrt(fmax(y[1], 0)) - y[0];
    return GSL_SUCCESS;
}

/* Motion branch of counterexample 2 at step dt: the largest relative error of x against t^3/3 on
 * [0.02, 0.06] (*early) and against an independent rk8pd integration on [0.1, 0.3] (*late). */
static void power_motion_errors(double dt, double *early, double *late)
{
    const char *m = "{\"mass\":1," LIN ",\"damper\":{\"law\":\"coulomb\",\"phi0\":1,\"relaxation\":{\"kind\":"
                    "\"power\",\"N\":2}},\"forcing\":{\"kind\":\"constant\",\"value\":1}}";
    char b[600];
    traj motion;
    assert_int_equal(traj_run(SPEC(b, "{\"model\":%s,\"solver\":{\"dt\":%g,\"t_end\":0.3,\"branch\":\"motion\"},"
                                   "\"output\":{\"every\":%d}}", m, dt, (int)(1e-4 / dt + 0.5)), &motion), DP_OK);
    assert_int_equal(motion.status, DP_DONE);
    *early = *late = 0;
    double y[2] = { 1e-6 / 3, 1e-4 }, t = 0.01; /* the asymptotic state x = t^3/3, x' = t^2 at t = 0.01 */
    gsl_odeiv2_system sys = { power_rhs, NULL, 2, NULL };
    gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-6, 1e-13, 1e-13);
    for (size_t i = 0; i < motion.n; i++) {
        double ti = motion.s[i].t, x = motion.s[i].x;
        if (ti >= 0.02 && ti <= 0.06)
            *early = fmax(*early, fabs(x * 3 / (ti * ti * ti) - 1));
        if (ti < 0.1)
            continue;
        assert_int_equal(gsl_odeiv2_driver_apply(d, &t, ti, y), GSL_SUCCESS);
        *late = fmax(*late, fabs(x - y[0]) / y[0]);
    }
    gsl_odeiv2_driver_free(d);
    assert_true(motion.s[motion.n - 1].x > 0.008); /* 0.3^3/3 = 0.009: it really left rest */
    traj_free(&motion);
}

/* Counterexample 2 (Pražák & Rajagopal 2016 (26)-(27)): Coulomb phi0 = 1 with gamma_N, N = 2, F = phi0 from rest.
 * Rest: x = 0 exactly. Motion: x'' + x = gamma_N(x') leaves rest like x' = t^N, x = t^(N+1)/(N+1);
 * backward Euler lags it by a few steps, so the error is O(dt / t) and shrinks tenfold with dt. */
static void test_counterexample_power_relaxation(void **state)
{
    (void)state;
    const char *m = "{\"mass\":1," LIN ",\"damper\":{\"law\":\"coulomb\",\"phi0\":1,\"relaxation\":{\"kind\":"
                    "\"power\",\"N\":2}},\"forcing\":{\"kind\":\"constant\",\"value\":1}}";
    char a[600];
    traj rest;
    assert_int_equal(traj_run(SPEC(a, "{\"model\":%s,\"solver\":{\"dt\":1e-4,\"t_end\":0.3}}", m), &rest), DP_OK);
    for (size_t i = 0; i < rest.n; i++)
        assert_true(rest.s[i].x == 0);
    traj_free(&rest);
    double e4, l4, e5, l5;
    power_motion_errors(1e-4, &e4, &l4);
    power_motion_errors(1e-5, &e5, &l5);
    printf("gamma_N motion branch: |3x/t^3 - 1| on [0.02, 0.06]: %.3e (dt 1e-4), %.3e (1e-5); "
           "vs rk8pd on [0.1, 0.3]: %.3e, %.3e\n", e4, e5, l4, l5);
    assert_true(e4 < 0.1 && e5 < 0.01);
    assert_true(l4 < 0.02 && l5 < 0.002);
    assert_true(l4 / l5 > 7 && l4 / l5 < 13); /* first order */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table),
        cmocka_unit_test(test_witnesses),
        cmocka_unit_test(test_counterexample_generalized_coulomb),
        cmocka_unit_test(test_counterexample_power_relaxation),
    };
    return cmocka_run_group_tests_name("wellposedness", tests, NULL, NULL);
}
