/* src/http/deadline.c - every request must arrive whole within --timeout seconds (slowloris defence).
 *
 * libmicrohttpd's connection timeout measures idleness: a client that sends its head one byte every few
 * seconds is never idle for long and would hold its connection (and a slot of --max-connections) forever.
 * So each connection is registered here when MHD opens it, stamped when it becomes ready for a request
 * (opened, or its previous response finished: keep-alive), and marked when the request has arrived (the
 * body too). The main thread calls deadline_sweep a few times a second; a connection still waiting for
 * its request past the deadline gets shutdown(2) on its socket, which MHD sees as the client hanging up
 * and cleans up as usual, from its own thread.
 *
 * The sweep also looks (recv with MSG_PEEK: nothing is consumed) at each connection still waiting for its
 * request: end-of-file there means the client left half-way through its head or body. libmicrohttpd
 * 0.9.75's edge-triggered epoll loop sometimes misses that end-of-file when it arrives with the last data
 * (tests/robustness/faults.sh saw ~1 in 300 such clients, every one without MHD_USE_TURBO), leaving the
 * socket in CLOSE-WAIT, and a slot taken, until the idle timeout. shutdown(SHUT_RD) wakes MHD, whose next
 * read then returns the same 0 the client's FIN should have given it.
 *
 * The list is guarded by one mutex taken on connection open and close and by the sweep; per request
 * only atomics are touched. MHD calls the CLOSED notification before it closes the socket, and the
 * entry leaves the list under the mutex there, so the sweep never shuts down a descriptor number that
 * has been reused.
 */
#include <stdlib.h>
#include <sys/socket.h>

#include "http.h"

typedef struct conn {
    struct conn *prev, *next;
    int fd;
    atomic_int arrived;       /* the current request has arrived (or was answered early) */
    atomic_int shut;          /* the sweep has shut it down already */
    _Atomic double ready_at;  /* monotonic seconds when it became ready for its current request */
    int admitted;             /* holds one of the --max-connections places (conn_admit) */
} conn;

/* A connection takes one of the --max-connections places when it opens, if one is free, and keeps it until
 * it closes; its requests are refused (503, connection closed) when it got none. Counting the open
 * connections instead (as before) counts, in a burst, the very connections about to be refused: a burst of
 * 80 against --max-connections 8 served 3. */
static int take_place(server *s)
{
    long long n = atomic_load(&s->connections_admitted);
    do {
        if (n >= (long long)s->cfg.max_connections)
            return 0;
    } while (!atomic_compare_exchange_weak(&s->connections_admitted, &n, n + 1));
    return 1;
}

int conn_admit(server *s, struct MHD_Connection *c)
{
    const union MHD_ConnectionInfo *info = MHD_get_connection_info(c, MHD_CONNECTION_INFO_SOCKET_CONTEXT);
    const conn *k = info ? info->socket_context : NULL;
    if (k == NULL) /* not watched (out of memory at open): the open count is all there is */
        return atomic_load(&s->m.connections_open) <= (long long)s->cfg.max_connections;
    return k->admitted;
}

void deadline_open(server *s, struct MHD_Connection *c, void **socket_context)
{
    const union MHD_ConnectionInfo *info = MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD);
    conn *k = calloc(1, sizeof *k);
    *socket_context = k;
    if (k == NULL || info == NULL) {
        free(k);
        *socket_context = NULL; /* not watched: MHD's idle timeout still applies */
        return;
    }
    k->fd = info->connect_fd;
    k->admitted = take_place(s);
    atomic_init(&k->ready_at, now_seconds());
    pthread_mutex_lock(&s->conns_lock);
    k->next = s->conns;
    if (s->conns)
        s->conns->prev = k;
    s->conns = k;
    pthread_mutex_unlock(&s->conns_lock);
}

void deadline_close(server *s, void **socket_context)
{
    conn *k = *socket_context;
    if (k == NULL)
        return;
    pthread_mutex_lock(&s->conns_lock);
    if (k->prev)
        k->prev->next = k->next;
    else
        s->conns = k->next;
    if (k->next)
        k->next->prev = k->prev;
    pthread_mutex_unlock(&s->conns_lock);
    if (k->admitted)
        atomic_fetch_sub(&s->connections_admitted, 1);
    free(k);
    *socket_context = NULL;
}

void deadline_mark(struct MHD_Connection *c, int arrived)
{
    const union MHD_ConnectionInfo *info = MHD_get_connection_info(c, MHD_CONNECTION_INFO_SOCKET_CONTEXT);
    conn *k = info ? info->socket_context : NULL;
    if (k == NULL)
        return;
    if (!arrived)
        atomic_store_explicit(&k->ready_at, now_seconds(), memory_order_relaxed);
    atomic_store_explicit(&k->arrived, arrived, memory_order_release);
}

unsigned deadline_sweep(server *s)
{
    double late = now_seconds() - (double)s->cfg.timeout;
    unsigned n = 0;
    pthread_mutex_lock(&s->conns_lock);
    for (conn *k = s->conns; k; k = k->next) {
        if (atomic_load_explicit(&k->arrived, memory_order_acquire) || atomic_load(&k->shut))
            continue;
        char c;
        if (atomic_load_explicit(&k->ready_at, memory_order_relaxed) <= late) {
            shutdown(k->fd, SHUT_RDWR);
            atomic_store(&k->shut, 1);
            n++;
        } else if (recv(k->fd, &c, 1, MSG_PEEK | MSG_DONTWAIT) == 0) {
            shutdown(k->fd, SHUT_RD); /* the client has gone: tell MHD again */
            atomic_store(&k->shut, 1);
        }
    }
    pthread_mutex_unlock(&s->conns_lock);
    if (n)
        atomic_fetch_add_explicit(&s->m.connections_timed_out, n, memory_order_relaxed);
    return n;
}
