/* src/core/laws/relaxation.c - relaxation functions gamma with gamma(0) = 0 (docs/mathematics.md §1):
 * rational a v/(b+|v|) (thesis ch. 4: Lipschitz a/b, |gamma| < a), linear L v, and the paper's
 * non-Lipschitz power law gamma_N(u) = N |u|^(1-1/N) sgn u (Pražák & Rajagopal 2016, (26)). */
#include <math.h>

#include "dashpot/model.h"

double dp_relaxation_eval(const dp_relaxation *r, double v)
{
    switch (r->kind) {
    case DP_RELAX_NONE: return 0;
    case DP_RELAX_RATIONAL: return r->a * v / (r->b + fabs(v));
    case DP_RELAX_LINEAR: return r->L * v;
    case DP_RELAX_POWER:
        if (v == 0)
            return 0;
        return copysign(r->N * pow(fabs(v), 1 - 1 / r->N), v);
    }
    return 0;
}

double dp_relaxation_slope(const dp_relaxation *r, double v)
{
    switch (r->kind) {
    case DP_RELAX_NONE: return 0;
    case DP_RELAX_RATIONAL: return r->a * r->b / ((r->b + fabs(v)) * (r->b + fabs(v)));
    case DP_RELAX_LINEAR: return r->L;
    case DP_RELAX_POWER:
        return v == 0 ? INFINITY : r->N * (1 - 1 / r->N) * pow(fabs(v), -1 / r->N);
    }
    return 0;
}

double dp_relaxation_lipschitz(const dp_relaxation *r)
{
    switch (r->kind) {
    case DP_RELAX_NONE: return 0;
    case DP_RELAX_RATIONAL: return r->a / r->b; /* the slope at 0 is the largest */
    case DP_RELAX_LINEAR: return fabs(r->L);
    case DP_RELAX_POWER: return INFINITY;    /* slope N (1-1/N) |u|^(-1/N) blows up at 0 */
    }
    return 0;
}

double dp_relaxation_bound(const dp_relaxation *r)
{
    switch (r->kind) {
    case DP_RELAX_NONE: return 0;
    case DP_RELAX_RATIONAL: return fabs(r->a);
    case DP_RELAX_LINEAR: return r->L == 0 ? 0 : INFINITY;
    case DP_RELAX_POWER: return INFINITY;
    }
    return 0;
}
