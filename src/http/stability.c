/* src/http/stability.c - POST /v1/stability: the analysis or parameter map of a linear implicit law.
 *
 * The work is dp_stability_respond (src/json/stability_json.c), shared with `dashpot stability`; this file
 * only negotiates the format and maps failures to problem documents. Answers are small and computed in one
 * go, so they are sent as a plain body with a Content-Length.
 */
#include "dashpot/stability_json.h"
#include "http.h"

static const char *const offers[] = { "application/json", "text/csv", "image/svg+xml" };
static const int offer_want[] = { DP_STABILITY_JSON, DP_STABILITY_CSV, DP_STABILITY_SVG };

enum MHD_Result handle_stability(struct MHD_Connection *c, request *r)
{
    int f = negotiate(MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT), offers, 3);
    if (f < 0)
        return respond_problem(c, r, 406, NULL, "this route answers application/json, text/csv or image/svg+xml",
                               NULL, NULL);
    dp_buf out = { 0 };
    dp_errors errs;
    dp_errors_init(&errs);
    int s = dp_stability_respond(r->body.data ? r->body.data : "", r->body.len, offer_want[f], &out, &errs);
    if (s != DP_OK) {
        dp_buf_free(&out);
        return respond_status(c, r, s, s == DP_ESYNTAX && errs.n ? errs.item[0].message : NULL, &errs);
    }
    static const char *const types[] = { "application/json", "text/csv; charset=utf-8", "image/svg+xml" };
    return respond_buffer(c, r, 200, types[f], &out);
}
