/* bench/modes_bench.c - natural modes of chains of 10, 100 and 1000 masses through dp_modes_solve (the
 * tridiagonal route, tridiag.c), timed per solve, and the same chains through the dense GSL route (a coupling of
 * 1e-300 in M forces it) for reference. Writes each chain's M and K diagonals for the peer
 * (bench/modes_peer.py, scipy.linalg.eigh) and "key value" lines: seconds per solve and the eigenvalues'
 * checksum. Usage: modes_bench OUTDIR */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>

#include "dashpot/modes.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* A fixed-free chain: masses 1 + 0.5 sin(i), springs 100 (1 + 0.3 cos(i)), ground spring at node 0. */
static void chain(size_t n, double *M, double *K)
{
    memset(M, 0, n * n * sizeof *M);
    memset(K, 0, n * n * sizeof *K);
    for (size_t i = 0; i < n; i++) {
        M[i * n + i] = 1 + 0.5 * sin((double)i);
        double k = 100 * (1 + 0.3 * cos((double)i));
        K[i * n + i] += k;
        if (i > 0) {
            K[(i - 1) * n + i - 1] += k;
            K[i * n + i - 1] = K[(i - 1) * n + i] = -k;
        }
    }
}

static double time_solve(size_t n, const double *M, const double *K, double *sum, int *route)
{
    int reps = 0;
    double t0 = now(), t;
    do {
        dp_modes md;
        dp_errors errs;
        dp_errors_init(&errs);
        if (dp_modes_solve(n, M, K, NULL, "", "", "", &md, &errs) != DP_OK) {
            fprintf(stderr, "modes_bench: solve failed: %s\n", errs.n ? errs.item[0].message : "");
            exit(1);
        }
        *sum = 0;
        for (size_t k = 0; k < n; k++)
            *sum += sqrt(md.lambda[k]);
        *route = md.tridiagonal;
        dp_modes_free(&md);
        reps++;
        t = now() - t0;
    } while (t < 0.3 && reps < 100000);
    return t / reps;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc != 2) {
        fprintf(stderr, "usage: modes_bench OUTDIR\n");
        return 2;
    }
    const size_t sizes[] = { 10, 100, 1000 };
    for (int s = 0; s < 3; s++) {
        size_t n = sizes[s];
        double *M = malloc(n * n * sizeof *M), *K = malloc(n * n * sizeof *K), sum;
        int route;
        chain(n, M, K);
        char path[4096];
        snprintf(path, sizeof path, "%s/chain%zu.txt", argv[1], n);
        FILE *f = fopen(path, "w");
        for (size_t i = 0; f && i < n; i++)
            fprintf(f, "%.17g %.17g %.17g\n", M[i * n + i], K[i * n + i], i + 1 < n ? K[i * n + i + 1] : 0.0);
        if (f)
            fclose(f);
        printf("n%zu_seconds %.9g\n", n, time_solve(n, M, K, &sum, &route));
        printf("n%zu_sum_omega %.17g\n", n, sum);
        printf("n%zu_route %s\n", n, route ? "tridiagonal" : "dense");
        M[1] = M[n] = 1e-300; /* not diagonal any more: the dense route, same eigenvalues */
        printf("n%zu_dense_seconds %.9g\n", n, time_solve(n, M, K, &sum, &route));
        printf("n%zu_dense_sum_omega %.17g\n", n, sum);
        free(M);
        free(K);
    }
    return 0;
}
