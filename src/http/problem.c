/* src/http/problem.c - queuing responses: plain bodies and application/problem+json (RFC 9457).
 *
 *   {"type":"/problems/invalid-spec","title":"Invalid specification","status":422,
 *    "detail":"2 errors in the request body","errors":[{"pointer":"/model/mass","detail":"..."}, ...]}
 *
 * "type" is a relative URI naming the kind of problem (documented in api/openapi.yaml); HTTP-level problems
 * (404, 405, 406, 413) use "about:blank" with the status phrase as title, as RFC 9457 section 4.2 suggests.
 * One table maps dp_status to HTTP status and problem type; nothing here ever answers 500.
 */
#include <stdio.h>
#include <string.h>

#include "http.h"

/* Title of an HTTP status (RFC 9110 reason phrases). */
static const char *status_title(int status)
{
    switch (status) {
    case 400: return "Bad Request";
    case 401: return "Unauthorized";
    case 404: return "Not Found";
    case 405: return "Method Not Allowed";
    case 406: return "Not Acceptable";
    case 413: return "Content Too Large";
    case 422: return "Unprocessable Content";
    case 503: return "Service Unavailable";
    default: return "Error";
    }
}

/* Adds the common headers, records what is sent, queues and drops our reference to resp. */
static enum MHD_Result queue(struct MHD_Connection *c, request *r, int status, struct MHD_Response *resp,
                             const char *type, size_t len, const char *allow)
{
    MHD_add_response_header(resp, MHD_HTTP_HEADER_CONTENT_TYPE, type);
    MHD_add_response_header(resp, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    if (allow)
        MHD_add_response_header(resp, MHD_HTTP_HEADER_ALLOW, allow);
    if (status == 503)
        MHD_add_response_header(resp, MHD_HTTP_HEADER_RETRY_AFTER, "1");
    if (r->close) /* MHD closes the connection after this response: nothing pipelined behind it is read */
        MHD_add_response_header(resp, MHD_HTTP_HEADER_CONNECTION, "close");
    if (status == 401)
        MHD_add_response_header(resp, MHD_HTTP_HEADER_WWW_AUTHENTICATE, "Bearer realm=\"dashpot\"");
    r->status = status;
    r->bytes = len;
    enum MHD_Result ok = MHD_queue_response(c, (unsigned)status, resp);
    MHD_destroy_response(resp);
    return ok;
}

/* A response owning body->data (MUST_FREE: it is malloc'd), or an empty one; body is emptied either way. */
static struct MHD_Response *from_buf(dp_buf *body)
{
    struct MHD_Response *resp = body->data
        ? MHD_create_response_from_buffer(body->len, body->data, MHD_RESPMEM_MUST_FREE)
        : MHD_create_response_from_buffer(0, (char *)"", MHD_RESPMEM_PERSISTENT);
    if (resp == NULL)
        dp_buf_free(body);
    body->data = NULL;
    body->cap = 0;
    return resp;
}

enum MHD_Result respond_buffer(struct MHD_Connection *c, request *r, int status, const char *type, dp_buf *body)
{
    size_t len = body->len;
    struct MHD_Response *resp = from_buf(body);
    body->len = 0;
    return resp ? queue(c, r, status, resp, type, len, NULL) : MHD_NO; /* MHD_NO: MHD closes the connection */
}

/* "errors": [{"pointer":..,"detail":..}, ...] and, if the list overflowed, how many were left out. */
static int put_errors(dp_buf *b, const dp_errors *errs)
{
    int s = dp_buf_append(b, ",\"errors\":[", 11);
    for (size_t i = 0; i < errs->n && s == DP_OK; i++) {
        s = dp_buf_append(b, i ? ",{\"pointer\":" : "{\"pointer\":", i ? 12 : 11);
        s = s ? s : dp_json_quote(b, errs->item[i].pointer);
        s = s ? s : dp_buf_append(b, ",\"detail\":", 10);
        s = s ? s : dp_json_quote(b, errs->item[i].message);
        s = s ? s : dp_buf_append(b, "}", 1);
    }
    s = s ? s : dp_buf_append(b, "]", 1);
    if (s == DP_OK && errs->dropped) {
        char t[64];
        int n = snprintf(t, sizeof t, ",\"errors_dropped\":%zu", errs->dropped);
        s = dp_buf_append(b, t, (size_t)n);
    }
    return s;
}

static int problem_body(dp_buf *b, int status, const char *type, const char *detail, const dp_errors *errs)
{
    char head[128];
    int s = dp_buf_append(b, "{\"type\":", 8);
    s = s ? s : dp_json_quote(b, type ? type : "about:blank");
    s = s ? s : dp_buf_append(b, ",\"title\":", 9);
    s = s ? s : dp_json_quote(b, status_title(status));
    int n = snprintf(head, sizeof head, ",\"status\":%d,\"detail\":", status);
    s = s ? s : dp_buf_append(b, head, (size_t)n);
    s = s ? s : dp_json_quote(b, detail ? detail : status_title(status));
    if (s == DP_OK && errs && errs->n)
        s = put_errors(b, errs);
    return s ? s : dp_buf_append(b, "}\n", 2);
}

enum MHD_Result respond_problem(struct MHD_Connection *c, request *r, int status, const char *type,
                                const char *detail, const dp_errors *errs, const char *allow)
{
    dp_buf b = { 0 };
    if (problem_body(&b, status, type, detail, errs) != DP_OK)
        dp_buf_free(&b); /* out of memory: a bodiless answer with the right status is all that is left */
    size_t len = b.len;
    struct MHD_Response *resp = from_buf(&b);
    return resp ? queue(c, r, status, resp, "application/problem+json", len, allow) : MHD_NO;
}

enum MHD_Result respond_status(struct MHD_Connection *c, request *r, int status, const char *detail,
                               const dp_errors *errs)
{
    const char *type;
    switch (status) {
    case DP_ESYNTAX: type = "/problems/malformed-json"; break;
    case DP_EINVAL: type = "/problems/invalid-spec"; break;
    case DP_ELIMIT: type = "/problems/over-limit"; break;
    case DP_ESOLVE: case DP_ENONFINITE: type = "/problems/run-failed"; break;
    case DP_ECANCEL: type = "/problems/timeout"; break;
    default: type = "/problems/unavailable"; break;
    }
    char fallback[64];
    if (detail == NULL && errs && errs->n) {
        snprintf(fallback, sizeof fallback, "%zu error%s in the request body", errs->n + errs->dropped,
                 errs->n + errs->dropped == 1 ? "" : "s");
        detail = fallback;
    }
    return respond_problem(c, r, dp_status_http(status), type, detail ? detail : dp_strerror(status), errs, NULL);
}

enum MHD_Result respond_answer(struct MHD_Connection *c, request *r, int s, dp_buf *out, const dp_errors *errs,
                               const char *type)
{
    if (s == DP_OK)
        return respond_buffer(c, r, 200, type, out);
    dp_buf_free(out);
    return respond_status(c, r, s, s == DP_ESYNTAX && errs->n ? errs->item[0].message : NULL, errs);
}

enum MHD_Result respond_json_answer(struct MHD_Connection *c, request *r, json_answer_fn answer)
{
    static const char *const offers[] = { "application/json" };
    if (negotiate(MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT), offers, 1) < 0)
        return respond_problem(c, r, 406, NULL, "this route answers application/json", NULL, NULL);
    dp_buf out = { 0 };
    dp_errors errs;
    dp_errors_init(&errs);
    int s = answer(r->body.data ? r->body.data : "", r->body.len, &out, &errs);
    return respond_answer(c, r, s, &out, &errs, "application/json");
}
