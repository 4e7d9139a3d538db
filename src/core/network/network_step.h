/* src/core/network/network_step.h - internal: the exact theta-step of a network (docs/systems.md §1) as one strictly
 * convex, piecewise quadratic problem
 *
 *     min_v  1/2 v^T W v - rhs^T v + h sum_e Psi_e(b_e^T v),   Psi_e' = Sigma_e,
 *     Sigma_e(z) = A_e(z - v_b,e) + S_e(u_e + h z),
 *
 * or, for an elastoplastic (Jenkins) spring stepped theta-consistently, theta S_e(u_e + h theta z) with u_e
 * the elongation plus h (1-theta) times its rate and S_e the return mapping's graph at the current plastic
 * offset (the caller rewrites it between steps and puts the (1-theta) part of the force in rhs),
 *
 * solved by a primal active-set method over the pieces of the graphs Sigma_e (network_step.c). W is given
 * in GSL's symmetric band storage: row i of an n x (p+1) array holds W(i+d, i), d = 0..p.
 */
#ifndef DASHPOT_CORE_NETWORK_STEP_H
#define DASHPOT_CORE_NETWORK_STEP_H

#include <stddef.h>
#include "dashpot/graph.h"
#include "dashpot/model.h"

/* An element whose law enters the step's convex problem: a set-valued or piecewise-linear damper A and/or
 * a spring graph S that is not linear (linear springs and viscous parts live in W). */
typedef struct dp_network_step_element {
    long a, b;            /* ends: node index or -1 for the ground; z = v_b - v_a */
    const dp_graph *A;    /* (z - vb, F_c) or NULL */
    const dp_graph *S;    /* (u + h z, F_s) or NULL */
    double vb;
    double ep_theta;      /* 0: S at u + h z with weight 1 (graph springs); theta > 0: S at u + h theta z,
                             weighted theta (an elastoplastic spring) */
    int s_whole;          /* S's force with weight 1 even at u + h theta z: a jump of a graph spring (constant
                             off its vertex, a reaction at it), network_run.c */
} dp_network_step_element;

/* What the step found for one element. */
typedef struct dp_network_step_forces {
    double z;             /* relative velocity at the step's end */
    double lambda;        /* Sigma_e's force: a + s */
    double a, s;          /* the damper's and the spring's parts */
    int at_rest;          /* held at A's vertex at zero relative velocity (sticking) */
} dp_network_step_forces;

typedef struct dp_network_step dp_network_step;

/* A workspace for n nodes, bandwidth p, and ne elements (the array is kept by reference). */
dp_network_step *dp_network_step_alloc(size_t n, size_t p, size_t ne, const dp_network_step_element *el);
void dp_network_step_free(dp_network_step *w);

/* A stop hook's poll (the run's, record/sink.h), asked after every solve of an assignment with the work done
 * since it was last asked: units of one band entry or element touched (a solve costs n (p+1) + ne, a
 * factorization nr (pr+1)^2 more). Nonzero: the solve ends at once with DP_ECANCEL. NULL: never asked. */
typedef int (*dp_network_step_poll_fn)(void *ctx, unsigned long long units);
void dp_network_step_set_poll(dp_network_step *w, dp_network_step_poll_fn poll, void *ctx);

/* The contracted matrix R (a tree of fixed elements is one unknown) keeps W's band where the trees are runs
 * of consecutive nodes, but trees that interleave widen it (a tree of the even nodes couples to every odd
 * one): R grows on demand, up to max_doubles (0: no bound); past it a solve returns DP_ELIMIT.
 * dp_network_step_reduced_need: the doubles the last contraction asked for. */
void dp_network_step_limit(dp_network_step *w, size_t max_doubles);
size_t dp_network_step_reduced_need(const dp_network_step *w);

/* Relaxation: Sigma_e gains -gamma_e(theta z + (1-theta) z_start - v_b), gamma[i] NULL where there is none
 * (the array is kept by reference). The step is then solved by Newton-Josephy iterations on the smooth
 * part, each an exact piecewise-linear problem; W - h theta sum L_e b b^T must stay positive definite. */
void dp_network_step_relaxation(dp_network_step *w, const dp_relaxation *const *gamma, double theta);

