/* src/http/server.c - libmicrohttpd set-up and the request lifecycle, as libmicrohttpd's own examples do it:
 * state on the first callback, the body read under a cap, everything freed in the completed callback.
 *
 * MHD calls the access handler at least twice per request: the first call allocates the request state and
 * resolves the route; it answers only an overload (503), a missing bearer token (401) or a declared
 * Content-Length over the limit (413): refusing before the upload saves reading it, and MHD then skips
 * "100 Continue" and closes. Later calls
 * accumulate the body under the cap (only for routes that take one); the call with *upload_data_size == 0
 * dispatches. The NOTIFY_COMPLETED callback logs, counts and releases the request.
 */
#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

#include "http.h"

/* Per-connection memory: the read buffer for headers and the write buffer the content reader fills. MHD
 * (0.9.75) zeroes the whole pool before every request of a connection, so its size is paid by every small
 * request. On the reference machine (48 KiB L1) glibc zeroes up to 48 KiB in 0.17-0.27 us and 56-64 KiB in
 * 1.2-1.35 us (it changes strategy past that size), and a small request of any route costs 1.5-2 us less
 * CPU at 48 KiB than at 64. Streams need the room: at 32 KiB they send 32 KiB per sendmsg and lose 5-10%
 * of their samples/s; at 48 KiB they are as fast as at 64. */
#define CONNECTION_MEMORY (48u << 10)
/* Connections MHD accepts beyond --max-connections, to tell them "503" rather than drop them silently. */
#define OVERLOAD_HEADROOM 64u

/* Content-Length above the limit: known before any byte of the body is read. */
static int declared_too_large(struct MHD_Connection *c, size_t limit)
{
    const char *cl = MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_CONTENT_LENGTH);
    if (cl == NULL)
        return 0;
    char *end;
    unsigned long long n = strtoull(cl, &end, 10);
    return end != cl && n > limit;
}

/* What the framing headers of a request say (RFC 9112 sections 3.2 and 6): counted over every field line,
 * since MHD's lookup only returns the first of repeated ones. */
typedef struct framing {
    unsigned hosts, lengths, encodings;
    int lengths_differ, not_chunked;
    const char *length;
} framing;

static enum MHD_Result count_framing(void *cls, enum MHD_ValueKind kind, const char *key, const char *value)
{
    (void)kind;
    framing *f = cls;
    if (strcasecmp(key, MHD_HTTP_HEADER_HOST) == 0) {
        f->hosts++;
    } else if (strcasecmp(key, MHD_HTTP_HEADER_CONTENT_LENGTH) == 0) {
        if (f->lengths++ && strcmp(f->length, value) != 0)
            f->lengths_differ = 1;
        f->length = value;
    } else if (strcasecmp(key, MHD_HTTP_HEADER_TRANSFER_ENCODING) == 0) {
        f->encodings++;
        f->not_chunked |= strcasecmp(value, "chunked") != 0; /* the only coding the daemon decodes */
    }
    return MHD_YES;
}

/* The framing fault of a request, NULL if none: a body whose length two headers tell differently, a
 * missing or repeated Host on HTTP/1.1. Answered 400 with the connection closed, since whatever follows
 * on it cannot be told apart from this request's body (request smuggling). */
static const char *framing_fault(struct MHD_Connection *c, const char *version)
{
    framing f = { 0 };
    MHD_get_connection_values(c, MHD_HEADER_KIND, count_framing, &f);
    if (f.lengths_differ)
        return "two different Content-Length values";
    if (f.lengths && f.encodings)
        return "Content-Length together with Transfer-Encoding";
    if (f.encodings > 1 || f.not_chunked)
        return "a Transfer-Encoding other than chunked";
    if (strcmp(version, MHD_HTTP_VERSION_1_0) != 0 && f.hosts != 1)
        return f.hosts ? "more than one Host header" : "no Host header (HTTP/1.1 requires one)";
    return NULL;
}

/* The first call: answers what can be answered without the body, or returns -1 to go on. */
static int first_call(struct MHD_Connection *c, request *r, const char *method, const char *url,
                      const char *version)
{
    server *s = r->srv;
    r->route = route_find(s, method, url, &r->allow);
    const char *fault = framing_fault(c, version);
    if (fault) {
        r->close = 1;
        return respond_problem(c, r, 400, "/problems/bad-framing", fault, NULL, NULL);
    }
    if (!conn_admit(s, c)) {
        atomic_fetch_add(&s->m.connections_rejected, 1);
        r->close = 1; /* its place in MHD's table goes back at once */
        return respond_problem(c, r, 503, "/problems/overloaded", "too many open connections; retry shortly",
                               NULL, NULL);
    }
    if (!auth_ok(s, c, url))
        return respond_problem(c, r, 401, "/problems/unauthorized",
                               "this route needs the header Authorization: Bearer <token>", NULL, NULL);
    if (r->allow == NULL && route_needs_body(r->route) && declared_too_large(c, s->cfg.body_limit)) {
        char detail[96];
        snprintf(detail, sizeof detail, "the request body is larger than %zu bytes", s->cfg.body_limit);
        return respond_problem(c, r, 413, NULL, detail, NULL, NULL);
    }
    return -1;
}

