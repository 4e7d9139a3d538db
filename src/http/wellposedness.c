/* src/http/wellposedness.c - POST /v1/wellposedness: which theorems apply to a model, what is guaranteed.
 *
 * The body is a simulation spec, or just {"model": ...}; user graphs may be non-monotone or have gaps here
 * (dp_model_parse_lenient), since saying why such a model is not covered is the point. The report is the
 * JSON of dp_wellposedness_json, the same object the meta line of every run carries.
 */
#include "dashpot/json.h"
#include "dashpot/wellposedness.h"
#include "http.h"

/* The report of the body's model as one JSON document (the answer respond_json_answer wants). */
static int report_answer(const char *body, size_t len, dp_buf *out, dp_errors *errs)
{
    dp_wp_report rep;
    int s = dp_wellposedness_parse(body, len, &rep, errs);
    if (s == DP_OK && (dp_wellposedness_json(&rep, out) != DP_OK || dp_buf_append(out, "\n", 1) != DP_OK))
        s = DP_ENOMEM;
    return s;
}

enum MHD_Result handle_wellposedness(struct MHD_Connection *c, request *r)
{
    return respond_json_answer(c, r, report_answer);
}
