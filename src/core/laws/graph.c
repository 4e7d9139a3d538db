/* src/core/laws/graph.c - piecewise-linear monotone graphs: evaluation, inverse, resolvent, Yosida.
 *
 * A graph is a curve through vertices (y_i, F_i), non-decreasing in both coordinates, with a ray at each
 * end. Along such a curve u = y + l*F is non-decreasing for l > 0, and strictly increasing except on
 * repeated vertices, so the resolvent J_l(s) (the y with y + l*A(y) containing s, Cibulka 2014, Lemma 1.2)
 * is found by one binary search on u and one linear interpolation: exact, no iteration.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/lower_bound.h"
#include "dashpot/graph.h"
#include "dashpot/status.h"

static int ray_ok(const double d[2])
{
    return isfinite(d[0]) && isfinite(d[1]) && d[0] >= 0 && d[1] >= 0 && (d[0] > 0 || d[1] > 0);
}

/* Copies the vertices into g's own arrays; on failure g is left empty. */
static int store(dp_graph *g, size_t n, const double *y, const double *f)
{
    g->y = malloc(n * sizeof *g->y);
    g->f = malloc(n * sizeof *g->f);
    if (g->y == NULL || g->f == NULL) {
        dp_graph_clear(g);
        return DP_ENOMEM;
    }
    memcpy(g->y, y, n * sizeof *y);
    memcpy(g->f, f, n * sizeof *f);
    g->n = n;
    return DP_OK;
}

int dp_graph_init(dp_graph *g, size_t n, const double *y, const double *f,
                  const double left[2], const double right[2])
{
    memset(g, 0, sizeof *g);
    if (n == 0 || n > DP_GRAPH_MAX_POINTS || !ray_ok(left) || !ray_ok(right))
        return DP_EINVAL;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(y[i]) || !isfinite(f[i]))
            return DP_EINVAL;
        /* a piece whose extent overflows would interpolate with inf * 0 */
        if (i > 0 && (!isfinite(y[i] - y[i - 1]) || !isfinite(f[i] - f[i - 1])))
            return DP_EINVAL;
        if (i > 0 && (y[i] < y[i - 1] || f[i] < f[i - 1]))
            return DP_EINVAL;
    }
    if (store(g, n, y, f) != DP_OK)
        return DP_ENOMEM;
    memcpy(g->left, left, sizeof g->left);
    memcpy(g->right, right, sizeof g->right);
    return DP_OK;
}

int dp_graph_init_points(dp_graph *g, size_t n, const double *y, const double *f)
{
    memset(g, 0, sizeof *g);
    if (n < 2)
        return DP_EINVAL;
    double left[2] = { y[1] - y[0], f[1] - f[0] };
    double right[2] = { y[n - 1] - y[n - 2], f[n - 1] - f[n - 2] };
    return dp_graph_init(g, n, y, f, left, right);
}

int dp_graph_init_raw(dp_graph *g, size_t n, const double *y, const double *f)
{
    memset(g, 0, sizeof *g);
    if (n < 2 || n > DP_GRAPH_MAX_POINTS)
        return DP_EINVAL;
    if (store(g, n, y, f) != DP_OK)
        return DP_ENOMEM;
    g->left[0] = y[1] - y[0], g->left[1] = f[1] - f[0];
    g->right[0] = y[n - 1] - y[n - 2], g->right[1] = f[n - 1] - f[n - 2];
    return DP_OK;
}

void dp_graph_clear(dp_graph *g)
{
    if (g == NULL)
        return;
    free(g->y);
    free(g->f);
    memset(g, 0, sizeof *g);
}

int dp_graph_copy(dp_graph *dst, const dp_graph *src)
{
    if (src->n == 0) {
        memset(dst, 0, sizeof *dst);
        return DP_OK;
    }
    return dp_graph_init(dst, src->n, src->y, src->f, src->left, src->right);
}

/* First index i with a[i] > x (n if none). */
static size_t upper_bound(const double *a, size_t n, double x)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (a[mid] <= x)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* How far a ray of direction (da, db) climbs in b over a distance d >= 0 in a: d (db/da), or where the
 * slope alone overflows (a ray nearly vertical, da subnormal) d/da db, which is finite when the climb is. */
static double ray(double d, double db, double da)
{
    double c = d * (db / da);
    return isfinite(c) || !isfinite(d) ? c : d / da * db;
}

/* The interval of `b` over the points of the curve whose `a` coordinate equals x. The curve is given by
 * sorted a[], b[] and rays whose components are (da, db) at index ia, ib of the direction arrays.
 * A non-finite x is refused before the search: a NaN compares false both ways, so the searches below would
 * find no index (upper_bound 0, then b[-1]), and an infinite x meets a horizontal ray as inf * 0. */
