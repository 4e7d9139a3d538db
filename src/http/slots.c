/* src/http/slots.c - solver work goes through --threads slots; libmicrohttpd runs one thread more.
 *
 * A connection thread that computes a block of a stream serves none of its other connections meanwhile. If
 * every thread could compute at once, /healthz and /readyz would wait behind solver work. (The answers
 * computed whole run on the compute threads instead, jobs.c, each holding a slot from its start until it
 * is answered, so that the slots count every computation.) So work is admitted through cfg.threads slots
 * while the pool has cfg.threads + 1 threads: at least one thread is always in its event loop, accepting
 * and answering the small routes within milliseconds. A request (or a stream's next block) that finds every slot taken is
 * parked: its connection is suspended (MHD_suspend_connection, from the access handler or the content
 * reader, the two places MHD allows it) and queued; whoever gives a slot back hands it straight to the
 * first in the queue and resumes that connection, so waiting is first come, first served and costs no
 * thread. /readyz says 503 /problems/busy while every slot is taken (slots_free == 0).
 *
 * The queue and the count are guarded by one mutex, taken once per block (a block is ~512 records), and a
 * connection is suspended and resumed under it, so a resume never comes before its suspend. At shutdown
 * slots_open lets everything through and resumes every parked connection (MHD must not be stopped with
 * suspended ones); runs then end at once on the abort flag. Every request gives back what it holds when it
 * completes (on_completed, stream_free), also a slot handed to it whose connection closed on resuming.
 */
#include "http.h"

/* A slot given back (slots_lock held): it passes on to the first parked request, whose connection resumes
 * (workers_busy stays), or it is free again. */
static void pass_on(server *s)
{
    request *w = s->wait_head;
    if (w == NULL) {
        atomic_fetch_sub(&s->m.workers_busy, 1);
        return;
    }
    s->wait_head = w->wait_next;
    if (s->wait_head == NULL)
        s->wait_tail = NULL;
    w->slot_granted = 1;
    struct MHD_Connection *c = w->wait_conn;
    w->wait_conn = NULL;
    MHD_resume_connection(c);
}

int slot_take(request *r, struct MHD_Connection *c)
{
    server *s = r->srv;
    if (r->slot_held)
        return 1;
    pthread_mutex_lock(&s->slots_lock);
    r->wait_conn = NULL;
    int got = r->slot_granted || s->slots_open || s->m.workers_busy < s->cfg.threads;
    if (got && !r->slot_granted && !s->slots_open)
        atomic_fetch_add(&s->m.workers_busy, 1);
    if (got) {
        r->slot_held = r->slot_granted || !s->slots_open;
        r->slot_granted = 0;
    } else {
        r->wait_conn = c;
        r->wait_next = NULL;
        if (s->wait_tail)
            s->wait_tail->wait_next = r;
        else
            s->wait_head = r;
        s->wait_tail = r;
        MHD_suspend_connection(c);
    }
    pthread_mutex_unlock(&s->slots_lock);
    return got;
}

void slot_give(request *r)
{
    server *s = r->srv;
    pthread_mutex_lock(&s->slots_lock);
    if (r->wait_conn != NULL) { /* still parked: the request ends before its turn came (not expected) */
        request **p = &s->wait_head, *prev = NULL;
        while (*p && *p != r)
            prev = *p, p = &(*p)->wait_next;
        if (*p) {
            *p = r->wait_next;
            if (s->wait_tail == r)
                s->wait_tail = prev;
        }
        r->wait_conn = NULL;
    }
    /* Held, or handed over while parked and never used (its connection closed on resuming): both count. */
    if (r->slot_held || r->slot_granted) {
        r->slot_held = r->slot_granted = 0;
        pass_on(s);
    }
    pthread_mutex_unlock(&s->slots_lock);
}

unsigned slots_free(server *s)
{
    unsigned busy = atomic_load(&s->m.workers_busy);
    return busy < s->cfg.threads ? s->cfg.threads - busy : 0;
}

void slots_open(server *s)
{
    pthread_mutex_lock(&s->slots_lock);
    s->slots_open = 1;
    for (request *w = s->wait_head, *next; w != NULL; w = next) {
        next = w->wait_next; /* read first: once resumed, w may be served and freed */
        struct MHD_Connection *c = w->wait_conn;
        w->wait_conn = NULL;
        MHD_resume_connection(c); /* it finds the slots open and goes on */
    }
    s->wait_head = s->wait_tail = NULL;
    pthread_mutex_unlock(&s->slots_lock);
}

/* ---- extra slots: a sweep's further executors (sweep.c) ----
 * A sweep holds its slot as any stream does and may take more that are free at that moment, one per further
 * thread computing its runs, so that workers_busy (and /readyz) still count every thread computing. It never
 * waits for one and never takes one a parked request waits for; each executor gives its slot back when it
 * ends, handing it to the first parked request as slot_give does. */

unsigned slot_try_extra(server *s, unsigned want)
{
    pthread_mutex_lock(&s->slots_lock);
    unsigned busy = atomic_load(&s->m.workers_busy), got = 0;
    /* Free now and wanted by nobody parked; none at shutdown (slots_open: nothing is counted then). */
    if (!s->slots_open && s->wait_head == NULL && busy < s->cfg.threads)
        got = s->cfg.threads - busy < want ? s->cfg.threads - busy : want;
    atomic_fetch_add(&s->m.workers_busy, got);
    pthread_mutex_unlock(&s->slots_lock);
    return got;
}

void slot_give_extra(server *s)
{
    pthread_mutex_lock(&s->slots_lock);
    pass_on(s);
    pthread_mutex_unlock(&s->slots_lock);
}

int slot_detach(request *r)
{
    pthread_mutex_lock(&r->srv->slots_lock);
    int held = r->slot_held;
    r->slot_held = 0; /* still counted in workers_busy: now the caller's to give back (slot_give_extra) */
    pthread_mutex_unlock(&r->srv->slots_lock);
    return held;
}
