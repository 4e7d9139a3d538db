/* src/http/modes.c - POST /v1/modes and POST /v1/response: the linear analysis of a network (natural modes,
 * damped eigenvalues; the receptance curve with its resonances and antiresonances), docs/modes.md.
 *
 * The work is dp_modes_respond_until / dp_response_respond_until (src/json/modes_json.c), shared with
 * `dashpot modes` and `dashpot response`; it runs on a compute thread (jobs.c) under the daemon's stop hook
 * (--max-wall, shutdown, hang-up): 2000 masses are seconds of eigensolver. This file only negotiates the
 * media type. The answer is computed whole (a curve is at most 10^5 points, a few MB), so it is not
 * streamed; the response curve is offered as JSON, NDJSON or CSV by Accept, as /v1/simulate offers them.
 */
#include "dashpot/modes_json.h"
#include "http.h"

static int modes_work(request *r, int arg, const dp_stop *stop, dp_buf *out, dp_errors *errs)
{
    (void)arg;
    return dp_modes_respond_until(r->body.data ? r->body.data : "", r->body.len, stop, out, errs);
}

static int response_work(request *r, int format, const dp_stop *stop, dp_buf *out, dp_errors *errs)
{
    return dp_response_respond_until(r->body.data ? r->body.data : "", r->body.len, format, stop, out, errs);
}

static const job_route modes_job = { modes_work, "the modal analysis", NULL };
static const job_route response_job = { response_work, "the response curve", NULL };

enum MHD_Result handle_modes(struct MHD_Connection *c, request *r)
{
    return job_submit_json(c, r, &modes_job);
}

enum MHD_Result handle_response(struct MHD_Connection *c, request *r)
{
    static const char *const offers[] = { "application/json", "application/x-ndjson", "text/csv" };
    static const int formats[] = { DP_FORMAT_JSON, DP_FORMAT_NDJSON, DP_FORMAT_CSV };
    int f = negotiate(MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT), offers, 3);
    if (f < 0)
        return respond_problem(c, r, 406, NULL, "this route answers application/json, application/x-ndjson or text/csv",
                               NULL, NULL);
    return job_submit(c, r, &response_job, formats[f], dp_format_content_type((dp_format)formats[f]));
}
