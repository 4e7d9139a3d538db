/* src/core/studies/convergence.c - how fast (PCn) / (PIk) approach the exact solution as n (or k) grows.
 *
 * The existence proofs (Pražák & Rajagopal 2016, Thm 3, Babováková 2012, Thm 2.1) give uniform convergence of x and x' along a
 * subsequence; on a finite horizon the error is O(1/n), dominated by creep in stick phases: where the exact
 * solution rests with |F - k x| < phi0, the regularized one obeys m x'' + n x' + k x = F and drifts like
 * exp(-k t / n) (docs/mathematics.md §3). The study measures that: one regularized run per n and a reference run
 * of the same model, pulled in lockstep sample by sample, so memory is a few blocks whatever t_end is.
 *
 * The reference is the closed form (Babováková 2012, (4.14)-(4.15), the analytic solver) where it applies, else
 * the stick-slip solver with events located (theta 1/2: second order; theta 1 for a graph spring, which
 * the theta-method only steps by backward Euler) at a step dt/m, a whole fraction of the output spacing so
 * that its samples fall on the same times.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/regularized.h"
#include "dashpot/run.h"

#define BLOCK 64

/* Reference steps: theta 1/2 errs ~ h^2 (1e-8 at 1e-4), theta 1 ~ h (1e-5); both well below the 1/n of
 * any n a study would use (<= 1e6). */
#define REF_H_SECOND_ORDER 1e-4
#define REF_H_FIRST_ORDER 1e-5

typedef struct stream {
    dp_run *run;
    int status;
    size_t n, i;
    int (*stop)(void *ctx);  /* asked before every block: nonzero ends the run with DP_ECANCEL */
    void *ctx;
    dp_record buf[BLOCK];
} stream;

/* The next sample of a run (events are skipped); 0 when the run has ended (status says how). */
static int next_sample(stream *s, dp_sample *out)
{
    for (;;) {
        while (s->i < s->n) {
            const dp_record *r = &s->buf[s->i++];
            if (r->type == DP_RECORD_SAMPLE) {
                *out = r->u.sample;
                return 1;
            }
        }
        if (s->status != DP_MORE)
            return 0;
        s->i = 0;
        if (s->stop && s->stop(s->ctx)) {
            s->status = DP_ECANCEL, s->n = 0;
            return 0;
        }
        s->status = dp_run_next(s->run, s->buf, BLOCK, &s->n);
        if (s->status < 0)
            s->n = 0; /* a failed run's last records are not compared */
    }
}

/* Turns spec into the reference's spec (a shallow copy: the model stays the caller's). */
static void reference_spec(const dp_spec *spec, double ref_dt, dp_spec *ref, dp_convergence *out)
{
    dp_errors scratch;
    dp_errors_init(&scratch);
    *ref = *spec;
    ref->output = (dp_output_spec){ .every = 1, .samples = 1, .events = 0 };
    ref->solver.kind = DP_SOLVER_ANALYTIC;
    out->reference = DP_REFERENCE_ANALYTIC;
    out->ref_dt = spec->solver.dt;
    out->ref_theta = NAN;
    if (dp_spec_check(ref, 0, &scratch) == DP_OK)
        return;
    int linear = dp_spring_linear(&spec->model.spring);
    double dt = spec->solver.dt, h = ref_dt > 0 ? ref_dt : linear ? REF_H_SECOND_ORDER : REF_H_FIRST_ORDER;
    double m = ref_dt > 0 ? fmax(1, round(dt / h)) : ceil(dt / h * (1 - 1e-12));
    ref->solver.kind = DP_SOLVER_STICK_SLIP;
    ref->solver.variant = DP_VARIANT_EXACT;
    ref->solver.events = DP_EVENTS_LOCATE;
    ref->solver.theta = linear ? 0.5 : 1;
    ref->solver.dt = dt / m;
    ref->output.every = (long)m;
    out->reference = DP_REFERENCE_STICK_SLIP;
    out->ref_dt = ref->solver.dt;
    out->ref_theta = ref->solver.theta;
}

/* Opens the reference (stream 0) and one run per n (streams 1..k). DP_OK or the first failure. */
static int open_streams(const dp_spec *spec, const dp_spec *ref, double max_steps, stream *st, size_t k,
                        dp_errors *errs)
{
    int status = DP_OK;
    dp_spec one = *spec;
    one.output = (dp_output_spec){ .every = 1, .samples = 1, .events = 0 };
    one.solver.n_count = 1;
    st[0].run = dp_run_alloc(ref, max_steps, errs, &status);
    for (size_t i = 1; i <= k && status == DP_OK; i++) {
        one.solver.n_list[0] = spec->solver.n_list[i - 1];
        st[i].run = dp_run_alloc(&one, max_steps, errs, &status);
    }
    for (size_t i = 0; i <= k; i++)
        st[i].status = DP_MORE;
    return status;
}

static double rate(double e_prev, double e, double n_prev, double n)
{
    return e_prev > 0 && e > 0 ? log(e_prev / e) / log(n / n_prev) : NAN;
}

/* Least-squares slope of -log e against log n over the rows with e > 0 (NAN with fewer than two). */
static double fitted_rate(const dp_convergence *c, int v)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0, m = 0;
    for (size_t i = 0; i < c->nrows; i++) {
        double e = v ? c->row[i].err_v : c->row[i].err_x;
        if (!(e > 0))
            continue;
        double X = log(c->row[i].n), Y = -log(e);
        sx += X, sy += Y, sxx += X * X, sxy += X * Y, m++;
    }
    double den = m * sxx - sx * sx;
    return m >= 2 && den > 0 ? (m * sxy - sx * sy) / den : NAN;
}

