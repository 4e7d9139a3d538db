/* include/dashpot/lcs.h - linear complementarity systems (Cibulka 2014 (1.10), §1.4; docs/systems.md §5):
 *
 *     x' = A x + B u + p,   w = C x + D u + q,   (u_i, w_i) in the law of component i,
 *
 * a law being complementarity 0 <= u_i ⊥ w_i >= 0 (an ideal diode: u the current or minus its voltage) or an
 * interval w_i ∈ -N_[lo,hi](u_i) (u = lo: w >= 0; u = hi: w <= 0; between: w = 0; a diode with breakdown,
 * a relay), or any maximal monotone piecewise-linear graph G in the (u, -w) plane: -w_i ∈ G(u_i), the
 * convention of the interval (whose G is the normal cone N_[lo,hi]). The θ-step takes u at the step's end:
 * x+ = E x + h W p + h W B u+, W = (I - hθA)^-1, E = W (I + h(1-θ)A), and u+ solves one LCP with matrix
 * D + h C W B per step (an interval as a pair of complementarity rows, a graph as one row per non-vertical
 * ray and two per non-vertical segment between the vertices where it turns: docs/lcs.md), exactly, by
 * Lemke's method (lcp.h).
 */
#ifndef DASHPOT_LCS_H
#define DASHPOT_LCS_H

#include <stddef.h>
#include "dashpot/lcp.h"
#include "dashpot/model.h"
#include "dashpot/spec.h"

/* GRAPH, COULOMB and ROPE are graph laws: `graph` holds their (u, -w) graph (the one-mass model's builders:
 * the damper's Coulomb graph, the spring's rope, user points) and the stepper uses nothing else. */
typedef enum dp_lcs_law_kind {
    DP_LCS_COMPLEMENTARITY = 0, DP_LCS_INTERVAL = 1, DP_LCS_GRAPH = 2, DP_LCS_COULOMB = 3, DP_LCS_ROPE = 4,
    DP_LCS_LAW_COUNT     /* not a law: the number of them (the law table's size) */
} dp_lcs_law_kind;

typedef struct dp_lcs_law {
    dp_lcs_law_kind kind;
    double lo, hi;       /* interval laws: lo <= hi */
    double phi0;         /* coulomb: -w ∈ phi0 Sgn(u) */
    double k, length;    /* rope: -w = k u for u < length, >= k length at u = length */
    dp_graph graph;      /* graph laws (an empty graph for the others) */
} dp_lcs_law;

/* The component laws' table (src/core/lcp/lcs_laws.c), as the one-mass laws' (dashpot/model.h): its name and
 * members, and what the stepper takes of it. A shape of 0 is no law: refused (dp_lcs_law_valid). */
typedef enum dp_lcs_shape {
    DP_LCS_SHAPE_NONE,
    DP_LCS_SHAPE_CONE,       /* 0 <= u ⊥ w >= 0: one complementarity row */
    DP_LCS_SHAPE_INTERVAL,   /* w ∈ -N_[lo,hi](u), lo and hi its members: two rows */
    DP_LCS_SHAPE_GRAPH       /* -w ∈ G(u), G the law's `graph` (user points, or built from its members) */
} dp_lcs_shape;

typedef struct dp_lcs_law_info {
    dp_law_row row;
    dp_lcs_shape shape;
    int (*build)(dp_lcs_law *law);   /* a named graph law's graph from its members; NULL for the others */
} dp_lcs_law_info;

extern const dp_lcs_law_info dp_lcs_laws[DP_LCS_LAW_COUNT];
/* A kind's entry; NULL for a value that is no law. */
const dp_lcs_law_info *dp_lcs_law_info_of(dp_lcs_law_kind kind);

/* Whether the stepper takes the law's graph (its entry's shape is a graph: GRAPH, COULOMB, ROPE). */
int dp_lcs_law_is_graph(const dp_lcs_law *law);
/* The LCP rows a law adds to a step: 1 for complementarity, 2 for an interval, for a graph one per
 * non-vertical end ray and two per non-vertical segment between the vertices where it turns (a user graph's
 * end points only set its rays; 0 for a vertical line: u fixed). */
size_t dp_lcs_law_rows(const dp_lcs_law *law);
/* Whether the stepper takes the law: an interval with lo <= hi, a non-empty graph whose pieces have finite
 * slopes (points near the ends of the double range can overflow one). */
int dp_lcs_law_valid(const dp_lcs_law *law);

/* The system; the caller owns the arrays (row-major: A n x n, B n x m, C m x n, D m x m, p n, q m). */
typedef struct dp_lcs {
    size_t n, m;
    const double *A, *B, *C, *D, *p, *q;
    const dp_lcs_law *law;
} dp_lcs;

