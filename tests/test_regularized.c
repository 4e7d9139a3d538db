/* tests/test_regularized.c - the regularized schemes (PCn), (PIk) (Pražák & Rajagopal 2016 (17), Babováková 2012 ch. 2) and their
 * convergence to the exact stick-slip solution.
 *
 * Reference problem (thesis ch. 4): m = k = phi0 = 1, F = 0, x(0) = 4.5, x'(0) = 0. Exact: half circles about
 * -/+1, turning at -2.5 (t = pi), at rest at x = 0.5 from t = 2 pi on. Regularized with g_n(v) =
 * clamp(n v, -1, 1): once |n v| < 1 the motion is m x'' + n x' + k x = 0, whose slow mode
 * z = (-n + sqrt(n^2 - 4 m k)) / (2 m) ~ -k/n makes x creep from 0.5 towards 0 (docs/mathematics.md §3).
 * Over [2 pi, T] the creep is 0.5 (1 - exp(-k (T - 2 pi)/n)) ~ 0.5 (T - 2 pi)/n: the O(1/n) error, and
 * the creep speed right after stopping, 0.5 k/n, is the error in v.
 */
#include <complex.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <cjson/cJSON.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_rng.h>

#include "dashpot/encode.h"
#include "dashpot/regularized.h"
#include "trajectory.h"
#include "base/dense.h"

#define COULOMB "{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":1}"
#define DECADES "[10,100,1000,10000]"

/* ---- helpers ---------------------------------------------------------------------------------------- */

static void run_ok(const char *spec, traj *t)
{
    assert_int_equal(traj_run(spec, t), DP_OK);
    if (t->status != DP_DONE)
        fprintf(stderr, "run failed: %s\n", t->error);
    assert_int_equal(t->status, DP_DONE);
}

/* Parses spec text and runs the study (asserting both succeed). */
static void study(const char *json, dp_convergence *c)
{
    dp_spec spec;
    dp_errors e;
    dp_spec_init(&spec);
    dp_errors_init(&e);
    int s = dp_spec_parse(json, strlen(json), 0, &spec, &e);
    if (s == DP_OK)
        s = dp_convergence_study(&spec, 0, 0, c, &e);
    if (s != DP_OK && e.n)
        fprintf(stderr, "study: %s: %s\n", e.item[0].pointer, e.item[0].message);
    dp_spec_clear(&spec);
    assert_int_equal(s, DP_OK);
}

static void print_study(const char *what, const dp_convergence *c)
{
    printf("%s (reference %s):\n", what, c->reference == DP_REFERENCE_ANALYTIC ? "closed form" : "stick-slip");
    for (size_t i = 0; i < c->nrows; i++) {
        const dp_convergence_row *r = &c->row[i];
        printf("  n=%-8g err_x %.3e err_v %.3e rate %.3f %.3f  steps %llu rejected %llu fevals %llu\n", r->n,
               r->err_x, r->err_v, r->rate_x, r->rate_v, r->steps, r->rejected, r->fevals);
    }
    printf("  fitted rates %.4f %.4f\n", c->rate_x, c->rate_v);
}

/* Every consecutive rate and the fitted one within [lo, hi], for x and v. */
static void assert_rates(const dp_convergence *c, double lo, double hi)
{
    for (size_t i = 1; i < c->nrows; i++) {
        assert_true(c->row[i].rate_x >= lo && c->row[i].rate_x <= hi);
        assert_true(c->row[i].rate_v >= lo && c->row[i].rate_v <= hi);
    }
    assert_true(c->rate_x >= lo && c->rate_x <= hi);
    assert_true(c->rate_v >= lo && c->rate_v <= hi);
}

/* ---- g_n: the Yosida form, the rotated form (17), Coulomb's clamp ---------------------------------------- */

static double rotation_of(void *g, double s)
{
    return dp_graph_rotation(g, s);
}

static int coulomb_graph(dp_graph *g, double phi0)
{
    double y[2] = { 0, 0 }, f[2] = { -phi0, phi0 }, r[2] = { 1, 0 };
    return dp_graph_init(g, 2, y, f, r, r);
}

/* phi of Lemma 1 for Coulomb (docs/mathematics.md §1) and g_n = clamp(n v, -phi0, phi0) both ways. */
static void test_coulomb_gn_is_clamp(void **state)
{
    (void)state;
    dp_graph g;
    double phi0 = 0.75;
    assert_int_equal(coulomb_graph(&g, phi0), DP_OK);
    for (double s = -3; s <= 3; s += 0.125) {
        double want = fabs(s) <= phi0 ? s : s > 0 ? 2 * phi0 - s : -2 * phi0 - s;
        assert_true(fabs(dp_graph_rotation(&g, s) - want) < 1e-15);
    }
    const double ns[] = { 1, 3, 10, 1e3, 1e6 };
    for (size_t i = 0; i < 5; i++) {
        for (double v = -2; v <= 2; v += 1.0 / 64) {
            double n = ns[i], want = fmin(fmax(n * v, -phi0), phi0), slope;
            double y = dp_graph_yosida_slope(&g, 1 / n, v, &slope);
            double r = dp_regularized_gn(rotation_of, &g, n, v, NULL);
            assert_true(fabs(y - want) <= 1e-15 * fmax(1, n * fabs(v)));
            assert_true(fabs(r - want) <= 1e-12);
            /* The slope on the vertical piece is 1/(1/n), n to rounding. */
            assert_true(fabs(slope - (fabs(n * v) < phi0 ? n : 0)) <= 4e-16 * n || fabs(n * v) == phi0);
        }
    }
    dp_graph_clear(&g);
}

/* A random maximal monotone piecewise-linear graph: vertical, horizontal and sloped pieces, and rays of
 * each kind, through distinct vertices. */
