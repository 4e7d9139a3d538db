/* tests/fuzz/fuzz_http.c - libFuzzer target: any bytes as the client side of one HTTP connection to a real
 * dashpotd, in process.
 *
 * The daemon is the real one (every file of src/http but main.c) over the real libmicrohttpd, started
 * "embedded" (config.embedded: no listening socket, no threads): each input gets a socketpair whose one
 * end is handed to MHD_add_connection, the bytes are written to the other end, which is then half-closed,
 * and this thread drives MHD_run until MHD has answered and closed. Single-threaded, so every input runs
 * the same way twice (libFuzzer needs that to reproduce and minimise) and its memory is freed before the
 * next one starts (the leak check is exact). So MHD parses whatever arrives - request lines, headers,
 * chunked bodies, pipelined requests - and dashpot's own code sees exactly what a socket would give it:
 * routing, negotiation, the token check, body accumulation, the limits, streaming and problem documents.
 * MHD itself is not instrumented, so coverage guidance comes from dashpot's code only.
 *
 * The daemon runs with small limits so that inputs stay fast (2000 steps, 0.25 s of wall time, 16 KiB of
 * body, 400 map points) and a bearer token (the seeds carry it; inputs without it exercise the 401).
 * Failures: any crash, leak or sanitizer report; an answer of 500 (dashpot never answers 500); a
 * connection not closed within 5 s (a hang); and a run, study or connection left open after it closed.
 */
#include <fcntl.h>
#include <gsl/gsl_errno.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "http.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define TOKEN "fuzz-token"
/* Wall-clock seconds an input may take before it counts as a hang (the runs stop at 0.25 s). */
#define HANG_SECONDS 5.0

static server *srv;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    gsl_set_error_handler_off();
    signal(SIGPIPE, SIG_IGN);
    char *args[] = { "fuzz_http", "--threads", "1", "--max-steps", "2000", "--max-wall", "0.25", "--timeout", "2",
                     "--body-limit", "16384", "--max-map-points", "400", "--max-connections", "4" };
    srv = server_new();
    if (srv == NULL || config_load(&srv->cfg, (int)(sizeof args / sizeof args[0]), args) != 0)
        abort();
    snprintf(srv->cfg.token, sizeof srv->cfg.token, "%s", TOKEN);
    srv->cfg.embedded = srv->cfg.quiet = 1;
    if (server_start(srv) != 0)
        abort();
    return 0;
}

/* The response bytes: only their status lines are looked at, so the first 1 MiB is plenty. */
typedef struct sink {
    char *data;
    size_t len, cap;
} sink;

static void keep(sink *k, const char *p, size_t n)
{
    if (k->len + n > k->cap)
        n = k->cap - k->len;
    memcpy(k->data + k->len, p, n);
    k->len += n;
}

/* 1 if a status line of the responses says 500. */
static int has_500(const sink *k)
{
    static const char *const lines[] = { "HTTP/1.1 500", "HTTP/1.0 500" };
    for (size_t i = 0; i + 12 <= k->len; i++)
        if ((i == 0 || k->data[i - 1] == '\n') && (memcmp(k->data + i, lines[0], 12) == 0 ||
                                                   memcmp(k->data + i, lines[1], 12) == 0))
            return 1;
    return 0;
}

/* Writes what the socket takes, half-closes when all is written; reads what is there. Returns 1 at EOF. */
static int pump(int fd, const uint8_t *data, size_t size, size_t *off, int *shut, sink *k, int *progress)
{
    if (!*shut) {
        ssize_t w = *off < size ? write(fd, data + *off, size - *off) : 0;
        if (w > 0)
            *off += (size_t)w, *progress = 1;
        if (*off == size) {
            shutdown(fd, SHUT_WR);
            *shut = 1;
        }
    }
    char buf[65536];
    ssize_t n;
    while ((n = read(fd, buf, sizeof buf)) > 0) {
        keep(k, buf, (size_t)n);
        *progress = 1;
    }
    return n == 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int sv[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
        abort();
    struct sockaddr_in peer = { .sin_family = AF_INET, .sin_port = htons(40000),
                                .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
    if (MHD_add_connection(srv->daemon, sv[1], (struct sockaddr *)&peer, sizeof peer) != MHD_YES) {
        close(sv[0]); /* MHD closed sv[1] */
        return 0;
    }
    fcntl(sv[0], F_SETFL, O_NONBLOCK);
    static char seen[1 << 20];
    sink k = { seen, 0, sizeof seen };
    size_t off = 0;
    int shut = 0, eof = 0;
    double give_up = now_seconds() + HANG_SECONDS;
    while (!eof) {
        int progress = 0;
        MHD_run(srv->daemon);
        eof = pump(sv[0], data, size, &off, &shut, &k, &progress);
        if (now_seconds() > give_up) {
            fprintf(stderr, "fuzz_http: the connection was still open after %g s\n", HANG_SECONDS);
            __builtin_trap();
        }
        if (!progress && !eof)
            poll(NULL, 0, 0); /* MHD waits for nothing but our next call: go round again */
    }
    MHD_run(srv->daemon); /* MHD frees the closed connection here */
    close(sv[0]);
    if (has_500(&k)) {
        fprintf(stderr, "fuzz_http: a response had status 500\n");
        __builtin_trap();
    }
    if (atomic_load(&srv->m.connections_open) != 0 || atomic_load(&srv->m.runs_in_flight) != 0 ||
        atomic_load(&srv->m.studies_in_flight) != 0) {
        fprintf(stderr, "fuzz_http: a connection, run or study outlived its connection\n");
        __builtin_trap();
    }
    return 0;
}