/* Compares one output time across the streams; DP_ESOLVE if the grids disagree. */
static int compare(dp_convergence *c, const dp_sample *ref, const dp_sample *s, size_t k)
{
    for (size_t i = 0; i < k; i++) {
        dp_convergence_row *r = &c->row[i];
        if (fabs(s[i].t - ref->t) > 1e-9 * fmax(1, fabs(ref->t)))
            return DP_ESOLVE;
        r->err_x = fmax(r->err_x, fabs(s[i].x - ref->x));
        r->err_v = fmax(r->err_v, fabs(s[i].v - ref->v));
        if (i > 0) {
            r->diff_x = fmax(r->diff_x, fabs(s[i].x - s[i - 1].x));
            r->diff_v = fmax(r->diff_v, fabs(s[i].v - s[i - 1].v));
        }
    }
    c->samples++;
    return DP_OK;
}

/* Pulls every stream to its end in lockstep. */
static int sweep(dp_convergence *c, stream *st, size_t k, dp_sample *cur, dp_errors *errs)
{
    dp_sample ref = { 0 };
    for (;;) {
        int got = next_sample(&st[0], &ref), all = got, none = !got, stopped = st[0].status == DP_ECANCEL;
        for (size_t i = 0; i < k; i++) {
            int g = next_sample(&st[i + 1], &cur[i]);
            all = all && g, none = none && !g, stopped = stopped || st[i + 1].status == DP_ECANCEL;
        }
        if (stopped) {
            dp_errors_add(errs, "", "the study was stopped after %llu of its output times", c->samples);
            return DP_ECANCEL;
        }
        if (none)
            break;
        if (!all || compare(c, &ref, cur, k) != DP_OK) {
            dp_errors_add(errs, "", "the runs' output grids disagree at t = %.17g", ref.t);
            return DP_ESOLVE;
        }
    }
    for (size_t i = 0; i <= k; i++) {
        if (st[i].status != DP_DONE) {
            const char *why = dp_run_error(st[i].run);
            dp_errors_add(errs, "", "the %s run failed: %s", i ? "regularized" : "reference",
                          why[0] ? why : dp_strerror(st[i].status));
            return st[i].status;
        }
    }
    return DP_OK;
}

static void finish_rows(dp_convergence *c, const dp_spec *spec, const stream *st)
{
    for (size_t i = 0; i < c->nrows; i++) {
        dp_convergence_row *r = &c->row[i];
        const dp_summary *s = dp_run_summary(st[i + 1].run);
        r->steps = s->steps, r->rejected = s->rejected, r->fevals = s->fevals, r->jevals = s->iterations;
        if (i == 0)
            continue;
        double n0 = spec->solver.n_list[i - 1];
        r->rate_x = rate(c->row[i - 1].err_x, r->err_x, n0, r->n);
        r->rate_v = rate(c->row[i - 1].err_v, r->err_v, n0, r->n);
    }
    c->rate_x = fitted_rate(c, 0);
    c->rate_v = fitted_rate(c, 1);
}

static void init_rows(dp_convergence *c, const dp_spec *spec)
{
    const dp_solver_spec *sv = &spec->solver;
    c->scheme = sv->scheme, c->stepper = sv->stepper;
    c->rtol = sv->rtol, c->atol = sv->atol, c->dt = sv->dt, c->t_end = sv->t_end;
    c->nrows = sv->n_count;
    for (size_t i = 0; i < c->nrows; i++)
        c->row[i] = (dp_convergence_row){ .n = sv->n_list[i], .diff_x = i ? 0 : NAN, .diff_v = i ? 0 : NAN,
                                          .rate_x = NAN, .rate_v = NAN };
}

int dp_convergence_study(const dp_spec *spec, double max_steps, double ref_dt, dp_convergence *out,
                         dp_errors *errs)
{
    return dp_convergence_study_until(spec, max_steps, ref_dt, NULL, NULL, out, errs);
}

int dp_convergence_study_until(const dp_spec *spec, double max_steps, double ref_dt, int (*stop)(void *ctx),
                               void *ctx, dp_convergence *out, dp_errors *errs)
{
    memset(out, 0, sizeof *out);
    if (spec->solver.kind != DP_SOLVER_REGULARIZED) {
        dp_errors_add(errs, "/solver/kind", "a convergence study needs the regularized solver");
        return DP_EINVAL;
    }
    int s = dp_spec_check(spec, max_steps, errs);
    if (s != DP_OK)
        return s;
    size_t k = spec->solver.n_count;
    dp_spec ref;
    init_rows(out, spec);
    reference_spec(spec, ref_dt, &ref, out);
    stream *st = calloc(k + 1, sizeof *st);
    dp_sample *cur = calloc(k, sizeof *cur);
    s = st && cur ? open_streams(spec, &ref, max_steps, st, k, errs) : DP_ENOMEM;
    for (size_t i = 0; st && i <= k; i++) {
        st[i].stop = stop, st[i].ctx = ctx;
        if (st[i].run && stop) /* inside a block too: a block of a decimated run may be the whole run */
            dp_run_set_stop(st[i].run, stop, ctx);
    }
    if (s == DP_OK)
        s = sweep(out, st, k, cur, errs);
    if (s == DP_OK)
        finish_rows(out, spec, st);
    for (size_t i = 0; st && i <= k; i++)
        dp_run_free(st[i].run);
    free(st);
    free(cur);
    return s;
}
