/* src/http/lcp.c - POST /v1/lcp: one linear complementarity problem w = Mz + q, 0 <= z ⊥ w >= 0, solved by
 * Lemke's method, its solutions enumerated when it is small, and the uniqueness theory (docs/lcs.md).
 *
 * The work is dp_lcp_respond_until (src/json/lcp_json.c), shared with `dashpot lcp`; it runs on a compute
 * thread (jobs.c) under the daemon's stop hook (--max-wall, shutdown, hang-up), since Murty's (1978)
 * examples take Lemke's method exponentially many pivots. This file only negotiates the media type.
 */
#include "dashpot/lcp_json.h"
#include "http.h"

static int lcp_work(request *r, int arg, const dp_stop *stop, dp_buf *out, dp_errors *errs)
{
    (void)arg;
    return dp_lcp_respond_until(r->body.data ? r->body.data : "", r->body.len, stop, out, errs);
}

static const job_route lcp_job = { lcp_work, "the LCP", NULL };

enum MHD_Result handle_lcp(struct MHD_Connection *c, request *r)
{
    return job_submit_json(c, r, &lcp_job);
}
