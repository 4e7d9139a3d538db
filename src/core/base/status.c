/* src/core/base/status.c - status descriptions and the located-error list (status.h). */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "dashpot/status.h"

const char *dp_strerror(int status)
{
    switch (status) {
    case DP_OK: return "success";
    case DP_MORE: return "more records follow";
    case DP_DONE: return "run complete";
    case DP_EINVAL: return "invalid specification";
    case DP_ENOMEM: return "out of memory";
    case DP_ELIMIT: return "limit exceeded";
    case DP_ESOLVE: return "a step could not be solved";
    case DP_ENONFINITE: return "the solution diverged (non-finite values)";
    case DP_ESYNTAX: return "malformed JSON";
    case DP_ECANCEL: return "cancelled";
    default: return "unknown status";
    }
}

void dp_errors_init(dp_errors *e)
{
    e->n = 0;
    e->dropped = 0;
}

void dp_errors_add(dp_errors *e, const char *pointer, const char *fmt, ...)
{
    if (e == NULL)
        return;
    if (e->n >= DP_ERRORS_MAX) {
        e->dropped++;
        return;
    }
    dp_error *it = &e->item[e->n++];
    snprintf(it->pointer, sizeof it->pointer, "%s", pointer ? pointer : "");
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(it->message, sizeof it->message, fmt, ap);
    va_end(ap);
}
