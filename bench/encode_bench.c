/* bench/encode_bench.c - dp_format_double against printf("%.17g") (the usual round-trip formatting) on four
 * kinds of doubles, and the NDJSON sample encoder as a whole; prints ns per call and the ratios.
 *
 *   uniform     random in [-1, 1): full 17-digit values, the worst case for shortest output
 *   trajectory  t = k dt, and damped oscillation values: what a run's samples look like
 *   steps       k 1e-6 alone: the times of bench/http.sh's stream, up to 7 digits
 *   bits        random bit patterns: every exponent, exponent notation
 *
 * The sample encoder gets blocks of 512 records made beforehand, as the daemon's stream gets them from the
 * solver, so that only dp_encoder_record is timed (cos and sin of the samples' values are not).
 *
 * Usage: encode_bench [N] (default 2^20 values, each formatted several times; best of 5 rounds).
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
        else if (kind == 2)
            v[i] = (double)i * 1e-6;
        else if (memcpy(&v[i], &b, sizeof b), !isfinite(v[i]))
            v[i] = 1.5;
    }
}

/* Best of 5 rounds of formatting every value; ns per value. */
static double time_format(const double *v, size_t n, int use_printf, size_t *bytes)
{
    double best = INFINITY;
    char out[64];
    for (int round = 0; round < 5; round++) {
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

#define BLOCK 512 /* records per solver block in the daemon (src/http/simulate.c) */

/* A block of the samples of an oscillation from sample `first` on, as a slipping Coulomb oscillator's:
 * t = k 1e-6, x and v changing in every digit, F_s = x (k = 1), F_d = F_c = -0.3. */
static void make_block(dp_record *r, size_t first)
{
    for (size_t i = 0; i < BLOCK; i++) {
        double t = (double)(first + i) * 1e-6;
        r[i] = (dp_record){ .type = DP_RECORD_SAMPLE,
                            .u.sample = { t, cos(t), -sin(t), cos(t), -0.3, -0.3, DP_PHASE_SLIP } };
    }
}

/* ns per sample of the NDJSON encoder (6 numbers and the framing), best of 5; only the encoding is timed. */
static double time_samples(size_t n)
{
    static dp_record r[BLOCK];
    dp_buf b = { 0 };
    double best = INFINITY;
    for (int round = 0; round < 5; round++) {
        dp_encoder e;
        dp_encoder_init(&e, DP_FORMAT_NDJSON);
        double dt = 0;
        for (size_t first = 0; first < n; first += BLOCK) {
            make_block(r, first);
            b.len = 0;
            double t0 = now();
            for (size_t i = 0; i < BLOCK; i++)
                if (dp_encoder_record(&e, &b, &r[i]) != DP_OK)
                    exit(1);
            dt += now() - t0;
        }
        best = dt < best ? dt : best;
        dp_encoder_clear(&e);
    }
    dp_buf_free(&b);
    return best / (double)(n / BLOCK * BLOCK) * 1e9;
}

int main(int argc, char **argv)
{
    size_t n = argc > 1 ? strtoul(argv[1], NULL, 10) : (1u << 20);
    double *v = malloc(n * sizeof *v);
    if (v == NULL || n == 0)
        return 1;
    static const char *const kinds[] = { "uniform", "trajectory", "steps", "bits" };
    printf("dp_format_double vs snprintf(\"%%.17g\"), %zu values each, best of 5\n", n);
    printf("  %-11s %10s %10s %8s %16s\n", "values", "dp ns", "%.17g ns", "speedup", "bytes dp/%.17g");
    for (int k = 0; k < 4; k++) {
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
