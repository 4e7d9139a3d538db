/* src/http/convergence.c - POST /v1/convergence: the convergence study of the regularized solver
 * (regularized.h, docs/regularized.md), the JSON `dashpot convergence` prints.
 *
 * The body is a simulation spec whose solver is "regularized" with "n" (or "k") a list; the study runs it
 * once per entry and an exact reference in lockstep and answers one JSON object. It is computed in one go
 * on the worker thread, so it is held to the limits of a stream: --max-steps per run (the reference's
 * steps included), and --max-wall seconds, checked between blocks through dp_convergence_study_until
 * (then 503 /problems/timeout), as is the end of the shutdown grace period (503 /problems/shutting-down).
 * The reference step is chosen automatically, as the CLI does without --ref-dt.
 */
#include <stdio.h>
#include <stdlib.h>

#include "dashpot/json.h"
#include "dashpot/regularized.h"
#include "http.h"

typedef struct watch {
    server *s;
    double deadline;   /* monotonic seconds */
    int why;           /* 1: wall time, 2: shutting down */
} watch;

/* Asked before every block of every run: a clock read costs ~20 ns against a block's microseconds. */
static int stop(void *ctx)
{
    watch *w = ctx;
    if (atomic_load_explicit(&w->s->abort_streams, memory_order_relaxed))
        w->why = 2;
    else if (now_seconds() > w->deadline)
        w->why = 1;
    return w->why;
}

static enum MHD_Result study_failed(struct MHD_Connection *c, request *r, int s, const watch *w,
                                    const dp_errors *errs)
{
    const char *why = errs->n ? errs->item[0].message : NULL;
    if (s == DP_ECANCEL && w->why == 2)
        return respond_problem(c, r, 503, "/problems/shutting-down", "the server is shutting down", NULL, NULL);
    if (s == DP_ECANCEL) {
        char detail[96];
        snprintf(detail, sizeof detail, "the study exceeded the wall-time limit of %g s", r->srv->cfg.max_wall);
        return respond_status(c, r, s, detail, NULL);
    }
    if (s == DP_ESOLVE || s == DP_ENONFINITE || s == DP_ENOMEM)
        return respond_status(c, r, s, why, NULL);
    return respond_status(c, r, s, s == DP_ESYNTAX ? why : NULL, errs);
}

enum MHD_Result handle_convergence(struct MHD_Connection *c, request *r)
{
    static const char *const offers[] = { "application/json" };
    if (negotiate(MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT), offers, 1) < 0)
        return respond_problem(c, r, 406, NULL, "this route answers application/json", NULL, NULL);
    server *srv = r->srv;
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(r->body.data ? r->body.data : "", r->body.len, srv->cfg.max_steps, &spec, &errs);
    dp_convergence *study = s == DP_OK ? malloc(sizeof *study) : NULL;
    if (s == DP_OK && study == NULL)
        s = DP_ENOMEM;
    watch w = { srv, r->t_start + srv->cfg.max_wall, 0 };
    if (s == DP_OK) {
        atomic_fetch_add(&srv->m.studies_in_flight, 1);
        s = dp_convergence_study_until(&spec, srv->cfg.max_steps, 0, stop, &w, study, &errs);
        atomic_fetch_sub(&srv->m.studies_in_flight, 1);
    }
    dp_spec_clear(&spec);
    dp_buf out = { 0 };
    if (s == DP_OK && dp_convergence_json(study, &out) != DP_OK)
        s = DP_ENOMEM;
    free(study);
    if (s != DP_OK) {
        dp_buf_free(&out);
        return study_failed(c, r, s, &w, &errs);
    }
    return respond_buffer(c, r, 200, "application/json", &out);
}
