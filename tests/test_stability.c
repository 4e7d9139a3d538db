/* tests/test_stability.c - stability of linear implicit laws: thesis models 1.2-1.4 on both sides
 * of (1.10), (1.12), (1.14) down to 1e-9 relative, Hurwitz minors against roots on 10^4 random polynomials,
 * maps against the closed-form boundaries, state matrices against the roots, DAE pencils, and the wire
 * format (dp_stability_respond) with a catalogue of invalid requests.
 *
 * Every check prints what it was about when it fails (CHECK). Tolerances are stated where they are used.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <cjson/cJSON.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_rng.h>

#include "dashpot/stability.h"
#include "dashpot/stability_json.h"

#include "check.h"

static dp_law law_of(double m, int nl, const double *l, int nm, const double *u)
{
    dp_law law = { .mass = m, .nlambda = nl, .nmu = nm };
    memcpy(law.lambda, l, (size_t)nl * sizeof *l);
    memcpy(law.mu, u, (size_t)nm * sizeof *u);
    return law;
}

static dp_stability analyse(dp_stability_ws *w, const dp_law *law)
{
    dp_stability st;
    int s = dp_stability_analyse(w, law, &st);
    CHECK(s == DP_OK, "dp_stability_analyse returned %d", s);
    return st;
}

static int setup(void **state)
{
    gsl_set_error_handler_off();
    *state = dp_stability_ws_alloc();
    return *state == NULL;
}

static int teardown(void **state)
{
    dp_stability_ws_free(*state);
    return 0;
}

/* ---- thesis corollaries 1.1 and 1.2: the minors in closed form ---- */

static void test_minors_closed_form(void **state)
{
    (void)state;
    /* (1.4): a1, a1 a2 - a0 a3, a3 (a1 a2 - a0 a3);  (1.7): a1, a1a2 - a0a3, a1(a2a3 - a1a4) - a0a3^2, a4 D3 */
    const double a3[] = { 0.7, 1.3, 2.9, 0.4 }, a4[] = { 0.3, 1.1, 2.3, 1.7, 0.6 };
    double m[4], t[4];
    assert_int_equal(dp_poly_hurwitz_minors(a3, 3, m, t), DP_OK);
    double d2 = a3[1] * a3[2] - a3[0] * a3[3];
    NEAR(m[0], a3[1], 1e-15);
    NEAR(m[1], d2, 1e-14);
    NEAR(m[2], a3[3] * d2, 1e-14);
    assert_int_equal(dp_poly_hurwitz_minors(a4, 4, m, t), DP_OK);
    double d3 = a4[1] * (a4[2] * a4[3] - a4[1] * a4[4]) - a4[0] * a4[3] * a4[3];
    NEAR(m[1], a4[1] * a4[2] - a4[0] * a4[3], 1e-14);
    NEAR(m[2], d3, 1e-14);
    NEAR(m[3], a4[4] * d3, 1e-14);
    for (int k = 0; k < 4; k++)
        CHECK(t[k] > 0 && t[k] < 1e-13, "tolerance of D_%d = %g should be a few eps", k + 1, t[k]);
}

/* ---- thesis models on both sides of their boundaries ---- */

/* The verdict at boundary*(1 + s*eps) for each relative offset: stable on the `stable_side` (+1/-1).
 * `param` points into *law. */
static void sides(dp_stability_ws *w, const char *what, dp_law *law, double *param, double boundary,
                  int stable_side, dp_thesis_model model)
{
    static const double offsets[] = { 1e-9, 3e-9, 1e-6, 1e-3, 0.1 };
    for (size_t i = 0; i < sizeof offsets / sizeof *offsets; i++)
        for (int sign = -1; sign <= 1; sign += 2) {
            *param = boundary * (1 + sign * offsets[i]);
            dp_stability st = analyse(w, law);
            dp_verdict want = sign == stable_side ? DP_VERDICT_STABLE : DP_VERDICT_UNSTABLE;
            CHECK(st.verdict == want, "%s at boundary*(1%+g): verdict %s, expected %s (abscissa %g +- %g)", what,
                  sign * offsets[i], dp_verdict_name(st.verdict), dp_verdict_name(want), st.poly.abscissa,
                  st.poly.abscissa_err);
            CHECK(!st.poly.near_boundary, "%s at boundary*(1%+g) should be decided by both tests", what,
                  sign * offsets[i]);
            CHECK(st.closed.model == model && st.closed.applies && st.closed.verdict == want,
                  "%s at boundary*(1%+g): closed form %s says %s", what, sign * offsets[i],
                  st.closed.condition ? st.closed.condition : "none", dp_verdict_name(st.closed.verdict));
            CHECK((st.poly.abscissa < 0) == (want == DP_VERDICT_STABLE), "%s: abscissa sign", what);
        }
}

