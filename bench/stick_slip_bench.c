/* bench/stick_slip_bench.c - dashpot's stick-slip solver measured for bench/siconos.sh: accuracy against
 * Siconos' trajectory and the closed form, wall time and memory per step, and the cost of NDJSON samples.
 *
 * The problem (the same keys as bench/siconos_peer.cpp and bench/floor.c, so that the script states a case
 * once and hands the same words to all three):
 *     m x'' + k x + Fc = F0 + amp cos(omega t + phase),   Fc in phi0 Sgn(x' - vb),   x(0) = x0, x'(0) = v0
 * stepped `steps` times with dt by dashpot's `stick-slip` solver at `theta`.
 *
 * Usage: stick_slip_bench mode=MODE key=value ...
 *   mode=compare sic=FILE  dashpot with "events":"none" (plain Moreau-Jean) next to Siconos' records
 *                          (FILE: t, x, v, Fc per step, native doubles): max |dx|, |dv|, |dFc|, the verdict
 *                          on rounding agreement, and the error of each (and of dashpot's located variant)
 *                          against the closed form where there is one (constant load).
 *   mode=time [reps=R]     output off ("samples": false): ns per step (best of R runs), peak RSS.
 *   mode=ndjson [reps=R]   every sample encoded as NDJSON (dp_encoder_record into a dp_buf reset per block of
 *                          4096 records, as the CLI does): samples/s, the encoder's own ns per sample.
 * Output: "key value" lines.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "dashpot/analytic.h"
#include "dashpot/encode.h"
#include "dashpot/json.h"
#include "dashpot/run.h"
#include "dashpot/status.h"

#define BLOCK 4096 /* records per dp_run_next, as the CLI's stream */
#define EPS 2.220446049250313e-16

typedef struct params {
    double m, k, phi0, vb, F0, amp, omega, phase, x0, v0, dt, theta;
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
    *p = (params){ .m = 1, .k = 1, .phi0 = 1, .dt = 1e-3, .theta = 0.5, .steps = 1000, .reps = 1,
                   .mode = "time" };
    struct { const char *key; double *d; } nums[] = {
        { "m", &p->m }, { "k", &p->k }, { "phi0", &p->phi0 }, { "vb", &p->vb }, { "F0", &p->F0 },
        { "amp", &p->amp }, { "omega", &p->omega }, { "phase", &p->phase }, { "x0", &p->x0 },
        { "v0", &p->v0 }, { "dt", &p->dt }, { "theta", &p->theta },
    };
    for (int i = 1; i < argc; i++) {
        char *eq = strchr(argv[i], '=');
        size_t n = eq ? (size_t)(eq - argv[i]) : 0;
        int known = 0;
        for (size_t j = 0; eq && j < sizeof nums / sizeof nums[0]; j++)
            if (strlen(nums[j].key) == n && strncmp(argv[i], nums[j].key, n) == 0)
                *nums[j].d = strtod(eq + 1, NULL), known = 1;
        if (eq && n == 5 && strncmp(argv[i], "steps", 5) == 0)
            p->steps = strtoll(eq + 1, NULL, 10), known = 1;
        if (eq && n == 4 && strncmp(argv[i], "reps", 4) == 0)
            p->reps = strtoll(eq + 1, NULL, 10), known = 1;
        if (eq && n == 4 && strncmp(argv[i], "mode", 4) == 0)
            p->mode = eq + 1, known = 1;
        if (eq && n == 3 && strncmp(argv[i], "sic", 3) == 0)
            p->sic = eq + 1, known = 1;
        if (!known) {
            fprintf(stderr, "stick_slip_bench: bad argument '%s'\n", argv[i]);
            return -1;
        }
    }
    if (p->steps < 1 || p->reps < 1) {
        fprintf(stderr, "stick_slip_bench: steps and reps must be >= 1\n");
        return -1;
    }
    return 0;
}

/* ---- running dashpot ------------------------------------------------------------------------------- */

