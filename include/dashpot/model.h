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
    DP_SPRING_ELASTOPLASTIC,     /* Jenkins: spring k in series with a slider of yield force F_y (docs/systems.md §3) */
    DP_SPRING_LAW_COUNT          /* not a law: the number of them (the law table's size) */
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
    DP_DAMPER_GENERALIZED_COULOMB, DP_DAMPER_GRAPH,
    DP_DAMPER_LAW_COUNT          /* not a law: the number of them (the law table's size) */
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

/* ---- the law table (src/core/laws/law_table.c) ------------------------------------------------------------
 *
 * One entry per law holds everything the code knows about it: its name and members (what the JSON parser
 * reads), how its graph is built, and every property a solver, a rule or a report decides by. Nothing else
 * classifies laws: code reads the entry (or the accessors below). Adding a law is its enum value, its entry
 * with its graph builder, and its OpenAPI entry. A property left out of an entry reads as 0, which is always
 * the general answer (the law's graph, the inclusion path, no event location, refused by the solvers with
 * closed forms): a law is never sent down a special path it did not ask for. */

typedef enum dp_member_bound { DP_MEMBER_ANY, DP_MEMBER_NONNEG, DP_MEMBER_POSITIVE } dp_member_bound;

/* A number-valued member of a law's JSON object, stored at byte `offset` of its struct (dp_spring, dp_damper,
 * dp_lcs_law). An optional member absent from the document takes `def`. */
typedef struct dp_law_member {
    const char *key;              /* NULL ends a list */
    size_t offset;
    dp_member_bound bound;
    int required;
    double def;
} dp_law_member;

#define DP_LAW_MAX_MEMBERS 4

/* What the parser needs of any law: its enum value, its name, its members, and, for a user graph, the name of
 * the abscissa of its "points" ([x, F], [v, F], [u, F]); NULL for a law built from its members. */
typedef struct dp_law_row {
    int law;
    const char *name;
    dp_law_member members[DP_LAW_MAX_MEMBERS + 1];
    const char *points;
} dp_law_row;

/* A field of a law's struct named by its offset; 0 (the offset of `law`) means none. */
typedef size_t dp_law_field;

typedef struct dp_spring_law_info {
    dp_law_row row;
    int (*build)(dp_spring *s);   /* its graph from its members (a user graph: checks it has points) */
    int linear;           /* F_s = k x: the solvers keep k as a number, no graph */
    int plastic;          /* a plastic offset as a state (dp_elastoplastic_return, the Jenkins element) */
    int locate;           /* one mass: stick-slip events located inside the step (else resolved to the step) */
    int locate_network;   /* networks: the same (a graph spring's pieces move with the step's length) */
    dp_law_field x_max;   /* a member bounding x from above (an inextensible rope's length) */
    dp_law_field elastic; /* a member holding its elastic stiffness (the fastest oscillation it allows) */
} dp_spring_law_info;

typedef struct dp_damper_law_info {
    dp_law_row row;
    int (*build)(dp_damper *d);   /* its graph from its members (a user graph: checks it has points) */
    dp_law_field viscous; /* c of a viscous part c (v - v_b) kept out of the graph (docs/mathematics.md §4) */
    dp_law_field kinetic; /* the kinetic threshold tau: the graph is the stick interval [-tau, tau] */
    dp_law_field static_threshold; /* a static threshold >= kinetic: breakaway from rest needs more */
    int closed_form;      /* the soft-threshold closed form of the stick-slip step applies (stick_slip.c) */
    int linear;           /* F_c = c (v - v_b): nothing set-valued */
    int locate;           /* stick-slip events located inside the step when it can stick */
    int analytic;         /* the analytic solver's closed form covers it (Coulomb's, or no damper) */
    int thesis;           /* algorithm 4.1 of Babováková 2012 (variant "thesis") covers it */
} dp_damper_law_info;

extern const dp_spring_law_info dp_spring_laws[DP_SPRING_LAW_COUNT];
extern const dp_damper_law_info dp_damper_laws[DP_DAMPER_LAW_COUNT];

/* A law's entry; NULL for a value that is no law. */
const dp_spring_law_info *dp_spring_law_info_of(dp_spring_law law);
const dp_damper_law_info *dp_damper_law_info_of(dp_damper_law law);

/* Reads of the entry. The k of a linear spring (0 for any other: its force is in its graph); whether the
 * spring is linear, whether it is plastic. */
double dp_spring_stiffness(const dp_spring *s);
int dp_spring_linear(const dp_spring *s);
int dp_spring_plastic(const dp_spring *s);
/* Whether the spring is a user graph of finite slope (no vertical piece, no vertical end ray): its force is
 * a Lipschitz function of the elongation, which a network theta-steps (a rope is not: its end ray is). */
int dp_spring_sloped_graph(const dp_spring *s);
/* Whether the spring is a user graph with a vertical piece that a network splits (network_run.c): its stops
 * (a vertical end ray: u <= hi, or u >= lo; *lo, *hi -/+INFINITY where its ray is not vertical), its jumps
 * inside them (a vertical piece of height J at y: a preload), and its sloped part, the graph with those
 * vertical pieces taken out (continuous, every piece of finite slope). On a network with events located the
 * sloped part is theta-stepped, each stop a rigid constraint as a rope's length is (network_contact.c), each
 * jump a step graph of its own. dp_spring_graph_jumps writes the jumps' y and J (arrays of the graph's
 * vertex count, or NULL to count them) and returns how many; dp_spring_bounded_part builds the sloped part
 * into part (empty on entry): DP_OK, DP_EINVAL (not such a spring) or DP_ENOMEM. */
int dp_spring_bounded_graph(const dp_spring *s, double *lo, double *hi);
size_t dp_spring_graph_jumps(const dp_spring *s, double *y, double *J);
int dp_spring_bounded_part(const dp_spring *s, dp_graph *part);
/* A rope or a split graph (dp_spring_bounded_graph): a spring with a vertical piece that a network with
 * events located steps as its parts. */
int dp_spring_is_split(const dp_spring *s);
/* The damper's viscous c (0 without a viscous part), its kinetic threshold (0 without one), its static
 * threshold (the kinetic one when it has none); whether it is linear, whether its stick-slip step has the
 * closed form. */
double dp_damper_viscous(const dp_damper *d);
int dp_damper_has_viscous(const dp_damper *d);
double dp_damper_kinetic(const dp_damper *d);
double dp_damper_static(const dp_damper *d);
int dp_damper_linear(const dp_damper *d);
int dp_damper_closed_form(const dp_damper *d);
/* The stick interval [-phi1, phi1] at the static threshold, into an empty g. DP_OK, DP_EINVAL, DP_ENOMEM. */
int dp_damper_static_graph(const dp_damper *d, dp_graph *g);
/* The key of the member of a row stored at `field` (NULL when none is); the number there in a law's struct. */
const char *dp_law_member_key(const dp_law_row *row, dp_law_field field);
double dp_law_field_value(const void *law_struct, dp_law_field field);

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
