/* src/core/base/root.h - internal: bracketed scalar root finding shared by the step solvers. */
#ifndef DASHPOT_CORE_ROOT_H
#define DASHPOT_CORE_ROOT_H

typedef double (*dp_root_fn)(void *ctx, double x);

/* A root of g in [a, b] given g(a) = ga and g(b) = gb of opposite signs (either may be zero), to within
 * `tol` or until g vanishes. Illinois regula falsi, safeguarded by bisection so that the bracket at least
 * halves every third iteration: at most ~3*64 evaluations for any double bracket. *evals is incremented
 * per evaluation (may be NULL). Returns the point with the smaller |g| of the final bracket. */
double dp_root_bracket(dp_root_fn g, void *ctx, double a, double b, double ga, double gb, double tol,
                       unsigned long long *evals);

#endif
