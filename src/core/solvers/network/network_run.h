/* src/core/solvers/network/network_run.h - internal: a network run's state, shared by the files of the
 * network run (the run, its exact step, located events, contacts, output, the regularized scheme and the
 * one-mass path), which write the same rows and events. */
#ifndef DASHPOT_CORE_NETWORK_RUN_H
#define DASHPOT_CORE_NETWORK_RUN_H

#include <float.h>
#include <math.h>

#include "network/network_step.h"
#include "record/row_queue.h"
#include "record/sink.h"
#include "rules/rules.h"
#include "solvers/run_types.h"
#include "solvers/stick_slip_step.h"

struct dp_network_regularized;

/* A unilateral constraint of the step (network_contact.c): an element's contact, or a rope's u <= L with events
 * located, which is the rigid contact between the rope's ends swapped at distance -L with restitution 0 (its gap
 * L - u). Its gap is x_b - x_a - law.distance in its own order of the ends. */
typedef struct network_bound {
    long a, b;
    dp_contact law;
    int rope;               /* a spring's stop (a rope's, a bounded graph's): its force is the spring's, written
                               in Fs; its events in the element's terms */
    int swapped;            /* its ends are the element's swapped (an upper stop u <= hi) */
} network_bound;

struct dp_network_run {
    size_t n, nel, p, nact;
    int relaxed;                /* some element has a relaxation gamma */
    double theta;
    const dp_network *net;
    double *M, *K, *C;          /* band storage n x (p+1) */
    dp_network_step_element *act;           /* the elements of the convex problem */
    const dp_relaxation **gamma; /* per active element, NULL without relaxation */
    dp_graph *static_A;         /* per active element: generalized Coulomb's static graph (phi1), else empty */
    unsigned char *held, *broke; /* per active element in a step: on its static graph; broke away this step */
    int has_static;
    int locate;                 /* events located inside the step (located_step) */
    int solved;                 /* the workspace holds the assignment of the last step */
    void *pattern;              /* the assignment at a sub-step's start */
    double *margin;             /* per active element, of the assignment held over a shorter step */
    double *roots;              /* per active element: its margin just after a sub-step's start */
    unsigned char *fails;       /* per active element: its held assignment fails at the located instant */
    double *scale;              /* per active element: the size of its margin over a step */
    unsigned char *fixed, *cand, *fails_at;   /* per active element: location's scratch */
    double *v1_keep;            /* n: a step's solution kept while location looks further */
    double *Mv, *Cv, *Mv_at;    /* n each, located runs: M v and C v for the velocity Mv_at, which every held
                                 * solve from one sub-step's start shares (Mv == NULL: not kept) */
    int Mv_valid;
    double *vb;                 /* nel: each element's belt velocity (0 without a damper), beside the element
                                 * structs whose damper it would otherwise read a cache line further on */
    double kmax, cmax, vbmax;   /* the largest |k|, |c| and |v_b| over the elements (network_run_forces_bounded) */
    int belt_viscous;
    /* located runs on a chain (half-bandwidth one): couple[i], nodes i and i+1 coupled in M, C or K; the
     * blocks of a held solve over candidates (pairs), their rows of W and of the right side (network_events.c) */
    unsigned char *couple;
    size_t *blk, blk_cap;
    double *blk_W, *blk_rhs;
    double *end_margin;         /* nact: the failing elements' margins at the held step's end (earliest_event) */           /* some element's viscous damper rides a moving belt (a term of each right side) */
    dp_network_step_forces *force_keep;   /* per active element, likewise */
    struct dp_network_regularized *reg;     /* the regularized scheme's integrator (network_regularized.c), or NULL */
    int one_mass;               /* stepped by the one-mass solver (network_one_mass.c) */
    long *act_of;               /* element -> its index in act, or -1 */
    size_t *act_el;             /* index in act -> element */
    double *k, *c;              /* per element: linear stiffness and viscosity */
    dp_network_step *ws;
    double h_W;                 /* the step W was built for */
    double *x, *v, *v1, *rhs, *tmp, *u;
    dp_network_step_forces *force;
    double *Fs, *Fd;            /* per element, at the current state */
    unsigned char *phase, *phase_prev, *can_stick;
    dp_columns cols;
    size_t *all_nodes, *all_elements;
    size_t *node_pos;           /* user node -> the run's (network_order.c), NULL when not renumbered */
    size_t row_len;             /* = cols.width */
    dp_row_slots slots;         /* the block's rows */
    double *final_row;          /* the summary's row */
    dp_row_queue queue;         /* records that did not fit the caller's block */
    double *pending_row;        /* a row made while records wait, before the queue copies it */
    /* elastoplastic (Jenkins) springs, per element (network_run.c): the plastic offset, the force, whether
     * the slider slid in the last step (+1/-1, 0) and in the one before, the step graph to move with p */
    int has_ep;
    double *ep_p, *ep_F;
    signed char *ep_flow, *ep_flow_prev;
    dp_graph **ep_graph;
    size_t *ep_cols, nep_cols;  /* the written elements with such a spring: the "p" column group */
    /* spring graphs of finite slope (network_smooth.c), per active element: such a spring, its force at the
     * state (stepped by the theta-rule when has_smooth: theta < 1), its vertex failing at the located instant;
     * per contact: a compliant one pressed (its gap closed) */
    int has_smooth;
    unsigned char *sm_on, *sm_kink, *sm_pressed;
    double *sm_F;
    /* the newmark solver (network_run.c, newmark_step.h): its stepper, the elastoplastic elements' ends,
     * stiffness, element index, force and tangent state in its order, the load vector */
    struct dp_nm *nm;
    long *nm_ea, *nm_eb;
    double *nm_ek, *nm_F, *nm_P;
    signed char *nm_flow;
    size_t *nm_el, nm_nep;
    /* unilateral contacts (network_contact.c): act[nact_el..nact) are the contacts, in element order, and with
     * events located the ropes' constraints u <= L (ropes_bound; nrope of the nc) */
    size_t nact_el, nc, nrope;
    int ropes_bound;            /* springs with a vertical piece are stepped as their parts
                                   (network_run_spring_split): a rope's linear spring k and u <= L, a graph's
                                   sloped part (stop_S), stops and jumps */
    dp_graph *stop_S;           /* per element: a split graph's sloped part, else empty (NULL: none) */
    unsigned char *jump;        /* per active element: a split graph's jump (its own entry), NULL: none */
    dp_graph *jump_S;           /* the jumps' step graphs (njump): 0 below y, [0, J] at it, J above */
    size_t njump;
    network_bound *ct;          /* per contact: its ends, its law, whether a rope's */
    size_t *ct_el;              /* per contact: its element */
    dp_graph cone;              /* the rigid contacts' cone, shared */
    dp_graph *ct_soft;          /* per contact: a compliant one's spring graph, else empty */
    unsigned char *ct_on;       /* per contact: armed for the current (sub-)step */
    unsigned char *ct_touch;    /* per contact: scratch of an instant */
    double *ct_last, *ct_pre;   /* per contact: time of its last located impact; its rate when armed (MJ) */
    double *ct_before;          /* per contact: time of the located impact before its last */
    unsigned char *ct_kicked;   /* per contact: another contact's impulse changed its rate since its last impact */
    unsigned char *ct_shadow;   /* per contact: a rigid one behind another between the same ends in the same
                                   order with a larger distance (or an equal one and a lower index) */
    double *Fn;                 /* per element: the contact's force */
    dp_network_step *iws;             /* the impact problem: W = M, the contacts' cones */
    dp_network_step_element *imp;
    dp_network_step_forces *iforce;
    double *iv;                 /* 2n: its right side and solution */
    unsigned long long impacts_step;
    struct dp_quakes *quakes;   /* output.quakes: the slip-event catalogue (network_quakes.c), else NULL */
    /* the stop hook inside a step (network_stepping.c): the work done (units of network_step.h's poll, a step
     * between them counted as nodes + elements), and a yield asked for inside a step, honoured after it */
    unsigned long long work;
    int yield;
    /* the grounded chain's workspace (network_grounded_chain.c), NULL on every other run type */
    struct network_chain *chain;
};

