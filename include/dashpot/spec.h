/* include/dashpot/spec.h - one simulation request as data: model, initial state, solver, output.
 *
 * Produced by the JSON layer (dp_spec_parse, json.h) and consumed by every solver (run.h), so the CLI and the
 * daemon accept exactly the same documents (docs/architecture.md, "The spec is data").
 */
#ifndef DASHPOT_SPEC_H
#define DASHPOT_SPEC_H

#include "dashpot/model.h"
#include "dashpot/network.h"
#include "dashpot/status.h"

/* Hard ceiling on time steps of one run (front ends may set lower ones): 10^9 steps of a few ns each
 * is seconds of CPU; beyond that a request is almost surely a mistake in dt or t_end. */
#define DP_SPEC_MAX_STEPS 1000000000.0

typedef enum dp_solver_kind {
    DP_SOLVER_STICK_SLIP, DP_SOLVER_ANALYTIC, DP_SOLVER_REGULARIZED,
    DP_SOLVER_NEWMARK,    /* Höschl's incremental Newmark (newmark.h): linear and elastoplastic springs */
    DP_SOLVER_RIGHT_HAND  /* right-hand solutions of friction with motion-dependent normal force (right_hand.h) */
} dp_solver_kind;

/* The regularized existence schemes (docs/mathematics.md §3): (PCn) F_c = g_n(x') with g_n the Yosida
 * approximation A_(1/n) (Pražák & Rajagopal 2016 (17)); (PIk) F_s = f_k^-1(x), F_d = g_k^-1(x') with f_k = f + u/k
 * (Babováková 2012 ch. 2). */
typedef enum dp_scheme { DP_SCHEME_PC, DP_SCHEME_PI } dp_scheme;

/* GSL odeiv2 steppers: implicit ones (with the analytic Jacobian) for the stiff large-n regime. */
typedef enum dp_stepper {
    DP_STEPPER_MSBDF, DP_STEPPER_RK4IMP, DP_STEPPER_BSIMP, DP_STEPPER_RKF45, DP_STEPPER_RKCK, DP_STEPPER_RK8PD
} dp_stepper;

#define DP_SPEC_MAX_NLIST 16

typedef enum dp_variant { DP_VARIANT_EXACT, DP_VARIANT_THESIS } dp_variant;

/* How the stick-slip solver treats a phase change inside a step: DP_EVENTS_LOCATE splits the step at the
 * event (keeps theta = 1/2 second order); DP_EVENTS_NONE is plain Moreau-Jean time stepping as in Siconos. */
typedef enum dp_events_mode { DP_EVENTS_LOCATE, DP_EVENTS_NONE } dp_events_mode;

/* Where solutions are not unique (Pražák & Rajagopal 2016 §4), which one to follow from rest: DP_BRANCH_REST stays at rest
 * whenever rest is a solution; DP_BRANCH_MOTION leaves rest whenever a motion is a solution. */
typedef enum dp_branch { DP_BRANCH_REST, DP_BRANCH_MOTION } dp_branch;

typedef struct dp_solver_spec {
    dp_solver_kind kind;
    double dt;            /* step (stick-slip) or sample spacing (analytic) */
    double t_end;
    double theta;         /* [1/2, 1] */
    dp_variant variant;
    int Z;                /* thesis: maximum fixed-point iterations (4.13) */
    double eps;           /* thesis: fixed-point stopping tolerance (4.13) */
    dp_events_mode events;
    dp_branch branch;
    /* regularized */
    dp_scheme scheme;
    double n_list[DP_SPEC_MAX_NLIST]; /* regularization parameters n (PCn) or k (PIk); a study when > 1 */
    size_t n_count;
    double rtol, atol;
    dp_stepper stepper;
    /* newmark */
    double beta, gamma;   /* (0, 1/2], [1/2, 1]; 1/6, 1/2 is Höschl's linear acceleration */
} dp_solver_spec;

typedef struct dp_output_spec {
    long every;           /* emit every n-th step as a sample, >= 1 */
    int samples;          /* emit samples at all */
    int events;           /* emit events */
    size_t *nodes, nnodes;        /* networks: the nodes written (NULL: all) */
    size_t *elements, nelements;  /* networks: the elements written (NULL: all) */
    int quakes;           /* networks with friction: the slip-event catalogue (docs/quakes.md) */
} dp_output_spec;

