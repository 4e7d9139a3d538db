/* src/http/sweep.c - POST /v1/sweep: a simulate document over a grid of parameters, one line per run as it
 * completes (docs/sweep.md), streamed as simulate.c streams a run.
 *
 * The runs execute in parallel, each the same computation as a lone simulate (so its features are the lone
 * run's bit for bit). Once the meta line is out, the request takes its solver slot (slots.c: it may park) and
 * then as many more as are free at that moment, up to one per run (slot_try_extra: never waits, never takes
 * one a parked request waits for); each slot drives one executor of runs k, k + n, k + 2n, ... (n executors,
 * as the CLI's --threads) on a thread the sweep starts and joins itself, and is given back as its executor
 * ends. So workers_busy counts every thread computing, and one connection thread stays free for /healthz. The executors append their finished lines to
 * a queue that holds at most ~QUEUE_BYTES (a producer waits for room: back-pressure, memory independent of
 * the sweep's length); MHD's content reader drains it, waiting at most a SLICE for a line before it lets its
 * thread serve its other connections, as simulate.c does. Lines come in the order runs finish, not by index.
 *
 * One stop word for the whole sweep, set once: the end of the shutdown grace period and --max-wall (seen by
 * every executor's hook and by the reader), the client's hang-up (seen by the reader, and by the response's
 * free callback), an executor out of memory. Every executor ends within one block of work of it; the reader
 * writes the error line once they all have and the slots are back, so a client that read the error line sees
 * no slot still held. A spent step budget (--max-steps times DP_SWEEP_STEP_FACTOR for the whole sweep) lets
 * the runs begun finish and begins no more, then is the error line too; a stop is never a silent cut. A run
 * that fails is its own line and the sweep goes on. A bad document is a 422 before the first byte, by pointer.
 * Whatever the order of events, the free callback sets the stop word and joins every executor (each has
 * given its slot back by then) before anything is freed. A client that stops reading makes the executors wait
 * for room in the queue, looking at the clock every slice: --max-wall still ends them and frees their slots.
 *
 * Formats (Accept): application/x-ndjson (the default: meta, run lines, summary), text/event-stream (the same
 * objects as events "meta", "run", "summary", "error"), application/json (one document
 * {"meta", "runs": [...], "summary"} or, on a stop, "error" in place of "summary").
 */
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dashpot/json.h"
#include "dashpot/sweep_json.h"
#include "http.h"

#define READ_BLOCK (64u << 10)
/* Finished lines waiting for the client at most (a producer then waits): a few hundred run lines. */
#define QUEUE_BYTES (256u << 10)
#define SLICE 0.01               /* as simulate.c: seconds the reader waits for a line before it yields */
#define MAX_EXECUTORS 64

enum { F_NDJSON, F_SSE, F_JSON };
enum { STOP_FAILED = STOP_GONE + 1 }; /* the stop word beyond watch.c's reasons: an executor failed */

struct sweep_stream;

typedef struct executor {
    struct sweep_stream *st;
    dp_sweep_exec *x;
    pthread_t tid;
    int slot;                    /* computes on a counted slot of its own, given back as it ends */
} executor;

