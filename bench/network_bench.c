/* bench/network_bench.c - dashpot's network stepping measured for bench/network.sh: agreement with
 * Siconos on chains, time per step and per block-step, memory, and a one-node network against the one-mass
 * model.
 *
 * The chain (the same key=value words as bench/siconos_chain_peer.cpp, whose heterogeneity formulas are
 * repeated here and must stay identical):
 *     m x_i'' + kg x_i + kc (2 x_i - x_{i-1} - x_{i+1}) + Fc_i + (pair friction) = F0 [i = n-1]
 *     Fc_i in phi0_i Sgn(x_i' - vb),   phi0_i = phi0 (1 + het sin(2.3 i))      (element i: ["ground", i])
 *     element n + i (i < n-1): ["i", i+1], spring kc, and Coulomb phic on no belt when phic > 0
 *     x_i(0) = xamp cos(1.3 i),   v_i(0) = 0,   written as the network document a user would send.
 * A Burridge-Knopoff chain is this chain in the plate's frame: kg the leaf springs, the belt at -V.
 *
 * Usage: network_bench mode=MODE key=value ...   keys: n m kg kc phi0 het phic vb F0 xamp dt steps theta reps
 *                                                  locate (1: "events":"locate", else "none")
 *   mode=compare sic=FILE  "events":"none" step by step against Siconos' records (per step t, x[n], v[n], Fc
 *                          per Coulomb element, native doubles): max |dx|, |dv|, |dF|, the rounding verdict.
 *   mode=time              output off ("samples": false): ns per step and per block-step (best of reps), the
 *                          phase changes per step (the summary's `events`), peak RSS.
 *   mode=doc               prints the case's document with every sample and event on, for `dashpot simulate`:
 *                          a change meant to keep the answers is checked on it bit for bit.
 *   mode=single            the same one-mass problem (n is ignored: m kg phi0 vb xamp) as the one-mass
 *                          model and as a one-node network: ns per step of each, the ratio, and whether both
 *                          end in the same state (they must, to the bit).
 * Output: "key value" lines.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "dashpot/json.h"
#include "dashpot/run.h"
#include "dashpot/status.h"

#define BLOCK 4096 /* records per dp_run_next, as the CLI's stream */
#define EPS 2.220446049250313e-16

typedef struct params {
    double n, m, kg, kc, phi0, het, phic, vb, F0, xamp, dt, theta, locate;
    long long steps, reps;
    const char *mode, *sic;
} params;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static long maxrss_kb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

static int parse_args(int argc, char **argv, params *p)
{
    *p = (params){ .n = 10, .m = 1, .kg = 1, .kc = 1, .phi0 = 0.5, .xamp = 1, .dt = 1e-3, .theta = 0.5,
                   .steps = 1000, .reps = 1, .mode = "time" };
    struct { const char *key; double *d; } nums[] = {
        { "n", &p->n }, { "m", &p->m }, { "kg", &p->kg }, { "kc", &p->kc }, { "phi0", &p->phi0 },
        { "het", &p->het }, { "phic", &p->phic }, { "vb", &p->vb }, { "F0", &p->F0 }, { "xamp", &p->xamp },
        { "dt", &p->dt }, { "theta", &p->theta }, { "locate", &p->locate },
    };
    for (int i = 1; i < argc; i++) {
        char *eq = strchr(argv[i], '=');
        size_t k = eq ? (size_t)(eq - argv[i]) : 0;
        int known = 0;
        for (size_t j = 0; eq && j < sizeof nums / sizeof nums[0]; j++)
            if (strlen(nums[j].key) == k && strncmp(argv[i], nums[j].key, k) == 0)
                *nums[j].d = strtod(eq + 1, NULL), known = 1;
        if (eq && k == 5 && strncmp(argv[i], "steps", 5) == 0)
            p->steps = strtoll(eq + 1, NULL, 10), known = 1;
        if (eq && k == 4 && strncmp(argv[i], "reps", 4) == 0)
            p->reps = strtoll(eq + 1, NULL, 10), known = 1;
        if (eq && k == 4 && strncmp(argv[i], "mode", 4) == 0)
            p->mode = eq + 1, known = 1;
        if (eq && k == 3 && strncmp(argv[i], "sic", 3) == 0)
            p->sic = eq + 1, known = 1;
        if (!known) {
            fprintf(stderr, "network_bench: bad argument '%s'\n", argv[i]);
            return -1;
        }
    }
    if (p->steps < 1 || p->reps < 1 || p->n < 1 || p->n > 1e6) {
        fprintf(stderr, "network_bench: n, steps and reps must be >= 1\n");
        return -1;
    }
    return 0;
}

