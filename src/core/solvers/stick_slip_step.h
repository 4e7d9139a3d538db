/* src/core/solvers/stick_slip_step.h - internal: one step of the stick-slip theta-method (stick_slip_step.c),
 * shared by the stepper (stick_slip.c) and event location (event_location.c). */
#ifndef DASHPOT_CORE_STICK_SLIP_STEP_H
#define DASHPOT_CORE_STICK_SLIP_STEP_H

#include <math.h>

#include "laws/inclusion.h"
#include "record/sink.h"

/* The coefficients of the closed-form step for step length h (stick_slip_step.c). */
void dp_ss_coef_init(const dp_ss_law *L, double h, dp_ss_coef *c);

static inline double sgn(double x)
{
    return (x > 0) - (x < 0);
}

/* F(t), without the call for the usual constant load. */
static inline double load(const dp_ss_law *L, double t)
{
    return L->F_const ? L->F0 : dp_forcing_eval(L->F, t);
}

/* Relative free velocity u of a step of length h from (t, x, v), with the step's coefficients in *c. */
static inline double free_velocity(const dp_ss_law *L, double t, double h, double x, double v, dp_ss_coef *c)
{
    if (h != L->h)
        dp_ss_coef_init(L, h, c);
    else
        *c = L->nominal;
    return c->cv * v + c->cx * x + c->cf * load(L, t + L->theta * h) + c->c0;
}

typedef struct step_state { double t, x, v; dp_phase phase; } step_state;

/* The closed form (soft threshold): advances s by a step of length h with the Moreau rule, from its free
 * velocity u and coefficients c (dp_ss_moreau computes them); returns the friction's mean force. */
double dp_ss_moreau_from(const dp_ss_law *L, step_state *s, double h, double u, const dp_ss_coef *c);
double dp_ss_moreau(const dp_ss_law *L, step_state *s, double h);

/* The general step: its inclusion (dp_inclusion), and one step through dp_inclusion_solve with the damper
 * and spring graph forces in *fc, *fs; DP_OK or DP_ESOLVE. dp_ss_run_inclusion is the run's own: an
 * elastoplastic spring's explicit share (1 - theta) F and its graph's argument x+ added (stick_slip.c). */
dp_inclusion dp_ss_step_inclusion(const dp_ss_law *L, const step_state *s, double h);
dp_inclusion dp_ss_run_inclusion(const dp_run *r, const step_state *s, double h);
int dp_ss_inclusion_step(dp_run *r, step_state *s, double h, double *fc, double *fs);

/* The events a located step found, in order, kept for its caller to emit (dp_ss_events_emit) or to drop
 * when the step was only a trial (a root search over the step's length). */
#define DP_SS_EVENTS_MAX 4
typedef struct dp_ss_events { size_t n; dp_event e[DP_SS_EVENTS_MAX]; } dp_ss_events;
void dp_ss_events_emit(dp_run *r, const dp_ss_events *ev);

/* Event location (event_location.c): one step split at the phase changes inside it, events emitted (or,
 * where ev is given, kept in *ev); return the time spent sticking (-1: the general step has no solution).
 * dp_ss_located_plastic_step also splits the step at an elastoplastic spring's yield and unload. */
double dp_ss_located_step(dp_run *r, step_state *s, double h, double *force);
double dp_ss_located_inclusion_step(dp_run *r, step_state *s, double h, double *fc, double *fs, dp_ss_events *ev);
double dp_ss_located_plastic_step(dp_run *r, step_state *s, double h, double *fc, double *fs);

/* ---- the Jenkins element's phase, for the solvers that locate its yield and unload ----------------------- */

/* Negative while the phase `flow` holds at (x, v): elastic (0), |k (x - p)| - F_y; sliding in direction
 * flow = +-1, -flow x', where a mass that came to rest (x' = 0 exactly: stopped, or stuck to a resting belt)
 * counts as past the root, so that the slider stops where the mass does. */
static inline double dp_plastic_margin(const dp_spring *sp, double p, int flow, double x, double v)
{
    if (flow == 0)
        return fabs(sp->k * (x - p)) - sp->yield;
    return v == 0 ? 1e-300 : -flow * v;
}

/* The phase change at x, where the margin's root put the element (on the yield surface to rounding, after
 * the return mapping there): a yield starts the slider in the force's direction with the force exactly on
 * the yield surface; an unload stops it, the force where the slide left it. Returns the event's kind. */
static inline dp_event_kind dp_plastic_switch(const dp_spring *sp, double x, double *p, double *F, int *flow)
{
    if (*flow != 0) {
        *flow = 0;
        return DP_EVENT_UNLOAD;
    }
    *flow = x - *p >= 0 ? 1 : -1;
    *F = *flow * sp->yield;
    *p = x - *flow * sp->yield / sp->k;
    return DP_EVENT_YIELD;
}

/* The one-mass stick-slip run (stick_slip.c): prepares the law's constants and the initial state (the thesis
 * variant and a one-mass network start the same way), then steps. */
int dp_stick_slip_init(dp_run *r);
int dp_stick_slip_advance(dp_run *r);

/* The damper forces possible at rest: the static interval of a generalized Coulomb law, else A(0). */
void dp_ss_stick_interval(const dp_ss_law *L, double *lo, double *hi);

/* A document whose numbers reach 10^+-100 leaves double precision (10^+-308) in products of three of
 * them, which is what a step forms: an overflow there is the document's scale, not the dynamics. */
#define DP_ONE_MASS_EXTREME_DECADES 100

/* The number of a one-mass document (its model, initial state, dt and t_end) farthest from 1 in decades. */
double dp_one_mass_extreme(const dp_spec *s);

/* Fails the run whose step at time t from the finite state (x, v) left the finite numbers: "the step's
 * quantities overflow at t = ..." (DP_ESOLVE) when the document reaches 10^+-DP_ONE_MASS_EXTREME_DECADES,
 * else `diverged` (DP_ENONFINITE: the solution grew from the document's scale). Messages hold finite
 * numbers only. */
int dp_one_mass_nonfinite(dp_run *r, const char *diverged, double t, double x, double v);

#endif
