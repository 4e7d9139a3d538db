/* src/http/routes.c - the route table and the small handlers (health, readiness, metrics, OpenAPI).
 *
 * A route with a body computes under a solver slot (slots.c); the ones answered whole hand their work to
 * the compute threads (jobs.c) and are answered here when it is done.
 *
 * Paths match exactly (MHD hands over the path without its query string). GET routes answer HEAD too.
 * A path that exists with another method is a 405 with an Allow header (counted under its route in the
 * metrics); anything else is a 404.
 */
#include <stdio.h>
#include <string.h>

#include "http.h"

typedef enum MHD_Result (*handler)(struct MHD_Connection *c, request *r);

static enum MHD_Result handle_healthz(struct MHD_Connection *c, request *r);
static enum MHD_Result handle_readyz(struct MHD_Connection *c, request *r);
static enum MHD_Result handle_metrics(struct MHD_Connection *c, request *r);
static enum MHD_Result handle_openapi(struct MHD_Connection *c, request *r);

static const struct route {
    const char *path, *method, *allow;
    int id, body;
    handler h;
} routes[] = {
    { "/v1/simulate", "POST", "POST", ROUTE_SIMULATE, 1, handle_simulate },
    { "/v1/stability", "POST", "POST", ROUTE_STABILITY, 1, handle_stability },
    { "/v1/wellposedness", "POST", "POST", ROUTE_WELLPOSEDNESS, 1, handle_wellposedness },
    { "/v1/convergence", "POST", "POST", ROUTE_CONVERGENCE, 1, handle_convergence },
    { "/v1/modes", "POST", "POST", ROUTE_MODES, 1, handle_modes },
    { "/v1/response", "POST", "POST", ROUTE_RESPONSE, 1, handle_response },
    { "/v1/lcp", "POST", "POST", ROUTE_LCP, 1, handle_lcp },
    { "/v1/sweep", "POST", "POST", ROUTE_SWEEP, 1, handle_sweep },
    { "/healthz", "GET", "GET, HEAD", ROUTE_HEALTHZ, 0, handle_healthz },
    { "/readyz", "GET", "GET, HEAD", ROUTE_READYZ, 0, handle_readyz },
    { "/metrics", "GET", "GET, HEAD", ROUTE_METRICS, 0, handle_metrics },
    { "/openapi.yaml", "GET", "GET, HEAD", ROUTE_OPENAPI, 0, handle_openapi },
    { "/bench/static", "GET", "GET, HEAD", ROUTE_STATIC, 0, handle_bench_static },
    { "/", "GET", "GET, HEAD", ROUTE_PAGE, 0, handle_page }, /* and every file of --web-dir: page.c */
};
enum { NTABLE = sizeof routes / sizeof routes[0] };

int route_find(const server *s, const char *method, const char *url, const char **allow)
{
    *allow = NULL;
    for (int i = 0; i < NTABLE; i++) {
        const struct route *rt = &routes[i];
        if ((rt->id == ROUTE_PAGE ? !page_route(s, url) : strcmp(rt->path, url) != 0) ||
            (rt->id == ROUTE_STATIC && s->cfg.bench_static[0] == '\0'))
            continue;
        if (strcmp(rt->method, method) != 0 && !(strcmp(rt->method, "GET") == 0 && strcmp(method, "HEAD") == 0))
            *allow = rt->allow;
        return rt->id;
    }
    return ROUTE_NONE;
}

int route_needs_body(int route)
{
    for (int i = 0; i < NTABLE; i++)
        if (routes[i].id == route)
            return routes[i].body;
    return 0;
}

enum MHD_Result route_dispatch(struct MHD_Connection *c, request *r)
{
    if (r->too_large) {
        char detail[96];
        snprintf(detail, sizeof detail, "the request body is larger than %zu bytes", r->srv->cfg.body_limit);
        return respond_problem(c, r, 413, NULL, detail, NULL, NULL);
    }
    if (r->allow)
        return respond_problem(c, r, 405, NULL, "this path does not take that method", NULL, r->allow);
    if (r->route == ROUTE_NONE)
        return respond_problem(c, r, 404, NULL, "no such route", NULL, NULL);
    for (int i = 0; i < NTABLE; i++) {
        if (routes[i].id != r->route)
            continue;
        if (!routes[i].body) /* the small routes: never behind solver work */
            return routes[i].h(c, r);
        if (!slot_take(r, c))
            return MHD_YES; /* parked until a slot is handed over: called again then */
        /* Called again once its job is done (jobs.c): the answer is ready. A job in flight keeps the slot. */
        enum MHD_Result res = r->job ? job_answer(c, r) : routes[i].h(c, r);
        if (!job_pending(r))
            slot_give(r);
        return res;
    }
    return respond_problem(c, r, 404, NULL, "no such route", NULL, NULL);
}

static enum MHD_Result respond_text(struct MHD_Connection *c, request *r, int status, const char *type,
                                    const char *text)
{
    dp_buf b = { 0 };
    if (dp_buf_append(&b, text, strlen(text)) != DP_OK)
        return respond_status(c, r, DP_ENOMEM, NULL, NULL);
    return respond_buffer(c, r, status, type, &b);
}

static enum MHD_Result handle_healthz(struct MHD_Connection *c, request *r)
{
    return respond_text(c, r, 200, "application/json", "{\"status\":\"ok\"}\n");
}

static enum MHD_Result handle_readyz(struct MHD_Connection *c, request *r)
{
    if (atomic_load(&r->srv->draining))
        return respond_problem(c, r, 503, "/problems/shutting-down", "the server is shutting down", NULL, NULL);
    if (slots_free(r->srv) == 0) /* a load balancer routes around the replica until a worker is free */
        return respond_problem(c, r, 503, "/problems/busy", "every worker is computing; retry shortly or elsewhere",
                               NULL, NULL);
    return respond_text(c, r, 200, "application/json", "{\"status\":\"ready\"}\n");
}

static enum MHD_Result handle_metrics(struct MHD_Connection *c, request *r)
{
    dp_buf b = { 0 };
    if (metrics_render(&r->srv->m, &b) != DP_OK) {
        dp_buf_free(&b);
        return respond_status(c, r, DP_ENOMEM, NULL, NULL);
    }
    return respond_buffer(c, r, 200, "text/plain; version=0.0.4; charset=utf-8", &b);
}

static enum MHD_Result handle_openapi(struct MHD_Connection *c, request *r)
{
    server *s = r->srv;
    if (s->openapi == NULL)
        return respond_problem(c, r, 404, NULL, "the OpenAPI document was not found at start-up (--openapi)",
                               NULL, NULL);
    struct MHD_Response *resp = MHD_create_response_from_buffer(s->openapi_len, s->openapi,
                                                                MHD_RESPMEM_PERSISTENT); /* the server owns it */
    if (resp == NULL)
        return MHD_NO;
    MHD_add_response_header(resp, MHD_HTTP_HEADER_CONTENT_TYPE, "application/yaml");
    r->status = 200;
    r->bytes = s->openapi_len;
    enum MHD_Result ok = MHD_queue_response(c, 200, resp);
    MHD_destroy_response(resp);
    return ok;
}