/* ---- the documents ---------------------------------------------------------------------------------- */

/* A growing text buffer; `bad` remembers an allocation failure so that the callers check once. */
typedef struct text {
    char *s;
    size_t len, cap;
    int bad;
} text;

static void add(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static void add(text *t, const char *fmt, ...)
{
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int k = t->bad ? 0 : vsnprintf(t->s ? t->s + t->len : NULL, t->s ? t->cap - t->len : 0, fmt, ap);
        va_end(ap);
        if (t->bad || k < 0) {
            t->bad = 1;
            return;
        }
        if (t->s && (size_t)k < t->cap - t->len) {
            t->len += (size_t)k;
            return;
        }
        size_t cap = 2 * (t->cap + (size_t)k + 1);
        char *s = realloc(t->s, cap);
        if (s == NULL) {
            t->bad = 1;
            return;
        }
        t->s = s, t->cap = cap;
    }
}

/* samples: 0 none, 1 every step's sample, 2 those and the events. */
static void solver_and_output(text *t, const params *p, int samples)
{
    add(t, "\"solver\":{\"kind\":\"stick-slip\",\"dt\":%.17g,\"t_end\":%.17g,\"theta\":%.17g,\"events\":\"%s\"},"
           "\"output\":{\"every\":1,\"samples\":%s,\"events\":%s}}",
        p->dt, (double)p->steps * p->dt, p->theta, p->locate == 1 ? "locate" : "none", samples ? "true" : "false",
        samples > 1 ? "true" : "false");
}

/* The chain as a network document (mode=single: one node, one element). */
static void chain_text(text *t, const params *p, int samples)
{
    long n = (long)p->n;
    add(t, "{\"model\":{\"masses\":[");
    for (long i = 0; i < n; i++)
        add(t, "%s%.17g", i ? "," : "", p->m);
    add(t, "],\"elements\":[");
    for (long i = 0; i < n; i++)
        add(t, "%s{\"between\":[\"ground\",%ld],\"spring\":{\"law\":\"linear\",\"k\":%.17g},"
               "\"damper\":{\"law\":\"coulomb\",\"phi0\":%.17g,\"belt_velocity\":%.17g}}",
            i ? "," : "", i, p->kg, p->phi0 * (1 + p->het * sin(2.3 * (double)i)), p->vb);
    for (long i = 0; i + 1 < n; i++) {
        add(t, ",{\"between\":[%ld,%ld],\"spring\":{\"law\":\"linear\",\"k\":%.17g}", i, i + 1, p->kc);
        if (p->phic > 0)
            add(t, ",\"damper\":{\"law\":\"coulomb\",\"phi0\":%.17g,\"belt_velocity\":0}", p->phic);
        add(t, "}");
    }
    add(t, "]");
    if (p->F0 != 0)
        add(t, ",\"forcing\":[{\"node\":%ld,\"kind\":\"constant\",\"value\":%.17g}]", n - 1, p->F0);
    add(t, "},\"initial\":{\"x\":[");
    for (long i = 0; i < n; i++)
        add(t, "%s%.17g", i ? "," : "", p->xamp * cos(1.3 * (double)i));
    add(t, "],\"v\":[");
    for (long i = 0; i < n; i++)
        add(t, "%s0", i ? "," : "");
    add(t, "]},");
    solver_and_output(t, p, samples);
}

/* mode=single's one-mass document: m x'' + kg x + Fc = 0, Fc in phi0 Sgn(x' - vb), x(0) = xamp. */
static void one_mass_text(text *t, const params *p)
{
    add(t, "{\"model\":{\"mass\":%.17g,\"spring\":{\"law\":\"linear\",\"k\":%.17g},"
           "\"damper\":{\"law\":\"coulomb\",\"phi0\":%.17g,\"belt_velocity\":%.17g}},"
           "\"initial\":{\"x\":%.17g,\"v\":0},", p->m, p->kg, p->phi0, p->vb, p->xamp);
    solver_and_output(t, p, 0);
}

