/* src/http/http.h - what the files of dashpotd share: its configuration, the server and request state, and
 * the functions each file offers the others (main.c, config.c, server.c, routes.c, simulate.c,
 * stability.c, wellposedness.c, modes.c, lcp.c, convergence.c, jobs.c, watch.c, bench_static.c,
 * negotiate.c, problem.c, metrics.c, log.c).
 *
 * Ownership: the server outlives every request (MHD_stop_daemon returns only after the last one is freed).
 * A request is allocated on MHD's first call for it and freed in the NOTIFY_COMPLETED callback, except that a
 * streamed response holds a second reference (released by the response's free callback), so whichever comes
 * last frees it. Shared counters are atomics; nothing else is shared between threads.
 */
#ifndef DASHPOT_HTTP_H
#define DASHPOT_HTTP_H

#include <microhttpd.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stddef.h>

#include "dashpot/encode.h"
#include "dashpot/stability.h"
#include "dashpot/status.h"

/* ---- configuration (config.c) ---- */

typedef struct config {
    unsigned port;               /* 0: an ephemeral port, printed in the start-up line */
    char bind[64];               /* IPv4 or IPv6 literal */
    unsigned threads;            /* MHD thread pool */
    unsigned max_connections;    /* open connections served; beyond: 503 */
    double max_steps;            /* per request, passed to dp_spec_parse and dp_run_alloc */
    double max_map_points;       /* grid points of one /v1/stability map */
    double max_wall;             /* seconds one request may take */
    unsigned timeout;            /* seconds a connection may stay idle, and a request may take to arrive */
    size_t body_limit;           /* bytes of a request body; beyond: 413 */
    double shutdown_grace;       /* seconds runs in flight get to finish after SIGTERM */
    char openapi[4096];          /* path of api/openapi.yaml */
    char bench_static[4096];     /* a file served at GET /bench/static (benchmarks only); "" = route off */
    char web_dir[4096];          /* the browser page's files (web/), served at / (page.c) */
    char token_file[4096];       /* a file holding the bearer token that /v1/ requires; "" = DASHPOT_TOKEN */
    char token[1024];            /* the token itself (auth_load); "" = /v1/ is open */
    int embedded;                /* not a flag: no listening socket, no threads; the caller adds connections
                                    and drives MHD_run (tests/fuzz/fuzz_http.c) */
    int quiet;                   /* not a flag: no log lines */
} config;

/* Fills c from defaults, DASHPOT_* variables and argv (flags win). Returns 0 to run, 1 when --help or
 * --version was printed, -1 on a bad value (message printed to stderr). */
int config_load(config *c, int argc, char **argv);

/* The defaults of --openapi and --web-dir (source-tree paths), and their names where `make install` puts
 * them: $(datadir)/dashpot/openapi.yaml and $(datadir)/dashpot/web. */
#define DEFAULT_OPENAPI "api/openapi.yaml"
#define DEFAULT_WEB_DIR "web"
#define INSTALLED_OPENAPI "openapi.yaml"
#define INSTALLED_WEB_DIR "web"

/* Where a file (want_dir 0) or directory (1) the daemon serves is: `given` itself when it exists (absolute,
 * or relative to the working directory); for a relative one, else beside the binary, else in the binary's
 * parent directory (build/dashpotd finds api/openapi.yaml), and, when `installed` is not NULL,
 * <binary's directory>/../share/dashpot/<installed> (make install's layout under any prefix: nothing is
 * compiled in). The path found goes into out; returns 0, or -1 when there is none (out = given). */
int data_path(const char *given, const char *installed, int want_dir, char *out, size_t cap);

/* ---- metrics (metrics.c) ---- */

enum { ROUTE_SIMULATE, ROUTE_STABILITY, ROUTE_WELLPOSEDNESS, ROUTE_CONVERGENCE, ROUTE_MODES, ROUTE_RESPONSE, ROUTE_LCP, ROUTE_SWEEP, ROUTE_HEALTHZ, ROUTE_READYZ, ROUTE_METRICS, ROUTE_OPENAPI,
       ROUTE_STATIC, ROUTE_PAGE, ROUTE_NONE, NROUTES };
