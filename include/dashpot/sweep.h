/* include/dashpot/sweep.h - sweeps: many runs of one spec over a grid of one or two parameters, each reduced
 * to a few numbers (features) and a Poincaré section, for response curves and bifurcation diagrams
 * (docs/sweep.md).
 *
 * What researchers in friction oscillators publish is a picture over a parameter: Den Hartog's (1931)
 * frequency-response curve of a forced Coulomb oscillator, the bifurcation diagram of a belt-driven
 * oscillator over the belt speed. The core part here knows no JSON: the grid of parameter values, the
 * features of one run computed from its records (dp_features), and one run driven to its features
 * (dp_sweep_one) with the run's output decimation chosen by the sweep (every step, every event), so a run's
 * features are computed from exactly the records a lone run with {"output": {"every": 1}} produces.
 * Substituting a grid point into the base document is the JSON layer's (sweep_json.h).
 */
#ifndef DASHPOT_SWEEP_H
#define DASHPOT_SWEEP_H

#include <stddef.h>
#include "dashpot/run.h"
#include "dashpot/spec.h"

/* Limits of one sweep (docs/sweep.md, "Limits"). */
#define DP_SWEEP_MAX_AXES 2
#define DP_SWEEP_MAX_RUNS 10000
#define DP_SWEEP_MAX_SECTION 1000          /* section points of one run */
#define DP_SWEEP_MAX_SECTION_TOTAL 1000000 /* runs x section points: bounds a one-document answer (~60 MB) */
/* The steps of all runs of a sweep together may be at most this many times the per-run limit (max_steps):
 * a sweep is one request, and a request is held to a bounded amount of work. */
#define DP_SWEEP_STEP_FACTOR 100.0

/* The features, in the order a run line writes them. */
typedef enum dp_feature {
    DP_FEATURE_X_MAX, DP_FEATURE_X_MIN, DP_FEATURE_V_MAX, DP_FEATURE_V_MIN, DP_FEATURE_AMPLITUDE,
    DP_FEATURE_PERIOD, DP_FEATURE_STICK_FRACTION, DP_FEATURE_COUNT
} dp_feature;

/* "x_max", ...; NULL out of range. */
const char *dp_feature_name(int f);
/* The feature named `name`, or -1. */
int dp_feature_from_name(const char *name);

typedef enum dp_section_kind { DP_SECTION_NONE, DP_SECTION_PERIOD, DP_SECTION_EVENT } dp_section_kind;

/* What a sweep records of each run. */
typedef struct dp_sweep_plan {
    double after;          /* transient discarded: features and section over t >= after (>= 0) */
    unsigned features;     /* bit (1u << f) per dp_feature wanted */
    dp_section_kind section;
    double section_period; /* DP_SECTION_PERIOD: points at t = after + k period, k = 0, 1, ... */
    dp_event_kind section_event; /* DP_SECTION_EVENT: a point at each event of this kind */
    size_t section_count;  /* at most this many points (<= DP_SWEEP_MAX_SECTION) */
    size_t node;           /* networks: the node whose x, v the features follow */
    size_t element;        /* networks: the element whose phase stick_fraction counts, whose events a section takes */
} dp_sweep_plan;

/* A plan with the defaults: after 0, every feature, no section, node 0, element 0. */
void dp_sweep_plan_init(dp_sweep_plan *p);

typedef struct dp_section_point { double t, x, v; } dp_section_point;

/* Reasons the period is null (static strings), NULL while it is not. */
typedef struct dp_feature_values {
    double value[DP_FEATURE_COUNT];
    int known[DP_FEATURE_COUNT];       /* 0: null (no sample after `after`, no period found) */
    const char *why[DP_FEATURE_COUNT]; /* why it is null */
} dp_feature_values;

/* A point of the trajectory the features walk through: a sample, or an event of the mass. */
typedef struct dp_traj_point {
    double t, x, v;
    int phase;         /* dp_phase of the sample; DP_PHASE_NONE for events */
    int event;         /* an event's point (never the middle of a v-extremum fit) */
} dp_traj_point;

#define DP_FEATURES_MAXIMA 512 /* the latest maxima kept to find the period */

