/* include/dashpot/model.h - the oscillator m x'' + F_s + F_d = F(t) (Babováková 2012 (1)) as plain data.
 *
 * Every law keeps its named parameters (for reports and closed forms) and, once dp_model_prepare() has run,
 * its monotone graph (graph.h), which is what the solvers use. The damper force is F_d = F_c - gamma(v - v_b)
 * with (F_c, v - v_b) in the damper graph A (Pražák & Rajagopal 2016 (3)-(4), thesis (3.2)); v_b is the belt speed.
 */
#ifndef DASHPOT_MODEL_H
#define DASHPOT_MODEL_H

#include <stddef.h>
#include "dashpot/graph.h"

typedef enum dp_spring_law {
    DP_SPRING_LINEAR, DP_SPRING_ROPE, DP_SPRING_GRAPH,
    DP_SPRING_ELASTOPLASTIC      /* Jenkins: spring k in series with a slider of yield force F_y (docs/systems.md §3) */
} dp_spring_law;

typedef struct dp_spring {
    dp_spring_law law;
    double k;          /* linear, rope: stiffness */
    double length;     /* rope: the rope's length L; x <= L always (thesis Fig. 1) */
    double yield;      /* elastoplastic: the yield force F_y > 0; F = k (x - p), |F| <= F_y */
    double offset;     /* elastoplastic: the initial plastic offset p(0) */
    dp_graph graph;    /* (x, F_s); user points for DP_SPRING_GRAPH, built by dp_model_prepare otherwise;
                          elastoplastic: the graph at the initial offset, vertices (p -/+ F_y/k, -/+F_y) with
                          horizontal rays, which the solvers move with p (dp_elastoplastic_graph) */
} dp_spring;

typedef enum dp_damper_law {
    DP_DAMPER_NONE, DP_DAMPER_LINEAR, DP_DAMPER_COULOMB, DP_DAMPER_BINGHAM,
    DP_DAMPER_GENERALIZED_COULOMB, DP_DAMPER_GRAPH
} dp_damper_law;

typedef enum dp_relaxation_kind {
    DP_RELAX_NONE, DP_RELAX_RATIONAL, DP_RELAX_LINEAR, DP_RELAX_POWER
} dp_relaxation_kind;

/* gamma: rational a v/(b+|v|) (thesis ch. 4), linear L v, power N |v|^(1-1/N) sgn v (Pražák & Rajagopal 2016 (26)). */
typedef struct dp_relaxation {
    dp_relaxation_kind kind;
    double a, b;       /* rational */
    double L;          /* linear */
    double N;          /* power, N > 1 */
} dp_relaxation;

typedef struct dp_damper {
    dp_damper_law law;
    double c;          /* linear, bingham: viscosity */
    double phi0;       /* coulomb, generalized-coulomb: (dynamic) threshold */
    double phi1;       /* generalized-coulomb: static threshold, phi1 >= phi0 */
    double tau;        /* bingham: yield stress */
    double belt_velocity;
    dp_relaxation relaxation;
    dp_graph graph;    /* (v - v_b, F_c); for generalized-coulomb the monotone part with threshold phi0 */
} dp_damper;

typedef enum dp_forcing_kind {
    DP_FORCING_NONE, DP_FORCING_CONSTANT, DP_FORCING_HARMONIC, DP_FORCING_TABLE, DP_FORCING_SUM
} dp_forcing_kind;

#define DP_FORCING_MAX_TERMS 64
#define DP_FORCING_MAX_DEPTH 8

/* F(t): constant value; harmonic amplitude cos(omega t + phase); table: piecewise linear through (t_i, F_i),
 * constant beyond the ends; sum of terms. */
typedef struct dp_forcing {
    dp_forcing_kind kind;
    double value;
    double amplitude, omega, phase;
    size_t n;              /* table: points */
    double *t, *F;         /* table: strictly increasing t */
    size_t nterms;         /* sum */
    struct dp_forcing *terms;
} dp_forcing;

/* A unilateral contact on an element (docs/systems.md §4): its elongation must stay at least `distance`.
 * Rigid (compliance 0): Newton's impact law with restitution e in [0, 1] at the velocity level (Moreau-Jean);
 * compliant (compliance k > 0): the force k max(distance - u, 0) pushing the ends apart instead, the Yosida
 * approximation of the rigid contact (002 (2.7)), which rebounds elastically. */
typedef struct dp_contact {
    double distance;
    double restitution;
    double compliance;
} dp_contact;

typedef struct dp_model {
    double mass;
    dp_spring spring;
    dp_damper damper;
    dp_forcing forcing;
    int has_contact;      /* a contact: the document runs as the one-node network (docs/contact.md) */
    dp_contact contact;
} dp_model;

/* Builds the graphs of the named laws (idempotent for user graphs). DP_OK, DP_EINVAL or DP_ENOMEM. */
int dp_model_prepare(dp_model *m);
/* The same for one spring or one damper (an LCS component's law reuses them, docs/lcs.md). */
int dp_spring_prepare(dp_spring *s);
int dp_damper_prepare(dp_damper *d);

/* Frees everything the model owns; accepts a zeroed model. */
void dp_model_clear(dp_model *m);

/* Deep copy into an uninitialised dst; on failure dst is left cleared. */
int dp_model_copy(dp_model *dst, const dp_model *src);

/* F(t). */
double dp_forcing_eval(const dp_forcing *f, double t);
/* dF/dt (one-sided at table vertices: the slope of the segment to the right; 0 beyond the ends). */
double dp_forcing_rate(const dp_forcing *f, double t);
int dp_forcing_copy(dp_forcing *dst, const dp_forcing *src);
void dp_forcing_clear(dp_forcing *f);
/* True when F is constant in time (none, constant, or a sum of those); *value receives it. */
int dp_forcing_is_constant(const dp_forcing *f, double *value);

/* gamma(v) and its global Lipschitz constant (INFINITY for power). */
double dp_relaxation_eval(const dp_relaxation *r, double v);
double dp_relaxation_lipschitz(const dp_relaxation *r);
/* gamma'(v) (INFINITY for power at 0). */
double dp_relaxation_slope(const dp_relaxation *r, double v);
/* sup |gamma| (INFINITY when unbounded). */
double dp_relaxation_bound(const dp_relaxation *r);

const char *dp_spring_law_name(dp_spring_law law);

/* The Jenkins element's step (docs/systems.md §3), exact by return mapping: from the plastic offset *p and the
 * elongation u at the step's end, the force clamp(k (u - p), -F_y, F_y), with *p moved so that
 * F = k (u - p). Returns the force; *flow is +1/-1 while the slider slides (the trial force left the
 * interval), 0 when the step stayed elastic. */
double dp_elastoplastic_return(const dp_spring *s, double u, double *p, int *flow);

/* Rewrites the 2-vertex graph g (n == 2) of an elastoplastic spring in place for offset p, its forces
 * scaled by `weight` (the theta of the step's weighting: the step sees theta F(u+)). */
void dp_elastoplastic_graph(const dp_spring *s, double p, double weight, dp_graph *g);
const char *dp_damper_law_name(dp_damper_law law);

#endif
