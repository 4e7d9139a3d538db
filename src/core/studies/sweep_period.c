/* src/core/studies/sweep_period.c - the end of a run's features (sweep.h): the extremes as found, the stick
 * fraction, and the period, the smallest number of like points after which a sequence repeats.
 *
 * "Like points" (Poincaré's return map read off a trajectory) are the section's points when there is a
 * section (the stroboscopic one at t = after + k T returns after p T; an event section after the mean time
 * of p events), else the maxima of x, which are like events whether the motion sticks or not: each stick
 * that follows a forward slip is one. A motion that never repeats within PERIOD_MAX_P points (quasi-periodic,
 * chaotic, or its transient not over by `after`) has a null period and says so.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "dashpot/sweep.h"

/* Longest period sought, in section points or maxima: a period-32 orbit is as far as a diagram is read. */
#define PERIOD_MAX_P 32
/* Points of a sequence "repeat" within this fraction of the motion's range (the extremes) at least: far above
 * the solver's rounding and the Hermite interpolant's error (h^4 on smooth data), far below any bifurcation a
 * diagram shows. */
#define PERIOD_RTOL 1e-6

/* The fraction the comparison allows: PERIOD_RTOL, or the discretization's own spread if larger. A step h
 * that does not divide the period T puts the step grid at another phase of the motion in every cycle, and
 * the θ-scheme's error (second order: about (ωh)²/12 of the range, ω = 2π/T) then differs from cycle to
 * cycle by up to that much: a period-1 motion's maxima differ by ~1e-4 of the range at ω h = 0.03. Compared
 * to 1e-6 they looked distinct, and a nearly commensurate 2T or 3T was reported instead of T. (ωh)² is 12
 * times that spread, still far below a diagram's splittings at usable steps (ωh <= 0.1: 1e-2). `T` is the
 * mean spacing of the sequence's points (one period of the basic motion), h the run's step. */
static double rtol(double h, double T)
{
    double wh = T > 0 ? 2 * M_PI * h / T : 0;
    return isfinite(wh) && wh * wh > PERIOD_RTOL ? wh * wh : PERIOD_RTOL;
}

/* The tolerance for "the same value" on a quantity ranging over [lo, hi]: rtol of the range, and a few
 * roundings of its size (a motion at rest repeats exactly). */
static double tolerance(double rel, double lo, double hi)
{
    return rel * (hi - lo) + 8 * DBL_EPSILON * fmax(fabs(lo), fabs(hi));
}

/* The smallest p <= PERIOD_MAX_P with x[j + p] = x[j] (and v[j + p] = v[j] when v is given) for every j,
 * seen at least twice over (n >= 2p + 1); 0 when there is none. */
static size_t repeat(const double *x, const double *v, size_t n, double tx, double tv)
{
    for (size_t p = 1; p <= PERIOD_MAX_P && n >= 2 * p + 1; p++) {
        size_t j = 0;
        while (j + p < n && fabs(x[j + p] - x[j]) <= tx && (v == NULL || fabs(v[j + p] - v[j]) <= tv))
            j++;
        if (j + p == n)
            return p;
    }
    return 0;
}

/* Mean of t[j + p] - t[j] over the sequence. */
static double mean_lag(const double *t, size_t n, size_t p)
{
    double sum = 0;
    for (size_t j = 0; j + p < n; j++)
        sum += t[j + p] - t[j];
    return sum / (double)(n - p);
}

static void set(dp_feature_values *o, int f, double value)
{
    o->value[f] = value;
    o->known[f] = isfinite(value);
    o->why[f] = o->known[f] ? NULL : "not finite";
}

static void null(dp_feature_values *o, int f, const char *why)
{
    o->value[f] = 0;
    o->known[f] = 0;
    o->why[f] = why;
}