static dp_run *start_text(const text *t)
{
    if (t->bad)
        return NULL;
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(t->s, t->len, 0, &spec, &errs);
    dp_run *run = s == DP_OK ? dp_run_alloc(&spec, 0, &errs, &s) : NULL;
    if (run == NULL)
        fprintf(stderr, "network_bench: spec rejected (%s): %s %s\n", dp_strerror(s),
                errs.n ? errs.item[0].pointer : "", errs.n ? errs.item[0].message : "");
    dp_spec_clear(&spec);
    return run;
}

/* Runs to the end, output off; returns the loop's seconds (setup in *setup), or a negative number. */
static double run_through(dp_run *run, dp_record *buf)
{
    int s;
    size_t got;
    double t0 = now();
    do
        s = dp_run_next(run, buf, BLOCK, &got);
    while (s == DP_MORE);
    double t = now() - t0;
    if (s != DP_DONE) {
        fprintf(stderr, "network_bench: run failed: %s\n", dp_run_error(run));
        return -1;
    }
    return t;
}

/* ---- mode=compare ---------------------------------------------------------------------------------- */

typedef struct diff {
    double dx, dv, dr;  /* max |difference| over the run: positions, velocities, friction resultants */
    double ax, av, ar;  /* max |value| (dashpot) */
    double split;       /* max |difference| of single element forces (not unique on a stuck cycle) */
    double over;        /* max excess of |F_e| over its bound phi_e, either code */
    long long n;        /* steps compared */
} diff;

/* The Coulomb elements' force on each node, r = -sum_e b_e F_e (into r[0..n)). Element order: the ground
 * elements 0..n-1, then the neighbours [i, i+1] n..2n-2 when nf > n. */
static void resultants(const double *F, size_t n, size_t nf, double *r)
{
    for (size_t i = 0; i < n; i++)
        r[i] = -F[i];
    for (size_t i = 0; i + 1 < n && nf > n; i++)
        r[i + 1] -= F[n + i], r[i] += F[n + i];
}

/* The bound of Coulomb element e, as chain_text writes it. */
static double bound(const params *p, size_t e)
{
    size_t n = (size_t)p->n;
    return e < n ? p->phi0 * (1 + p->het * sin(2.3 * (double)e)) : p->phic;
}

/* Compares one dashpot row with Siconos' next record. The motion is unique, so x and v are compared node by
 * node. The friction forces are unique only through their resultant on each node (W (v_free - v+) / h):
 * where stuck elements close a cycle (ground-i-(i+1)-ground with friction on the pair) the split of force
 * around it is not, and the two codes may report different, equally valid splits. So the resultants are
 * compared, each element force is checked against its bound, and the element-wise difference is reported
 * as `split`. Returns -1 when the record is missing or at another time. */
static int compare_row(const params *p, const dp_columns *c, const dp_row *row, size_t nf, FILE *sic, double *rec,
                       double *work, diff *d)
{
    size_t n = (size_t)p->n, len = 1 + 2 * n + nf;
    const double *x = row->val, *v = row->val + c->nodes, *Fd = row->val + 2 * c->nodes + c->elements;
    if (fread(rec, sizeof *rec, len, sic) != len || fabs(rec[0] - row->t) > 1e-9 * (1 + row->t)) {
        fprintf(stderr, "network_bench: Siconos' record %lld missing or at t = %.17g, not %.17g\n", d->n, rec[0],
                row->t);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        d->dx = fmax(d->dx, fabs(x[i] - rec[1 + i]));
        d->dv = fmax(d->dv, fabs(v[i] - rec[1 + n + i]));
        d->ax = fmax(d->ax, fabs(x[i]));
        d->av = fmax(d->av, fabs(v[i]));
    }
    const double *Fs = rec + 1 + 2 * n;
    for (size_t e = 0; e < nf; e++) {
        double phi = bound(p, e);
        d->split = fmax(d->split, fabs(Fd[e] - Fs[e]));
        d->over = fmax(d->over, fmax(fabs(Fd[e]) - phi, fabs(Fs[e]) - phi));
    }
    resultants(Fd, n, nf, work);
    resultants(Fs, n, nf, work + n);
    for (size_t i = 0; i < n; i++) {
        d->dr = fmax(d->dr, fabs(work[i] - work[n + i]));
        d->ar = fmax(d->ar, fabs(work[i]));
    }
    d->n++;
    return 0;
}

