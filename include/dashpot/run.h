/* include/dashpot/run.h - a solver run as a pull iterator (docs/architecture.md, "Solvers are iterators").
 *
 *     dp_run *run = dp_run_alloc(&spec, &errs, &status);
 *     while ((s = dp_run_next(run, buf, cap, &n)) == DP_MORE) consume(buf, n);
 *     if (s == DP_DONE) report(dp_run_summary(run));
 *     dp_run_free(run);
 *
 * The run owns a deep copy of what it needs from the spec, so the spec may be freed after dp_run_alloc.
 * Memory is fixed at allocation: a run of 10^9 steps uses what a run of 10 steps uses.
 */
#ifndef DASHPOT_RUN_H
#define DASHPOT_RUN_H

#include <stddef.h>
#include "dashpot/spec.h"

typedef enum dp_phase { DP_PHASE_NONE = 0, DP_PHASE_STICK = 1, DP_PHASE_SLIP = 2 } dp_phase;

typedef struct dp_sample {
    double t, x, v;
    double Fs;       /* spring force */
    double Fd;       /* damper force F_c - gamma */
    double Fc;       /* the damper graph's force (Coulomb part with its viscous part) */
    dp_phase phase;  /* DP_PHASE_NONE for dampers that cannot stick */
    int plastic;     /* the spring is elastoplastic: p is its plastic offset (written as "p") */
    double p;
} dp_sample;

typedef enum dp_event_kind {
    DP_EVENT_STICK = 1, DP_EVENT_SLIP = 2, DP_EVENT_YIELD = 3, DP_EVENT_UNLOAD = 4, DP_EVENT_IMPACT = 5,
    DP_EVENT_LIFTOFF = 6, DP_EVENT_ON = 7, DP_EVENT_OFF = 8, DP_EVENT_TOUCH = 9, DP_EVENT_SEPARATE = 10
} dp_event_kind;

/* A phase change: DP_EVENT_STICK is slip -> stick, DP_EVENT_SLIP is stick -> slip; an elastoplastic
 * spring's DP_EVENT_YIELD (its slider starts sliding) and DP_EVENT_UNLOAD (it stops: elastic again); a
 * contact's DP_EVENT_IMPACT (v the rate before, v_after after, impulse >= 0 pushing the ends apart; a rope's,
 * with events located, its going taut or passing an impulse on: impulse >= 0 its tension's, pulling the ends
 * together, v and v_after the element's rate u'); a compliant contact's DP_EVENT_TOUCH (its gap closes) and
 * DP_EVENT_SEPARATE (it opens); Painlevé's
 * rod leaving the floor, DP_EVENT_LIFTOFF (x, v: the end's height and upward rate, docs/right-hand.md); a linear
 * complementarity system's mode change (lcs.h), DP_EVENT_ON along the component's graph, DP_EVENT_OFF back
 * (element: the component, mode: the mode entered, x, v: its u and w then). */
typedef struct dp_event {
    dp_event_kind kind;
    double t, x, v;
    size_t element;  /* networks: the element that changed phase (x, v: its elongation and rate) */
    double v_after, impulse;   /* DP_EVENT_IMPACT only */
    size_t mode;     /* DP_EVENT_ON, DP_EVENT_OFF only */
} dp_event;

/* One named group of a row's numbers: written as an array "name": [...] in JSON, as columns name<index>
 * in CSV. A phase group holds dp_phase codes, written "stick", "slip" or null. */
typedef struct dp_column_group {
    const char *name;
    size_t n;
    const size_t *index;   /* each entry's index in the model (a node, an element), for CSV headers */
    int phase;
} dp_column_group;

#define DP_COLUMNS_MAX_GROUPS 8

/* What the rows of a run hold (dp_run_columns), declared once at the run's start so that the encoders
 * build their keys from it: groups in order, width numbers per row. Networks also keep which nodes and
 * elements the groups are over. */
typedef struct dp_columns {
    size_t ngroups;
    dp_column_group group[DP_COLUMNS_MAX_GROUPS];
    size_t width;
    size_t nodes, elements;
    const size_t *node, *element;
} dp_columns;

/* A sample as a time and a run-owned row of `width` numbers (the groups in order), valid until the run's
 * next dp_run_next. */
typedef struct dp_row {
    double t;
    const double *val;
} dp_row;

/* A quake of a network run with output.quakes (docs/quakes.md): a connected slip episode of friction elements,
 * handed out when it ends (or at t_end, open). t: when it started; size: the distinct elements that slipped
 * in it; hypocentre: the element that started it; moment: the sum over them of the integral of |u' - v_b|
 * (the potency); peak_rate: the largest |u' - v_b| seen at a step's end; first, last: the lowest and
 * highest element index in it. */