/* At the boundary itself p has a pair +-i omega: marginal (or "near boundary"), never a firm verdict. */
static void on_boundary(dp_stability_ws *w, const char *what, const dp_law *law, double omega2)
{
    dp_stability st = analyse(w, law);
    CHECK(st.verdict == DP_VERDICT_MARGINAL || st.verdict == DP_VERDICT_BOUNDARY,
          "%s on the boundary: verdict %s", what, dp_verdict_name(st.verdict));
    CHECK(fabs(st.poly.abscissa) < 1e-12, "%s on the boundary: abscissa %g", what, st.poly.abscissa);
    int found = 0;
    for (int i = 0; i < st.poly.degree; i++)
        found |= fabs(st.poly.root_im[i] * st.poly.root_im[i] - omega2) < 1e-10 * omega2;
    CHECK(found, "%s on the boundary: no root at +-i sqrt(%g)", what, omega2);
}

static void test_model_1_2(void **state)
{
    /* F_V + lambda F_V' = mu1 x + mu2 x'; p = lambda m z^3 + m z^2 + mu2 z + mu1; stable iff mu2 > lambda mu1
     * (1.10). On the boundary p = (lambda z + 1)(m z^2 + mu1): omega^2 = mu1/m. */
    double m = 1.7, lam = 0.8, mu1 = 1.3;
    dp_law law = law_of(m, 2, (double[]){ 1, lam }, 2, (double[]){ mu1, 0 });
    sides(*state, "model 1.2 in mu2", &law, &law.mu[1], lam * mu1, +1, DP_MODEL_1_2);
    law.mu[1] = 2.0;    /* boundary in lambda: lambda* = mu2/mu1, stable below */
    sides(*state, "model 1.2 in lambda", &law, &law.lambda[1], 2.0 / mu1, -1, DP_MODEL_1_2);
    dp_law exact = law_of(1, 2, (double[]){ 1, 0.5 }, 2, (double[]){ 2, 1 });   /* mu2 = lambda mu1 exactly */
    on_boundary(*state, "model 1.2", &exact, 2.0);
    dp_stability st = analyse(*state, &exact);
    CHECK(st.verdict == DP_VERDICT_MARGINAL, "exact model 1.2 boundary is marginal, got %s",
          dp_verdict_name(st.verdict));
}

static void test_model_1_3(void **state)
{
    /* F_V + l1 F_V' + l2 F_V'' = mu1 x + mu2 x'; (1.12) l1 m (mu2 - l1 mu1) > l2 mu2^2: a quadratic in mu2,
     * l2 mu2^2 - l1 m mu2 + l1^2 m mu1 < 0, stable strictly between its roots. */
    double m = 2.0, l1 = 1.5, l2 = 0.4, mu1 = 0.3;
    double b = l1 * m, disc = b * b - 4 * l2 * l1 * l1 * m * mu1;
    double lo = (b - sqrt(disc)) / (2 * l2), hi = (b + sqrt(disc)) / (2 * l2);
    lo = l1 * l1 * m * mu1 / (l2 * hi);                       /* the small root without cancellation */
    dp_law law = law_of(m, 3, (double[]){ 1, l1, l2 }, 2, (double[]){ mu1, 0 });
    sides(*state, "model 1.3 lower mu2", &law, &law.mu[1], lo, +1, DP_MODEL_1_3);
    sides(*state, "model 1.3 upper mu2", &law, &law.mu[1], hi, -1, DP_MODEL_1_3);
    /* On the boundary the pair is +-i omega with omega^2 = mu2/(l1 m) (D_3 = 0 makes a1 w^2 = a3). */
    law.mu[1] = hi;
    on_boundary(*state, "model 1.3", &law, hi / (l1 * m));
}

static void test_model_1_4(void **state)
{
    /* ... + mu3 x''; (1.14) l1 (m + mu3) - l2 mu2 > l1^2 m mu1/mu2: stable iff mu1 < mu1*, linear in mu1. */
    double m = 1.0, l1 = 0.9, l2 = 0.25, mu2 = 1.2, mu3 = 0.6;
    double mu1 = (l1 * (m + mu3) - l2 * mu2) * mu2 / (l1 * l1 * m);
    dp_law law = law_of(m, 3, (double[]){ 1, l1, l2 }, 3, (double[]){ 0, mu2, mu3 });
    sides(*state, "model 1.4 in mu1", &law, &law.mu[0], mu1, -1, DP_MODEL_1_4);
    law.mu[0] = mu1;
    on_boundary(*state, "model 1.4", &law, mu2 / (l1 * m));
    /* With mu3 = 0 model 1.4 is model 1.3 (the thesis' remark after (1.14)). */
    dp_law m13 = law_of(m, 3, (double[]){ 1, l1, l2 }, 2, (double[]){ 0.5, mu2 });
    dp_law m14 = law_of(m, 3, (double[]){ 1, l1, l2 }, 3, (double[]){ 0.5, mu2, 1e-12 });
    dp_stability a = analyse(*state, &m13), c = analyse(*state, &m14);
    assert_int_equal(a.closed.model, DP_MODEL_1_3);
    assert_int_equal(c.closed.model, DP_MODEL_1_4);
    /* mu2 * (1.14) = (1.12) + l1 mu2 mu3 (the thesis' rearrangement) */
    NEAR(c.closed.value * mu2, a.closed.value + l1 * mu2 * 1e-12, 1e-12);
}

/* ---- normalisation, zero roots, the undamped oscillator ---- */

