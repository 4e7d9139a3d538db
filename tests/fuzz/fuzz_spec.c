/* tests/fuzz/fuzz_spec.c - libFuzzer target: any bytes through the spec parser and validator, and when they
 * make a valid spec, a short solver run whose every record must be finite, encoded as NDJSON; the same
 * bytes through the lenient model parser and the well-posedness report. Crashes, leaks, sanitizer reports
 * and non-finite output are all failures (the last by __builtin_trap).
 *
 * A run stops after RUN_SECONDS of wall time, as the daemon stops one at --max-wall: the regularized
 * solver's step count is bounded by its stiffness, not by the spec's step count (k = 1e69 takes 10^9 steps
 * and minutes), and that is a cost, not a crash. The run's stop hook (as the daemon's) says stop at that
 * time or on its stop_at-th call (from the input's bytes), and yields on every third call: the property of
 * the stop contract is that the dp_run_next during which it said stop returns DP_ECANCEL, every later one too, and
 * that no two polls are more than GAP_SECONDS apart, whatever the laws, tables and `every`. */
#include <math.h>
#include <time.h>
#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_errno.h>

#include "dashpot/encode.h"
#include "dashpot/json.h"
#include "dashpot/wellposedness.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* As every user of the library must (include/dashpot/status.h): GSL's default handler aborts on errors the
 * library checks for itself, such as a band Cholesky that finds a step matrix indefinite. */
int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    gsl_set_error_handler_off();
    return 0;
}

/* Short runs keep the fuzzer fast: 2000 steps is enough to reach events and stick phases. */
#define FUZZ_MAX_STEPS 2000
/* Wall time one run may take (the fuzzer's -timeout is 10 s; a dp_run_next call does at most 10^5 steps). */
#define RUN_SECONDS 2.0

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Far above the documented bound (a few ms of work between polls; tests/test_stop.c holds it to 50 ms) for a
 * sanitized -O1 build on a loaded machine; a run that does not poll at all still trips it. */
#define GAP_SECONDS 1.0

typedef struct fuzz_stop {
    double until, last, worst;
    unsigned calls, stop_at;
    int said_stop;
} fuzz_stop;

static int fuzz_hook(void *ctx)
{
    fuzz_stop *f = ctx;
    double t = seconds();
    if (t - f->last > f->worst)
        f->worst = t - f->last;
    f->last = t;
    if (++f->calls >= f->stop_at || t > f->until)
        return f->said_stop = 1;
    return f->calls % 3 == 0 ? -1 : 0;
}

static void check_sample(const dp_sample *s)
{
    if (!isfinite(s->t) || !isfinite(s->x) || !isfinite(s->v) || !isfinite(s->Fs) || !isfinite(s->Fd)
        || !isfinite(s->Fc))
        __builtin_trap();
}

static void run_spec(const dp_spec *spec, unsigned stop_at)
{
    dp_errors errs;
    dp_errors_init(&errs);
    int s;
    dp_run *run = dp_run_alloc(spec, FUZZ_MAX_STEPS, &errs, &s);
    if (run == NULL)
        return;
    dp_record rec[64];
    dp_buf b = { 0 };
    dp_encoder enc;
    dp_encoder_init(&enc, DP_FORMAT_NDJSON);
    dp_encoder_begin(&enc, &b, "{}");
    size_t n;
    fuzz_stop stop = { .until = seconds() + RUN_SECONDS, .last = seconds(), .stop_at = stop_at };
    dp_run_set_stop(run, fuzz_hook, &stop);
    do {
        s = dp_run_next(run, rec, 64, &n);
        if (stop.said_stop && s != DP_ECANCEL)
            __builtin_trap(); /* told to stop, yet it went on */
        for (size_t i = 0; i < n; i++) {
            if (rec[i].type == DP_RECORD_SAMPLE)
                check_sample(&rec[i].u.sample);
            dp_encoder_record(&enc, &b, &rec[i]);
        }
        b.len = 0;
    } while (s == DP_MORE);
    if (s == DP_ECANCEL && (dp_run_next(run, rec, 64, &n) != DP_ECANCEL || n != 0))
        __builtin_trap(); /* a stopped run stays stopped */
    if (fmax(stop.worst, seconds() - stop.last) > GAP_SECONDS)
        __builtin_trap(); /* the hook was not asked for too long */
    if (s == DP_DONE)
        check_sample(&dp_run_summary(run)->final);
    dp_encoder_clear(&enc);
    dp_buf_free(&b);
    dp_run_free(run);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *text = (const char *)data;
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    if (dp_spec_parse(text, size, FUZZ_MAX_STEPS, &spec, &errs) == DP_OK) {
        dp_buf meta = { 0 };
        dp_spec_meta_json(&spec, &meta);
        dp_buf_free(&meta);
        unsigned sum = 0; /* the poll at which the hook says stop: 1 to 16, from the input */
        for (size_t i = 0; i < size; i++)
            sum += data[i];
        run_spec(&spec, 1 + sum % 16);
    }
    dp_spec_clear(&spec);
    dp_model m = { 0 };
    dp_errors_init(&errs);
    if (dp_model_parse_lenient(text, size, &m, &errs) == DP_OK) {
        dp_wp_report rep;
        dp_wellposedness(&m, &rep);
        dp_buf b = { 0 };
        dp_wellposedness_json(&rep, &b);
        dp_buf_free(&b);
    }
    dp_model_clear(&m);
    return 0;
}
