/* src/core/regularized.c - the regularized existence schemes (PCn) and (PIk) as solvers (issue 5).
 * Not implemented yet: every spec asking for it is rejected with a clear error, never run. */
#include "run_internal.h"

void dp_regularized_check(const dp_spec *s, dp_errors *e)
{
    (void)s;
    dp_errors_add(e, "/solver/kind", "the regularized solver is not available in this version");
}

int dp_regularized_init(dp_run *r)
{
    return dp_run_fail(r, DP_EINVAL, "the regularized solver is not available in this version");
}

int dp_regularized_advance(dp_run *r)
{
    return dp_run_fail(r, DP_EINVAL, "the regularized solver is not available in this version");
}

void dp_regularized_free(struct dp_regularized *reg)
{
    (void)reg;
}
