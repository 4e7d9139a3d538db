/* src/core/runs/run.c - the pull iterator every run is driven through (docs/architecture.md, "Solvers are
 * iterators"): one allocation per run, the run type chosen once from the table (run_table.c), called once
 * per block, not once per step. It knows no solver by name: what differs between them is in their type. */
#include <stdlib.h>

#include "record/sink.h"
#include "runs/run_table.h"

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
    r->type = dp_run_type_of(spec);
    s = r->type->init(r);
    if (s != DP_OK) {
        dp_errors_add(errs, r->error_pointer, "%s", r->error[0] ? r->error : dp_strerror(s));
        dp_run_free(r);
        *status = s;
        return NULL;
    }
    r->sum.final = r->cur;
    *status = DP_OK;
    return r;
}

static int type_pending(const dp_run *r)
{
    return r->type->pending != NULL && r->type->pending(r);
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
    if (dp_run_room(r) || (type_pending(r) && r->status == DP_OK)) {
        int s = r->type->advance(r);
        if (s < 0 && r->status == DP_OK)
            dp_run_fail(r, s, "%s", dp_strerror(s));
    }
    *n = r->out_n;
    r->out = NULL;
    r->sum.final = r->cur;
    if (r->type->block && r->type->block(r, buf, *n) != DP_OK)
        dp_run_fail(r, DP_ENOMEM, "out of memory for the rows of a block");
    if (r->status != DP_OK)
        return r->status;
    if (r->finished && r->npending == 0 && !type_pending(r))
        return DP_DONE;
    return DP_MORE;
}

void dp_run_set_stop(dp_run *r, dp_stop_fn stop, void *ctx)
{
    r->stop = stop;
    r->stop_ctx = ctx;
    r->poll_at = 0; /* asked at the next poll */
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

const dp_columns *dp_run_columns(const dp_run *r)
{
    return r->cols;
}

const char *dp_run_error(const dp_run *r)
{
    return r->error;
}

void dp_run_free(dp_run *r)
{
    if (r == NULL)
        return;
    if (r->type && r->type->free)
        r->type->free(r->state);
    dp_spec_clear(&r->spec);
    free(r);
}
