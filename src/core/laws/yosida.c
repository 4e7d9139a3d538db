/* src/core/laws/yosida.c - the single-valued regularizations of a maximal monotone graph that the schemes (PCn)
 * and (PIk) integrate (docs/mathematics.md §3).
 *
 * (PCn), Pražák & Rajagopal 2016, (17): F_c = G_n(F_c, v) := n/(n+1) (v + phi(v + (n-1)/n F_c)), with phi the 45-degree
 * rotation of the graph (Lemma 1, (11)). Undoing the rotation, (17) says (F_c, v - F_c/n) in A, i.e.
 * v = y + F_c/n with F_c in A(y): y = J_(1/n)(v) and F_c = n (v - J_(1/n)(v)) = A_(1/n)(v), the Yosida
 * approximation. (PIk), Babováková 2012, (FIk): x = f(F) + F/k says (x - F/k, F) on the graph, the same equation
 * with 1/k for 1/n, so f_k^-1 = A_(1/k). For piecewise-linear graphs the Yosida approximation is exact
 * (graph.c: one binary search); dp_regularized_gn solves (17) for any 1-Lipschitz phi and is the second
 * method the tests hold the first one to.
 */
#include <math.h>

#include "dashpot/regularized.h"
#include "base/root.h"

double dp_graph_rotation(const dp_graph *g, double s)
{
    return s - 2 * dp_graph_resolvent(g, 1, s);
}

/* The piece of the curve on which u = y + l F passes the value s (the right one at a vertex): its first
 * vertex (*yb, *fb) and direction (*dy, *dF); for the left ray, vertex 0 and the ray's direction. */
static void piece_at(const dp_graph *g, double l, double s, double *yb, double *fb, double *dy, double *dF)
{
    size_t n = g->n, lo = 0, hi = n - 1;
    if (s < g->y[0] + l * g->f[0]) {
        *yb = g->y[0], *fb = g->f[0], *dy = g->left[0], *dF = g->left[1];
        return;
    }
    if (s >= g->y[n - 1] + l * g->f[n - 1]) {
        *yb = g->y[n - 1], *fb = g->f[n - 1], *dy = g->right[0], *dF = g->right[1];
        return;
    }
    /* u strictly increases along distinct vertices (l > 0): invariant u(lo) <= s < u(hi). */
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (g->y[mid] + l * g->f[mid] <= s)
            lo = mid;
        else
            hi = mid;
    }
    *yb = g->y[lo], *fb = g->f[lo], *dy = g->y[hi] - g->y[lo], *dF = g->f[hi] - g->f[lo];
}

double dp_graph_yosida_slope(const dp_graph *g, double l, double y, double *slope)
{
    double yb, fb, dy, dF;
    piece_at(g, l, y, &yb, &fb, &dy, &dF);
    /* Along the piece u = y + l F moves by dy + l dF while A_l = (u - J_l(u))/l moves by dF. Taken from the
     * piece's vertex, the value is exact on flat pieces (Coulomb's +-phi0 in slip) and never cancels
     * y - J_l(y) the way (y - J_l(y))/l does. */
    double s = dF / (dy + l * dF);
    if (slope)
        *slope = s;
    return fb + (y - (yb + l * fb)) * s;
}

/* ---- paper (17) by its contraction --------------------------------------------------------------------- */

typedef struct gn_ctx {
    dp_rotation_fn phi;
    void *ctx;
    double n, v;
    unsigned long long *evals;
    int bad;
} gn_ctx;

static double G(gn_ctx *c, double F)
{
    double p = c->phi(c->ctx, c->v + (c->n - 1) / c->n * F);
    if (c->evals)
        (*c->evals)++;
    if (!isfinite(p))
        c->bad = 1;
    return c->n / (c->n + 1) * (c->v + p);
}

/* F - G_n(F, v): increasing with slope >= 1 - |alpha|, so its root is the fixed point of (17). */
static double residual(void *p, double F)
{
    return F - G(p, F);
}

double dp_regularized_gn(dp_rotation_fn phi, void *ctx, double n, double v, unsigned long long *evals)
{
    gn_ctx c = { phi, ctx, n, v, evals, 0 };
    if (!(n > 0) || !isfinite(n) || !isfinite(v))
        return NAN;
    /* A-priori bound (14) from the Picard iterate F0 = G_n(0, v): |g_n(v) - F0| <= |G_n(F0) - F0| / (1 - |a|). */
    double alpha = fabs((n - 1) / (n + 1));
    double F0 = G(&c, 0), r0 = residual(&c, F0);
    if (c.bad)
        return NAN;
    if (r0 == 0)
        return F0;
    /* Widen by a little more than the rounding of the bound itself so that the ends straddle the root. */
    double R = fabs(r0) / (1 - alpha) * (1 + 1e-12) + 4 * 2.220446049250313e-16 * fabs(F0);
    double a = F0 - R, b = F0 + R, ra = residual(&c, a), rb = residual(&c, b);
    if (c.bad || !(ra <= 0 && rb >= 0))
        return NAN;
    double F = dp_root_bracket(residual, &c, a, b, ra, rb, 0, NULL); /* G counts the phi calls */
    return c.bad ? NAN : F;
}

/* ---- names --------------------------------------------------------------------------------------------- */

const char *dp_scheme_name(dp_scheme s)
{
    return s == DP_SCHEME_PI ? "PI" : "PC";
}

const char *dp_stepper_name(dp_stepper s)
{
    static const char *names[] = { "msbdf", "rk4imp", "bsimp", "rkf45", "rkck", "rk8pd" };
    return (unsigned)s < 6 ? names[s] : "?";
}
