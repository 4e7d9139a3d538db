/* src/http/stability.c - POST /v1/stability: the analysis or parameter map of a linear implicit law.
 *
 * The work is dp_stability_respond (src/json/stability_json.c), shared with `dashpot stability`; this file
 * only negotiates the format, holds maps to the daemon's --max-map-points and maps failures to problem
 * documents. A body that may ask for a map is computed on a compute thread (jobs.c), never on a connection
 * thread; the analysis of one law (microseconds) is answered at once. Answers are computed in one go and
 * sent as a plain body with a Content-Length, so a map's size is its cost twice: ~2.5 us of CPU and ~70
 * bytes of CSV per point (the library allows 2000 x 2000, 10 s and 300 MB; the daemon's default, 40 000
 * points, is ~0.1 s and ~3 MB).
 *
 * GSL's workspaces (dp_stability_ws) are kept between requests in the server's pool, WS_POOL slots taken
 * and returned by atomic exchange: allocating them was ~0.5 us of a small analysis. A workspace holds
 * scratch memory only, never a result, so a reused one gives the same bytes as a new one.
 */
#define _GNU_SOURCE /* memmem */
#include <cjson/cJSON.h>
#include <math.h>
#include <string.h>

#include "dashpot/stability_json.h"
#include "http.h"

static const char *const offers[] = { "application/json", "text/csv", "image/svg+xml" };
static const int offer_want[] = { DP_STABILITY_JSON, DP_STABILITY_CSV, DP_STABILITY_SVG };

static double axis_steps(const cJSON *map, const char *axis)
{
    const cJSON *steps = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(map, axis), "steps");
    return cJSON_IsNumber(steps) && steps->valuedouble > 0 ? steps->valuedouble : 0;
}

/* Whether a body can name a "map" member: "map" or a \u escape in it. */
static int may_name_map(const char *body, size_t len)
{
    return len > 0 && (memmem(body, len, "map", 3) || memmem(body, len, "\\u", 2));
}

/* The grid points the body's map asks for; 0 without a map, or when it is malformed (the full parse
 * says why). Bodies that cannot name a "map" member are not parsed twice: the small analysis request stays
 * as cheap as it was. */
static double map_points(const char *body, size_t len)
{
    if (!may_name_map(body, len))
        return 0;
    cJSON *root = cJSON_ParseWithLength(body, len);
    const cJSON *map = cJSON_GetObjectItemCaseSensitive(root, "map");
    double n = cJSON_IsObject(map) ? axis_steps(map, "x") * axis_steps(map, "y") : 0;
    cJSON_Delete(root);
    return isfinite(n) ? n : 0;
}

/* An idle workspace of the server's, or a new one (NULL when out of memory). */
static dp_stability_ws *ws_take(server *s)
{
    for (int i = 0; i < WS_POOL; i++) {
        if (atomic_load_explicit(&s->ws_pool[i], memory_order_relaxed) == NULL)
            continue;
        dp_stability_ws *w = atomic_exchange(&s->ws_pool[i], NULL);
        if (w != NULL)
            return w;
    }
    return dp_stability_ws_alloc();
}

/* Back into an empty slot, or freed when all are taken. */
static void ws_give(server *s, dp_stability_ws *w)
{
    for (int i = 0; i < WS_POOL && w != NULL; i++) {
        dp_stability_ws *empty = NULL;
        if (atomic_compare_exchange_strong(&s->ws_pool[i], &empty, w))
            return;
    }
    dp_stability_ws_free(w);
}

void stability_pool_free(server *s)
{
    for (int i = 0; i < WS_POOL; i++)
        dp_stability_ws_free(atomic_exchange(&s->ws_pool[i], NULL));
}

/* The analysis or the map, within the server's --max-map-points. A map's library call polls no stop hook;
 * its cost is bounded by that limit (~0.1 s at the default). */
static int stability_work(request *r, int f, const dp_stop *stop, dp_buf *out, dp_errors *errs)
{
    (void)stop;
    const char *body = r->body.data ? r->body.data : "";
    double points = map_points(body, r->body.len);
    if (points > r->srv->cfg.max_map_points) {
        dp_errors_add(errs, "/map", "a map of %.0f points is over this server's limit of %.0f (--max-map-points)",
                      points, r->srv->cfg.max_map_points);
        return DP_ELIMIT;
    }
    dp_stability_ws *w = ws_take(r->srv);
    int s = w ? dp_stability_respond_ws(w, body, r->body.len, offer_want[f], out, errs) : DP_ENOMEM;
    ws_give(r->srv, w);
    return s;
}

static const job_route map_job = { stability_work, "the map", NULL };

enum MHD_Result handle_stability(struct MHD_Connection *c, request *r)
{
    static const char *const types[] = { "application/json", "text/csv; charset=utf-8", "image/svg+xml" };
    int f = negotiate(MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT), offers, 3);
    if (f < 0)
        return respond_problem(c, r, 406, NULL, "this route answers application/json, text/csv or image/svg+xml",
                               NULL, NULL);
    if (may_name_map(r->body.data, r->body.len)) /* a map: up to --max-map-points, on a compute thread */
        return job_submit(c, r, &map_job, f, types[f]);
    dp_buf out = { 0 }; /* the analysis of one law: microseconds, answered here */
    dp_errors errs;
    dp_errors_init(&errs);
    int s = stability_work(r, f, NULL, &out, &errs);
    return respond_answer(c, r, s, &out, &errs, types[f]);
}
