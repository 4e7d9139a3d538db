/* include/dashpot/status.h - status codes and located errors shared by every layer of libdashpot.
 *
 * The core returns a dp_status and never prints. Validation errors carry the JSON Pointer of the field
 * they are about (RFC 6901), so that the CLI and the daemon can say exactly what is wrong and where.
 *
 * Before using the library, call gsl_set_error_handler_off() (<gsl/gsl_errno.h>) once, before starting
 * threads: libdashpot checks every GSL status itself and returns it as a dp_status, but GSL's default
 * handler aborts the process first (docs/operations.md, "Linking against libdashpot").
 */
#ifndef DASHPOT_STATUS_H
#define DASHPOT_STATUS_H

#include <stddef.h>

typedef enum dp_status {
    DP_OK = 0,
    DP_MORE = 1,      /* an iterator produced records and has more */
    DP_DONE = 2,      /* an iterator is exhausted; the summary is final */
    DP_EINVAL = -1,   /* invalid argument or spec (see the dp_errors list) */
    DP_ENOMEM = -2,   /* allocation failed */
    DP_ELIMIT = -3,   /* a documented limit was exceeded */
    DP_ESOLVE = -4,   /* a step could not be solved (no bracket, no convergence) */
    DP_ENONFINITE = -5, /* the solution left the finite numbers (divergence) */
    DP_ESYNTAX = -6,  /* malformed input document (JSON syntax) */
    DP_ECANCEL = -7   /* stopped on request (deadline, client gone) */
} dp_status;

/* A static English description of a status; never NULL. */
const char *dp_strerror(int status);

#define DP_POINTER_MAX 160
#define DP_MESSAGE_MAX 320
#define DP_ERRORS_MAX 32

/* One located error: where (JSON Pointer, "" for the document itself) and what was expected. */
typedef struct dp_error {
    char pointer[DP_POINTER_MAX];
    char message[DP_MESSAGE_MAX];
} dp_error;

/* A caller-owned list of errors. Errors past DP_ERRORS_MAX are counted in `dropped`, not stored. */
typedef struct dp_errors {
    size_t n;
    size_t dropped;
    dp_error item[DP_ERRORS_MAX];
} dp_errors;

/* Empties the list. */
void dp_errors_init(dp_errors *e);

/* Appends an error; `fmt` is printf-style. Never fails (overflow is counted in `dropped`). */
void dp_errors_add(dp_errors *e, const char *pointer, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* A stop hook for one computation (a network step, Lemke's pivots, an eigensolver, a response curve): `fn`
 * returns > 0 when the work must end now (a deadline passed, the client left, shutdown), 0 to go on.
 * Computations poll it every so often (at most ~DP_RUN_POLL_WORK units of work apart) and then return
 * DP_ECANCEL. A NULL dp_stop, or one whose fn is NULL, never stops. */
typedef struct dp_stop {
    int (*fn)(void *ctx);
    void *ctx;
} dp_stop;

static inline int dp_stop_now(const dp_stop *stop)
{
    return stop && stop->fn && stop->fn(stop->ctx) > 0;
}

#endif
