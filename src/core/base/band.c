/* src/core/base/band.c - symmetric band matrices (band.h): written once here, the network step, the Newmark
 * step and the network run had each kept their own copy. The factorization and the solve are GSL's; at
 * half-bandwidth one (a chain: the network step's every solve and refactorization) both are written out,
 * since GSL's generic band routines (dscal, dsyr, dtbsv through CBLAS) cost several times the bidiagonal
 * sweeps they perform there. Each entry is formed by the same operations in the same order as GSL's, so the
 * answers are the same bit for bit (checked against GSL on random bands while writing them). */
#include <math.h>
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

/* y = A x at half-bandwidth one, every y[i] summed in the order of the general loop below: its diagonal
 * term, then the term from row i-1, then the one from row i+1. */
static void symv_tridiagonal(const double *A, size_t n, const double *x, double *y)
{
    double carry = A[0] * x[0];   /* y[i] so far: its diagonal term plus row i-1's */
    for (size_t i = 0; i + 1 < n; i++) {
        double a = A[2 * i + 1];
        y[i] = carry + a * x[i + 1];
        carry = A[2 * (i + 1)] * x[i + 1] + a * x[i];
    }
    y[n - 1] = carry;
}

void dp_band_symv(const double *A, size_t n, size_t p, const double *x, double *y)
{
    if (n == 0)
        return;
    if (p == 0) {   /* diagonal (masses alone, one node) */
        for (size_t i = 0; i < n; i++)
            y[i] = A[i] * x[i];
        return;
    }
    if (p == 1) {
        symv_tridiagonal(A, n, x, y);
        return;
    }
    size_t p1 = p + 1;
    for (size_t i = 0; i < n; i++)
        y[i] = A[i * p1] * x[i];
    for (size_t i = 0; i < n; i++) {
        const double *row = A + i * p1;
        size_t dmax = n - 1 - i < p ? n - 1 - i : p;
        for (size_t d = 1; d <= dmax; d++) {
            double a = row[d];
            y[i] += a * x[i + d];
            y[i + d] += a * x[i];
        }
    }
}

void dp_band_axpy(const double *A, size_t n, size_t p, double s, const double *x, double *y)
{
    size_t p1 = p + 1;
    for (size_t i = 0; i < n; i++) {
        const double *row = A + i * p1;
        size_t dmax = n - 1 - i < p ? n - 1 - i : p;
        y[i] += s * row[0] * x[i];
        for (size_t d = 1; d <= dmax; d++) {
            double a = s * row[d];
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

/* GSL's band Cholesky at half-bandwidth one, operation for operation (gsl_linalg_cholesky_band_decomp: the
 * pivot's square root, the column scaled by its inverse (dscal), the next pivot less the column's square
 * (dsyr with alpha -1)), without the 1-norm GSL keeps in the unused last entry for its condition estimate. */
static int cholesky_bidiagonal(double *F, size_t n)
{
    for (size_t j = 0; j < n; j++) {
        double ajj = F[2 * j];
        if (ajj <= 0.0)
            return DP_ESOLVE;
        ajj = sqrt(ajj);
        F[2 * j] = ajj;
        if (j + 1 < n) {
            double v = (1.0 / ajj) * F[2 * j + 1];
            F[2 * j + 1] = v;
            F[2 * (j + 1)] += v * (-1.0 * v);
        }
    }
    return DP_OK;
}

int dp_band_cholesky(double *F, size_t n, size_t p)
{
    if (p == 1 && n > 1)
        return cholesky_bidiagonal(F, n);
    gsl_matrix_view Fv = gsl_matrix_view_array(F, n, p + 1);
    return gsl_linalg_cholesky_band_decomp(&Fv.matrix) == 0 ? DP_OK : DP_ESOLVE;
}

/* L L^T x = b for a bidiagonal L (row j of F: L(j,j), L(j+1,j)): L z = b forwards, L^T x = z backwards. */
static void solve_bidiagonal(const double *F, size_t n, double *x)
{
    x[0] = x[0] / F[0];
    for (size_t j = 1; j < n; j++)
        x[j] = (x[j] - F[2 * (j - 1) + 1] * x[j - 1]) / F[2 * j];
    x[n - 1] = x[n - 1] / F[2 * (n - 1)];
    for (size_t j = n - 1; j-- > 0;)
        x[j] = (x[j] - F[2 * j + 1] * x[j + 1]) / F[2 * j];
}

int dp_band_cholesky_solve(const double *F, size_t n, size_t p, double *x)
{
    if (p == 1 && n > 0) {
        solve_bidiagonal(F, n, x);
        return DP_OK;
    }
    gsl_matrix_const_view Fv = gsl_matrix_const_view_array(F, n, p + 1);
    gsl_vector_view xv = gsl_vector_view_array(x, n);
    return gsl_linalg_cholesky_band_svx(&Fv.matrix, &xv.vector) == 0 ? DP_OK : DP_ESOLVE;
}
