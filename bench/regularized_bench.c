/* bench/regularized_bench.c - cost of the regularized solver (PCn) as n grows, per GSL stepper.
 *
 * The problem (the one bench/regularized_peer.py gives SciPy): m = k = phi0 = 1, Coulomb, x(0) = 4.5,
 * x'(0) = 0, t in [0, 30], samples every 0.1 (301), rtol = atol = 1e-10: the regularized ODE
 * x'' = -x - clamp(n x', -1, 1), stiff like n. One line per (stepper, n):
 *     stepper n steps rejected fevals jevals seconds x_end
 * seconds is the best of several repetitions of the whole run (parse excluded, allocation included).
 * Usage: regularized_bench [N_MAX] (default 1e5).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>

#include "dashpot/json.h"
#include "dashpot/run.h"

#define BLOCK 512

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One complete run, records consumed and dropped; returns the final status. */
static int run_once(const dp_spec *spec, dp_summary *sum)
{
    static dp_record buf[BLOCK];
    dp_errors e;
    int s;
    dp_errors_init(&e);
    dp_run *r = dp_run_alloc(spec, 0, &e, &s);
    if (r == NULL)
        return s;
    size_t n;
    while ((s = dp_run_next(r, buf, BLOCK, &n)) == DP_MORE)
        ;
    *sum = *dp_run_summary(r);
    dp_run_free(r);
    return s;
}

static int bench(const char *stepper, double n)
{
    char json[512];
    snprintf(json, sizeof json,
             "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\","
             "\"phi0\":1}},\"initial\":{\"x\":4.5,\"v\":0},\"solver\":{\"kind\":\"regularized\",\"n\":%.17g,"
             "\"t_end\":30,\"dt\":0.1,\"rtol\":1e-10,\"atol\":1e-10,\"stepper\":\"%s\"}}", n, stepper);
    dp_spec spec;
    dp_errors e;
    dp_spec_init(&spec);
    dp_errors_init(&e);
    int s = dp_spec_parse(json, strlen(json), 0, &spec, &e);
    dp_summary sum = { 0 };
    double best = 1e300, spent = 0;
    /* Repeat until 0.3 s are spent (at least twice, at most 200 times): the best time is the cost. */
    for (int rep = 0; s == DP_OK && rep < 200 && (rep < 2 || spent < 0.3); rep++) {
        double t0 = now();
        s = run_once(&spec, &sum);
        double t = now() - t0;
        spent += t;
        best = t < best ? t : best;
        s = s == DP_DONE ? DP_OK : s;
    }
    dp_spec_clear(&spec);
    if (s != DP_OK) {
        fprintf(stderr, "regularized_bench: %s n=%g: %s\n", stepper, n, dp_strerror(s));
        return 1;
    }
    printf("%s %g %llu %llu %llu %llu %.6e %.12f\n", stepper, n, sum.steps, sum.rejected, sum.fevals,
           sum.iterations, best, sum.final.x);
    return 0;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    double nmax = argc > 1 ? strtod(argv[1], NULL) : 1e5;
    const char *steppers[] = { "msbdf", "rk4imp", "bsimp", "rkf45", "rk8pd" };
    int fail = 0;
    for (size_t i = 0; i < sizeof steppers / sizeof *steppers; i++)
        for (double n = 10; n <= nmax * 1.0001; n *= 10)
            fail |= bench(steppers[i], n);
    return fail;
}
