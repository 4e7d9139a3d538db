/* include/dashpot/lcp.h - the linear complementarity problem w = Mz + q, 0 <= z ⊥ w >= 0 (Cibulka 2014 (1.10),
 * Examples 1.6, 2.4, 2.6; docs/systems.md §5): Lemke's complementary pivoting, all solutions of a small problem by
 * enumerating its 2^m complementary bases, and what the theory says about uniqueness (Cibulka 2014 Lemma 2.5,
 * Theorem 2.3: a positive definite symmetric part, µ = λ_min((M + Mᵀ)/2) > 0, gives exactly one solution,
 * Lipschitz in q with constant 1/µ; a P-matrix, all principal minors > 0, is exactly the class where every q
 * has one solution).
 *
 * Every computation here is invariant under the problem's units: it works on M and q equilibrated by powers of
 * two (positive diagonal scalings of rows and columns keep the solutions and the P property), and a candidate
 * is accepted by a relative test, each row against the size of its own terms (docs/lcs.md, "Scaling and
 * tolerances"). Scaling M and q by 1e-200 or 1e200 changes no decision and no count.
 */
#ifndef DASHPOT_LCP_H
#define DASHPOT_LCP_H

#include <stddef.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>
#include "dashpot/status.h"

/* Largest size for the enumeration of all complementary bases and the P-matrix test (2^12 = 4096 bases). */
#define DP_LCP_ENUM_MAX 12
/* Largest size the wire accepts (a 500x500 tableau is 4 MB). */
#define DP_LCP_MAX 500

/* How Lemke's method ended. */
typedef enum dp_lcp_outcome {
    DP_LCP_SOLVED = 0,   /* z, w solve the problem */
    DP_LCP_RAY = 1,      /* secondary ray: no solution for a P-matrix, a copositive-plus (e.g. PSD) M, ... */
    DP_LCP_INACCURATE = 2 /* the final basis' answer (or the ray's direction) fails its check: rounding on an
                          * ill-conditioned basis; z, wv unspecified, never a solution */
} dp_lcp_outcome;

typedef struct dp_lcp_result {
    dp_lcp_outcome outcome;
    size_t pivots;       /* pivots taken (0 when q >= 0) */
    double residual;     /* relative, dimensionless: per row i, with s_i = |q_i| + Σ_j |M_ij z_j|, the largest of
                          * a negative w_i, of the change in w a negative z_j makes, and of the smaller of z_i, w_i
                          * when both are positive, each against s_i (accepted up to 1e-9); for a ray, that of its
                          * direction in the homogeneous equations */
} dp_lcp_result;

/* A workspace for problems of size m (the tableau, the basis, LU scratch); one per thread. */
typedef struct dp_lcp dp_lcp;

/* NULL when out of memory or m == 0 or m > DP_LCP_MAX. */
dp_lcp *dp_lcp_alloc(size_t m);
void dp_lcp_free(dp_lcp *w);

/* Lemke's method with the covering vector e = (1, ..., 1) and the lexicographic ratio test (no cycling on
 * degenerate problems) on the equilibrated problem. M is m x m, q, z, wv of length m (z and wv written). On
 * DP_OK, res->outcome says whether z, wv solve the problem; a solution is read from the final tableau after one
 * step of iterative refinement with the tableau's basis inverse and checked (res->residual, relative), and
 * it meets z >= 0, w >= 0, zᵀw = 0 exactly. The workspace makes a solve allocation-free. DP_EINVAL: sizes
 * differ from the workspace or a non-finite entry; DP_ELIMIT: dp_lcp_pivot_limit(m) pivots were taken
 * (Murty 1978's matrices need 2^m; res->pivots says how many); DP_ENONFINITE: the solution is beyond the
 * doubles (a z or w above 1.8e308); z, wv are then unspecified. */
int dp_lcp_lemke(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, gsl_vector *z, gsl_vector *wv,
                 dp_lcp_result *res);

/* The same, asking `stop` (may be NULL) every millisecond or so of pivoting: DP_ECANCEL once it said stop. */
int dp_lcp_lemke_until(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, gsl_vector *z, gsl_vector *wv,
                       dp_lcp_result *res, const dp_stop *stop);

/* The pivot limit for size m: 1000 + 200 m, far above what a lexicographic run takes on the problems of this
 * project (a few m), far below Murty's 2^m, and a bound on the work of a hostile input. */
size_t dp_lcp_pivot_limit(size_t m);

/* All solutions found by trying every complementary basis (m <= DP_LCP_ENUM_MAX): for each set a of
 * indices with z basic, M_aa z_a = -q_a solved on the equilibrated problem, kept when the relative test of
 * dp_lcp_result's residual accepts it (so each listed pair meets z >= 0, w >= 0, zᵀw = 0 exactly), duplicates
 * merged. `singular` counts the bases whose M_aa is singular to rounding (its determinant below 1e-12 of
 * Hadamard's bound, on the scaled matrix): a continuum of solutions may pass through them (Cibulka 2014
 * Example 2.4 with a = 0, p = 0), and it is not enumerated. */
typedef struct dp_lcp_solutions {
    size_t m, n, cap;
    double *z;           /* n solutions, z[k*m .. k*m + m) */
    double *w;           /* their w = Mz + q, settled */
    size_t singular;
} dp_lcp_solutions;

/* DP_OK, DP_EINVAL (m > DP_LCP_ENUM_MAX, sizes, non-finite), DP_ENONFINITE (a solution beyond the doubles),
 * DP_ENOMEM. `out` is initialized here and must be cleared with dp_lcp_solutions_clear whatever the status. */
int dp_lcp_enumerate(const gsl_matrix *M, const gsl_vector *q, dp_lcp_solutions *out);
/* The same, asking `stop` (may be NULL) every 256 bases: DP_ECANCEL once it said stop. */
int dp_lcp_enumerate_until(const gsl_matrix *M, const gsl_vector *q, dp_lcp_solutions *out, const dp_stop *stop);
void dp_lcp_solutions_clear(dp_lcp_solutions *s);

/* Uniqueness theory of M. p_matrix: 1 all principal minors > 0, 0 not (witness: the set in `minor_set`, a
 * bit mask, with its minor, negative or 0 when singular to rounding, NaN when beyond the doubles), -1 not
 * decided (m > DP_LCP_ENUM_MAX and the symmetric part not positive definite). The minors' signs are read from
 * LU factors of the equilibrated matrix, compared with Hadamard's bound in logarithms: no product of m
 * entries is formed, so 1e-200 I is a P-matrix as I is. mu = λ_min((M + Mᵀ)/2), computed on M scaled by a
 * power of two; pd_symmetric = mu > 0 (then M is a P-matrix and the solution map q -> z has Lipschitz constant
 * 1/mu: Theorem 2.3 with L = 1; +inf when 1/mu is beyond the doubles). psd = mu >= -tolerance. */
typedef struct dp_lcp_theory {
    int p_matrix;
    unsigned minor_set;
    double minor;
    double mu;
    int pd_symmetric, psd;
    double lipschitz;    /* 1/mu when pd_symmetric, else +inf */
} dp_lcp_theory;

/* DP_OK, DP_EINVAL (not square, non-finite), DP_ENOMEM, DP_ESOLVE (the eigensolver failed), DP_ENONFINITE
 * (mu beyond the doubles: |M| near 1.8e308). */
int dp_lcp_theory_of(const gsl_matrix *M, dp_lcp_theory *t);

#endif
