/* tests/test_newmark.c - the newmark solver (Höschl 003 §15, Ex. 40; docs/systems.md §3) against independent
 * references: the incremental form's coefficients against Höschl's linear-acceleration numbers, its steps
 * against the textbook (total) Newmark form on a damped, forced two-mass chain, second order for gamma = 1/2
 * (first for gamma > 1/2), the stability limit dt/T = sqrt(3)/pi of beta = 1/6 from both sides, exact
 * energy conservation of beta = 1/4 on a linear undamped system, bad input. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "dashpot/newmark.h"
#include "trajectory.h"

/* Höschl's (and every textbook's) linear-acceleration form, beta = 1/6, gamma = 1/2:
 * K^ = K + 3 C/h + 6 M/h^2, dP^ = dP + M (6 v/h + 3 a) + C (3 v + h a/2), dv = 3 dx/h - 3 v - h a/2. */
static void test_hoschl_coefficients(void **state)
{
    (void)state;
    double h = 0.37;
    dp_newmark_coef c;
    dp_newmark_coef_init(1.0 / 6, 0.5, h, &c);
    double want[9] = { 6 / (h * h), 3 / h, 6 / h, 3, 3, h / 2, 3 / h, -3, -h / 2 };
    double got[9] = { c.kM, c.kC, c.pMv, c.pMa, c.pCv, c.pCa, c.vx, c.vv, c.va };
    for (int i = 0; i < 9; i++)
        assert_true(fabs(got[i] - want[i]) <= 1e-14 * fabs(want[i]));
    /* average acceleration, beta = 1/4: K^ = K + 2 C/h + 4 M/h^2, dv = 2 dx/h - 2 v, no a term */
    dp_newmark_coef_init(0.25, 0.5, h, &c);
    assert_true(fabs(c.kM - 4 / (h * h)) <= 1e-14 * c.kM && fabs(c.kC - 2 / h) <= 1e-14 * c.kC);
    assert_true(fabs(c.vx - 2 / h) <= 1e-14 * c.vx && c.vv == -2 && fabs(c.va) <= 1e-15);
}

/* ---- a damped, forced two-mass chain --------------------------------------------------------------------- */

static const char *chain_doc = "{\"model\":{\"masses\":[1,2],\"elements\":[{\"between\":[\"ground\",0],\"spring\":"
    "{\"law\":\"linear\",\"k\":3},\"damper\":{\"law\":\"linear\",\"c\":%g}},{\"between\":[0,1],\"spring\":{\"law\":"
    "\"linear\",\"k\":2}}],\"forcing\":[{\"node\":1,\"kind\":\"harmonic\",\"amplitude\":%g,\"omega\":1.3,"
    "\"phase\":0}]},\"initial\":{\"x\":[0.5,-0.2],\"v\":[0,0.4]},\"solver\":{\"kind\":\"newmark\",\"dt\":%.17g,"
    "\"t_end\":%g,\"beta\":%.17g,\"gamma\":%.17g}}";

typedef struct rowset { double *d; size_t n, cap, width; } rowset;

static void run_rows(const char *doc, rowset *rs)
{
    memset(rs, 0, sizeof *rs);
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(doc, strlen(doc), 0, &spec, &errs);
    if (s != DP_OK && errs.n)
        fprintf(stderr, "%s: %s\n", errs.item[0].pointer, errs.item[0].message);
    assert_int_equal(s, DP_OK);
    dp_run *run = dp_run_alloc(&spec, 0, &errs, &s);
    dp_spec_clear(&spec);
    assert_non_null(run);
    rs->width = 1 + dp_run_columns(run)->width;
    dp_record buf[128];
    size_t n;
    do {
        s = dp_run_next(run, buf, 128, &n);
        for (size_t i = 0; i < n; i++) {
            if (buf[i].type != DP_RECORD_ROW)
                continue;
            if (rs->n == rs->cap)
                rs->d = realloc(rs->d, (rs->cap = rs->cap ? 2 * rs->cap : 256) * rs->width * sizeof *rs->d);
            double *o = rs->d + rs->n++ * rs->width;
            o[0] = buf[i].u.row.t;
            memcpy(o + 1, buf[i].u.row.val, (rs->width - 1) * sizeof *o);
        }
    } while (s == DP_MORE);
    assert_int_equal(s, DP_DONE);
    dp_run_free(run);
}

/* The textbook total form: (M + gamma h C + beta h^2 K) a+ = P+ - C (v + (1-gamma) h a)
 * - K (x + h v + (1/2 - beta) h^2 a), then x+, v+ (2 x 2, Cramer). */
