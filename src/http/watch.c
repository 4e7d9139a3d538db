/* src/http/watch.c - the three reasons dashpotd stops a computation, in one place for every route: the
 * request's --max-wall (counted from its start, upload included), the end of the shutdown grace period (the
 * server's abort flag), and the client's hang-up (its socket, looked at every PEER_CHECK_INTERVAL).
 *
 * A stream's run (simulate.c) and a job (jobs.c) both poll a watch through their stop hook, and both say
 * why they stopped in the same words: the stream in its error line, a job in its problem document
 * (respond_stopped: 503 /problems/timeout or /problems/shutting-down; nothing for a client that has gone).
 */
#include <errno.h>
#include <stdio.h>
#include <sys/socket.h>

#include "http.h"

/* Seconds between two looks at the socket for a hang-up while a computation runs (a recv each). */
#define PEER_CHECK_INTERVAL 0.01

int peer_gone(int fd)
{
    char ch;
    ssize_t n = recv(fd, &ch, 1, MSG_PEEK | MSG_DONTWAIT);
    return n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR);
}

void watch_init(watch *w, request *r, struct MHD_Connection *c)
{
    const union MHD_ConnectionInfo *ci = c ? MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD) : NULL;
    w->s = r->srv;
    w->deadline = r->t_start + r->srv->cfg.max_wall;
    w->fd = ci ? ci->connect_fd : -1;
    w->peer_check = now_seconds() + PEER_CHECK_INTERVAL;
    w->why = STOP_NONE;
}

int watch_check(watch *w, double now)
{
    if (w->why != STOP_NONE)
        return w->why;
    if (atomic_load_explicit(&w->s->abort_streams, memory_order_relaxed))
        w->why = STOP_SHUTDOWN;
    else if (now > w->deadline)
        w->why = STOP_DEADLINE;
    else if (w->fd >= 0 && now >= w->peer_check) {
        w->peer_check = now + PEER_CHECK_INTERVAL;
        if (peer_gone(w->fd))
            w->why = STOP_GONE;
    }
    return w->why;
}

int watch_stop(void *ctx)
{
    return watch_check(ctx, now_seconds()) != STOP_NONE;
}

void watch_slice(watch *w, double seconds)
{
    w->slice_end = now_seconds() + seconds;
    w->yielded = 0;
}

int watch_stop_sliced(void *ctx)
{
    watch *w = ctx;
    double now = now_seconds();
    if (watch_check(w, now) != STOP_NONE)
        return 1;
    if (now > w->slice_end) {
        w->yielded = 1;
        return -1;
    }
    return 0;
}

void watch_detail(const watch *w, const char *what, char *out, size_t cap)
{
    if (w->why == STOP_DEADLINE)
        snprintf(out, cap, "%s exceeded the wall-time limit of %g s", what, w->s->cfg.max_wall);
    else
        snprintf(out, cap, "%s", w->why == STOP_SHUTDOWN ? "the server is shutting down" : "the client has gone");
}

enum MHD_Result respond_stopped(struct MHD_Connection *c, request *r, const watch *w, const char *what)
{
    if (w->why == STOP_GONE)
        return MHD_NO; /* nobody to answer: MHD closes the connection */
    char detail[128];
    watch_detail(w, what, detail, sizeof detail);
    if (w->why == STOP_SHUTDOWN)
        return respond_problem(c, r, 503, "/problems/shutting-down", detail, NULL, NULL);
    return respond_status(c, r, DP_ECANCEL, detail, NULL); /* 503 /problems/timeout */
}
