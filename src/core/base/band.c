/* src/core/base/band.c - symmetric band matrices (band.h): written once here, the network step, the Newmark
 * step and the network run had each kept their own copy. The factorization is GSL's. */
#include <stdlib.h>

#include <gsl/gsl_linalg.h>

#include "base/band.h"
#include "dashpot/status.h"

void dp_band_from_dense(const double *A, size_t n, size_t p, double *B)
{
    for (size_t i = 0; i < n; i++)
        for (size_t d = 0; d <= p && i + d < n; d++)
            B[i * (p + 1) + d] = A[(i + d) * n + i];
}

void dp_band_symv(const double *A, size_t n, size_t p, const double *x, double *y)
{
    for (size_t i = 0; i < n; i++)
        y[i] = A[i * (p + 1)] * x[i];
    for (size_t i = 0; i < n; i++)
        for (size_t d = 1; d <= p && i + d < n; d++) {
            double a = A[i * (p + 1) + d];
            y[i] += a * x[i + d];
            y[i + d] += a * x[i];
        }
}

void dp_band_axpy(const double *A, size_t n, size_t p, double s, const double *x, double *y)
{
    for (size_t i = 0; i < n; i++) {
        y[i] += s * A[i * (p + 1)] * x[i];
        for (size_t d = 1; d <= p && i + d < n; d++) {
            double a = s * A[i * (p + 1) + d];
            y[i] += a * x[i + d];
            y[i + d] += a * x[i];
        }
    }
}

void dp_band_add_incidence(double *B, size_t p, long a, long b, double w)
{
    if (a >= 0)
        B[(size_t)a * (p + 1)] += w;
    if (b >= 0)
        B[(size_t)b * (p + 1)] += w;
    if (a >= 0 && b >= 0) {
        size_t lo = (size_t)(a < b ? a : b), d = (size_t)labs(a - b);
        B[lo * (p + 1) + d] -= w;
    }
}

int dp_band_cholesky(double *F, size_t n, size_t p)
{
    gsl_matrix_view Fv = gsl_matrix_view_array(F, n, p + 1);
    return gsl_linalg_cholesky_band_decomp(&Fv.matrix) == 0 ? DP_OK : DP_ESOLVE;
}

int dp_band_cholesky_solve(const double *F, size_t n, size_t p, double *x)
{
    gsl_matrix_const_view Fv = gsl_matrix_const_view_array(F, n, p + 1);
    gsl_vector_view xv = gsl_vector_view_array(x, n);
    return gsl_linalg_cholesky_band_svx(&Fv.matrix, &xv.vector) == 0 ? DP_OK : DP_ESOLVE;
}
