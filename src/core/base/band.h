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
/* Entry i of the product A x with Ai pointing at row i of A's band storage (the rows above it before it, as
 * in dp_band_symv's storage or a block of consecutive rows), its terms summed in dp_band_symv's order (the
 * diagonal, the rows above, then row i's own), so that it equals that product's entry bit for bit. */
static inline double dp_band_row(const double *Ai, size_t p, const double *x, size_t i, size_t n)
{
    size_t p1 = p + 1;
    double y = Ai[0] * x[i];
    for (size_t k = i < p ? i : p; k > 0; k--)   /* row i - k's entry d = k, p1 - 1 before each row on */
        y += Ai[-(ptrdiff_t)(k * (p1 - 1))] * x[i - k];
    for (size_t d = 1; d <= p && i + d < n; d++)
        y += Ai[d] * x[i + d];
    return y;
}

/* The Cholesky factor of F in place, and a solve with it in place of x: DP_OK or DP_ESOLVE. */
int dp_band_cholesky(double *F, size_t n, size_t p);
int dp_band_cholesky_solve(const double *F, size_t n, size_t p, double *x);

#endif
