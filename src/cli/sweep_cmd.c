/* src/cli/sweep_cmd.c - `dashpot sweep SWEEP.json [--shard i/N] [--threads T]`: a sweep's lines on stdout
 * (docs/sweep.md), the same lines POST /v1/sweep streams.
 *
 * A line per run as it completes (NDJSON), between a meta line and a summary line. --shard i/N runs the runs
 * whose index is i mod N, so N machines (a Slurm array, a Kubernetes Indexed Job) run a sweep between them
 * and their run lines, sorted by index, are the whole sweep's. --threads runs that many runs at once, each
 * thread taking every T-th run of the shard; a line is written whole under a lock, so lines never mix.
 * Exit status: 0 when the sweep ran to its end (runs that failed are lines saying why, counted in the
 * summary), 1 when it stopped (out of memory, output not writable), 2 for a bad document or usage.
 */
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "dashpot/json.h"
#include "dashpot/sweep_json.h"

#define MAX_THREADS 64

typedef struct shared {
    const dp_sweep_doc *doc;
    pthread_mutex_t out_lock;
    _Atomic unsigned long long budget;
    int io_failed;               /* under out_lock */
} shared;

typedef struct worker {
    shared *sh;
    pthread_t tid;
    dp_sweep_exec *x;
    int status;                  /* DP_DONE, or why it stopped */
    const char *why;
} worker;

static int usage(const char *why, const char *what)
{
    if (why != NULL)
        fprintf(stderr, "dashpot: sweep: %s%s%s\n", why, what ? what : "", what ? "\"" : "");
    fprintf(stderr, "usage: dashpot sweep SWEEP.json|- [--shard i/N] [--threads T] (dashpot sweep --help)\n");
    return DP_EXIT_USAGE;
}

/* Writes one line (and its newline) whole. */
static void emit(shared *sh, dp_buf *line)
{
    pthread_mutex_lock(&sh->out_lock);
    if (!sh->io_failed && (fwrite(line->data, 1, line->len, stdout) != line->len || fputc('\n', stdout) == EOF ||
                           fflush(stdout) != 0))
        sh->io_failed = 1;
    pthread_mutex_unlock(&sh->out_lock);
    line->len = 0;
}

static void *work(void *arg)
{
    worker *w = arg;
    dp_buf line = { 0 };
    int s, ready;
    do {
        s = dp_sweep_exec_next(w->x, &line, &ready, &w->why);
        if (ready)
            emit(w->sh, &line);
    } while (s == DP_MORE);
    w->status = s;
    dp_buf_free(&line);
    return NULL;
}

/* "i/N" with 0 <= i < N <= DP_SWEEP_MAX_RUNS into *i, *n; 0, or -1. */
static int parse_shard(const char *text, size_t *i, size_t *n)
{
    char *end;
    unsigned long a = strtoul(text, &end, 10);
    if (end == text || *end != '/' || text[0] == '-')
        return -1;
    const char *b = end + 1;
    unsigned long c = strtoul(b, &end, 10);
    if (end == b || *end != '\0' || b[0] == '-' || c == 0 || c > DP_SWEEP_MAX_RUNS || a >= c)
        return -1;
    *i = a;
    *n = c;
    return 0;
}

/* Runs the document's runs on `threads` threads; the exit status. */
static int run_all(dp_sweep_doc *doc, size_t threads)
{
    shared sh = { .doc = doc };
    pthread_mutex_init(&sh.out_lock, NULL);
    worker w[MAX_THREADS] = { 0 };
    dp_buf line = { 0 };
    int rc = DP_EXIT_OK;
    if (dp_sweep_meta_json(doc, DP_SPEC_MAX_STEPS, &line) != DP_OK)
        rc = DP_EXIT_FAIL;
    else
        emit(&sh, &line);
    size_t started = 0;
    for (size_t t = 0; t < threads && rc == DP_EXIT_OK; t++) {
        w[t] = (worker){ .sh = &sh };
        w[t].x = dp_sweep_exec_new(doc, t, threads, DP_SPEC_MAX_STEPS, &sh.budget,
                                   DP_SPEC_MAX_STEPS * DP_SWEEP_STEP_FACTOR);
        if (w[t].x == NULL || pthread_create(&w[t].tid, NULL, work, &w[t]) != 0) {
            dp_sweep_exec_free(w[t].x);
            rc = DP_EXIT_FAIL;
            break;
        }
        started++;
    }
    dp_sweep_totals tot = { 0 };
    for (size_t t = 0; t < started; t++) {
        pthread_join(w[t].tid, NULL);
        const dp_sweep_totals *x = dp_sweep_exec_totals(w[t].x);
        tot.completed += x->completed;
        tot.failed += x->failed;
        tot.steps += x->steps;
        if (w[t].status != DP_DONE) {
            fprintf(stderr, "dashpot: sweep: %s\n", w[t].why ? w[t].why : dp_strerror(w[t].status));
            rc = DP_EXIT_FAIL;
        }
        dp_sweep_exec_free(w[t].x);
    }
    if (rc == DP_EXIT_OK && dp_sweep_summary_json(dp_sweep_doc_count(doc), &tot, &line) == DP_OK)
        emit(&sh, &line);
    if (sh.io_failed) {
        fprintf(stderr, "dashpot: sweep: cannot write the output\n");
        rc = DP_EXIT_FAIL;
    }
    dp_buf_free(&line);
    pthread_mutex_destroy(&sh.out_lock);
    return rc;
}

int dp_cli_sweep(int argc, char **argv)
{
    const char *path = NULL;
    size_t shard_i = 0, shard_n = 0, threads = 1;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--shard") == 0 && i + 1 < argc) {
            if (parse_shard(argv[++i], &shard_i, &shard_n) != 0)
                return usage("--shard takes i/N with 0 <= i < N <= 10000, got \"", argv[i]);
        } else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
            char *end;
            long t = strtol(argv[++i], &end, 10);
            if (*end != '\0' || t < 1 || t > MAX_THREADS)
                return usage("--threads takes 1 to 64, got \"", argv[i]);
            threads = (size_t)t;
        } else if (strcmp(argv[i], "--shard") == 0 || strcmp(argv[i], "--threads") == 0) {
            return usage("a value is missing after \"", argv[i]);
        } else if (path == NULL && (argv[i][0] != '-' || strcmp(argv[i], "-") == 0)) {
            path = argv[i];
        } else {
            return usage(argv[i][0] == '-' ? "unknown option \"" : "one document only, got a second: \"", argv[i]);
        }
    }
    if (path == NULL)
        return usage("no document given: a file, or - for standard input", NULL);
    size_t len;
    char *text = dp_cli_read_input(path, &len);
    if (text == NULL)
        return DP_EXIT_USAGE;
    dp_errors errs;
    dp_errors_init(&errs);
    dp_sweep_doc *doc;
    int s = dp_sweep_parse(text, len, &doc, &errs);
    free(text);
    if (s != DP_OK) {
        dp_cli_print_errors(path, &errs);
        return s == DP_ENOMEM ? DP_EXIT_FAIL : DP_EXIT_USAGE;
    }
    if (shard_n)
        dp_sweep_doc_set_shard(doc, shard_i, shard_n);
    int rc = run_all(doc, threads);
    dp_sweep_doc_free(doc);
    return rc;
}
