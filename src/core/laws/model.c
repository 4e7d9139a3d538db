/* src/core/model.c - the named laws of mathematics.md §1 turned into monotone graphs, and model lifetime.
 *
 * Springs live in the (x, F_s) plane, dampers in the (v - v_b, F_c) plane. The damper graph holds only the
 * part a solver must treat implicitly as a set: Coulomb's and Bingham's stick interval; their viscous
 * part c stays a number so that the theta-method can weight it (mathematics.md §4).
 */
#include <math.h>
#include <string.h>

#include "dashpot/model.h"
#include "dashpot/status.h"

static const double RIGHT[2] = { 1, 0 };  /* horizontal ray: force constant */
static const double UP[2] = { 0, 1 };     /* vertical ray: force unbounded at a fixed position */

static int line_graph(dp_graph *g, double slope)
{
    double y = 0, f = 0, d[2] = { 1, slope };
    return dp_graph_init(g, 1, &y, &f, d, d);
}

/* The stick interval [-phi, phi] at zero relative velocity, flat beyond (Coulomb, seed 000 (C)). */
static int threshold_graph(dp_graph *g, double phi)
{
    if (phi == 0)
        return line_graph(g, 0);
    double y[2] = { 0, 0 }, f[2] = { -phi, phi };
    return dp_graph_init(g, 2, y, f, RIGHT, RIGHT);
}

int dp_spring_prepare(dp_spring *s)
{
    if (s->law == DP_SPRING_GRAPH)
        return s->graph.n > 0 ? DP_OK : DP_EINVAL;
    dp_graph_clear(&s->graph);
    if (s->law == DP_SPRING_LINEAR)
        return line_graph(&s->graph, s->k);
    if (s->law == DP_SPRING_ELASTOPLASTIC) {
        if (!(s->k > 0 && s->yield > 0 && isfinite(s->offset)))
            return DP_EINVAL;
        double y[2] = { s->offset - s->yield / s->k, s->offset + s->yield / s->k }, f[2] = { -s->yield, s->yield };
        double flat[2] = { 1, 0 };
        return dp_graph_init(&s->graph, 2, y, f, flat, flat);
    }
    /* Rope (thesis Fig. 1): F_s = k x while slack; at x = L the rope takes any extra tension. */
    double y = s->length, f = s->k * s->length, left[2] = { 1, s->k };
    return dp_graph_init(&s->graph, 1, &y, &f, left, UP);
}

int dp_damper_prepare(dp_damper *d)
{
    switch (d->law) {
    case DP_DAMPER_GRAPH:
        return d->graph.n > 0 ? DP_OK : DP_EINVAL;
    case DP_DAMPER_NONE:
    case DP_DAMPER_LINEAR:
        dp_graph_clear(&d->graph);
        return line_graph(&d->graph, 0);
    case DP_DAMPER_COULOMB:
    case DP_DAMPER_GENERALIZED_COULOMB:
        dp_graph_clear(&d->graph);
        return threshold_graph(&d->graph, d->phi0);
    case DP_DAMPER_BINGHAM:
        dp_graph_clear(&d->graph);
        return threshold_graph(&d->graph, d->tau);
    }
    return DP_EINVAL;
}

int dp_model_prepare(dp_model *m)
{
    int s = dp_spring_prepare(&m->spring);
    if (s != DP_OK)
        return s;
    return dp_damper_prepare(&m->damper);
}

void dp_model_clear(dp_model *m)
{
    if (m == NULL)
        return;
    dp_graph_clear(&m->spring.graph);
    dp_graph_clear(&m->damper.graph);
    dp_forcing_clear(&m->forcing);
}

int dp_model_copy(dp_model *dst, const dp_model *src)
{
    *dst = *src;
    memset(&dst->spring.graph, 0, sizeof dst->spring.graph);
    memset(&dst->damper.graph, 0, sizeof dst->damper.graph);
    memset(&dst->forcing, 0, sizeof dst->forcing);
    int s = dp_graph_copy(&dst->spring.graph, &src->spring.graph);
    if (s == DP_OK)
        s = dp_graph_copy(&dst->damper.graph, &src->damper.graph);
    if (s == DP_OK)
        s = dp_forcing_copy(&dst->forcing, &src->forcing);
    if (s != DP_OK)
        dp_model_clear(dst);
    return s;
}

const char *dp_spring_law_name(dp_spring_law law)
{
    static const char *names[] = { "linear", "rope", "graph", "elastoplastic" };
    return (unsigned)law < 4 ? names[law] : "?";
}

const char *dp_damper_law_name(dp_damper_law law)
{
    static const char *names[] = { "none", "linear", "coulomb", "bingham", "generalized-coulomb", "graph" };
    return (unsigned)law < 6 ? names[law] : "?";
}