/* The features of one run, accumulated record by record (dp_features_add) in one pass. */
typedef struct dp_features {
    dp_sweep_plan plan;
    dp_feature_values out;       /* final after dp_features_finish */
    dp_section_point *section;   /* plan.section_count places */
    size_t nsection;
    /* the walk */
    dp_traj_point p1, p2;        /* the last two points (p1 the latest) */
    int npts;                    /* points seen (capped at 2) */
    double xmax, xmin, vmax, vmin;
    int any;                     /* a point at t >= after was seen */
    double t_first, t_last;      /* of the points at t >= after */
    double h;                    /* the longest gap between two points at t >= after: the run's step */
    int phase;                   /* the stick bookkeeping: the phase since `mark` */
    double mark, stick;
    double max_t[DP_FEATURES_MAXIMA], max_x[DP_FEATURES_MAXIMA]; /* ring of the latest maxima of x */
    size_t nmax;                 /* maxima seen (the ring holds the last DP_FEATURES_MAXIMA) */
    size_t k_next;               /* DP_SECTION_PERIOD: the index of the next section time */
    /* networks: where the node's x, v and the element's phase are in a row (-1: not there) */
    long col_x, col_v, col_phase;
} dp_features;

/* Prepares f for one run under plan (copied): DP_OK or DP_ENOMEM. `cols` are the run's columns (NULL for
 * the one-mass model); the node and element of the plan must be among them (dp_sweep_one checks). */
int dp_features_init(dp_features *f, const dp_sweep_plan *plan, const dp_columns *cols);
/* One record of the run, in the run's order. */
void dp_features_add(dp_features *f, const dp_record *r);
/* The features once the run is done (f->out). */
void dp_features_finish(dp_features *f);
/* Frees the section; accepts a zeroed f. */
void dp_features_clear(dp_features *f);

/* The Hermite cubic through (t0, x0, v0) and (t1, x1, v1) at t in [t0, t1]: its value and slope. */
void dp_hermite_eval(const dp_traj_point *a, const dp_traj_point *b, double t, double *x, double *v);
/* Where the Hermite cubic's slope has its zero between a and b (a->v and b->v of opposite signs, t1 > t0). */
double dp_hermite_turn(const dp_traj_point *a, const dp_traj_point *b);

/* ---- one run driven to its features ---- */

typedef struct dp_sweep_one dp_sweep_one;

/* A run of spec (checked with max_steps, as dp_run_alloc) whose output is set by the sweep: every step a
 * sample, every event, every node and element written. NULL with *status and errs on failure (the plan's
 * node or element outside the network: DP_EINVAL at pointer `plan_pointer`/node or /element). */
dp_sweep_one *dp_sweep_one_alloc(const dp_spec *spec, const dp_sweep_plan *plan, double max_steps,
                                 const char *plan_pointer, dp_errors *errs, int *status);
/* The stop hook of the run (dp_run_set_stop; a yield returns DP_MORE from dp_sweep_one_next). */
void dp_sweep_one_set_stop(dp_sweep_one *o, dp_stop_fn stop, void *ctx);
/* Advances the run by one block of records: DP_MORE, DP_DONE (the features are final), or the run's error. */
int dp_sweep_one_next(dp_sweep_one *o);
const dp_features *dp_sweep_one_features(const dp_sweep_one *o);
const dp_summary *dp_sweep_one_summary(const dp_sweep_one *o);
const char *dp_sweep_one_error(const dp_sweep_one *o);
void dp_sweep_one_free(dp_sweep_one *o);

/* ---- the grid ---- */

typedef struct dp_sweep_axis {
    char pointer[DP_POINTER_MAX]; /* into the base document (RFC 6901) */
    double *values;
    size_t n;
} dp_sweep_axis;

typedef struct dp_sweep_grid {
    size_t naxes;
    dp_sweep_axis axis[DP_SWEEP_MAX_AXES];
} dp_sweep_grid;

/* count values from `from` to `to` (both included, count >= 1; count 1 is `from`), evenly spaced or, with
 * `log`, evenly spaced in log (from, to > 0). The last value is `to` itself. DP_OK or DP_ENOMEM. */
int dp_sweep_axis_fill(dp_sweep_axis *a, double from, double to, size_t count, int log);
/* Runs of the grid: the product of the axes' sizes. */
size_t dp_sweep_grid_runs(const dp_sweep_grid *g);
/* The values of run `index`, row-major: index = i0 * n1 + i1 (the last axis varies fastest). */
void dp_sweep_grid_values(const dp_sweep_grid *g, size_t index, double *values);
void dp_sweep_grid_clear(dp_sweep_grid *g);

/* Whether shard i of n (0 <= i < n) runs `index`: runs are dealt round-robin, index mod n == i, so every
 * part gets runs from the whole grid (cheap and costly corners alike). */
static inline int dp_sweep_shard_owns(size_t index, size_t i, size_t n)
{
    return n <= 1 || index % n == i;
}

#endif
