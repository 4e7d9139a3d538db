/* tests/test_laws.c - every law, relaxation and forcing kind against an independent reference:
 * closed forms (Coulomb resolvent = soft threshold, Yosida = clamp, damped oscillator), hand-computed
 * steps (Bingham, belt), and invariants (the rope never stretches past its length). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "dashpot/graph.h"
#include "dashpot/model.h"
#include "trajectory.h"

static void run_ok(const char *spec, traj *t)
{
    assert_int_equal(traj_run(spec, t), DP_OK);
    if (t->status != DP_DONE)
        fprintf(stderr, "run failed: %s\n", t->error);
    assert_int_equal(t->status, DP_DONE);
}

/* Coulomb: J_l(v) = sgn(v) max(|v| - l phi0, 0), A_l(v) = clamp(v/l, -phi0, phi0) (docs/mathematics.md §1). */
static void test_coulomb_resolvent_and_yosida(void **state)
{
    (void)state;
    dp_model m = { .mass = 1, .spring = { .law = DP_SPRING_LINEAR, .k = 1 },
                   .damper = { .law = DP_DAMPER_COULOMB, .phi0 = 0.7 } };
    assert_int_equal(dp_model_prepare(&m), DP_OK);
    const dp_graph *g = &m.damper.graph;
    for (double v = -3; v <= 3; v += 0.125) {
        for (double l = 0.25; l <= 4; l *= 2) {
            double J = copysign(fmax(fabs(v) - l * 0.7, 0), v);
            double Y = fmin(fmax(v / l, -0.7), 0.7);
            assert_true(fabs(dp_graph_resolvent(g, l, v) - J) < 1e-15);
            assert_true(fabs(dp_graph_yosida(g, l, v) - Y) < 1e-14);
        }
    }
    double lo, hi;
    dp_graph_force(g, 0, &lo, &hi);
    assert_true(lo == -0.7 && hi == 0.7);
    dp_graph_force(g, 1e-300, &lo, &hi);
    assert_true(lo == 0.7 && hi == 0.7);
    dp_graph_kinematic(g, 0.3, &lo, &hi);
    assert_true(lo == 0 && hi == 0);
    assert_true(isinf(dp_graph_lipschitz(g)));
    dp_model_clear(&m);
}

/* Rope (thesis Fig. 1): F = k x below L, any F >= kL at L, nothing beyond; Bingham: slope c past tau. */
static void test_rope_and_bingham_graphs(void **state)
{
    (void)state;
    dp_model m = { .mass = 1, .spring = { .law = DP_SPRING_ROPE, .k = 2, .length = 1.5 },
                   .damper = { .law = DP_DAMPER_BINGHAM, .tau = 0.5, .c = 3 } };
    assert_int_equal(dp_model_prepare(&m), DP_OK);
    double lo, hi;
    dp_graph_force(&m.spring.graph, 1, &lo, &hi);
    assert_true(lo == 2 && hi == 2);
    dp_graph_force(&m.spring.graph, 1.5, &lo, &hi);
    assert_true(lo == 3 && isinf(hi) && hi > 0);
    dp_graph_force(&m.spring.graph, 1.6, &lo, &hi);
    assert_true(isinf(lo) && lo > 0);
    dp_graph_kinematic(&m.spring.graph, 10, &lo, &hi);
    assert_true(lo == 1.5 && hi == 1.5);
    assert_true(dp_graph_lipschitz(&m.spring.graph) == INFINITY);
    /* the Bingham graph here is the stick interval only; its viscous part c is stepped by theta */
    dp_graph_force(&m.damper.graph, 0, &lo, &hi);
    assert_true(lo == -0.5 && hi == 0.5);
    dp_model_clear(&m);
    dp_graph g;
    double y[3] = { -1, 0, 2 }, f[3] = { -3, 0, 1 };
    assert_int_equal(dp_graph_init_points(&g, 3, y, f), DP_OK);
    assert_true(fabs(dp_graph_lipschitz(&g) - 3) < 1e-15);
    dp_graph_force(&g, 4, &lo, &hi); /* right ray continues the last segment, slope 1/2 */
    assert_true(fabs(lo - 2) < 1e-15);
    dp_graph_force(&g, -2, &lo, &hi);
    assert_true(fabs(lo + 6) < 1e-15);
    double bad_f[3] = { 0, -1, 1 };
    dp_graph g2;
    assert_int_equal(dp_graph_init_points(&g2, 3, y, bad_f), DP_EINVAL);
    dp_graph_clear(&g);
}

