/* tests/test_sweep.c - sweeps (sweep.h, sweep_json.h) against closed forms and against lone runs.
 *
 * - Den Hartog 1931: the steady non-stop amplitude of m x'' + k x + F sgn(x') = P cos(omega t), derived as
 *   he does from the half-period symmetric solution (docs/sweep.md): with beta = omega/omega_n,
 *   U = sin(pi/beta) / (beta (1 + cos(pi/beta))),  X / (P/k) = sqrt(1/(1 - beta^2)^2 - (F U / P)^2);
 *   the sweep's located amplitude agrees to 5e-5 (theta = 1/2 at dt = 0.005: second order, ~1e-5 seen), and
 *   the lone simulate's sampled maxima agree too (the formula checked against the solver independently of
 *   the features' interpolation).
 * - a forced linear oscillator: period 2 pi / omega and the amplitude P / sqrt((k - m w^2)^2 + (c w)^2).
 * - a run's features equal, bit for bit, those computed from the lone run of its document with every = 1.
 * - stick_fraction over the whole run equals the solver's own stick_time / t_end.
 * - bad documents answered by pointer; a value that breaks the base fails its run only, by the base's pointer.
 * - shards' run lines, sorted by index, are the whole sweep's, byte for byte.
 * - a network (a 2-mass chain, record.node): each node's period 2 pi / omega and amplitude |X_i| of the
 *   steady forced response (K - omega^2 M + i omega C) X = F, solved here in complex arithmetic; and a chain
 *   with a Coulomb element, its features and event section (record.node, record.element) the lone run's,
 *   bit for bit.
 */
#include <complex.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>
#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "dashpot/json.h"
#include "dashpot/sweep_json.h"

#include "check.h"

#define DEN_HARTOG_BASE                                                                                      \
    "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\","         \
    "\"phi0\":0.1},\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":1,\"omega\":2}},"                         \
    "\"solver\":{\"dt\":0.005,\"t_end\":1500}}"

/* All the lines of a sweep document run to its end, as one NDJSON text; the exec's status in *status. */
static char *sweep_lines(const char *doc_text, size_t shard_i, size_t shard_n, int *status)
{
    dp_errors errs;
    dp_errors_init(&errs);
    dp_sweep_doc *doc;
    int s = dp_sweep_parse(doc_text, strlen(doc_text), &doc, &errs);
    CHECK(s == DP_OK, "parse: %d %s %s", s, errs.n ? errs.item[0].pointer : "", errs.n ? errs.item[0].message : "");
    if (shard_n)
        dp_sweep_doc_set_shard(doc, shard_i, shard_n);
    dp_sweep_exec *x = dp_sweep_exec_new(doc, 0, 1, 0, NULL, 0);
    dp_buf out = { 0 };
    int line;
    const char *why;
    while ((s = dp_sweep_exec_next(x, &out, &line, &why)) == DP_MORE)
        if (line)
            dp_buf_append(&out, "\n", 1);
    *status = s;
    dp_buf_append(&out, "", 1);
    dp_sweep_exec_free(x);
    dp_sweep_doc_free(doc);
    return out.data;
}

/* The run line of `index` among the lines, parsed. */
static cJSON *run_line(const char *lines, size_t index)
{
    for (const char *p = lines; *p;) {
        const char *e = strchr(p, '\n');
        cJSON *o = cJSON_ParseWithLength(p, (size_t)(e - p));
        cJSON *i = cJSON_GetObjectItem(o, "index");
        if (i && (size_t)i->valuedouble == index)
            return o;
        cJSON_Delete(o);
        p = e + 1;
    }
    return NULL;
}

