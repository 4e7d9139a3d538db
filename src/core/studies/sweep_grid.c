/* src/core/studies/sweep_grid.c - the grid of a sweep (sweep.h): each axis' values and the run index,
 * row-major (the last axis varies fastest), so that a shard's and the whole sweep's indices agree. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/sweep.h"

int dp_sweep_axis_fill(dp_sweep_axis *a, double from, double to, size_t count, int log_scale)
{
    a->values = malloc((count ? count : 1) * sizeof *a->values);
    if (a->values == NULL)
        return DP_ENOMEM;
    a->n = count;
    for (size_t j = 0; j < count; j++) {
        /* from + (to - from) u, from (to / from)^u with u = j / (count - 1): no drift from adding a step */
        double u = count > 1 ? (double)j / (double)(count - 1) : 0;
        a->values[j] = log_scale ? from * pow(to / from, u) : from + (to - from) * u;
    }
    a->values[0] = from;
    if (count > 1)
        a->values[count - 1] = to;
    return DP_OK;
}

size_t dp_sweep_grid_runs(const dp_sweep_grid *g)
{
    size_t n = g->naxes ? 1 : 0;
    for (size_t k = 0; k < g->naxes; k++)
        n *= g->axis[k].n;
    return n;
}

void dp_sweep_grid_values(const dp_sweep_grid *g, size_t index, double *values)
{
    for (size_t k = g->naxes; k-- > 0;) {
        values[k] = g->axis[k].values[index % g->axis[k].n];
        index /= g->axis[k].n;
    }
}

void dp_sweep_grid_clear(dp_sweep_grid *g)
{
    for (size_t k = 0; k < g->naxes; k++)
        free(g->axis[k].values);
    memset(g, 0, sizeof *g);
}