enum { NSTATUS = 12, NBUCKETS = 12 };

typedef struct metrics {
    atomic_ullong requests[NROUTES][NSTATUS];    /* by route and status (metrics.c: status_slot) */
    atomic_ullong duration_bucket[NROUTES][NBUCKETS]; /* cumulative only when rendered */
    atomic_ullong duration_us_sum[NROUTES];
    atomic_ullong samples_streamed, bytes_streamed;
    atomic_ullong runs_started, runs_completed, runs_failed, runs_cancelled;
    atomic_ullong events, impacts;   /* of the runs that ended */
    atomic_llong runs_in_flight, connections_open;
    atomic_llong studies_in_flight;              /* /v1/convergence studies computing now */
    atomic_uint workers_busy;                    /* solver slots taken (slots.c); written under its lock */
    atomic_ullong connections_rejected;
    atomic_ullong connections_timed_out;         /* closed by the request deadline (deadline.c) */
} metrics;

void metrics_request(metrics *m, int route, int status, double seconds);
/* The Prometheus text exposition (version 0.0.4) of every counter into out. */
int metrics_render(const metrics *m, dp_buf *out);
const char *route_name(int route);

/* ---- the server (server.c) ---- */

/* Idle stability workspaces the server keeps (stability.c); more requests at once allocate their own. */
#define WS_POOL 16

typedef struct server {
    config cfg;
    struct MHD_Daemon *daemon;
    metrics m;
    char *openapi;               /* the file's text, NULL if it could not be read */
    size_t openapi_len;
    struct web *web;             /* the page's files, read at start-up (page.c) */
    atomic_int draining;         /* SIGTERM seen: /readyz says 503 */
    atomic_int abort_streams;    /* grace period over: streams end with an error line */
    atomic_llong connections_admitted; /* connections holding a --max-connections place (conn_admit) */
    atomic_llong requests_open;  /* requests begun and not completed (a body arriving, a stream): the drain waits
                                    for them, so a request that began before SIGTERM is answered, not cut */
    pthread_mutex_t conns_lock;  /* guards `conns`, the open connections (deadline.c) */
    struct conn *conns;
    _Atomic(dp_stability_ws *) ws_pool[WS_POOL]; /* NULL or an idle workspace, taken by exchange */
    pthread_mutex_t slots_lock;  /* guards the solver slots and their queue (slots.c) */
    int slots_open;              /* shutdown: every request goes through */
    struct request *wait_head, *wait_tail; /* requests parked for a slot, first come first served */
    pthread_mutex_t jobs_lock;   /* guards the job queue; a job's connection is suspended and resumed under it */
    pthread_cond_t jobs_cond;    /* a job was queued, or the compute threads are to end */
    struct job *jobs_head, *jobs_tail; /* queued for the compute threads (jobs.c) */
    int jobs_quit;               /* jobs_stop: the threads end once the queue is empty; no job is queued after */
    pthread_t *job_threads;      /* the compute threads, job_nthreads of them (0: jobs run inline) */
    unsigned job_nthreads;
} server;

typedef struct stream stream;

typedef struct request {
    server *srv;
    struct request *wait_next;   /* the slot queue (slots.c) */
    struct MHD_Connection *wait_conn;
    int slot_held, slot_granted; /* holds a solver slot; one was handed over while it was parked */
    atomic_int refs;             /* 1, or 2 while a streamed response holds it */
    int route;                   /* ROUTE_* */
    const char *allow;           /* wrong method: the methods the path takes (a static string), else NULL */
    int status;                  /* HTTP status queued, 0 until then */
    int too_large;               /* the body passed cfg.body_limit */
    int close;                   /* the response closes the connection (a framing fault) */
    double t_start;              /* monotonic seconds */
    unsigned long long bytes;    /* body bytes sent (streams count as they go) */
    dp_buf body;                 /* the request body as it arrives */
    char method[16];
    char path[256];              /* the URL as received, truncated */
    stream *stream;              /* the streamed response's state, if any */
    struct job *job;             /* its computation on the compute threads, if any (jobs.c) */
} request;