static void test_special_polynomials(void **state)
{
    dp_law undamped = law_of(2, 1, (double[]){ 1 }, 1, (double[]){ 8 });      /* 2 x'' + 8 x = 0: +-2i */
    dp_stability st = analyse(*state, &undamped);
    CHECK(st.verdict == DP_VERDICT_MARGINAL, "undamped oscillator: %s", dp_verdict_name(st.verdict));
    dp_law zero = law_of(1, 1, (double[]){ 1 }, 2, (double[]){ 0, 3 });       /* x'' + 3 x' = 0: 0, -3 */
    st = analyse(*state, &zero);
    CHECK(st.verdict == DP_VERDICT_MARGINAL, "simple zero root: %s", dp_verdict_name(st.verdict));
    dp_law free_mass = law_of(1, 2, (double[]){ 1, 1 }, 1, (double[]){ 0 });  /* z^3 + z^2: double zero */
    st = analyse(*state, &free_mass);
    CHECK(st.verdict == DP_VERDICT_UNSTABLE, "double zero root: %s", dp_verdict_name(st.verdict));
    dp_law neg = law_of(1, 1, (double[]){ -1 }, 2, (double[]){ -1, -1 });     /* -(z^2 + z + 1) */
    st = analyse(*state, &neg);
    CHECK(st.verdict == DP_VERDICT_STABLE, "sign of p is irrelevant: %s", dp_verdict_name(st.verdict));
    assert_true(st.poly.a[0] > 0);
    dp_law scaled = law_of(1, 2, (double[]){ 2, 1 }, 2, (double[]){ 2, 2 });  /* model 1.2 times 2 */
    st = analyse(*state, &scaled);
    assert_int_equal(st.closed.model, DP_MODEL_1_2);
    NEAR(st.closed.lambda1, 0.5, 1e-15);
    NEAR(st.closed.value, 1 - 0.5, 1e-15);
}

/* ---- 10^4 random polynomials: Hurwitz minors against roots ---- */

/* A polynomial of degree n from random roots (real, or conjugate pairs) with real parts in [-1, 0.3], some
 * of them pushed to within 1e-12 .. 1e-5 of the axis; or with random positive coefficients. */
static int random_poly(gsl_rng *r, double *a, double *truth)
{
    int n = 1 + (int)gsl_rng_uniform_int(r, 8);
    *truth = NAN;                 /* the largest real part of the roots, when known */
    if (gsl_rng_uniform(r) < 0.3) {
        for (int i = 0; i <= n; i++)
            a[i] = 0.1 + 2 * gsl_rng_uniform(r);
        return n;
    }
    double c[11] = { 1 };   /* ascending product of factors */
    int d = 0;
    while (d < n) {
        double re = -1 + 1.3 * gsl_rng_uniform(r), u = gsl_rng_uniform(r);
        if (u < 0.2)
            re = (gsl_rng_uniform(r) < 0.5 ? -1 : 1) * pow(10, -12 + 7 * gsl_rng_uniform(r));
        double f[3];
        int k;
        *truth = d == 0 ? re : fmax(*truth, re);
        if (d + 2 <= n && gsl_rng_uniform(r) < 0.6) {
            double im = 0.1 + 2 * gsl_rng_uniform(r);
            f[0] = re * re + im * im, f[1] = -2 * re, f[2] = 1, k = 2;
        } else {
            f[0] = -re, f[1] = 1, k = 1;
        }
        double nc[11] = { 0 };
        for (int i = 0; i <= d; i++)
            for (int j = 0; j <= k; j++)
                nc[i + j] += c[i] * f[j];
        d += k;
        memcpy(c, nc, sizeof c);
    }
    for (int i = 0; i <= n; i++)
        a[i] = c[n - i];
    return n;
}

static void test_random_cross_check(void **state)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 20261121);
    dp_poly_ws *w = dp_stability_ws_poly(*state);
    int counts[6] = { 0 }, both_certain = 0, undecided = 0, contradictions = 0;
    const int N = 20000;
    for (int t = 0; t < N; t++) {
        double a[11], truth;
        int n = random_poly(r, a, &truth);
        dp_poly_report rep;
        assert_int_equal(dp_poly_analyse(w, a, n, &rep), DP_OK);
        counts[rep.verdict]++;
        int hc = rep.by_hurwitz != DP_VERDICT_UNDECIDED, rc = rep.by_roots != DP_VERDICT_UNDECIDED;
        undecided += !hc || !rc;
        if (hc && rc) {
            both_certain++;
            contradictions += rep.by_hurwitz != rep.by_roots;
            CHECK(rep.by_hurwitz == rep.by_roots || rep.verdict == DP_VERDICT_BOUNDARY,
                  "poly %d degree %d: Hurwitz %s, roots %s, verdict %s", t, n, dp_verdict_name(rep.by_hurwitz),
                  dp_verdict_name(rep.by_roots), dp_verdict_name(rep.verdict));
        }
        /* The roots were chosen: a real part beyond 1e-9 of the axis must be seen on its side. */
        if (fabs(truth) > 1e-9)
            CHECK(rep.verdict == (truth < 0 ? DP_VERDICT_STABLE : DP_VERDICT_UNSTABLE),
                  "poly %d degree %d with max Re = %g: verdict %s", t, n, truth, dp_verdict_name(rep.verdict));
        dp_verdict fast;
        assert_int_equal(dp_poly_verdict(w, a, n, &fast, NULL, NULL), DP_OK);
        CHECK(fast == rep.verdict || contradictions > 0, "poly %d: fast verdict %s, full %s", t,
              dp_verdict_name(fast), dp_verdict_name(rep.verdict));
    }
    print_message("random: %d polynomials, %d with both tests certain, %d with one undecided, %d contradictions;"
                  " stable %d marginal %d unstable %d near-boundary %d\n", N, both_certain, undecided,
                  contradictions, counts[0], counts[1], counts[2], counts[3]);
    CHECK(contradictions == 0, "the two tests contradicted each other %d times", contradictions);
    CHECK(both_certain > N * 8 / 10, "only %d of %d decided by both tests", both_certain, N);
    CHECK(counts[0] > N / 5 && counts[2] > N / 5, "both stable and unstable cases are exercised");
    gsl_rng_free(r);
}