/* The period from the section's points. */
static void period_of_section(dp_features *f, double *t, double *x, double *v)
{
    dp_feature_values *o = &f->out;
    size_t n = f->nsection;
    for (size_t i = 0; i < n; i++) {
        t[i] = f->section[i].t;
        x[i] = f->section[i].x;
        v[i] = f->section[i].v;
    }
    if (n < 3) {
        null(o, DP_FEATURE_PERIOD, "fewer than 3 section points after t = after");
        return;
    }
    double T = f->plan.section == DP_SECTION_PERIOD ? f->plan.section_period : mean_lag(t, n, 1);
    double rel = rtol(f->h, T);
    size_t p = repeat(x, v, n, tolerance(rel, f->xmin, f->xmax), tolerance(rel, f->vmin, f->vmax));
    if (p == 0)
        null(o, DP_FEATURE_PERIOD, "the section's points do not repeat within 32 of them (quasi-periodic or "
                                   "chaotic motion, or a transient longer than after)");
    else if (f->plan.section == DP_SECTION_PERIOD)
        set(o, DP_FEATURE_PERIOD, (double)p * f->plan.section_period);
    else
        set(o, DP_FEATURE_PERIOD, mean_lag(t, n, p));
}

/* The period from the latest maxima of x, oldest first. */
static void period_of_maxima(dp_features *f, double *t, double *x)
{
    size_t n = f->nmax < DP_FEATURES_MAXIMA ? f->nmax : DP_FEATURES_MAXIMA;
    size_t first = f->nmax - n;
    for (size_t i = 0; i < n; i++) {
        t[i] = f->max_t[(first + i) % DP_FEATURES_MAXIMA];
        x[i] = f->max_x[(first + i) % DP_FEATURES_MAXIMA];
    }
    if (n < 3) {
        null(&f->out, DP_FEATURE_PERIOD, "fewer than 3 maxima of x after t = after (the motion comes to rest "
                                         "or does not turn)");
        return;
    }
    size_t p = repeat(x, NULL, n, tolerance(rtol(f->h, mean_lag(t, n, 1)), f->xmin, f->xmax), 0);
    if (p == 0)
        null(&f->out, DP_FEATURE_PERIOD, "the maxima of x do not repeat within 32 of them (quasi-periodic or "
                                         "chaotic motion, or a transient longer than after)");
    else
        set(&f->out, DP_FEATURE_PERIOD, mean_lag(t, n, p));
}

static void period(dp_features *f)
{
    size_t cap = f->nsection > DP_FEATURES_MAXIMA ? f->nsection : DP_FEATURES_MAXIMA;
    double *buf = malloc(3 * (cap ? cap : 1) * sizeof *buf);
    if (buf == NULL) {
        null(&f->out, DP_FEATURE_PERIOD, "out of memory");
        return;
    }
    if (f->plan.section != DP_SECTION_NONE)
        period_of_section(f, buf, buf + cap, buf + 2 * cap);
    else
        period_of_maxima(f, buf, buf + cap);
    free(buf);
}

void dp_features_finish(dp_features *f)
{
    dp_feature_values *o = &f->out;
    double window = f->t_last - f->plan.after;
    if (!f->any) {
        const char *why = "no sample at t >= after (the run ends before after)";
        for (int k = 0; k < DP_FEATURE_COUNT; k++)
            null(o, k, why);
        if (f->col_x == -1 || f->col_v == -1)
            for (int k = 0; k < DP_FEATURE_COUNT; k++)
                null(o, k, "the run's rows hold no x and v of the node");
        return;
    }
    set(o, DP_FEATURE_X_MAX, f->xmax);
    set(o, DP_FEATURE_X_MIN, f->xmin);
    set(o, DP_FEATURE_V_MAX, f->vmax);
    set(o, DP_FEATURE_V_MIN, f->vmin);
    set(o, DP_FEATURE_AMPLITUDE, 0.5 * (f->xmax - f->xmin));
    if (window > 0) {
        /* the phase since the last mark lasts to the end (the last record is the final sample) */
        double stick = f->stick;
        if (f->phase == DP_PHASE_STICK && f->t_last > fmax(f->mark, f->plan.after))
            stick += f->t_last - fmax(f->mark, f->plan.after);
        set(o, DP_FEATURE_STICK_FRACTION, fmin(1.0, stick / window));
    } else {
        null(o, DP_FEATURE_STICK_FRACTION, "no time after t = after (t_end = after)");
    }
    if (f->plan.features & (1u << DP_FEATURE_PERIOD))
        period(f);
    else
        null(o, DP_FEATURE_PERIOD, "not asked for");
}
