/* src/core/solvers/network/network_smooth.c - spring graphs of finite slope on a network: a "graph" spring
 * whose pieces are all sloped (no vertical piece, no vertical end ray) and a compliant contact, whose graph
 * is -k max(d - u, 0) (the Yosida approximation of the rigid contact, docs/systems.md §4).
 *
 * Such a spring's force is a Lipschitz function of the elongation, so it is stepped as a linear spring is,
 * by the theta-rule on its force: theta S(u+) + (1 - theta) S(u), u+ = u + h ((1 - theta) u' + theta z+),
 * the same weighting the elastoplastic spring uses (network_step.h, ep_theta); at theta = 1/2 the
 * trapezoidal rule. Its vertices (a kink of the graph: a compliant contact's first touch, its separation)
 * are located inside the step like any other event (network_events.c): the held piece's margin is the
 * elongation's distance from the piece's ends, and at the root the assignment is renewed over a sliver of
 * the step (as after a yield), so the rest of the step is taken on the next piece and theta = 1/2 stays
 * second order through the kink. Graphs with a vertical piece (a rope, a user graph's stop or jump) are split
 * by network_run.c, with events located, into such a sloped part, rigid constraints (network_contact.c) and
 * step elements; without, they are stepped whole by backward Euler (network_check.c).
 * A compliant contact's touch and separation are written as events by network_output.c. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "solvers/network/network_run.h"

/* Whether a spring graph has finite slope everywhere (no vertical piece, no vertical end ray). */
static int sloped(const dp_graph *g)
{
    return g != NULL && g->n > 0 && isfinite(dp_graph_lipschitz(g));
}

/* The force of k's spring graph at the current state (single-valued: the graph has no vertical piece). */
static double start_force(const struct dp_network_run *nr, size_t k)
{
    double lo, hi;
    dp_graph_force(nr->act[k].S, network_run_rel(nr->act[k].a, nr->act[k].b, nr->x), &lo, &hi);
    return lo;
}

int network_run_smooth_setup(struct dp_network_run *nr)
{
    size_t na = nr->nact;
    for (size_t k = 0; k < na; k++) {
        dp_network_step_element *e = &nr->act[k];
        if (e->ep_theta != 0 || !sloped(e->S))
            continue;
        if (nr->sm_on == NULL) {   /* the first such spring: the arrays for all */
            nr->sm_on = calloc(na, 1);
            nr->sm_F = calloc(na, sizeof *nr->sm_F);
            nr->sm_kink = calloc(na, 1);
            nr->sm_pressed = calloc(nr->nc ? nr->nc : 1, 1);
            if (!nr->sm_on || !nr->sm_F || !nr->sm_kink || !nr->sm_pressed)
                return DP_ENOMEM;
        }
        nr->sm_on[k] = 1;
        if (nr->theta < 1)   /* at theta = 1 the weighting is backward Euler's, bit for bit */
            e->ep_theta = nr->theta, nr->has_smooth = 1;
    }
    return DP_OK;
}

void network_run_smooth_free(struct dp_network_run *nr)
{
    free(nr->sm_on), free(nr->sm_F), free(nr->sm_kink), free(nr->sm_pressed);
}

void network_run_smooth_update(struct dp_network_run *nr)
{
    for (size_t k = 0; nr->has_smooth && k < nr->nact; k++)
        if (nr->sm_on[k])
            nr->sm_F[k] = start_force(nr, k);
}

size_t network_run_smooth_overflow(const struct dp_network_run *nr)
{
    for (size_t k = 0; nr->sm_on && k < nr->nact; k++)
        if (nr->sm_on[k] && !isfinite(start_force(nr, k)))
            return nr->act_el[k] + 1;
    return 0;
}

double network_run_smooth_force(const struct dp_network_run *nr, size_t k, double stepped)
{
    return nr->has_smooth && nr->sm_on[k] ? nr->sm_F[k] : stepped;
}

/* The distance, in z, from the held step's end elongation u+ = u_e + s beta z+ to the nearest vertex of k's
 * spring graph (nr->u and nr->force from a held solve of length s). */
static double vertex_distance(const struct dp_network_run *nr, size_t k, double s)
{
    const dp_network_step_element *e = &nr->act[k];
    double beta = s * (e->ep_theta > 0 ? e->ep_theta : 1), up = nr->u[k] + beta * nr->force[k].z, d = INFINITY;
    for (size_t j = 0; j < e->S->n; j++)
        d = fmin(d, fabs(up - e->S->y[j]));
    return d / beta;
}

/* The same from z to the nearest vertex of k's damper graph (INFINITY without one). */
static double damper_distance(const struct dp_network_run *nr, size_t k)
{
    const dp_network_step_element *e = &nr->act[k];
    double d = INFINITY;
    for (size_t j = 0; e->A && j < e->A->n; j++)
        d = fmin(d, fabs(nr->force[k].z - e->vb - e->A->y[j]));
    return d;
}

size_t network_run_smooth_kinks_at(struct dp_network_run *nr, double at)
{
    size_t n = 0;
    for (size_t k = 0; nr->sm_on && k < nr->nact; k++) {
        nr->sm_kink[k] = 0;
        if (!nr->sm_on[k] || !nr->fails[k] || dp_network_step_fixed(nr->ws, k) || !(at > 0))
            continue;
        if (vertex_distance(nr, k, at) > damper_distance(nr, k))
            continue;      /* its damper's event, not the spring's */
        nr->sm_kink[k] = 1;
        n++;
    }
    return n;
}

int network_run_smooth_kink(const struct dp_network_run *nr, size_t k)
{
    return nr->sm_kink && nr->sm_kink[k];
}