/* The spec of the case as a user would write it. */
static int spec_text(const params *p, const char *events, int samples, char *out, size_t cap)
{
    char forcing[512] = "";
    char harm[256];
    snprintf(harm, sizeof harm, "{\"kind\":\"harmonic\",\"amplitude\":%.17g,\"omega\":%.17g,\"phase\":%.17g}",
             p->amp, p->omega, p->phase);
    if (p->amp != 0 && p->F0 != 0)
        snprintf(forcing, sizeof forcing, ",\"forcing\":{\"kind\":\"sum\",\"terms\":[{\"kind\":\"constant\","
                 "\"value\":%.17g},%s]}", p->F0, harm);
    else if (p->amp != 0)
        snprintf(forcing, sizeof forcing, ",\"forcing\":%s", harm);
    else if (p->F0 != 0)
        snprintf(forcing, sizeof forcing, ",\"forcing\":{\"kind\":\"constant\",\"value\":%.17g}", p->F0);
    int n = snprintf(out, cap,
        "{\"model\":{\"mass\":%.17g,\"spring\":{\"law\":\"linear\",\"k\":%.17g},"
        "\"damper\":{\"law\":\"coulomb\",\"phi0\":%.17g,\"belt_velocity\":%.17g}%s},"
        "\"initial\":{\"x\":%.17g,\"v\":%.17g},"
        "\"solver\":{\"kind\":\"stick-slip\",\"dt\":%.17g,\"t_end\":%.17g,\"theta\":%.17g,\"events\":\"%s\"},"
        "\"output\":{\"every\":1,\"samples\":%s,\"events\":%s}}",
        p->m, p->k, p->phi0, p->vb, forcing, p->x0, p->v0, p->dt, (double)p->steps * p->dt, p->theta, events,
        samples ? "true" : "false", samples ? "true" : "false");
    return n > 0 && (size_t)n < cap ? 0 : -1;
}

static dp_run *start(const params *p, const char *events, int samples)
{
    char text[2048];
    if (spec_text(p, events, samples, text, sizeof text) != 0)
        return NULL;
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(text, strlen(text), 0, &spec, &errs);
    dp_run *run = s == DP_OK ? dp_run_alloc(&spec, 0, &errs, &s) : NULL;
    if (run == NULL)
        fprintf(stderr, "stick_slip_bench: spec rejected (%s): %s\n", dp_strerror(s),
                errs.n ? errs.item[0].message : "");
    dp_spec_clear(&spec);
    return run;
}

/* ---- the closed form (constant load, any belt speed) ------------------------------------------------ */

/* m x'' + k x + Fc = F0, Fc in phi0 Sgn(x' - vb): harmonic arcs about (F0 - s phi0)/k while the relative
 * velocity has sign s, joined where x' = vb; there the mass sticks (moves with the belt) while the holding
 * force F0 - k x stays in [-phi0, phi0], and breaks away where it leaves. For vb = 0 this is dp_coulomb_arcs
 * (thesis (4.14)-(4.15)), which dashpot has; a belt is not in it, so the segments are built here, one at a
 * time, and checked against dp_coulomb_arcs on the ground (vb = 0) case. */
typedef struct closed {
    double m, k, phi0, F0, vb, w;
    double t0, x0, v0; /* start of the current segment */
    int mode;          /* sign of x' - vb while slipping, 0 sticking */
    double t1;         /* its end (INFINITY if none) */
} closed;

static double wrap_2pi(double a)
{
    a = fmod(a, 2 * M_PI);
    return a < 0 ? a + 2 * M_PI : a;
}

