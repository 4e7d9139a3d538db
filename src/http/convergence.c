/* src/http/convergence.c - POST /v1/convergence: the convergence study of the regularized solver
 * (regularized.h, docs/regularized.md), the JSON `dashpot convergence` prints.
 *
 * The body is a simulation spec whose solver is "regularized" with "n" (or "k") a list; the study runs it
 * once per entry and an exact reference in lockstep and answers one JSON object. It is computed in one go
 * on a compute thread (jobs.c), so it is held to the limits of a stream: --max-steps per run (the
 * reference's steps included), and the job's stop hook, asked between blocks through
 * dp_convergence_study_until: --max-wall (503 /problems/timeout), the end of the shutdown grace period
 * (503 /problems/shutting-down), the client's hang-up. The reference step is chosen automatically, as the
 * CLI does without --ref-dt.
 */
#include <stdlib.h>

#include "dashpot/json.h"
#include "dashpot/regularized.h"
#include "http.h"

static int study_work(request *r, int arg, const dp_stop *stop, dp_buf *out, dp_errors *errs)
{
    (void)arg;
    server *srv = r->srv;
    dp_spec spec;
    dp_spec_init(&spec);
    int s = dp_spec_parse(r->body.data ? r->body.data : "", r->body.len, srv->cfg.max_steps, &spec, errs);
    dp_convergence *study = s == DP_OK ? malloc(sizeof *study) : NULL;
    if (s == DP_OK && study == NULL)
        s = DP_ENOMEM;
    if (s == DP_OK) {
        atomic_fetch_add(&srv->m.studies_in_flight, 1);
        s = dp_convergence_study_until(&spec, srv->cfg.max_steps, 0, stop->fn, stop->ctx, study, errs);
        atomic_fetch_sub(&srv->m.studies_in_flight, 1);
    }
    dp_spec_clear(&spec);
    if (s == DP_OK && dp_convergence_json(study, out) != DP_OK)
        s = DP_ENOMEM;
    free(study);
    return s;
}

/* A run of the study that failed says why in its detail; a bad spec lists its errors. */
static enum MHD_Result study_failed(struct MHD_Connection *c, request *r, int s, const dp_errors *errs)
{
    const char *why = errs->n ? errs->item[0].message : NULL;
    if (s == DP_ESOLVE || s == DP_ENONFINITE || s == DP_ENOMEM)
        return respond_status(c, r, s, why, NULL);
    return respond_status(c, r, s, s == DP_ESYNTAX ? why : NULL, errs);
}

static const job_route study_job = { study_work, "the study", study_failed };

enum MHD_Result handle_convergence(struct MHD_Connection *c, request *r)
{
    return job_submit_json(c, r, &study_job);
}
