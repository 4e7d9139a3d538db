/* src/http/simulate.c - POST /v1/simulate: parse, run, and stream the samples as the client reads them.
 *
 * The response is chunked and pulled: MHD calls stream_read only when the socket can take more, and only
 * then does the solver advance by one block (BLOCK records, ~50 KiB of text). So a run of 10^8 steps
 * streams in the memory of one block, a slow client slows the run down instead of filling memory, and a
 * client that hangs up stops its run at once (MHD stops calling, then frees the response: stream_free).
 *
 * Everything that can fail before the first byte (format, body, spec, the first block) is answered with a
 * problem document; a failure later (divergence, the wall-time limit, shutdown) becomes the format's error
 * line, so a stream is never silently cut.
 *
 * A run that ends within its first block (up to 512 records: every small request) is answered whole, as
 * a buffer with a Content-Length: the same bytes, but libmicrohttpd then sends head and body in one
 * sendmsg instead of three sends (head, chunk, last chunk), and allocates no 64 KiB reader block.
 * Measured on the 2-sample request of bench/http.sh: that was most of what it cost beyond /healthz.
 */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/json.h"
#include "dashpot/run.h"
#include "http.h"

/* Records per solver block: ~100 bytes each as NDJSON, so a block is ~50 KiB, about what MHD asks for. */
#define BLOCK 512
/* Bytes MHD asks the reader for at most per call (bounded by the connection's memory too). */
#define READ_BLOCK (64u << 10)
/* The meta object (~1.3 KB with its well-posedness report) and a small run's whole answer: reserved at
 * once rather than grown from 256 bytes by doubling, copying each time. */
#define META_BYTES 2048
#define SMALL_ANSWER_BYTES 4096

struct stream {
    request *r;
    server *s;
    dp_run *run;
    dp_encoder enc;
    dp_buf out;           /* encoded text not yet handed to MHD: out.data[off..len) */
    size_t off;
    int closed;           /* the summary or the error line is in `out` */
    int failed;           /* ...and it was an error */
    int delivered;        /* MHD was told END_OF_STREAM: the client got everything */
    struct MHD_Connection *conn; /* parked there when no solver slot is free (slots.c) */
    watch w;              /* --max-wall, shutdown, the client's hang-up (watch.c); w.why: why the run stopped */
    dp_record recs[BLOCK];
};

static const char *const offers[] = { "application/json", "application/x-ndjson", "text/event-stream",
                                      "text/csv" };
static const dp_format offer_format[] = { DP_FORMAT_JSON, DP_FORMAT_NDJSON, DP_FORMAT_SSE, DP_FORMAT_CSV };

/* Seconds of solver work one call computes before it yields: libmicrohttpd pins each connection to one
 * pool thread, so a block computed for seconds would hold up every other connection of that thread
 * (a health probe among them), however many threads are free. */
#define SLICE 0.01

/* Writes the closing error (its encoding failing too leaves the stream to end as it is). */
static void stream_fail(stream *st, int status, const char *detail)
{
    dp_encoder_fail(&st->enc, &st->out, status, detail);
    st->closed = st->failed = 1;
}

/* One block: the solver's next records, encoded and appended to `out`. Returns the run's status. */
static int stream_fill(stream *st)
{
    size_t n = 0, samples = 0;
    watch_slice(&st->w, SLICE);
    int s = watch_stop_sliced(&st->w) > 0 ? DP_ECANCEL : dp_run_next(st->run, st->recs, BLOCK, &n);
    if (s == DP_ECANCEL && st->w.why != STOP_NONE) {
        char detail[128];
        watch_detail(&st->w, "the run", detail, sizeof detail);
        stream_fail(st, DP_ECANCEL, detail);
        return DP_ECANCEL;
    }
    for (size_t i = 0; i < n; i++) {
        samples += st->recs[i].type == DP_RECORD_SAMPLE;
        if (dp_encoder_record(&st->enc, &st->out, &st->recs[i]) != DP_OK) {
            stream_fail(st, DP_ENOMEM, dp_strerror(DP_ENOMEM));
            return DP_ENOMEM;
        }
    }
    atomic_fetch_add_explicit(&st->s->m.samples_streamed, samples, memory_order_relaxed);
    if (s == DP_DONE) {
        st->closed = 1;
        if (dp_encoder_end(&st->enc, &st->out, dp_run_summary(st->run), NULL) != DP_OK)
            stream_fail(st, DP_ENOMEM, dp_strerror(DP_ENOMEM));
    } else if (s < 0) {
        const char *why = dp_run_error(st->run);
        stream_fail(st, s, why && *why ? why : dp_strerror(s));
    }
    return s;
}