typedef struct dp_spec {
    dp_model model;
    double x0, v0;
    dp_solver_spec solver;
    dp_output_spec output;
    dp_network *net;      /* a network document ("masses" or "mass_matrix"); NULL for the one-mass model */
    double *x0v, *v0v;    /* networks: the initial state, net->n each; right-hand models: 2 each,
                                 * Painlevé's rod 3: its end's height and rate after q */
    struct dp_lcs_model *lcs; /* a linear complementarity system (lcs.h); NULL otherwise */
    unsigned chosen;      /* DP_CHOSEN_* bits: the members dashpot chose because the document left them out */
    struct dp_right_hand_model *rh; /* a right-hand friction model (right_hand.h); NULL otherwise */
} dp_spec;

/* A spec with every default set (stick-slip, exact, theta 1, dt 1e-3, t_end 10, every 1) and an empty model. */
void dp_spec_init(dp_spec *s);

/* Frees what the spec owns; accepts an initialised or zeroed spec. */
void dp_spec_clear(dp_spec *s);

/* Deep copy of a whole spec into an uninitialised dst. DP_OK or DP_ENOMEM (dst then cleared). */
int dp_spec_copy(dp_spec *dst, const dp_spec *src);

/* The network rules (network_check.c): mass matrix positive definite, stiffness and damping semidefinite,
 * no element from an end to itself, the solver and laws the network stepping supports. */
void dp_network_check(const dp_spec *s, dp_errors *errs);

/* Whether a network run locates its events inside steps (network_run.c): events "locate", some element can
 * stick, and every law's pieces stay put as the step shrinks (linear springs, no relaxation or static
 * threshold); otherwise a phase change is reported at the end of its step. */
int dp_network_locates(const dp_spec *s);

/* Whether a network is one mass on one element [ground, 0] with diagonal mass, stepped by the stick-slip
 * solver: then it runs on the one-mass solver itself (network_one_mass.c), bit for bit and as fast. */
int dp_network_is_one_mass(const dp_spec *s);

/* Checks the spec as a whole (the cross-field rules the JSON schema cannot state: theta only with linear
 * parts, the contraction condition (4.10) for the thesis variant, x0 within the rope, the step count limit
 * `max_steps`), appending located errors. Requires dp_model_prepare() to have run.
 * Returns DP_OK or DP_EINVAL / DP_ELIMIT. */
int dp_spec_check(const dp_spec *s, double max_steps, dp_errors *errs);

/* The model family a spec holds: the one-mass model, a network, a linear complementarity system or a
 * right-hand friction model (its own member of dp_spec each). */
typedef enum dp_family { DP_FAMILY_ONE_MASS, DP_FAMILY_NETWORK, DP_FAMILY_LCS, DP_FAMILY_RIGHT_HAND } dp_family;
dp_family dp_spec_family(const dp_spec *s);

/* The regularized solver's own rules (regularized.c): which laws each scheme takes, n/k > 0, tolerances. */
void dp_regularized_check(const dp_spec *s, dp_errors *errs);

/* The right-hand solver's rules (right_hand_check.c): its models only with it, and it only with them. */
void dp_right_hand_check(const dp_spec *s, dp_errors *errs);

/* Number of steps the spec asks for: ceil(t_end / dt) (with a rounding guard). */
double dp_spec_steps(const dp_spec *s);

/* Members a document may leave out for dashpot to choose (dp_spec_choose), named in the meta line's "chosen":
 *   DP_CHOSEN_THETA  solver.theta = 1/2 (the trapezoidal rule: second order) where the model's rules allow it
 *                    (a stick-slip run of the exact variant whose springs are linear or elastoplastic, whose
 *                    contacts are rigid and whose step stays uniquely solvable), else 1 (backward Euler);
 *   DP_CHOSEN_EVERY  output.every, the smallest that keeps the run within DP_SPEC_SAMPLE_BUDGET samples. */
#define DP_CHOSEN_THETA 1u
#define DP_CHOSEN_EVERY 2u
#define DP_SPEC_SAMPLE_BUDGET 10001   /* the initial state and 10 000 more: a default run of 10^4 steps keeps them all */
double dp_spec_default_theta(const dp_spec *s);
/* The smallest every that gives at most `samples` (>= 2) samples, the first and the last included. */
long dp_spec_every_for(const dp_spec *s, double samples);
/* Sets the members named by `which` (DP_CHOSEN_* bits) as above and records them in s->chosen (theta only for
 * the theta-method, the stick-slip solver); the solver's kind, dt, t_end and the model must be parsed first. */
void dp_spec_choose(dp_spec *s, unsigned which);

#endif