static int random_graph(gsl_rng *rng, dp_graph *g)
{
    size_t n = 1 + gsl_rng_uniform_int(rng, 8);
    double y[8], f[8], d[3][2] = { { 0, 1 }, { 1, 0 }, { 1, 0 } };
    y[0] = 4 * gsl_rng_uniform(rng) - 2, f[0] = 4 * gsl_rng_uniform(rng) - 2;
    for (size_t i = 1; i < n; i++) {
        unsigned kind = (unsigned)gsl_rng_uniform_int(rng, 3); /* vertical, horizontal, sloped */
        double a = 0.05 + gsl_rng_uniform(rng), b = 0.05 + 3 * gsl_rng_uniform(rng);
        y[i] = y[i - 1] + (kind == 0 ? 0 : a);
        f[i] = f[i - 1] + (kind == 1 ? 0 : b);
    }
    d[2][1] = 0.01 + 5 * gsl_rng_uniform(rng);
    const double *left = d[gsl_rng_uniform_int(rng, 3)], *right = d[gsl_rng_uniform_int(rng, 3)];
    return dp_graph_init(g, n, y, f, left, right);
}

/* Paper (17) says (F_c, v - F_c/n) is on the graph; Lemma 1 says that is F - y = phi(F + y). g_n is
 * monotone and n-Lipschitz (the Yosida approximation A_(1/n)); the rotated fixed point agrees with it. */
static void check_gn_pair(dp_graph *g, double n, double v1, double v2, double *worst)
{
    double s1, s2, a = dp_graph_yosida_slope(g, 1 / n, v1, &s1), b = dp_graph_yosida_slope(g, 1 / n, v2, &s2);
    /* a = n (v - J): J carries the rounding of the vertices (|y| <= ~11 here), which n amplifies. */
    double scale = 1 + fabs(a) + fabs(b) + n * (fabs(v1) + fabs(v2) + 11);
    double tol = 16 * 2.220446049250313e-16 * scale;
    double r = dp_regularized_gn(rotation_of, g, n, v1, NULL);
    assert_true(fabs(r - a) <= 1e-10 * scale);
    assert_true(fabs(dp_graph_yosida(g, 1 / n, v1) - a) <= tol); /* graph.c's (y - J(y)) / l */
    double y = v1 - a / n;
    assert_true(fabs((a - y) - dp_graph_rotation(g, a + y)) <= tol);
    if (v1 < v2)
        assert_true(a <= b + tol);
    assert_true(fabs(b - a) <= n * fabs(v2 - v1) * (1 + 1e-12) + tol);
    assert_true(s1 >= 0 && s1 <= n * (1 + 1e-12));
    *worst = fmax(*worst, fabs(r - a) / scale);
}

static void test_gn_monotone_lipschitz_random(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 20160117);
    double worst = 0;
    for (int k = 0; k < 300; k++) {
        dp_graph g;
        assert_int_equal(random_graph(rng, &g), DP_OK);
        double n = pow(10, 4 * gsl_rng_uniform(rng));
        for (int j = 0; j < 200; j++) {
            double v1 = 6 * gsl_rng_uniform(rng) - 3, v2 = v1 + 0.1 * gsl_rng_uniform(rng) * (j % 2 ? 1 : 1e-4);
            check_gn_pair(&g, n, v1, v2, &worst);
        }
        dp_graph_clear(&g);
    }
    printf("300 random graphs x 200 pairs: |g_n by (17) - A_(1/n)| <= %.2e (relative)\n", worst);
    gsl_rng_free(rng);
}

/* The Jacobian's slope is the derivative of the Yosida approximation: central differences agree wherever
 * no kink lies within h. */
static void test_yosida_slope_is_derivative(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 7);
    int checked = 0;
    for (int k = 0; k < 200; k++) {
        dp_graph g;
        assert_int_equal(random_graph(rng, &g), DP_OK);
        double l = pow(10, -3 * gsl_rng_uniform(rng)), h = 1e-6, s, sm, sp;
        for (int j = 0; j < 50; j++) {
            double y = 6 * gsl_rng_uniform(rng) - 3;
            dp_graph_yosida_slope(&g, l, y, &s);
            dp_graph_yosida_slope(&g, l, y - h, &sm);
            dp_graph_yosida_slope(&g, l, y + h, &sp);
            if (sm != s || sp != s)
                continue; /* a kink nearby */
            double fd = (dp_graph_yosida(&g, l, y + h) - dp_graph_yosida(&g, l, y - h)) / (2 * h);
            assert_true(fabs(fd - s) <= 1e-6 * (1 + s));
            checked++;
        }
        dp_graph_clear(&g);
    }
    assert_true(checked > 5000);
    gsl_rng_free(rng);
}

/* ---- (PCn) against the closed form ------------------------------------------------------------------ */

static void test_coulomb_free_decay_first_order(void **state)
{
    (void)state;
    dp_convergence c;
    study("{\"model\":" COULOMB "},\"initial\":{\"x\":4.5},"
          "\"solver\":{\"kind\":\"regularized\",\"n\":" DECADES ",\"t_end\":10,\"dt\":0.01}}", &c);
    print_study("Coulomb free decay, PC", &c);
    assert_int_equal(c.reference, DP_REFERENCE_ANALYTIC);
    assert_int_equal(c.samples, 1001);
    assert_rates(&c, 0.8, 1.2);
    /* The creep law predicts the constants: n err_x -> 0.5 (10 - 2 pi), n err_v -> 0.5 (see the top). */
    const dp_convergence_row *r = &c.row[3];
    assert_true(fabs(r->n * r->err_x / (0.5 * (10 - 2 * M_PI)) - 1) < 0.01);
    assert_true(fabs(r->n * r->err_v / 0.5 - 1) < 0.01);
    assert_true(isnan(c.row[0].diff_x) && isnan(c.row[0].rate_x));
    /* Successive differences shrink like the errors (a Cauchy sequence at rate 1). */
    assert_true(fabs(c.row[3].diff_x / c.row[2].diff_x - 0.1) < 0.02);
}

