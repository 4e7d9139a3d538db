/* src/http/jobs.c - every computation answered whole (an LCP, modes, a response curve, a convergence study,
 * a stability map) runs on a compute thread, never on one of libmicrohttpd's connection threads.
 *
 * libmicrohttpd pins each connection to one thread of its pool, and a thread that computes serves none of its
 * other connections: a health probe accepted by the same thread waited behind a 3 s modal analysis, or was
 * dropped after 30 s. So the access handler only reads the body and negotiates the media type; then
 * job_submit queues the computation for the cfg.threads compute threads (started with the server, joined at
 * shutdown) and suspends the connection (MHD_suspend_connection, allowed from the access handler). The
 * compute thread runs it with a stop hook (watch.c: --max-wall, the end of the shutdown grace period, the
 * client's hang-up), stores the outcome and resumes the connection; libmicrohttpd then calls the handler
 * again and route_dispatch answers (job_answer). A suspended connection costs no thread and no timeout
 * runs on it (libmicrohttpd restarts the timeout on resuming), which is why the hang-up is watched here.
 *
 * A pool rather than a thread per job: the request keeps its solver slot (slots.c) until it is answered, so
 * at most cfg.threads jobs compute at once and a slot always finds a compute thread free; a queued job waits
 * only at shutdown, when slots_open lets everything through, and then its hook says stop before it starts.
 * A connection is suspended and resumed under jobs_lock, so a resume never comes before its suspend; once
 * resumed the job belongs to the connection's thread again. MHD must not be stopped with a suspended
 * connection: jobs_stop (after the abort flag is set) waits for every job and resumes its connection first.
 */
#include <stdlib.h>

#include "http.h"

struct job {
    struct job *next;            /* the queue */
    request *r;
    struct MHD_Connection *conn;
    const job_route *route;
    int arg;                     /* the route's choice from Accept (a format) */
    const char *type;            /* the answer's media type */
    watch w;
    atomic_int done;             /* the outcome is in: status, out, errs */
    int status;
    dp_buf out;
    dp_errors errs;
};

/* The work, unless its hook says stop before it starts (a job queued at shutdown). */
static void compute(struct job *j)
{
    dp_stop stop = { watch_stop, &j->w };
    j->status = watch_stop(&j->w) ? DP_ECANCEL : j->route->work(j->r, j->arg, &stop, &j->out, &j->errs);
}

static void *compute_thread(void *arg)
{
    server *s = arg;
    pthread_mutex_lock(&s->jobs_lock);
    for (;;) {
        while (s->jobs_head == NULL && !s->jobs_quit)
            pthread_cond_wait(&s->jobs_cond, &s->jobs_lock);
        struct job *j = s->jobs_head;
        if (j == NULL)
            break; /* told to end, and nothing left to do */
        s->jobs_head = j->next;
        if (s->jobs_head == NULL)
            s->jobs_tail = NULL;
        pthread_mutex_unlock(&s->jobs_lock);
        compute(j);
        pthread_mutex_lock(&s->jobs_lock);
        atomic_store(&j->done, 1);
        MHD_resume_connection(j->conn); /* from here on j is the connection thread's */
    }
    pthread_mutex_unlock(&s->jobs_lock);
    return NULL;
}

int jobs_start(server *s)
{
    if (s->cfg.embedded) /* no threads at all: the caller drives MHD, jobs run inline */
        return 0;
    s->job_threads = calloc(s->cfg.threads, sizeof *s->job_threads);
    if (s->job_threads == NULL)
        return -1;
    for (unsigned i = 0; i < s->cfg.threads; i++) {
        if (pthread_create(&s->job_threads[i], NULL, compute_thread, s) != 0) {
            jobs_stop(s);
            return -1;
        }
        s->job_nthreads++;
    }
    return 0;
}

void jobs_stop(server *s)
{
    pthread_mutex_lock(&s->jobs_lock);
    s->jobs_quit = 1;
    pthread_cond_broadcast(&s->jobs_cond);
    unsigned n = s->job_nthreads;
    pthread_mutex_unlock(&s->jobs_lock);
    for (unsigned i = 0; i < n; i++)
        pthread_join(s->job_threads[i], NULL);
    pthread_mutex_lock(&s->jobs_lock);
    s->job_nthreads = 0;
    pthread_mutex_unlock(&s->jobs_lock);
    free(s->job_threads);
    s->job_threads = NULL;
}

enum MHD_Result job_submit(struct MHD_Connection *c, request *r, const job_route *route, int arg, const char *type)
{
    server *s = r->srv;
    struct job *j = calloc(1, sizeof *j);
    if (j == NULL)
        return respond_status(c, r, DP_ENOMEM, NULL, NULL);
    j->r = r;
    j->conn = c;
    j->route = route;
    j->arg = arg;
    j->type = type;
    dp_errors_init(&j->errs);
    watch_init(&j->w, r, c);
    r->job = j;
    pthread_mutex_lock(&s->jobs_lock);
    int quit = s->jobs_quit, queued = !quit && s->job_nthreads > 0;
    if (queued) {
        if (s->jobs_tail)
            s->jobs_tail->next = j;
        else
            s->jobs_head = j;
        s->jobs_tail = j;
        MHD_suspend_connection(c);
        pthread_cond_signal(&s->jobs_cond);
    }
    pthread_mutex_unlock(&s->jobs_lock);
    if (queued)
        return MHD_YES; /* called again once resumed: route_dispatch then calls job_answer */
    if (quit) { /* the compute threads are gone: shutting down */
        j->w.why = STOP_SHUTDOWN;
        j->status = DP_ECANCEL;
    } else {
        compute(j); /* embedded: this thread is the only one */
    }
    atomic_store(&j->done, 1);
    return job_answer(c, r);
}

enum MHD_Result job_submit_json(struct MHD_Connection *c, request *r, const job_route *route)
{
    static const char *const offers[] = { "application/json" };
    if (negotiate(MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_ACCEPT), offers, 1) < 0)
        return respond_problem(c, r, 406, NULL, "this route answers application/json", NULL, NULL);
    return job_submit(c, r, route, 0, "application/json");
}

int job_pending(const request *r)
{
    return r->job != NULL && !atomic_load(&r->job->done);
}

enum MHD_Result job_answer(struct MHD_Connection *c, request *r)
{
    struct job *j = r->job;
    enum MHD_Result res;
    if (j->status == DP_ECANCEL && j->w.why != STOP_NONE)
        res = respond_stopped(c, r, &j->w, j->route->what);
    else if (j->status != DP_OK && j->route->failed)
        res = j->route->failed(c, r, j->status, &j->errs);
    else
        res = respond_answer(c, r, j->status, &j->out, &j->errs, j->type);
    job_free(r);
    return res;
}

void job_free(request *r)
{
    if (r->job == NULL)
        return;
    dp_buf_free(&r->job->out);
    free(r->job);
    r->job = NULL;
}
