/* src/core/analysis/stability_map.c - stability maps: verdict and spectral abscissa over a grid of two coefficients,
 * and the closed-form boundary ((1.10), (1.12), (1.14)) traced over the same grid by marching squares.
 *
 * A map answers "where in the (x, y) plane is the law stable?" the way the thesis' conditions do in closed
 * form; drawing both shows where the conditions are exact and where their assumptions (all coefficients of
 * p positive) stop holding.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/stability.h"

int dp_param_parse(const char *name, dp_param_kind *kind, int *index)
{
    if (strcmp(name, "mass") == 0) {
        *kind = DP_PARAM_MASS;
        *index = 0;
        return 0;
    }
    size_t skip = strncmp(name, "lambda[", 7) == 0 ? 7 : strncmp(name, "mu[", 3) == 0 ? 3 : 0;
    if (skip == 0)
        return -1;
    const char *d = name + skip;
    if (d[0] < '0' || d[0] > '9' || d[1] != ']' || d[2] != '\0')   /* one digit: orders 0 .. 8 */
        return -1;
    *kind = skip == 7 ? DP_PARAM_LAMBDA : DP_PARAM_MU;
    *index = d[0] - '0';
    return 0;
}

void dp_param_name(dp_param_kind kind, int index, char *out, size_t cap)
{
    if (kind == DP_PARAM_MASS)
        snprintf(out, cap, "mass");
    else
        snprintf(out, cap, "%s[%d]", kind == DP_PARAM_LAMBDA ? "lambda" : "mu", index);
}

static int axis_value_ok(const dp_map_axis *ax, double v)
{
    if (ax->kind == DP_PARAM_MASS)
        return v >= DP_STAB_COEF_MIN && v <= DP_STAB_COEF_MAX;
    return fabs(v) <= DP_STAB_COEF_MAX;
}

int dp_map_axis_check(const dp_map_axis *ax, const dp_law *law, const char *ptr, dp_errors *errs)
{
    char p[DP_POINTER_MAX];
    int s = DP_OK;
    int n = ax->kind == DP_PARAM_LAMBDA ? law->nlambda : law->nmu;
    if (ax->kind != DP_PARAM_MASS && (ax->index < 0 || ax->index >= n)) {
        snprintf(p, sizeof p, "%s/param", ptr);
        dp_errors_add(errs, p, "the law has no coefficient %s[%d] (it has %d)",
                      ax->kind == DP_PARAM_LAMBDA ? "lambda" : "mu", ax->index, n);
        s = DP_EINVAL;
    }
    snprintf(p, sizeof p, "%s/to", ptr);
    if (!(ax->from < ax->to)) {
        dp_errors_add(errs, p, "expected to > from");
        s = DP_EINVAL;
    } else if (!axis_value_ok(ax, ax->from) || !axis_value_ok(ax, ax->to)) {
        dp_errors_add(errs, p, ax->kind == DP_PARAM_MASS ? "the mass must stay in [%g, %g]"
                                                         : "values must stay within +-%g",
                      DP_STAB_COEF_MIN, DP_STAB_COEF_MAX);
        s = s == DP_OK ? DP_ELIMIT : s;
    }
    if (ax->steps < 2 || ax->steps > DP_STAB_MAP_MAX_STEPS) {
        snprintf(p, sizeof p, "%s/steps", ptr);
        dp_errors_add(errs, p, "expected 2 .. %d grid points", DP_STAB_MAP_MAX_STEPS);
        s = ax->steps < 2 ? DP_EINVAL : (s == DP_OK ? DP_ELIMIT : s);
    }
    return s;
}

double dp_map_axis_value(const dp_map_axis *ax, int i)
{
    double t = (double)i / (ax->steps - 1);
    double v = i == ax->steps - 1 ? ax->to : ax->from + (ax->to - ax->from) * t;
    /* A grid through zero lands near, not on, 0; below the coefficient floor it is 0. */
    return fabs(v) < DP_STAB_COEF_MIN ? 0.0 : v;
}

static void set_param(dp_law *law, const dp_map_axis *ax, double v)
{
    if (ax->kind == DP_PARAM_MASS)
        law->mass = v;
    else if (ax->kind == DP_PARAM_LAMBDA)
        law->lambda[ax->index] = v;
    else
        law->mu[ax->index] = v;
}

void dp_map_clear(dp_map *map)
{
    if (map == NULL)
        return;
    free(map->abscissa);
    free(map->has_abscissa);
    free(map->verdict);
    free(map->closed_value);
    free(map->closed_applies);
    memset(map, 0, sizeof *map);
}

static int map_alloc(dp_map *map, size_t n, int closed)
{
    map->abscissa = malloc(n * sizeof *map->abscissa);
    map->has_abscissa = malloc(n);
    map->verdict = malloc(n);
    if (closed) {
        map->closed_value = malloc(n * sizeof *map->closed_value);
        map->closed_applies = malloc(n);
    }
    int ok = map->abscissa && map->has_abscissa && map->verdict
             && (!closed || (map->closed_value && map->closed_applies));
    return ok ? DP_OK : DP_ENOMEM;
}