/* F = 2 cos(1.3 t): stick phases start and end while the load turns; against stick-slip theta 1/2. */
static void test_coulomb_harmonic_first_order(void **state)
{
    (void)state;
    dp_convergence c;
    study("{\"model\":" COULOMB ",\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":2,\"omega\":1.3}},"
          "\"initial\":{\"x\":1},\"solver\":{\"kind\":\"regularized\",\"n\":" DECADES ",\"t_end\":10,"
          "\"dt\":0.01}}", &c);
    print_study("Coulomb, harmonic forcing, PC", &c);
    assert_int_equal(c.reference, DP_REFERENCE_STICK_SLIP);
    assert_true(c.ref_theta == 0.5 && c.ref_dt == 1e-4);
    assert_rates(&c, 0.8, 1.2);
    assert_true(c.row[3].err_x < 2e-4 && c.row[3].err_x > 2e-5);
}

/* In a stick phase F_c = g_n(v) = n v exactly and x decays with the slow root of m z^2 + n z + k. */
static void test_creep_law(void **state)
{
    (void)state;
    const double n = 100, z = (-n + sqrt(n * n - 4)) / 2; /* m = k = 1 */
    traj t;
    run_ok("{\"model\":" COULOMB "},\"initial\":{\"x\":4.5},\"solver\":{\"kind\":\"regularized\",\"n\":100,"
           "\"t_end\":30,\"dt\":0.5,\"rtol\":1e-10,\"atol\":1e-12}}", &t);
    assert_int_equal(t.n, 61);
    const dp_sample *a = &t.s[20], *b = &t.s[60]; /* t = 10 and 30: long after the stop at ~2 pi */
    assert_true(a->t == 10 && b->t == 30);
    double want = exp(z * 20), got = b->x / a->x;
    printf("creep x(30)/x(10) = %.12f, exp(z 20) = %.12f, exp(-20 k/n) = %.12f\n", got, want, exp(-0.2));
    assert_true(fabs(got / want - 1) < 1e-7);
    assert_true(fabs(a->v / a->x - z) < 1e-7 * fabs(z)); /* on the slow eigenvector */
    for (size_t i = 0; i < t.n; i++) {
        assert_int_equal(t.s[i].phase, DP_PHASE_NONE);
        /* (v - J(v)) n cancels: a few ulps of n |v|. */
        double clamp = fmin(fmax(n * t.s[i].v, -1), 1);
        assert_true(fabs(t.s[i].Fc - clamp) <= 8 * 2.220446049250313e-16 * (1 + n * fabs(t.s[i].v)));
        assert_true(t.s[i].Fd == t.s[i].Fc && t.s[i].Fs == t.s[i].x);
    }
    assert_int_equal(t.ne, 0);
    traj_free(&t);
}

/* ---- (PIk) ------------------------------------------------------------------------------------------ */

/* Bingham (tau = 1, c = 0.3): both laws regularized, k from 1e2 to 1e5, against stick-slip theta 1/2. */
static void test_pi_bingham_converges(void **state)
{
    (void)state;
    dp_convergence c;
    study("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"bingham\","
          "\"tau\":1,\"c\":0.3}},\"initial\":{\"x\":4.5},\"solver\":{\"kind\":\"regularized\",\"scheme\":\"PI\","
          "\"k\":[100,1000,10000,100000],\"t_end\":10,\"dt\":0.01}}", &c);
    print_study("Bingham, PI", &c);
    assert_int_equal(c.scheme, DP_SCHEME_PI);
    assert_rates(&c, 0.8, 1.2);
    assert_true(c.row[3].err_x < 1e-4 && c.row[3].err_v < 1e-4);
}

/* The max of x over a PI run with a rope of length 1 and a constant pull F0. */
static double rope_peak(double k, double x0, double F0, double *final_x)
{
    char spec[600];
    traj t;
    run_ok(SPEC(spec, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"rope\",\"k\":1,\"length\":1},"
                "\"damper\":{\"law\":\"bingham\",\"tau\":0.2,\"c\":0.5},\"forcing\":{\"kind\":\"constant\","
                "\"value\":%g}},\"initial\":{\"x\":%g},\"solver\":{\"kind\":\"regularized\",\"scheme\":\"PI\","
                "\"k\":%g,\"t_end\":20,\"dt\":0.001}}", F0, x0, k), &t);
    double peak = -INFINITY;
    for (size_t i = 0; i < t.n; i++)
        peak = fmax(peak, t.s[i].x);
    *final_x = t.s[t.n - 1].x;
    traj_free(&t);
    return peak;
}

/* The rope (x <= L = 1) regularized: S_(1/k)(x) = x / (1/k_s + 1/k) below L + k_s L/k, k (x - L) beyond (the
 * vertical ray seen through (FIk): x = L + F/k). Loaded from rest at L by F0 = 3 (k_s = 1), it settles where
 * F_s = 3, at x - L = 3/k, and (damped) overshoots it at most twice: x <= L + 6/k = L + O(1/k). Arriving
 * at speed v_c instead, the overshoot is ~ v_c sqrt(m/k): O(k^-1/2), the price of an impact. */
