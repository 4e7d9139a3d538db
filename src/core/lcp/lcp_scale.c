/* src/core/lcp/lcp_scale.c - the equilibration of an LCP by powers of two and the relative acceptance test of
 * a candidate solution (lcp_scale.h has why). Lemke's method, the enumeration and the P-matrix test all work on
 * the scaled problem; the answer goes back to the problem's units only at the end, checked to stay finite.
 */
#include <math.h>
#include <string.h>

#include "lcp/lcp_scale.h"

/* An entry of z this far below its largest, on the equilibrated problem, is rounding (an LU solve's, a
 * tableau's) when keeping it fails the test: a degenerate component that is 0 in exact arithmetic. */
#define Z_ROUNDING 1e-14

/* Binades of q kept below its largest entry before the scaling lets the largest grow instead. */
#define Q_SPAN 1000

/* The exponent that brings x != 0 into [1, 2): -floor(log2 |x|), subnormal numbers included; 0 for 0. */
static int exponent_to_one(double x)
{
    return x == 0 ? 0 : -ilogb(x);
}

int lcp_equilibrate(const gsl_matrix *M, const gsl_vector *q, double *Ms, double *qs, lcp_scaling *sc)
{
    size_t m = M->size1;
    for (size_t i = 0; i < m; i++) {
        double big = 0;
        for (size_t j = 0; j < m; j++) {
            double x = M->data[i * M->tda + j];
            if (!isfinite(x))
                return 0;
            big = fmax(big, fabs(x));
        }
        sc->r[i] = exponent_to_one(big);
    }
    /* Columns after rows: each row's largest entry is in [1, 2), so a column's largest is at most 2. */
    for (size_t j = 0; j < m; j++) {
        double big = 0;
        for (size_t i = 0; i < m; i++)
            big = fmax(big, fabs(ldexp(M->data[i * M->tda + j], sc->r[i])));
        sc->c[j] = exponent_to_one(big);
    }
    for (size_t i = 0; i < m; i++)
        for (size_t j = 0; j < m; j++) /* one ldexp from the original: no double rounding of tiny entries */
            Ms[i * m + j] = ldexp(M->data[i * M->tda + j], sc->r[i] + sc->c[j]);
    sc->s = 0;
    if (q == NULL)
        return 1;
    int have = 0, top = 0, bottom = 0;
    for (size_t i = 0; i < m; i++) {
        double x = q->data[i * q->stride];
        if (!isfinite(x))
            return 0;
        if (x != 0) {
            int e = ilogb(x) + sc->r[i]; /* the exponent of 2^r_i q_i, formed without forming it */
            top = have && top > e ? top : e;
            bottom = have && bottom < e ? bottom : e;
            have = 1;
        }
    }
    /* q's largest entry to [1, 2), unless its entries span more than Q_SPAN binades: then its smallest to
     * 2^-Q_SPAN, so that none is lost below the normal numbers (the largest stays below 2^(1023 - Q_SPAN + ...)). */
    sc->s = top - bottom <= Q_SPAN ? top : bottom + Q_SPAN;
    for (size_t i = 0; i < m; i++)
        qs[i] = ldexp(q->data[i * q->stride], sc->r[i] - sc->s);
    return 1;
}

/* s_i = |q_i| + Σ_j |M_ij z_j|, row i's terms at z; then infl_j = max_i |M_ij| / s_i (0 for a zero column):
 * setting z_j to 0 changes no w_i by more than |z_j| infl_j of its row's terms. */
static void sizes_and_influence(const gsl_matrix *M, const gsl_vector *q, const double *z, long double *size,
                                long double *infl)
{
    size_t m = M->size1;
    for (size_t i = 0; i < m; i++) {
        const double *Mi = M->data + i * M->tda;
        long double t = fabsl((long double)q->data[i * q->stride]);
        for (size_t j = 0; j < m; j++)
            t += fabsl((long double)Mi[j] * z[j]);
        size[i] = t;
        infl[i] = 0;
    }
    for (size_t i = 0; i < m; i++) {
        const double *Mi = M->data + i * M->tda;
        if (size[i] == 0)
            continue; /* every term of the row is 0: nothing in it to compare with */
        for (size_t j = 0; j < m; j++)
            infl[j] = fmaxl(infl[j], fabsl((long double)Mi[j]) / size[i]);
    }
}