/* ---- state matrices and pencils ---- */

static void test_thesis_state_matrices(void **state)
{
    /* (1.9): [[0,1,0],[0,0,-1/m],[mu1/l, mu2/l, -1/l]] */
    double m = 2, l = 0.5, u1 = 3, u2 = 4;
    dp_law law = law_of(m, 2, (double[]){ 1, l }, 2, (double[]){ u1, u2 });
    dp_stability st = analyse(*state, &law);
    const double s9[] = { 0, 1, 0, 0, 0, -1 / m, u1 / l, u2 / l, -1 / l };
    assert_int_equal(st.state.dim, 3);
    for (int i = 0; i < 9; i++)
        NEAR(st.state.s[i], s9[i], 1e-15);
    /* (1.13): last row [mu1/l2, mu2/l2, -mu3/(l2 m) - 1/l2, -l1/l2] */
    double l1 = 0.7, l2 = 0.2, u3 = 0.9;
    law = law_of(m, 3, (double[]){ 1, l1, l2 }, 3, (double[]){ u1, u2, u3 });
    st = analyse(*state, &law);
    const double last[] = { u1 / l2, u2 / l2, -u3 / (l2 * m) - 1 / l2, -l1 / l2 };
    assert_int_equal(st.state.dim, 4);
    for (int j = 0; j < 4; j++)
        NEAR(st.state.s[12 + j], last[j], 1e-13);
    NEAR(st.state.s[1 * 4 + 2], -1 / m, 1e-15);
    NEAR(st.state.s[2 * 4 + 3], 1, 0);
}

static void test_state_eigenvalues_equal_roots(void **state)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 7);
    double worst = 0;
    for (int t = 0; t < 2000; t++) {
        dp_law law = { .mass = 0.5 + gsl_rng_uniform(r), .nlambda = 1 + (int)gsl_rng_uniform_int(r, 9),
                       .nmu = 1 + (int)gsl_rng_uniform_int(r, 9) };
        for (int i = 0; i < law.nlambda; i++)
            law.lambda[i] = 0.2 + gsl_rng_uniform(r);
        for (int j = 0; j < law.nmu; j++)
            law.mu[j] = gsl_rng_uniform(r) - 0.3;
        dp_stability st = analyse(*state, &law);
        if (st.dae)
            continue;
        /* Both are backward-stable eigen solvers of different matrices: they agree to the roots' own
         * error radius (condition x eps), bounded here by 1e-6 relative. */
        for (int i = 0; i < st.poly.degree; i++) {
            double mag = fmax(1, hypot(st.poly.root_re[i], st.poly.root_im[i]));
            double d = hypot(st.state.eig_re[i] - st.poly.root_re[i], st.state.eig_im[i] - st.poly.root_im[i]);
            double tol = fmax(1e-10 * mag, 100 * st.poly.root_err[i]);
            CHECK(d <= tol && tol < 1e-6 * mag, "law %d root %d: eigenvalue off by %g (tolerance %g)", t, i, d, tol);
            worst = fmax(worst, d / mag);
        }
    }
    print_message("state matrices: worst relative eigenvalue-root distance %g\n", worst);
    gsl_rng_free(r);
}

