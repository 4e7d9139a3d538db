/* src/core/base/tridiag.h - internal: the symmetric tridiagonal eigensolver of the chain route (tridiag.c). */
#ifndef DASHPOT_CORE_TRIDIAG_H
#define DASHPOT_CORE_TRIDIAG_H

#include <stddef.h>

#include "dashpot/status.h"

/* All eigenpairs of the symmetric tridiagonal matrix with diagonal d[0..n) and off-diagonal e[0..n-1):
 * eigenvalues ascending into w[0..n), eigenvector r (unit length) into Z[r*n .. r*n+n). 0, or -1 when out
 * of memory. O(n^2) time for well-separated eigenvalues, O(n^2) memory (Z). */
int dp_tridiag_eigen(size_t n, const double *d, const double *e, double *w, double *Z);

/* The same, polling `stop` (may be NULL) between blocks and between eigenvectors: -2 once it said stop
 * (w and Z are then incomplete). Inverse iteration re-orthogonalizes within clusters, O(n^3) when every
 * eigenvalue is within 1e-3 ||T|| of the others (a chain with one very stiff spring), so it must stop. */
int dp_tridiag_eigen_until(size_t n, const double *d, const double *e, double *w, double *Z, const dp_stop *stop);

#endif