/* Queues a record for the caller (its block, else the run's queue, which grows rather than drop). */
void network_run_put(dp_run *r, const dp_record *rec);
/* A row of the current state at r->cur.t, if samples are wanted; restarts the decimation. */
void network_run_emit_row(dp_run *r);
/* A compliant contact's touch and separation (network_output.c): which are pressed at the run's start (h its
 * step), and the events at t of those that changed since (called by network_run_step_events). */
void network_run_touch_start(struct dp_network_run *nr, double h);
void network_run_touch_events(dp_run *r, double t);
/* Events at time t for the elements whose phase differs from `before`. */
void network_run_step_events(dp_run *r, const unsigned char *before, double t);
/* Time spent sticking over a (sub-)step of length h by the elements whose phase is `ph`. */
void network_run_stick_time(dp_run *r, const unsigned char *ph, double h);
/* Moves queued records into the caller's block; row slots for this block. */
void network_run_flush(dp_run *r);
int network_run_reserve_rows(dp_run *r);
/* The summary's final row from the current state. */
void network_run_finalize_summary(dp_run *r);
/* Every position, velocity and force finite (and not absurdly large). */
int network_run_state_finite(const struct dp_network_run *nr);
/* After a step was solved: the step count and t move on, a state that is not `finite` fails the run ("the
 * solution diverged"), the last step closes the summary, and the row is written when due. DP_OK or the
 * run's failure status. */