/* One grid point: verdict, abscissa and (when the base law has a thesis shape) the closed-form value. */
static int map_point(dp_stability_ws *w, const dp_law *law, dp_map *map, size_t k)
{
    dp_verdict v;
    double ab = 0.0;
    int has = 0;
    int s = dp_stability_verdict(w, law, &v, &ab, &has);
    if (s != DP_OK)
        return s;
    map->verdict[k] = (unsigned char)v;
    map->abscissa[k] = has ? ab : 0.0;
    map->has_abscissa[k] = (unsigned char)has;
    if (map->closed_value != NULL) {
        dp_closed_form cf;
        dp_law_closed_form(law, &cf);
        int same = cf.model == map->closed.model;
        map->closed_value[k] = same ? cf.value : 0.0;
        map->closed_applies[k] = (unsigned char)(same && cf.applies);
    }
    return DP_OK;
}

int dp_stability_map(dp_stability_ws *w, const dp_law *law, const dp_map_axis *x, const dp_map_axis *y,
                     dp_map *map)
{
    memset(map, 0, sizeof *map);
    if (dp_law_check(law, "", NULL) != DP_OK || dp_map_axis_check(x, law, "", NULL) != DP_OK
        || dp_map_axis_check(y, law, "", NULL) != DP_OK)
        return DP_EINVAL;
    map->x = *x;
    map->y = *y;
    map->nx = (size_t)x->steps;
    map->ny = (size_t)y->steps;
    int closed = dp_law_closed_form(law, &map->closed);
    int s = map_alloc(map, map->nx * map->ny, closed);
    dp_law pt = *law;
    for (size_t j = 0; s == DP_OK && j < map->ny; j++) {
        set_param(&pt, y, dp_map_axis_value(y, (int)j));
        for (size_t i = 0; s == DP_OK && i < map->nx; i++) {
            set_param(&pt, x, dp_map_axis_value(x, (int)i));
            s = map_point(w, &pt, map, j * map->nx + i);
        }
    }
    if (s != DP_OK)
        dp_map_clear(map);
    return s;
}

/* ---- marching squares on the closed-form value ---- */

/* Where value crosses 0 on the edge from corner (x0, y0) with value a to (x1, y1) with value b. */
static void crossing(double a, double b, double x0, double y0, double x1, double y1, double *px, double *py)
{
    double t = a / (a - b);
    *px = x0 + t * (x1 - x0);
    *py = y0 + t * (y1 - y0);
}

/* One cell with corners c[0] = (i, j), c[1] = (i+1, j), c[2] = (i+1, j+1), c[3] = (i, j+1). */
static int cell(const double c[4], double i, double j, int (*emit)(void *, double, double, double, double),
                void *ctx)
{
    static const double cx[4] = { 0, 1, 1, 0 }, cy[4] = { 0, 0, 1, 1 };
    double px[4], py[4];
    int n = 0;
    for (int e = 0; e < 4; e++) {          /* edge e joins corner e and corner e+1 */
        int f = (e + 1) % 4;
        if ((c[e] > 0) != (c[f] > 0)) {
            crossing(c[e], c[f], i + cx[e], j + cy[e], i + cx[f], j + cy[f], &px[n], &py[n]);
            n++;
        }
    }
    if (n == 2)
        return emit(ctx, px[0], py[0], px[1], py[1]);
    if (n != 4)
        return 0;
    /* Saddle: the centre decides which opposite corners are joined. Crossings are on edges 0,1,2,3 in order;
     * if the centre has corner 0's sign, corners 1 and 3 are cut off: pairs (0,1) and (2,3). */
    double centre = (c[0] + c[1] + c[2] + c[3]) / 4;
    int r = ((centre > 0) == (c[0] > 0)) ? emit(ctx, px[0], py[0], px[1], py[1])
                                          : emit(ctx, px[3], py[3], px[0], py[0]);
    if (r != 0)
        return r;
    return ((centre > 0) == (c[0] > 0)) ? emit(ctx, px[2], py[2], px[3], py[3])
                                        : emit(ctx, px[1], py[1], px[2], py[2]);
}

int dp_map_boundary(const dp_map *map, int (*emit)(void *ctx, double, double, double, double), void *ctx)
{
    if (map->closed_value == NULL)
        return 0;
    size_t nx = map->nx;
    for (size_t j = 0; j + 1 < map->ny; j++)
        for (size_t i = 0; i + 1 < nx; i++) {
            size_t k[4] = { j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i };
            double c[4];
            int ok = 1;
            for (int q = 0; q < 4; q++) {
                ok = ok && map->closed_applies[k[q]];
                c[q] = map->closed_value[k[q]];
            }
            int r = ok ? cell(c, (double)i, (double)j, emit, ctx) : 0;
            if (r != 0)
                return r;
        }
    return 0;
}
