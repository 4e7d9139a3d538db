/* include/dashpot/regularized.h - the regularized existence schemes (PCn), (PIk) and their convergence study.
 *
 * Both schemes replace a set-valued constitutive relation by a single-valued Lipschitz one and integrate the
 * resulting ODE (docs/mathematics.md §3). For a maximal monotone graph A in the (y, F) plane they are the same
 * object seen from two sources:
 *   (PCn), Pražák & Rajagopal 2016 (17): (F_c, y - F_c/n) in A   <=>  F_c = g_n(y) = A_(1/n)(y), the Yosida approximation;
 *   (PIk), Babováková 2012 (FIk): y = f(F) + F/k          <=>  F = f_k^-1(y) = A_(1/k)(y) with A the graph of f.
 * The solvers use the Yosida form (exact for piecewise-linear graphs, O(log vertices)); the 45-degree rotation
 * of Lemma 1 (Pražák & Rajagopal 2016 (11)) gives g_n for any maximal monotone graph through a 1-Lipschitz phi, and the
 * tests check that both agree.
 */
#ifndef DASHPOT_REGULARIZED_H
#define DASHPOT_REGULARIZED_H

#include "dashpot/graph.h"
#include "dashpot/spec.h"

/* ---- the regularized laws ------------------------------------------------------------------------------ */

/* phi(s) of Lemma 1: (F, y) in A <=> F - y = phi(F + y). For a graph, the point with y + F = s is
 * (J_1(s), s - J_1(s)), so phi(s) = s - 2 J_1(s): 1-Lipschitz. Coulomb: s on |s| <= phi0, 2 phi0 - s beyond. */
double dp_graph_rotation(const dp_graph *g, double s);

/* The Yosida approximation A_l(y) and (slope != NULL) its derivative, the one from the right at a kink:
 * dF/(dy + l dF) on the piece the resolvent lands on, 1/l on a vertical piece. The value is
 * dp_graph_yosida(g, l, y) up to rounding, computed from the piece's vertex: exact on flat pieces. */
double dp_graph_yosida_slope(const dp_graph *g, double l, double y, double *slope);

/* A 1-Lipschitz function phi: R -> R (Lemma 1), as a callback. */
typedef double (*dp_rotation_fn)(void *ctx, double s);

/* g_n(v) from paper (17): the fixed point F = G_n(F, v) = n/(n+1) (v + phi(v + (n-1)/n F)), n >= 1, for any
 * 1-Lipschitz phi. G_n contracts with alpha = (n-1)/(n+1), so the root of F - G_n(F, v) (slope >= 1 - alpha)
 * is bracketed by the a-priori bound (14) and found to rounding. *evals counts phi calls (may be NULL).
 * Returns NAN when phi returns a non-finite value. */
double dp_regularized_gn(dp_rotation_fn phi, void *ctx, double n, double v, unsigned long long *evals);

/* ---- the convergence study ----------------------------------------------------------------------------- */

/* One regularization parameter of a study. Distances are sup-norms over the common output times
 * t_j = j dt (and t_end). Rates are log(e_prev / e) / log(n / n_prev); NAN where undefined. */
typedef struct dp_convergence_row {
    double n;                            /* n of (PCn) or k of (PIk) */
    double err_x, err_v;                 /* against the exact (reference) solution */
    double diff_x, diff_v;               /* against the previous row's solution (NAN on the first row) */
    double rate_x, rate_v;               /* observed order of err_x, err_v against the previous row */
    unsigned long long steps, rejected;  /* the integrator's accepted and rejected steps */
    unsigned long long fevals, jevals;   /* right-hand side and Jacobian evaluations */
} dp_convergence_row;

typedef enum dp_reference_kind { DP_REFERENCE_ANALYTIC, DP_REFERENCE_STICK_SLIP } dp_reference_kind;

typedef struct dp_convergence {
    dp_scheme scheme;
    dp_stepper stepper;
    double rtol, atol, dt, t_end;
    /* The exact solution compared against: the closed form (Babováková 2012 (4.14)) where it exists, otherwise the
     * stick-slip solver with events located, theta 1/2 (theta 1 for a graph spring) and step ref_dt. */
    dp_reference_kind reference;
    double ref_dt, ref_theta;
    unsigned long long samples;          /* output times compared */
    double rate_x, rate_v;               /* least-squares slope of -log err against log n over all rows */
    size_t nrows;
    dp_convergence_row row[DP_SPEC_MAX_NLIST];
} dp_convergence;

/* Runs the regularized solver of `spec` (kind DP_SOLVER_REGULARIZED) once per entry of its n_list and the
 * reference solver, all in lockstep, so memory does not grow with t_end. `max_steps` (<= 0: the ceiling)
 * bounds each run's step count as for dp_run_alloc; `ref_dt` <= 0 picks the reference step (dt/ref_dt an
 * integer, at most 1e-4 for theta 1/2 and 1e-5 for theta 1). Returns DP_OK with *out filled, DP_EINVAL /
 * DP_ELIMIT with located errors, DP_ENOMEM, or a run's DP_ESOLVE / DP_ENONFINITE (message in errs); on
 * error *out holds no meaningful rows. */
int dp_convergence_study(const dp_spec *spec, double max_steps, double ref_dt, dp_convergence *out,
                         dp_errors *errs);

/* The same, asking stop(ctx) (may be NULL) before each block of every run (at most 64 records or 10^5
 * integrator steps apart): when it answers nonzero the study ends with DP_ECANCEL and an error at "".
 * This is how a server holds a study to a wall-time limit. */
int dp_convergence_study_until(const dp_spec *spec, double max_steps, double ref_dt, int (*stop)(void *ctx),
                               void *ctx, dp_convergence *out, dp_errors *errs);

struct dp_buf;

/* Appends the study as one JSON object (json layer, src/json/convergence_json.c):
 * {"scheme","stepper","rtol","atol","dt","t_end","reference":{"solver","dt","theta"},"samples",
 *  "rate_x","rate_v","rows":[{"n","err_x","err_v","diff_x","diff_v","rate_x","rate_v","steps","rejected",
 *  "fevals","jevals"}...]} with round-trip doubles; undefined numbers are null. DP_OK or DP_ENOMEM. */
int dp_convergence_json(const dp_convergence *c, struct dp_buf *out);

/* Names used on the wire: "PC"/"PI", "msbdf", "rk4imp", "bsimp", "rkf45", "rkck", "rk8pd". */
const char *dp_scheme_name(dp_scheme s);
const char *dp_stepper_name(dp_stepper s);

#endif