static void textbook(double c1, double amp, double h, double beta, double gamma, size_t steps, double *xs, double *vs)
{
    double M[2] = { 1, 2 }, K[2][2] = { { 5, -2 }, { -2, 2 } }, C[2][2] = { { c1, 0 }, { 0, 0 } };
    double x[2] = { 0.5, -0.2 }, v[2] = { 0, 0.4 }, a[2];
    for (int i = 0; i < 2; i++)   /* M a = P(0) - C v - K x */
        a[i] = ((i == 1 ? amp : 0) - C[i][0] * v[0] - C[i][1] * v[1] - K[i][0] * x[0] - K[i][1] * x[1]) / M[i];
    for (size_t n = 1; n <= steps; n++) {
        double t = (double)n * h, A[2][2], b[2], xp[2], vp[2];
        for (int i = 0; i < 2; i++) {
            xp[i] = x[i] + h * v[i] + (0.5 - beta) * h * h * a[i];
            vp[i] = v[i] + (1 - gamma) * h * a[i];
        }
        for (int i = 0; i < 2; i++) {
            b[i] = (i == 1 ? amp * cos(1.3 * t) : 0);
            for (int j = 0; j < 2; j++) {
                A[i][j] = (i == j ? M[i] : 0) + gamma * h * C[i][j] + beta * h * h * K[i][j];
                b[i] -= C[i][j] * vp[j] + K[i][j] * xp[j];
            }
        }
        double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
        double a0 = (b[0] * A[1][1] - A[0][1] * b[1]) / det, a1 = (A[0][0] * b[1] - A[1][0] * b[0]) / det;
        a[0] = a0, a[1] = a1;
        for (int i = 0; i < 2; i++) {
            x[i] = xp[i] + beta * h * h * a[i];
            v[i] = vp[i] + gamma * h * a[i];
        }
        xs[2 * n] = x[0], xs[2 * n + 1] = x[1], vs[2 * n] = v[0], vs[2 * n + 1] = v[1];
    }
}

static void test_incremental_is_the_textbook_form(void **state)
{
    (void)state;
    const double betas[2] = { 1.0 / 6, 0.25 }, h = 0.05;
    for (int k = 0; k < 2; k++) {
        char doc[2048];
        snprintf(doc, sizeof doc, chain_doc, 0.3, 0.8, h, 10.0, betas[k], 0.5);
        rowset rs;
        run_rows(doc, &rs);
        assert_int_equal(rs.n, 201);
        double xs[2 * 202], vs[2 * 202];
        textbook(0.3, 0.8, h, betas[k], 0.5, 200, xs, vs);
        for (size_t n = 1; n < rs.n; n++) {
            const double *r = rs.d + n * rs.width;   /* t, x0, x1, v0, v1, ... */
            for (int i = 0; i < 2; i++) {
                assert_true(fabs(r[1 + i] - xs[2 * n + i]) <= 1e-11);
                assert_true(fabs(r[3 + i] - vs[2 * n + i]) <= 1e-11);
            }
        }
        free(rs.d);
    }
}

/* ---- one mass: order and stability ------------------------------------------------------------------------ */

static double oscillator_error(double dt, double beta, double gamma, double t_end)
{
    char doc[1024];
    snprintf(doc, sizeof doc, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":"
             "\"none\"}},\"initial\":{\"x\":1,\"v\":0},\"solver\":{\"kind\":\"newmark\",\"dt\":%.17g,\"t_end\":%.17g,"
             "\"beta\":%.17g,\"gamma\":%.17g},\"output\":{\"every\":100000000}}", dt, t_end, beta, gamma);
    traj t;
    assert_int_equal(traj_run(doc, &t), DP_OK);
    assert_int_equal(t.status, DP_DONE);
    double T = t.sum.final.t, e = fmax(fabs(t.sum.final.x - cos(T)), fabs(t.sum.final.v + sin(T)));
    traj_free(&t);
    return e;
}

static void test_second_order_for_gamma_half(void **state)
{
    (void)state;
    const double betas[2] = { 1.0 / 6, 0.25 };
    for (int k = 0; k < 2; k++) {
        double e1 = oscillator_error(0.02, betas[k], 0.5, 10), e2 = oscillator_error(0.01, betas[k], 0.5, 10);
        double e3 = oscillator_error(0.005, betas[k], 0.5, 10);
        double o1 = log2(e1 / e2), o2 = log2(e2 / e3);
        printf("beta %.4f gamma 0.5: orders %.3f %.3f\n", betas[k], o1, o2);
        assert_true(o1 > 1.9 && o1 < 2.1 && o2 > 1.9 && o2 < 2.1);
    }
    /* gamma > 1/2 damps numerically and is first order: the measurement tells the two apart */
    double e1 = oscillator_error(0.02, 0.3, 0.6, 10), e2 = oscillator_error(0.01, 0.3, 0.6, 10);
    assert_true(log2(e1 / e2) > 0.9 && log2(e1 / e2) < 1.1);
}

