/* src/json/sweep_exec.c - a sweep's runs one block at a time, and the lines that answer them (sweep_json.h).
 *
 * The daemon computes a sweep in slices on its worker (as a simulate stream) and the CLI on a few threads;
 * both drive the same executor: take the next run of the document, parse its substituted base, run it to its
 * features block by block (the stop hook polled inside blocks), write its line. A run that fails is a line
 * with its problem and the sweep goes on; a stop (deadline, hang-up, shutdown) or a spent step budget ends it.
 */
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/json.h"
#include "dashpot/sweep_json.h"

static int put(dp_buf *b, const char *s)
{
    return dp_buf_append(b, s, strlen(s));
}

static int put_num(dp_buf *b, double x)
{
    char t[40];
    return dp_buf_append(b, t, dp_format_double(t, x));
}

static int put_size(dp_buf *b, const char *key, unsigned long long x)
{
    char t[96];
    int n = snprintf(t, sizeof t, "\"%s\":%llu", key, x);
    return dp_buf_append(b, t, (size_t)n);
}

static int put_values(dp_buf *b, const double *v, size_t n)
{
    int s = put(b, "[");
    for (size_t i = 0; i < n && s == DP_OK; i++) {
        s = i ? put(b, ",") : DP_OK;
        s = s ? s : put_num(b, v[i]);
    }
    return s ? s : put(b, "]");
}

/* {"type":"run","index":i,"values":[...] */
static int run_head(const dp_sweep_doc *d, size_t index, dp_buf *b)
{
    const dp_sweep_grid *g = dp_sweep_doc_grid(d);
    double v[DP_SWEEP_MAX_AXES];
    dp_sweep_grid_values(g, index, v);
    int s = put(b, "{\"type\":\"run\",");
    s = s ? s : put_size(b, "index", index);
    s = s ? s : put(b, ",\"values\":");
    return s ? s : put_values(b, v, g->naxes);
}

static int put_features(const dp_features *f, dp_buf *b)
{
    int s = put(b, ",\"features\":{"), first = 1, nulls = 0;
    for (int k = 0; k < DP_FEATURE_COUNT && s == DP_OK; k++) {
        if (!(f->plan.features & (1u << k)))
            continue;
        s = put(b, first ? "\"" : ",\"");
        s = s ? s : put(b, dp_feature_name(k));
        s = s ? s : put(b, "\":");
        s = s ? s : f->out.known[k] ? put_num(b, f->out.value[k]) : put(b, "null");
        nulls += !f->out.known[k];
        first = 0;
    }
    s = s ? s : put(b, "}");
    if (nulls == 0 || s != DP_OK)
        return s;
    s = put(b, ",\"null\":{");
    first = 1;
    for (int k = 0; k < DP_FEATURE_COUNT && s == DP_OK; k++) {
        if (!(f->plan.features & (1u << k)) || f->out.known[k])
            continue;
        s = put(b, first ? "\"" : ",\"");
        s = s ? s : put(b, dp_feature_name(k));
        s = s ? s : put(b, "\":");
        s = s ? s : dp_json_quote(b, f->out.why[k] ? f->out.why[k] : "unknown");
        first = 0;
    }
    return s ? s : put(b, "}");
}

static int put_section(const dp_features *f, dp_buf *b)
{
    int s = put(b, ",\"section\":[");
    for (size_t i = 0; i < f->nsection && s == DP_OK; i++) {
        double p[3] = { f->section[i].t, f->section[i].x, f->section[i].v };
        s = i ? put(b, ",") : DP_OK;
        s = s ? s : put_values(b, p, 3);
    }
    return s ? s : put(b, "]");
}

int dp_sweep_run_json(const dp_sweep_doc *d, size_t index, const dp_features *f, dp_buf *b)
{
    int s = run_head(d, index, b);
    s = s ? s : put_features(f, b);
    if (s == DP_OK && f->plan.section != DP_SECTION_NONE)
        s = put_section(f, b);
    return s ? s : put(b, "}");
}