static void test_dae_pencils(void **state)
{
    /* model 1.2 written with lambda_2 = 0: same finite spectrum, one infinite eigenvalue */
    dp_law law = law_of(1, 3, (double[]){ 1, 0.5, 0 }, 2, (double[]){ 1, 1 });
    dp_stability st = analyse(*state, &law), ref;
    dp_law m12 = law_of(1, 2, (double[]){ 1, 0.5 }, 2, (double[]){ 1, 1 });
    ref = analyse(*state, &m12);
    assert_true(st.dae);
    assert_int_equal(st.pencil.dim, 4);
    assert_int_equal(st.pencil.ninfinite, 1);
    assert_int_equal(st.pencil.nfinite, 3);
    assert_false(st.pencil.singular);
    CHECK(st.pencil.deviation >= 0 && st.pencil.deviation < 1e-12, "pencil vs roots %g", st.pencil.deviation);
    for (int i = 0; i < 3; i++)
        NEAR(st.pencil.fin_re[i], ref.poly.root_re[i], 1e-12);
    assert_int_equal(st.verdict, ref.verdict);
    /* two trailing zeros: two infinite eigenvalues */
    law = law_of(1, 4, (double[]){ 1, 0.5, 0, 0 }, 2, (double[]){ 1, 1 });
    st = analyse(*state, &law);
    assert_int_equal(st.pencil.ninfinite, 2);
    /* m x'' + F = 0 with F = x + x' - x'' (m = 1): x' + x = 0, index-2 style: p = z + 1 */
    law = law_of(1, 1, (double[]){ 1 }, 3, (double[]){ 1, 1, -1 });
    st = analyse(*state, &law);
    assert_true(st.dae);
    assert_int_equal(st.poly.degree, 1);
    assert_int_equal(st.pencil.nfinite, 1);
    assert_int_equal(st.pencil.ninfinite, 2);
    NEAR(st.pencil.fin_re[0], -1, 1e-12);
    assert_int_equal(st.verdict, DP_VERDICT_STABLE);
    /* lambda = [0], mu = [1]: the law says x = 0; no finite mode at all */
    law = law_of(1, 1, (double[]){ 0 }, 1, (double[]){ 1 });
    st = analyse(*state, &law);
    assert_int_equal(st.pencil.nfinite, 0);
    assert_int_equal(st.pencil.ninfinite, 3);
    assert_int_equal(st.verdict, DP_VERDICT_STABLE);
    assert_false(st.poly.has_abscissa);
    /* singular: m = 2, F = -2 x'' - ... the law repeats Newton's: p = 2 z^2 (1 + z/2) - 2 z^2 - z^3 = 0 */
    law = law_of(2, 2, (double[]){ 1, 0.5 }, 4, (double[]){ 0, 0, -2, -1 });
    st = analyse(*state, &law);
    assert_true(st.pencil.singular);
    assert_int_equal(st.verdict, DP_VERDICT_ILL_POSED);
    assert_int_equal(st.poly.degree, -1);
}

/* The simplest singular pencil: F_V = -m x'' restates Newton's law, p = z^2 - z^2 = 0, x is undetermined. */
static void test_singular_pencil_qz(void **state)
{
    dp_law law = law_of(1, 1, (double[]){ 1 }, 3, (double[]){ 0, 0, -1 });   /* F = -x'': p = z^2 - z^2 */
    dp_stability st = analyse(*state, &law);
    assert_true(st.dae);
    assert_true(st.pencil.singular);
    assert_int_equal(st.verdict, DP_VERDICT_ILL_POSED);
}

/* ---- maps against the closed forms ---- */

/* Every grid point whose verdict differs from the closed form's sign must have a neighbour (within one
 * step) on the other side of the closed-form boundary: agreement to the grid resolution. */
static void map_agrees(dp_stability_ws *w, const char *what, const dp_law *law, dp_map_axis x, dp_map_axis y)
{
    dp_map map;
    assert_int_equal(dp_stability_map(w, law, &x, &y, &map), DP_OK);
    assert_non_null(map.closed_value);
    int changes = 0, far_mismatch = 0, nx = (int)map.nx, ny = (int)map.ny;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            size_t k = (size_t)j * map.nx + (size_t)i;
            if (!map.closed_applies[k])
                continue;
            int cs = map.closed_value[k] > 0, vs = map.verdict[k] == DP_VERDICT_STABLE;
            if (cs == vs)
                continue;
            changes++;
            int near = 0;
            for (int dj = -1; dj <= 1; dj++)
                for (int di = -1; di <= 1; di++) {
                    int ii = i + di, jj = j + dj;
                    if (ii >= 0 && jj >= 0 && ii < nx && jj < ny)
                        near |= (map.closed_value[(size_t)jj * map.nx + (size_t)ii] > 0) != cs;
                }
            far_mismatch += !near;
        }
    print_message("%s: %zux%zu map, %d points off the closed form, all within a grid step: %s\n", what, map.nx,
                  map.ny, changes, far_mismatch ? "no" : "yes");
    CHECK(far_mismatch == 0, "%s: %d points disagree with %s farther than one grid step", what, far_mismatch,
          map.closed.condition);
    dp_map_clear(&map);
}

static void test_maps_match_closed_forms(void **state)
{
    dp_law m12 = law_of(1, 2, (double[]){ 1, 0.5 }, 2, (double[]){ 1, 1 });
    map_agrees(*state, "1.2 (mu2, lambda)", &m12, (dp_map_axis){ DP_PARAM_MU, 1, 0.05, 3, 181 },
               (dp_map_axis){ DP_PARAM_LAMBDA, 1, 0.05, 3, 173 });
    dp_law m13 = law_of(2, 3, (double[]){ 1, 1.5, 0.4 }, 2, (double[]){ 0.3, 1 });
    map_agrees(*state, "1.3 (mu2, lambda2)", &m13, (dp_map_axis){ DP_PARAM_MU, 1, 0.01, 8, 200 },
               (dp_map_axis){ DP_PARAM_LAMBDA, 2, 0.01, 2, 150 });
    dp_law m14 = law_of(1, 3, (double[]){ 1, 0.9, 0.25 }, 3, (double[]){ 1, 1.2, 0.6 });
    map_agrees(*state, "1.4 (mu1, mu3)", &m14, (dp_map_axis){ DP_PARAM_MU, 0, 0.01, 3, 160 },
               (dp_map_axis){ DP_PARAM_MU, 2, -0.5, 2, 140 });
}

