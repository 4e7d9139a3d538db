/* src/core/run_internal.h - internal: the run object shared by the iterator plumbing (run.c) and the
 * solvers (stick_slip.c, thesis.c, analytic.c). Not part of the public API. */
#ifndef DASHPOT_CORE_RUN_INTERNAL_H
#define DASHPOT_CORE_RUN_INTERNAL_H

#include <gsl/gsl_odeiv2.h>

#include "dashpot/analytic.h"
#include "dashpot/run.h"

#define DP_RUN_PENDING 8

/* The coefficients of the closed-form step for one step length h (stick_slip.c): u = cv v + cx x + cf F + c0,
 * stick widths thr = h tau / W and thr_s = h tau_s / W. */
typedef struct dp_ss_coef { double W, cv, cx, cf, c0, thr, thr_s; } dp_ss_coef;

/* The constants of one stick-slip run, fixed at allocation (mathematics.md §4 notation). */
typedef struct dp_ss_law {
    double m, k, c;      /* mass, linear spring stiffness (0 for a graph spring), viscous part of the damper */
    double tau, tau_s;   /* kinetic and static stick thresholds (tau_s = phi1 for generalized Coulomb) */
    double vb, theta;
    int can_stick;       /* the damper graph has a vertical piece at zero relative velocity */
    int closed;          /* linear spring, threshold damper, no relaxation: the soft-threshold closed form */
    int locate;          /* split steps at phase changes (events "locate" and a damper that can stick) */
    int motion;          /* branch "motion": leave rest whenever a motion solves the step */
    const dp_graph *A, *S;
    size_t *kink_hint;   /* where the last step's kink searches ended (the run's kink_hint[2]) */
    const dp_relaxation *gamma;
    const dp_forcing *F;
    int F_const;         /* F is `none` or `constant`: F0 */
    double F0;
    double h;            /* the nominal step */
    dp_ss_coef nominal;  /* its coefficients */
} dp_ss_law;

/* A kind of solver, as GSL's stepper types (gsl_odeiv2_step_type): its name, how a run of it starts (state,
 * workspaces, the first records) and how it goes on (records into the caller's block until the block is full
 * or the run ends). Chosen once, when the run is allocated (run.c). */
typedef struct dp_run_type {
    const char *name;
    int (*init)(dp_run *r);
    int (*advance)(dp_run *r);
} dp_run_type;

struct dp_run {
    const dp_run_type *type;    /* the solver (run.c); a network of one mass steps as the stick-slip one */
    dp_spec spec;               /* deep copy: the run owns it */
    double h;                   /* nominal step */
    unsigned long long nsteps;  /* steps to t_end */
    double max_steps;           /* the front end's step limit; also bounds an adaptive integrator's steps */
    unsigned long long n;       /* steps done */
    long countdown;             /* steps until the next decimated sample */
    dp_sample cur;              /* state at t = cur.t */
    dp_summary sum;
    dp_ss_law law;
    size_t kink_hint[2];        /* stick-slip: the damper's and the spring graph's last kink (inclusion.c) */
    int finished, status;
    char error[256];
    char error_pointer[DP_POINTER_MAX]; /* where an allocation-time error is (a spec field), "" if anywhere */
    /* Output of the block being produced; overflow goes to `pending`, drained first on the next call. */
    dp_record *out;
    size_t out_n, out_cap;
    dp_record pending[DP_RUN_PENDING];
    size_t npending, ipending;
    /* analytic solver */
    double an_F0;
    dp_coulomb_arc an_arc;
    /* regularized solver (regularized.c): its GSL workspace */
    struct dp_regularized *reg;
    /* one mass on an elastoplastic spring (stick_slip.c): its plastic offset and force after the last
     * step, whether its slider slid in it (+1/-1, 0) */
    int ep, ep_flow;
    double ep_p, ep_F;
    /* the one-mass newmark run (newmark.c): its stepper and 1 x 1 band matrices */
    struct dp_nm *nm;
    double nm_M, nm_C, nm_K;
    /* network solver (network_run.c) */
    struct dp_net_run *net;
    /* linear complementarity system (lcs_run.c) */
    struct dp_lcs_run *lcs;
    /* right-hand friction solver (right_hand_run.c) */
    struct dp_rh_run *rh;
    /* the columns of a run whose samples are rows (dp_run_columns); NULL for one-mass samples */
    const dp_columns *cols;
    /* the stop hook (dp_run_set_stop) and the work count at which it is polled next */
    dp_stop_fn stop;
    void *stop_ctx;
    unsigned long long poll_at;
};