int dp_sweep_failed_json(const dp_sweep_doc *d, size_t index, int status, const char *detail,
                         const dp_errors *errs, dp_buf *b)
{
    char t[64];
    snprintf(t, sizeof t, ",\"status\":%d,\"title\":", dp_status_http(status));
    int s = run_head(d, index, b);
    s = s ? s : put(b, t);
    s = s ? s : dp_json_quote(b, dp_strerror(status));
    s = s ? s : put(b, ",\"detail\":");
    s = s ? s : dp_json_quote(b, detail && *detail ? detail : errs && errs->n ? "the run's document is invalid"
                                                                          : dp_strerror(status));
    if (s == DP_OK && errs && errs->n) {
        s = put(b, ",\"errors\":[");
        for (size_t i = 0; i < errs->n && s == DP_OK; i++) {
            s = put(b, i ? ",{\"pointer\":" : "{\"pointer\":");
            s = s ? s : dp_json_quote(b, errs->item[i].pointer);
            s = s ? s : put(b, ",\"detail\":");
            s = s ? s : dp_json_quote(b, errs->item[i].message);
            s = s ? s : put(b, "}");
        }
        s = s ? s : put(b, "]");
    }
    return s ? s : put(b, "}");
}

static int put_record(const dp_sweep_plan *p, dp_buf *b)
{
    static const char *const events[] = { "", "stick", "slip", "yield", "unload", "impact" };
    int s = put(b, ",\"record\":{\"after\":");
    s = s ? s : put_num(b, p->after);
    s = s ? s : put(b, ",\"features\":[");
    for (int k = 0, first = 1; k < DP_FEATURE_COUNT && s == DP_OK; k++)
        if (p->features & (1u << k)) {
            s = put(b, first ? "\"" : ",\"");
            s = s ? s : put(b, dp_feature_name(k));
            s = s ? s : put(b, "\"");
            first = 0;
        }
    s = s ? s : put(b, "]");
    if (s == DP_OK && p->section == DP_SECTION_PERIOD) {
        s = put(b, ",\"section\":{\"period\":");
        s = s ? s : put_num(b, p->section_period);
    } else if (s == DP_OK && p->section == DP_SECTION_EVENT) {
        s = put(b, ",\"section\":{\"event\":\"");
        s = s ? s : put(b, events[p->section_event]);
        s = s ? s : put(b, "\"");
    }
    if (s == DP_OK && p->section != DP_SECTION_NONE) {
        s = put(b, ",");
        s = s ? s : put_size(b, "count", p->section_count);
        s = s ? s : put(b, "}");
    }
    s = s ? s : put(b, ",");
    s = s ? s : put_size(b, "node", p->node);
    s = s ? s : put(b, ",");
    s = s ? s : put_size(b, "element", p->element);
    return s ? s : put(b, "}");
}

int dp_sweep_meta_json(const dp_sweep_doc *d, double max_steps, dp_buf *b)
{
    const dp_sweep_grid *g = dp_sweep_doc_grid(d);
    int s = put(b, "{\"type\":\"meta\",\"version\":\"" DP_VERSION "\",");
    s = s ? s : put_size(b, "runs", dp_sweep_grid_runs(g));
    s = s ? s : put(b, ",");
    s = s ? s : put_size(b, "selected", dp_sweep_doc_count(d));
    s = s ? s : put(b, ",\"order\":\"row-major: index = i0 * n1 + i1, the last axis fastest\",\"axes\":[");
    for (size_t k = 0; k < g->naxes && s == DP_OK; k++) {
        s = put(b, k ? ",{\"pointer\":" : "{\"pointer\":");
        s = s ? s : dp_json_quote(b, g->axis[k].pointer);
        s = s ? s : put(b, ",\"values\":");
        s = s ? s : put_values(b, g->axis[k].values, g->axis[k].n);
        s = s ? s : put(b, "}");
    }
    s = s ? s : put(b, "]");
    s = s ? s : put_record(dp_sweep_doc_plan(d), b);
    s = s ? s : put(b, ",\"limits\":{");
    s = s ? s : put_size(b, "runs", DP_SWEEP_MAX_RUNS);
    s = s ? s : put(b, ",\"steps_per_run\":");
    s = s ? s : put_num(b, max_steps);
    s = s ? s : put(b, ",\"steps\":");
    s = s ? s : put_num(b, max_steps * DP_SWEEP_STEP_FACTOR);
    return s ? s : put(b, "}}");
}

int dp_sweep_summary_json(size_t runs, const dp_sweep_totals *t, dp_buf *b)
{
    int s = put(b, "{\"type\":\"summary\",");
    s = s ? s : put_size(b, "runs", runs);
    s = s ? s : put(b, ",");
    s = s ? s : put_size(b, "completed", t->completed);
    s = s ? s : put(b, ",");
    s = s ? s : put_size(b, "failed", t->failed);
    s = s ? s : put(b, ",");
    s = s ? s : put_size(b, "steps", t->steps);
    return s ? s : put(b, "}");
}

/* ---- the executor ---- */

