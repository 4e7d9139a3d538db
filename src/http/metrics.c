/* src/http/metrics.c - dashpotd's counters (atomics, no locks) and their Prometheus text exposition.
 *
 * Requests are counted by route and status, durations go into a histogram per route with fixed buckets
 * from 0.5 ms to 60 s (a health check to a long stream). Counters only ever grow; gauges (runs in flight,
 * open connections) go up and down. Relaxed ordering is enough: every number is read on its own.
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "http.h"

static const int status_codes[NSTATUS] = { 200, 304, 400, 401, 404, 405, 406, 413, 422, 500, 503, 0 };
static const double bucket_le[NBUCKETS - 1] = { 0.0005, 0.001, 0.005, 0.01, 0.05, 0.1, 0.5, 1, 5, 10, 60 };
static const char *const bucket_text[NBUCKETS] = {
    "0.0005", "0.001", "0.005", "0.01", "0.05", "0.1", "0.5", "1", "5", "10", "60", "+Inf"
};

const char *route_name(int route)
{
    static const char *const names[NROUTES] = { "/v1/simulate", "/v1/stability", "/v1/wellposedness",
                                                "/v1/convergence", "/v1/modes", "/v1/response", "/v1/lcp", "/v1/sweep", "/healthz",
                                                "/readyz", "/metrics", "/openapi.yaml", "/bench/static", "/",
                                                "unmatched" };
    return route >= 0 && route < NROUTES ? names[route] : "unmatched";
}

/* The slot of a status; the last one collects every other status. */
static int status_slot(int status)
{
    for (int i = 0; i < NSTATUS - 1; i++)
        if (status_codes[i] == status)
            return i;
    return NSTATUS - 1;
}

void metrics_request(metrics *m, int route, int status, double seconds)
{
    if (route < 0 || route >= NROUTES)
        route = ROUTE_NONE;
    atomic_fetch_add_explicit(&m->requests[route][status_slot(status)], 1, memory_order_relaxed);
    int b = 0;
    while (b < NBUCKETS - 1 && seconds > bucket_le[b])
        b++;
    atomic_fetch_add_explicit(&m->duration_bucket[route][b], 1, memory_order_relaxed);
    unsigned long long us = seconds > 0 ? (unsigned long long)(seconds * 1e6) : 0;
    atomic_fetch_add_explicit(&m->duration_us_sum[route], us, memory_order_relaxed);
}

#define LOAD(x) atomic_load_explicit(&(x), memory_order_relaxed)

/* Appends printf-formatted text; sticky failure through *s. */
static void put(dp_buf *b, int *s, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

static void put(dp_buf *b, int *s, const char *fmt, ...)
{
    char line[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    if (*s == DP_OK && n > 0)
        *s = dp_buf_append(b, line, (size_t)n < sizeof line ? (size_t)n : sizeof line - 1);
}

static void render_requests(const metrics *m, dp_buf *b, int *s)
{
    put(b, s, "# HELP dashpot_http_requests_total HTTP requests answered, by route and status.\n"
              "# TYPE dashpot_http_requests_total counter\n");
    for (int r = 0; r < NROUTES; r++)
        for (int i = 0; i < NSTATUS; i++) {
            unsigned long long n = LOAD(m->requests[r][i]);
            if (n == 0)
                continue;
            if (status_codes[i])
                put(b, s, "dashpot_http_requests_total{route=\"%s\",status=\"%d\"} %llu\n", route_name(r),
                    status_codes[i], n);
            else
                put(b, s, "dashpot_http_requests_total{route=\"%s\",status=\"other\"} %llu\n", route_name(r), n);
        }
}

static void render_durations(const metrics *m, dp_buf *b, int *s)
{
    put(b, s, "# HELP dashpot_http_request_duration_seconds Time from the request's first byte to its last "
              "response byte.\n# TYPE dashpot_http_request_duration_seconds histogram\n");
    for (int r = 0; r < NROUTES; r++) {
        unsigned long long cum = 0;
        for (int i = 0; i < NBUCKETS; i++)
            cum += LOAD(m->duration_bucket[r][i]);
        if (cum == 0)
            continue;
        cum = 0;
        for (int i = 0; i < NBUCKETS; i++) {
            cum += LOAD(m->duration_bucket[r][i]);
            put(b, s, "dashpot_http_request_duration_seconds_bucket{route=\"%s\",le=\"%s\"} %llu\n",
                route_name(r), bucket_text[i], cum);
        }
        put(b, s, "dashpot_http_request_duration_seconds_sum{route=\"%s\"} %.6f\n", route_name(r),
            (double)LOAD(m->duration_us_sum[r]) * 1e-6);
        put(b, s, "dashpot_http_request_duration_seconds_count{route=\"%s\"} %llu\n", route_name(r), cum);
    }
}

static void render_one(dp_buf *b, int *s, const char *name, const char *type, const char *help,
                       long long value)
{
    put(b, s, "# HELP %s %s\n# TYPE %s %s\n%s %lld\n", name, help, name, type, name, value);
}

int metrics_render(const metrics *m, dp_buf *b)
{
    int s = DP_OK;
    render_requests(m, b, &s);
    render_durations(m, b, &s);
    render_one(b, &s, "dashpot_samples_streamed_total", "counter", "Samples written to clients.",
               (long long)LOAD(m->samples_streamed));
    render_one(b, &s, "dashpot_bytes_streamed_total", "counter", "Body bytes of simulation responses.",
               (long long)LOAD(m->bytes_streamed));
    render_one(b, &s, "dashpot_runs_started_total", "counter", "Simulation runs started.",
               (long long)LOAD(m->runs_started));
    render_one(b, &s, "dashpot_runs_completed_total", "counter", "Runs that streamed their summary.",
               (long long)LOAD(m->runs_completed));
    render_one(b, &s, "dashpot_runs_failed_total", "counter", "Runs that ended with an error line.",
               (long long)LOAD(m->runs_failed));
    render_one(b, &s, "dashpot_runs_cancelled_total", "counter",
               "Runs stopped because the client went away (or the connection timed out).",
               (long long)LOAD(m->runs_cancelled));
    render_one(b, &s, "dashpot_events_total", "counter", "Events (stick, slip, yield, unload, impact) of runs that "
               "ended.", (long long)LOAD(m->events));
    render_one(b, &s, "dashpot_impacts_total", "counter", "Contacts' impacts of runs that ended (docs/contact.md).",
               (long long)LOAD(m->impacts));
    render_one(b, &s, "dashpot_runs_in_flight", "gauge", "Runs streaming now.", LOAD(m->runs_in_flight));
    render_one(b, &s, "dashpot_studies_in_flight", "gauge", "Convergence studies computing now.",
               LOAD(m->studies_in_flight));
    render_one(b, &s, "dashpot_workers_busy", "gauge", "Solver slots taken (of --threads); all taken: /readyz is 503.",
               LOAD(m->workers_busy));
    render_one(b, &s, "dashpot_connections_open", "gauge", "Open client connections.",
               LOAD(m->connections_open));
    render_one(b, &s, "dashpot_connections_rejected_total", "counter",
               "Requests answered 503 because --max-connections were open.",
               (long long)LOAD(m->connections_rejected));
    render_one(b, &s, "dashpot_connections_timed_out_total", "counter",
               "Connections closed because their request did not arrive whole within --timeout seconds.",
               (long long)LOAD(m->connections_timed_out));
    return s;
}
