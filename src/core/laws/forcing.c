/* src/core/laws/forcing.c - the load F(t): constant, harmonic amplitude*cos(omega t + phase), piecewise-linear
 * table (held constant beyond its ends), and sums of those (docs/architecture.md, "A model"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/model.h"
#include "dashpot/status.h"

/* The table segment [t[*lo], t[*hi]] holding t, for t strictly inside the table's span. */
static void table_segment(const dp_forcing *f, double t, size_t *lo, size_t *hi)
{
    size_t a = 0, b = f->n - 1; /* invariant: t[a] <= t < t[b] */
    while (b - a > 1) {
        size_t mid = a + (b - a) / 2;
        if (f->t[mid] <= t)
            a = mid;
        else
            b = mid;
    }
    *lo = a, *hi = b;
}

static double table_eval(const dp_forcing *f, double t)
{
    size_t n = f->n, lo, hi;
    if (t <= f->t[0])
        return f->F[0];
    if (t >= f->t[n - 1])
        return f->F[n - 1];
    table_segment(f, t, &lo, &hi);
    double s = (t - f->t[lo]) / (f->t[hi] - f->t[lo]);
    return f->F[lo] + s * (f->F[hi] - f->F[lo]);
}

/* dF/dt of a table: the slope of the segment holding t, 0 beyond the ends (constant there). */
static double table_rate(const dp_forcing *f, double t)
{
    size_t lo, hi;
    if (f->n < 2 || !(t >= f->t[0]) || t >= f->t[f->n - 1])
        return 0;
    table_segment(f, t, &lo, &hi);
    return (f->F[hi] - f->F[lo]) / (f->t[hi] - f->t[lo]);
}

double dp_forcing_rate(const dp_forcing *f, double t)
{
    double s = 0;
    switch (f->kind) {
    case DP_FORCING_HARMONIC:
        return -f->amplitude * f->omega * sin(f->omega * t + f->phase);
    case DP_FORCING_TABLE:
        return table_rate(f, t);
    case DP_FORCING_SUM:
        for (size_t i = 0; i < f->nterms; i++)
            s += dp_forcing_rate(&f->terms[i], t);
        return s;
    default:
        return 0;
    }
}

double dp_forcing_eval(const dp_forcing *f, double t)
{
    switch (f->kind) {
    case DP_FORCING_NONE: return 0;
    case DP_FORCING_CONSTANT: return f->value;
    case DP_FORCING_HARMONIC: return f->amplitude * cos(f->omega * t + f->phase);
    case DP_FORCING_TABLE: return table_eval(f, t);
    case DP_FORCING_SUM: {
        double s = 0;
        for (size_t i = 0; i < f->nterms; i++)
            s += dp_forcing_eval(&f->terms[i], t);
        return s;
    }
    }
    return 0;
}

int dp_forcing_is_constant(const dp_forcing *f, double *value)
{
    switch (f->kind) {
    case DP_FORCING_NONE: *value = 0; return 1;
    case DP_FORCING_CONSTANT: *value = f->value; return 1;
    case DP_FORCING_HARMONIC:
        *value = f->amplitude * cos(f->phase);
        return f->amplitude == 0 || f->omega == 0;
    case DP_FORCING_TABLE: {
        for (size_t i = 1; i < f->n; i++)
            if (f->F[i] != f->F[0])
                return 0;
        *value = f->F[0];
        return 1;
    }
    case DP_FORCING_SUM: {
        double s = 0, v;
        for (size_t i = 0; i < f->nterms; i++) {
            if (!dp_forcing_is_constant(&f->terms[i], &v))
                return 0;
            s += v;
        }
        *value = s;
        return 1;
    }
    }
    return 0;
}

void dp_forcing_clear(dp_forcing *f)
{
    if (f == NULL)
        return;
    free(f->t);
    free(f->F);
    for (size_t i = 0; i < f->nterms && f->terms; i++)
        dp_forcing_clear(&f->terms[i]);
    free(f->terms);
    memset(f, 0, sizeof *f);
}

static double *dup_array(const double *a, size_t n)
{
    double *p = malloc(n * sizeof *p);
    if (p)
        memcpy(p, a, n * sizeof *p);
    return p;
}

int dp_forcing_copy(dp_forcing *dst, const dp_forcing *src)
{
    *dst = *src;
    dst->t = dst->F = NULL;
    dst->terms = NULL;
    dst->nterms = 0;
    if (src->kind == DP_FORCING_TABLE && src->n > 0) {
        dst->t = dup_array(src->t, src->n);
        dst->F = dup_array(src->F, src->n);
        if (!dst->t || !dst->F)
            goto fail;
    }
    if (src->kind == DP_FORCING_SUM && src->nterms > 0) {
        dst->terms = calloc(src->nterms, sizeof *dst->terms);
        if (!dst->terms)
            goto fail;
        for (size_t i = 0; i < src->nterms; i++) {
            dst->nterms = i + 1;
            if (dp_forcing_copy(&dst->terms[i], &src->terms[i]) != DP_OK)
                goto fail;
        }
    }
    return DP_OK;
fail:
    dp_forcing_clear(dst);
    return DP_ENOMEM;
}