static void test_relaxation_values(void **state)
{
    (void)state;
    dp_relaxation r = { .kind = DP_RELAX_RATIONAL, .a = 0.5, .b = 1 };
    assert_true(fabs(dp_relaxation_eval(&r, 1) - 0.25) < 1e-16);
    assert_true(fabs(dp_relaxation_eval(&r, -3) + 0.375) < 1e-16);
    assert_true(dp_relaxation_lipschitz(&r) == 0.5 && dp_relaxation_bound(&r) == 0.5);
    dp_relaxation p = { .kind = DP_RELAX_POWER, .N = 2 };
    assert_true(fabs(dp_relaxation_eval(&p, 4) - 4) < 1e-15);  /* 2 * 4^(1/2) */
    assert_true(fabs(dp_relaxation_eval(&p, -0.25) + 1) < 1e-15);
    assert_true(dp_relaxation_eval(&p, 0) == 0 && isinf(dp_relaxation_lipschitz(&p)));
    dp_relaxation l = { .kind = DP_RELAX_LINEAR, .L = -0.3 };
    assert_true(fabs(dp_relaxation_eval(&l, 2) + 0.6) < 1e-16 && dp_relaxation_lipschitz(&l) == 0.3);
}

static void test_forcing_values(void **state)
{
    (void)state;
    double t[3] = { 0, 1, 3 }, F[3] = { 0, 2, -2 };
    dp_forcing terms[3] = {
        { .kind = DP_FORCING_CONSTANT, .value = 1.5 },
        { .kind = DP_FORCING_HARMONIC, .amplitude = 2, .omega = 3, .phase = 0.5 },
        { .kind = DP_FORCING_TABLE, .n = 3, .t = t, .F = F },
    };
    assert_true(fabs(dp_forcing_eval(&terms[1], 0.7) - 2 * cos(2.1 + 0.5)) < 1e-15);
    assert_true(fabs(dp_forcing_eval(&terms[2], 0.5) - 1) < 1e-15);
    assert_true(fabs(dp_forcing_eval(&terms[2], 2) - 0) < 1e-15);
    assert_true(dp_forcing_eval(&terms[2], -1) == 0 && dp_forcing_eval(&terms[2], 9) == -2);
    dp_forcing sum = { .kind = DP_FORCING_SUM, .nterms = 3, .terms = terms };
    assert_true(fabs(dp_forcing_eval(&sum, 2) - (1.5 + 2 * cos(6.5) + 0)) < 1e-15);
    double v;
    assert_false(dp_forcing_is_constant(&sum, &v));
    dp_forcing one = { .kind = DP_FORCING_SUM, .nterms = 1, .terms = terms };
    assert_true(dp_forcing_is_constant(&one, &v) && v == 1.5);
}

/* Linear damper, no threshold: the damped oscillator x'' + 0.4 x' + 4 x = 0, x(0) = 1 has the closed form
 * x = e^{-0.2 t}(cos(w t) + 0.2/w sin(w t)), w = sqrt(4 - 0.04); theta = 1/2 is second order. */
