/* src/core/solvers/lcs_run.c - a linear complementarity system run (docs/lcs.md): the θ-step of lcs.c driven
 * through the pull iterator, each sample a row of the groups x (n states), u and w (m components each).
 *
 * A block takes as many rows as the caller's buffer has slots (within ROW_BUDGET numbers) and the stepping
 * pauses when it is full, so a stream of any length runs in constant memory; the records of a step that do
 * not fit (its mode changes and its row) wait in a queue, in order. With events "locate" (the default) each
 * step that changes a component's mode is split at the change (lcs_events.c) and the change is an event;
 * with "none" the steps are the plain θ-steps, as before events were located.
 * The first row is the initial state with u, w from the algebraic part alone (D u + C x0 + q in the laws).
 * A step whose LCP has no solution Lemke's method can find ends the run with DP_ESOLVE, saying when; a
 * failure of the solver itself (its pivot limit, an answer that fails its check) names the solver, never the
 * user's data. Each step's Lemke asks the run's stop hook through its pivots (a step of a large LCP can pivot
 * for seconds), besides the poll between steps.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/lcs.h"
#include "record/row_queue.h"
#include "record/sink.h"
#include "solvers/run_types.h"

#define ROW_BUDGET (1u << 20)
#define QCAP0 16      /* records a queue starts with room for: a step's few mode changes and its row */

struct dp_lcs_run {
    dp_lcs_stepper *step, *last;   /* the nominal step, and the shorter last one (NULL when equal) */
    dp_lcs_locator *locate;        /* events "locate": splits steps at mode changes; NULL for "none" */
    size_t n, m, width;
    double *x, *u, *w, *p;        /* p: the offset at the step's θ-point, for a time-dependent one */
    double *final_row, *row;      /* the summary's row; a row on its way to the queue */
    dp_row_slots slots;            /* the rows of the block being produced */
    dp_row_queue queue;            /* records that did not fit the block, in order */
    size_t *index;                 /* 0, 1, 2, ... for the CSV headers */
    int started;
    dp_columns cols;
};

static void lcs_run_free(void *state)
{
    struct dp_lcs_run *lr = state;
    if (lr == NULL)
        return;
    dp_lcs_stepper_free(lr->step);
    dp_lcs_stepper_free(lr->last);
    dp_lcs_locator_free(lr->locate);
    free(lr->x);
    free(lr->u);
    free(lr->w);
    free(lr->p);
    free(lr->slots.data);
    dp_row_queue_clear(&lr->queue);
    free(lr->row);
    free(lr->final_row);
    free(lr->index);
    free(lr);
}

static void declare_columns(struct dp_lcs_run *lr)
{
    static const char *const names[3] = { "x", "u", "w" };
    size_t len[3] = { lr->n, lr->m, lr->m };
    lr->cols.ngroups = 3;
    for (size_t g = 0; g < 3; g++)
        lr->cols.group[g] = (dp_column_group){ names[g], len[g], lr->index, 0 };
    lr->cols.width = lr->width;
}

/* The initial u, w: the algebraic part at x0 (dp_lcs_check made sure there is one, or left a problem too
 * large for its budget undecided). Solved at the run's first advance, not at its set-up, so that its pivots
 * are under the run's stop hook (a set-up runs before the caller can give one). */
static int initial_algebraic(struct dp_lcs_run *lr, const dp_lcs *sys, dp_lcp_result *res, const dp_stop *stop)
{
    int s;
    *res = (dp_lcp_result){ DP_LCP_SOLVED, 0, 0.0 };
    dp_lcs_stepper *alg = dp_lcs_stepper_alloc(sys, 0.0, 1.0, &s);
    if (alg == NULL)
        return s;
    s = dp_lcs_step_until(alg, lr->x, lr->u, lr->w, res, stop);
    if (s == DP_OK && lr->locate)
        dp_lcs_locator_start(lr->locate, alg);   /* the modes at t = 0 */
    dp_lcs_stepper_free(alg);
    return s;
}