static void test_pi_rope(void **state)
{
    (void)state;
    const double ks[] = { 1e2, 1e3, 1e4 };
    double over[3], impact[3], fx;
    for (int i = 0; i < 3; i++) {
        over[i] = rope_peak(ks[i], 1, 3, &fx) - 1;
        printf("k=%g: quasi-static peak x - L %.4e (bound 6/k = %.4e), final x - L = %.4e (3/k = %.4e)\n", ks[i],
               over[i], 6 / ks[i], fx - 1, 3 / ks[i]);
        assert_true(over[i] > 3 / ks[i] && over[i] <= 6 / ks[i]);
        assert_true(fabs((fx - 1) * ks[i] / 3 - 1) < 0.02);
        impact[i] = rope_peak(ks[i], 0, 3, &fx) - 1;
    }
    for (int i = 1; i < 3; i++) {
        double p = log10(over[i - 1] / over[i]), q = log10(impact[i - 1] / impact[i]);
        printf("decade %d: static overshoot order %.3f, impact overshoot order %.3f\n", i, p, q);
        assert_true(p > 0.9 && p < 1.1);
        assert_true(q > 0.4 && q < 0.6);
    }
}

/* ---- the run: grid, decimation, steppers, failures ------------------------------------------------------ */

/* Samples on t_j = j dt and t_end whatever the steps. msbdf's steps do not depend on the output grid, so
 * output.every = 4 gives bitwise the samples of every = 1 at the times it keeps (it used to land on them: the
 * two runs took different steps and agreed to 1e-8). */
static void test_samples_on_grid_and_decimation(void **state)
{
    (void)state;
    traj a, b;
    run_ok("{\"model\":" COULOMB "},\"initial\":{\"x\":3},\"solver\":{\"kind\":\"regularized\",\"n\":1000,"
           "\"t_end\":1.05,\"dt\":0.1,\"rtol\":1e-11,\"atol\":1e-12}}", &a);
    run_ok("{\"model\":" COULOMB "},\"initial\":{\"x\":3},\"solver\":{\"kind\":\"regularized\",\"n\":1000,"
           "\"t_end\":1.05,\"dt\":0.1,\"rtol\":1e-11,\"atol\":1e-12},\"output\":{\"every\":4}}", &b);
    assert_int_equal(a.n, 12); /* 0, 0.1, ..., 1.0, 1.05 */
    for (size_t i = 0; i + 1 < a.n; i++)
        assert_true(a.s[i].t == (double)i * 0.1);
    assert_true(a.s[11].t == 1.05);
    assert_int_equal(b.n, 4); /* 0, 0.4, 0.8, 1.05 */
    for (size_t i = 0; i < b.n; i++)
        assert_memory_equal(&b.s[i], &a.s[i < 3 ? 4 * i : 11], sizeof b.s[i]);
    assert_true(a.sum.steps == b.sum.steps && a.sum.fevals == b.sum.fevals);
    assert_true(a.sum.fevals > a.sum.steps && a.sum.iterations > 0 && a.sum.steps > 10);
    traj_free(&a);
    traj_free(&b);
}

/* Every stepper solves the same ODE: x(t_end) agrees to the tolerance's order. */
static void test_steppers_agree(void **state)
{
    (void)state;
    const char *names[] = { "msbdf", "rk4imp", "bsimp", "rkf45", "rkck", "rk8pd" };
    double x0 = 0;
    for (int i = 0; i < 6; i++) {
        char spec[512];
        traj t;
        run_ok(SPEC(spec, "{\"model\":" COULOMB "},\"initial\":{\"x\":4.5},\"solver\":{\"kind\":\"regularized\","
                    "\"n\":100,\"t_end\":10,\"dt\":1,\"stepper\":\"%s\",\"rtol\":1e-10,\"atol\":1e-10}}", names[i]),
               &t);
        double x = t.sum.final.x;
        printf("%-7s x(10) = %.12f steps %llu rejected %llu fevals %llu\n", names[i], x, t.sum.steps,
               t.sum.rejected, t.sum.fevals);
        if (i == 0)
            x0 = x;
        assert_true(fabs(x - x0) < 1e-7);
        traj_free(&t);
    }
}

/* ---- samples between the integrator's steps (src/core/base/dense.c) --------------------------------------- */

/* The quintic Hermite interpolant reproduces a quintic from its ends' values and two derivatives, and misses
 * t^6 by its error term h^6/720 s^3 (s - 1)^3 exactly; Neville's polynomial reproduces its degree. */
static void test_dense_interpolants_exact(void **state)
{
    (void)state;
    const double c[6] = { 0.3, -1.2, 0.7, 2.1, -0.4, 0.15 }, ta = 1.5, tb = 2.25, h = tb - ta;
    double y[2][3]; /* the quintic sum c_k t^k and t^6: value, first and second derivative at both ends */
    double z[2][3];
    for (int e = 0; e < 2; e++) {
        double t = e ? tb : ta;
        y[e][0] = y[e][1] = y[e][2] = 0;
        for (int k = 5; k >= 0; k--) {
            y[e][2] = y[e][2] * t + y[e][1] * 2, y[e][1] = y[e][1] * t + y[e][0], y[e][0] = y[e][0] * t + c[k];
        }
        z[e][0] = pow(t, 6), z[e][1] = 6 * pow(t, 5), z[e][2] = 30 * pow(t, 4);
    }
    for (double s = 0; s <= 1; s += 0.125) {
        double t = ta + s * h, p = 0, out;
        for (int k = 5; k >= 0; k--)
            p = p * t + c[k];
        dp_hermite_end a = { ta, &y[0][0], &y[0][1], &y[0][2] }, b = { tb, &y[1][0], &y[1][1], &y[1][2] };
        dp_hermite5(&a, &b, 1, t, &out);
        assert_true(fabs(out - p) <= 1e-14 * (1 + fabs(p)));
        dp_hermite_end a6 = { ta, &z[0][0], &z[0][1], &z[0][2] }, b6 = { tb, &z[1][0], &z[1][1], &z[1][2] };
        dp_hermite5(&a6, &b6, 1, t, &out);
        double want = pow(h, 6) * pow(s, 3) * pow(s - 1, 3); /* t^6 - p(t), y^(6) = 720 */
        assert_true(fabs(pow(t, 6) - out - want) <= 1e-12);
        /* Degree 4 through 5 points, two components, unevenly spaced as an integrator's steps are. */
        const double ts[5] = { 0, 0.1, 0.35, 0.8, 1.5 };
        double ys[5][2], q[2];
        for (int k = 0; k < 5; k++)
            ys[k][0] = 1 - 2 * ts[k] + pow(ts[k], 4), ys[k][1] = 3 * pow(ts[k], 3);
        dp_poly_interp(ts, ys[0], 5, 2, s, q);
        assert_true(fabs(q[0] - (1 - 2 * s + pow(s, 4))) < 1e-14 && fabs(q[1] - 3 * pow(s, 3)) < 1e-14);
    }
}