/* An LCS model as a spec holds it (the document's "model": {"lcs": {...}, "laws": [...]}, "initial"): owned
 * arrays, D, p, q zero when the document leaves them out, x0 the initial state. */
typedef struct dp_lcs_model {
    size_t n, m;
    double *A, *B, *C, *D, *p, *q, *x0;
    dp_lcs_law *law;
    dp_forcing *pf;      /* NULL, or n offsets in time added to p (the document's forcing objects in "p") */
} dp_lcs_model;

/* Accepts NULL. */
void dp_lcs_model_free(dp_lcs_model *lm);
/* A deep copy, or NULL when out of memory. */
dp_lcs_model *dp_lcs_model_copy(const dp_lcs_model *lm);
/* The system view of a model (pointers into it). */
dp_lcs dp_lcs_model_system(const dp_lcs_model *lm);

/* The spec rules of an LCS run (the stick-slip solver, t_end/dt within max_steps, an initial state the laws
 * admit: some u with (u, Cx0 + Du + q) in the laws), appended as located errors. DP_OK, DP_EINVAL, DP_ELIMIT. */
int dp_lcs_check(const dp_spec *s, double max_steps, dp_errors *e);

/* What Cibulka 2014's theory says about a checked LCS spec (framework "LCS"): existence and uniqueness by
 * Theorem 2.3 when D's symmetric part is positive definite, and whether the θ-step's matrix is a P-matrix.
 * DP_OK, DP_ENOMEM, DP_ESOLVE. */
struct dp_wp_report;
int dp_lcs_wellposedness(const dp_spec *s, struct dp_wp_report *rep);

typedef struct dp_lcs_stepper dp_lcs_stepper;

/* A stepper for step h >= 0 and θ in [0, 1]; h = 0 is the algebraic part alone (M = D: a step leaves x and
 * finds u, w at it). NULL with *status DP_EINVAL (sizes, non-finite data, an interval with lo > hi, an empty
 * graph, an LCP of more than DP_LCP_MAX rows, I - hθA singular) or DP_ENOMEM. The system's arrays are
 * copied (a graph law's pieces too). */
dp_lcs_stepper *dp_lcs_stepper_alloc(const dp_lcs *sys, double h, double theta, int *status);
/* The same, and when it refuses the system, the member of an LCS simulate document that made it (a JSON
 * Pointer: "/solver/dt" for a singular I - hθA, "/model/lcs/A", "/model/lcs/B", "/model/lcs/C",
 * "/model/lcs/D", "/model/lcs/p" or "/model/laws" for a product that leaves the doubles: every quantity the
 * step derives from the data is checked finite where it is formed; "" for invalid sizes or no memory) and a
 * sentence, both static strings. */
dp_lcs_stepper *dp_lcs_stepper_alloc_why(const dp_lcs *sys, double h, double theta, int *status, const char **where,
                                         const char **why);
void dp_lcs_stepper_free(dp_lcs_stepper *st);

/* The step's LCP matrix D + h C W B (m x m) for the uniqueness theory (dp_lcp_theory_of). */
const gsl_matrix *dp_lcs_step_matrix(const dp_lcs_stepper *st);

/* Sets the offset p (n numbers) of the following steps: p(t_n + θh) for a time-dependent one. O(n^2). */
void dp_lcs_stepper_set_p(dp_lcs_stepper *st, const double *p);

/* Discretizes the stepper again for the step h > 0 (the same system, θ and current p): a sub-step of a step
 * split at an event. DP_OK, DP_EINVAL (I - hθA singular, or a product beyond the doubles, at this h: the
 * stepper is then unusable until a later call succeeds), DP_ENOMEM. O(n^3). */
int dp_lcs_stepper_set_h(dp_lcs_stepper *st, double h);

/* ---- modes and their boundaries (docs/lcs.md, "Mode changes are events") ----------------------------------
 * A component's law splits its graph in the (u, -w) plane into modes, numbered 0, 1, ... left to right along
 * the graph: each vertical piece (u held while w moves) and each non-vertical piece (u moves) is one. An ideal
 * diode's complementarity has two, 0 (u = 0 <= w) and 1 (u > 0 = w); an interval three, 0 (u = lo, w >= 0),
 * 1 (lo < u < hi, w = 0) and 2 (u = hi, w <= 0); `coulomb` three (sliding left, held, sliding right); a graph
 * one per piece. Consecutive modes meet at a boundary, a point of the graph; a component in mode k has passed
 * exactly k of its boundaries. */

