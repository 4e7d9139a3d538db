/* src/core/laws/inclusion.h - internal: the scalar monotone inclusion every implicit step reduces to. */
#ifndef DASHPOT_CORE_INCLUSION_H
#define DASHPOT_CORE_INCLUSION_H

#include "dashpot/graph.h"
#include "dashpot/model.h"

/* Find w with 0 in Phi(w) = W w - b + h A(w - a_shift) + h S(s_x + s_h w) - h gamma(g_theta w + g_shift).
 * A is the damper graph (v - v_b, F_c); S (may be NULL) a spring graph (x, F_s) stepped implicitly;
 * gamma (may be NULL or DP_RELAX_NONE) the relaxation. Phi is strictly increasing when
 * W > h g_theta L_gamma (docs/mathematics.md §4, "Exact form of the step"), and the solution is then unique. */
typedef struct dp_inclusion {
    double W, b, h;
    const dp_graph *A;
    double a_shift;
    const dp_graph *S;
    double s_x, s_h;
    const dp_relaxation *gamma;
    double g_theta, g_shift;
    size_t *hint;      /* NULL, or two slots (A, S) remembering where the last step's kink search ended */
} dp_inclusion;

/* Solves for *w and splits the set-valued part into the damper force *a in A(w - a_shift) and the spring
 * force *s in S(...) (0 without S). Exact at vertices (sticking, a taut rope) and on affine pieces without
 * relaxation; with relaxation the root is bracketed and refined to rounding. *evals counts evaluations.
 * Returns DP_OK, DP_ESOLVE (no finite bracket) or DP_ENONFINITE (Phi or the forces are not numbers: the
 * step's quantities overflow). */
int dp_inclusion_solve(const dp_inclusion *p, double *w, double *a, double *s, unsigned long long *evals);

/* A solution strictly on one side of rest, sgn(w - a_shift) = dir, if there is one (DP_ESOLVE if not):
 * the motion branch where rest is also a solution (Pražák & Rajagopal 2016, (26)-(27)). */
int dp_inclusion_solve_side(const dp_inclusion *p, double dir, double *w, double *a, double *s,
                            unsigned long long *evals);

/* [*lo, *hi] = Phi(w) with A's interval at w replaced by [flo, fhi]. */
void dp_inclusion_phi_with(const dp_inclusion *p, double w, double flo, double fhi, double *lo, double *hi);

/* Whether w solves the inclusion when A's interval at w is replaced by [flo, fhi] (a static threshold). */
int dp_inclusion_holds_with(const dp_inclusion *p, double w, double flo, double fhi);

#endif
