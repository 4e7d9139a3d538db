/* src/core/base/dense.h - internal: values between the accepted steps of an adaptive integrator, so that it can
 * step freely and still report samples on a fixed output grid (regularized.c). */
#ifndef DASHPOT_CORE_DENSE_H
#define DASHPOT_CORE_DENSE_H

#include <stddef.h>

/* One end of a step: the time, and the state with its first and second time derivatives there
 * (dim values each). */
typedef struct dp_hermite_end {
    double t;
    const double *y, *dy, *d2y;
} dp_hermite_end;

/* out[i] = p_i(t) for the degree-5 polynomial p_i matching y, y' and y'' of component i at both ends a, b
 * (a->t < b->t; t in [a->t, b->t]). Exact for polynomials of degree <= 5; for a smooth solution the error is
 * at most h^6 max|y^(6)| / 46080 with h = b->t - a->t. The derivative data must be good: an error e in y'
 * or E in y'' moves the result by up to 0.15 h e + 0.017 h^2 E. */
void dp_hermite5(const dp_hermite_end *a, const dp_hermite_end *b, size_t dim, double t, double out[]);

#define DP_POLY_MAX 8

/* out[i] = the value at t of the polynomial of degree n - 1 through (ts[k], ys[k][i]), k < n <= DP_POLY_MAX,
 * ys[k] = ys + k * dim, the ts distinct (Neville's scheme). A BDF method's own interpolant: through the
 * last q + 1 accepted values of an order-q step. */
void dp_poly_interp(const double ts[], const double *ys, size_t n, size_t dim, double t, double out[]);

#endif
