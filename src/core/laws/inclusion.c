/* src/core/laws/inclusion.c - solving the implicit step K w - gamma(w) + A(w) + S(w) containing b exactly.
 *
 * The step of any maximal monotone damper graph and monotone spring graph is one scalar inclusion
 * (docs/mathematics.md §4). Its set-valued part lives at the graphs' vertices, so the vertices are searched
 * first (binary search: Phi is monotone), which makes sticking and the taut rope exact rather than
 * approximately reached; between two neighbouring vertices every graph is affine, so without relaxation
 * the root is one division, and with it one bracketed root search.
 */
#include <math.h>

#include "dashpot/status.h"
#include "laws/inclusion.h"
#include "base/root.h"

static double gamma_at(const dp_inclusion *p, double w)
{
    return p->gamma ? dp_relaxation_eval(p->gamma, p->g_theta * w + p->g_shift) : 0;
}

void dp_inclusion_phi_with(const dp_inclusion *p, double w, double alo, double ahi, double *lo, double *hi)
{
    double slo = 0, shi = 0;
    if (p->S)
        dp_graph_force(p->S, p->s_x + p->s_h * w, &slo, &shi);
    /* The graph forces balance the load b at rest; subtract them first so that what remains near rest
     * (W w and the relaxation, both tiny there) is not rounded away. */
    double g = p->h * gamma_at(p, w);
    *lo = (p->h * (alo + slo) - p->b) + p->W * w - g;
    *hi = (p->h * (ahi + shi) - p->b) + p->W * w - g;
}

static void phi(const dp_inclusion *p, double w, double *lo, double *hi)
{
    double alo, ahi;
    dp_graph_force(p->A, w - p->a_shift, &alo, &ahi);
    dp_inclusion_phi_with(p, w, alo, ahi, lo, hi);
}

int dp_inclusion_holds_with(const dp_inclusion *p, double w, double flo, double fhi)
{
    double lo, hi;
    dp_inclusion_phi_with(p, w, flo, fhi, &lo, &hi);
    return lo <= 0 && 0 <= hi;
}

/* The side() of a Phi that is not a number: the step's quantities overflowed (an end of a product of the
 * document's numbers past the doubles), which no search can get past. */
#define NOT_A_SIDE 2

/* -1: the solution lies right of w; +1: left of it; 0: w solves; NOT_A_SIDE: Phi(w) is NaN. */
static int side(const dp_inclusion *p, double w, unsigned long long *evals)
{
    double lo, hi;
    phi(p, w, &lo, &hi);
    (*evals)++;
    if (isnan(lo) || isnan(hi))
        return NOT_A_SIDE;
    return hi < 0 ? -1 : lo > 0 ? 1 : 0;
}

/* Narrows [*a, *b) (the first kink whose side is >= 0 lies in it) around the kink the last step ended at,
 * galloping outwards from it: a step moves the solution by little, so a few evaluations find the kink that
 * a plain bisection of a 10^4-point graph would take 14 evaluations (each with its own graph searches)
 * for. Returns 1 if a kink solves (*w). */
static int gallop(const dp_inclusion *p, const double *y, size_t n, double off, double scale, size_t h,
                  size_t *a, size_t *b, double *w, unsigned long long *evals)
{
    double k = (y[h] - off) / scale;
    int s = side(p, k, evals), dir = s; /* dir < 0: the kink sought is right of h; > 0: h or left of it */
    if (s == NOT_A_SIDE)
        return -1;
    if (s == 0) {
        *w = k;
        return 1;
    }
    if (dir < 0)
        *a = h + 1;
    else
        *b = h;
    for (size_t d = 1; dir < 0 ? d < n - h : d <= h; d *= 2) {
        size_t i = dir < 0 ? h + d : h - d;
        k = (y[i] - off) / scale;
        s = side(p, k, evals);
        if (s == NOT_A_SIDE)
            return -1;
        if (s == 0) {
            *w = k;
            return 1;
        }
        if (s < 0)
            *a = i + 1;
        else
            *b = i;
        if (s != dir) /* passed it: it lies in [a, b) */
            return 0;
    }
    return 0;
}

/* Narrows (*lo, *hi) with the kinks off + scale * y[i] of one graph; returns 1 if a kink solves, -1 if Phi
 * is NaN at one. */
static int search_kinks(const dp_inclusion *p, const double *y, size_t n, double off, double scale,
                        double *lo, double *hi, double *w, size_t *hint, unsigned long long *evals)
{
    size_t a = 0, b = n; /* first kink whose side is >= 0 */
    int g = hint && *hint < n ? gallop(p, y, n, off, scale, *hint, &a, &b, w, evals) : 0;
    if (g != 0)
        return g;
    while (a < b) {
        size_t mid = a + (b - a) / 2;
        double k = (y[mid] - off) / scale;
        int s = side(p, k, evals);
        if (s == NOT_A_SIDE)
            return -1;
        if (s == 0) {
            *w = k;
            return 1;
        }
        if (s < 0)
            a = mid + 1;
        else
            b = mid;
    }
    if (hint)
        *hint = a < n ? a : n - 1;
    if (a > 0)
        *lo = fmax(*lo, (y[a - 1] - off) / scale);
    if (a < n)
        *hi = fmin(*hi, (y[a] - off) / scale);
    return 0;
}

