/* src/http/main.c - dashpotd: configuration, signals, start, graceful stop.
 *
 * SIGTERM and SIGINT are blocked in every thread (MHD's threads inherit the mask) and taken synchronously
 * by sigwait in the main thread: no handler, no flag shared with an interrupt. On either, the daemon stops
 * accepting, gives runs in flight --shutdown-grace seconds, ends the rest with an error line, exits 0.
 */
#include <gsl/gsl_errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dashpot/json.h"
#include "http.h"

/* Blocks SIGTERM and SIGINT for this thread and all it creates; ignores SIGPIPE (a vanished client). */
static void take_signals(sigset_t *set)
{
    sigemptyset(set);
    sigaddset(set, SIGTERM);
    sigaddset(set, SIGINT);
    pthread_sigmask(SIG_BLOCK, set, NULL);
    signal(SIGPIPE, SIG_IGN);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    server *s = calloc(1, sizeof *s);
    if (s == NULL)
        return 1;
    int rc = config_load(&s->cfg, argc, argv);
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
    int sig = 0;
    sigwait(&set, &sig);
    log_line("received %s: draining (grace %gs)", sig == SIGTERM ? "SIGTERM" : "SIGINT", s->cfg.shutdown_grace);
    server_shutdown(s);
    log_line("stopped");
    server_free(s);
    return 0;
}