/* A stepper refused at set-up: the member that made it (lcs.h) as the error's place. */
static int setup_failed(dp_run *r, int s, const char *where, const char *fmt, const char *why)
{
    snprintf(r->error_pointer, sizeof r->error_pointer, "%s", where);
    return dp_run_fail(r, s, fmt, why);
}

/* A step's failure, `when` saying which: the solver's own (its pivot limit, an answer that fails its check)
 * named at /solver, the stop hook's, the data's (no u: a ray), or the offsets leaving the doubles. */
static int step_failed(dp_run *r, int s, const dp_lcp_result *res, const char *when)
{
    if (s == DP_ECANCEL)
        return dp_run_fail(r, s, "the run was stopped at t = %.17g, inside Lemke's pivots", r->cur.t);
    if (s == DP_ELIMIT || (s == DP_ESOLVE && res->outcome == DP_LCP_INACCURATE))
        snprintf(r->error_pointer, sizeof r->error_pointer, "/solver");
    if (s == DP_ELIMIT)
        return dp_run_fail(r, s, "Lemke's method took its limit of %zu pivots on %s without ending", res->pivots, when);
    if (s == DP_ESOLVE && res->outcome == DP_LCP_INACCURATE)
        return dp_run_fail(r, s, "Lemke's method ended %s on a basis whose answer fails its check (relative "
                           "residual %.3g): the step's matrix is too ill-conditioned for the rounding", when, res->residual);
    if (s == DP_ESOLVE)
        return dp_run_fail(r, s, "%s has no solution Lemke's method can find (a ray: the step's matrix is neither "
                           "a P-matrix nor copositive-plus here)", when);
    if (s == DP_ENONFINITE)
        return dp_run_fail(r, s, "the LCP of %s left the finite numbers", when);
    return dp_run_fail(r, s, "%s failed (%s)", when, dp_strerror(s));
}

static int lcs_run_init(dp_run *r)
{
    const dp_lcs_model *lm = r->spec.lcs;
    struct dp_lcs_run *lr = calloc(1, sizeof *lr);
    if (lr == NULL)
        return DP_ENOMEM;
    r->state = lr;
    size_t n = lm->n, m = lm->m, k = n > m ? n : m;
    lr->n = n, lr->m = m, lr->width = n + 2 * m;
    lr->x = malloc(n * sizeof *lr->x), lr->u = malloc(m * sizeof *lr->u), lr->w = malloc(m * sizeof *lr->w);
    lr->final_row = malloc(lr->width * sizeof *lr->final_row), lr->index = malloc(k * sizeof *lr->index);
    lr->p = malloc(n * sizeof *lr->p), lr->row = malloc(lr->width * sizeof *lr->row);
    lr->slots.width = lr->width;
    if (!lr->x || !lr->u || !lr->w || !lr->p || !lr->final_row || !lr->row || !lr->index ||
        dp_row_queue_init(&lr->queue, lr->width, QCAP0) != DP_OK)
        return DP_ENOMEM;
    for (size_t i = 0; i < k; i++)
        lr->index[i] = i;
    memcpy(lr->x, lm->x0, n * sizeof *lr->x);
    dp_lcs sys = dp_lcs_model_system(lm);
    int s;
    const char *where, *why;
    lr->step = dp_lcs_stepper_alloc_why(&sys, r->h, r->spec.solver.theta, &s, &where, &why);
    if (lr->step == NULL)
        return setup_failed(r, s, where, "the θ-step could not be set up: %s", why);
    double hl = r->spec.solver.t_end - (double)(r->nsteps - 1) * r->h;
    if (fabs(hl - r->h) > 1e-12 * r->h && hl > 0) {
        lr->last = dp_lcs_stepper_alloc_why(&sys, hl, r->spec.solver.theta, &s, &where, &why);
        if (lr->last == NULL)
            return setup_failed(r, s, where, "the last, shorter step could not be set up: %s", why);
    }
    if (r->spec.solver.events == DP_EVENTS_LOCATE) {
        lr->locate = dp_lcs_locator_alloc(&sys, lm->pf, r->h, r->spec.solver.theta, &s);
        if (lr->locate == NULL)
            return setup_failed(r, s, "", "the location of mode changes could not be set up: %s", dp_strerror(s));
    }
    declare_columns(lr);
    r->cols = &lr->cols;
    r->cur.t = 0;
    return DP_OK;
}

