/* include/dashpot/modes.h - linear analysis of a network: natural modes, damped eigenvalues and the
 * receptance (Höschl's dynamic compliance), docs/systems.md §2.
 *
 *     M x'' + C x' + K x = f,   K phi = omega^2 M phi,   H(omega) = (K - omega^2 M + i omega C)^-1
 *
 * The core works on dense n*n row-major matrices (dp_network_linear_parts gives them for a network), so
 * that Höschl's coupled examples given as matrices and chains of elements go through the same code. A
 * diagonal M with a tridiagonal K (every chain) takes a tridiagonal route (bisection and inverse
 * iteration), O(n^2) with the shapes; anything else takes GSL's generalized symmetric solver.
 */
#ifndef DASHPOT_MODES_H
#define DASHPOT_MODES_H

#include <stddef.h>
#include "dashpot/status.h"

/* Dense eigenproblems cost n^3: documents past these sizes are refused (DP_ELIMIT). */
#define DP_MODES_MAX_NODES 2000         /* chains (the O(n^2) route) */
#define DP_MODES_MAX_DENSE_NODES 1000   /* anything else */
#define DP_MODES_MAX_DAMPED_NODES 400

/* One damped eigenvalue lambda of (lambda^2 M + lambda C + K) phi = 0 with Im lambda >= 0. */
typedef struct dp_damped_eig {
    double re, im;
    double damping_ratio;    /* -Re lambda / |lambda|; NaN for lambda = 0 (a rigid mode): written null */
} dp_damped_eig;

typedef struct dp_modes {
    size_t n;
    double *lambda;          /* n eigenvalues omega^2, ascending (0 for rigid modes) */
    double *shape;           /* n*n: mode k is shape[k*n .. k*n+n), M-normalized, first clear entry > 0 */
    int *rigid;              /* 1 where the mode is a rigid-body (zero-frequency) mode */
    double *participation;   /* phi_k^T M 1: how a uniform ground motion excites mode k */
    double *modal_damping;   /* phi_k^T C phi_k / (2 omega_k): the modal damping ratio (exact when C is
                                proportional); NaN when there is no C or the mode is rigid */
    int damped;              /* a nonzero C was given: the damped eigenvalues below are filled */
    int proportional;        /* Phi^T C Phi is diagonal (Rayleigh damping among others) */
    size_t ndamped;
    dp_damped_eig *eig;      /* ndamped eigenvalues with Im >= 0, ascending in |lambda| */
    int tridiagonal;         /* which route the undamped problem took (for the reader and the benchmark) */
} dp_modes;

/* Solves the modes of (M, K) and, when C is not NULL and not zero, the damped eigenvalues. M must be
 * symmetric positive definite, K and C symmetric positive semidefinite; a violation is DP_EINVAL with an
 * error whose pointer is `pointer_M`, `pointer_K` or `pointer_C` (the fields the matrices came from).
 * DP_ELIMIT past the size limits, DP_ESOLVE if an eigensolver fails, DP_ENOMEM. `out` is always to be
 * dp_modes_free'd. */
int dp_modes_solve(size_t n, const double *M, const double *K, const double *C, const char *pointer_M,
                   const char *pointer_K, const char *pointer_C, dp_modes *out, dp_errors *errs);

/* Where M, K and C came from, and how to solve them (dp_modes_solve_until). */
typedef struct dp_modes_opts {
    const char *pointer_M, *pointer_K, *pointer_C;   /* the fields the matrices came from */
    /* Optional: writes into `pointer` (cap bytes) the JSON Pointer of the member that makes row `row` of
     * matrix `which` ('M', 'K' or 'C') as large or as small as it is, for errors about scale (an overflow);
     * NULL: such errors name pointer_M, pointer_K or pointer_C. */
    void (*member)(void *ctx, char which, size_t row, char *pointer, size_t cap);
    void *ctx;
    int skip_damped;          /* leave the damped eigenvalues out (a receptance needs only the modes) */
    const dp_stop *stop;      /* polled between phases, between modes and inside the chain solver; may be NULL */
} dp_modes_opts;

/* dp_modes_solve with options: also DP_ECANCEL once `stop` said stop, and DP_EINVAL with an error at the
 * member to blame when a derived quantity (M^-1/2 K M^-1/2, L^-1 K L^-T, the first-order matrix, an
 * eigenvalue, a modal damping) would leave the finite numbers even after scaling (docs/modes.md, "Limits"). */
int dp_modes_solve_until(size_t n, const double *M, const double *K, const double *C, const dp_modes_opts *opts,
                         dp_modes *out, dp_errors *errs);

void dp_modes_free(dp_modes *m);

/* ---- frequency response (response.c) ---- */

typedef struct dp_response_point {
    double omega;
    double re, im;           /* H_ji(omega) */
    double magnitude, phase; /* |H| and arg H in (-pi, pi]; both NaN (written null) where H is infinite: an
                                undamped system sampled exactly at a resonance */
} dp_response_point;

typedef struct dp_response {
    size_t npoints;
    dp_response_point *point;
    size_t nres, nanti;
    double *resonance;       /* omega_k of the modes that node i excites and node j sees, inside the range */
    size_t *resonance_mode;  /* their mode indices */
    double *antiresonance;   /* zeros of the undamped H_ji inside the range, located by Brent's method */
} dp_response;

/* The receptance of node j (response) to a harmonic unit force at node i over `points` frequencies from
 * `from` to `to` (log spacing when `log_spacing`, from > 0 then). `modes` must be the dp_modes_solve of the
 * same M, K, C. A modal sum when the damping is absent or proportional, a complex solve per frequency
 * otherwise. DP_OK, DP_ELIMIT (the work would exceed the budget), DP_ENOMEM. */
int dp_response_solve(size_t n, const double *M, const double *K, const double *C, const dp_modes *modes,
                      size_t i, size_t j, double from, double to, size_t points, int log_spacing,
                      dp_response *out);

/* dp_response_solve polling `stop` (may be NULL) before every point: DP_ECANCEL once it said stop. Also
 * DP_ENONFINITE when a receptance of a finite system is not a finite number (past DBL_MAX). */
int dp_response_solve_until(size_t n, const double *M, const double *K, const double *C, const dp_modes *modes,
                            size_t i, size_t j, double from, double to, size_t points, int log_spacing,
                            const dp_stop *stop, dp_response *out);

void dp_response_free(dp_response *r);

#endif
