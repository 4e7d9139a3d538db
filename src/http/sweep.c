/* src/http/sweep.c - POST /v1/sweep: a simulate document over a grid of parameters, one line per run as it
 * completes (docs/sweep.md), streamed as simulate.c streams a run.
 *
 * The runs go one after another on the request's solver slot, in slices: a content-reader call computes until
 * a line is ready or SLICE seconds passed, then lets the thread serve its other connections. The stop hook is
 * simulate's: the end of the shutdown grace period, --max-wall for the whole sweep, and the client's hang-up
 * end the sweep within a bounded amount of work; a stop, like a spent step budget (--max-steps times
 * DP_SWEEP_STEP_FACTOR for the whole sweep), is the format's error line, never a silent cut. A run that fails
 * is its own line and the sweep goes on. A bad document is a 422 before the first byte, by pointer.
 *
 * Formats (Accept): application/x-ndjson (the default: meta, run lines, summary), text/event-stream (the same
 * objects as events "meta", "run", "summary", "error"), application/json (one document
 * {"meta", "runs": [...], "summary"} or, on a stop, "error" in place of "summary").
 */
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/json.h"
#include "dashpot/sweep_json.h"
#include "http.h"

#define READ_BLOCK (64u << 10)
/* Text gathered before a call hands it over: a few run lines, or one with a long section. */
#define FLUSH_BYTES (32u << 10)
#define SLICE 0.01               /* as simulate.c: seconds of work before the thread serves others */

enum { F_NDJSON, F_SSE, F_JSON };

typedef struct sweep_stream {
    request *r;
    server *s;
    struct MHD_Connection *conn;
    dp_sweep_doc *doc;
    dp_sweep_exec *x;
    int format;
    dp_buf out, line;
    size_t off, lines;
    int closed, delivered, failed;
    watch w;            /* --max-wall for the whole sweep, shutdown, the client's hang-up (watch.c) */
    _Atomic unsigned long long budget;
} sweep_stream;

static int put(dp_buf *b, const char *s)
{
    return dp_buf_append(b, s, strlen(s));
}

/* One object of kind `type` ("meta", "run", "summary", "error") framed for the format. */
static int frame(sweep_stream *st, const char *type, const dp_buf *obj)
{
    dp_buf *b = &st->out;
    int s = DP_OK;
    if (st->format == F_SSE) {
        s = put(b, "event: ");
        s = s ? s : put(b, type);
        s = s ? s : put(b, "\ndata: ");
    } else if (st->format == F_JSON) {
        int run = strcmp(type, "run") == 0;
        s = put(b, strcmp(type, "meta") == 0 ? "{\"meta\":" : run ? (st->lines++ ? ",\n" : "") :
                   strcmp(type, "summary") == 0 ? "],\"summary\":" : "],\"error\":");
    }
    s = s ? s : dp_buf_append(b, obj->data, obj->len);
    s = s ? s : put(b, st->format == F_SSE ? "\n\n" : st->format == F_NDJSON ? "\n" :
                       strcmp(type, "meta") == 0 ? ",\"runs\":[\n" : strcmp(type, "run") == 0 ? "" : "}\n");
    return s;
}

/* The closing error object ({"type":"error","status","title","detail"}). */
static void sweep_fail(sweep_stream *st, int status, const char *detail)
{
    char head[96];
    snprintf(head, sizeof head, "{\"type\":\"error\",\"status\":%d,\"title\":", dp_status_http(status));
    st->line.len = 0;
    int s = put(&st->line, head);
    s = s ? s : dp_json_quote(&st->line, dp_strerror(status));
    s = s ? s : put(&st->line, ",\"detail\":");
    s = s ? s : dp_json_quote(&st->line, detail);
    s = s ? s : put(&st->line, "}");
    if (s == DP_OK)
        frame(st, "error", &st->line);
    st->closed = st->failed = 1;
}

static void stopped(sweep_stream *st)
{
    char detail[128];
    watch_detail(&st->w, "the sweep", detail, sizeof detail);
    sweep_fail(st, DP_ECANCEL, detail);
}

/* Runs the sweep until a slice ends or enough text waits; the last status of the executor. */
static int sweep_fill(sweep_stream *st)
{
    watch_slice(&st->w, SLICE);
    int s = DP_MORE, ready;
    const char *why;
    while (s == DP_MORE && !st->w.yielded && st->out.len < FLUSH_BYTES) {
        if (watch_stop_sliced(&st->w) > 0) {
            stopped(st);
            return DP_ECANCEL;
        }
        st->line.len = 0;
        s = dp_sweep_exec_next(st->x, &st->line, &ready, &why);
        if (ready && frame(st, "run", &st->line) != DP_OK)
            s = DP_ENOMEM, why = dp_strerror(DP_ENOMEM);
    }
    if (s == DP_DONE) {
        st->line.len = 0;
        if (dp_sweep_summary_json(dp_sweep_doc_count(st->doc), dp_sweep_exec_totals(st->x), &st->line) != DP_OK ||
            frame(st, "summary", &st->line) != DP_OK)
            sweep_fail(st, DP_ENOMEM, dp_strerror(DP_ENOMEM));
        st->closed = 1;
    } else if (s == DP_ECANCEL && st->w.why != STOP_NONE) {
        stopped(st);
    } else if (s < 0) {
        sweep_fail(st, s, why ? why : dp_strerror(s));
    }
    return s;
}

