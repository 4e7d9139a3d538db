/* src/core/studies/sweep_one.c - one run of a sweep driven to its features (sweep.h).
 *
 * The run is the lone simulate's run of the same spec (dp_run_alloc, dp_run_next), with only its output
 * changed: every step a sample, every event, every node and element written. Output decimation decides which
 * records are written, never how the solver steps, so the features are those of the lone run asked with
 * {"output": {"every": 1}}, bit for bit (tests/test_sweep.c); the records are reduced here block by block and
 * never kept, so a sweep's memory does not grow with its runs' length.
 */
#include <stdio.h>
#include <stdlib.h>

#include "dashpot/sweep.h"

/* Records per block: what a front end's stop hook and yield see between two looks. */
#define BLOCK 512

struct dp_sweep_one {
    dp_run *run;
    dp_features f;
    int done;
    dp_record recs[BLOCK];
};

/* The plan's node and element exist in the run's columns (networks). */
static int plan_fits(const dp_columns *cols, const dp_sweep_plan *plan, const char *at, dp_errors *errs)
{
    if (cols == NULL)
        return 1;
    int ok = 1;
    char p[DP_POINTER_MAX];
    if (plan->node >= cols->nodes) {
        snprintf(p, sizeof p, "%.140s/node", at);
        dp_errors_add(errs, p, "the model has %zu node(s); node %zu does not exist", cols->nodes, plan->node);
        ok = 0;
    }
    if (plan->element >= cols->elements && cols->elements > 0) {
        snprintf(p, sizeof p, "%.140s/element", at);
        dp_errors_add(errs, p, "the model has %zu element(s); element %zu does not exist", cols->elements,
                      plan->element);
        ok = 0;
    }
    return ok;
}

dp_sweep_one *dp_sweep_one_alloc(const dp_spec *spec, const dp_sweep_plan *plan, double max_steps,
                                 const char *plan_pointer, dp_errors *errs, int *status)
{
    dp_spec s = *spec; /* shallow: the run deep-copies what it keeps; only the output differs */
    s.output.every = 1;
    s.output.samples = 1;
    s.output.events = 1;
    s.output.nodes = s.output.elements = NULL;
    s.output.nnodes = s.output.nelements = 0;
    dp_sweep_one *o = malloc(sizeof *o);
    if (o == NULL) {
        *status = DP_ENOMEM;
        return NULL;
    }
    o->done = 0;
    o->run = dp_run_alloc(&s, max_steps, errs, status);
    if (o->run == NULL) {
        free(o);
        return NULL;
    }
    if (!plan_fits(dp_run_columns(o->run), plan, plan_pointer, errs)) {
        dp_run_free(o->run);
        free(o);
        *status = DP_EINVAL;
        return NULL;
    }
    if (dp_features_init(&o->f, plan, dp_run_columns(o->run)) != DP_OK) {
        dp_run_free(o->run);
        free(o);
        *status = DP_ENOMEM;
        return NULL;
    }
    *status = DP_OK;
    return o;
}

void dp_sweep_one_set_stop(dp_sweep_one *o, dp_stop_fn stop, void *ctx)
{
    dp_run_set_stop(o->run, stop, ctx);
}

int dp_sweep_one_next(dp_sweep_one *o)
{
    if (o->done)
        return DP_DONE;
    size_t n = 0;
    int s = dp_run_next(o->run, o->recs, BLOCK, &n);
    for (size_t i = 0; i < n; i++)
        dp_features_add(&o->f, &o->recs[i]);
    if (s == DP_DONE) {
        dp_features_finish(&o->f);
        o->done = 1;
    }
    return s;
}

const dp_features *dp_sweep_one_features(const dp_sweep_one *o)
{
    return &o->f;
}

const dp_summary *dp_sweep_one_summary(const dp_sweep_one *o)
{
    return dp_run_summary(o->run);
}

const char *dp_sweep_one_error(const dp_sweep_one *o)
{
    return dp_run_error(o->run);
}

void dp_sweep_one_free(dp_sweep_one *o)
{
    if (o == NULL)
        return;
    dp_features_clear(&o->f);
    dp_run_free(o->run);
    free(o);
}
