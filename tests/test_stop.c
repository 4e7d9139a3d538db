/* tests/test_stop.c - a run stops when its stop hook says so, within a bounded amount of work,
 * and NUL characters and duplicate keys are refused with their pointers.
 *
 * The property: for random valid specs (every solver, variant and law, graph and table sizes up to the
 * maximum, relaxation, belt, output decimation from 1 to 10^15), the hook is asked at least every
 * STOP_BOUND_MS of wall time while the run computes, and once it says stop, that very dp_run_next returns
 * DP_ECANCEL with an error message, and so does every later call. Without a stop, a hook changes nothing:
 * the records are bit for bit those of the same run without one.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include "dashpot/json.h"
#include "dashpot/stability_json.h"

/* The documented bound (docs/operations.md, "Stopping a run"), with room for a sanitizer build. */
#define STOP_BOUND_MS 50.0
#define CASES 400

/* The thread's CPU time, not the wall clock: the bound is on the solver's work between two polls, and a
 * shared machine (a parallel build, CI's neighbours) may preempt the test for longer than that. The wall-clock
 * side, with a daemon under load, is tests/robustness/stop.sh. */
static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

/* ---- random specs --------------------------------------------------------------------------------- */

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static uint64_t next_u64(void)
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return rng;
}
static int pick(int n) { return (int)(next_u64() % (uint64_t)n); }
static double unit(void) { return (double)(next_u64() >> 11) / 9007199254740992.0; }

typedef struct text { char *s; size_t len, cap; } text;