struct dp_sweep_exec {
    const dp_sweep_doc *doc;
    size_t k, stride;
    double max_steps;
    _Atomic unsigned long long *budget;
    double budget_max;
    dp_sweep_one *one;   /* the run under way, NULL between runs */
    size_t index;
    dp_stop_fn stop;
    void *ctx;
    dp_sweep_totals tot;
    char why[DP_MESSAGE_MAX];
};

dp_sweep_exec *dp_sweep_exec_new(const dp_sweep_doc *doc, size_t first, size_t stride, double max_steps,
                                 _Atomic unsigned long long *budget, double budget_max)
{
    dp_sweep_exec *x = calloc(1, sizeof *x);
    if (x == NULL)
        return NULL;
    x->doc = doc;
    x->k = first;
    x->stride = stride ? stride : 1;
    x->max_steps = max_steps;
    x->budget = budget;
    x->budget_max = budget_max;
    return x;
}

void dp_sweep_exec_set_stop(dp_sweep_exec *x, dp_stop_fn stop, void *ctx)
{
    x->stop = stop;
    x->ctx = ctx;
    if (x->one)
        dp_sweep_one_set_stop(x->one, stop, ctx);
}

/* The run's line is written; on to the next run. */
static int run_ended(dp_sweep_exec *x, int *line)
{
    dp_sweep_one_free(x->one);
    x->one = NULL;
    x->k += x->stride;
    *line = 1;
    return DP_MORE;
}

/* Parses the next run and starts it; a run that cannot start is its failed line. */
static int start(dp_sweep_exec *x, dp_buf *out, int *line, const char **why)
{
    size_t index = dp_sweep_doc_index(x->doc, x->k);
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_sweep_doc_spec(x->doc, index, x->max_steps, &spec, &errs);
    if (s == DP_OK && x->budget) {
        unsigned long long steps = (unsigned long long)dp_spec_steps(&spec);
        if ((double)(atomic_fetch_add(x->budget, steps) + steps) > x->budget_max) {
            dp_spec_clear(&spec);
            snprintf(x->why, sizeof x->why, "the sweep's runs ask for more than %.0f steps in all (%g per run "
                     "times %g)", x->budget_max, x->max_steps, DP_SWEEP_STEP_FACTOR);
            *why = x->why;
            return DP_ELIMIT;
        }
    }
    if (s == DP_OK)
        x->one = dp_sweep_one_alloc(&spec, dp_sweep_doc_plan(x->doc), x->max_steps, "/record", &errs, &s);
    dp_spec_clear(&spec);
    if (s == DP_ENOMEM)
        return *why = dp_strerror(s), s;
    if (s != DP_OK) {
        x->tot.failed++;
        if (dp_sweep_failed_json(x->doc, index, s, s == DP_ESYNTAX && errs.n ? errs.item[0].message : NULL,
                                 s == DP_ESYNTAX ? NULL : &errs, out) != DP_OK)
            return *why = dp_strerror(DP_ENOMEM), DP_ENOMEM;
        x->k += x->stride;
        *line = 1;
        return DP_MORE;
    }
    x->index = index;
    dp_sweep_one_set_stop(x->one, x->stop, x->ctx);
    return DP_MORE;
}

int dp_sweep_exec_next(dp_sweep_exec *x, dp_buf *out, int *line, const char **why)
{
    *line = 0;
    *why = NULL;
    if (x->one == NULL) {
        if (x->k >= dp_sweep_doc_count(x->doc))
            return DP_DONE;
        int s = start(x, out, line, why);
        if (s != DP_MORE || *line)
            return s;
    }
    int s = dp_sweep_one_next(x->one);
    if (s == DP_MORE)
        return DP_MORE;
    if (s == DP_ECANCEL) {
        snprintf(x->why, sizeof x->why, "%s", dp_sweep_one_error(x->one));
        *why = x->why;
        return DP_ECANCEL;
    }
    int w;
    if (s == DP_DONE) {
        x->tot.completed++;
        x->tot.steps += dp_sweep_one_summary(x->one)->steps;
        w = dp_sweep_run_json(x->doc, x->index, dp_sweep_one_features(x->one), out);
    } else {
        x->tot.failed++;
        w = dp_sweep_failed_json(x->doc, x->index, s, dp_sweep_one_error(x->one), NULL, out);
    }
    if (w != DP_OK)
        return *why = dp_strerror(DP_ENOMEM), DP_ENOMEM;
    return run_ended(x, line);
}

const dp_sweep_totals *dp_sweep_exec_totals(const dp_sweep_exec *x)
{
    return &x->tot;
}

void dp_sweep_exec_free(dp_sweep_exec *x)
{
    if (x == NULL)
        return;
    dp_sweep_one_free(x->one);
    free(x);
}