/* Whether column j of M is zero: a z_j no row can see. */
static int zero_column(const gsl_matrix *M, size_t j)
{
    for (size_t i = 0; i < M->size1; i++)
        if (M->data[i * M->tda + j] != 0)
            return 0;
    return 1;
}

/* w_i = q_i + Σ_j M_ij z_j in long double. */
static long double row_value(const gsl_matrix *M, const gsl_vector *q, const double *z, size_t i)
{
    const double *Mi = M->data + i * M->tda;
    long double acc = q->data[i * q->stride];
    for (size_t j = 0; j < M->size2; j++)
        acc += (long double)Mi[j] * z[j];
    return acc;
}

/* The violations of z, each relative to its row's terms (lcp_scale.h), the largest; zero[j] = 1 where z_j
 * must go to 0 to settle (negative, or positive beside a w_j that is relatively larger). */
static double violations(const gsl_matrix *M, const gsl_vector *q, const double *z, long double *scratch,
                         char *zero)
{
    size_t m = M->size1;
    long double *size = scratch, *infl = scratch + m, worst = 0;
    sizes_and_influence(M, q, z, size, infl);
    for (size_t i = 0; i < m; i++) {
        long double wi = row_value(M, q, z, i), si = size[i];
        long double wr = si > 0 ? fabsl(wi) / si : (wi != 0 ? (long double)INFINITY : 0.0L);
        long double zr = zero_column(M, i) ? (z[i] < 0 ? (long double)INFINITY : 0.0L)
                                           : fabsl((long double)z[i]) * infl[i];
        zero[i] = z[i] < 0;
        if (wi < 0)
            worst = fmaxl(worst, wr);
        if (z[i] < 0)
            worst = fmaxl(worst, zr);
        if (z[i] > 0 && wi > 0) {
            worst = fmaxl(worst, fminl(wr, zr));
            zero[i] = zr < wr;
        }
    }
    return (double)worst;
}

/* z with the entries that are rounding next to its largest, on the equilibrated problem, set to 0. */
static void clean(size_t m, const lcp_scaling *sc, const double *z, double *zc)
{
    double big = 0;
    for (size_t j = 0; j < m; j++)
        big = fmax(big, fabs(ldexp(z[j], -sc->c[j])));
    for (size_t j = 0; j < m; j++)
        zc[j] = fabs(ldexp(z[j], -sc->c[j])) <= Z_ROUNDING * big ? 0.0 : z[j];
}

double lcp_settle(const gsl_matrix *M, const gsl_vector *q, const lcp_scaling *sc, double *z, double *w,
                  long double *scratch, int *finite)
{
    size_t m = M->size1;
    char *zero = (char *)(scratch + 2 * m); /* 2m long doubles, then m flags */
    double worst = violations(M, q, z, scratch, zero);
    if (worst > LCP_ACCEPT) { /* a degenerate entry computed as rounding instead of 0? */
        clean(m, sc, z, w);
        double again = violations(M, q, w, scratch, zero);
        if (again < worst)
            memcpy(z, w, m * sizeof *z), worst = again;
        else
            violations(M, q, z, scratch, zero);
    }
    for (size_t j = 0; j < m; j++)
        z[j] = zero[j] ? 0.0 : z[j];
    *finite = 1;
    for (size_t i = 0; i < m; i++) { /* w of the settled z: w_i = 0 beside z_i > 0, rounding below 0 cleared */
        long double wi = row_value(M, q, z, i);
        w[i] = z[i] > 0 || wi < 0 ? 0.0 : (double)wi;
        *finite &= isfinite(w[i]);
    }
    return worst;
}

int lcp_unscale(size_t m, const lcp_scaling *sc, const double *zs, const double *ws, double *zo, double *wo)
{
    int ok = 1;
    for (size_t j = 0; j < m; j++) {
        zo[j] = ldexp(zs[j], sc->c[j] + sc->s);
        ok &= isfinite(zo[j]);
    }
    for (size_t i = 0; ws && i < m; i++) {
        wo[i] = ldexp(ws[i], sc->s - sc->r[i]);
        ok &= isfinite(wo[i]);
    }
    return ok;
}
