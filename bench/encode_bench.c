/* bench/encode_bench.c - dp_format_double against printf("%.17g") (the usual round-trip formatting) on three
 * kinds of doubles, and the NDJSON sample encoder as a whole; prints ns per call and the ratios.
 *
 *   uniform     random in [-1, 1): full 17-digit values, the worst case for shortest output
 *   trajectory  t = k dt, and damped oscillation values: what a run's samples look like
 *   bits        random bit patterns: every exponent, exponent notation
 *
 * Usage: encode_bench [N] (default 2^20 values, each formatted several times; best of 3 rounds).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dashpot/encode.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint64_t rng = 88172645463325252ULL;
static uint64_t next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

static void fill(double *v, size_t n, int kind)
{
    for (size_t i = 0; i < n; i++) {
        uint64_t b = next();
        double t = (double)(i / 6) * 1e-3;
        if (kind == 0)
            v[i] = (double)(b >> 11) / 9007199254740992.0 * 2 - 1;
        else if (kind == 1)
            v[i] = i % 6 == 0 ? t : i % 2 ? exp(-0.1 * t) * cos(t + (double)(i % 6)) : -0.3;
        else if (memcpy(&v[i], &b, sizeof b), !isfinite(v[i]))
            v[i] = 1.5;
    }
}

/* Best of 3 rounds of formatting every value; ns per value. */
static double time_format(const double *v, size_t n, int use_printf, size_t *bytes)
{
    double best = INFINITY;
    char out[64];
    for (int round = 0; round < 3; round++) {
        size_t total = 0;
        double t0 = now();
        for (size_t i = 0; i < n; i++)
            total += use_printf ? (size_t)snprintf(out, sizeof out, "%.17g", v[i]) : dp_format_double(out, v[i]);
        double dt = now() - t0;
        best = dt < best ? dt : best;
        *bytes = total;
    }
    return best / (double)n * 1e9;
}

/* ns per sample of the NDJSON encoder (6 numbers and the framing), best of 3. */
static double time_samples(size_t n)
{
    dp_record r = { .type = DP_RECORD_SAMPLE };
    dp_buf b = { 0 };
    double best = INFINITY;
    for (int round = 0; round < 3; round++) {
        dp_encoder e;
        dp_encoder_init(&e, DP_FORMAT_NDJSON);
        double t0 = now();
        for (size_t i = 0; i < n; i++) {
            double t = (double)i * 1e-6;
            r.u.sample = (dp_sample){ t, cos(t), -sin(t), cos(t), -0.3, -0.3, DP_PHASE_SLIP };
            if (dp_encoder_record(&e, &b, &r) != DP_OK)
                exit(1);
            if (b.len > (1u << 20))
                b.len = 0;
        }
        double dt = now() - t0;
        best = dt < best ? dt : best;
        dp_encoder_clear(&e);
    }
    dp_buf_free(&b);
    return best / (double)n * 1e9;
}

int main(int argc, char **argv)
{
    size_t n = argc > 1 ? strtoul(argv[1], NULL, 10) : (1u << 20);
    double *v = malloc(n * sizeof *v);
    if (v == NULL || n == 0)
        return 1;
    static const char *const kinds[] = { "uniform", "trajectory", "bits" };
    printf("dp_format_double vs snprintf(\"%%.17g\"), %zu values each, best of 3\n", n);
    printf("  %-11s %10s %10s %8s %16s\n", "values", "dp ns", "%.17g ns", "speedup", "bytes dp/%.17g");
    for (int k = 0; k < 3; k++) {
        size_t bd, bp;
        fill(v, n, k);
        double d = time_format(v, n, 0, &bd), p = time_format(v, n, 1, &bp);
        printf("  %-11s %10.1f %10.1f %7.1fx %16.2f\n", kinds[k], d, p, p / d, (double)bd / (double)bp);
    }
    double s = time_samples(n);
    printf("  NDJSON sample encoder (6 numbers + framing, no solver): %.1f ns/sample = %.2f M samples/s\n", s,
           1e3 / s);
    free(v);
    return 0;
}
