/* src/core/base/root.c - a safeguarded Illinois method for a bracketed root (used at events and in the
 * relaxation step, never per step of the closed-form path). Illinois halves the retained end's value when
 * the same end is kept twice, which restores superlinear convergence of regula falsi (Dowell & Jarratt
 * 1971); a bisection every third step without halving the bracket bounds the worst case. */
#include <math.h>

#include "base/root.h"

double dp_root_bracket(dp_root_fn g, void *ctx, double a, double b, double ga, double gb, double tol,
                       unsigned long long *evals)
{
    if (ga == 0)
        return a;
    if (gb == 0)
        return b;
    int side = 0, since_halved = 0;
    double width = fabs(b - a);
    for (int it = 0; it < 400 && fabs(b - a) > tol; it++) {
        double c;
        if (since_halved >= 3) {
            c = a + (b - a) / 2;
            since_halved = 0;
        } else {
            c = (a * gb - b * ga) / (gb - ga);
            if (!(c > fmin(a, b) && c < fmax(a, b)))
                c = a + (b - a) / 2;
        }
        if (c == a || c == b)
            break; /* the bracket is as narrow as the doubles allow */
        double gc = g(ctx, c);
        if (evals)
            (*evals)++;
        if (gc == 0 || isnan(gc))
            return c;
        if ((gc < 0) == (ga < 0)) {
            a = c, ga = gc;
            if (side == -1)
                gb /= 2;
            side = -1;
        } else {
            b = c, gb = gc;
            if (side == 1)
                ga /= 2;
            side = 1;
        }
        if (fabs(b - a) <= width / 2) {
            width = fabs(b - a);
            since_halved = 0;
        } else {
            since_halved++;
        }
    }
    return fabs(ga) <= fabs(gb) ? a : b;
}
