/* include/dashpot/right_hand.h - Coulomb friction whose normal reaction depends on the accelerations
 * (Matrosov & Finogenko 1995; docs/systems.md §6): the acceleration problem of one instant solved by
 * enumerating every stick/slip mode, so that Painlevé's paradoxes (no solution: inconsistency; several:
 * indeterminacy) are found and reported, never guessed; the paper's conditions (1.2), (2.3), (6.2)-(6.4).
 *
 * Both models have two Lagrangian coordinates q = (q0, q1) and the form
 *     A(q) q'' = b(q, q') + Q,   Q_s = friction of coordinate s,
 *     slip:  Q_s = -sgn(q_s') f_s |N_s(q, q', q'')|,
 *     rest:  stick (q_s'' = 0, |Q_s| <= f_s |N_s|) or start (Q_s = -sigma f_s |N_s|, sigma q_s'' > 0),
 * with each N_s affine in q'' (signed, |N| = its absolute value) or the Euclidean norm of an affine 2-vector.
 */
#ifndef DASHPOT_RIGHT_HAND_H
#define DASHPOT_RIGHT_HAND_H

#include <stddef.h>

typedef enum dp_right_hand_kind { DP_RIGHT_HAND_PISTON_HINGE = 0, DP_RIGHT_HAND_ROD = 1 } dp_right_hand_kind;

/* piston-hinge (Matrosov & Finogenko 1995 §6): q = (x, beta), parameters m1, m2, J_C, r, alpha, f1 (a coefficient), f2 (a
 * length: the hinge's friction moment is f2 |N2|), g.
 * painleve-rod: a uniform rod of mass m and length `length` whose lower end A rests on a rough floor with
 * coefficient mu; q = (x_A, theta), theta the angle between the rod and the floor. */
typedef struct dp_right_hand_model {
    dp_right_hand_kind kind;
    double m1, m2, J_C, r, alpha, f1, f2;
    double m, length, mu;
    double e;         /* the rod's restitution at an impact: Stronge's energetic coefficient, in [0, 1] */
    double g;
} dp_right_hand_model;

typedef enum dp_right_hand_mode {
    DP_RIGHT_HAND_FREE = 0,      /* no friction on this coordinate */
    DP_RIGHT_HAND_STICK = 1,
    DP_RIGHT_HAND_SLIP_POS = 2,  /* sliding (or starting) with q_s' > 0: friction -f|N| */
    DP_RIGHT_HAND_SLIP_NEG = 3
} dp_right_hand_mode;

#define DP_RIGHT_HAND_MAX_SOL 16

/* One solution of the acceleration problem. N: the normal reactions (signed for an affine N, the norm for
 * the hinge's N2; the rod has only N[0]); Q: the friction generalized forces. */
typedef struct dp_right_hand_sol {
    double qdd[2], N[2], Q[2];
    dp_right_hand_mode mode[2];
    int liftoff;      /* the rod leaving the floor (N = 0, free flight): a candidate this model does not follow */
} dp_right_hand_sol;

typedef struct dp_right_hand_result {
    int n;            /* distinct solutions found (those past DP_RIGHT_HAND_MAX_SOL are counted, not stored) */
    int continuum;    /* a mode whose equations are singular and consistent: infinitely many solutions */
    dp_right_hand_sol sol[DP_RIGHT_HAND_MAX_SOL];
} dp_right_hand_result;

/* The model's equations at one state: A q'' = b + Q and the normal reactions' affine maps. */
typedef struct dp_right_hand_frame {
    double A[2][2], b[2];
    int fric[2];              /* coordinate s carries friction (f_s > 0) */
    double f[2];
    int ndim[2];              /* 1: N_s = W[s][0] . q'' + w[s][0] (signed); 2: |N_s| = ||W[s] q'' + w[s]|| */
    int unilateral[2];        /* a floor: N_s >= 0 while in contact (the rod) */
    double W[2][2][2], w[2][2];
} dp_right_hand_frame;

/* Fills the frame of model m at (q, qd). */
void dp_right_hand_frame_at(const dp_right_hand_model *m, const double q[2], const double qd[2], dp_right_hand_frame *fr);

/* The force tolerance of the cone and sign tests at a frame (1e-10 of its force scale). */
double dp_right_hand_force_tol(const dp_right_hand_frame *fr);

/* Every solution of the acceleration problem at (q, qd): modes forced by the velocities' signs where they
 * move, all three (stick, start +, start -) where they rest (qd_s == 0 exactly); for the rod also leaving
 * the floor (liftoff) when its free flight lifts the end A. If `fixed` is not NULL
 * only that mode combination is solved and the stick cone is not checked: the solver's smooth phases,
 * where leaving the cone is a located event instead (a start's direction is checked: it tells the two
 * solutions of a mode apart at the phase's first instant). Never fails. */
void dp_right_hand_solve(const dp_right_hand_model *m, const double q[2], const double qd[2], const dp_right_hand_mode *fixed,
                 dp_right_hand_result *res);