static void test_linear_damper_closed_form(void **state)
{
    (void)state;
    double err[2];
    for (int i = 0; i < 2; i++) {
        char spec[400];
        traj t;
        run_ok(SPEC(spec, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":4},\"damper\":{\"law\":"
                    "\"linear\",\"c\":0.4}},\"initial\":{\"x\":1},\"solver\":{\"dt\":%g,\"t_end\":5,\"theta\":0.5}}",
                    i ? 1e-3 : 1e-2), &t);
        double w = sqrt(3.96), e = 0;
        for (size_t j = 0; j < t.n; j++) {
            double tt = t.s[j].t, x = exp(-0.2 * tt) * (cos(w * tt) + 0.2 / w * sin(w * tt));
            e = fmax(e, fabs(t.s[j].x - x));
            assert_true(t.s[j].phase == DP_PHASE_NONE);
        }
        err[i] = e;
        traj_free(&t);
    }
    printf("linear damper errors %.3e %.3e order %.3f\n", err[0], err[1], log10(err[0] / err[1]));
    assert_true(err[1] < 1e-5 && fabs(log10(err[0] / err[1]) - 2) < 0.1);
}

/* Bingham, one step by hand (theta = 1): m = 1, k = 2, c = 3, tau = 0.5, h = 0.1, x = 1, v = 0, F = 0:
 * W = 1 + 0.3 + 0.02 = 1.32; u = (1*0 - 0.1*2*1)/1.32 = -0.151515...; thr = 0.05/1.32;
 * v1 = u + thr = -0.15/1.32 = -0.113636..., x1 = 1 + 0.1 v1. */
static void test_bingham_step_by_hand(void **state)
{
    (void)state;
    char spec[400];
    traj t;
    run_ok(SPEC(spec, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":2},\"damper\":{\"law\":"
                "\"bingham\",\"tau\":0.5,\"c\":3}},\"initial\":{\"x\":1},\"solver\":{\"dt\":0.1,\"t_end\":0.1,\"theta\":1}}"),
           &t);
    assert_int_equal(t.n, 2);
    double v1 = -0.15 / 1.32;
    assert_true(fabs(t.s[1].v - v1) < 1e-15);
    assert_true(fabs(t.s[1].x - (1 + 0.1 * v1)) < 1e-15);
    assert_true(fabs(t.s[1].Fc - (-0.5 + 3 * v1)) < 1e-14); /* yield force plus viscous part */
    assert_int_equal(t.s[1].phase, DP_PHASE_SLIP);
    traj_free(&t);
}

/* The rope holds: pulled by a constant load beyond kL, the mass stops at x = L and the rope carries the
 * rest of the load (F_s = F once at rest), never x > L. */
static void test_rope_holds(void **state)
{
    (void)state;
    char spec[400];
    traj t;
    run_ok(SPEC(spec, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"rope\",\"k\":1,\"length\":1},"
                "\"damper\":{\"law\":\"linear\",\"c\":0.5},\"forcing\":{\"kind\":\"constant\",\"value\":3}},"
                "\"solver\":{\"dt\":1e-3,\"t_end\":5}}"), &t);
    int hit = 0;
    for (size_t i = 0; i < t.n; i++) {
        assert_true(t.s[i].x <= 1);
        hit |= t.s[i].x == 1;
    }
    assert_true(hit);
    assert_true(t.sum.final.x == 1 && t.sum.final.v == 0);
    assert_true(fabs(t.sum.final.Fs - 3) < 1e-12);
    traj_free(&t);
}

/* Belt-driven stick-slip with static phi1 = 1 > kinetic phi0 = 0.8: during stick the block moves with the
 * belt (v = v_b exactly); the spring tears it loose when k x reaches phi1: every slip starts at x = 1, the
 * first at t = 1/v_b = 2.5. It then swings about phi0/k = 0.8 until its speed meets the belt's again. */