/* Ends the current segment: sets t1 from (t0, x0, v0, mode). */
static void closed_segment_end(closed *c)
{
    if (c->mode == 0) {
        /* The holding force decreases along a forward belt (increases along a backward one). */
        if (c->vb == 0) {
            c->t1 = INFINITY;
            return;
        }
        double edge = c->vb > 0 ? (c->F0 + c->phi0) / c->k : (c->F0 - c->phi0) / c->k;
        c->t1 = c->t0 + fmax((edge - c->x0) / c->vb, 0);
        return;
    }
    double xc = (c->F0 - c->mode * c->phi0) / c->k, a = c->x0 - xc;
    /* v(tau) = R cos(w tau + alpha); it meets vb rising (mode -1) or falling (mode +1). */
    double R = hypot(c->v0, a * c->w), alpha = atan2(a * c->w, c->v0);
    if (R < fabs(c->vb) || R == 0) {
        c->t1 = INFINITY;
        return;
    }
    double beta = acos(fmin(fmax(c->vb / R, -1), 1));
    double tau = wrap_2pi(c->mode * beta - alpha) / c->w;
    if (tau * c->w < 1e-9) /* starting on the crossing itself (leaving stick tangentially): a full turn */
        tau += 2 * M_PI / c->w;
    c->t1 = c->t0 + tau;
}

static void closed_eval(const closed *c, double t, double *x, double *v)
{
    double tau = t - c->t0;
    if (c->mode == 0) {
        *x = c->x0 + c->vb * tau;
        *v = c->vb;
        return;
    }
    double xc = (c->F0 - c->mode * c->phi0) / c->k, a = c->x0 - xc, cs = cos(c->w * tau), sn = sin(c->w * tau);
    *x = xc + a * cs + c->v0 / c->w * sn;
    *v = -a * c->w * sn + c->v0 * cs;
}

/* Enters the segment that starts at state (t, x, vb) where the last one ended. */
static void closed_next(closed *c)
{
    double x, v, hold;
    if (c->mode == 0) {
        x = c->vb > 0 ? (c->F0 + c->phi0) / c->k : (c->F0 - c->phi0) / c->k;
        c->mode = c->vb > 0 ? -1 : 1; /* the spring pulls back harder than friction can hold */
    } else {
        closed_eval(c, c->t1, &x, &v);
        hold = c->F0 - c->k * x;
        c->mode = fabs(hold) <= c->phi0 ? 0 : (hold > 0 ? 1 : -1);
    }
    c->t0 = c->t1, c->x0 = x, c->v0 = c->vb;
    closed_segment_end(c);
}

static void closed_init(closed *c, const params *p)
{
    *c = (closed){ .m = p->m, .k = p->k, .phi0 = p->phi0, .F0 = p->F0, .vb = p->vb, .w = sqrt(p->k / p->m),
                   .t0 = 0, .x0 = p->x0, .v0 = p->v0 };
    double rel = p->v0 - p->vb, hold = p->F0 - p->k * p->x0;
    c->mode = rel != 0 ? (rel > 0 ? 1 : -1) : fabs(hold) <= p->phi0 ? 0 : (hold > 0 ? 1 : -1);
    closed_segment_end(c);
}

/* The closed form at t (t non-decreasing between calls). */
static void closed_at(closed *c, double t, double *x, double *v)
{
    while (t > c->t1)
        closed_next(c);
    closed_eval(c, t, x, v);
}

/* The reference a run is measured against: on the ground (vb = 0) dashpot's own dp_coulomb_arcs, with a
 * belt the construction above (whose belt-free half is checked against dp_coulomb_arcs on every run). */
typedef struct reference {
    dp_coulomb_problem cp;
    dp_coulomb_arc *arcs; /* NULL: use `c` */
    size_t n, j;
    closed c;
} reference;

static int reference_init(reference *ref, const params *p, int belt)
{
    memset(ref, 0, sizeof *ref);
    closed_init(&ref->c, p);
    if (belt)
        return 0;
    ref->cp = (dp_coulomb_problem){ .m = p->m, .k = p->k, .phi0 = p->phi0, .F0 = p->F0, .x0 = p->x0, .v0 = p->v0 };
    size_t cap = 1 << 16;
    ref->arcs = malloc(cap * sizeof *ref->arcs);
    if (ref->arcs == NULL || dp_coulomb_arcs(&ref->cp, (double)p->steps * p->dt, ref->arcs, cap, &ref->n) != 0) {
        free(ref->arcs);
        ref->arcs = NULL;
        return -1;
    }
    return 0;
}