static ssize_t stream_read(void *cls, uint64_t pos, char *buf, size_t max)
{
    (void)pos;
    stream *st = cls;
    if (st->w.why == STOP_GONE)
        return MHD_CONTENT_READER_END_WITH_ERROR; /* nobody to write the error line to */
    while (st->off == st->out.len) {
        if (st->closed) {
            st->delivered = 1;
            return MHD_CONTENT_READER_END_OF_STREAM;
        }
        if (!slot_take(st->r, st->conn))
            return 0; /* parked (suspended): called again once a slot is handed over */
        st->out.len = st->off = 0;
        int s = stream_fill(st);
        if (!st->w.yielded || st->off != st->out.len) /* a slice with nothing to send keeps its slot */
            slot_give(st->r);
        if (s == DP_ECANCEL && st->w.why == STOP_GONE)
            return MHD_CONTENT_READER_END_WITH_ERROR;
        if (st->w.yielded && st->off == st->out.len) { /* a slice, nothing to send yet: let the thread */
            MHD_suspend_connection(st->conn);         /* serve its other connections, then come back */
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

void stream_free(stream *st)
{
    if (st == NULL)
        return;
    metrics *m = &st->s->m;
    if (st->run) {
        const dp_summary *sum = dp_run_summary(st->run);
        atomic_fetch_add_explicit(&m->events, sum->events, memory_order_relaxed);
        atomic_fetch_add_explicit(&m->impacts, sum->impacts, memory_order_relaxed);
    }
    if (!st->delivered)
        atomic_fetch_add(&m->runs_cancelled, 1);
    else
        atomic_fetch_add(st->failed ? &m->runs_failed : &m->runs_completed, 1);
    atomic_fetch_sub(&m->runs_in_flight, 1);
    slot_give(st->r); /* held if the stream ended in the middle of a sliced block */
    dp_run_free(st->run);
    dp_encoder_clear(&st->enc);
    dp_buf_free(&st->out);
    request_release(st->r);
    free(st);
}

static void stream_free_cb(void *cls)
{
    stream_free(cls);
}

/* Parses the body into a run, writing its meta object; on failure answers with the problem (*answer) and
 * returns NULL. */
static dp_run *prepare(struct MHD_Connection *c, request *r, dp_buf *meta, enum MHD_Result *answer)
{
    const config *cfg = &r->srv->cfg;
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int st = dp_spec_parse(r->body.data ? r->body.data : "", r->body.len, cfg->max_steps, &spec, &errs);
    dp_run *run = NULL;
    if (st == DP_OK) {
        run = dp_run_alloc(&spec, cfg->max_steps, &errs, &st);
        if (run && dp_spec_meta_json(&spec, meta) != DP_OK) {
            dp_run_free(run);
            run = NULL;
            st = DP_ENOMEM;
        }
    }
    dp_spec_clear(&spec);
    if (run == NULL)
        *answer = respond_status(c, r, st, st == DP_ESYNTAX && errs.n ? errs.item[0].message : NULL, &errs);
    return run;
}

/* A stream over run (owned from here on, also on failure) with the opening already encoded. */
static stream *stream_new(struct MHD_Connection *c, request *r, dp_run *run, dp_format f, const char *meta)
{
    stream *st = malloc(sizeof *st);
    if (st == NULL) {
        dp_run_free(run);
        return NULL;
    }
    memset(st, 0, offsetof(stream, recs)); /* the record block (32 KiB) is written before it is read */
    st->r = r;
    st->s = r->srv;
    st->run = run;
    st->conn = c;
    watch_init(&st->w, r, c);
    dp_run_set_stop(run, watch_stop_sliced, &st->w);
    atomic_fetch_add(&r->refs, 1);
    atomic_fetch_add(&st->s->m.runs_started, 1);
    atomic_fetch_add(&st->s->m.runs_in_flight, 1);
    dp_encoder_init(&st->enc, f);
    dp_encoder_set_columns(&st->enc, dp_run_columns(run));
    if (dp_buf_reserve(&st->out, SMALL_ANSWER_BYTES) != DP_OK ||
        dp_encoder_begin(&st->enc, &st->out, meta) != DP_OK) {
        st->delivered = st->failed = 1; /* not a client's cancellation */
        stream_free(st);
        return NULL;
    }
    return st;
}

/* The run ended within its first block: the whole answer as one buffer (the stream's text, handed over). */
static enum MHD_Result whole(struct MHD_Connection *c, stream *st, dp_format f)
{
    request *r = st->r;
    dp_buf body = st->out;
    st->out = (dp_buf){ 0 };
    st->delivered = 1;
    atomic_fetch_add_explicit(&st->s->m.bytes_streamed, body.len, memory_order_relaxed);
    stream_free(st);
    return respond_buffer(c, r, 200, dp_format_content_type(f), &body);
}

/* The first block failed before any byte went out: a problem document instead of a stream. */
static enum MHD_Result early_failure(struct MHD_Connection *c, stream *st, int s)
{
    char why[DP_MESSAGE_MAX];
    snprintf(why, sizeof why, "%s", *dp_run_error(st->run) ? dp_run_error(st->run) : dp_strerror(s));
    request *r = st->r;
    st->delivered = st->failed = 1;
    stream_free(st);
    return respond_status(c, r, s, why, NULL);
}

enum MHD_Result handle_simulate(struct MHD_Connection *c, request *r)
{
    int f = negotiate(MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT), offers, 4);
    if (f < 0)
        return respond_problem(c, r, 406, NULL, "this route answers application/json, application/x-ndjson, "
                               "text/event-stream or text/csv", NULL, NULL);
    dp_buf meta = { 0 };
    enum MHD_Result answer = MHD_NO;
    if (dp_buf_reserve(&meta, META_BYTES) != DP_OK)
        return respond_status(c, r, DP_ENOMEM, NULL, NULL);
    dp_run *run = prepare(c, r, &meta, &answer);
    stream *st = run ? stream_new(c, r, run, offer_format[f], meta.data) : NULL;
    dp_buf_free(&meta);
    if (run == NULL)
        return answer;
    if (st == NULL)
        return respond_status(c, r, DP_ENOMEM, NULL, NULL);
    int s = stream_fill(st);
    if (s < 0 && s != DP_ECANCEL)
        return early_failure(c, st, s);
    if (s == DP_DONE && st->off == 0)
        return whole(c, st, offer_format[f]);
    struct MHD_Response *resp =
        MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, READ_BLOCK, stream_read, st, stream_free_cb);
    if (resp == NULL) {
        stream_free(st);
        return MHD_NO;
    }
    MHD_add_response_header(resp, MHD_HTTP_HEADER_CONTENT_TYPE, dp_format_content_type(offer_format[f]));
    MHD_add_response_header(resp, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    MHD_add_response_header(resp, "X-Accel-Buffering", "no"); /* proxies: pass the stream through */
    r->status = 200;
    r->stream = st;
    enum MHD_Result ok = MHD_queue_response(c, 200, resp);
    MHD_destroy_response(resp); /* MHD holds it now; stream_free_cb runs when it is done with it */
    return ok;
}
