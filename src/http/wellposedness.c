/* src/http/wellposedness.c - POST /v1/wellposedness: which theorems apply to a model, what is guaranteed.
 *
 * The body is a simulation spec, or just {"model": ...}; user graphs may be non-monotone or have gaps here
 * (dp_model_parse_lenient), since saying why such a model is not covered is the point. The report is the
 * JSON of dp_wellposedness_json, the same object the meta line of every run carries.
 */
#include "dashpot/json.h"
#include "dashpot/wellposedness.h"
#include "http.h"

enum MHD_Result handle_wellposedness(struct MHD_Connection *c, request *r)
{
    const char *accept = MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT);
    static const char *const offers[] = { "application/json" };
    if (negotiate(accept, offers, 1) < 0)
        return respond_problem(c, r, 406, NULL, "this route answers application/json", NULL, NULL);
    dp_errors errs;
    dp_errors_init(&errs);
    dp_wp_report rep;
    int s = dp_wellposedness_parse(r->body.data ? r->body.data : "", r->body.len, &rep, &errs);
    if (s != DP_OK)
        return respond_status(c, r, s, s == DP_ESYNTAX && errs.n ? errs.item[0].message : NULL, &errs);
    dp_buf out = { 0 };
    if (dp_wellposedness_json(&rep, &out) != DP_OK || dp_buf_append(&out, "\n", 1) != DP_OK) {
        dp_buf_free(&out);
        return respond_status(c, r, DP_ENOMEM, NULL, NULL);
    }
    return respond_buffer(c, r, 200, "application/json", &out);
}