/* beta = 1/6, gamma = 1/2 on m = k = 1 (T = 2 pi): stable for dt/T <= sqrt(3)/pi = 0.5513, growing beyond;
 * the meta line says which side dt is on. */
static void stability_run(double ratio, double *amp, int *inside, double *limit)
{
    double dt = ratio * 2 * M_PI;
    char doc[1024];
    snprintf(doc, sizeof doc, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":"
             "\"none\"}},\"initial\":{\"x\":1,\"v\":0},\"solver\":{\"kind\":\"newmark\",\"dt\":%.17g,\"t_end\":%.17g,"
             "\"beta\":%.17g,\"gamma\":0.5}}", dt, 400 * dt, 1.0 / 6);
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    assert_int_equal(dp_spec_parse(doc, strlen(doc), 0, &spec, &errs), DP_OK);
    dp_newmark_limit L;
    assert_int_equal(dp_newmark_limit_of(&spec, &L), DP_OK);
    *inside = L.inside, *limit = L.ratio_limit;
    assert_true(fabs(L.T_min - 2 * M_PI) <= 1e-12 && fabs(L.ratio - ratio) <= 1e-12);
    dp_buf meta = { 0 };
    assert_int_equal(dp_spec_meta_json(&spec, &meta), DP_OK);
    assert_int_equal(dp_buf_append(&meta, "", 1), DP_OK);
    assert_non_null(strstr(meta.data, L.inside ? "\"inside\":true" : "\"inside\":false"));
    dp_buf_free(&meta);
    dp_spec_clear(&spec);
    traj t;
    assert_int_equal(traj_run(doc, &t), DP_OK);
    *amp = 0;
    for (size_t i = 0; i < t.n; i++)
        *amp = fmax(*amp, hypot(t.s[i].x, t.s[i].v));
    traj_free(&t);
}

static void test_stability_limit_both_sides(void **state)
{
    (void)state;
    double amp_in, amp_out, limit;
    int in, out;
    stability_run(0.54, &amp_in, &in, &limit);
    assert_true(fabs(limit - sqrt(3) / M_PI) <= 1e-12);
    stability_run(0.56, &amp_out, &out, &limit);
    printf("dt/T 0.54: max |(x, v)| %.3g; 0.56: %.3g\n", amp_in, amp_out);
    assert_true(in && !out);
    assert_true(amp_in < 2);
    assert_true(amp_out > 1e6);
}

/* The highest mode of the two-mass chain (M = diag(1, 2), K = [[5, -2], [-2, 2]]): omega^2 = 3 + sqrt(6) from
 * det(K - omega^2 M) = 0; an elastoplastic spring counts with its elastic k. */
static void test_limit_of_a_network(void **state)
{
    (void)state;
    const char *docs[2] = {
        "{\"model\":{\"masses\":[1,2],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":\"linear\","
        "\"k\":3}},{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":2}}]},\"initial\":{\"x\":[0,0],"
        "\"v\":[0,0]},\"solver\":{\"kind\":\"newmark\",\"dt\":0.1,\"t_end\":1,\"beta\":0.16666666666666666}}",
        "{\"model\":{\"masses\":[1,2],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":\"linear\","
        "\"k\":3}},{\"between\":[0,1],\"spring\":{\"law\":\"elastoplastic\",\"k\":2,\"yield\":0.1}}]},"
        "\"initial\":{\"x\":[0,0],\"v\":[0,0]},\"solver\":{\"kind\":\"newmark\",\"dt\":0.1,\"t_end\":1,"
        "\"beta\":0.16666666666666666}}" };
    for (int k = 0; k < 2; k++) {
        dp_spec spec;
        dp_errors errs;
        dp_spec_init(&spec);
        dp_errors_init(&errs);
        assert_int_equal(dp_spec_parse(docs[k], strlen(docs[k]), 0, &spec, &errs), DP_OK);
        dp_newmark_limit L;
        assert_int_equal(dp_newmark_limit_of(&spec, &L), DP_OK);
        double w = sqrt(3 + sqrt(6));
        assert_true(fabs(L.omega_max - w) <= 1e-12 * w);
        assert_true(fabs(L.ratio - 0.1 * w / (2 * M_PI)) <= 1e-12);
        assert_true(L.inside);
        dp_spec_clear(&spec);
    }
}