/* The paper's conditions at a state and one solution of it (margins: > 0 holds, <= 0 fails). */
typedef struct dp_right_hand_conditions {
    double c12;        /* (1.2): min over friction coordinates of a_ss - f_s |d|N_s|/d q_s''| (none: min a_ss) */
    double c23;        /* (2.3) (signs corrected, docs/right-hand.md): min of a_ss/k* - |J_sv| */
    double c62, c63, c64; /* piston-hinge (6.2), (6.3), (6.4) (min of its three); NAN for the rod */
    int in_A;          /* the state is in the set A: no resting coordinate on its cone with N_s = 0 */
} dp_right_hand_conditions;

void dp_right_hand_conditions_at(const dp_right_hand_model *m, const double q[2], const double qd[2], const dp_right_hand_sol *sol,
                         dp_right_hand_conditions *c);

struct dp_wp_report;
/* The theorems of Matrosov & Finogenko 1995 (3.1, 4.1/4.2, 5.1) and their hypotheses at the initial state (q, qd). */
void dp_right_hand_wellposedness(const dp_right_hand_model *m, const double q[2], const double qd[2], struct dp_wp_report *rep);

/* The rod off the floor and back (src/core/right_hand/rod_flight.c). Its state in the plane: the end A at
 * (x, y) (y its height above the floor, 0 in contact), theta the angle from A to the other end B, and their
 * rates; the centre G = A + l (cos theta, sin theta), l = length/2, the moment of inertia m l^2/3 about G. */
typedef struct dp_right_hand_rod_state {
    double x, y, theta, xd, yd, thetad;
} dp_right_hand_rod_state;

/* A free flight from t0: G's parabola from (xG, yG) with (vx, vy), the rod turning uniformly at omega. */
typedef struct dp_right_hand_flight {
    double t0, xG, yG, vx, vy, theta, omega;
} dp_right_hand_flight;

void dp_right_hand_flight_start(const dp_right_hand_model *m, double t0, const dp_right_hand_rod_state *s,
                                dp_right_hand_flight *f);
/* The state at t (closed form); xdd receives x'' (the end A's horizontal acceleration). */
void dp_right_hand_flight_at(const dp_right_hand_model *m, const dp_right_hand_flight *f, double t,
                             dp_right_hand_rod_state *s, double *xdd);

enum { DP_FLIGHT_ON = 0, DP_FLIGHT_LANDS = 1, DP_FLIGHT_BUDGET = -1, DP_FLIGHT_OVERFLOW = -2 };

/* The first time after *t, and not after t_max, at which an end of the rod reaches the floor: *t moves only
 * by advances under which no end can reach it (a lower bound of the end's height by its Taylor polynomial,
 * the third derivative bounded by l |omega|^3), so no landing is stepped over. Returns DP_FLIGHT_LANDS with
 * *t the landing and *end 0 for A, 1 for B; DP_FLIGHT_ON with *t = t_max; DP_FLIGHT_BUDGET after `budget`
 * advances (*t safe, to resume from); DP_FLIGHT_OVERFLOW when the motion leaves double precision. *used
 * counts the advances. */
int dp_right_hand_flight_landing(const dp_right_hand_model *m, const dp_right_hand_flight *f, double *t, double t_max,
                                 unsigned long budget, unsigned long *used, int *end);

/* One impact of the end A on the floor (Stronge's energetic restitution with Coulomb friction, the impulse
 * integrated along the normal impulse after Routh: right_hand/rod_flight.c, docs/right-hand.md). */
typedef struct dp_right_hand_impact {
    double vt0, vn0;        /* A's velocity before: along the floor and up */
    double vt, vn;          /* after */
    double thetad;          /* theta' after */
    double Pt, Pn;          /* the impulse of the floor on A */
    double work_c, work_r;  /* the normal impulse's work in compression (<= 0) and in restitution (>= 0) */
    double work_t;          /* the friction impulse's work (<= 0) */
    int stick;              /* A sticks at the end of the impulse (vt = 0 exactly) */
} dp_right_hand_impact;

/* The impact of the rod at theta with A's velocity (xd, yd), yd < 0, and rate thetad, restitution e;
 * 0 when the impulse does not end (not for a rod: its Delassus matrix is positive definite). */
int dp_right_hand_rod_impact(const dp_right_hand_model *m, double theta, double xd, double yd, double thetad, double e,
                             dp_right_hand_impact *out);

/* The rod's kinetic energy in the state s. */
double dp_right_hand_rod_kinetic(const dp_right_hand_model *m, const dp_right_hand_rod_state *s);

/* "piston-hinge" or "painleve-rod". */
const char *dp_right_hand_kind_name(dp_right_hand_kind k);

/* Checks a model's parameters; on failure writes the offending key and a reason and returns 0. */
int dp_right_hand_model_valid(const dp_right_hand_model *m, const char **key, const char **why);

#endif