static double phi_mid(void *ctx, double w)
{
    double lo, hi;
    phi((const dp_inclusion *)ctx, w, &lo, &hi);
    return lo; /* single-valued strictly between kinks */
}

/* Pushes an infinite end of the bracket out until Phi changes sign; 0 if it never does. */
static int expand(const dp_inclusion *p, double from, double dir, double *end, double *g,
                  unsigned long long *evals)
{
    double d = fmax(1.0, fabs(from));
    for (int i = 0; i < 1100; i++, d *= 2) {
        double w = from + dir * d;
        if (!isfinite(w))
            return 0;
        double v = phi_mid((void *)p, w);
        (*evals)++;
        if ((dir < 0 && v < 0) || (dir > 0 && v > 0)) {
            *end = w, *g = v;
            return 1;
        }
    }
    return 0;
}

static void split_forces(const dp_inclusion *p, double w, double *a, double *s)
{
    double alo, ahi, slo = 0, shi = 0;
    dp_graph_force(p->A, w - p->a_shift, &alo, &ahi);
    if (p->S)
        dp_graph_force(p->S, p->s_x + p->s_h * w, &slo, &shi);
    double R = (p->b - p->W * w + p->h * gamma_at(p, w)) / p->h; /* = a + s */
    /* The damper takes the force of least magnitude the spring leaves to it (unique unless both graphs
     * are vertical at w, e.g. a taut rope on a stuck block). */
    double amin = fmax(alo, R - shi), amax = fmin(ahi, R - slo);
    *a = amax < amin ? (alo == ahi ? alo : R - slo) : fmin(fmax(0.0, amin), amax);
    *s = p->S ? R - *a : 0;
}

int dp_inclusion_solve(const dp_inclusion *p, double *w, double *a, double *s, unsigned long long *evals)
{
    unsigned long long ev = 0;
    double lo = -INFINITY, hi = INFINITY, root;
    int hit = search_kinks(p, p->A->y, p->A->n, -p->a_shift, 1.0, &lo, &hi, &root, p->hint, &ev);
    if (!hit && p->S)
        hit = search_kinks(p, p->S->y, p->S->n, p->s_x, p->s_h, &lo, &hi, &root, p->hint ? p->hint + 1 : NULL, &ev);
    if (hit < 0)
        return DP_ENONFINITE;
    if (!hit) {
        double glo, ghi, t;
        if (isfinite(lo)) {
            phi(p, lo, &t, &glo); /* right limit at a kink: the top of its interval */
        } else if (!expand(p, hi, -1, &lo, &glo, &ev)) {
            return DP_ESOLVE;
        }
        if (isfinite(hi)) {
            phi(p, hi, &ghi, &t);
        } else if (!expand(p, lo, 1, &hi, &ghi, &ev)) {
            return DP_ESOLVE;
        }
        double tol = 4 * 2.220446049250313e-16 * fmax(fabs(lo), fabs(hi));
        root = dp_root_bracket(phi_mid, (void *)p, lo, hi, glo, ghi, tol, &ev);
    }
    if (!isfinite(root))
        return DP_ESOLVE;
    *w = root;
    split_forces(p, root, a, s);
    if (evals)
        *evals += ev;
    return isfinite(*a) && isfinite(*s) ? DP_OK : DP_ENONFINITE;
}

typedef struct side_ctx { const dp_inclusion *p; double dir; } side_ctx;

/* Phi at a_shift + dir e^u, signed so that it is negative just off rest and positive far out. */
static double phi_log(void *ctx, double u)
{
    const side_ctx *c = ctx;
    return c->dir * phi_mid((void *)c->p, c->p->a_shift + c->dir * exp(u));
}

int dp_inclusion_solve_side(const dp_inclusion *p, double dir, double *w, double *a, double *s,
                            unsigned long long *evals)
{
    /* Off rest the solution may sit extremely close to it (it leaves like t^N), so search in log |w - v_b|:
     * from the smallest normal distance up to where Phi has certainly turned positive. */
    side_ctx c = { p, dir };
    double lo = log(2.2250738585072014e-308), hi = 0, glo = phi_log(&c, lo), ghi = phi_log(&c, hi);
    unsigned long long ev = 2;
    while (!(ghi > 0) && hi < 700) {
        hi += 8;
        ghi = phi_log(&c, hi);
        ev++;
    }
    if (!(glo < 0) || !(ghi > 0))
        return DP_ESOLVE;
    double u = dp_root_bracket(phi_log, &c, lo, hi, glo, ghi, 1e-13, &ev);
    *w = p->a_shift + dir * exp(u);
    split_forces(p, *w, a, s);
    if (evals)
        *evals += ev;
    return DP_OK;
}