/* The reference at t (t non-decreasing between calls). */
static void reference_at(reference *ref, double t, double *x, double *v)
{
    if (ref->arcs == NULL) {
        closed_at(&ref->c, t, x, v);
        return;
    }
    while (ref->j + 1 < ref->n && ref->arcs[ref->j + 1].t0 <= t)
        ref->j++;
    dp_coulomb_arc_eval(&ref->cp, &ref->arcs[ref->j], t, x, v);
}

static void reference_free(reference *ref)
{
    free(ref->arcs);
}

/* The construction above with the belt removed against dp_coulomb_arcs on the same problem: it must
 * reproduce dashpot's closed form to rounding, or the belt figures mean nothing. */
static int closed_self_check(const params *p)
{
    params q = *p;
    q.vb = 0;
    reference dp_ref, own;
    if (reference_init(&dp_ref, &q, 0) != 0 || reference_init(&own, &q, 1) != 0) {
        reference_free(&dp_ref);
        return -1;
    }
    double worst = 0, scale = 1;
    for (long long i = 0; i <= p->steps; i += 1 + p->steps / 4096) {
        double t = (double)i * p->dt, xa, va, xb, vb;
        reference_at(&dp_ref, t, &xa, &va);
        reference_at(&own, t, &xb, &vb);
        worst = fmax(worst, fmax(fabs(xa - xb), fabs(va - vb)));
        scale = fmax(scale, fabs(xa));
    }
    reference_free(&dp_ref);
    printf("closed_form_self_check %.3g\n", worst);
    return worst <= 1e-9 * scale ? 0 : -1;
}

/* ---- mode=compare ---------------------------------------------------------------------------------- */

typedef struct diff {
    double dx, dv, df;        /* max |difference| over the run */
    double ax, av, af;        /* max |value| (dashpot) */
    double ex, ev;            /* max error of dashpot against the closed form */
    double sx, sv;            /* max error of Siconos against the closed form */
    long long n;
} diff;

/* Runs dashpot (events mode `events`) over the case; with `sic` open, compares step by step with Siconos'
 * records (rewound first); with `with_closed`, both against the closed form. Returns 0, or -1 on failure. */
static int sweep(const params *p, const char *events, FILE *sic, int with_closed, diff *d)
{
    memset(d, 0, sizeof *d);
    dp_run *run = start(p, events, 1);
    dp_record *buf = malloc(BLOCK * sizeof *buf);
    if (run == NULL || buf == NULL) {
        dp_run_free(run);
        free(buf);
        return -1;
    }
    reference ref;
    if (with_closed && reference_init(&ref, p, p->vb != 0) != 0) {
        dp_run_free(run);
        free(buf);
        return -1;
    }
    if (sic)
        rewind(sic);
    int s, bad = 0;
    size_t n;
    do {
        s = dp_run_next(run, buf, BLOCK, &n);
        for (size_t i = 0; i < n && !bad; i++) {
            if (buf[i].type != DP_RECORD_SAMPLE)
                continue;
            const dp_sample *a = &buf[i].u.sample;
            d->ax = fmax(d->ax, fabs(a->x));
            d->av = fmax(d->av, fabs(a->v));
            if (a->t == 0)
                continue; /* Siconos' records start after the first step */
            d->af = fmax(d->af, fabs(a->Fc));
            double r[4] = { 0 };
            if (sic) {
                if (fread(r, sizeof r, 1, sic) != 1 || fabs(r[0] - a->t) > 1e-9 * (1 + a->t)) {
                    fprintf(stderr, "stick_slip_bench: Siconos' record %lld missing or at t = %.17g, not %.17g\n",
                            d->n, r[0], a->t);
                    bad = 1;
                    break;
                }
                d->dx = fmax(d->dx, fabs(a->x - r[1]));
                d->dv = fmax(d->dv, fabs(a->v - r[2]));
                d->df = fmax(d->df, fabs(a->Fc - r[3]));
            }
            if (with_closed) {
                double x, v;
                reference_at(&ref, a->t, &x, &v);
                d->ex = fmax(d->ex, fabs(a->x - x));
                d->ev = fmax(d->ev, fabs(a->v - v));
                if (sic) {
                    d->sx = fmax(d->sx, fabs(r[1] - x));
                    d->sv = fmax(d->sv, fabs(r[2] - v));
                }
            }
            d->n++;
        }
    } while (s == DP_MORE && !bad);
    if (s < 0 && !bad) {
        fprintf(stderr, "stick_slip_bench: dashpot run failed: %s\n", dp_run_error(run));
        bad = 1;
    }
    dp_run_free(run);
    free(buf);
    if (with_closed)
        reference_free(&ref);
    if (!bad && d->n != p->steps) {
        fprintf(stderr, "stick_slip_bench: %lld steps compared, expected %lld\n", d->n, p->steps);
        bad = 1;
    }
    return bad ? -1 : 0;
}