typedef struct seg_ctx { const dp_map *map; int n; double worst; } seg_ctx;

/* The closed-form value interpolated bilinearly at a point in grid coordinates. */
static double closed_at(const dp_map *m, double x, double y)
{
    size_t i = (size_t)fmin(floor(x), (double)m->nx - 2), j = (size_t)fmin(floor(y), (double)m->ny - 2);
    double fx = x - (double)i, fy = y - (double)j, *v = m->closed_value;
    size_t k = j * m->nx + i;
    return (1 - fy) * ((1 - fx) * v[k] + fx * v[k + 1]) + fy * ((1 - fx) * v[k + m->nx] + fx * v[k + m->nx + 1]);
}

static int on_segment(void *ctx, double x0, double y0, double x1, double y1)
{
    seg_ctx *c = ctx;
    c->n++;
    c->worst = fmax(c->worst, fmax(fabs(closed_at(c->map, x0, y0)), fabs(closed_at(c->map, x1, y1))));
    return 0;
}

static void test_boundary_segments(void **state)
{
    /* model 1.2 over (mu2, lambda) with mu1 = 1: the boundary is the diagonal mu2 = lambda. */
    dp_law m12 = law_of(1, 2, (double[]){ 1, 0.5 }, 2, (double[]){ 1, 1 });
    dp_map map;
    assert_int_equal(dp_stability_map(*state, &m12, &(dp_map_axis){ DP_PARAM_MU, 1, 0, 2, 41 },
                                      &(dp_map_axis){ DP_PARAM_LAMBDA, 1, 0.1, 2.1, 41 }, &map), DP_OK);
    seg_ctx c = { &map, 0, 0 };
    dp_map_boundary(&map, on_segment, &c);
    CHECK(c.n >= 39, "the diagonal crosses ~40 cells, got %d segments", c.n);
    CHECK(c.worst < 1e-12, "segment ends lie on the zero set (|value| %g)", c.worst);
    dp_map_clear(&map);
}

/* ---- the wire ---- */

static int respond(const char *doc, int want, dp_buf *out, dp_errors *e)
{
    char *text = strdup(doc);
    for (char *p = text; *p; p++)
        if (*p == '\'')
            *p = '"';
    dp_errors_init(e);
    int s = dp_stability_respond(text, strlen(text), want, out, e);
    free(text);
    return s;
}

static void test_respond_analysis(void **state)
{
    (void)state;
    dp_buf out = { 0 };
    dp_errors e;
    assert_int_equal(respond("{'mass': 1, 'law': {'lambda': [1, 0.5], 'mu': [1, 1]}}", 0, &out, &e), DP_OK);
    cJSON *d = cJSON_ParseWithLength(out.data, out.len);
    CHECK(d != NULL, "the response is JSON (no NaN/Inf): %s", out.data);
    assert_string_equal(cJSON_GetObjectItem(d, "verdict")->valuestring, "asymptotically stable");
    assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(d, "roots")), 3);
    assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(d, "hurwitz_minors")), 3);
    cJSON *model = cJSON_GetObjectItem(d, "model");
    assert_string_equal(cJSON_GetObjectItem(model, "condition")->valuestring, "(1.10)");
    NEAR(cJSON_GetObjectItem(model, "value")->valuedouble, 0.5, 1e-15);
    cJSON *sm = cJSON_GetObjectItem(d, "state_matrix");
    assert_string_equal(cJSON_GetObjectItem(sm, "equation")->valuestring, "(1.9)");
    assert_true(cJSON_IsNull(cJSON_GetObjectItem(d, "pencil")));
    cJSON_Delete(d);
    out.len = 0;
    assert_int_equal(respond("{'mass': 1, 'law': {'lambda': [0], 'mu': [1]}}", 0, &out, &e), DP_OK);
    d = cJSON_ParseWithLength(out.data, out.len);
    assert_non_null(d);
    assert_true(cJSON_IsNull(cJSON_GetObjectItem(d, "spectral_abscissa")));
    assert_int_equal(cJSON_GetObjectItem(cJSON_GetObjectItem(d, "pencil"), "infinite_eigenvalues")->valueint, 3);
    cJSON_Delete(d);
    free(out.data);
}

