/* bench/lcp_bench.c - LCP solves per second: dashpot's Lemke (src/core/lcp/lemke.c) against Siconos numerics'
 * lexicographic Lemke (lcp_lexicolemke, SICONOS_LCP_LEMKE) on the same random problems of sizes 2, 10 and
 * 100 (M = B Bᵀ + I/m + a skew part: positive definite symmetric part, so each has one solution and both
 * must find it), printed side by side with the ratio. Run by bench/lcp.sh.
 *
 * Each problem is solved once by both and the answers compared (max |z_dashpot - z_siconos| relative to
 * |z|, and dashpot's residual); then each solver runs the whole set repeatedly, in ROUNDS alternating
 * rounds of 0.1 s, and its best round is its rate. Siconos
 * is given its problem once (its dense column-major copy made outside the timing, as dashpot's workspace
 * is). Exit 1 when the answers disagree beyond 1e-9 relative: a speed figure for a wrong answer is no figure.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_rng.h>

#include <LCP_Solvers.h>
#include <LinearComplementarityProblem.h>
#include <NumericsMatrix.h>
#include <SolverOptions.h>
#include <lcp_cst.h>

#include "dashpot/lcp.h"
#include "dashpot/status.h"

#define NPROB 16
#define ROUNDS 7

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void random_problem(gsl_rng *rng, size_t m, double *M, double *q)
{
    memset(M, 0, m * m * sizeof *M);
    for (size_t c = 0; c < m; c++) {
        double b[DP_LCP_MAX];
        for (size_t i = 0; i < m; i++)
            b[i] = (2 * gsl_rng_uniform(rng) - 1) / sqrt((double)m);
        for (size_t i = 0; i < m; i++)
            for (size_t j = 0; j < m; j++)
                M[i * m + j] += b[i] * b[j];
    }
    for (size_t i = 0; i < m; i++) {
        M[i * m + i] += 1.0 / (double)m;
        for (size_t j = 0; j < i; j++) {
            double s = 0.5 * (2 * gsl_rng_uniform(rng) - 1);
            M[i * m + j] += s, M[j * m + i] -= s;
        }
    }
    for (size_t i = 0; i < m; i++)
        q[i] = 2 * gsl_rng_uniform(rng) - 1;
}

typedef struct bench_set {
    size_t m;
    double *M[NPROB], *q[NPROB];
    LinearComplementarityProblem *sic[NPROB];
} bench_set;

static LinearComplementarityProblem *siconos_problem(size_t m, const double *M, const double *q)
{
    LinearComplementarityProblem *p = newLCP();
    double *cm = malloc(m * m * sizeof *cm), *qq = malloc(m * sizeof *qq);
    for (size_t i = 0; i < m; i++)
        for (size_t j = 0; j < m; j++)
            cm[j * m + i] = M[i * m + j]; /* column-major */
    memcpy(qq, q, m * sizeof *qq);
    p->size = (int)m;
    p->M = NM_create_from_data(NM_DENSE, (int)m, (int)m, cm);
    p->q = qq;
    return p;
}

static int run_dashpot(const bench_set *s, dp_lcp *ws, gsl_vector *z, gsl_vector *w, size_t k, double *res)
{
    gsl_matrix_view M = gsl_matrix_view_array(s->M[k], s->m, s->m);
    gsl_vector_view q = gsl_vector_view_array(s->q[k], s->m);
    dp_lcp_result r;
    int st = dp_lcp_lemke(ws, &M.matrix, &q.vector, z, w, &r);
    if (res)
        *res = r.residual;
    return st == DP_OK && r.outcome == DP_LCP_SOLVED;
}

static int run_siconos(const bench_set *s, SolverOptions *opt, double *z, double *w, size_t k)
{
    int info = 0;
    lcp_lexicolemke(s->sic[k], z, w, &info, opt);
    return info == 0;
}

static int bench_size(gsl_rng *rng, size_t m)
{
    bench_set s = { .m = m };
    for (size_t k = 0; k < NPROB; k++) {
        s.M[k] = malloc(m * m * sizeof(double));
        s.q[k] = malloc(m * sizeof(double));
        random_problem(rng, m, s.M[k], s.q[k]);
        s.sic[k] = siconos_problem(m, s.M[k], s.q[k]);
    }
    dp_lcp *ws = dp_lcp_alloc(m);
    gsl_vector *z = gsl_vector_alloc(m), *w = gsl_vector_alloc(m);
    double *zs = malloc(m * sizeof *zs), *wsic = malloc(m * sizeof *wsic);
    SolverOptions *opt = solver_options_create(SICONOS_LCP_LEMKE);
    double maxdiff = 0, maxres = 0;
    int ok = 1;
    for (size_t k = 0; k < NPROB; k++) {
        double res;
        ok &= run_dashpot(&s, ws, z, w, k, &res) && run_siconos(&s, opt, zs, wsic, k);
        double zn = 1;
        for (size_t i = 0; i < m; i++)
            zn = fmax(zn, fabs(zs[i]));
        for (size_t i = 0; i < m; i++)
            maxdiff = fmax(maxdiff, fabs(gsl_vector_get(z, i) - zs[i]) / zn);
        maxres = fmax(maxres, res);
    }
    /* Rounds of 0.1 s each, the two solvers alternating, the best round of each kept: on a machine shared
     * with other work a slow round is someone else's load, and alternating exposes both to the same. */
    double rate[2] = { 0, 0 };
    for (int round = 0; round < ROUNDS; round++) {
        for (int who = 0; who < 2; who++) {
            size_t solves = 0;
            double t0 = now(), t;
            do {
                for (size_t k = 0; k < NPROB; k++)
                    who == 0 ? run_dashpot(&s, ws, z, w, k, NULL) : run_siconos(&s, opt, zs, wsic, k);
                solves += NPROB;
            } while ((t = now() - t0) < 0.1);
            rate[who] = fmax(rate[who], (double)solves / t);
        }
    }
    int agree = ok && maxdiff <= 1e-9;
    printf("%5zu %14.4g %14.4g %8.2f %12.2g %12.2g  %s\n", m, rate[0], rate[1], rate[0] / rate[1], maxdiff, maxres,
           agree ? "ok" : "FAIL");
    solver_options_delete(opt);
    for (size_t k = 0; k < NPROB; k++) {
        freeLinearComplementarityProblem(s.sic[k]);
        free(s.M[k]);
        free(s.q[k]);
    }
    dp_lcp_free(ws);
    gsl_vector_free(z);
    gsl_vector_free(w);
    free(zs);
    free(wsic);
    return agree;
}

int main(void)
{
    gsl_set_error_handler_off();
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    printf("LCP solves/s: dashpot Lemke vs Siconos lcp_lexicolemke, %d random problems per size "
           "(PD symmetric part)\n", NPROB);
    printf("%5s %14s %14s %8s %12s %12s\n", "m", "dashpot/s", "siconos/s", "ratio", "max|dz|", "residual");
    int ok = 1;
    size_t sizes[] = { 2, 10, 100 };
    for (size_t i = 0; i < 3; i++)
        ok &= bench_size(rng, sizes[i]);
    gsl_rng_free(rng);
    return ok ? 0 : 1;
}