/* Queues one record for the caller. */
void dp_run_emit(dp_run *r, const dp_record *rec);
/* Emits a sample of the current state (the decimation said it is due). */
void dp_run_emit_sample(dp_run *r);

/* Whether the step just done produces a sample (every n-th step, and the last one). */
static inline int dp_run_sample_due(const dp_run *r)
{
    return (r->countdown <= 1 && r->spec.output.samples) || r->n >= r->nsteps;
}

/* Emits a sample of the current state if due; inline so that decimated steps cost one decrement. */
static inline void dp_run_emit_state(dp_run *r)
{
    if (--r->countdown > 0 && r->n < r->nsteps)
        return;
    dp_run_emit_sample(r);
}
/* Emits a phase-change event at time t, position x, velocity v (if events are wanted). */
void dp_run_emit_event(dp_run *r, dp_event_kind kind, double t, double x, double v);
/* Marks the run failed with a status and message; returns the status. */
int dp_run_fail(dp_run *r, int status, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* Work done so far by a time-stepping solver: steps plus the evaluations and iterations inside them. */
static inline unsigned long long dp_run_work(const dp_run *r)
{
    return r->n + r->sum.iterations;
}

/* Asks the stop hook (run.c); on stop fails the run with DP_ECANCEL and returns 1; on a yield returns 1
 * with r->status still DP_OK. */
int dp_run_poll_stop(dp_run *r, unsigned long long work);

/* The solvers' advance loops call this with their work count (monotone): the hook is asked once every
 * DP_RUN_POLL_WORK units, so the check costs one comparison per step. Returns 1 when the advance loop must
 * return r->status now: DP_ECANCEL (stopped) or DP_OK (a yield; call it only between steps). */
static inline int dp_run_stopped(dp_run *r, unsigned long long work)
{
    return r->stop != NULL && work >= r->poll_at && dp_run_poll_stop(r, work);
}

/* Solver entry points: prepare at allocation, then advance until the block is full or the run ends. */
int dp_stick_slip_init(dp_run *r);
void dp_ss_coef_init(const dp_ss_law *L, double h, dp_ss_coef *c);
int dp_stick_slip_advance(dp_run *r);
int dp_thesis_advance(dp_run *r);
int dp_analytic_init(dp_run *r);
int dp_analytic_advance(dp_run *r);
int dp_regularized_init(dp_run *r);
int dp_regularized_advance(dp_run *r);
void dp_regularized_free(struct dp_regularized *reg);
/* The GSL odeiv2 stepper of a dp_stepper (regularized.c). */
const gsl_odeiv2_step_type *dp_regularized_step_type(dp_stepper s);
int dp_newmark_init(dp_run *r);
int dp_newmark_advance(dp_run *r);
void dp_nm_free(struct dp_nm *w);
int dp_network_run_init(dp_run *r);
int dp_network_run_advance(dp_run *r);
void dp_network_run_free(struct dp_net_run *nr);
/* A network stepped by the one-mass solver (network_one_mass.c): its block rewritten as rows. */
int dp_network_run_is_one_mass(const dp_run *r);
int dp_network_one_mass_rows(dp_run *r, dp_record *buf, size_t n);
int dp_lcs_run_init(dp_run *r);
int dp_lcs_run_advance(dp_run *r);
void dp_lcs_run_free(struct dp_lcs_run *lr);
int dp_rh_run_init(dp_run *r);
int dp_rh_run_advance(dp_run *r);
int dp_rh_run_pending(const dp_run *r);
void dp_rh_run_free(struct dp_rh_run *rr);
/* Whether records wait in the network run's queue. */
int dp_network_run_pending(const dp_run *r);

/* The step length of step n (the last one ends exactly at t_end). */
static inline double dp_run_step_length(const dp_run *r)
{
    if (r->n + 1 < r->nsteps)
        return r->h;
    return r->spec.solver.t_end - (double)(r->nsteps - 1) * r->h;
}

/* Whether the block being produced has room and the run goes on. */
static inline int dp_run_room(const dp_run *r)
{
    return r->out_n < r->out_cap && r->npending == 0 && !r->finished;
}

#endif