static ssize_t sweep_read(void *cls, uint64_t pos, char *buf, size_t max)
{
    (void)pos;
    sweep_stream *st = cls;
    if (st->w.why == STOP_GONE)
        return MHD_CONTENT_READER_END_WITH_ERROR;
    while (st->off == st->out.len) {
        if (st->closed) {
            st->delivered = 1;
            return MHD_CONTENT_READER_END_OF_STREAM;
        }
        if (!slot_take(st->r, st->conn))
            return 0;
        st->out.len = st->off = 0;
        sweep_fill(st);
        if (!st->w.yielded || st->off != st->out.len)
            slot_give(st->r);
        if (st->w.why == STOP_GONE)
            return MHD_CONTENT_READER_END_WITH_ERROR;
        if (st->w.yielded && st->off == st->out.len) {
            MHD_suspend_connection(st->conn);
            MHD_resume_connection(st->conn);
            return 0;
        }
    }
    size_t n = st->out.len - st->off < max ? st->out.len - st->off : max;
    memcpy(buf, st->out.data + st->off, n);
    st->off += n;
    st->r->bytes += n;
    atomic_fetch_add_explicit(&st->s->m.bytes_streamed, n, memory_order_relaxed);
    return (ssize_t)n;
}

static void sweep_free(void *cls)
{
    sweep_stream *st = cls;
    metrics *m = &st->s->m;
    if (!st->delivered)
        atomic_fetch_add(&m->runs_cancelled, 1);
    else
        atomic_fetch_add(st->failed ? &m->runs_failed : &m->runs_completed, 1);
    atomic_fetch_sub(&m->runs_in_flight, 1);
    slot_give(st->r);
    dp_sweep_exec_free(st->x);
    dp_sweep_doc_free(st->doc);
    dp_buf_free(&st->out);
    dp_buf_free(&st->line);
    request_release(st->r);
    free(st);
}

/* A stream over doc (owned from here on), its meta object framed; NULL when out of memory. */
static sweep_stream *sweep_new(struct MHD_Connection *c, request *r, dp_sweep_doc *doc, int format)
{
    const config *cfg = &r->srv->cfg;
    sweep_stream *st = calloc(1, sizeof *st);
    if (st == NULL) {
        dp_sweep_doc_free(doc);
        return NULL;
    }
    *st = (sweep_stream){ .r = r, .s = r->srv, .conn = c, .doc = doc, .format = format };
    watch_init(&st->w, r, c);
    st->x = dp_sweep_exec_new(doc, 0, 1, cfg->max_steps, &st->budget, cfg->max_steps * DP_SWEEP_STEP_FACTOR);
    atomic_fetch_add(&r->refs, 1);
    atomic_fetch_add(&st->s->m.runs_started, 1);
    atomic_fetch_add(&st->s->m.runs_in_flight, 1);
    if (st->x == NULL || dp_sweep_meta_json(doc, cfg->max_steps, &st->line) != DP_OK ||
        frame(st, "meta", &st->line) != DP_OK) {
        st->delivered = st->failed = 1;
        sweep_free(st);
        return NULL;
    }
    dp_sweep_exec_set_stop(st->x, watch_stop_sliced, &st->w);
    return st;
}

enum MHD_Result handle_sweep(struct MHD_Connection *c, request *r)
{
    static const char *const offers[] = { "application/x-ndjson", "text/event-stream", "application/json" };
    int f = negotiate(MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT), offers, 3);
    if (f < 0)
        return respond_problem(c, r, 406, NULL, "this route answers application/x-ndjson, text/event-stream or "
                               "application/json", NULL, NULL);
    dp_errors errs;
    dp_errors_init(&errs);
    dp_sweep_doc *doc;
    int s = dp_sweep_parse(r->body.data ? r->body.data : "", r->body.len, &doc, &errs);
    if (s != DP_OK)
        return respond_status(c, r, s, s == DP_ESYNTAX && errs.n ? errs.item[0].message : NULL, &errs);
    sweep_stream *st = sweep_new(c, r, doc, f);
    if (st == NULL)
        return respond_status(c, r, DP_ENOMEM, NULL, NULL);
    struct MHD_Response *resp =
        MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, READ_BLOCK, sweep_read, st, sweep_free);
    if (resp == NULL) {
        sweep_free(st);
        return MHD_NO;
    }
    MHD_add_response_header(resp, MHD_HTTP_HEADER_CONTENT_TYPE, offers[f]);
    MHD_add_response_header(resp, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    MHD_add_response_header(resp, "X-Accel-Buffering", "no");
    r->status = 200;
    enum MHD_Result ok = MHD_queue_response(c, 200, resp);
    MHD_destroy_response(resp);
    return ok;
}