/* The number of boundaries of the stepper's laws, component i's numbered first[i] .. first[i+1] - 1 in order
 * along its graph (*first: m + 1 entries, owned by the stepper). */
size_t dp_lcs_boundaries(const dp_lcs_stepper *st, const size_t **first);

/* After a step, each boundary's margin: > 0 when the step's solution lies past it along the graph, < 0 before
 * it, 0 on it. Each is z - w (or w - z) of one complementary pair of the step's LCP, of which Lemke's settled
 * answer makes one exactly 0, so its sign is exact. On the side where u moves along a piece it measures u, on
 * the other the force -w. */
void dp_lcs_margins(const dp_lcs_stepper *st, double *margin);

/* The side of boundary b (+1: past it, -1: before it, 0: neither) where the margin is a multiplier's: u on a
 * flat piece of a component whose w does not depend on u (D's row and column zero; an ideal diode that
 * blocks with D = 0 holds w = 0 by u). The θ-step takes such a u as its mean over the step, which is u at
 * the step's θ-point to second order, not at its end; the other margins are the end's. */
int dp_lcs_boundary_lag(const dp_lcs_stepper *st, size_t b);

/* A mode change located inside a step: component `component` went from mode `from` to mode `mode` at time t
 * (on: along its graph to the right, u or -w growing: for complementarity u_i leaves 0; off: back), u and w
 * its u_i and w_i there. Changes through several modes at one instant are one event. */
typedef struct dp_lcs_event {
    size_t component, from, mode;
    int on;
    double t, u, w;
} dp_lcs_event;

/* Locates mode changes: each step that changes a component's mode is split at the instant the first change
 * happens (a root of that boundary's margin as a function of the sub-step's length, by a safeguarded
 * Illinois iteration on sub-steps from the step's start), and continued from there with the new mode, so
 * θ = 1/2 keeps its order through the switches. */
typedef struct dp_lcs_locator dp_lcs_locator;

/* A locator for steps of the system with θ in [0, 1]; pf is NULL or n forcings, p(t) = sys->p + pf(t) taken
 * at each sub-step's θ-point. The system's arrays and pf must outlive it. NULL with *status (as
 * dp_lcs_stepper_alloc; h is a step the system admits, the locator's sub-steps are shorter). */
dp_lcs_locator *dp_lcs_locator_alloc(const dp_lcs *sys, const dp_forcing *pf, double h, double theta, int *status);
void dp_lcs_locator_free(dp_lcs_locator *lc);

/* The modes at the start, from a step just taken by st (the algebraic part at x0): a component on one of its
 * boundaries has no mode until a step leaves it, and no event then. */
void dp_lcs_locator_start(dp_lcs_locator *lc, const dp_lcs_stepper *st);

/* One step of length h from time t: x (n), u, w (m) in and out, as dp_lcs_step_until with `nominal` (its
 * offset already p at this step's θ-point). When the nominal step leaves every mode as it was, its result is
 * taken as it is (bit for bit); otherwise the step is split at each change, found to a few ulps of t. A
 * sub-step that fails (I - hθA singular at its length, no LCP solution) gives the change up: the nominal
 * step is taken and its changes dated at its end. Statuses as dp_lcs_step_until, for the nominal step. */
int dp_lcs_step_located(dp_lcs_locator *lc, dp_lcs_stepper *nominal, double t, double h, double *x, double *u,
                        double *w, dp_lcp_result *res, const dp_stop *stop);

/* The changes of the last located step, in time order: *n of them. */
const dp_lcs_event *dp_lcs_located_events(const dp_lcs_locator *lc, size_t *n);

/* The sub-steps taken so far to locate changes (each one LCP). */
unsigned long long dp_lcs_locator_substeps(const dp_lcs_locator *lc);

/* One step: x (n) in, x+ out; u, w (m) out at the step's end. DP_OK, DP_ESOLVE when the step's LCP has no
 * solution Lemke can find (res->outcome: a ray, or an answer that fails its check; x unchanged), DP_ELIMIT
 * (Lemke's pivot limit; x unchanged), DP_ENONFINITE (the step's LCP offsets leave the doubles). res: Lemke's
 * report. */
int dp_lcs_step(dp_lcs_stepper *st, double *x, double *u, double *w, dp_lcp_result *res);
/* The same, asking `stop` (may be NULL) through Lemke's pivots: DP_ECANCEL once it said stop (x unchanged). */
int dp_lcs_step_until(dp_lcs_stepper *st, double *x, double *u, double *w, dp_lcp_result *res, const dp_stop *stop);

#endif
