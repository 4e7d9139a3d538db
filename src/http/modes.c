/* src/http/modes.c - POST /v1/modes and POST /v1/response: the linear analysis of a network (natural modes,
 * damped eigenvalues; the receptance curve with its resonances and antiresonances), docs/modes.md.
 *
 * The work is dp_modes_respond / dp_response_respond (src/json/modes_json.c), shared with `dashpot modes`
 * and `dashpot response`; this file only negotiates the media type and maps failures to problem
 * documents. The answer is computed whole (a curve is at most 10^5 points, a few MB), so it is not
 * streamed; the response curve is offered as JSON, NDJSON or CSV by Accept, as /v1/simulate offers them.
 */
#include "dashpot/modes_json.h"
#include "http.h"

enum MHD_Result handle_modes(struct MHD_Connection *c, request *r)
{
    return respond_json_answer(c, r, dp_modes_respond);
}

enum MHD_Result handle_response(struct MHD_Connection *c, request *r)
{
    static const char *const offers[] = { "application/json", "application/x-ndjson", "text/csv" };
    static const int formats[] = { DP_FORMAT_JSON, DP_FORMAT_NDJSON, DP_FORMAT_CSV };
    int f = negotiate(MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT), offers, 3);
    if (f < 0)
        return respond_problem(c, r, 406, NULL, "this route answers application/json, application/x-ndjson or text/csv",
                               NULL, NULL);
    dp_buf out = { 0 };
    dp_errors errs;
    dp_errors_init(&errs);
    int s = dp_response_respond(r->body.data ? r->body.data : "", r->body.len, formats[f], &out, &errs);
    return respond_answer(c, r, s, &out, &errs, dp_format_content_type((dp_format)formats[f]));
}