/* beta = 1/4, gamma = 1/2 on a linear undamped chain: 1/2 v^T M v + 1/2 x^T K x is the same at every step. */
static void test_average_acceleration_conserves_energy(void **state)
{
    (void)state;
    char doc[2048];
    snprintf(doc, sizeof doc, chain_doc, 0.0, 0.0, 0.3, 300.0, 0.25, 0.5);
    rowset rs;
    run_rows(doc, &rs);
    double E0 = 0;
    for (size_t n = 0; n < rs.n; n++) {
        const double *r = rs.d + n * rs.width, *x = r + 1, *v = r + 3;
        double E = 0.5 * (v[0] * v[0] + 2 * v[1] * v[1]) + 0.5 * (5 * x[0] * x[0] - 4 * x[0] * x[1] + 2 * x[1] * x[1]);
        if (n == 0)
            E0 = E;
        assert_true(fabs(E - E0) <= 1e-12 * E0);
    }
    /* beta = 1/6 does not conserve it exactly: the check above would see that */
    free(rs.d);
    snprintf(doc, sizeof doc, chain_doc, 0.0, 0.0, 0.3, 300.0, 1.0 / 6, 0.5);
    run_rows(doc, &rs);
    double worst = 0;
    for (size_t n = 0; n < rs.n; n++) {
        const double *r = rs.d + n * rs.width, *x = r + 1, *v = r + 3;
        double E = 0.5 * (v[0] * v[0] + 2 * v[1] * v[1]) + 0.5 * (5 * x[0] * x[0] - 4 * x[0] * x[1] + 2 * x[1] * x[1]);
        worst = fmax(worst, fabs(E - E0) / E0);
    }
    assert_true(worst > 1e-6);
    free(rs.d);
}

/* ---- bad input ---------------------------------------------------------------------------------------------- */

static void expect_error(const char *json, const char *pointer, const char *needle)
{
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(json, strlen(json), 0, &spec, &errs);
    if (s == DP_OK)
        assert_null(dp_run_alloc(&spec, 0, &errs, &s));
    int found = 0;
    for (size_t i = 0; i < errs.n; i++)
        found |= strcmp(errs.item[i].pointer, pointer) == 0 && strstr(errs.item[i].message, needle) != NULL;
    for (size_t i = 0; !found && i < errs.n; i++)
        fprintf(stderr, "error %s: %s\n", errs.item[i].pointer, errs.item[i].message);
    assert_true(found);
    dp_spec_clear(&spec);
}

static void test_bad_input(void **state)
{
    (void)state;
    const char *one = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":%s},"
                      "\"solver\":{\"kind\":\"newmark\",\"dt\":0.01,\"t_end\":1%s}}";
    char doc[1024];
    snprintf(doc, sizeof doc, one, "{\"law\":\"coulomb\",\"phi0\":0.2}", "");
    expect_error(doc, "/model/damper/law", "\"kind\": \"stick-slip\"");
    snprintf(doc, sizeof doc, one, "{\"law\":\"bingham\",\"tau\":0.2,\"c\":1}", "");
    expect_error(doc, "/model/damper/law", "set-valued");
    snprintf(doc, sizeof doc, one, "{\"law\":\"none\"}", ",\"beta\":0");
    expect_error(doc, "/solver/beta", "(0, 0.5]");
    snprintf(doc, sizeof doc, one, "{\"law\":\"none\"}", ",\"beta\":0.6");
    expect_error(doc, "/solver/beta", "(0, 0.5]");
    snprintf(doc, sizeof doc, one, "{\"law\":\"none\"}", ",\"gamma\":0.4");
    expect_error(doc, "/solver/gamma", "[0.5, 1]");
    snprintf(doc, sizeof doc, one, "{\"law\":\"none\"}", ",\"gamma\":1.5");
    expect_error(doc, "/solver/gamma", "[0.5, 1]");
    expect_error("{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":\"linear\","
                 "\"k\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":0.1}}]},\"initial\":{\"x\":[0],\"v\":[0]},"
                 "\"solver\":{\"kind\":\"newmark\",\"dt\":0.01,\"t_end\":1}}", "/model/elements/0/damper/law",
                 "stick-slip");
    expect_error("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"rope\",\"k\":1,\"length\":2},\"damper\":{\"law\":"
                 "\"none\"}},\"solver\":{\"kind\":\"newmark\",\"dt\":0.01,\"t_end\":1}}", "/model/spring/law",
                 "linear and elastoplastic");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hoschl_coefficients),
        cmocka_unit_test(test_incremental_is_the_textbook_form),
        cmocka_unit_test(test_second_order_for_gamma_half),
        cmocka_unit_test(test_stability_limit_both_sides),
        cmocka_unit_test(test_limit_of_a_network),
        cmocka_unit_test(test_average_acceleration_conserves_energy),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
