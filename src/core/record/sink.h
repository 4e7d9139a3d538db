/* src/core/record/sink.h - internal: the run object and the record sink every solver writes into (rows,
 * samples, events, errors, stop polling). It sits below the solvers and above the models, so that the solvers
 * call down into it and the run-type table (runs/) calls down into the solvers: no circle. Not public API. */
#ifndef DASHPOT_CORE_RECORD_SINK_H
#define DASHPOT_CORE_RECORD_SINK_H

#include "dashpot/run.h"

#define DP_RUN_PENDING 8

/* The coefficients of the closed-form step for one step length h (stick_slip.c): u = cv v + cx x + cf F + c0,
 * stick widths thr = h tau / W and thr_s = h tau_s / W. */
typedef struct dp_ss_coef { double W, cv, cx, cf, c0, thr, thr_s; } dp_ss_coef;

/* The constants of one stick-slip run, fixed at allocation (docs/mathematics.md §4 notation). */
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

/* A kind of run, as GSL's stepper types (gsl_odeiv2_step_type): everything the iterator and the meta line
 * need to know of it, so that adding one is its own file plus a row of the run-type table (runs/run_table.c).
 *   name     the solver as the meta line names it
 *   variant  its variant as the meta line names it (NULL: the meta line has none)
 *   events_mode  how it reports phase changes for a spec: "locate" (located inside the step), "step"
 *           (at the end of the step that made them), "none" (NULL function: the meta line has no such member)
 *   check    its cross-field rules and limits (dp_spec_check calls it; DP_OK, DP_EINVAL or DP_ELIMIT)
 *   init     allocates its state (r->state), prepares, queues the first records
 *   advance  writes records into the caller's block until the block is full or the run ends
 *   pending  whether records wait in its own queue (NULL: it has none)
 *   block    rewrites a finished block in place (NULL: nothing to do)
 *   free     releases r->state (accepts NULL) */
typedef struct dp_run_type {
    const char *name;
    const char *variant;
    const char *(*events_mode)(const dp_spec *s);
    int (*check)(const dp_spec *s, double max_steps, dp_errors *e);
    int (*init)(dp_run *r);
    int (*advance)(dp_run *r);
    int (*pending)(const dp_run *r);
    int (*block)(dp_run *r, dp_record *buf, size_t n);
    void (*free)(void *state);
} dp_run_type;

struct dp_run {
    const dp_run_type *type;    /* chosen once from the run-type table (runs/run_table.c) */
    dp_spec spec;               /* deep copy: the run owns it */
    double h;                   /* nominal step */
    unsigned long long nsteps;  /* steps to t_end */
    double max_steps;           /* the front end's step limit; also bounds an adaptive integrator's steps */
    unsigned long long n;       /* steps done */
    long countdown;             /* steps until the next decimated sample */
    dp_sample cur;              /* state at t = cur.t */
    dp_summary sum;
    dp_ss_law law;              /* the one-mass model's stepping constants (stick-slip, thesis, analytic) */
    size_t kink_hint[2];        /* stick-slip: the damper's and the spring graph's last kink (inclusion.c) */
    int finished, status;
    char error[256];
    char error_pointer[DP_POINTER_MAX]; /* where an allocation-time error is (a spec field), "" if anywhere */
    /* Output of the block being produced; overflow goes to `pending`, drained first on the next call. */
    dp_record *out;
    size_t out_n, out_cap;
    dp_record pending[DP_RUN_PENDING];
    size_t npending, ipending;
    /* one mass on an elastoplastic spring (stick_slip.c, newmark.c): its plastic offset and force after the
     * last step, whether its slider slid in it (+1/-1, 0) */
    int ep, ep_flow;
    double ep_p, ep_F;
    /* the run type's own state: init allocates it, free releases it */
    void *state;
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

/* Asks the stop hook (sink.c); on stop fails the run with DP_ECANCEL and returns 1; on a yield returns 1
 * with r->status still DP_OK. */
int dp_run_poll_stop(dp_run *r, unsigned long long work);

/* The solvers' advance loops call this with their work count (monotone): the hook is asked once every
 * DP_RUN_POLL_WORK units, so the check costs one comparison per step. Returns 1 when the advance loop must
 * return r->status now: DP_ECANCEL (stopped) or DP_OK (a yield; call it only between steps). */
static inline int dp_run_stopped(dp_run *r, unsigned long long work)
{
    return r->stop != NULL && work >= r->poll_at && dp_run_poll_stop(r, work);
}

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
