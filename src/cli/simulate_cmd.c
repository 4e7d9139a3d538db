/* src/cli/simulate_cmd.c - `dashpot simulate SPEC.json [--format json|ndjson|csv]`: one run to stdout.
 *
 * Output is written block by block as the solver produces it, so memory stays flat however long the run;
 * a progress bar goes to stderr only when stderr is a terminal and the run is long enough to need one.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "commands.h"
#include "dashpot/encode.h"
#include "dashpot/json.h"

#define BLOCK 4096
#define PROGRESS_MIN_STEPS 2e6   /* shorter runs finish before a bar would be read */

typedef struct progress { int on; double next; } progress;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void progress_show(progress *p, double fraction, int final)
{
    if (!p->on || (!final && now() < p->next))
        return;
    p->next = now() + 0.1;
    int width = 40, done = (int)(fraction * width);
    fprintf(stderr, "\r[%.*s%*s] %5.1f%%", done, "########################################", width - done, "",
            100 * fraction);
    if (final)
        fputc('\n', stderr);
}

/* What was wrong (NULL: nothing to add), then the usage line; exit status 2. */
static int usage(const char *why, const char *what)
{
    if (why != NULL)
        fprintf(stderr, "dashpot: simulate: %s%s%s\n", why, what ? what : "", what ? "\"" : "");
    fprintf(stderr, "usage: dashpot simulate SPEC.json|- [--format json|ndjson|csv] [--quiet]"
                    " (dashpot simulate --help)\n");
    return DP_EXIT_USAGE;
}

/* Writes and empties the buffer; 0 on success. */
static int flush(dp_buf *b)
{
    int ok = b->len == 0 || fwrite(b->data, 1, b->len, stdout) == b->len;
    b->len = 0;
    return ok ? 0 : -1;
}

static int stream(dp_run *run, dp_format fmt, const dp_buf *meta, progress *pg)
{
    dp_record *recs = malloc(BLOCK * sizeof *recs);
    dp_buf b = { 0 };
    dp_encoder enc;
    dp_encoder_init(&enc, fmt);
    dp_encoder_set_columns(&enc, dp_run_columns(run));
    int s = recs ? dp_encoder_begin(&enc, &b, meta->data) : DP_ENOMEM, io = 0;
    size_t n;
    while (s == DP_OK || s == DP_MORE) {
        s = dp_run_next(run, recs, BLOCK, &n);
        for (size_t i = 0; i < n && io == 0; i++)
            if (dp_encoder_record(&enc, &b, &recs[i]) != DP_OK)
                io = -1;
        io = io ? io : flush(&b);
        if (io)
            break;
        progress_show(pg, dp_run_progress(run), 0);
    }
    /* The closing part must be written whole too, or the document is cut short: that is a failure. */
    int end = DP_OK;
    if (s == DP_DONE && io == 0)
        end = dp_encoder_end(&enc, &b, dp_run_summary(run), NULL);
    else if (io == 0)
        end = dp_encoder_fail(&enc, &b, s, dp_run_error(run)[0] ? dp_run_error(run) : dp_strerror(s));
    io = io ? io : end != DP_OK ? -1 : flush(&b);
    io = io ? io : fflush(stdout) != 0 ? -1 : 0;
    progress_show(pg, dp_run_progress(run), 1);
    if (s != DP_DONE)
        fprintf(stderr, "dashpot: simulate: %s\n", dp_run_error(run)[0] ? dp_run_error(run) : dp_strerror(s));
    if (io)
        fprintf(stderr, "dashpot: simulate: cannot write the output\n");
    dp_encoder_clear(&enc);
    dp_buf_free(&b);
    free(recs);
    return s == DP_DONE && io == 0 ? DP_EXIT_OK : DP_EXIT_FAIL;
}

int dp_cli_simulate(int argc, char **argv)
{
    const char *path = NULL, *format = "json";
    int quiet = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--format") == 0 && i + 1 < argc)
            format = argv[++i];
        else if (strncmp(argv[i], "--format=", 9) == 0)
            format = argv[i] + 9;
        else if (strcmp(argv[i], "--quiet") == 0)
            quiet = 1;
        else if (strcmp(argv[i], "--format") == 0)
            return usage("--format needs a value: json, ndjson or csv", NULL);
        else if (path == NULL && (argv[i][0] != '-' || strcmp(argv[i], "-") == 0))
            path = argv[i];
        else if (argv[i][0] == '-' && strcmp(argv[i], "-") != 0)
            return usage("unknown option \"", argv[i]);
        else
            return usage("one spec only, got a second: \"", argv[i]);
    }
    int fmt = dp_format_from_name(format);
    if (fmt < 0 || fmt == DP_FORMAT_SSE)
        return usage("unknown format (expected json, ndjson or csv): \"", format);
    if (path == NULL)
        return usage("no spec given: a file, or - for standard input", NULL);
    dp_spec spec;
    dp_errors errs;
    dp_errors_init(&errs);
    int s = dp_cli_parse_spec(path, &spec);
    dp_run *run = s == DP_OK ? dp_run_alloc(&spec, 0, &errs, &s) : NULL;
    dp_buf meta = { 0 };
    if (run != NULL && (dp_spec_meta_json(&spec, &meta) != DP_OK || dp_buf_append(&meta, "", 1) != DP_OK)) {
        dp_run_free(run);
        run = NULL;
        s = DP_ENOMEM;
    }
    double steps = spec.solver.t_end / spec.solver.dt;
    dp_spec_clear(&spec);
    if (run == NULL) {
        dp_buf_free(&meta);
        dp_cli_print_errors(path, &errs);
        return s == DP_ENOMEM ? DP_EXIT_FAIL : DP_EXIT_USAGE;
    }
    progress pg = { .on = !quiet && isatty(STDERR_FILENO) && steps >= PROGRESS_MIN_STEPS };
    int rc = stream(run, (dp_format)fmt, &meta, &pg);
    dp_run_free(run);
    dp_buf_free(&meta);
    return rc;
}