/* A zeroed server with its lock initialized (NULL when out of memory); server_free releases it. */
server *server_new(void);
int server_start(server *s);
/* Stops accepting, lets runs finish within the grace period, then ends the rest with an error line. */
void server_shutdown(server *s);
void server_free(server *s);
/* Port actually bound. */
unsigned server_port(const server *s);
double now_seconds(void);

/* A request of server s (request.c): one reference, its start time taken; NULL if out of memory. */
request *request_new(server *s, const char *method, const char *url);
/* Drops a reference; the last one frees the request (and logs it). */
void request_release(request *r);

/* ---- responses (problem.c) ---- */

/* Queues a buffer response (takes ownership of body->data) with a content type; records the status. */
enum MHD_Result respond_buffer(struct MHD_Connection *c, request *r, int status, const char *type, dp_buf *body);
/* Queues an application/problem+json document (RFC 9457) with type, title, status, detail and, when errs has
 * any, "errors": [{"pointer", "detail"}]. `allow` (may be NULL) becomes an Allow header. */
enum MHD_Result respond_problem(struct MHD_Connection *c, request *r, int status, const char *type,
                                const char *detail, const dp_errors *errs, const char *allow);
/* The problem for a failed dp_status (syntax 400, invalid 422, limit 422, memory 503, ...). */
enum MHD_Result respond_status(struct MHD_Connection *c, request *r, int status, const char *detail,
                               const dp_errors *errs);
/* The outcome of a JSON-layer function that answered the body into `out`: 200 with `type`, or (out freed)
 * the problem for status s, a syntax error's message as its detail. */
enum MHD_Result respond_answer(struct MHD_Connection *c, request *r, int s, dp_buf *out, const dp_errors *errs,
                               const char *type);
/* A route whose answer is one JSON document computed from the body by `answer`: 406 unless JSON is
 * acceptable, then respond_answer. */
typedef int (*json_answer_fn)(const char *body, size_t len, dp_buf *out, dp_errors *errs);
enum MHD_Result respond_json_answer(struct MHD_Connection *c, request *r, json_answer_fn answer);

/* ---- routes (routes.c, simulate.c, stability.c) ---- */

/* The ROUTE_* of a path (ROUTE_NONE if unknown); *allow is set to the methods it takes when `method` is not
 * one of them (then the answer is 405), NULL otherwise. */
int route_find(const server *s, const char *method, const char *url, const char **allow);
int route_needs_body(int route);
enum MHD_Result route_dispatch(struct MHD_Connection *c, request *r);

enum MHD_Result handle_simulate(struct MHD_Connection *c, request *r);
enum MHD_Result handle_stability(struct MHD_Connection *c, request *r);
/* Frees the idle stability workspaces (server_free). */
void stability_pool_free(server *s);
enum MHD_Result handle_wellposedness(struct MHD_Connection *c, request *r);
enum MHD_Result handle_convergence(struct MHD_Connection *c, request *r);
/* POST /v1/modes and /v1/response (modes.c). */
enum MHD_Result handle_modes(struct MHD_Connection *c, request *r);
enum MHD_Result handle_response(struct MHD_Connection *c, request *r);
/* POST /v1/lcp (lcp.c). */
enum MHD_Result handle_lcp(struct MHD_Connection *c, request *r);
/* POST /v1/sweep (sweep.c): a stream of one line per run. */
enum MHD_Result handle_sweep(struct MHD_Connection *c, request *r);
/* GET /bench/static: the --bench-static file through the same chunked content-reader path as a stream. */
enum MHD_Result handle_bench_static(struct MHD_Connection *c, request *r);
/* Called by the stream's free callback: the run is gone; counts it as cancelled if it had not finished. */
void stream_free(stream *st);
/* The browser page (page.c): reads --web-dir at start-up; "/" and "/FILE" name it (page_route); GET / HEAD. */
void page_load(server *s);
void page_free(server *s);
int page_route(const server *s, const char *url);
enum MHD_Result handle_page(struct MHD_Connection *c, request *r);