int network_run_step_taken(dp_run *r, int finite);
/* x_b - x_a with the ground at 0. */
static inline double network_run_rel(long a, long b, const double *x)
{
    return (b >= 0 ? x[b] : 0) - (a >= 0 ? x[a] : 0);
}

/* Constraint b's gap x_b - x_a - d in its own order of the ends, and how close to zero a gap counts as
 * touching: the rounding of the positions and a billionth of what the gap moves in a step h. */
static inline double network_run_bound_gap(const network_bound *b, const double *x)
{
    return network_run_rel(b->a, b->b, x) - b->law.distance;
}

static inline double network_run_touch_tol(const network_bound *b, const double *x, const double *v, double h)
{
    double xs = fabs(b->law.distance) + (b->a >= 0 ? fabs(x[b->a]) : 0) + (b->b >= 0 ? fabs(x[b->b]) : 0);
    return 1e-9 * h * fabs(network_run_rel(b->a, b->b, v)) + 64 * DBL_EPSILON * xs;
}

/* The stop hook polled inside a step: set on the step's workspaces (network_run_setup), it counts their work
 * and asks the run's hook every DP_RUN_POLL_WORK units; 1 when the run was stopped (r->status DP_ECANCEL).
 * A yield asked for inside a step sets nr->yield and is honoured between steps. */
int network_run_step_poll(void *run, unsigned long long units);
static inline int network_run_cancelled(const dp_run *r)
{
    return r->status == DP_ECANCEL;
}

/* network_run_step_poll for a lean step (network_contact_lean.c, network_grounded_chain.c), its common case
 * inline: the work counted, the run's hook asked only when due. */
static inline int network_run_poll_lean(dp_run *r, struct dp_network_run *nr, unsigned long long units)
{
    nr->work += units;
    if (network_run_cancelled(r))
        return 1;
    if (r->stop == NULL || nr->work < r->poll_at)
        return 0;
    return network_run_step_poll(r, 0);
}

/* Before each step of an advance (the general and the lean contact run types): room in the caller's block,
 * the run's queue and the row slots, and the run not finished; then the step's work counted (at least a unit
 * per node and element, its solves' band entries polled inside it: 10^4 blocks poll every step or so, one
 * mass every 4096 steps), a yield asked for inside the last step honoured, the stop hook asked. 1: take the
 * step; 0: the advance returns *status. */
