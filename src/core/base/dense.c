/* src/core/base/dense.c - samples inside an integrator step. An adaptive integrator that lands on every output
 * time takes a clipped step before each one (and msbdf then lowers its order); stepping freely and
 * interpolating costs a few evaluations per step that holds a sample instead. Two interpolants:
 *   - quintic Hermite from y, y', y'' at both ends: error h^6 |y^(6)| / 46080 on a smooth stretch, for
 *     steps where the derivatives f(y), J f + f_t are as good as y (non-stiff steps);
 *   - the polynomial through the last accepted values, which is what a BDF step of that order is built on:
 *     no derivatives, so a stiff step (h |J| >> 1, where f(y) carries the step's error times |J|) loses
 *     nothing (docs/regularized.md, "Samples between steps"). */
#include "base/dense.h"

void dp_hermite5(const dp_hermite_end *a, const dp_hermite_end *b, size_t dim, double t, double out[])
{
    double h = b->t - a->t, s = (t - a->t) / h, u = 1 - s;
    double s2 = s * s, s3 = s2 * s, u2 = u * u;
    /* p = y0 + w5 (y1 - y0) + h (w1 y0' + w4 y1') + h^2 (w2 y0'' + w3 y1''), the usual basis in factored form:
     * w5 = 10 s^3 - 15 s^4 + 6 s^5, and each other w vanishes to third order at the end it does not belong to. */
    double w5 = s3 * (10 - 15 * s + 6 * s2);
    double w1 = s * u2 * u * (1 + 3 * s), w4 = -s3 * u * (4 - 3 * s);
    double w2 = 0.5 * s2 * u2 * u, w3 = 0.5 * s3 * u2;
    for (size_t i = 0; i < dim; i++)
        out[i] = a->y[i] + w5 * (b->y[i] - a->y[i]) + h * (w1 * a->dy[i] + w4 * b->dy[i])
                 + h * h * (w2 * a->d2y[i] + w3 * b->d2y[i]);
}

void dp_poly_interp(const double ts[], const double *ys, size_t n, size_t dim, double t, double out[])
{
    double c[DP_POLY_MAX];
    for (size_t i = 0; i < dim; i++) {
        for (size_t k = 0; k < n; k++)
            c[k] = ys[k * dim + i];
        /* After round m, c[k] is the value at t of the polynomial through points k .. k + m. */
        for (size_t m = 1; m < n; m++)
            for (size_t k = 0; k + m < n; k++)
                c[k] = ((t - ts[k + m]) * c[k] + (ts[k] - t) * c[k + 1]) / (ts[k] - ts[k + m]);
        out[i] = c[0];
    }
}