/* x(t), v(t) of m x'' + c x' + k x = A cos(w t), x(0) = x0, v(0) = 0 (the regularized ODE of a linear spring
 * and a linear damper, whatever n). Roots q/m and k/q with q = -(c + sqrt(c^2 - 4 m k))/2 (no cancellation). */
static void linear_exact(double m, double c, double k, double A, double w, double x0, double t, double *x,
                         double *v)
{
    double complex q = -(c + csqrt(c * c - 4 * m * k)) / 2, l1 = q / m, l2 = k / q;
    double d = (k - m * w * w) * (k - m * w * w) + c * c * w * w;
    double X = A * (k - m * w * w) / d, Y = A * c * w / d; /* particular X cos + Y sin */
    double complex b = (-Y * w - l1 * (x0 - X)) / (l2 - l1), a = x0 - X - b;
    *x = creal(a * cexp(l1 * t) + b * cexp(l2 * t)) + X * cos(w * t) + Y * sin(w * t);
    *v = creal(a * l1 * cexp(l1 * t) + b * l2 * cexp(l2 * t)) - X * w * sin(w * t) + Y * w * cos(w * t);
}

#define FORCED_LINEAR "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":" \
    "\"linear\",\"c\":%g},\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":2,\"omega\":1.3}},\"initial\":{\"x\":1}," \
    "\"solver\":{\"kind\":\"regularized\",\"n\":100,\"t_end\":%.17g,\"dt\":%g,\"rtol\":%g,\"atol\":%g," \
    "\"stepper\":\"%s\"}}"

/* The largest |error| / (1 + |exact|) of a run's x and v against the closed form. */
static double linear_error(const traj *t, double c)
{
    double worst = 0;
    for (size_t j = 0; j < t->n; j++) {
        double x, v;
        linear_exact(1, c, 1, 2, 1.3, 1, t->s[j].t, &x, &v);
        worst = fmax(worst, fmax(fabs(t->s[j].x - x) / (1 + fabs(x)), fabs(t->s[j].v - v) / (1 + fabs(v))));
    }
    return worst;
}

/* The largest |difference| / (1 + |y|) between a's samples at T and runs that end at T, for T = 0.37 j: a
 * free stepper's run to T takes a's steps up to the one that holds T and then lands on T (unless a step
 * attempt that reached past T was rejected: then the two part a little earlier), so this is the
 * interpolant's error plus one local error, with no global error in it. */
static double landing_difference(const traj *a, double c, double tol, const char *st)
{
    double worst = 0;
    for (int j = 1; j <= 13; j++) {
        double T = 0.37 * j;
        size_t i = (size_t)llround(T / 0.001);
        char spec[600];
        traj b;
        run_ok(SPEC(spec, FORCED_LINEAR, c, T, 0.001, tol, tol, st), &b);
        const dp_sample *p = &a->s[i], *q = &b.s[b.n - 1];
        assert_true(fabs(p->t - T) < 1e-12 && q->t == T);
        worst = fmax(worst, fmax(fabs(p->x - q->x) / (1 + fabs(q->x)), fabs(p->v - q->v) / (1 + fabs(q->v))));
        traj_free(&b);
    }
    return worst;
}

/* (a) Linear spring and damper driven by 2 cos 1.3t (closed form): samples far denser (dt = 0.001) and far
 * sparser (dt = 1.25) than the steps, a light damper (c = 0.5: Hermite) and a stiff one (c = 1000, h |J| up
 * to ~1e3: msbdf's own polynomial), msbdf and the explicit rkf45. Against runs that land on the sample time,
 * every sample is within 3 tol (measured <= 1.3): the interpolant adds about one local error. Against the
 * closed form, within 200 tol: that is the integrators' global error, the same at the landings (msbdf on the
 * light damper: 160 tol by t = 5; rkf45: 1 tol). */
static void test_interpolated_samples_linear(void **state)
{
    (void)state;
    const char *steppers[] = { "msbdf", "rkf45" };
    const double cs[] = { 0.5, 1000 }, tols[] = { 1e-6, 1e-9 };
    for (int i = 0; i < 8; i++) {
        const char *st = steppers[i & 1];
        double c = cs[(i >> 1) & 1], tol = tols[(i >> 2) & 1];
        char spec[600];
        traj dense, sparse;
        run_ok(SPEC(spec, FORCED_LINEAR, c, 5.0, 0.001, tol, tol, st), &dense);
        run_ok(SPEC(spec, FORCED_LINEAR, c, 5.0, 1.25, tol, tol, st), &sparse);
        double ed = linear_error(&dense, c), es = linear_error(&sparse, c), el = landing_difference(&dense, c, tol, st);
        printf("%-5s c = %-4g tol = %g: %4llu steps; error dt = 0.001 %6.2f tol, dt = 1.25 %6.2f tol; "
               "against landing %.2f tol\n", st, c, tol, dense.sum.steps, ed / tol, es / tol, el / tol);
        assert_int_equal(dense.n, 5001);
        assert_int_equal(sparse.n, 5);
        assert_true(ed <= 200 * tol && es <= 200 * tol);
        assert_true(el <= 3 * tol);
        traj_free(&dense);
        traj_free(&sparse);
    }
}