static int section(size_t n, const double *a, const double *b, const double left[2],
                   const double right[2], int ia, int ib, double x, double *lo, double *hi)
{
    if (!isfinite(x)) {
        *lo = *hi = NAN;
        return DP_ENONFINITE;
    }
    if (x < a[0]) {
        if (left[ia] > 0)
            *lo = *hi = b[0] - ray(a[0] - x, left[ib], left[ia]);
        else
            *lo = *hi = -INFINITY; /* vertical left ray: x lies outside the graph's domain */
        return DP_OK;
    }
    if (x > a[n - 1]) {
        if (right[ia] > 0)
            *lo = *hi = b[n - 1] + ray(x - a[n - 1], right[ib], right[ia]);
        else
            *lo = *hi = INFINITY;
        return DP_OK;
    }
    size_t i = dp_lower_bound(a, n, x);
    if (a[i] > x) { /* strictly inside segment (i-1, i), which is not vertical */
        double s = (x - a[i - 1]) / (a[i] - a[i - 1]);
        *lo = *hi = b[i - 1] + s * (b[i] - b[i - 1]);
        return DP_OK;
    }
    size_t j = upper_bound(a, n, x) - 1;
    *lo = (i == 0 && left[ia] == 0) ? -INFINITY : b[i];
    *hi = (j == n - 1 && right[ia] == 0) ? INFINITY : b[j];
    return DP_OK;
}

int dp_graph_force(const dp_graph *g, double y, double *lo, double *hi)
{
    return section(g->n, g->y, g->f, g->left, g->right, 0, 1, y, lo, hi);
}

int dp_graph_kinematic(const dp_graph *g, double F, double *lo, double *hi)
{
    return section(g->n, g->f, g->y, g->left, g->right, 1, 0, F, lo, hi);
}

double dp_graph_resolvent(const dp_graph *g, double l, double s)
{
    size_t n = g->n;
    if (!isfinite(s) || !isfinite(l))
        return NAN; /* no search with a NaN: its comparisons are all false */
    double u0 = g->y[0] + l * g->f[0];
    double un = g->y[n - 1] + l * g->f[n - 1];
    if (s <= u0) /* on the left ray: u falls at rate dy + l dF > 0 */
        return g->y[0] - (u0 - s) * g->left[0] / (g->left[0] + l * g->left[1]);
    if (s >= un)
        return g->y[n - 1] + (s - un) * g->right[0] / (g->right[0] + l * g->right[1]);
    size_t lo = 0, hi = n - 1; /* invariant: u(lo) < s < u(hi) */
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        double um = g->y[mid] + l * g->f[mid];
        if (um == s)
            return g->y[mid];
        if (um < s)
            lo = mid;
        else
            hi = mid;
    }
    double ulo = g->y[lo] + l * g->f[lo], uhi = g->y[hi] + l * g->f[hi];
    return g->y[lo] + (s - ulo) / (uhi - ulo) * (g->y[hi] - g->y[lo]);
}

double dp_graph_yosida(const dp_graph *g, double l, double y)
{
    return (y - dp_graph_resolvent(g, l, y)) / l;
}

static double slope(double dy, double dF)
{
    if (dF == 0)
        return 0;
    return dy == 0 ? INFINITY : dF / dy;
}

double dp_graph_lipschitz(const dp_graph *g)
{
    double L = fmax(slope(g->left[0], g->left[1]), slope(g->right[0], g->right[1]));
    for (size_t i = 1; i < g->n; i++)
        L = fmax(L, slope(g->y[i] - g->y[i - 1], g->f[i] - g->f[i - 1]));
    return L;
}

/* The piece of the curve that leaves y towards dir (+1 or -1): used by the network step, which walks a
 * graph piece by piece (network_step.c). */
void dp_graph_piece(const dp_graph *g, double y, int dir, dp_graph_piece_t *pc)
{
    size_t n = g->n;
    double slope, y0, f0;        /* the piece is F = f0 + slope (y - y0) */
    pc->blocked = 0;
    if (dir > 0) {
        size_t j = upper_bound(g->y, n, y);
        if (j == n) {             /* on the right ray (or at its vertex) */
            if (g->right[0] == 0) {
                pc->blocked = 1;
                pc->slope = 0, pc->f = g->f[n - 1], pc->next = y;
                return;
            }
            slope = g->right[1] / g->right[0], y0 = g->y[n - 1], f0 = g->f[n - 1];
            pc->next = INFINITY;
        } else if (j == 0) {      /* left of the first vertex: on the left ray */
            slope = g->left[0] > 0 ? g->left[1] / g->left[0] : 0;
            y0 = g->y[0], f0 = g->f[0];
            pc->next = g->y[0];
        } else {
            slope = (g->f[j] - g->f[j - 1]) / (g->y[j] - g->y[j - 1]);
            y0 = g->y[j - 1], f0 = g->f[j - 1];
            pc->next = g->y[j];
        }
    } else {
        size_t j = dp_lower_bound(g->y, n, y);
        if (j == 0) {             /* on the left ray (or at its vertex) */
            if (g->left[0] == 0) {
                pc->blocked = 1;
                pc->slope = 0, pc->f = g->f[0], pc->next = y;
                return;
            }
            slope = g->left[1] / g->left[0], y0 = g->y[0], f0 = g->f[0];
            pc->next = -INFINITY;
        } else if (j == n) {      /* right of the last vertex: on the right ray */
            slope = g->right[0] > 0 ? g->right[1] / g->right[0] : 0;
            y0 = g->y[n - 1], f0 = g->f[n - 1];
            pc->next = g->y[n - 1];
        } else {
            slope = (g->f[j] - g->f[j - 1]) / (g->y[j] - g->y[j - 1]);
            y0 = g->y[j], f0 = g->f[j];
            pc->next = g->y[j - 1];
        }
    }
    pc->slope = slope;
    pc->f = y == y0 ? f0 : f0 + slope * (y - y0);
}

int dp_graph_has_vertex(const dp_graph *g, double y)
{
    size_t j = dp_lower_bound(g->y, g->n, y);
    return j < g->n && g->y[j] == y;
}