static void put(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(text *t, const char *fmt, ...)
{
    va_list ap;
    for (;;) {
        va_start(ap, fmt);
        int n = vsnprintf(t->s + t->len, t->cap - t->len, fmt, ap);
        va_end(ap);
        if ((size_t)n < t->cap - t->len) {
            t->len += (size_t)n;
            return;
        }
        t->cap = 2 * t->cap + (size_t)n + 64;
        t->s = realloc(t->s, t->cap);
        assert_non_null(t->s);
    }
}

/* Graph points: n up to the maximum, monotone; `jump` puts a Coulomb-like step at 0. */
static void graph_points(text *t, int n, double slope, double jump)
{
    put(t, "[");
    for (int i = 0; i < n; i++) {
        double y = -1 + 2.0 * i / (n - 1);
        double f = slope * y * (1 + 0.1 * fabs(y)) + (i >= n / 2 ? jump : -jump);
        put(t, "%s[%.9g,%.9g]", i ? "," : "", y, f);
    }
    put(t, "]");
}

static int big_n(void)
{
    static const int sizes[] = { 2, 3, 17, 500, 4000, 10000 };
    return sizes[pick(6)];
}

static void forcing(text *t, double t_end)
{
    switch (pick(5)) {
    case 0: put(t, "{\"kind\":\"constant\",\"value\":%.3g}", unit() - 0.5); break;
    case 1: put(t, "{\"kind\":\"harmonic\",\"amplitude\":%.3g,\"omega\":%.3g}", unit(), 0.1 + 3 * unit()); break;
    case 2: {
        int n = big_n();
        put(t, "{\"kind\":\"table\",\"points\":[");
        for (int i = 0; i < n; i++)
            put(t, "%s[%.9g,%.6g]", i ? "," : "", t_end * i / (n - 1), 0.5 * sin(7.0 * i));
        put(t, "]}");
        break;
    }
    case 3: put(t, "{\"kind\":\"sum\",\"terms\":[{\"kind\":\"constant\",\"value\":0.1},"
                   "{\"kind\":\"harmonic\",\"amplitude\":0.4,\"omega\":1.1}]}"); break;
    default: put(t, "{\"kind\":\"constant\",\"value\":0}"); break;
    }
}

static void relaxation(text *t)
{
    switch (pick(4)) {
    case 0: put(t, ",\"relaxation\":{\"kind\":\"rational\",\"a\":%.3g,\"b\":1}", 0.1 + unit()); break;
    case 1: put(t, ",\"relaxation\":{\"kind\":\"linear\",\"L\":%.3g}", 0.1 * unit()); break;
    case 2: put(t, ",\"relaxation\":{\"kind\":\"power\",\"N\":%d}", 2 + pick(3)); break;
    default: break;
    }
}

/* One random spec of 10^7 to 10^8 steps (or a regularized run as long). */
static void random_spec(text *t)
{
    double dt = pick(2) ? 1e-6 : 1e-5, t_end = dt * (1e7 + 9e7 * unit());
    static const char *const every[] = { "1", "1000", "1e6", "1e15" };
    int solver = pick(6); /* 0-2 stick-slip exact, 3 thesis, 4 analytic, 5 regularized */
    put(t, "{\"model\":{\"mass\":%.3g,\"spring\":", 0.5 + unit());
    if (solver < 3 && pick(2)) {
        put(t, "{\"law\":\"graph\",\"points\":");
        graph_points(t, big_n(), 1 + unit(), 0);
        put(t, "}");
    } else {
        put(t, "{\"law\":\"linear\",\"k\":%.3g}", 0.5 + 2 * unit());
    }
    put(t, ",\"damper\":");
    int law = solver == 4 ? 0 : pick(4);
    if (law == 0)
        put(t, "{\"law\":\"coulomb\",\"phi0\":%.3g", 0.05 + 0.3 * unit());
    else if (law == 1)
        put(t, "{\"law\":\"bingham\",\"tau\":%.3g,\"c\":%.3g", 0.1 * unit(), unit());
    else if (law == 2)
        put(t, "{\"law\":\"generalized-coulomb\",\"phi0\":0.1,\"phi1\":%.3g", 0.1 + 0.2 * unit());
    else {
        put(t, "{\"law\":\"graph\",\"points\":");
        graph_points(t, big_n(), 0.5, 0.3 * unit());
    }
    if (solver != 4)
        relaxation(t);
    if (solver < 3 && pick(2))
        put(t, ",\"belt_velocity\":0.3");
    put(t, "}");
    if (solver != 4) {
        put(t, ",\"forcing\":");
        forcing(t, t_end);
    }
    put(t, "},\"initial\":{\"x\":%.3g,\"v\":0},\"solver\":", 2 * unit() - 1);
    if (solver < 3)
        put(t, "{\"kind\":\"stick-slip\",\"dt\":%g,\"t_end\":%.17g,\"theta\":%s,\"events\":\"%s\",\"branch\":\"%s\"}",
            dt, t_end, pick(2) ? "1" : "0.5", pick(2) ? "locate" : "none", pick(4) ? "rest" : "motion");
    else if (solver == 3)
        put(t, "{\"kind\":\"stick-slip\",\"variant\":\"thesis\",\"dt\":%g,\"t_end\":%.17g,\"Z\":%d,\"eps\":1e-300}",
            dt, t_end, pick(2) ? 1000000 : 100);
    else if (solver == 4)
        put(t, "{\"kind\":\"analytic\",\"dt\":%g,\"t_end\":%.17g}", dt, t_end);
    else {
        static const char *const steppers[] = { "msbdf", "rk4imp", "bsimp", "rkf45", "rkck", "rk8pd" };
        put(t, "{\"kind\":\"regularized\",\"scheme\":\"%s\",\"n\":%d,\"dt\":%g,\"t_end\":%.17g,\"stepper\":\"%s\"}",
            pick(2) ? "PC" : "PI", 10 + pick(1000), dt * 1000, t_end, steppers[pick(6)]);
    }
    put(t, ",\"output\":{\"every\":%s}}", every[pick(4)]);
}

/* The slow spec of the stop tests (~1.9 us a step before): 10^4-point graph spring and damper, rational relaxation,
 * a belt, a 10^4-point table load, 10^8 steps of 10^-7, one sample in 10^15. */
static void slow_spec(text *t)
{
    put(t, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"graph\",\"points\":");
    graph_points(t, 10000, 1, 0);
    put(t, "},\"damper\":{\"law\":\"graph\",\"points\":");
    graph_points(t, 10000, 0.5, 0.3);
    put(t, ",\"relaxation\":{\"kind\":\"rational\",\"a\":1,\"b\":1},\"belt_velocity\":0.3},\"forcing\":"
           "{\"kind\":\"table\",\"points\":[");
    for (int i = 0; i < 10000; i++)
        put(t, "%s[%.9g,%.6g]", i ? "," : "", 10.0 * i / 9999, 0.5 * ((i * 7919) % 13) / 13);
    put(t, "]}},\"initial\":{\"x\":0,\"v\":0},\"solver\":{\"kind\":\"stick-slip\",\"dt\":1e-7,\"t_end\":10},"
           "\"output\":{\"every\":1e15}}");
}

/* ---- the property ---------------------------------------------------------------------------------- */

typedef struct watch {
    int calls, stop_at;   /* says stop on call number stop_at */
    double last, max_gap; /* ms */
} watch;

static int hook(void *ctx)
{
    watch *w = ctx;
    double t = now_ms();
    if (t - w->last > w->max_gap)
        w->max_gap = t - w->last;
    w->last = t;
    return ++w->calls >= w->stop_at;
}

static dp_record recs[512];

static void cancelled_runs_stop_within_the_bound(void **state)
{
    (void)state;
    int accepted = 0, by_kind[3] = { 0 };
    double worst = 0;
    for (int k = 0; k < CASES; k++) {
        text t = { 0 };
        if (k == 0)
            slow_spec(&t);
        else
            random_spec(&t);
        dp_spec spec;
        dp_errors errs;
        dp_spec_init(&spec);
        dp_errors_init(&errs);
        int st = dp_spec_parse(t.s, t.len, 1e9, &spec, &errs);
        dp_run *run = st == DP_OK ? dp_run_alloc(&spec, 1e9, &errs, &st) : NULL;
        if (run == NULL) { /* a combination the checks refuse (e.g. a step too long for the law): skip it */
            dp_spec_clear(&spec);
            free(t.s);
            continue;
        }
        accepted++;
        by_kind[spec.solver.kind == DP_SOLVER_REGULARIZED ? 2 : spec.solver.kind == DP_SOLVER_ANALYTIC]++;
        watch w = { .stop_at = k == 0 ? 50 : 2 + pick(3), .last = now_ms() };
        dp_run_set_stop(run, hook, &w);
        size_t n;
        int s;
        while ((s = dp_run_next(run, recs, 512, &n)) == DP_MORE)
            if (w.calls >= w.stop_at)
                fail_msg("case %d: the hook said stop, yet dp_run_next returned DP_MORE", k);
        double gap = fmax(w.max_gap, now_ms() - w.last);
        if (s != DP_DONE) { /* a run may finish (or diverge) before its stop; else it must say it stopped */
            if (w.calls >= w.stop_at) {
                assert_int_equal(s, DP_ECANCEL);
                assert_non_null(strstr(dp_run_error(run), "stopped"));
                assert_int_equal(dp_run_next(run, recs, 512, &n), DP_ECANCEL);
                assert_int_equal(n, 0);
            } else {
                assert_true(s == DP_ENONFINITE || s == DP_ESOLVE);
            }
        }
        if (gap > worst)
            worst = gap;
        if (getenv("STOP_DEBUG") && gap > 2)
            print_message("case %d: %.2f ms, %d polls: %.200s ... %s\n", k, gap, w.calls, t.s, t.s + t.len - 200);
        if (gap > STOP_BOUND_MS)
            fail_msg("case %d: %.1f ms between two polls of the stop hook (bound %.0f ms): %.300s", k, gap,
                     STOP_BOUND_MS, t.s);
        dp_run_free(run);
        dp_spec_clear(&spec);
        free(t.s);
    }
    print_message("    %d of %d random specs ran (stick-slip %d, analytic %d, regularized %d); longest gap "
                  "between polls %.2f ms\n", accepted, CASES, by_kind[0], by_kind[1], by_kind[2], worst);
    assert_true(accepted >= CASES / 3);
    assert_true(by_kind[0] > 10 && by_kind[1] > 3 && by_kind[2] > 3);
}

static int never(void *ctx)
{
    (*(int *)ctx)++;
    return 0;
}

/* Records of one run of doc with output every 1 into out (cap records); returns how many. */
static size_t collect(const char *doc, int with_hook, dp_record *out, size_t cap, int *polls)
{
    dp_spec spec;
    dp_errors errs;
    int st;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    assert_int_equal(dp_spec_parse(doc, strlen(doc), 0, &spec, &errs), DP_OK);
    dp_run *run = dp_run_alloc(&spec, 0, &errs, &st);
    assert_non_null(run);
    if (with_hook)
        dp_run_set_stop(run, never, polls);
    size_t total = 0, n;
    while ((st = dp_run_next(run, recs, 512, &n)) >= 0) {
        for (size_t i = 0; i < n && total < cap; i++)
            out[total++] = recs[i];
        if (st == DP_DONE)
            break;
    }
    assert_int_equal(st, DP_DONE);
    dp_run_free(run);
    dp_spec_clear(&spec);
    return total;
}

/* A hook that never stops changes nothing, bit for bit, and is asked about once per DP_RUN_POLL_WORK steps. */
static void a_hook_that_never_stops_changes_nothing(void **state)
{
    (void)state;
    static const char *const docs[] = {
        "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":0.2},"
        "\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":0.5,\"omega\":1}},\"initial\":{\"x\":1,\"v\":0},"
        "\"solver\":{\"dt\":1e-4,\"t_end\":20},\"output\":{\"every\":1000}}",
        "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":0.2,"
        "\"relaxation\":{\"kind\":\"rational\",\"a\":1,\"b\":1}}},\"initial\":{\"x\":1,\"v\":0},"
        "\"solver\":{\"dt\":1e-4,\"t_end\":10},\"output\":{\"every\":1000}}",
    };
    static dp_record a[1000], b[1000];
    for (size_t d = 0; d < sizeof docs / sizeof docs[0]; d++) {
        int polls = 0;
        size_t na = collect(docs[d], 0, a, 1000, &polls), nb = collect(docs[d], 1, b, 1000, &polls);
        assert_int_equal(na, nb);
        assert_true(na > 100);
        assert_memory_equal(a, b, na * sizeof a[0]);
        /* 2*10^5 or 10^5 steps: at least steps / DP_RUN_POLL_WORK polls, at most one per step */
        assert_true(polls >= 100000 / DP_RUN_POLL_WORK && polls < 100000);
    }
}