static dp_row fill_row(const struct dp_lcs_run *lr, double t, double *d)
{
    memcpy(d, lr->x, lr->n * sizeof *d);
    memcpy(d + lr->n, lr->u, lr->m * sizeof *d);
    memcpy(d + lr->n + lr->m, lr->w, lr->m * sizeof *d);
    return (dp_row){ .t = t, .val = d };
}

/* Makes the block's row slots (as many as its records, within ROW_BUDGET numbers) and moves waiting records in. */
static int reserve_rows(dp_run *r, struct dp_lcs_run *lr)
{
    size_t want = r->out_cap, fit = ROW_BUDGET / lr->width;
    if (want > fit)
        want = fit ? fit : 1;
    if (dp_row_slots_reserve(&lr->slots, want) != DP_OK)
        return DP_ENOMEM;
    dp_row_queue_flush(&lr->queue, r, &lr->slots);
    return DP_OK;
}

/* A record into the block, or into the queue when the block is full or records already wait (so that they
 * keep their order); row: a row's numbers (NULL for an event). */
static int put_record(dp_run *r, struct dp_lcs_run *lr, dp_record *rec, const double *row)
{
    double *slot = NULL;
    if (!dp_row_queue_waiting(&lr->queue) && r->out_n < r->out_cap && (row == NULL || (slot = dp_row_slots_take(&lr->slots)))) {
        if (slot) {
            memcpy(slot, row, lr->width * sizeof *slot);
            rec->u.row.val = slot;
        }
        r->out[r->out_n++] = *rec;
        return DP_OK;
    }
    return dp_row_queue_push(&lr->queue, rec, row);
}

/* A row of the current state. */
static int emit_row(dp_run *r, struct dp_lcs_run *lr)
{
    r->countdown = r->spec.output.every;
    if (!r->spec.output.samples)
        return DP_OK;
    dp_record rec = { .type = DP_RECORD_ROW };
    rec.u.row = fill_row(lr, r->cur.t, lr->row);
    r->sum.samples++;
    return put_record(r, lr, &rec, lr->row);
}

/* The mode changes the last located step found, as events (counted, and handed out if events are wanted). */
static int emit_events(dp_run *r, struct dp_lcs_run *lr)
{
    size_t k;
    const dp_lcs_event *ev = dp_lcs_located_events(lr->locate, &k);
    r->sum.events += k;
    r->sum.iterations = dp_lcs_locator_substeps(lr->locate);
    for (size_t i = 0; i < k && r->spec.output.events; i++) {
        dp_record rec = { .type = DP_RECORD_EVENT };
        rec.u.event = (dp_event){ .kind = ev[i].on ? DP_EVENT_ON : DP_EVENT_OFF, .t = ev[i].t, .x = ev[i].u,
                                  .v = ev[i].w, .element = ev[i].component, .mode = ev[i].mode };
        if (put_record(r, lr, &rec, NULL) != DP_OK)
            return DP_ENOMEM;
    }
    return DP_OK;
}

static int block_full(const dp_run *r, const struct dp_lcs_run *lr)
{
    return r->out_n >= r->out_cap || lr->slots.used >= lr->slots.cap || dp_row_queue_waiting(&lr->queue);
}

static int state_finite(const struct dp_lcs_run *lr)
{
    for (size_t i = 0; i < lr->n; i++)
        if (!(fabs(lr->x[i]) < 1e300))
            return 0;
    return 1;
}

/* p(t_n + θh) = the constant part plus each forcing at the step's θ-point (the θ-method's own point). */
static void set_offsets(const dp_run *r, struct dp_lcs_run *lr, dp_lcs_stepper *st)
{
    const dp_lcs_model *lm = r->spec.lcs;
    double h = dp_run_step_length(r), t = (double)r->n * r->h + r->spec.solver.theta * h;
    for (size_t i = 0; i < lr->n; i++)
        lr->p[i] = lm->p[i] + dp_forcing_eval(&lm->pf[i], t);
    dp_lcs_stepper_set_p(st, lr->p);
}

