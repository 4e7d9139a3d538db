/* src/core/base/band.h - symmetric band matrices in GSL's storage (row i of an n x (p+1) array holds
 * A(i+d, i), d = 0..p): the products, the assembly of an element and the Cholesky factorization that the
 * network step, the Newmark step and the network run share. */
#ifndef DASHPOT_CORE_BASE_BAND_H
#define DASHPOT_CORE_BASE_BAND_H

#include <stddef.h>

/* The band (n, p) of a dense row-major n x n symmetric A into B. */
void dp_band_from_dense(const double *A, size_t n, size_t p, double *B);
/* y = A x. */
void dp_band_symv(const double *A, size_t n, size_t p, const double *x, double *y);
/* y += s A x. */
void dp_band_axpy(const double *A, size_t n, size_t p, double s, const double *x, double *y);
/* B += w b b^T for the incidence vector b of an element between nodes a and b (< 0: the ground). */
void dp_band_add_incidence(double *B, size_t p, long a, long b, double w);
/* The Cholesky factor of F in place, and a solve with it in place of x: DP_OK or DP_ESOLVE. */
int dp_band_cholesky(double *F, size_t n, size_t p);
int dp_band_cholesky_solve(const double *F, size_t n, size_t p, double *x);

#endif