/* W's band storage, to be filled by the caller; call dp_network_step_W_changed after changing it. */
double *dp_network_step_W(dp_network_step *w);
void dp_network_step_W_changed(dp_network_step *w);

/* Solves the step: v (n) receives the minimizer, f (ne) each element's forces; u (ne) are the elongations
 * the spring graphs see (u_e + h z), v_guess a warm start (the previous velocity). *iters counts the
 * active-set iterations. DP_OK, DP_ESOLVE (no feasible start, cycling), DP_ECANCEL (the poll), DP_ELIMIT (R's
 * bound) or DP_ENOMEM. */
int dp_network_step_solve(dp_network_step *w, double h, const double *rhs, const double *u, const double *v_guess,
                 double *v, dp_network_step_forces *f, unsigned long long *iters);

/* ---- for event location (network_run.c): the assignment kept fixed over a shorter step ---- */

/* Bytes of the current assignment (which elements are fixed where, which piece the others are on). A buffer
 * is written by pattern_save only: the workspace remembers the one it last saved to or restored from and
 * what changed since, and copies only that to or from it again (a held solve changes a few elements). */
size_t dp_network_step_pattern_bytes(const dp_network_step *w);
void dp_network_step_pattern_save(dp_network_step *w, void *buf);
void dp_network_step_pattern_restore(dp_network_step *w, const void *buf);

/* Solves a step of length h with the current assignment held (no vertex met, no release): v and f as
 * dp_network_step_solve, and margin[i] >= 0 while element i's assignment is consistent (a free element inside its
 * piece, a fixed one's multiplier inside its interval), < 0 once it is not. DP_OK, DP_ESOLVE or DP_ECANCEL. */
int dp_network_step_solve_frozen(dp_network_step *w, double h, const double *rhs, const double *u, double *v, dp_network_step_forces *f,
                        double *margin);

/* A held solve's margins for the candidates `cand` (ne flags) alone, on a chain (half-bandwidth one; couple[i]:
 * nodes i and i+1 coupled in W) whose fixed elements each hold one node to the ground: blocks_for writes into
 * blk (pairs lo, hi of node indices, at most cap / 2) the sorted, disjoint blocks of nodes those margins need
 * and returns how many (0: not such a chain now, or too many: solve the whole step). solve_blocks takes, for
 * each block in turn, rows lo-1 .. hi of W (two entries a row, concatenated: Wl) and rows lo .. hi of the
 * right side (rl), and writes the candidates' margins as solve_frozen would, bit for bit, and the fixed ones'
 * multipliers; 1 done, 0 not such a block (solve the whole step), -1 the poll said stop. */
size_t dp_network_step_blocks(dp_network_step *w, const unsigned char *cand, const unsigned char *couple,
                              size_t *blk, size_t cap);
int dp_network_step_solve_blocks(dp_network_step *w, double h, const size_t *blk, size_t nb, const double *Wl,
                                 const double *rl, const double *u, const unsigned char *cand, double *margin);

/* With relaxation: the velocity a held step starts from (gamma's argument is theta z + (1-theta) z_start);
 * solve_frozen then iterates on gamma as a whole solve does. Nothing without relaxation. */
void dp_network_step_relaxation_start(dp_network_step *w, const double *v_start);

/* Whether the current assignment is the saved one (same fixed vertices, same pieces). */
int dp_network_step_pattern_same(const dp_network_step *w, const void *buf);

/* At a located event: a free element i that reached an end of its piece is fixed at that end (the one
 * nearer its relative velocity in v); a fixed one is freed onto the piece towards its multiplier's
 * violation (the last held solve's). dp_network_step_violation: +1 above its interval, -1 below, and inside it
 * the side of the nearer bound (0 for a free element). */
void dp_network_step_fix_end(dp_network_step *w, size_t i, const double *v);
int dp_network_step_violation(const dp_network_step *w, size_t i, double h, const double *u);
void dp_network_step_slip(dp_network_step *w, size_t i, double h, const double *u, int dir);
/* Element i is fixed (at any vertex) / at its damper's vertex at zero relative velocity (sticking). */
int dp_network_step_fixed(const dp_network_step *w, size_t i);
int dp_network_step_at_rest(const dp_network_step *w, size_t i);

#endif