/* "Agree to rounding": both codes do the same arithmetic on the same numbers, in a different order, so each
 * step differs by a few ulps. Where the motion is neutrally stable (along an orbit: the belt's limit cycle)
 * those differences add up instead of decaying, so the honest bound grows with the number of steps N:
 *     |dx| <= N eps (1 + max|x|),   |dv| <= N eps (1 + max|v|)
 * (N = 2e4: 4.4e-12 relative; measured 0.02-0.1 of it). The stick force is recovered as W u / h, so its
 * rounding is the velocity's magnified by m/h: |dF| <= N eps (1 + max|F|) + N eps (1 + max|v|) m / h.
 * A real difference of the schemes is far above this: the load quadrature below gives 1e-6 at dt = 1e-3. */
static int rounding_ok(const params *p, const diff *d)
{
    double tol = (double)p->steps * EPS;
    return d->dx <= tol * (1 + d->ax) && d->dv <= tol * (1 + d->av)
        && d->df <= tol * (1 + d->af) + tol * (1 + d->av) * p->m / p->dt;
}

static int compare(const params *p)
{
    FILE *sic = p->sic ? fopen(p->sic, "rb") : NULL;
    if (sic == NULL) {
        fprintf(stderr, "stick_slip_bench: cannot open Siconos' records '%s'\n", p->sic ? p->sic : "");
        return 1;
    }
    int with_closed = p->amp == 0;
    if (with_closed && closed_self_check(p) != 0) {
        fprintf(stderr, "stick_slip_bench: the belt closed form does not reproduce dp_coulomb_arcs\n");
        fclose(sic);
        return 1;
    }
    diff d, loc;
    if (sweep(p, "none", sic, with_closed, &d) != 0 || sweep(p, "locate", NULL, with_closed, &loc) != 0) {
        fclose(sic);
        return 1;
    }
    printf("steps %lld\nmax_dx %.3g\nmax_dv %.3g\nmax_dF %.3g\nmax_abs_x %.6g\nmax_abs_v %.6g\nmax_abs_F %.6g\n",
           d.n, d.dx, d.dv, d.df, d.ax, d.av, d.af);
    if (with_closed)
        printf("err_x_dashpot %.3g\nerr_v_dashpot %.3g\nerr_x_siconos %.3g\nerr_v_siconos %.3g\n"
               "err_x_located %.3g\nerr_v_located %.3g\n", d.ex, d.ev, d.sx, d.sv, loc.ex, loc.ev);
    int agree = rounding_ok(p, &d);
    printf("rounding %d\n", agree);
    if (p->amp != 0) {
        /* Siconos' EulerMoreauOSI weights the load theta F(t+h) + (1-theta) F(t); dashpot evaluates
         * F(t + theta h). For a harmonic load the first is exactly the second with amplitude amp |z| and phase
         * phase + arg z - omega theta h, z = 1 - theta + theta e^{i omega h}. Running dashpot with that load
         * separates the quadrature of the load (an O(h^2) difference of the schemes) from everything else,
         * which must then agree to rounding. */
        double wh = p->omega * p->dt, re = 1 - p->theta + p->theta * cos(wh), im = p->theta * sin(wh);
        params q = *p;
        q.amp = p->amp * hypot(re, im);
        q.phase = p->phase + atan2(im, re) - wh * p->theta;
        diff m;
        if (sweep(&q, "none", sic, 0, &m) != 0) {
            fclose(sic);
            return 1;
        }
        printf("matched_load_max_dx %.3g\nmatched_load_max_dv %.3g\nmatched_load_max_dF %.3g\n", m.dx, m.dv, m.df);
        agree = rounding_ok(&q, &m);
        printf("matched_load_rounding %d\n", agree);
    }
    printf("agree %d\n", agree);
    fclose(sic);
    return 0;
}