static inline int network_run_step_due(dp_run *r, int *status)
{
    struct dp_network_run *nr = r->state;
    *status = DP_OK;
    if (!(r->out_n < r->out_cap && !dp_row_queue_waiting(&nr->queue) && nr->slots.used < nr->slots.cap &&
          !r->finished))
        return 0;
    nr->work += nr->n + nr->nel;
    if (nr->yield) {
        nr->yield = 0;
        return 0;
    }
    if (dp_run_stopped(r, nr->work)) {
        *status = r->status;
        return 0;
    }
    return 1;
}

/* Whether every element's linear forces k u and c (z - v_b) are finite by a bound from the state's largest
 * |x| and |v| (xm, vm; both below 1e300): |k u| <= k_max 2 xm, |c (z - v_b)| <= c_max (2 vm + max|v_b|), each
 * below 1e300, with room for the rounding of u and z. A step that writes no row shows its forces finite by it
 * instead of forming them. */
static inline int network_run_forces_bounded(const struct dp_network_run *nr, double xm, double vm)
{
    return nr->kmax * (2 * xm) < 1e300 && nr->cmax * (2 * vm + nr->vbmax) < 1e300;
}

/* Whether the step being taken writes a row or the final state (network_run_step_taken): only those read
 * the elements' forces. */
static inline int network_run_writes_row(const dp_run *r)
{
    return (r->countdown <= 1 && r->spec.output.samples) || r->n + 1 >= r->nsteps;
}

/* The stepping pieces located events are made of (network_stepping.c): the right side of a step of length h
 * from time t, its exact solution into v1 and the forces (state unmoved), moving the state by it, and the
 * elements' forces and phases (`stepped`: from the last solution; else the initial state). */
void network_run_step_rhs(struct dp_network_run *nr, double t, double h);
/* Rows lo-1 .. hi of W (two entries each; zeros for row -1) and lo .. hi of the right side of a step of length h
 * from t, each entry as network_run_build_W and network_run_step_rhs form it, at half-bandwidth one on a
 * network without a viscous damper on a moving belt nor theta-weighted springs. */
void network_run_block_rows(const struct dp_network_run *nr, double t, double h, size_t lo, size_t hi, double *Wl,
                            double *rl);
int network_run_net_step_keep(dp_run *r, double t, double h);
void network_run_take_velocity(struct dp_network_run *nr, double h);
void network_run_element_forces(struct dp_network_run *nr, int stepped);
/* After a step that writes no row: the phases network_run_element_forces would set, without the forces; 1
 * when a bound shows the forces and the state finite, 0 when they must be formed and checked (then nothing
 * is set; also for networks whose forces are more than k u + c (z - v_b) + the step's part). */
int network_run_element_phases(struct dp_network_run *nr);
/* W for step length h into the workspace; one whole step from t (the state moved, the forces set). */
void network_run_build_W(struct dp_network_run *nr, double h);
int network_run_net_step(dp_run *r, double t, double h);
/* The elastoplastic springs' offsets and forces after a step (network_stepping.c). */
void network_run_ep_update(struct dp_network_run *nr);
/* One step of length h from t split at its phase changes (network_events.c). */
int network_run_located_step(dp_run *r, double t, double h);

/* Contacts (network_contact.c): set-up after the elements' laws, Moreau-Jean arming and its impact events,
 * located impacts at an instant, the unarmed contacts' gaps as held margins, their forces. */
