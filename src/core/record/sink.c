/* src/core/record/sink.c - where every solver's records go: samples decimated by output.every, events,
 * the failure of a run and the stop hook's poll. It is below the solvers so that they can call it while the
 * run-type table above them calls them (no circle); records are written straight into the caller's block,
 * the few that do not fit parked in a fixed queue (DP_RUN_PENDING). */
#include <stdarg.h>
#include <stdio.h>

#include "record/sink.h"

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