static void test_respond_map(void **state)
{
    (void)state;
    const char *doc = "{'mass': 1, 'law': {'lambda': [1, 0.5], 'mu': [1, 1]}, 'map': {"
                      "'x': {'param': 'mu[1]', 'from': 0.1, 'to': 2, 'steps': 30},"
                      "'y': {'param': 'lambda[1]', 'from': 0.1, 'to': 2, 'steps': 20}}}";
    dp_buf out = { 0 };
    dp_errors e;
    assert_int_equal(respond(doc, 0, &out, &e), DP_OK);
    cJSON *d = cJSON_ParseWithLength(out.data, out.len), *map = cJSON_GetObjectItem(d, "map");
    assert_non_null(map);
    assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(map, "verdict")), 20);
    assert_int_equal(strlen(cJSON_GetArrayItem(cJSON_GetObjectItem(map, "verdict"), 0)->valuestring), 30);
    assert_int_equal(cJSON_GetArraySize(cJSON_GetArrayItem(cJSON_GetObjectItem(map, "spectral_abscissa"), 3)), 30);
    cJSON_Delete(d);
    out.len = 0;
    assert_int_equal(respond(doc, 1, &out, &e), DP_OK);
    int lines = 0;
    for (size_t i = 0; i < out.len; i++)
        lines += out.data[i] == '\n';
    assert_int_equal(lines, 1 + 30 * 20);
    assert_memory_equal(out.data, "mu[1],lambda[1],spectral_abscissa,verdict\n", 42);
    out.len = 0;
    assert_int_equal(respond(doc, 2, &out, &e), DP_OK);
    assert_memory_equal(out.data, "<svg", 4);
    assert_non_null(strstr(out.data, "<path d=\"M"));     /* the (1.10) boundary is drawn */
    assert_non_null(strstr(out.data, "</svg>"));
    free(out.data);
}

typedef struct bad_row {
    const char *doc;
    int want, status;
    const char *pointer, *fragment;
} bad_row;

static const bad_row BAD[] = {
    { "{'mass': 1, 'law': ", 0, DP_ESYNTAX, "", "malformed" },
    { "", 0, DP_ESYNTAX, "", "empty" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1]}} x", 0, DP_ESYNTAX, "", "malformed" },
    { "[1]", 0, DP_EINVAL, "", "object" },
    { "{'law': {'lambda': [1], 'mu': [1]}}", 0, DP_EINVAL, "/mass", "missing required key \"mass\" (a finite number)" },
    { "{'mass': 0, 'law': {'lambda': [1], 'mu': [1]}}", 0, DP_EINVAL, "/mass", "> 0" },
    { "{'mass': -2, 'law': {'lambda': [1], 'mu': [1]}}", 0, DP_EINVAL, "/mass", "> 0" },
    { "{'mass': '1', 'law': {'lambda': [1], 'mu': [1]}}", 0, DP_EINVAL, "/mass", "must be a finite number, got a string" },
    { "{'mass': 1e999, 'law': {'lambda': [1], 'mu': [1]}}", 0, DP_EINVAL, "/mass", "got a literal too large for a double" },
    { "{'mass': 1e13, 'law': {'lambda': [1], 'mu': [1]}}", 0, DP_ELIMIT, "/mass", "mass in" },
    { "{'mass': 1}", 0, DP_EINVAL, "/law", "required" },
    { "{'mass': 1, 'law': [1]}", 0, DP_EINVAL, "/law", "must be an object, got an array" },
    { "{'mass': 1, 'law': {'mu': [1]}}", 0, DP_EINVAL, "/law/lambda", "required" },
    { "{'mass': 1, 'law': {'lambda': [], 'mu': [1]}}", 0, DP_EINVAL, "/law/lambda", "at least one" },
    { "{'mass': 1, 'law': {'lambda': 1, 'mu': [1]}}", 0, DP_EINVAL, "/law/lambda", "array" },
    { "{'mass': 1, 'law': {'lambda': [1,2,3,4,5,6,7,8,9,10], 'mu': [1]}}", 0, DP_ELIMIT, "/law/lambda",
      "at most 9" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1, null]}}", 0, DP_EINVAL, "/law/mu/1", "finite number" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1, -1e999]}}", 0, DP_EINVAL, "/law/mu/1", "finite" },
    { "{'mass': 1, 'law': {'lambda': [1, 2e12], 'mu': [1]}}", 0, DP_ELIMIT, "/law/lambda/1", "magnitude" },
    { "{'mass': 1, 'law': {'lambda': [1, 1e-300], 'mu': [1]}}", 0, DP_ELIMIT, "/law/lambda/1", "magnitude" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1], 'nu': [1]}}", 0, DP_EINVAL, "/law/nu",
      "unknown key \"nu\"; expected one of: lambda, mu" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1]}, 'a/b~c': 1}", 0, DP_EINVAL, "/a~1b~0c", "unknown key \"a/b~c\"" },
    { "{'mass': 1, 'mass': 1, 'law': {'lambda': [1], 'mu': [1]}}", 0, DP_EINVAL, "/mass", "duplicate key \"mass\"" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1]}, 'map': {'x': {'param': 'mu[0]', 'from': 0, 'to': 1, 'steps': 5, "
      "'steps': 6}, 'y': {'param': 'mu[1]', 'from': 0, 'to': 1, 'steps': 5}}}", 0, DP_EINVAL, "/map/x/steps",
      "duplicate key \"steps\"" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [NaN]}}", 0, DP_ESYNTAX, "",
      "malformed JSON near byte 42 (line 1, column 43): JSON has no NaN or Infinity; send a number or null" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1]}, 'spring': 1}", 0, DP_EINVAL, "/spring", "unknown" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1]}}", 1, DP_EINVAL, "/map", "CSV and SVG" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1]}}", 2, DP_EINVAL, "/map", "map" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1]}, 'map': 3}", 0, DP_EINVAL, "/map", "object" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1]}, 'map': {'x': {'param': 'mu[0]', 'from': 0, 'to': 1, "
      "'steps': 5}}}", 0, DP_EINVAL, "/map/y", "required" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1, 1]}, 'map': {'x': {'param': 'mu[3]', 'from': 0, 'to': 1, "
      "'steps': 5}, 'y': {'param': 'mu[0]', 'from': 0, 'to': 1, 'steps': 5}}}", 0, DP_EINVAL, "/map/x/param",
      "no coefficient" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1, 1]}, 'map': {'x': {'param': 'nu[0]', 'from': 0, 'to': 1, "
      "'steps': 5}, 'y': {'param': 'mu[0]', 'from': 0, 'to': 1, 'steps': 5}}}", 0, DP_EINVAL, "/map/x/param",
      "must be \"mass\", \"lambda[i]\" or \"mu[j]\" with i, j in 0..8, got \"nu[0]\"" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1, 1]}, 'map': {'x': {'param': 'mu[1]', 'from': 1, 'to': 1, "
      "'steps': 5}, 'y': {'param': 'mu[0]', 'from': 0, 'to': 1, 'steps': 5}}}", 0, DP_EINVAL, "/map/x/to",
      "to > from" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1, 1]}, 'map': {'x': {'param': 'mu[1]', 'from': 0, 'to': 1, "
      "'steps': 2001}, 'y': {'param': 'mu[0]', 'from': 0, 'to': 1, 'steps': 5}}}", 0, DP_ELIMIT,
      "/map/x/steps", "2 .. 2000" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1, 1]}, 'map': {'x': {'param': 'mu[1]', 'from': 0, 'to': 1, "
      "'steps': 2.5}, 'y': {'param': 'mu[0]', 'from': 0, 'to': 1, 'steps': 5}}}", 0, DP_EINVAL,
      "/map/x/steps", "integer" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1, 1]}, 'map': {'x': {'param': 'mass', 'from': -1, 'to': 1, "
      "'steps': 5}, 'y': {'param': 'mu[0]', 'from': 0, 'to': 1, 'steps': 5}}}", 0, DP_ELIMIT, "/map/x/to",
      "mass must stay" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1, 1]}, 'map': {'x': {'param': 'mu[0]', 'from': 0, 'to': 1, "
      "'steps': 5}, 'y': {'param': 'mu[0]', 'from': 0, 'to': 1, 'steps': 5}}}", 0, DP_EINVAL, "/map/y/param",
      "same coefficient" },
    { "{'mass': 1, 'law': {'lambda': [1], 'mu': [1, 1]}, 'map': {'x': {'param': 'mu[0]', 'from': 0, 'to': 1, "
      "'steps': 5, 'step': 1}, 'y': {'param': 'mu[1]', 'from': 0, 'to': 1, 'steps': 5}}}", 0, DP_EINVAL,
      "/map/x/step", "unknown" },
};

