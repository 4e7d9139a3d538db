/* src/core/lcp/lcp_scale.h - internal: the scaling every LCP computation of this folder works in, and the one
 * acceptance test of a candidate solution (lcp_scale.c). Why: w = Mz + q, 0 <= z ⊥ w >= 0 keeps its solutions
 * under positive diagonal scalings, w' = R w = (R M C) z' + R q with z = C z' (Cottle, Pang & Stone 1992,
 * §2.2; a P-matrix stays one, principal minors only gain positive factors), so every decision taken on the
 * equilibrated problem (rows, then columns, of largest entry in [1, 2)) is one the problem's units cannot
 * move: a matrix scaled by 1e-200 or 1e200 is answered as the same matrix scaled by 1. The factors are powers
 * of two, so scaling is exact and the floating-point arithmetic on the scaled problem is the original's,
 * times powers of two, but where an entry falls below 2^-1022 of its row's largest (an absolute change
 * far below the rounding of that row). Not public API.
 */
#ifndef DASHPOT_CORE_LCP_SCALE_H
#define DASHPOT_CORE_LCP_SCALE_H

#include <stddef.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>

/* A candidate is a solution when its relative residual (lcp_settle) is at most this: a backward stable solve
 * (LU with partial pivoting, a refined tableau) reaches about m eps times a modest growth factor, and a
 * real violation (a negative z or w, or both positive) is of order 1. */
#define LCP_ACCEPT 1e-9

/* The exponents: M' = 2^(r_i + c_j) M_ij, q' = 2^(r_i - s) q_i; back: z_j = 2^(c_j + s) z'_j,
 * w_i = 2^(s - r_i) w'_i. s brings q's largest entry to [1, 2), or, when q's entries span more than 1000
 * binades, its smallest to 2^-1000 (none lost to underflow). */
typedef struct lcp_scaling {
    int *r, *c;
    int s;
} lcp_scaling;

/* M (m x m, any row stride) and q (NULL for the matrix alone: s = 0) equilibrated into Ms (row-major) and qs;
 * 0 when an entry is not finite. */
int lcp_equilibrate(const gsl_matrix *M, const gsl_vector *q, double *Ms, double *qs, lcp_scaling *sc);

/* The relative residual of z (the problem's units) for w = Mz + q, 0 <= z ⊥ w >= 0: per row i, with
 * s_i = |q_i| + Σ_j |M_ij z_j| (its terms at z), the size of a negative w_i, of a negative z_j (the change in
 * w that setting it to 0 makes, relative to the s_i of the rows it enters), and of the smaller of w_i and z_i
 * when both are positive, each relative to s_i; the largest of them. Invariant under positive diagonal
 * scalings of rows and columns and under scaling q with z. When z fails, it is tried once more with its
 * entries below 1e-14 of its largest (on the equilibrated problem, sc) set to 0: a degenerate component, 0 in
 * exact arithmetic, whose rounding a row with no other term cannot absorb. Then z is settled (its negative
 * parts, and of a pair z_i, w_i both positive the relatively smaller z_i, set to 0) and w = Mz + q recomputed
 * for it (0 beside a positive z_i, rounding below 0 cleared), so that the answer meets z >= 0, w >= 0,
 * zᵀw = 0 exactly; a solution when the residual is at most LCP_ACCEPT. The sums are formed in long double:
 * x86-64's extended exponent holds every product of two doubles, so the test sees the problem as given, also
 * where the scaled problem lost an entry below 2^-1022 of its row. *finite = 0 when a w_i is beyond the
 * doubles. scratch: 2m long doubles and m bytes (LCP_SETTLE_SCRATCH). */
#define LCP_SETTLE_SCRATCH(m) (2 * (m) + ((m) + sizeof(long double) - 1) / sizeof(long double))
double lcp_settle(const gsl_matrix *M, const gsl_vector *q, const lcp_scaling *sc, double *z, double *w,
                  long double *scratch, int *finite);

/* z (and w, may be NULL) back in the problem's units into zo, wo; 0 when one of them leaves the doubles. */
int lcp_unscale(size_t m, const lcp_scaling *sc, const double *zs, const double *ws, double *zo, double *wo);

#endif
