/* include/dashpot/lcp.h - the linear complementarity problem w = Mz + q, 0 <= z ⊥ w >= 0 (Cibulka 2014 (1.10),
 * Examples 1.6, 2.4, 2.6; docs/systems.md §5): Lemke's complementary pivoting, all solutions of a small problem by
 * enumerating its 2^m complementary bases, and what the theory says about uniqueness (Cibulka 2014 Lemma 2.5,
 * Theorem 2.3: a positive definite symmetric part, µ = λ_min((M + Mᵀ)/2) > 0, gives exactly one solution,
 * Lipschitz in q with constant 1/µ; a P-matrix, all principal minors > 0, is exactly the class where every q
 * has one solution).
 */
#ifndef DASHPOT_LCP_H
#define DASHPOT_LCP_H

#include <stddef.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>

/* Largest size for the enumeration of all complementary bases and the P-matrix test (2^12 = 4096 bases). */
#define DP_LCP_ENUM_MAX 12
/* Largest size the wire accepts (a 500x500 tableau is 4 MB). */
#define DP_LCP_MAX 500

/* How Lemke's method ended. */
typedef enum dp_lcp_outcome {
    DP_LCP_SOLVED = 0,   /* z, w solve the problem */
    DP_LCP_RAY = 1       /* secondary ray: no solution for a P-matrix, a copositive-plus (e.g. PSD) M, ... */
} dp_lcp_outcome;

typedef struct dp_lcp_result {
    dp_lcp_outcome outcome;
    size_t pivots;       /* pivots taken (0 when q >= 0) */
    double residual;     /* max over i of |min(z_i, w_i)|, max(-z_i, 0), max(-w_i, 0) and |w - Mz - q|_i */
} dp_lcp_result;

/* A workspace for problems of size m (the tableau, the basis, LU scratch); one per thread. */
typedef struct dp_lcp dp_lcp;

/* NULL when out of memory or m == 0 or m > DP_LCP_MAX. */
dp_lcp *dp_lcp_alloc(size_t m);
void dp_lcp_free(dp_lcp *w);

/* Lemke's method with the covering vector e = (1, ..., 1) and the lexicographic ratio test (no cycling on
 * degenerate problems). M is m x m, q, z, wv of length m (z and wv written). On DP_OK, res->outcome says
 * whether z, wv solve the problem; a solution is read from the final tableau after one step of iterative
 * refinement with the tableau's basis inverse, so it is exact to rounding unless the basis is ill-conditioned,
 * and checked (res->residual, in the problem's units). The workspace makes a solve allocation-free. DP_EINVAL: sizes differ from the workspace or a non-finite entry;
 * DP_ELIMIT: the pivot limit (a number of pivots no lexicographic run reaches on the problems of this
 * project, kept as a guard) was reached; z, wv are then unspecified. */
int dp_lcp_lemke(dp_lcp *w, const gsl_matrix *M, const gsl_vector *q, gsl_vector *z, gsl_vector *wv,
                 dp_lcp_result *res);

/* All solutions found by trying every complementary basis (m <= DP_LCP_ENUM_MAX): for each set a of
 * indices with z basic, M_aa z_a = -q_a, kept when z_a >= 0 and w >= 0 (to a tolerance relative to the
 * data), duplicates merged. `singular` counts the bases whose M_aa is singular: a continuum of solutions may
 * pass through them (Cibulka 2014 Example 2.4 with a = 0, p = 0), and it is not enumerated. */
typedef struct dp_lcp_solutions {
    size_t m, n, cap;
    double *z;           /* n solutions, z[k*m .. k*m + m) */
    size_t singular;
} dp_lcp_solutions;

/* DP_OK, DP_EINVAL (m > DP_LCP_ENUM_MAX, sizes, non-finite), DP_ENOMEM. `out` is initialized here and
 * must be cleared with dp_lcp_solutions_clear whatever the status. */
int dp_lcp_enumerate(const gsl_matrix *M, const gsl_vector *q, dp_lcp_solutions *out);
void dp_lcp_solutions_clear(dp_lcp_solutions *s);

/* Uniqueness theory of M. p_matrix: 1 all principal minors > 0, 0 not (witness: the set in `minor_set`, a
 * bit mask, with its minor), -1 not decided (m > DP_LCP_ENUM_MAX and the symmetric part not positive
 * definite). mu = λ_min((M + Mᵀ)/2); pd_symmetric = mu > 0 (then M is a P-matrix and the solution map
 * q -> z has Lipschitz constant 1/mu: Theorem 2.3 with L = 1). psd = mu >= -tolerance. */
typedef struct dp_lcp_theory {
    int p_matrix;
    unsigned minor_set;
    double minor;
    double mu;
    int pd_symmetric, psd;
    double lipschitz;    /* 1/mu when pd_symmetric, else +inf */
} dp_lcp_theory;

/* DP_OK, DP_EINVAL (not square, non-finite), DP_ENOMEM, DP_ESOLVE (the eigensolver failed). */
int dp_lcp_theory_of(const gsl_matrix *M, dp_lcp_theory *t);

#endif