static void test_respond_invalid(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof BAD / sizeof *BAD; i++) {
        const bad_row *b = &BAD[i];
        dp_buf out = { 0 };
        dp_errors e;
        int s = respond(b->doc, b->want, &out, &e);
        int found = 0;
        for (size_t k = 0; k < e.n; k++)
            found |= strcmp(e.item[k].pointer, b->pointer) == 0 && strstr(e.item[k].message, b->fragment);
        if (s != b->status || !found) {
            for (size_t k = 0; k < e.n; k++)
                print_error("  error: \"%s\" %s\n", e.item[k].pointer, e.item[k].message);
        }
        CHECK(s == b->status, "row %zu %s: status %d, expected %d", i, b->doc, s, b->status);
        CHECK(found, "row %zu %s: no error at \"%s\" mentioning \"%s\"", i, b->doc, b->pointer, b->fragment);
        CHECK(out.len == 0, "row %zu: nothing written on failure", i);
        free(out.data);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_minors_closed_form),
        cmocka_unit_test(test_model_1_2),
        cmocka_unit_test(test_model_1_3),
        cmocka_unit_test(test_model_1_4),
        cmocka_unit_test(test_special_polynomials),
        cmocka_unit_test(test_random_cross_check),
        cmocka_unit_test(test_thesis_state_matrices),
        cmocka_unit_test(test_state_eigenvalues_equal_roots),
        cmocka_unit_test(test_dae_pencils),
        cmocka_unit_test(test_singular_pencil_qz),
        cmocka_unit_test(test_maps_match_closed_forms),
        cmocka_unit_test(test_boundary_segments),
        cmocka_unit_test(test_respond_analysis),
        cmocka_unit_test(test_respond_map),
        cmocka_unit_test(test_respond_invalid),
    };
    gsl_set_error_handler_off();
    return cmocka_run_group_tests(tests, setup, teardown);
}
