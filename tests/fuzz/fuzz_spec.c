/* tests/fuzz/fuzz_spec.c - libFuzzer target: any bytes through the spec parser and validator, and when they
 * make a valid spec, a short solver run whose every record must be finite, encoded as NDJSON; the same
 * bytes through the lenient model parser and the well-posedness report. Crashes, leaks, sanitizer reports
 * and non-finite output are all failures (the last by __builtin_trap).
 *
 * A run stops after RUN_SECONDS of wall time, as the daemon stops one at --max-wall: the regularized
 * solver's step count is bounded by its stiffness, not by the spec's step count (k = 1e69 takes 10^9 steps
 * and minutes), and that is a cost, not a crash. */
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

static void check_sample(const dp_sample *s)
{
    if (!isfinite(s->t) || !isfinite(s->x) || !isfinite(s->v) || !isfinite(s->Fs) || !isfinite(s->Fd)
        || !isfinite(s->Fc))
        __builtin_trap();
}

static void run_spec(const dp_spec *spec)
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
    double until = seconds() + RUN_SECONDS;
    do {
        s = dp_run_next(run, rec, 64, &n);
        for (size_t i = 0; i < n; i++) {
            if (rec[i].type == DP_RECORD_SAMPLE)
                check_sample(&rec[i].u.sample);
            dp_encoder_record(&enc, &b, &rec[i]);
        }
        b.len = 0;
    } while (s == DP_MORE && seconds() < until);
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
        run_spec(&spec);
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