static void test_belt_stick_slip(void **state)
{
    (void)state;
    char spec[400];
    traj t;
    run_ok(SPEC(spec, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":"
                "\"generalized-coulomb\",\"phi0\":0.8,\"phi1\":1,\"belt_velocity\":0.4}},\"initial\":{\"v\":0.4},\"solver\":{\"dt\":1e-3,\"t_end\":30,"
                "\"theta\":0.5}}"), &t);
    assert_true(t.ne >= 4);
    assert_int_equal(t.e[0].kind, DP_EVENT_SLIP);
    assert_true(fabs(t.e[0].t - 2.5) < 1e-9 && fabs(t.e[0].x - 1) < 1e-9);
    size_t nstick = 0;
    for (size_t i = 0; i < t.n; i++)
        if (t.s[i].phase == DP_PHASE_STICK) {
            assert_true(t.s[i].v == 0.4);
            nstick++;
        }
    assert_true(nstick > 0);
    /* In this stick-slip cycle every slip starts at x = phi0/k = 1. */
    for (size_t i = 0; i < t.ne; i++)
        if (t.e[i].kind == DP_EVENT_SLIP)
            assert_true(fabs(t.e[i].x - 1) < 1e-6);
    traj_free(&t);
}

/* Harmonic forcing with sticking: theta = 1 converges to the theta = 1/2 solution at first order. */
static void test_harmonic_forcing_cross_check(void **state)
{
    (void)state;
    const char *model = "{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\","
                        "\"phi0\":0.5},\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":1,\"omega\":0.7}}";
    char a[600], b[600], c[600];
    traj ref, t1, t2;
    run_ok(SPEC(a, "{\"model\":%s,\"solver\":{\"dt\":1e-4,\"t_end\":20,\"theta\":0.5},\"output\":{\"every\":100}}",
                model), &ref);
    run_ok(SPEC(b, "{\"model\":%s,\"solver\":{\"dt\":1e-2,\"t_end\":20,\"theta\":1},\"output\":{\"every\":1}}", model), &t1);
    run_ok(SPEC(c, "{\"model\":%s,\"solver\":{\"dt\":1e-3,\"t_end\":20,\"theta\":1},\"output\":{\"every\":10}}", model), &t2);
    assert_int_equal(ref.n, t1.n);
    assert_int_equal(ref.n, t2.n);
    double e1 = 0, e2 = 0;
    for (size_t i = 0; i < ref.n; i++) {
        e1 = fmax(e1, fabs(t1.s[i].x - ref.s[i].x));
        e2 = fmax(e2, fabs(t2.s[i].x - ref.s[i].x));
    }
    printf("harmonic forcing: theta=1 errors %.3e %.3e order %.3f; %llu events\n", e1, e2, log10(e1 / e2),
           (unsigned long long)ref.sum.events);
    assert_true(ref.sum.events >= 2);
    assert_true(fabs(log10(e1 / e2) - 1) < 0.2);
    traj_free(&ref);
    traj_free(&t1);
    traj_free(&t2);
}

/* x'' + c x' + k x = F(t), integrated independently by GSL rk8pd. */
typedef struct smooth { double c, k; } smooth;

static double forcing_sum(double t)
{
    /* 0.5 cos(1.3 t + 0.2) + table (0, 0) (2, 1) (4, -1) (6, 0), the forcing of the spec below */
    double tab = t <= 0 ? 0 : t < 2 ? t / 2 : t < 4 ? 1 - (t - 2) : t < 6 ? -1 + (t - 4) / 2 : 0;
    return 0.5 * cos(1.3 * t + 0.2) + tab;
}

static int smooth_rhs(double t, const double y[], double f[], void *p)
{
    const smooth *s = p;
    f[0] = y[1];
    f[1] = forcing_sum(t) - s->c * y[1] - s->k * y[0];
    return GSL_SUCCESS;
}

/* Harmonic + table forcing through a sum, with no damper and with a linear damper whose viscosity is
 * partly cancelled by a linear relaxation (F_d = c v - L v): theta = 1/2 against rk8pd, second order. */