/* ---- access control (auth.c) ---- */

/* The bearer token into c->token: the --token-file's first line, else DASHPOT_TOKEN, else none. 0, or -1
 * with a message on stderr (unreadable file, empty token, characters outside RFC 6750's b64token). */
int auth_load(config *c);
/* 1 when the request may go on: no token is set, the path is outside /v1/, or the request carries
 * "Authorization: Bearer <token>" (compared in time independent of where it differs). */
int auth_ok(const server *s, struct MHD_Connection *c, const char *url);

/* ---- solver slots (slots.c) ---- */

/* Takes one of the cfg.threads solver slots for r (1), or parks the connection (suspended, queued) and
 * returns 0: the caller then returns at once (MHD_YES from the access handler, 0 from a content reader) and
 * is called again when the slot has been handed to it. Call only from those two places. */
int slot_take(request *r, struct MHD_Connection *c);
/* Gives r's slot back (to the first parked request, if any); nothing if r holds none. */
void slot_give(request *r);
/* Up to `want` more slots for a request that holds one already (a sweep's further executors, sweep.c), taken
 * only if free now and no request is parked for one: never waits, never parks. How many were taken; each is
 * given back with slot_give_extra (from any thread). 0 at shutdown. */
unsigned slot_try_extra(server *s, unsigned want);
void slot_give_extra(server *s);
/* The slot r holds becomes one as slot_try_extra's, given back with slot_give_extra (by the thread that computes
 * on it, not when r completes). 1, or 0 when r holds none (at shutdown: nothing is counted then). */
int slot_detach(request *r);
/* Slots not taken now (0: every worker is computing; /readyz says busy). */
unsigned slots_free(server *s);
/* Shutdown: lets every request through from now on and resumes the parked ones. */
void slots_open(server *s);

/* ---- why a computation stops (watch.c) ---- */

enum { STOP_NONE, STOP_SHUTDOWN, STOP_DEADLINE, STOP_GONE };

/* What a computation for one request watches: the request's --max-wall, the end of the shutdown grace period,
 * the client's hang-up. Used by one thread at a time (the one computing). */
typedef struct watch {
    server *s;
    double deadline;             /* monotonic seconds: the request's start + cfg.max_wall */
    int fd;                      /* the connection's socket, watched for a hang-up (-1: not watched) */
    double peer_check;           /* monotonic seconds of the next look at the socket */
    int why;                     /* STOP_*: the first reason seen, which stays */
    double slice_end;            /* streams: monotonic seconds when the work in hand yields (watch_slice) */
    int yielded;                 /* ...and it did */
} watch;

/* Whether the client has closed or reset its connection: a recv that peeks (consumes nothing) without
 * waiting; 0 is its FIN, an error other than "nothing yet" its RST. Pipelined bytes read as "still here". */
int peer_gone(int fd);
/* A watch for r, whose socket is c's (c NULL: no hang-up watched). */
void watch_init(watch *w, request *r, struct MHD_Connection *c);
/* The reason to stop now (STOP_*, STOP_NONE to go on), `now` being now_seconds(). */
int watch_check(watch *w, double now);
/* The dp_stop hook over a watch (ctx): 1 to stop, 0 to go on. */
int watch_stop(void *ctx);
/* Streams (simulate.c, sweep.c) compute in slices so that their thread serves its other connections too:
 * watch_slice starts one of `seconds`, and watch_stop_sliced, the hook, then says 1 to stop (as watch_stop)
 * or -1 to yield once the slice is over (w->yielded is set), 0 to go on. */
void watch_slice(watch *w, double seconds);
int watch_stop_sliced(void *ctx);
/* Why it stopped, in words: "<what> exceeded the wall-time limit of N s", "the server is shutting down",
 * "the client has gone". */
