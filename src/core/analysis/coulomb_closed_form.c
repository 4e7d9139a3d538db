/* src/core/analysis/coulomb_closed_form.c - the closed-form Coulomb oscillator (Babováková 2012, (4.14)-(4.15)):
 * the arcs between turning points that the `analytic` solver (solvers/analytic.c) and the tests step along.
 *
 * In the plane (y, w) = (x - xc, v/omega) an arc is a clockwise rotation at rate omega = sqrt(k/m) about
 * the arc's centre, so the time to the next turning point is an angle divided by omega: no root finding,
 * and turning points and rest positions come out to rounding (|x_{j+1} - xc| = |x_j - xc| by symmetry).
 */
#include <math.h>

#include "dashpot/analytic.h"

dp_coulomb_arc dp_coulomb_arc_from(const dp_coulomb_problem *p, double t0, double x0, double v0)
{
    dp_coulomb_arc a = { .t0 = t0, .x0 = x0, .v0 = v0, .t1 = INFINITY, .x1 = x0 };
    double need = p->F0 - p->k * x0;
    if (v0 == 0 && fabs(need) <= p->phi0) {
        a.xc = x0; /* rest: dir 0 */
        return a;
    }
    a.dir = v0 != 0 ? (v0 > 0 ? 1 : -1) : (need > 0 ? 1 : -1);
    a.xc = (p->F0 - a.dir * p->phi0) / p->k;
    if (p->phi0 == 0)
        return a; /* undamped: one endless harmonic arc */
    double om = sqrt(p->k / p->m);
    double y = x0 - a.xc, w = v0 != 0 ? v0 / om : copysign(0.0, a.dir);
    double ang = atan2(w, y); /* in (0, pi] moving right, [-pi, 0) moving left */
    a.t1 = t0 + (a.dir > 0 ? ang : ang + M_PI) / om;
    a.x1 = a.xc + a.dir * hypot(y, w);
    return a;
}

void dp_coulomb_arc_eval(const dp_coulomb_problem *p, const dp_coulomb_arc *a, double t, double *x, double *v)
{
    if (a->dir == 0) {
        *x = a->x0, *v = 0;
        return;
    }
    double om = sqrt(p->k / p->m), s = om * (t - a->t0);
    double y = a->x0 - a->xc, w = a->v0 / om, c = cos(s), sn = sin(s);
    *x = a->xc + y * c + w * sn;
    *v = om * (w * c - y * sn);
}

int dp_coulomb_arcs(const dp_coulomb_problem *p, double t_end, dp_coulomb_arc *arcs, size_t cap, size_t *n)
{
    *n = 0;
    dp_coulomb_arc a = dp_coulomb_arc_from(p, 0, p->x0, p->v0);
    for (;;) {
        if (*n == cap)
            return -1;
        arcs[(*n)++] = a;
        if (a.dir == 0 || !(a.t1 < t_end))
            return 0;
        a = dp_coulomb_arc_from(p, a.t1, a.x1, 0);
    }
}