/* ---- NUL characters and duplicate keys -------------------------------------------------------------- */

static void expect_spec_error(const char *doc, size_t len, const char *pointer, const char *fragment)
{
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int st = dp_spec_parse(doc, len, 0, &spec, &errs);
    dp_spec_clear(&spec);
    assert_int_equal(st, DP_EINVAL);
    for (size_t i = 0; i < errs.n; i++)
        if (strcmp(errs.item[i].pointer, pointer) == 0 && strstr(errs.item[i].message, fragment))
            return;
    for (size_t i = 0; i < errs.n; i++)
        print_error("    %s: %s\n", errs.item[i].pointer, errs.item[i].message);
    fail_msg("no error at \"%s\" saying \"%s\"", pointer, fragment);
}

#define MODEL_TAIL "\"damper\":{\"law\":\"coulomb\",\"phi0\":1}},\"solver\":{\"dt\":0.1,\"t_end\":1}}"

static void nul_in_a_spec_string_is_refused(void **state)
{
    (void)state;
    const char *value = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\\u0000xx\",\"k\":1}," MODEL_TAIL;
    expect_spec_error(value, strlen(value), "/model/spring/law", "NUL");
    const char *key = "{\"model\":{\"ma\\u0000ss\":1,\"spring\":{\"law\":\"linear\",\"k\":1}," MODEL_TAIL;
    expect_spec_error(key, strlen(key), "/model", "a key of this object contains a NUL");
    const char *deep = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"graph\",\"points\":[[0,0],[1,\"a\\u0000\"]]},"
                       MODEL_TAIL;
    expect_spec_error(deep, strlen(deep), "/model/spring/points/1/1", "NUL");
    char raw[] = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear@\",\"k\":1}," MODEL_TAIL;
    *strchr(raw, '@') = '\0'; /* a raw NUL byte inside the string */
    expect_spec_error(raw, sizeof raw - 1, "/model/spring/law", "NUL");
    /* an escaped backslash before u0000 is no NUL: the document is merely an unknown law */
    const char *not_nul = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"x\\\\u0000\",\"k\":1}," MODEL_TAIL;
    expect_spec_error(not_nul, strlen(not_nul), "/model/spring/law", "unknown law");
}