/* Agreement to rounding. Both codes compute the same Moreau-Jean step on the same numbers in a different
 * order (dashpot: band Cholesky of W and an active-set solve; Siconos: a dense LU of I - h theta A of size 2n
 * and Lemke's method on the 2n x 2n LCP of the relay), so every step differs by rounding, and the chain is
 * neutrally stable between stick phases, so those differences add up over the N steps instead of decaying.
 * A dense solve of size 2n is backward stable with a constant growing like n (Higham, Thm 9.4), so the bound
 * is N n eps relative (N = 2000, n = 10: 4.4e-12), still 10^4 below a real difference of the schemes (the
 * load's quadrature or a misplaced theta gives ~1e-6 at dt = 1e-3). Stick forces are recovered from a
 * velocity balance over one step, so their rounding is the velocity's magnified by m/h; the same allowance
 * bounds how far a force may stand outside its interval. */
static int rounding_ok(const params *p, const diff *d)
{
    double tol = (double)p->steps * p->n * EPS;
    double force_tol = tol * (1 + d->ar) + tol * (1 + d->av) * p->m / p->dt;
    return d->dx <= tol * (1 + d->ax) && d->dv <= tol * (1 + d->av) && d->dr <= force_tol && d->over <= force_tol;
}

static int compare(const params *p)
{
    FILE *sic = p->sic ? fopen(p->sic, "rb") : NULL;
    size_t n = (size_t)p->n, nf = p->phic > 0 ? 2 * n - 1 : n;
    double *rec = malloc((1 + 2 * n + nf) * sizeof *rec), *work = malloc(2 * n * sizeof *work);
    dp_record *buf = malloc(BLOCK * sizeof *buf);
    text t = { 0 };
    chain_text(&t, p, 1);
    dp_run *run = start_text(&t);
    free(t.s);
    int bad = sic == NULL || rec == NULL || work == NULL || buf == NULL || run == NULL, s = DP_DONE;
    if (sic == NULL)
        fprintf(stderr, "network_bench: cannot open Siconos' records '%s'\n", p->sic ? p->sic : "");
    diff d = { 0 };
    size_t got;
    unsigned long long events = 0;
    while (!bad) {
        s = dp_run_next(run, buf, BLOCK, &got);
        for (size_t i = 0; i < got && !bad; i++)
            if (buf[i].type == DP_RECORD_ROW && buf[i].u.row.t > 0) /* Siconos' records start after step 1 */
                bad = compare_row(p, dp_run_columns(run), &buf[i].u.row, nf, sic, rec, work, &d) != 0;
        if (s != DP_MORE)
            break;
    }
    if (!bad && s != DP_DONE) {
        fprintf(stderr, "network_bench: dashpot run failed: %s\n", dp_run_error(run));
        bad = 1;
    }
    if (!bad && d.n != p->steps) {
        fprintf(stderr, "network_bench: %lld steps compared, expected %lld\n", d.n, p->steps);
        bad = 1;
    }
    if (!bad)
        events = dp_run_summary(run)->events;
    dp_run_free(run);
    free(buf);
    free(rec);
    free(work);
    if (sic)
        fclose(sic);
    if (bad)
        return 1;
    printf("steps %lld\nevents %llu\nmax_dx %.3g\nmax_dv %.3g\nmax_dR %.3g\nmax_split %.3g\nmax_over %.3g\n"
           "max_abs_x %.6g\nmax_abs_v %.6g\nmax_abs_R %.6g\ntol_rel %.3g\nagree %d\n", d.n, events, d.dx, d.dv,
           d.dr, d.split, d.over, d.ax, d.av, d.ar, (double)p->steps * p->n * EPS, rounding_ok(p, &d));
    return 0;
}

/* ---- mode=time ------------------------------------------------------------------------------------- */

