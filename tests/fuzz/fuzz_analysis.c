/* tests/fuzz/fuzz_analysis.c - libFuzzer target: any bytes through the three analysis entry points that are
 * not runs - one linear complementarity problem (POST /v1/lcp), the modes of a network (POST /v1/modes) and
 * its receptance curve (POST /v1/response, in each of its three formats) - with a stop hook, as the daemon
 * calls them on its compute threads.
 *
 * Failures: a crash, leak or sanitizer report; a hang (libFuzzer's -timeout: an eigensolver or a pivot loop
 * that never returns); a status outside the documented ones; an answer holding a non-finite number ("nan",
 * "inf"), or a failure that left bytes in the output; and a computation that went on after its stop hook
 * said stop (it must return DP_ECANCEL). The hook says stop at its stop_at-th poll, 1 to 64 from the input's
 * bytes, or never (stop_at 0), so both the stopped and the finished paths are reached.
 *
 * Seeds (tests/fuzz/corpus-analysis): the LCP, modes and response requests of the answers corpus
 * (tests/corpus/inputs), and hostile-*.json, the requests an adversarial review found to spin, to list
 * non-solutions or to lose real modes (1e308 stiffness under Rayleigh damping, a 5e-324 mass, Murty's m = 12
 * matrix, M = 1e200 I, a duplicate key). */
#include <ctype.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <strings.h>

#include <gsl/gsl_errno.h>

#include "dashpot/encode.h"
#include "dashpot/lcp_json.h"
#include "dashpot/modes_json.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    gsl_set_error_handler_off();
    return 0;
}

typedef struct fuzz_stop {
    unsigned calls, stop_at;
    int said_stop;
} fuzz_stop;

static int fuzz_hook(void *ctx)
{
    fuzz_stop *f = ctx;
    if (f->stop_at && ++f->calls >= f->stop_at)
        return f->said_stop = 1;
    return 0;
}

/* The statuses docs/http.md maps to answers; anything else would be a 500. */
static int documented(int s)
{
    return s == DP_OK || s == DP_EINVAL || s == DP_ESYNTAX || s == DP_ELIMIT || s == DP_ESOLVE
        || s == DP_ENONFINITE || s == DP_ENOMEM || s == DP_ECANCEL;
}

/* A finite answer: our encoders write non-finite numbers as null, never as the words nan or inf (in any case,
 * with any sign). Whole words only: "resonance" holds "nan". */
static int has_nonfinite_text(const dp_buf *b)
{
    size_t i = 0;
    while (i < b->len) {
        while (i < b->len && !isalpha((unsigned char)b->data[i]))
            i++;
        size_t start = i;
        while (i < b->len && isalpha((unsigned char)b->data[i]))
            i++;
        size_t n = i - start;
        if ((n == 3 && (strncasecmp(b->data + start, "nan", 3) == 0 || strncasecmp(b->data + start, "inf", 3) == 0))
            || (n == 8 && strncasecmp(b->data + start, "infinity", 8) == 0))
            return 1;
    }
    return 0;
}

typedef int (*entry_fn)(const char *text, size_t size, int format, const dp_stop *stop, dp_buf *out,
                        dp_errors *errs);

static int lcp(const char *t, size_t n, int f, const dp_stop *st, dp_buf *o, dp_errors *e)
{
    (void)f;
    return dp_lcp_respond_until(t, n, st, o, e);
}

static int modes(const char *t, size_t n, int f, const dp_stop *st, dp_buf *o, dp_errors *e)
{
    (void)f;
    return dp_modes_respond_until(t, n, st, o, e);
}

static int response(const char *t, size_t n, int f, const dp_stop *st, dp_buf *o, dp_errors *e)
{
    return dp_response_respond_until(t, n, f, st, o, e);
}

static void check(entry_fn fn, const char *text, size_t size, int format, unsigned stop_at)
{
    fuzz_stop f = { 0, stop_at, 0 };
    dp_stop stop = { fuzz_hook, &f };
    dp_errors errs;
    dp_errors_init(&errs);
    dp_buf out = { 0 };
    int s = fn(text, size, format, &stop, &out, &errs);
    if (!documented(s))
        __builtin_trap();
    if (f.said_stop && s != DP_ECANCEL && s != DP_OK)
        __builtin_trap(); /* told to stop, it failed otherwise: a stop must read as a stop */
    if (s != DP_OK && out.len != 0)
        __builtin_trap(); /* "on failure `out` is as it was" */
    if (s == DP_OK && has_nonfinite_text(&out))
        __builtin_trap();
    dp_buf_free(&out);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *text = (const char *)data;
    unsigned sum = 0;
    for (size_t i = 0; i < size; i++)
        sum += data[i];
    unsigned stop_at = sum % 65; /* 0: never */
    check(lcp, text, size, 0, stop_at);
    check(modes, text, size, 0, stop_at);
    check(response, text, size, DP_FORMAT_JSON, stop_at);
    check(response, text, size, DP_FORMAT_NDJSON, stop_at);
    check(response, text, size, DP_FORMAT_CSV, stop_at);
    return 0;
}