static void test_forcing_and_relaxation_against_rk8pd(void **state)
{
    (void)state;
    const char *dampers[2] = { "{\"law\":\"none\"}",
                               "{\"law\":\"linear\",\"c\":1,\"relaxation\":{\"kind\":\"linear\",\"L\":0.4}}" };
    const double ceff[2] = { 0, 0.6 };
    for (int k = 0; k < 2; k++) {
        double err[2];
        for (int j = 0; j < 2; j++) {
            char spec[1024];
            traj t;
            run_ok(SPEC(spec, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":2},\"damper\":%s,"
                        "\"forcing\":{\"kind\":\"sum\",\"terms\":[{\"kind\":\"harmonic\",\"amplitude\":0.5,"
                        "\"omega\":1.3,\"phase\":0.2},{\"kind\":\"table\",\"points\":[[0,0],[2,1],[4,-1],[6,0]]}]}},"
                        "\"initial\":{\"x\":0.3,\"v\":-0.2},\"solver\":{\"dt\":%g,\"t_end\":8,\"theta\":0.5},"
                        "\"output\":{\"every\":%d}}", dampers[k], j ? 1e-3 : 1e-2, j ? 100 : 10), &t);
            smooth p = { ceff[k], 2 };
            gsl_odeiv2_system sys = { smooth_rhs, NULL, 2, &p };
            gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-3, 1e-13, 1e-13);
            double y[2] = { 0.3, -0.2 }, tt = 0, e = 0;
            for (size_t i = 1; i < t.n; i++) {
                assert_int_equal(gsl_odeiv2_driver_apply(d, &tt, t.s[i].t, y), GSL_SUCCESS);
                e = fmax(e, fabs(t.s[i].x - y[0]));
            }
            gsl_odeiv2_driver_free(d);
            err[j] = e;
            traj_free(&t);
        }
        printf("forcing sum, damper %d: errors %.3e %.3e order %.3f\n", k, err[0], err[1], log10(err[0] / err[1]));
        /* the table's kinks cost a local O(dt^2) each, still second order globally */
        assert_true(err[1] < 1e-5 && log10(err[0] / err[1]) > 1.7);
    }
}

/* Found by the fuzzer: a user spring graph whose last piece is vertical bounds x like a rope; a start
 * beyond it has no solution and must be refused at /initial/x (and likewise for a velocity limit). */
static void test_initial_state_outside_graph_domain(void **state)
{
    (void)state;
    const char *docs[2] = {
        "{\"model\":{\"mass\":2,\"spring\":{\"law\":\"graph\",\"points\":[[-1,-2],[0,0],[1,1],[1,5]]},"
        "\"damper\":{\"law\":\"none\"}},\"initial\":{\"x\":5.5}}",
        "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"graph\","
        "\"points\":[[-1,-1],[0,0],[0,1]],\"belt_velocity\":0.3}},\"initial\":{\"v\":0.5}}",
    };
    const char *ptr[2] = { "/initial/x", "/initial/v" };
    for (int i = 0; i < 2; i++) {
        dp_spec spec;
        dp_errors errs;
        dp_spec_init(&spec);
        dp_errors_init(&errs);
        assert_int_equal(dp_spec_parse(docs[i], strlen(docs[i]), 0, &spec, &errs), DP_EINVAL);
        assert_int_equal(errs.n, 1);
        assert_string_equal(errs.item[0].pointer, ptr[i]);
        assert_non_null(strstr(errs.item[0].message, i ? "v - belt_velocity <= 0" : "x <= 1"));
        dp_spec_clear(&spec);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_coulomb_resolvent_and_yosida),
        cmocka_unit_test(test_rope_and_bingham_graphs),
        cmocka_unit_test(test_relaxation_values),
        cmocka_unit_test(test_forcing_values),
        cmocka_unit_test(test_linear_damper_closed_form),
        cmocka_unit_test(test_bingham_step_by_hand),
        cmocka_unit_test(test_rope_holds),
        cmocka_unit_test(test_belt_stick_slip),
        cmocka_unit_test(test_harmonic_forcing_cross_check),
        cmocka_unit_test(test_forcing_and_relaxation_against_rk8pd),
        cmocka_unit_test(test_initial_state_outside_graph_domain),
    };
    return cmocka_run_group_tests_name("laws", tests, NULL, NULL);
}