static void expect_stability_error(const char *doc, const char *pointer, const char *fragment)
{
    dp_buf out = { 0 };
    dp_errors errs;
    dp_errors_init(&errs);
    assert_int_equal(dp_stability_respond(doc, strlen(doc), DP_STABILITY_JSON, &out, &errs), DP_EINVAL);
    dp_buf_free(&out);
    for (size_t i = 0; i < errs.n; i++)
        if (strcmp(errs.item[i].pointer, pointer) == 0 && strstr(errs.item[i].message, fragment))
            return;
    for (size_t i = 0; i < errs.n; i++)
        print_error("    %s: %s\n", errs.item[i].pointer, errs.item[i].message);
    fail_msg("no error at \"%s\" saying \"%s\"", pointer, fragment);
}

static void stability_refuses_nul_and_duplicate_keys(void **state)
{
    (void)state;
    expect_stability_error("{\"mass\": 1, \"mass\": 2, \"law\": {\"lambda\": [1, 0.5], \"mu\": [1, 1]}}", "/mass",
                           "duplicate key");
    expect_stability_error("{\"mass\": 1, \"law\": {\"lambda\": [1, 0.5], \"mu\": [1, 1], \"mu\": [2, 2]}}", "/law/mu",
                           "duplicate key");
    expect_stability_error("{\"mass\": 1, \"law\": {\"lambda\": [1, 0.5], \"mu\": [1, 1]}, \"map\": "
                           "{\"x\": {\"param\": \"a\\u0000\", \"from\": 0, \"to\": 1, \"steps\": 2}}}",
                           "/map/x/param", "NUL");
    expect_stability_error("{\"mass\": 1, \"law\": {\"lambda\": [1, 0.5], \"m\\u0000u\": [1, 1]}}", "/law",
                           "a key of this object contains a NUL");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(nul_in_a_spec_string_is_refused),
        cmocka_unit_test(stability_refuses_nul_and_duplicate_keys),
        cmocka_unit_test(a_hook_that_never_stops_changes_nothing),
        cmocka_unit_test(cancelled_runs_stop_within_the_bound),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
