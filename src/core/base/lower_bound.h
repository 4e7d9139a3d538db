/* src/core/base/lower_bound.h - internal: the search of a sorted array that the graphs' lookups (laws/graph.c)
 * and the network step's starting pieces (network/network_step.c) both make, so that both find the same
 * index for the same number. */
#ifndef DASHPOT_CORE_LOWER_BOUND_H
#define DASHPOT_CORE_LOWER_BOUND_H

#include <stddef.h>

/* First index i in [0, n) with a[i] >= x (n if none), for a non-decreasing a: the classic lower bound. */
static inline size_t dp_lower_bound(const double *a, size_t n, double x)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (a[mid] < x)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

#endif