typedef struct sweep_stream {
    request *r;
    server *s;
    struct MHD_Connection *conn;
    dp_sweep_doc *doc;
    int format;
    /* The reader's (MHD's thread for this connection): */
    dp_buf out, line, batch;
    size_t off, lines;
    int closed, delivered, failed;
    watch w;                     /* --max-wall, shutdown, the client's hang-up (watch.c), polled by the reader */
    int started;                 /* the executors were set off (sweep_start) */
    executor *ex;                /* nex of them, nexec of which have a thread, joined by sweep_free */
    size_t nex, nexec;
    /* Shared: */
    double deadline;             /* w.deadline, for the executors' hooks */
    atomic_int stop;             /* STOP_NONE, a watch reason or STOP_FAILED: set once */
    _Atomic unsigned long long budget;
    pthread_mutex_t lock;        /* guards what follows */
    pthread_cond_t more, room;   /* a line or an executor's end is queued; room in the queue, or a stop */
    dp_buf queue;                /* finished lines, each with its newline */
    size_t running;              /* executors not ended */
    int status;                  /* DP_DONE, or the first failure of an executor (DP_ELIMIT, DP_ENOMEM) */
    char why[DP_MESSAGE_MAX];    /* ...and its words */
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

/* ---- the executors ---- */

/* Sets the stop word (the first reason stays) and wakes whoever waits on the queue. */
static void stop_all(sweep_stream *st, int why)
{
    int none = STOP_NONE;
    atomic_compare_exchange_strong(&st->stop, &none, why);
    pthread_mutex_lock(&st->lock);
    pthread_cond_broadcast(&st->room);
    pthread_cond_broadcast(&st->more);
    pthread_mutex_unlock(&st->lock);
}

/* A reason to stop the executors have to see for themselves: the end of the grace period, --max-wall (the
 * hang-up is the reader's to see: the socket belongs to MHD's thread). */
static int own_reason(const sweep_stream *st)
{
    return atomic_load_explicit(&st->s->abort_streams, memory_order_relaxed) ? STOP_SHUTDOWN :
           now_seconds() > st->deadline ? STOP_DEADLINE : STOP_NONE;
}

/* The executors' dp_stop hook: the stop word, or a reason of their own, which sets it. 1 to stop. */
static int sweep_stop(void *ctx)
{
    sweep_stream *st = ctx;
    if (atomic_load_explicit(&st->stop, memory_order_relaxed) != STOP_NONE)
        return 1;
    int why = own_reason(st);
    if (why != STOP_NONE)
        stop_all(st, why);
    return why != STOP_NONE;
}

/* Waits (st->lock held) on cv until a SLICE from now at most. */
static void wait_slice(pthread_cond_t *cv, pthread_mutex_t *lock)
{
    struct timespec until;
    clock_gettime(CLOCK_MONOTONIC, &until);
    until.tv_nsec += (long)(SLICE * 1e9);
    if (until.tv_nsec >= 1000000000L)
        until.tv_sec++, until.tv_nsec -= 1000000000L;
    pthread_cond_timedwait(cv, lock, &until);
}

/* Queues a finished line, waiting while the queue is full; DP_ECANCEL once the sweep stops. The wait looks at
 * the clock every slice, so that a client that stops reading still has its sweep end at --max-wall. */
static int deliver(sweep_stream *st, const dp_buf *line)
{
    pthread_mutex_lock(&st->lock);
    while (st->queue.len > QUEUE_BYTES && atomic_load(&st->stop) == STOP_NONE) {
        int why = own_reason(st), none = STOP_NONE;
        if (why != STOP_NONE && atomic_compare_exchange_strong(&st->stop, &none, why))
            pthread_cond_broadcast(&st->room), pthread_cond_broadcast(&st->more);
        else if (why == STOP_NONE)
            wait_slice(&st->room, &st->lock);
    }
    size_t len = st->queue.len;
    int s = atomic_load(&st->stop) != STOP_NONE ? DP_ECANCEL : dp_buf_append(&st->queue, line->data, line->len);
    s = s ? s : dp_buf_append(&st->queue, "\n", 1);
    if (s != DP_OK)
        st->queue.len = len;
    pthread_cond_signal(&st->more);
    pthread_mutex_unlock(&st->lock);
    return s;
}

/* An executor has ended with status s: its failure recorded (the first one), the reader woken. */
static void ended(sweep_stream *st, int s, const char *why)
{
    pthread_mutex_lock(&st->lock);
    if (s != DP_DONE && s != DP_ECANCEL && st->status == DP_DONE) {
        st->status = s;
        snprintf(st->why, sizeof st->why, "%s", why ? why : dp_strerror(s));
    }
    st->running--;
    pthread_cond_broadcast(&st->more);
    pthread_mutex_unlock(&st->lock);
}

static void *executor_main(void *arg)
{
    executor *e = arg;
    sweep_stream *st = e->st;
    dp_buf line = { 0 };
    const char *why = NULL;
    int s, ready;
    do {
        line.len = 0;
        s = dp_sweep_exec_next(e->x, &line, &ready, &why);
        if (ready && s == DP_MORE && (s = deliver(st, &line)) == DP_OK)
            s = DP_MORE;
    } while (s == DP_MORE);
    if (s == DP_ENOMEM)
        why = dp_strerror(s);
    dp_buf_free(&line);
    if (e->slot)                /* its slot back before it says it ended: the reader closes the stream */
        slot_give_extra(st->s); /* with every slot back */
    ended(st, s, why);
    if (s == DP_ENOMEM)
        stop_all(st, STOP_FAILED);
    return NULL;
}

/* The executors, one on the request's slot and one on each extra slot free now; their threads started. The
 * request's slot is detached from it (slot_detach), so that whatever happens to the connection each slot is
 * given back by the thread computing on it as it ends. A failure is the stop word (STOP_FAILED) with the
 * status, the executors started running down. */
static void sweep_start(sweep_stream *st)
{
    const config *cfg = &st->s->cfg;
    size_t runs = dp_sweep_doc_count(st->doc), want = runs > MAX_EXECUTORS ? MAX_EXECUTORS : runs;
    size_t extra = want > 1 ? slot_try_extra(st->s, (unsigned)(want - 1)) : 0, n = 1 + extra, k;
    int own = slot_detach(st->r);
    st->started = 1;
    st->ex = calloc(n, sizeof *st->ex);
    st->nex = st->ex ? n : 0;
    for (k = 0; st->ex != NULL && k < n; k++) {
        executor *e = &st->ex[k];
        *e = (executor){ .st = st, .slot = k > 0 || own };
        e->x = dp_sweep_exec_new(st->doc, k, n, cfg->max_steps, &st->budget, cfg->max_steps * DP_SWEEP_STEP_FACTOR);
        if (e->x == NULL)
            break;
        dp_sweep_exec_set_stop(e->x, sweep_stop, st);
    }
    st->running = n;
    int ok = st->ex != NULL && k == n;
    for (k = 0; ok && k < n; k++, st->nexec++)
        if (pthread_create(&st->ex[k].tid, NULL, executor_main, &st->ex[k]) != 0)
            break;
    if (st->nexec < n) {         /* the runs of an executor not started would be missing: stop the sweep */
        pthread_mutex_lock(&st->lock);
        st->status = DP_ENOMEM;
        snprintf(st->why, sizeof st->why, "%s", "cannot start the sweep's executors");
        st->running -= n - st->nexec;
        pthread_mutex_unlock(&st->lock);
        for (k = st->nexec; k < n; k++)
            if (k > 0 || own)
                slot_give_extra(st->s);
        stop_all(st, STOP_FAILED);
    }
}

/* ---- the reader ---- */

/* Waits up to a SLICE for a line or an executor's end, then takes the queued lines into st->batch. Returns
 * how many executors still run. */
static size_t take_lines(sweep_stream *st)
{
    pthread_mutex_lock(&st->lock);
    if (st->queue.len == 0 && st->running > 0)
        wait_slice(&st->more, &st->lock);
    dp_buf full = st->queue;
    st->queue = st->batch;
    st->batch = full;
    size_t running = st->running;
    pthread_cond_broadcast(&st->room);
    pthread_mutex_unlock(&st->lock);
    return running;
}

/* The lines of the batch framed into out. */
static int frame_batch(sweep_stream *st)
{
    int s = DP_OK;
    for (size_t i = 0; i < st->batch.len && s == DP_OK;) {
        const char *nl = memchr(st->batch.data + i, '\n', st->batch.len - i);
        size_t end = (size_t)(nl - st->batch.data);
        st->line.len = 0;
        s = dp_buf_append(&st->line, st->batch.data + i, end - i);
        s = s ? s : frame(st, "run", &st->line);
        i = end + 1;
    }
    st->batch.len = 0;
    return s;
}

/* Every executor has ended and every slot is back: the summary, or why the sweep stopped. */
static void sweep_close(sweep_stream *st, int why)
{
    dp_sweep_totals tot = { 0 };
    for (size_t k = 0; k < st->nexec; k++) {
        const dp_sweep_totals *x = dp_sweep_exec_totals(st->ex[k].x);
        tot.completed += x->completed;
        tot.failed += x->failed;
        tot.steps += x->steps;
    }
    char detail[DP_MESSAGE_MAX];
    if (why == STOP_FAILED || (why == STOP_NONE && st->status != DP_DONE)) {
        sweep_fail(st, st->status, st->why); /* the executors have ended: status and why are settled */
    } else if (why != STOP_NONE) {
        st->w.why = why;
        watch_detail(&st->w, "the sweep", detail, sizeof detail);
        sweep_fail(st, DP_ECANCEL, detail);
    } else {
        st->line.len = 0;
        if (dp_sweep_summary_json(dp_sweep_doc_count(st->doc), &tot, &st->line) != DP_OK ||
            frame(st, "summary", &st->line) != DP_OK)
            sweep_fail(st, DP_ENOMEM, dp_strerror(DP_ENOMEM));
        st->closed = 1;
    }
}

/* The lines finished meanwhile (waiting a SLICE at most), and the end once every executor has ended. */
static void sweep_fill(sweep_stream *st)
{
    size_t running = take_lines(st);
    if (frame_batch(st) != DP_OK) {
        pthread_mutex_lock(&st->lock);
        if (st->status == DP_DONE)
            st->status = DP_ENOMEM, snprintf(st->why, sizeof st->why, "%s", dp_strerror(DP_ENOMEM));
        pthread_mutex_unlock(&st->lock);
        stop_all(st, STOP_FAILED);
    }
    if (atomic_load(&st->stop) == STOP_NONE && watch_check(&st->w, now_seconds()) != STOP_NONE)
        stop_all(st, st->w.why);
    if (running == 0)
        sweep_close(st, atomic_load(&st->stop));
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
        st->out.len = st->off = 0;
        if (!st->started) {
            if (!slot_take(st->r, st->conn))
                return 0; /* parked (suspended): called again once a slot is handed over */
            sweep_start(st);
        }
        sweep_fill(st);
        if (st->w.why == STOP_GONE)
            return MHD_CONTENT_READER_END_WITH_ERROR; /* the free callback stops and joins the executors */
        if (st->off == st->out.len && !st->closed) { /* nothing yet: let the thread serve its other */
            MHD_suspend_connection(st->conn);        /* connections, then come back */
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
    stop_all(st, STOP_GONE); /* nothing if the sweep has ended or stopped already */
    for (size_t k = 0; k < st->nexec; k++)
        pthread_join(st->ex[k].tid, NULL);
    if (!st->delivered)
        atomic_fetch_add(&m->runs_cancelled, 1);
    else
        atomic_fetch_add(st->failed ? &m->runs_failed : &m->runs_completed, 1);
    atomic_fetch_sub(&m->runs_in_flight, 1);
    slot_give(st->r); /* one handed over while parked, the connection closing before it was used */
    for (size_t k = 0; k < st->nex; k++)
        dp_sweep_exec_free(st->ex[k].x);
    free(st->ex);
    pthread_cond_destroy(&st->more);
    pthread_cond_destroy(&st->room);
    pthread_mutex_destroy(&st->lock);
    dp_sweep_doc_free(st->doc);
    dp_buf_free(&st->out);
    dp_buf_free(&st->line);
    dp_buf_free(&st->batch);
    dp_buf_free(&st->queue);
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
    *st = (sweep_stream){ .r = r, .s = r->srv, .conn = c, .doc = doc, .format = format, .status = DP_DONE };
    pthread_condattr_t monotonic; /* the waits are timed on the clock now_seconds reads */
    pthread_condattr_init(&monotonic);
    pthread_condattr_setclock(&monotonic, CLOCK_MONOTONIC);
    pthread_mutex_init(&st->lock, NULL);
    pthread_cond_init(&st->more, &monotonic);
    pthread_cond_init(&st->room, &monotonic);
    pthread_condattr_destroy(&monotonic);
    watch_init(&st->w, r, c);
    st->deadline = st->w.deadline;
    atomic_fetch_add(&r->refs, 1);
    atomic_fetch_add(&st->s->m.runs_started, 1);
    atomic_fetch_add(&st->s->m.runs_in_flight, 1);
    if (dp_sweep_meta_json(doc, cfg->max_steps, &st->line) != DP_OK ||
        frame(st, "meta", &st->line) != DP_OK) {
        st->delivered = st->failed = 1;
        sweep_free(st);
        return NULL;
    }
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
