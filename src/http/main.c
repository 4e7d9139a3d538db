/* src/http/main.c - dashpotd: configuration, signals, start, graceful stop.
 *
 * SIGTERM, SIGINT and SIGHUP are blocked in every thread (MHD's threads inherit the mask) and taken
 * synchronously by sigtimedwait in the main thread: no handler, no flag shared with an interrupt. Between
 * signals the main thread enforces the request deadline (deadline.c) four times a second. On any of them the
 * daemon stops accepting, gives runs and computations in flight --shutdown-grace seconds, ends the rest (an
 * error line, a 503), joins the compute threads (jobs.c), exits 0. SIGHUP is there because its default action kills at once: a daemon left in a terminal that closes
 * would cut its streams without an error line. There is no configuration to reload.
 */
#include <arpa/inet.h>
#include <gsl/gsl_errno.h>
#include <malloc.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dashpot/json.h"
#include "http.h"

/* Blocks SIGTERM, SIGINT and SIGHUP for this thread and all it creates; ignores SIGPIPE (a vanished client). */
static void take_signals(sigset_t *set)
{
    sigemptyset(set);
    sigaddset(set, SIGTERM);
    sigaddset(set, SIGINT);
    sigaddset(set, SIGHUP);
    pthread_sigmask(SIG_BLOCK, set, NULL);
    signal(SIGPIPE, SIG_IGN);
}

/* 1 for 127.0.0.0/8 and ::1, the addresses only this machine reaches. */
static int loopback(const char *bind)
{
    unsigned char a[16];
    if (inet_pton(AF_INET, bind, a) == 1)
        return a[0] == 127;
    static const unsigned char one[16] = { [15] = 1 };
    return inet_pton(AF_INET6, bind, a) == 1 && memcmp(a, one, 16) == 0;
}

/* Hands freed memory back to the system once a burst is over: glibc keeps what a thread freed in that
 * thread's arena (and raises its mmap threshold after large frees), so without this the RSS after 50
 * concurrent streams stays at their peak for good. Once a second at most, and only when no run is in flight
 * and runs have ended since the last time; malloc_trim holds each arena's lock for ~10-100 us. */
static void trim_after_burst(server *s, unsigned long long *ended_before)
{
    const metrics *m = &s->m;
    unsigned long long ended = atomic_load(&m->runs_completed) + atomic_load(&m->runs_failed) +
                               atomic_load(&m->runs_cancelled);
    if (ended == *ended_before || atomic_load(&m->runs_in_flight) != 0 || atomic_load(&m->studies_in_flight) != 0)
        return;
    *ended_before = ended;
    malloc_trim(0);
}

/* Waits for one of the signals in set, sweeping late requests meanwhile; returns the signal. */
static int wait_signal(server *s, const sigset_t *set)
{
    const struct timespec quarter = { 0, 250 * 1000 * 1000 };
    unsigned long long ended = 0;
    for (unsigned tick = 1;; tick++) {
        int sig = sigtimedwait(set, NULL, &quarter);
        if (sig > 0)
            return sig;
        unsigned n = deadline_sweep(s);
        if (n)
            log_line("closed %u connection(s) whose request did not arrive within %u s", n, s->cfg.timeout);
        if (tick % 4 == 0)
            trim_after_burst(s, &ended);
    }
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    server *s = server_new();
    if (s == NULL)
        return 1;
    int rc = config_load(&s->cfg, argc, argv);
    if (rc == 0 && auth_load(&s->cfg) != 0)
        rc = -1;
    if (rc != 0) {
        server_free(s);
        return rc > 0 ? 0 : 2;
    }
    sigset_t set;
    take_signals(&set);
    if (server_start(s) != 0) {
        server_free(s);
        return 1;
    }
    log_line("dashpotd %s listening on http://%s%s%s:%u (threads %u, max-connections %u, max-steps %g, "
             "max-wall %gs, body-limit %zu)", DP_VERSION, strchr(s->cfg.bind, ':') ? "[" : "", s->cfg.bind,
             strchr(s->cfg.bind, ':') ? "]" : "", server_port(s), s->cfg.threads, s->cfg.max_connections,
             s->cfg.max_steps, s->cfg.max_wall, s->cfg.body_limit);
    log_line("/v1/ routes: %s", s->cfg.token[0] ? "bearer token required" : "open (no token set)");
    if (!loopback(s->cfg.bind) && !s->cfg.token[0])
        log_line("warning: listening on %s without a token: anyone who reaches this port can run simulations "
                 "(set DASHPOT_TOKEN or --token-file, or bind 127.0.0.1 behind a proxy)", s->cfg.bind);
    int sig = wait_signal(s, &set);
    log_line("received %s: draining (grace %gs)", sig == SIGTERM ? "SIGTERM" : sig == SIGINT ? "SIGINT" : "SIGHUP",
             s->cfg.shutdown_grace);
    server_shutdown(s);
    log_line("stopped");
    server_free(s);
    return 0;
}