/* ---- mode=time ------------------------------------------------------------------------------------- */

static int time_steps(const params *p)
{
    dp_record *buf = malloc(BLOCK * sizeof *buf);
    if (buf == NULL)
        return 1;
    double best = INFINITY, setup = INFINITY, xf = 0, vf = 0;
    for (long long r = 0; r < p->reps; r++) {
        double t0 = now();
        dp_run *run = start(p, "none", 0);
        if (run == NULL) {
            free(buf);
            return 1;
        }
        double t1 = now();
        int s;
        size_t n;
        do
            s = dp_run_next(run, buf, BLOCK, &n);
        while (s == DP_MORE);
        double t2 = now();
        if (s != DP_DONE) {
            fprintf(stderr, "stick_slip_bench: run failed: %s\n", dp_run_error(run));
            dp_run_free(run);
            free(buf);
            return 1;
        }
        xf = dp_run_summary(run)->final.x, vf = dp_run_summary(run)->final.v;
        dp_run_free(run);
        best = fmin(best, t2 - t1);
        setup = fmin(setup, t1 - t0);
    }
    free(buf);
    printf("steps %lld\nreps %lld\nsetup_seconds %.6g\nloop_seconds %.6g\nns_per_step %.4g\nmaxrss_kb %ld\n"
           "final_x %.17g\nfinal_v %.17g\n", p->steps, p->reps, setup, best, 1e9 * best / (double)p->steps,
           maxrss_kb(), xf, vf);
    return 0;
}

/* ---- mode=ndjson ----------------------------------------------------------------------------------- */

static int time_ndjson(const params *p)
{
    dp_record *buf = malloc(BLOCK * sizeof *buf);
    if (buf == NULL)
        return 1;
    double best = INFINITY, best_enc = INFINITY;
    unsigned long long samples = 0, bytes = 0;
    for (long long r = 0; r < p->reps; r++) {
        dp_run *run = start(p, "none", 1);
        if (run == NULL) {
            free(buf);
            return 1;
        }
        dp_encoder e;
        dp_buf b = { 0 };
        dp_encoder_init(&e, DP_FORMAT_NDJSON);
        double enc = 0, t0 = now();
        int s, ok = 1;
        size_t n;
        samples = bytes = 0;
        do {
            s = dp_run_next(run, buf, BLOCK, &n);
            double e0 = now();
            b.len = 0; /* the block went to the socket */
            for (size_t i = 0; i < n; i++)
                ok &= dp_encoder_record(&e, &b, &buf[i]) == DP_OK;
            enc += now() - e0;
            bytes += b.len;
            samples += n;
        } while (s == DP_MORE && ok);
        double t = now() - t0;
        dp_encoder_clear(&e);
        dp_buf_free(&b);
        dp_run_free(run);
        if (s != DP_DONE || !ok) {
            fprintf(stderr, "stick_slip_bench: NDJSON run failed\n");
            free(buf);
            return 1;
        }
        best = fmin(best, t);
        best_enc = fmin(best_enc, enc);
    }
    free(buf);
    printf("samples %llu\nbytes_per_sample %.1f\nseconds %.6g\nsamples_per_second %.4g\nencode_ns_per_sample %.4g\n"
           "solve_ns_per_sample %.4g\nmaxrss_kb %ld\n", samples, (double)bytes / (double)samples, best,
           (double)samples / best, 1e9 * best_enc / (double)samples, 1e9 * (best - best_enc) / (double)samples,
           maxrss_kb());
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
    if (strcmp(p.mode, "ndjson") == 0)
        return time_ndjson(&p);
    fprintf(stderr, "stick_slip_bench: unknown mode '%s'\n", p.mode);
    return 2;
}
