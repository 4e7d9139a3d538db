/* bench/stability_bench.c - how fast libdashpot decides stability: verdicts per second for degree-4 laws
 * (thesis model 1.4 shape, p = m l2 z^4 + m l1 z^3 + (m + u2) z^2 + u1 z + u0) and one 1000 x 1000 map.
 *
 * Usage: stability_bench N LAWS.bin MAP_STEPS. The N random laws are written to LAWS.bin (7 doubles each:
 * m, 1, l1, l2, u0, u1, u2) so that the numpy peer (stability_peer.py) decides exactly the same laws; the
 * counts of stable verdicts are printed by both as a cross-check. Output: "key value" lines.
 */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_rng.h>

#include "dashpot/stability.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Coefficients around the (1.14) boundary so that both verdicts are common. */
static void random_laws(double *laws, long n)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 4);
    for (long i = 0; i < n; i++) {
        double *l = laws + 7 * i;
        l[0] = 0.5 + gsl_rng_uniform(r);
        l[1] = 1.0;
        l[2] = 0.2 + 2 * gsl_rng_uniform(r);
        l[3] = 0.05 + gsl_rng_uniform(r);
        l[4] = 0.1 + 2 * gsl_rng_uniform(r);
        l[5] = 0.1 + 2 * gsl_rng_uniform(r);
        l[6] = gsl_rng_uniform(r);
    }
    gsl_rng_free(r);
}

static dp_law law_at(const double *l)
{
    dp_law law = { .mass = l[0], .nlambda = 3, .nmu = 3 };
    for (int k = 0; k < 3; k++) {
        law.lambda[k] = l[1 + k];
        law.mu[k] = l[4 + k];
    }
    return law;
}

/* Decides every law; with_abscissa forces the roots too. Returns the stable count, -1 on error. */
static long decide(dp_stability_ws *w, const double *laws, long n, int with_abscissa, double *seconds)
{
    long stable = 0;
    double t0 = now();
    for (long i = 0; i < n; i++) {
        dp_law law = law_at(laws + 7 * i);
        dp_verdict v;
        double ab;
        int has;
        if (dp_stability_verdict(w, &law, &v, with_abscissa ? &ab : NULL, &has) != DP_OK)
            return -1;
        stable += v == DP_VERDICT_STABLE;
    }
    *seconds = now() - t0;
    return stable;
}

static int map_bench(dp_stability_ws *w, int steps)
{
    dp_law law = law_at((const double[]){ 1, 1, 0.9, 0.25, 1, 1.2, 0.6 });
    dp_map_axis x = { DP_PARAM_MU, 0, 0.01, 3, steps }, y = { DP_PARAM_MU, 2, -0.5, 2, steps };
    dp_map map;
    double t0 = now();
    if (dp_stability_map(w, &law, &x, &y, &map) != DP_OK)
        return -1;
    double t = now() - t0;
    long stable = 0;
    for (size_t k = 0; k < map.nx * map.ny; k++)
        stable += map.verdict[k] == DP_VERDICT_STABLE;
    printf("map_points %zu\nmap_seconds %.4f\nmap_stable %ld\n", map.nx * map.ny, t, stable);
    dp_map_clear(&map);
    return 0;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc != 4) {
        fprintf(stderr, "usage: stability_bench N LAWS.bin MAP_STEPS\n");
        return 2;
    }
    long n = atol(argv[1]);
    int steps = atoi(argv[3]);
    double *laws = n > 0 ? malloc((size_t)n * 7 * sizeof *laws) : NULL;
    dp_stability_ws *w = dp_stability_ws_alloc();
    FILE *f = fopen(argv[2], "wb");
    if (laws == NULL || w == NULL || f == NULL || steps < 2)
        return 1;
    random_laws(laws, n);
    int ok = fwrite(laws, sizeof *laws, (size_t)n * 7, f) == (size_t)n * 7;
    ok = fclose(f) == 0 && ok;
    double t_fast, t_full;
    long s_fast = decide(w, laws, n, 0, &t_fast), s_full = decide(w, laws, n, 1, &t_full);
    if (!ok || s_fast < 0 || s_full < 0 || map_bench(w, steps) != 0)
        return 1;
    printf("laws %ld\nverdict_seconds %.4f\nverdict_stable %ld\nroots_seconds %.4f\nroots_stable %ld\n", n, t_fast,
           s_fast, t_full, s_full);
    dp_stability_ws_free(w);
    free(laws);
    return 0;
}