/* Appends an upload piece, or only notes that the body passed the limit (the rest is read and dropped). */
static void accumulate(request *r, const char *data, size_t n)
{
    if (r->too_large || r->allow || !route_needs_body(r->route))
        return;
    if (r->body.len + n > r->srv->cfg.body_limit || dp_buf_append(&r->body, data, n) != DP_OK) {
        r->too_large = 1;
        dp_buf_free(&r->body);
    }
}

static enum MHD_Result on_request(void *cls, struct MHD_Connection *c, const char *url, const char *method,
                                  const char *version, const char *upload_data, size_t *upload_data_size,
                                  void **con_cls)
{
    request *r = *con_cls;
    if (r == NULL) {
        if ((r = request_new(cls, method, url)) == NULL)
            return MHD_NO;
        *con_cls = r;
        atomic_fetch_add(&((server *)cls)->requests_open, 1);
        int answered = first_call(c, r, method, url, version);
        if (answered >= 0)
            deadline_mark(c, 1);
        return answered < 0 ? MHD_YES : (enum MHD_Result)answered;
    }
    if (*upload_data_size) {
        if (r->status == 0)
            accumulate(r, upload_data, *upload_data_size);
        *upload_data_size = 0;
        return MHD_YES;
    }
    if (r->status)
        return MHD_YES;
    deadline_mark(c, 1);
    return route_dispatch(c, r);
}

static void on_completed(void *cls, struct MHD_Connection *c, void **con_cls, enum MHD_RequestTerminationCode toe)
{
    (void)toe;
    server *s = cls;
    request *r = *con_cls;
    if (r == NULL)
        return;
    *con_cls = NULL;
    atomic_fetch_sub(&s->requests_open, 1);
    slot_give(r); /* a slot it holds or was handed (a stream gives its own back in stream_free) */
    job_free(r);  /* a finished job whose connection closed on resuming (a job in flight keeps it suspended) */
    deadline_mark(c, 0);
    double dt = now_seconds() - r->t_start;
    metrics_request(&s->m, r->route, r->status, dt);
    if (!s->cfg.quiet)
        log_request(r, dt);
    request_release(r);
}

static void on_connection(void *cls, struct MHD_Connection *c, void **socket_context,
                          enum MHD_ConnectionNotificationCode code)
{
    server *s = cls;
    int started = code == MHD_CONNECTION_NOTIFY_STARTED;
    atomic_fetch_add(&s->m.connections_open, started ? 1 : -1);
    if (started)
        deadline_open(s, c, socket_context);
    else
        deadline_close(s, socket_context);
}

static int hex_digit(char ch)
{
    return ch >= '0' && ch <= '9' ? ch - '0' : ch >= 'a' && ch <= 'f' ? ch - 'a' + 10
         : ch >= 'A' && ch <= 'F' ? ch - 'A' + 10 : -1;
}

/* Unescapes %HH in the path and query as MHD's own unescaper does, except %00: decoded, it would end the C
 * string MHD hands to the handler, so "/healthz%00anything" would be served as "/healthz". Left as it is,
 * it matches no route (404) and shows in the log as sent. */
static size_t unescape_keep_nul(void *cls, struct MHD_Connection *c, char *str)
{
    (void)cls, (void)c;
    char *w = str;
    for (const char *r = str; *r;) {
        int hi = r[0] == '%' ? hex_digit(r[1]) : -1, lo = hi >= 0 ? hex_digit(r[2]) : -1;
        if (lo >= 0 && (hi | lo) != 0) {
            *w++ = (char)(hi * 16 + lo);
            r += 3;
        } else {
            *w++ = *r++;
        }
    }
    *w = '\0';
    return (size_t)(w - str);
}