/* (b) The Coulomb free decay (a kink at every turning point and at the stop, a stiff creep after it) sampled
 * every 0.01 at rtol = atol = 1e-8, against the same run at 1e-12 and against runs that land on the sample
 * times. msbdf's global error here is ~300 tol, landing or not (rkf45's ~70); the interpolant adds ~1 tol,
 * up to ~10 tol next to the stop where the landing run's last steps differ. After the stop v ~ -x/n is slaved
 * to x by the stiff mode: Hermite from f(y) misses it by 17 tol at n = 100 and 84 tol at n = 1e4 (measured);
 * msbdf's own polynomial is within its global error, x's divided by n (2.8 and 0.02 tol). */
static void test_interpolated_samples_coulomb(void **state)
{
    (void)state;
    const double tol = 1e-8, ns[] = { 100, 1e4, 1000 };
    const char *steppers[] = { "msbdf", "msbdf", "rkf45" };
    for (int i = 0; i < 3; i++) {
        char spec[600];
        traj a, ref;
        run_ok(SPEC(spec, "{\"model\":" COULOMB "},\"initial\":{\"x\":4.5},\"solver\":{\"kind\":\"regularized\","
                    "\"n\":%g,\"t_end\":10,\"dt\":0.01,\"rtol\":%g,\"atol\":%g,\"stepper\":\"%s\"}}", ns[i], tol, tol,
                    steppers[i]), &a);
        run_ok(SPEC(spec, "{\"model\":" COULOMB "},\"initial\":{\"x\":4.5},\"solver\":{\"kind\":\"regularized\","
                    "\"n\":%g,\"t_end\":10,\"dt\":0.01,\"rtol\":1e-12,\"atol\":1e-12,\"stepper\":\"%s\"}}", ns[i],
                    steppers[i]), &ref);
        assert_int_equal(a.n, 1001);
        assert_int_equal(ref.n, 1001);
        double dy = 0, creep = 0, land = 0;
        for (size_t j = 0; j < a.n; j++) {
            dy = fmax(dy, fmax(fabs(a.s[j].x - ref.s[j].x), fabs(a.s[j].v - ref.s[j].v)));
            if (a.s[j].t >= 7) /* the stop is at 2 pi */
                creep = fmax(creep, fabs(a.s[j].v - ref.s[j].v));
        }
        for (int j = 1; j <= 27; j++) {
            double T = 0.37 * j;
            traj b;
            run_ok(SPEC(spec, "{\"model\":" COULOMB "},\"initial\":{\"x\":4.5},\"solver\":{\"kind\":"
                        "\"regularized\",\"n\":%g,\"t_end\":%.17g,\"dt\":0.01,\"rtol\":%g,\"atol\":%g,"
                        "\"stepper\":\"%s\"}}", ns[i], T, tol, tol, steppers[i]), &b);
            const dp_sample *p = &a.s[llround(T / 0.01)], *q = &b.s[b.n - 1];
            land = fmax(land, fmax(fabs(p->x - q->x), fabs(p->v - q->v)) / (1 + fabs(q->x)));
            traj_free(&b);
        }
        printf("%-5s n = %-5g %4llu steps: against 1e-12 %.0f tol, after the stop |dv| %.2f tol; against "
               "landing %.2f tol\n", steppers[i], ns[i], a.sum.steps, dy / tol, creep / tol, land / tol);
        assert_true(dy <= 500 * tol);
        assert_true(creep <= 10 * tol);
        assert_true(land <= 20 * tol);
        traj_free(&a);
        traj_free(&ref);
    }
}

/* Runs spec pulling at most cap records per dp_run_next call (traj_run pulls 257). */
static void run_blocks(const char *json, size_t cap, traj *t)
{
    memset(t, 0, sizeof *t);
    dp_spec spec;
    dp_errors e;
    int s;
    dp_spec_init(&spec);
    dp_errors_init(&e);
    assert_int_equal(dp_spec_parse(json, strlen(json), 0, &spec, &e), DP_OK);
    dp_run *r = dp_run_alloc(&spec, 0, &e, &s);
    dp_spec_clear(&spec);
    assert_non_null(r);
    dp_record *buf = malloc(cap * sizeof *buf);
    size_t n;
    do {
        s = dp_run_next(r, buf, cap, &n);
        for (size_t i = 0; i < n; i++)
            traj_push(t, &buf[i]);
    } while (s == DP_MORE);
    t->status = s;
    t->sum = *dp_run_summary(r);
    free(buf);
    dp_run_free(r);
}

/* (c) Pulling a run one record at a time gives bitwise the samples and summary of pulling it 4096 at a time:
 * msbdf with 100 samples inside most steps (a block ends between two samples of one step), and rkf45 at
 * n = 1e5, whose 1.5e5 explicit steps (most in the stiff creep after the stop) outlast the 1e5-step budget
 * of a call (a block ends between two steps, with no sample due). */
static void test_blocks_bitwise(void **state)
{
    (void)state;
    const char *specs[] = {
        "{\"model\":" COULOMB "},\"initial\":{\"x\":4.5},\"solver\":{\"kind\":\"regularized\",\"n\":1000,"
        "\"t_end\":10,\"dt\":0.001}}",
        "{\"model\":" COULOMB "},\"initial\":{\"x\":4.5},\"solver\":{\"kind\":\"regularized\",\"n\":1e5,"
        "\"t_end\":11,\"dt\":0.01,\"stepper\":\"rkf45\"}}",
    };
    for (int i = 0; i < 2; i++) {
        traj one, many;
        run_blocks(specs[i], 1, &one);
        run_blocks(specs[i], 4096, &many);
        printf("blocks of 1 and of 4096: %zu and %zu samples, %llu and %llu steps\n", one.n, many.n, one.sum.steps,
               many.sum.steps);
        assert_int_equal(one.status, DP_DONE);
        assert_int_equal(many.status, DP_DONE);
        assert_int_equal(one.n, many.n);
        assert_memory_equal(one.s, many.s, one.n * sizeof *one.s);
        assert_memory_equal(&one.sum, &many.sum, sizeof one.sum);
        assert_true(i == 0 || one.sum.steps > 100000);
        traj_free(&one);
        traj_free(&many);
    }
}