void watch_detail(const watch *w, const char *what, char *out, size_t cap);
/* The answer of a request whose computation (`what`: "the study") the watch stopped: 503 /problems/timeout,
 * 503 /problems/shutting-down, or MHD_NO (the connection closes) for a client that has gone. */
enum MHD_Result respond_stopped(struct MHD_Connection *c, request *r, const watch *w, const char *what);

/* ---- jobs: computations on the compute threads (jobs.c) ---- */

/* One route's computation: the answer to r's body into out (and its type's choice, `arg`, made by the
 * handler from Accept), polling `stop`; a dp_status. Runs on a compute thread; reads r's body and the
 * server's configuration only. */
typedef int (*job_work)(request *r, int arg, const dp_stop *stop, dp_buf *out, dp_errors *errs);
/* The answer for a failure other than a stop (NULL: respond_answer's). */
typedef enum MHD_Result (*job_failed)(struct MHD_Connection *c, request *r, int status, const dp_errors *errs);

typedef struct job_route {
    job_work work;
    const char *what;            /* its name in the wall-time detail: "the study", "the computation" */
    job_failed failed;
} job_route;

/* Starts the cfg.threads compute threads (none when cfg.embedded: jobs then run inline). 0, or -1. */
int jobs_start(server *s);
/* Ends the compute threads once every queued job is done (call with the abort flag set, so that they end at
 * once); their connections are resumed. From then on a job is answered 503 /problems/shutting-down at once.
 * Idempotent. */
void jobs_stop(server *s);
/* Hands r's computation to a compute thread: r's connection is suspended until it is done, then the access
 * handler is called again and route_dispatch answers it (job_answer). Returns MHD_YES (or an answer, when
 * jobs run inline or no longer run). r keeps its solver slot meanwhile. */
enum MHD_Result job_submit(struct MHD_Connection *c, request *r, const job_route *route, int arg, const char *type);
/* A route answering one JSON document: 406 unless JSON is acceptable, then job_submit. */
enum MHD_Result job_submit_json(struct MHD_Connection *c, request *r, const job_route *route);
/* A job of r computes now (its slot is still needed). */
int job_pending(const request *r);
/* The answer of r's finished job: 200 with its type, the stop's problem, or the failure's; frees the job. */
enum MHD_Result job_answer(struct MHD_Connection *c, request *r);
/* Frees a job of r that was never answered (its connection closed on resuming); on_completed. */
void job_free(request *r);

/* ---- request deadlines (deadline.c) ---- */

/* A request must arrive whole (head and body) within cfg.timeout seconds of its connection becoming ready
 * for it (opened, or the previous response sent); MHD's own timeout only bounds idleness, which a client
 * sending a byte at a time never reaches. The NOTIFY_CONNECTION callback registers connections; the main
 * thread calls deadline_sweep a few times a second and shuts down the sockets of late ones. */
void deadline_open(server *s, struct MHD_Connection *c, void **socket_context);
void deadline_close(server *s, void **socket_context);
/* The request has arrived (1) or its response is done and the next one's clock starts (0). */
void deadline_mark(struct MHD_Connection *c, int arrived);
/* Whether connection c may be served: it holds, or now takes, one of the cfg.max_connections places. */
int conn_admit(server *s, struct MHD_Connection *c);
/* Shuts down connections past their deadline; returns how many. */
unsigned deadline_sweep(server *s);

/* ---- content negotiation (negotiate.c) ---- */

/* Index of the media type in offers[0..n) that the Accept header prefers (q > 0), offers[0] when the header
 * is absent or empty, -1 when it accepts none of them. */
int negotiate(const char *accept, const char *const *offers, int n);

/* ---- logging (log.c) ---- */

/* One line on stderr per request: time, method, path (escaped), status, bytes, duration. */
void log_request(const request *r, double seconds);
/* A free-form line prefixed with the time, for start-up and shutdown. */
void log_line(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

#endif