int network_run_contacts_setup(struct dp_network_run *nr);
void network_run_contacts_free(struct dp_network_run *nr);
void network_run_contacts_arm_mj(struct dp_network_run *nr, double h);
void network_run_contacts_mj_events(dp_run *r, double t, double h);
int network_run_contacts_instant(dp_run *r, double t, double h);
void network_run_contacts_margins(struct dp_network_run *nr, double s);
int network_run_contacts_penetrate(struct dp_network_run *nr, double h);
size_t network_run_contacts_arm_closing(struct dp_network_run *nr, double h);
int network_run_contacts_chattering(const struct dp_network_run *nr);
void network_run_contacts_forces(struct dp_network_run *nr, int stepped);
void network_run_contacts_after_probe(struct dp_network_run *nr);
/* Whether element e's spring is stepped as its parts (events located, the stick-slip solver): a rope as a
 * linear spring k plus the rigid constraint u <= L, a graph with a vertical piece as its sloped part, rigid
 * constraints at its stops and an entry per jump (network_contact.c, network_run.c); otherwise it is its
 * graph, stepped by backward Euler. */
int network_run_spring_split(const struct dp_network_run *nr, const dp_element *e);
/* How many constraints element e's spring adds with events located: a rope's u <= L, a bounded graph's
 * stops (dp_spring_bounded_graph), 0 otherwise. */
size_t network_run_spring_stops(const struct dp_network_run *nr, const dp_element *e);
/* A compliant contact's force at elongation u, -k max(d - u, 0) (0 for a rigid one: k = 0). */
double network_run_compliant_force(const dp_contact *c, double u);
/* An impact of element i's contact at t: relative velocity before and after, the impulse (>= 0). */
void network_run_impact_event(dp_run *r, double t, size_t i, double before, double after, double impulse);

/* Spring graphs of finite slope (network_smooth.c): flagging the active elements
 * that are (theta-stepped below theta = 1); their forces at the state after it moved (the step's right side
 * takes their known part, network_stepping.c); the reported force (theirs at the state, else the step's `stepped`); which of the
 * failing elements (nr->fails) fail at a vertex of their spring at the located instant `at` (the held state
 * there), and whether k is one of them. */
int network_run_smooth_setup(struct dp_network_run *nr);
void network_run_smooth_free(struct dp_network_run *nr);
void network_run_smooth_update(struct dp_network_run *nr);
double network_run_smooth_force(const struct dp_network_run *nr, size_t k, double stepped);
/* 1 + the element whose sloped spring's force at the state is not finite, else 0. */
size_t network_run_smooth_overflow(const struct dp_network_run *nr);
size_t network_run_smooth_kinks_at(struct dp_network_run *nr, double at);
int network_run_smooth_kink(const struct dp_network_run *nr, size_t k);

/* Yield and unload events at time t of the elastoplastic springs whose slider started or stopped sliding. */
void network_run_plastic_events(dp_run *r, double t);

/* A row over the columns from the current state, its numbers written to data and ph. */
dp_row network_run_fill_row(const struct dp_network_run *nr, double t, double *data);

/* Renumbers the run's copy of the network (and its initial state) for a narrow band, where that at least
 * halves it; sets nr->node_pos then (network_order.c). DP_OK or DP_ENOMEM. */
int network_run_reorder(struct dp_network_run *nr, dp_network *net, double *x0, double *v0);

/* The network run (network_run.c), whose setup, queue and state the one-mass network's type shares
 * (network_one_mass.c). */
int network_run_setup(dp_run *r);
int network_run_pending(const dp_run *r);
/* How a network's stick-slip run reports its events (dp_network_locates): "locate", "step" or "none". */
const char *network_run_events_mode(const dp_spec *s);
void network_run_free(void *state);

/* The run's state. */
static inline struct dp_network_run *network_run_of(const dp_run *r)
{
    return r->state;
}

/* The regularized scheme on networks (network_regularized.c). */
int dp_network_regularized_init(dp_run *r);
int dp_network_regularized_advance(dp_run *r);
void dp_network_regularized_free(struct dp_network_regularized *g);

/* The grounded chain (network_grounded_chain.c): how many of its steps so far the general solve decided
 * (a pass that did not settle, a NaN, a pivot not positive); -1 when the run has no chain workspace (the
 * general advance steps it). For tests. */
long long network_chain_handed(const struct dp_network_run *nr);

#endif