static void on_mhd_error(void *cls, const char *fmt, va_list ap)
{
    const server *s = cls;
    if (s->cfg.quiet)
        return;
    char msg[512];
    vsnprintf(msg, sizeof msg, fmt, ap);
    msg[strcspn(msg, "\n")] = '\0';
    /* A client that hangs up mid-response is routine (its run is cancelled and counted); say so, so that the
     * line does not read like a failure of the daemon. */
    static const char *const hang_up[] = { "Failed to send", "closed by remote", "no longer available for sending" };
    for (size_t i = 0; i < sizeof hang_up / sizeof hang_up[0]; i++)
        if (strstr(msg, hang_up[i]) != NULL) {
            log_line("client hung up (not an error of the daemon): libmicrohttpd: %s", msg);
            return;
        }
    log_line("libmicrohttpd: %s", msg);
}

/* Reads a whole file into a malloc'd buffer; NULL if it cannot. */
static char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    dp_buf b = { 0 };
    char chunk[8192];
    size_t n;
    while ((n = fread(chunk, 1, sizeof chunk, f)) > 0)
        if (dp_buf_append(&b, chunk, n) != DP_OK)
            break;
    int bad = ferror(f) || !feof(f);
    fclose(f);
    if (bad || b.data == NULL) {
        dp_buf_free(&b);
        return NULL;
    }
    *len = b.len;
    return b.data;
}

/* --openapi where data_path finds it: as given, beside the binary or in its parent (build/dashpotd finds
 * api/openapi.yaml from anywhere), or for the default, ../share/dashpot/openapi.yaml (an installed one). */
static void load_openapi(server *s)
{
    char path[8300];
    int is_default = strcmp(s->cfg.openapi, DEFAULT_OPENAPI) == 0;
    if (data_path(s->cfg.openapi, is_default ? INSTALLED_OPENAPI : NULL, 0, path, sizeof path) == 0)
        s->openapi = read_file(path, &s->openapi_len);
    if (s->openapi == NULL)
        log_line("warning: %s not found; /openapi.yaml will answer 404", s->cfg.openapi);
    else
        log_line("serving the OpenAPI document from %s", path);
}

static int make_address(const config *cfg, struct sockaddr_storage *sa, int *ipv6)
{
    memset(sa, 0, sizeof *sa);
    struct sockaddr_in *v4 = (struct sockaddr_in *)sa;
    struct sockaddr_in6 *v6 = (struct sockaddr_in6 *)sa;
    if (inet_pton(AF_INET, cfg->bind, &v4->sin_addr) == 1) {
        v4->sin_family = AF_INET;
        v4->sin_port = htons((uint16_t)cfg->port);
        *ipv6 = 0;
        return 0;
    }
    if (inet_pton(AF_INET6, cfg->bind, &v6->sin6_addr) == 1) {
        v6->sin6_family = AF_INET6;
        v6->sin6_port = htons((uint16_t)cfg->port);
        *ipv6 = 1;
        return 0;
    }
    return -1;
}

int server_start(server *s)
{
    struct sockaddr_storage sa;
    int ipv6 = 0, embedded = s->cfg.embedded;
    if (!embedded && make_address(&s->cfg, &sa, &ipv6) != 0) {
        log_line("error: --bind %s is not an IPv4 or IPv6 address", s->cfg.bind);
        return -1;
    }
    load_openapi(s);
    page_load(s);
    if (jobs_start(s) != 0) {
        log_line("error: cannot start %u compute threads", s->cfg.threads);
        return -1;
    }
    unsigned flags = embedded ? MHD_USE_NO_LISTEN_SOCKET | MHD_USE_ERROR_LOG | MHD_ALLOW_SUSPEND_RESUME
                              : MHD_USE_EPOLL_INTERNAL_THREAD | MHD_USE_ITC | MHD_USE_TURBO | MHD_USE_ERROR_LOG |
                                    MHD_ALLOW_SUSPEND_RESUME | (ipv6 ? MHD_USE_IPv6 : 0);
    /* Function pointers travel as intptr_t in MHD_OptionItem.value (MHD's documented convention). */
    struct MHD_OptionItem opts[] = {
        { MHD_OPTION_EXTERNAL_LOGGER, (intptr_t)on_mhd_error, s }, /* first, so that it sees every message */
        { MHD_OPTION_CONNECTION_LIMIT, (intptr_t)(s->cfg.max_connections + OVERLOAD_HEADROOM), NULL },
        { MHD_OPTION_CONNECTION_TIMEOUT, (intptr_t)s->cfg.timeout, NULL },
        { MHD_OPTION_CONNECTION_MEMORY_LIMIT, (intptr_t)CONNECTION_MEMORY, NULL },
        { MHD_OPTION_NOTIFY_COMPLETED, (intptr_t)on_completed, s },
        { MHD_OPTION_NOTIFY_CONNECTION, (intptr_t)on_connection, s },
        { MHD_OPTION_UNESCAPE_CALLBACK, (intptr_t)unescape_keep_nul, NULL },
        { embedded ? MHD_OPTION_END : MHD_OPTION_SOCK_ADDR, 0, &sa },
        /* one thread more than solver slots (slots.c): the small routes never wait behind a stream's block */
        { MHD_OPTION_THREAD_POOL_SIZE, (intptr_t)(s->cfg.threads + 1), NULL },
        { MHD_OPTION_END, 0, NULL },
    };
    s->daemon = MHD_start_daemon(flags, (uint16_t)s->cfg.port, NULL, NULL, on_request, s, MHD_OPTION_ARRAY, opts,
                                 MHD_OPTION_END);
    if (s->daemon == NULL) {
        log_line("error: cannot listen on %s port %u (in use? pick another with --port N or DASHPOT_PORT=N; "
                 "0 takes any free port)", s->cfg.bind, s->cfg.port);
        return -1;
    }
    return 0;
}

