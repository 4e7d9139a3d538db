/* src/core/laws/elastoplastic.c - the Jenkins element (a spring k in series with a Coulomb slider of yield
 * force F_y; Höschl 003 §15, docs/systems.md §3): its return mapping and its step graph.
 *
 * Why a separate graph per step: the law has memory (the plastic offset p), so the force at the step's end
 * as a function of the elongation there, F+ = clamp(k (u+ - p), -F_y, F_y), is a monotone piecewise-linear
 * graph whose two vertices sit at p -/+ F_y/k and move only when the slider slides. The solvers rewrite the
 * two vertices in place before a step (no allocation) and move p after it by the return mapping, which is
 * the exact backward-Euler integral of the flow rule p' in N_[-F_y, F_y](F).
 */
#include <math.h>

#include "dashpot/model.h"

double dp_elastoplastic_return(const dp_spring *s, double u, double *p, int *flow)
{
    double trial = s->k * (u - *p);
    *flow = 0;
    if (trial > s->yield) {
        *p = u - s->yield / s->k, *flow = 1;
        return s->yield;
    }
    if (trial < -s->yield) {
        *p = u + s->yield / s->k, *flow = -1;
        return -s->yield;
    }
    return trial;
}

void dp_elastoplastic_graph(const dp_spring *s, double p, double weight, dp_graph *g)
{
    double d = s->yield / s->k;
    g->y[0] = p - d, g->y[1] = p + d;
    g->f[0] = -weight * s->yield, g->f[1] = weight * s->yield;
}
