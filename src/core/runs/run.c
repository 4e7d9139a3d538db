/* src/core/run.c - the pull iterator every solver is driven through (architecture.md, "Solvers are
 * iterators"): one allocation per run, records written straight into the caller's block, the few that do
 * not fit parked in a fixed queue. The solver is a type (dp_run_type, chosen once when the run is
 * allocated), called once per block, not once per step. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "record/run_internal.h"

void dp_run_emit(dp_run *r, const dp_record *rec)
{
    if (r->out_n < r->out_cap)
        r->out[r->out_n++] = *rec;
    else if (r->npending < DP_RUN_PENDING)
        r->pending[r->npending++] = *rec;
}

void dp_run_emit_sample(dp_run *r)
{
    r->countdown = r->spec.output.every;
    if (!r->spec.output.samples)
        return;
    dp_record rec = { .type = DP_RECORD_SAMPLE, .u.sample = r->cur };
    dp_run_emit(r, &rec);
    r->sum.samples++;
}

void dp_run_emit_event(dp_run *r, dp_event_kind kind, double t, double x, double v)
{
    r->sum.events++;
    if (!r->spec.output.events)
        return;
    dp_record rec = { .type = DP_RECORD_EVENT, .u.event = { .kind = kind, .t = t, .x = x, .v = v } };
    dp_run_emit(r, &rec);
}

int dp_run_fail(dp_run *r, int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->error, sizeof r->error, fmt, ap);
    va_end(ap);
    r->status = status;
    r->finished = 1;
    return status;
}

/* The solvers. The one-mass stick-slip solver's variants differ in their step only. */
static const dp_run_type lcs_type = { "lcs", dp_lcs_run_init, dp_lcs_run_advance };
static const dp_run_type right_hand_type = { "right-hand", dp_rh_run_init, dp_rh_run_advance };
static const dp_run_type network_type = { "network", dp_network_run_init, dp_network_run_advance };
static const dp_run_type analytic_type = { "analytic", dp_analytic_init, dp_analytic_advance };
static const dp_run_type regularized_type = { "regularized", dp_regularized_init, dp_regularized_advance };
static const dp_run_type newmark_type = { "newmark", dp_newmark_init, dp_newmark_advance };
static const dp_run_type thesis_type = { "thesis", dp_stick_slip_init, dp_thesis_advance };
static const dp_run_type stick_slip_type = { "stick-slip", dp_stick_slip_init, dp_stick_slip_advance };

/* The solver of a spec: its model's (LCS, right-hand, network), else the one-mass solver it names. */
static const dp_run_type *run_type(const dp_spec *spec)
{
    if (spec->lcs)
        return &lcs_type;
    if (spec->rh)
        return &right_hand_type;
    if (spec->net)
        return &network_type;
    switch (spec->solver.kind) {
    case DP_SOLVER_ANALYTIC: return &analytic_type;
    case DP_SOLVER_REGULARIZED: return &regularized_type;
    case DP_SOLVER_NEWMARK: return &newmark_type;
    default: return spec->solver.variant == DP_VARIANT_THESIS ? &thesis_type : &stick_slip_type;
    }
}

dp_run *dp_run_alloc(const dp_spec *spec, double max_steps, dp_errors *errs, int *status)
{
    int s = dp_spec_check(spec, max_steps, errs);
    if (s != DP_OK) {
        *status = s;
        return NULL;
    }
    dp_run *r = calloc(1, sizeof *r);
    if (r == NULL) {
        *status = DP_ENOMEM;
        return NULL;
    }
    if (dp_spec_copy(&r->spec, spec) != DP_OK) {
        dp_run_free(r);
        *status = DP_ENOMEM;
        return NULL;
    }
    r->h = spec->solver.dt;
    r->max_steps = max_steps > 0 && max_steps < DP_SPEC_MAX_STEPS ? max_steps : DP_SPEC_MAX_STEPS;
    r->nsteps = (unsigned long long)dp_spec_steps(spec);
    r->countdown = 1; /* the initial state is always a sample */
    r->type = run_type(spec);
    s = r->type->init(r);
    if (s != DP_OK) {
        dp_errors_add(errs, r->error_pointer, "%s", r->error[0] ? r->error : dp_strerror(s));
        dp_run_free(r);
        *status = s;
        return NULL;
    }
    if (dp_network_run_is_one_mass(r))  /* a network of one mass steps on the one-mass solver itself */
        r->type = &stick_slip_type;
    r->sum.final = r->cur;
    if ((r->net == NULL && r->lcs == NULL && r->rh == NULL) || dp_network_run_is_one_mass(r))
        dp_run_emit_state(r); /* queued in `pending`: no block yet */
    *status = DP_OK;
    return r;
}

int dp_run_next(dp_run *r, dp_record *buf, size_t cap, size_t *n)
{
    *n = 0;
    if (r == NULL || buf == NULL || cap == 0)
        return DP_EINVAL;
    r->out = buf;
    r->out_cap = cap;
    r->out_n = 0;
    while (r->ipending < r->npending && r->out_n < cap)
        buf[r->out_n++] = r->pending[r->ipending++];
    if (r->ipending == r->npending)
        r->npending = r->ipending = 0;
    if (dp_run_room(r) || (((r->net && dp_network_run_pending(r)) || dp_rh_run_pending(r)) && r->status == DP_OK)) {
        int s = r->type->advance(r);
        if (s < 0 && r->status == DP_OK)
            dp_run_fail(r, s, "%s", dp_strerror(s));
    }
    *n = r->out_n;
    r->out = NULL;
    r->sum.final = r->cur;
    if (r->net && dp_network_run_is_one_mass(r) && dp_network_one_mass_rows(r, buf, *n) != DP_OK)
        dp_run_fail(r, DP_ENOMEM, "out of memory for the rows of a block");
    if (r->status != DP_OK)
        return r->status;
    if (r->finished && r->npending == 0 && !(r->net && dp_network_run_pending(r)))
        return DP_DONE;
    return DP_MORE;
}

void dp_run_set_stop(dp_run *r, dp_stop_fn stop, void *ctx)
{
    r->stop = stop;
    r->stop_ctx = ctx;
    r->poll_at = 0; /* asked at the next poll */
}

int dp_run_poll_stop(dp_run *r, unsigned long long work)
{
    r->poll_at = work + DP_RUN_POLL_WORK;
    int v = r->stop(r->stop_ctx);
    if (v == 0)
        return 0;
    if (v < 0)
        return 1; /* yield: the solver returns with r->status still DP_OK, dp_run_next says DP_MORE */
    dp_run_fail(r, DP_ECANCEL, "the run was stopped at t = %.17g", r->cur.t);
    return 1;
}

const dp_summary *dp_run_summary(const dp_run *r)
{
    return &r->sum;
}

double dp_run_progress(const dp_run *r)
{
    double p = r->nsteps ? (double)r->n / (double)r->nsteps : 1;
    return p > 1 ? 1 : p;
}

const char *dp_run_error(const dp_run *r)
{
    return r->error;
}

void dp_run_free(dp_run *r)
{
    if (r == NULL)
        return;
    dp_regularized_free(r->reg);
    dp_network_run_free(r->net);
    dp_lcs_run_free(r->lcs);
    dp_nm_free(r->nm);
    dp_rh_run_free(r->rh);
    dp_spec_clear(&r->spec);
    free(r);
}