unsigned server_port(const server *s)
{
    const union MHD_DaemonInfo *info = MHD_get_daemon_info(s->daemon, MHD_DAEMON_INFO_BIND_PORT);
    return info ? info->port : s->cfg.port;
}

/* Waits until no run or study is in flight and no request is open (one whose body was still arriving when
 * the signal came becomes a run, or a 503 since draining is set), or `seconds` pass; returns how many runs
 * and requests still are. Connections keep their request deadline meanwhile. */
static long long wait_runs(server *s, double seconds)
{
    double until = now_seconds() + seconds;
    long long n;
    while ((n = atomic_load(&s->m.runs_in_flight) + atomic_load(&s->m.studies_in_flight) +
                atomic_load(&s->requests_open)) > 0 &&
           now_seconds() < until) {
        struct timespec ts = { 0, 20 * 1000 * 1000 };
        nanosleep(&ts, NULL);
        deadline_sweep(s);
    }
    return n;
}

/* Seconds streams get to write their error line once the grace period is over. */
#define ABORT_WAIT 2.0

void server_shutdown(server *s)
{
    atomic_store(&s->draining, 1);
    MHD_socket fd = MHD_quiesce_daemon(s->daemon);
    if (fd != MHD_INVALID_SOCKET)
        close(fd);
    long long left = wait_runs(s, s->cfg.shutdown_grace);
    if (left > 0) {
        log_line("shutdown: grace period over, ending what is open (%lld runs and requests) with an error line",
                 left);
        atomic_store(&s->abort_streams, 1);
        slots_open(s);
        left = wait_runs(s, ABORT_WAIT);
    }
    /* From here on whatever still begins (a request on a kept-alive connection) stops at once. MHD must not be
     * stopped with connections suspended: parked ones are let through, and every job ends and resumes its. */
    atomic_store(&s->abort_streams, 1);
    slots_open(s);
    jobs_stop(s);
    if (left > 0)
        log_line("shutdown: closing %lld stalled stream(s)", left);
    MHD_stop_daemon(s->daemon);
    s->daemon = NULL;
}

server *server_new(void)
{
    server *s = calloc(1, sizeof *s);
    if (s == NULL)
        return NULL;
    int locks = pthread_mutex_init(&s->conns_lock, NULL) == 0;
    locks += locks == 1 && pthread_mutex_init(&s->slots_lock, NULL) == 0;
    locks += locks == 2 && pthread_mutex_init(&s->jobs_lock, NULL) == 0;
    locks += locks == 3 && pthread_cond_init(&s->jobs_cond, NULL) == 0;
    if (locks == 4)
        return s;
    if (locks > 2)
        pthread_mutex_destroy(&s->jobs_lock);
    if (locks > 1)
        pthread_mutex_destroy(&s->slots_lock);
    if (locks > 0)
        pthread_mutex_destroy(&s->conns_lock);
    free(s);
    return NULL;
}

void server_free(server *s)
{
    if (s == NULL)
        return;
    if (s->daemon) { /* not shut down (an embedded server): nothing of it computes or is suspended */
        atomic_store(&s->abort_streams, 1);
        slots_open(s);
        jobs_stop(s);
        MHD_stop_daemon(s->daemon);
    }
    jobs_stop(s); /* threads of a start that failed after them */
    free(s->openapi);
    page_free(s);
    stability_pool_free(s);
    pthread_mutex_destroy(&s->conns_lock);
    pthread_mutex_destroy(&s->slots_lock);
    pthread_mutex_destroy(&s->jobs_lock);
    pthread_cond_destroy(&s->jobs_cond);
    free(s);
}
