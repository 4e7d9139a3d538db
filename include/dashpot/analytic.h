/* include/dashpot/analytic.h - the closed-form solution of m x'' + k x + F_c = F0, F_c in phi0 Sgn(x')
 * (Babováková 2012 (4.14)-(4.15)): harmonic arcs about (F0 -/+ phi0)/k joined at turning points, ending at rest
 * at the first turning point where |F0 - k x| <= phi0. The reference every stick-slip solver is tested
 * against, and the `analytic` solver's engine. */
#ifndef DASHPOT_ANALYTIC_H
#define DASHPOT_ANALYTIC_H

#include <stddef.h>

typedef struct dp_coulomb_problem {
    double m, k, phi0, F0;  /* m > 0, k > 0, phi0 >= 0 */
    double x0, v0;
} dp_coulomb_problem;

/* One arc: from (t0, x0, v0) moving in direction dir (+1/-1) about the centre xc = (F0 - dir phi0)/k,
 * until t1 (INFINITY for phi0 = 0) where it turns at x1 with zero velocity. dir = 0 marks final rest
 * at x0 from t0 on. */
typedef struct dp_coulomb_arc {
    double t0, x0, v0;
    int dir;
    double xc, t1, x1;
} dp_coulomb_arc;

/* The arcs that start before t_end (the last may be the rest arc), up to cap of them; *n their number.
 * Returns 0, or -1 if cap was too small (the first cap arcs are written). Inputs must be finite. */
int dp_coulomb_arcs(const dp_coulomb_problem *p, double t_end, dp_coulomb_arc *arcs, size_t cap, size_t *n);

/* Position and velocity on an arc at time t in [t0, t1]. */
void dp_coulomb_arc_eval(const dp_coulomb_problem *p, const dp_coulomb_arc *a, double t, double *x, double *v);

/* The first arc from a state (t0, x0, v0) (rest if the mass is at rest and the force holds it). */
dp_coulomb_arc dp_coulomb_arc_from(const dp_coulomb_problem *p, double t0, double x0, double v0);

#endif