typedef struct dp_quake {
    double t, duration, moment, peak_rate;
    size_t size, hypocentre, first, last;
    int open;        /* still slipping at t_end */
} dp_quake;

typedef enum dp_record_type {
    DP_RECORD_SAMPLE = 1, DP_RECORD_EVENT = 2, DP_RECORD_ROW = 3, DP_RECORD_QUAKE = 4
} dp_record_type;

typedef struct dp_record {
    dp_record_type type;
    union { dp_sample sample; dp_event event; dp_row row; dp_quake quake; } u;
} dp_record;

typedef struct dp_summary {
    dp_sample final;          /* state at t_end */
    unsigned long long steps; /* time steps taken (stick-slip), arcs (analytic), accepted steps (regularized) */
    unsigned long long samples, events;
    double stick_time;        /* total time spent sticking */
    unsigned long long iterations; /* thesis: fixed-point iterations; exact: bracketing evaluations;
                                    * regularized: Jacobian evaluations */
    unsigned long long rejected;   /* regularized: steps the error control rejected (0 elsewhere) */
    unsigned long long fevals;     /* regularized: right-hand side evaluations (0 elsewhere) */
    unsigned long long impacts;    /* contacts' impacts (among `events`) */
    dp_row final_row;              /* runs with columns: the state at t_end (valid while the run lives) */
} dp_summary;

typedef struct dp_run dp_run;

/* Validates (dp_spec_check with `max_steps`, <= 0 for DP_SPEC_MAX_STEPS) and prepares a run.
 * On failure returns NULL, sets *status (DP_EINVAL, DP_ELIMIT, DP_ENOMEM) and appends to errs. */
dp_run *dp_run_alloc(const dp_spec *spec, double max_steps, dp_errors *errs, int *status);

/* What runs a checked spec, as its meta line says it: the solver ("stick-slip", "regularized", ...), its
 * variant (NULL where the solver has none), and how its phase changes are reported ("locate": located
 * inside the step; "step": at the end of the step that made them; "none"; NULL where it reports none).
 * Never NULL for the solver. */
const char *dp_spec_solver(const dp_spec *s);
const char *dp_spec_variant(const dp_spec *s);
const char *dp_spec_events_mode(const dp_spec *s);

/* Produces up to `cap` records (cap >= 1) into buf, *n of them. Returns DP_MORE while records remain,
 * DP_DONE once the run is complete (possibly with *n > 0 final records), or an error (DP_ENONFINITE when
 * the solution diverged, DP_ESOLVE, DP_ECANCEL when the stop hook said so) after which the run is finished; no record with a non-finite number
 * is ever produced. */
int dp_run_next(dp_run *run, dp_record *buf, size_t cap, size_t *n);

/* Running totals; final once dp_run_next returned DP_DONE. */
const dp_summary *dp_run_summary(const dp_run *run);

/* A run's columns when its samples are rows (networks); NULL for the one-mass model (dp_sample records). */
const dp_columns *dp_run_columns(const dp_run *run);

/* Fraction of simulated time done, in [0, 1]. */
double dp_run_progress(const dp_run *run);

/* A description of the last error of dp_run_next, "" if none. */
const char *dp_run_error(const dp_run *run);

/* A stop hook: returns > 0 when the run must end now (a deadline passed, the client left, shutdown), 0 to
 * go on, < 0 to yield: dp_run_next then returns DP_MORE at once with the records made so far (maybe none),
 * and the run goes on at the next call (a server's thread serves its other connections meanwhile).
 * The solvers poll it every DP_RUN_POLL_WORK units of work (a unit is one time step, one evaluation of a
 * step's implicit equation, one fixed-point iteration, one right-hand side evaluation or one sample), never
 * between records only, so a run stops within a bounded amount of work whatever its output decimation
 * (docs/operations.md, "Stopping a run"). Once it said stop, dp_run_next returns DP_ECANCEL and
 * dp_run_error says when the run stopped. A yield inside a step (a thesis step of up to 10^6 iterations)
 * is honoured after that step. The hook runs on the thread calling dp_run_next; NULL removes it. */
typedef int (*dp_stop_fn)(void *ctx);
#define DP_RUN_POLL_WORK 4096
void dp_run_set_stop(dp_run *run, dp_stop_fn stop, void *ctx);

/* Accepts NULL. */
void dp_run_free(dp_run *run);

#endif