static int lcs_run_advance(dp_run *r)
{
    struct dp_lcs_run *lr = r->state;
    if (reserve_rows(r, lr) != DP_OK)
        return dp_run_fail(r, DP_ENOMEM, "out of memory for the rows of a block");
    if (!lr->started) {
        dp_lcs sys = dp_lcs_model_system(r->spec.lcs);
        const dp_stop stop = { r->stop, r->stop_ctx };
        dp_lcp_result res;
        int s = initial_algebraic(lr, &sys, &res, &stop);
        if (s == DP_ESOLVE && res.outcome == DP_LCP_RAY)
            return dp_run_fail(r, s, "the laws admit no u at the initial state");
        if (s != DP_OK)
            return step_failed(r, s, &res, "the algebraic part at t = 0");
        lr->started = 1;
        if (emit_row(r, lr) != DP_OK)
            return dp_run_fail(r, DP_ENOMEM, "out of memory for the records of a block");
    }
    /* At most about 2^24 flops per call, so that a front end regains control (deadlines, cancellation) even
     * when samples are off and a step is a large LCP: the caller then gets DP_MORE with fewer records. */
    double per_step = (double)(lr->n * lr->n + 4 * lr->m * lr->m * lr->m) + 1;
    size_t budget = per_step > 16777216.0 ? 1 : (size_t)(16777216.0 / per_step);
    while (r->n < r->nsteps && !block_full(r, lr) && budget-- > 0) {
        if (dp_run_stopped(r, dp_run_work(r))) {
            if (r->status != DP_OK)
                return r->status;
            break; /* a yield: the block so far, the run goes on at the next call */
        }
        dp_lcs_stepper *st = r->n + 1 == r->nsteps && lr->last ? lr->last : lr->step;
        if (r->spec.lcs->pf)
            set_offsets(r, lr, st);
        dp_lcp_result res;
        const dp_stop stop = { r->stop, r->stop_ctx }; /* a yield (< 0) inside a step waits for its end */
        unsigned long long sub = r->sum.iterations;
        int s = lr->locate ? dp_lcs_step_located(lr->locate, st, (double)r->n * r->h, dp_run_step_length(r), lr->x,
                                                 lr->u, lr->w, &res, &stop)
                           : dp_lcs_step_until(st, lr->x, lr->u, lr->w, &res, &stop);
        if (s != DP_OK) {
            char when[64];
            snprintf(when, sizeof when, "the step from t = %.17g", r->cur.t);
            return step_failed(r, s, &res, when);
        }
        r->n++;
        r->cur.t = r->n == r->nsteps ? r->spec.solver.t_end : (double)r->n * r->h;
        if (!state_finite(lr))
            return dp_run_fail(r, DP_ENONFINITE, "the state left the finite numbers at t = %.17g", r->cur.t);
        if ((lr->locate && emit_events(r, lr) != DP_OK) ||
            ((--r->countdown <= 0 || r->n == r->nsteps) && emit_row(r, lr) != DP_OK))
            return dp_run_fail(r, DP_ENOMEM, "out of memory for the records of a block");
        sub = r->sum.iterations - sub;     /* a located step's sub-steps count against the budget too */
        budget -= sub < budget ? sub : budget;
    }
    r->sum.steps = r->n;
    r->sum.final_row = fill_row(lr, r->cur.t, lr->final_row);
    if (r->n >= r->nsteps)
        r->finished = 1;
    return DP_OK;
}

static int lcs_run_pending(const dp_run *r)
{
    const struct dp_lcs_run *lr = r->state;
    return dp_row_queue_waiting(&lr->queue);
}

/* "locate": mode changes split their steps and are events; "none": plain θ-steps, no events. */
static const char *lcs_events_mode(const dp_spec *s)
{
    return s->solver.events == DP_EVENTS_NONE ? "none" : "locate";
}

const dp_run_type dp_run_lcs = {
    .name = "stick-slip", .events_mode = lcs_events_mode, .check = dp_lcs_check, .init = lcs_run_init,
    .advance = lcs_run_advance, .pending = lcs_run_pending, .free = lcs_run_free,
};
