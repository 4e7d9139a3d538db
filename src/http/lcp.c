/* src/http/lcp.c - POST /v1/lcp: one linear complementarity problem w = Mz + q, 0 <= z ⊥ w >= 0, solved by
 * Lemke's method, its solutions enumerated when it is small, and the uniqueness theory (docs/lcs.md).
 *
 * The work is dp_lcp_respond (src/json/lcp_json.c), shared with `dashpot lcp`; this file only negotiates the
 * media type and maps failures to problem documents.
 */
#include "dashpot/lcp_json.h"
#include "http.h"

enum MHD_Result handle_lcp(struct MHD_Connection *c, request *r)
{
    static const char *const offers[] = { "application/json" };
    if (negotiate(MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT), offers, 1) < 0)
        return respond_problem(c, r, 406, NULL, "this route answers application/json", NULL, NULL);
    dp_buf out = { 0 };
    dp_errors errs;
    dp_errors_init(&errs);
    int s = dp_lcp_respond(r->body.data ? r->body.data : "", r->body.len, &out, &errs);
    if (s != DP_OK) {
        dp_buf_free(&out);
        return respond_status(c, r, s, s == DP_ESYNTAX && errs.n ? errs.item[0].message : NULL, &errs);
    }
    return respond_buffer(c, r, 200, "application/json", &out);
}