static double feature(const cJSON *line, const char *name)
{
    const cJSON *v = cJSON_GetObjectItem(cJSON_GetObjectItem(line, "features"), name);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

static double den_hartog(double beta, double F_over_P)
{
    double th = M_PI / beta, U = sin(th) / (beta * (1 + cos(th)));
    return sqrt(1 / ((1 - beta * beta) * (1 - beta * beta)) - F_over_P * F_over_P * U * U);
}

static void test_den_hartog(void **state)
{
    (void)state;
    static const double omega[] = { 0.7, 0.8, 1.5, 2, 3 };
    int s;
    char *lines = sweep_lines("{\"base\":" DEN_HARTOG_BASE ",\"vary\":[{\"pointer\":\"/model/forcing/omega\","
                              "\"values\":[0.7,0.8,1.5,2,3]}],\"record\":{\"after\":1200}}", 0, 0, &s);
    assert_int_equal(s, DP_DONE);
    for (size_t i = 0; i < 5; i++) {
        cJSON *l = run_line(lines, i);
        double X = den_hartog(omega[i], 0.1);
        NEAR(feature(l, "amplitude") / X, 1, 5e-5);
        NEAR(feature(l, "x_max") / X, 1, 5e-5);
        NEAR(feature(l, "period"), 2 * M_PI / omega[i], 1e-6);
        NEAR(feature(l, "stick_fraction"), 0, 0); /* non-stop motion: it never sticks */
        cJSON_Delete(l);
    }
    free(lines);
}

/* The period of a non-stop Den Hartog motion at frequencies whose period the step does not divide: the step
 * grid meets the motion at another phase every cycle, so its maxima differ from cycle to cycle by the
 * scheme's error (~(wh)^2/12 of the range), not by rounding. Compared to rounding they looked distinct, and
 * 2T or 3T was reported at w = 2.5, 2.6, 2.7, 2.8, 2.9, 3 with dt = 0.01 and record.after 800 (sweep_period.c). */
static void test_period_incommensurate_step(void **state)
{
    (void)state;
    static const double omega[] = { 2.5, 2.6, 2.7, 2.8, 2.9 };
    int s;
    char *lines = sweep_lines("{\"base\":{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},"
                              "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.1},\"forcing\":{\"kind\":\"harmonic\","
                              "\"amplitude\":1,\"omega\":2}},\"solver\":{\"dt\":0.01,\"t_end\":1000}},"
                              "\"vary\":[{\"pointer\":\"/model/forcing/omega\",\"values\":[2.5,2.6,2.7,2.8,2.9]}],"
                              "\"record\":{\"after\":800}}", 0, 0, &s);
    assert_int_equal(s, DP_DONE);
    for (size_t i = 0; i < 5; i++) {
        cJSON *l = run_line(lines, i);
        NEAR(feature(l, "period"), 2 * M_PI / omega[i], 1e-5);
        cJSON_Delete(l);
    }
    free(lines);
}

/* The closed form against a lone simulate's samples, without the sweep: max |x| over t in [1200, 1500]. */
static void test_den_hartog_lone(void **state)
{
    (void)state;
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    const char *doc = DEN_HARTOG_BASE;
    assert_int_equal(dp_spec_parse(doc, strlen(doc), 0, &spec, &errs), DP_OK);
    spec.output.every = 1;
    int st;
    dp_run *run = dp_run_alloc(&spec, 0, &errs, &st);
    dp_record rec[512];
    size_t n;
    double xmax = 0;
    while ((st = dp_run_next(run, rec, 512, &n)) >= 0) {
        for (size_t i = 0; i < n; i++)
            if (rec[i].type == DP_RECORD_SAMPLE && rec[i].u.sample.t >= 1200)
                xmax = fmax(xmax, fabs(rec[i].u.sample.x));
        if (st == DP_DONE)
            break;
    }
    assert_int_equal(st, DP_DONE);
    /* sampled every 0.005 at omega = 2: a maximum is missed by at most X (omega h)^2 / 8 = 1.2e-5 X */
    NEAR(xmax / den_hartog(2, 0.1), 1, 5e-5);
    dp_run_free(run);
    dp_spec_clear(&spec);
}

static void test_linear_period(void **state)
{
    (void)state;
    int s;
    char *lines = sweep_lines(
        "{\"base\":{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"linear\","
        "\"c\":0.2},\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":1,\"omega\":1}},\"solver\":{\"dt\":0.01,"
        "\"t_end\":400}},\"vary\":[{\"pointer\":\"/model/forcing/omega\",\"from\":0.5,\"to\":3,\"count\":3}],"
        "\"record\":{\"after\":250,\"features\":[\"period\",\"amplitude\"]}}", 0, 0, &s);
    assert_int_equal(s, DP_DONE);
    static const double omega[] = { 0.5, 1.75, 3 };
    for (size_t i = 0; i < 3; i++) {
        cJSON *l = run_line(lines, i);
        double w = omega[i], X = 1 / sqrt((1 - w * w) * (1 - w * w) + 0.04 * w * w);
        NEAR(feature(l, "period"), 2 * M_PI / w, 1e-7 * 2 * M_PI / w);
        NEAR(feature(l, "amplitude") / X, 1, 1e-4);
        CHECK(cJSON_GetObjectItem(cJSON_GetObjectItem(l, "features"), "x_max") == NULL, "x_max was not asked for");
        cJSON_Delete(l);
    }
    free(lines);
}

/* Features from a lone run of the document's run `index` (its text with every = 1), by hand. */
static void lone_features(const char *doc_text, size_t index, dp_features *f)
{
    dp_errors errs;
    dp_errors_init(&errs);
    dp_sweep_doc *doc;
    assert_int_equal(dp_sweep_parse(doc_text, strlen(doc_text), &doc, &errs), DP_OK);
    char *text = dp_sweep_doc_text(doc, index);
    cJSON *lone = cJSON_Parse(text);
    cJSON *out = cJSON_CreateObject();
    cJSON_AddNumberToObject(out, "every", 1);
    cJSON_DeleteItemFromObject(lone, "output");
    cJSON_AddItemToObject(lone, "output", out);
    char *lone_text = cJSON_PrintUnformatted(lone);
    dp_spec spec;
    dp_spec_init(&spec);
    assert_int_equal(dp_spec_parse(lone_text, strlen(lone_text), 0, &spec, &errs), DP_OK);
    int st;
    dp_run *run = dp_run_alloc(&spec, 0, &errs, &st);
    assert_non_null(run);
    assert_int_equal(dp_features_init(f, dp_sweep_doc_plan(doc), dp_run_columns(run)), DP_OK);
    dp_record rec[100]; /* another block size than the sweep's: the features must not depend on it */
    size_t n;
    do {
        st = dp_run_next(run, rec, 100, &n);
        for (size_t i = 0; i < n; i++)
            dp_features_add(f, &rec[i]);
    } while (st == DP_MORE);
    assert_int_equal(st, DP_DONE);
    dp_features_finish(f);
    dp_run_free(run);
    dp_spec_clear(&spec);
    free(lone_text);
    cJSON_Delete(lone);
    free(text);
    dp_sweep_doc_free(doc);
}

/* A belt-driven oscillator (generalized Coulomb, phi1 > phi0: stick-slip) over the belt speed, and a forced
 * Coulomb one with a stroboscopic section: the sweep's numbers are the lone run's, bit for bit. */
static void test_bit_for_bit(void **state)
{
    (void)state;
    static const char *const docs[] = {
        "{\"base\":{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":"
        "\"generalized-coulomb\",\"phi0\":0.8,\"phi1\":1,\"belt_velocity\":0.4}},\"initial\":{\"v\":0.4},"
        "\"solver\":{\"dt\":0.001,\"t_end\":60,\"theta\":0.5},\"output\":{\"every\":10}},\"vary\":[{\"pointer\":"
        "\"/model/damper/belt_velocity\",\"from\":0.1,\"to\":0.8,\"count\":3}],\"record\":{\"after\":20,"
        "\"section\":{\"event\":\"stick\",\"count\":10}}}",
        "{\"base\":" DEN_HARTOG_BASE ",\"vary\":[{\"pointer\":\"/model/forcing/omega\",\"values\":[0.6,2.5]},"
        "{\"pointer\":\"/model/damper/phi0\",\"values\":[0.05,0.5]}],\"record\":{\"after\":100,"
        "\"section\":{\"period\":2.5,\"count\":40}}}",
    };
    for (size_t d = 0; d < 2; d++) {
        int s;
        char *lines = sweep_lines(docs[d], 0, 0, &s);
        assert_int_equal(s, DP_DONE);
        size_t runs = d == 0 ? 3 : 4;
        for (size_t i = 0; i < runs; i++) {
            dp_features f;
            lone_features(docs[d], i, &f);
            cJSON *l = run_line(lines, i);
            for (int k = 0; k < DP_FEATURE_COUNT; k++) {
                const cJSON *v = cJSON_GetObjectItem(cJSON_GetObjectItem(l, "features"), dp_feature_name(k));
                CHECK(f.out.known[k] ? cJSON_IsNumber(v) && v->valuedouble == f.out.value[k] : cJSON_IsNull(v),
                      "doc %zu run %zu %s: sweep %.17g, lone %.17g", d, i, dp_feature_name(k),
                      v ? v->valuedouble : NAN, f.out.value[k]);
            }
            const cJSON *sec = cJSON_GetObjectItem(l, "section");
            assert_int_equal((size_t)cJSON_GetArraySize(sec), f.nsection);
            CHECK(f.nsection > 0, "doc %zu run %zu: an empty section", d, i);
            for (size_t j = 0; j < f.nsection; j++) {
                const cJSON *p = cJSON_GetArrayItem(sec, (int)j);
                CHECK(cJSON_GetArrayItem(p, 0)->valuedouble == f.section[j].t &&
                          cJSON_GetArrayItem(p, 1)->valuedouble == f.section[j].x &&
                          cJSON_GetArrayItem(p, 2)->valuedouble == f.section[j].v,
                      "doc %zu run %zu section point %zu differs", d, i, j);
            }
            if (d == 0) /* the belt: stick-slip at every speed here */
                CHECK(f.out.value[DP_FEATURE_STICK_FRACTION] > 0.05, "stick fraction %g",
                      f.out.value[DP_FEATURE_STICK_FRACTION]);
            cJSON_Delete(l);
            dp_features_clear(&f);
        }
        free(lines);
    }
}

/* From t = 0 on, the stick fraction is the solver's own stick time over t_end. */
static void test_stick_fraction(void **state)
{
    (void)state;
    const char *doc = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":"
                      "\"generalized-coulomb\",\"phi0\":0.8,\"phi1\":1,\"belt_velocity\":0.4}},\"initial\":{\"v\":0.4},"
                      "\"solver\":{\"dt\":0.001,\"t_end\":30,\"theta\":0.5}}";
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    assert_int_equal(dp_spec_parse(doc, strlen(doc), 0, &spec, &errs), DP_OK);
    dp_sweep_plan plan;
    dp_sweep_plan_init(&plan);
    int st;
    dp_sweep_one *o = dp_sweep_one_alloc(&spec, &plan, 0, "/record", &errs, &st);
    while ((st = dp_sweep_one_next(o)) == DP_MORE)
        ;
    assert_int_equal(st, DP_DONE);
    const dp_features *f = dp_sweep_one_features(o);
    double expect = dp_sweep_one_summary(o)->stick_time / 30;
    CHECK(expect > 0.2, "the run sticks: %g", expect);
    NEAR(f->out.value[DP_FEATURE_STICK_FRACTION], expect, 1e-12);
    NEAR(f->out.value[DP_FEATURE_V_MAX], 0.4, 1e-12); /* it rides the belt; the slips go backwards */
    dp_sweep_one_free(o);
    dp_spec_clear(&spec);
}

/* Bad sweep documents, each answered at the pointer of its fault. */
static void test_bad_documents(void **state)
{
    (void)state;
    static const struct { const char *doc, *pointer; } cases[] = {
        { "{\"vary\":[{\"pointer\":\"/a\",\"values\":[1]}]}", "/base" },
        { "{\"base\":{\"a\":1},\"vary\":{}}", "/vary" },
        { "{\"base\":{\"a\":1},\"vary\":[]}", "/vary" },
        { "{\"base\":{\"model\":{}},\"vary\":[{\"pointer\":\"/model/nope/x\",\"values\":[1]}]}", "/vary/0/pointer" },
        { "{\"base\":{\"solver\":{\"kind\":\"stick-slip\"}},\"vary\":[{\"pointer\":\"/solver/kind\",\"values\":[1]}]}",
          "/vary/0/pointer" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"a\",\"values\":[1]}]}", "/vary/0/pointer" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a~2\",\"values\":[1]}]}", "/vary/0/pointer" },
        { "{\"base\":{\"a\":[1,2]},\"vary\":[{\"pointer\":\"/a/2\",\"values\":[1]}]}", "/vary/0/pointer" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"from\":0,\"to\":1,\"count\":3,\"scale\":\"log\"}]}",
          "/vary/0/from" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"from\":0,\"to\":1,\"count\":0}]}", "/vary/0/count" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"values\":[1],\"from\":0}]}", "/vary/0" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\"}]}", "/vary/0" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"values\":[1,\"x\"]}]}", "/vary/0/values/1" },
        { "{\"base\":{\"a\":1,\"b\":1},\"vary\":[{\"pointer\":\"/a\",\"from\":0,\"to\":1,\"count\":200},"
          "{\"pointer\":\"/b\",\"from\":0,\"to\":1,\"count\":200}]}", "/vary" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"values\":[1]},{\"pointer\":\"/a\",\"values\":[2]}]}",
          "/vary/1/pointer" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"values\":[1]}],\"record\":{\"section\":{\"period\":1,"
          "\"event\":\"stick\"}}}", "/record/section" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"values\":[1]}],\"record\":{\"section\":{\"period\":0}}}",
          "/record/section/period" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"values\":[1]}],\"record\":{\"features\":[\"x_mx\"]}}",
          "/record/features/0" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"values\":[1]}],\"record\":{\"after\":-1}}",
          "/record/after" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"values\":[1]}],\"shard\":{\"index\":2,\"count\":2}}",
          "/shard/index" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"values\":[1]}],\"runs\":[1]}", "/runs/0" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"values\":[1,2]}],\"runs\":[1,1]}", "/runs/1" },
        { "{\"base\":{\"a\":1},\"vary\":[{\"pointer\":\"/a\",\"values\":[1]}],\"foo\":1}", "/foo" },
        { "{\"base\":7,\"vary\":[{\"pointer\":\"/a\",\"values\":[1]}]}", "/base" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dp_errors errs;
        dp_errors_init(&errs);
        dp_sweep_doc *doc;
        int s = dp_sweep_parse(cases[i].doc, strlen(cases[i].doc), &doc, &errs);
        CHECK(s == DP_EINVAL && doc == NULL, "case %zu: status %d", i, s);
        int found = 0;
        for (size_t e = 0; e < errs.n; e++)
            found |= strcmp(errs.item[e].pointer, cases[i].pointer) == 0;
        CHECK(found, "case %zu: expected an error at %s, first is %s: %s", i, cases[i].pointer,
              errs.n ? errs.item[0].pointer : "(none)", errs.n ? errs.item[0].message : "");
    }
    dp_errors errs;
    dp_errors_init(&errs);
    dp_sweep_doc *doc;
    assert_int_equal(dp_sweep_parse("{\"base\":", 8, &doc, &errs), DP_ESYNTAX);
}

/* A value that makes the base invalid fails that run alone, by the base's pointer; a missing member is added. */
static void test_bad_run(void **state)
{
    (void)state;
    int s;
    char *lines = sweep_lines("{\"base\":{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":"
                              "{\"law\":\"none\"}},\"initial\":{\"x\":1},\"solver\":{\"dt\":0.01,\"t_end\":60}},"
                              "\"vary\":[{\"pointer\":\"/model/mass\",\"values\":[1,-1,4]},{\"pointer\":\"/initial/v\","
                              "\"values\":[0]}]}", 0, 0, &s);
    assert_int_equal(s, DP_DONE);
    cJSON *bad = run_line(lines, 1), *good = run_line(lines, 2);
    assert_int_equal(cJSON_GetObjectItem(bad, "status")->valueint, 422);
    const cJSON *err = cJSON_GetArrayItem(cJSON_GetObjectItem(bad, "errors"), 0);
    assert_string_equal(cJSON_GetObjectItem(err, "pointer")->valuestring, "/model/mass");
    /* m = 4, k = 1: omega_n = 1/2; the trapezoidal rule (theta = 1/2, chosen) turns at exactly
     * omega_h = (2/h) atan(omega_n h / 2) per unit time on a linear oscillator */
    NEAR(feature(good, "period"), 2 * M_PI / (200 * atan(0.5 * 0.01 / 2)), 1e-9);
    NEAR(feature(good, "x_max"), 1, 1e-9);
    cJSON_Delete(bad);
    cJSON_Delete(good);
    free(lines);
}

/* Run lines sorted by index, as one text. */
static char *sorted_runs(char **parts, size_t nparts, size_t runs)
{
    dp_buf out = { 0 };
    for (size_t i = 0; i < runs; i++)
        for (size_t p = 0; p < nparts; p++) {
            char key[64];
            snprintf(key, sizeof key, "{\"type\":\"run\",\"index\":%zu,", i);
            const char *at = strstr(parts[p], key);
            if (at == NULL)
                continue;
            dp_buf_append(&out, at, (size_t)(strchr(at, '\n') - at) + 1);
        }
    dp_buf_append(&out, "", 1);
    return out.data;
}

static void test_shards(void **state)
{
    (void)state;
    const char *doc = "{\"base\":{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":"
                      "{\"law\":\"coulomb\",\"phi0\":0.2}},\"initial\":{\"x\":1},\"solver\":{\"dt\":0.01,\"t_end\":20}},"
                      "\"vary\":[{\"pointer\":\"/model/damper/phi0\",\"values\":[0.05,0.1,0.2]},{\"pointer\":"
                      "\"/initial/x\",\"from\":0.5,\"to\":4,\"count\":4,\"scale\":\"log\"}],\"record\":{\"section\":"
                      "{\"event\":\"stick\",\"count\":3}}}";
    int s;
    char *whole = sweep_lines(doc, 0, 0, &s), *parts[3];
    for (size_t i = 0; i < 3; i++)
        parts[i] = sweep_lines(doc, i, 3, &s);
    char *a = sorted_runs(&whole, 1, 12), *b = sorted_runs(parts, 3, 12);
    CHECK(strlen(a) > 12 * 50, "12 run lines: %zu bytes", strlen(a));
    assert_string_equal(a, b);
    CHECK(strstr(parts[1], "\"index\":0,") == NULL && strstr(parts[1], "\"index\":4,") != NULL,
          "shard 1 of 3 runs 1, 4, 7, 10");
    /* row-major: run 5 is phi0 = 0.1 (i0 = 1), x0 = the second log value 1 (i1 = 1) */
    cJSON *five = run_line(whole, 5);
    const cJSON *v = cJSON_GetObjectItem(five, "values");
    NEAR(cJSON_GetArrayItem(v, 0)->valuedouble, 0.1, 0);
    NEAR(cJSON_GetArrayItem(v, 1)->valuedouble, 1, 1e-15);
    cJSON_Delete(five);
    free(a);
    free(b);
    free(whole);
    for (size_t i = 0; i < 3; i++)
        free(parts[i]);
}

static int stop_now(void *ctx)
{
    (void)ctx;
    return 1;
}

/* The stop hook ends the sweep inside a run; a spent step budget ends it before a run starts. */
static void test_stop_and_budget(void **state)
{
    (void)state;
    const char *text = "{\"base\":" DEN_HARTOG_BASE ",\"vary\":[{\"pointer\":\"/model/forcing/omega\","
                       "\"values\":[1,2,3]}]}";
    dp_errors errs;
    dp_errors_init(&errs);
    dp_sweep_doc *doc;
    assert_int_equal(dp_sweep_parse(text, strlen(text), &doc, &errs), DP_OK);
    dp_sweep_exec *x = dp_sweep_exec_new(doc, 0, 1, 0, NULL, 0);
    dp_sweep_exec_set_stop(x, stop_now, NULL);
    dp_buf out = { 0 };
    int line, s;
    const char *why;
    while ((s = dp_sweep_exec_next(x, &out, &line, &why)) == DP_MORE)
        ;
    assert_int_equal(s, DP_ECANCEL);
    dp_sweep_exec_free(x);
    _Atomic unsigned long long budget = 0;
    x = dp_sweep_exec_new(doc, 0, 1, 0, &budget, 500000); /* 300 000 steps a run: the second is over */
    while ((s = dp_sweep_exec_next(x, &out, &line, &why)) == DP_MORE)
        ;
    assert_int_equal(s, DP_ELIMIT);
    assert_int_equal(dp_sweep_exec_totals(x)->completed, 1);
    dp_sweep_exec_free(x);
    dp_buf_free(&out);
    dp_sweep_doc_free(doc);
}

/* The interpolant's turn of x = sin t between samples about pi/2. */
static void test_hermite(void **state)
{
    (void)state;
    dp_traj_point a = { 1.5, sin(1.5), cos(1.5), 0, 0 }, b = { 1.6, sin(1.6), cos(1.6), 0, 0 };
    double t = dp_hermite_turn(&a, &b), x, v;
    dp_hermite_eval(&a, &b, t, &x, &v);
    /* the cubic's slope is x' to O(h^3): h^3 / 24 = 4e-5 bounds its error, the turn's time follows; x at the
     * turn is second order in that error */
    NEAR(t, M_PI / 2, 4e-5);
    NEAR(x, 1, 2.7e-7); /* the cubic Hermite interpolant's error bound h^4 max|x''''| / 384 */
    NEAR(v, 0, 1e-12);
}

/* A 2-mass chain: ground -k1,c1- node 0 -k2,c2- node 1, node 1 forced by P cos(omega t). C = 0.2 K: every mode
 * damped (zeta_j = 0.1 omega_j, natural frequencies 0.618 and 1.618), so by t = 400 the transient is
 * exp(-0.1 * 0.618^2 * 400) = 2e-7 of its start. */
#define CHAIN_BASE                                                                                           \
    "{\"model\":{\"masses\":[1,1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":\"linear\","  \
    "\"k\":1},\"damper\":{\"law\":\"linear\",\"c\":0.2}},{\"between\":[0,1],\"spring\":{\"law\":\"linear\","  \
    "\"k\":1},\"damper\":{\"law\":\"linear\",\"c\":0.2}}],\"forcing\":[{\"node\":1,\"kind\":\"harmonic\","     \
    "\"amplitude\":1,\"omega\":1,\"phase\":0}]},\"initial\":{\"x\":[0,0],\"v\":[0,0]},"                       \
    "\"solver\":{\"kind\":\"stick-slip\",\"dt\":0.005,\"t_end\":500,\"theta\":0.5}}"

/* |X_node| of the chain's steady response to a unit force at node 1: (K - w^2 M + i w C) X = (0, 1). */
static double chain_amplitude(double w, size_t node)
{
    double complex z00 = 2 - w * w + I * w * 0.4, z01 = -1 - I * w * 0.2, z11 = 1 - w * w + I * w * 0.2;
    double complex det = z00 * z11 - z01 * z01;
    return cabs(node == 0 ? -z01 / det : z00 / det);
}

static void test_network_chain(void **state)
{
    (void)state;
    static const double omega[] = { 0.4, 1, 2 };
    for (size_t node = 0; node < 2; node++) {
        char doc[2048];
        snprintf(doc, sizeof doc,
                 "{\"base\":" CHAIN_BASE ",\"vary\":[{\"pointer\":\"/model/forcing/0/omega\",\"values\":[0.4,1,2]}],"
                 "\"record\":{\"after\":400,\"node\":%zu,\"features\":[\"period\",\"amplitude\",\"x_max\"]}}",
                 node);
        int s;
        char *lines = sweep_lines(doc, 0, 0, &s);
        assert_int_equal(s, DP_DONE);
        for (size_t i = 0; i < 3; i++) {
            cJSON *l = run_line(lines, i);
            double w = omega[i], X = chain_amplitude(w, node);
            NEAR(feature(l, "period"), 2 * M_PI / w, 1e-7 * 2 * M_PI / w);
            /* theta = 1/2 at dt = 0.005: the trapezoidal rule's second-order error, 4e-5 seen at most (node 0 at
             * omega = 2, above both natural frequencies, where its response is the smaller one) */
            CHECK(fabs(feature(l, "amplitude") / X - 1) < 1e-4, "node %zu omega %g: amplitude %.9g, closed form %.9g",
                  node, w, feature(l, "amplitude"), X);
            NEAR(feature(l, "x_max") / X, 1, 1e-4);
            cJSON_Delete(l);
        }
        free(lines);
    }
    /* the nodes' amplitudes differ (at 0.4: 1.81 and 3.34): the features follow record.node, not node 0 */
    CHECK(fabs(chain_amplitude(0.4, 0) - chain_amplitude(0.4, 1)) > 0.5, "the nodes' amplitudes are alike");
}

/* A chain whose first element has Coulomb friction (stick-slip on the ground), the features of node 1 and the
 * stick events of element 0: the sweep's numbers are the lone run's, bit for bit. */
static void test_network_bit_for_bit(void **state)
{
    (void)state;
    static const char *const doc =
        "{\"base\":{\"model\":{\"masses\":[1,2],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":"
        "\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":0.3}},{\"between\":[0,1],\"spring\":{\"law\":"
        "\"linear\",\"k\":2},\"damper\":{\"law\":\"linear\",\"c\":0.1}}],\"forcing\":[{\"node\":1,\"kind\":"
        "\"harmonic\",\"amplitude\":0.5,\"omega\":1,\"phase\":0}]},\"initial\":{\"x\":[0.5,0],\"v\":[0,0]},"
        "\"solver\":{\"kind\":\"stick-slip\",\"dt\":0.002,\"t_end\":60,\"theta\":0.5}},\"vary\":[{\"pointer\":"
        "\"/model/forcing/0/omega\",\"values\":[0.3,1.2]}],\"record\":{\"after\":20,\"node\":1,\"element\":0,"
        "\"section\":{\"event\":\"stick\",\"count\":20}}}";
    int s;
    char *lines = sweep_lines(doc, 0, 0, &s);
    assert_int_equal(s, DP_DONE);
    for (size_t i = 0; i < 2; i++) {
        dp_features f;
        lone_features(doc, i, &f);
        cJSON *l = run_line(lines, i);
        for (int k = 0; k < DP_FEATURE_COUNT; k++) {
            const cJSON *v = cJSON_GetObjectItem(cJSON_GetObjectItem(l, "features"), dp_feature_name(k));
            CHECK(f.out.known[k] ? cJSON_IsNumber(v) && v->valuedouble == f.out.value[k] : cJSON_IsNull(v),
                  "run %zu %s: sweep %.17g, lone %.17g", i, dp_feature_name(k), v ? v->valuedouble : NAN,
                  f.out.value[k]);
        }
        const cJSON *sec = cJSON_GetObjectItem(l, "section");
        assert_int_equal((size_t)cJSON_GetArraySize(sec), f.nsection);
        CHECK(f.nsection > 0, "run %zu: element 0 never sticks after t = 20", i);
        CHECK(f.out.value[DP_FEATURE_STICK_FRACTION] > 0 && f.out.value[DP_FEATURE_STICK_FRACTION] < 1,
              "run %zu: stick fraction %g", i, f.out.value[DP_FEATURE_STICK_FRACTION]);
        for (size_t j = 0; j < f.nsection; j++) {
            const cJSON *p = cJSON_GetArrayItem(sec, (int)j);
            CHECK(cJSON_GetArrayItem(p, 0)->valuedouble == f.section[j].t &&
                      cJSON_GetArrayItem(p, 1)->valuedouble == f.section[j].x,
                  "run %zu section point %zu differs", i, j);
        }
        cJSON_Delete(l);
        dp_features_clear(&f);
    }
    free(lines);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hermite),
        cmocka_unit_test(test_den_hartog),
        cmocka_unit_test(test_den_hartog_lone),
        cmocka_unit_test(test_period_incommensurate_step),
        cmocka_unit_test(test_linear_period),
        cmocka_unit_test(test_bit_for_bit),
        cmocka_unit_test(test_stick_fraction),
        cmocka_unit_test(test_bad_documents),
        cmocka_unit_test(test_bad_run),
        cmocka_unit_test(test_shards),
        cmocka_unit_test(test_stop_and_budget),
        cmocka_unit_test(test_network_chain),
        cmocka_unit_test(test_network_bit_for_bit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