static int linear_rhs(double t, const double y[], double f[], void *p)
{
    const double *c = p; /* m, k, c, A, w */
    f[0] = y[1];
    f[1] = (c[3] * cos(c[4] * t + 0) - c[1] * y[0] - c[2] * y[1]) / c[0];
    return GSL_SUCCESS;
}

static int linear_jac(double t, const double y[], double *dfdy, double dfdt[], void *p)
{
    const double *c = p;
    (void)y;
    dfdy[0] = 0, dfdy[1] = 1, dfdy[2] = -c[1] / c[0], dfdy[3] = -c[2] / c[0];
    dfdt[0] = 0, dfdt[1] = -c[3] * c[4] * sin(c[4] * t + 0) / c[0];
    return GSL_SUCCESS;
}

/* (d) The sample at t_end is the integrator's own landing there, not an interpolation: for msbdf and rkf45
 * it is bitwise what a plain GSL evolve loop to t_end gives (same system, first step, tolerances), whatever
 * the output grid, and the steps are the same with samples every 0.01 or only at t_end. */
static void test_t_end_sample_is_landing(void **state)
{
    (void)state;
    const char *steppers[] = { "msbdf", "rkf45" };
    const gsl_odeiv2_step_type *types[2];
    types[0] = gsl_odeiv2_step_msbdf, types[1] = gsl_odeiv2_step_rkf45;
    double law[5] = { 1, 1, 3, 2, 1.3 }, t_end = 7.3;
    for (int i = 0; i < 2; i++) {
        char spec[600];
        traj grid, ends;
        run_ok(SPEC(spec, FORCED_LINEAR, law[2], t_end, 0.01, 1e-9, 1e-9, steppers[i]), &grid);
        run_ok(SPEC(spec, FORCED_LINEAR, law[2], t_end, t_end, 1e-9, 1e-9, steppers[i]), &ends);
        gsl_odeiv2_system sys = { linear_rhs, linear_jac, 2, law };
        double h = 1e-3 / (100 + 1), t = 0, y[2] = { 1, 0 }; /* the first step dashpot takes: 1e-3 m/(n+1) */
        gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, types[i], h, 1e-9, 1e-9);
        while (t < t_end)
            assert_int_equal(gsl_odeiv2_evolve_apply(d->e, d->c, d->s, &sys, &t, t_end, &h, y), GSL_SUCCESS);
        const dp_sample *a = &grid.s[grid.n - 1], *b = &ends.s[ends.n - 1];
        printf("%-5s x(t_end) %.17g: dt = 0.01 %s, dt = t_end %s, GSL loop %llu steps, dashpot %llu\n",
               steppers[i], y[0], a->x == y[0] ? "same" : "DIFFERS", b->x == y[0] ? "same" : "DIFFERS",
               (unsigned long long)d->e->count, grid.sum.steps);
        assert_int_equal(grid.n, 731);
        assert_int_equal(ends.n, 2);
        assert_true(a->t == t_end && b->t == t_end);
        assert_true(a->x == y[0] && a->v == y[1] && b->x == y[0] && b->v == y[1]);
        assert_memory_equal(a, b, sizeof *a);
        assert_true(grid.sum.steps == d->e->count && ends.sum.steps == d->e->count);
        gsl_odeiv2_driver_free(d);
        traj_free(&grid);
        traj_free(&ends);
    }
}

/* Negative damping gamma = 100 v: the solution grows like e^(100 t) and leaves the doubles near t = 7;
 * the run fails with DP_ENONFINITE and no sample holds a non-finite number. */
static void test_divergence_is_an_error(void **state)
{
    (void)state;
    traj t;
    assert_int_equal(traj_run("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":"
                              "\"coulomb\",\"phi0\":1,\"relaxation\":{\"kind\":\"linear\",\"L\":100}}},"
                              "\"initial\":{\"x\":1},\"solver\":{\"kind\":\"regularized\",\"n\":10,\"t_end\":20,"
                              "\"dt\":0.1}}", &t), DP_OK);
    printf("diverging run: status %d, %zu samples, \"%s\"\n", t.status, t.n, t.error);
    assert_int_equal(t.status, DP_ENONFINITE);
    assert_true(t.n > 10 && t.n < 200);
    for (size_t i = 0; i < t.n; i++)
        assert_true(isfinite(t.s[i].x) && isfinite(t.s[i].v) && isfinite(t.s[i].Fd));
    traj_free(&t);
}

/* atol = 1e-300 with rtol = 0 asks for more digits than doubles hold: the step size collapses at t = 0 and
 * the run stops with DP_ESOLVE at once (not after 10^9 steps of 1e-150), with only the initial sample. */
static void test_impossible_tolerance_is_an_error(void **state)
{
    (void)state;
    traj t;
    assert_int_equal(traj_run("{\"model\":" COULOMB "},\"initial\":{\"x\":4.5},\"solver\":{\"kind\":"
                              "\"regularized\",\"n\":1000,\"dt\":1,\"rtol\":0,\"atol\":1e-300}}", &t), DP_OK);
    printf("impossible tolerance: status %d after %llu steps: \"%s\"\n", t.status, t.sum.steps, t.error);
    assert_int_equal(t.status, DP_ESOLVE);
    assert_true(strstr(t.error, "cannot be met") != NULL);
    assert_true(t.sum.steps < 1000);
    assert_int_equal(t.n, 1);
    traj_free(&t);
}