/* Best of reps over fresh runs of `t`; the last run's summary in *sum. */
static int best_time(const params *p, const text *t, double *best, double *setup, dp_summary *sum)
{
    dp_record *buf = malloc(BLOCK * sizeof *buf);
    if (buf == NULL)
        return -1;
    *best = *setup = INFINITY;
    for (long long r = 0; r < p->reps; r++) {
        double t0 = now();
        dp_run *run = start_text(t);
        double t1 = now(), loop = run ? run_through(run, buf) : -1;
        if (loop < 0) {
            dp_run_free(run);
            free(buf);
            return -1;
        }
        *best = fmin(*best, loop);
        *setup = fmin(*setup, t1 - t0);
        *sum = *dp_run_summary(run);
        sum->final_row = (dp_row){ 0 }; /* its arrays die with the run */
        dp_run_free(run);
    }
    free(buf);
    return 0;
}

static int time_steps(const params *p)
{
    text t = { 0 };
    chain_text(&t, p, 0);
    double best, setup;
    dp_summary sum;
    int s = best_time(p, &t, &best, &setup, &sum);
    free(t.s);
    if (s != 0)
        return 1;
    double steps = (double)p->steps;
    printf("n %.0f\nsteps %lld\nreps %lld\nsetup_seconds %.6g\nloop_seconds %.6g\nns_per_step %.4g\n"
           "ns_per_block_step %.4g\nevents %llu\nevents_per_step %.4g\nstick_fraction %.3f\n"
           "iterations_per_step %.4g\nmaxrss_kb %ld\n", p->n, p->steps, p->reps, setup, best, 1e9 * best / steps,
           1e9 * best / steps / p->n, sum.events, (double)sum.events / steps,
           sum.stick_time / (steps * p->dt * p->n), (double)sum.iterations / steps, maxrss_kb());
    return 0;
}

/* ---- mode=single ----------------------------------------------------------------------------------- */

static int single(const params *p)
{
    params q = *p;
    q.n = 1, q.F0 = 0, q.phic = 0, q.het = 0;
    text a = { 0 }, b = { 0 };
    one_mass_text(&a, &q);
    chain_text(&b, &q, 0);
    double ta, tb, sa, sb;
    dp_summary ra, rb;
    /* Alternated, so that a change of the machine's load falls on both. */
    int s = best_time(&q, &a, &ta, &sa, &ra) || best_time(&q, &b, &tb, &sb, &rb);
    double ta2, sa2, tb2, sb2;
    s = s || best_time(&q, &a, &ta2, &sa2, &ra) || best_time(&q, &b, &tb2, &sb2, &rb);
    free(a.s);
    free(b.s);
    if (s)
        return 1;
    ta = fmin(ta, ta2), tb = fmin(tb, tb2);
    /* The state at the end: the one-mass summary's final sample against the network's, run once more
     * with its arrays alive. */
    text c = { 0 };
    chain_text(&c, &q, 0);
    dp_run *run = start_text(&c);
    free(c.s);
    dp_record *buf = malloc(BLOCK * sizeof *buf);
    int same = 0;
    if (run && buf && run_through(run, buf) >= 0) {
        const dp_row *f = &dp_run_summary(run)->final_row;
        same = f->val[0] == ra.final.x && f->val[1] == ra.final.v;   /* one node: x, v first */
        printf("final_x_one_mass %.17g\nfinal_x_network %.17g\n", ra.final.x, f->val[0]);
    }
    dp_run_free(run);
    free(buf);
    double steps = (double)q.steps;
    printf("steps %lld\nevents_one_mass %llu\nevents_network %llu\none_mass_ns_per_step %.4g\n"
           "network_ns_per_step %.4g\nratio %.3f\nsame_final_state %d\n", q.steps, ra.events, rb.events,
           1e9 * ta / steps, 1e9 * tb / steps, tb / ta, same);
    return 0;
}

int main(int argc, char **argv)
{
    params p;
    if (parse_args(argc, argv, &p) != 0)
        return 2;
    if (strcmp(p.mode, "compare") == 0)
        return compare(&p);
    if (strcmp(p.mode, "time") == 0)
        return time_steps(&p);
    if (strcmp(p.mode, "single") == 0)
        return single(&p);
    if (strcmp(p.mode, "doc") == 0) {
        text t = { 0 };
        chain_text(&t, &p, 2);
        int bad = t.bad || fwrite(t.s, 1, t.len, stdout) != t.len;
        free(t.s);
        return bad;
    }
    fprintf(stderr, "network_bench: unknown mode '%s'\n", p.mode);
    return 2;
}