static void test_rules(void **state)
{
    (void)state;
    traj t;
    const char *bad[] = {
        "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"generalized-coulomb\","
        "\"phi0\":1,\"phi1\":2}},\"solver\":{\"kind\":\"regularized\"}}",
        "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":1,"
        "\"relaxation\":{\"kind\":\"power\",\"N\":2}}},\"solver\":{\"kind\":\"regularized\"}}",
        "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":1,"
        "\"relaxation\":{\"kind\":\"linear\",\"L\":0.1}}},\"solver\":{\"kind\":\"regularized\",\"scheme\":\"PI\"}}",
    };
    for (int i = 0; i < 3; i++)
        assert_int_equal(traj_run(bad[i], &t), DP_EINVAL);
    dp_convergence c;
    dp_spec spec;
    dp_errors e;
    dp_spec_init(&spec);
    dp_errors_init(&e);
    assert_int_equal(dp_convergence_study(&spec, 0, 0, &c, &e), DP_EINVAL); /* not the regularized solver */
    assert_string_equal(e.item[0].pointer, "/solver/kind");
}

/* A stop callback that answers "stop" on its n-th call. */
static int stop_after(void *ctx)
{
    int *left = ctx;
    return --*left <= 0;
}

/* dp_convergence_study_until: a study that is asked to stop ends with DP_ECANCEL and an error at "", after
 * asking once per block; one that is never asked to stop gives what dp_convergence_study gives. */
static void test_study_stop(void **state)
{
    (void)state;
    const char *json = "{\"model\":" COULOMB "},\"initial\":{\"x\":2},\"solver\":{\"kind\":\"regularized\","
                       "\"n\":[10,100],\"t_end\":20,\"dt\":0.01}}";
    dp_spec spec;
    dp_errors e;
    dp_spec_init(&spec);
    dp_errors_init(&e);
    assert_int_equal(dp_spec_parse(json, strlen(json), 0, &spec, &e), DP_OK);
    dp_convergence a, b;
    int left = 5;
    assert_int_equal(dp_convergence_study_until(&spec, 0, 0, stop_after, &left, &a, &e), DP_ECANCEL);
    assert_int_equal(e.n, 1);
    assert_string_equal(e.item[0].pointer, "");
    assert_true(a.samples < 2001);
    printf("stopped after %llu of 2001 output times: %s\n", a.samples, e.item[0].message);
    dp_errors_init(&e);
    left = 1 << 30;
    assert_int_equal(dp_convergence_study_until(&spec, 0, 0, stop_after, &left, &a, &e), DP_OK);
    assert_int_equal(dp_convergence_study(&spec, 0, 0, &b, &e), DP_OK);
    assert_int_equal(a.samples, 2001);
    assert_true(a.row[1].err_x == b.row[1].err_x && a.rate_x == b.rate_x);
    dp_spec_clear(&spec);
}

/* The JSON of a study parses back with its numbers and nulls. */
static void test_study_json(void **state)
{
    (void)state;
    dp_convergence c;
    study("{\"model\":" COULOMB "},\"initial\":{\"x\":2},\"solver\":{\"kind\":\"regularized\",\"n\":[10,100],"
          "\"t_end\":2,\"dt\":0.5}}", &c);
    dp_buf b = { 0 };
    assert_int_equal(dp_convergence_json(&c, &b), DP_OK);
    cJSON *root = cJSON_Parse(b.data);
    assert_non_null(root);
    assert_string_equal(cJSON_GetObjectItem(root, "scheme")->valuestring, "PC");
    assert_string_equal(cJSON_GetObjectItem(cJSON_GetObjectItem(root, "reference"), "solver")->valuestring,
                        "analytic");
    cJSON *rows = cJSON_GetObjectItem(root, "rows");
    assert_int_equal(cJSON_GetArraySize(rows), 2);
    cJSON *r0 = cJSON_GetArrayItem(rows, 0), *r1 = cJSON_GetArrayItem(rows, 1);
    assert_true(cJSON_IsNull(cJSON_GetObjectItem(r0, "rate_x")));
    assert_true(cJSON_GetObjectItem(r1, "err_x")->valuedouble == c.row[1].err_x);
    assert_true(cJSON_GetObjectItem(r1, "steps")->valuedouble == (double)c.row[1].steps);
    cJSON_Delete(root);
    dp_buf_free(&b);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_coulomb_gn_is_clamp),
        cmocka_unit_test(test_gn_monotone_lipschitz_random),
        cmocka_unit_test(test_yosida_slope_is_derivative),
        cmocka_unit_test(test_coulomb_free_decay_first_order),
        cmocka_unit_test(test_coulomb_harmonic_first_order),
        cmocka_unit_test(test_creep_law),
        cmocka_unit_test(test_pi_bingham_converges),
        cmocka_unit_test(test_pi_rope),
        cmocka_unit_test(test_samples_on_grid_and_decimation),
        cmocka_unit_test(test_steppers_agree),
        cmocka_unit_test(test_dense_interpolants_exact),
        cmocka_unit_test(test_interpolated_samples_linear),
        cmocka_unit_test(test_interpolated_samples_coulomb),
        cmocka_unit_test(test_blocks_bitwise),
        cmocka_unit_test(test_t_end_sample_is_landing),
        cmocka_unit_test(test_divergence_is_an_error),
        cmocka_unit_test(test_impossible_tolerance_is_an_error),
        cmocka_unit_test(test_rules),
        cmocka_unit_test(test_study_json),
        cmocka_unit_test(test_study_stop),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
