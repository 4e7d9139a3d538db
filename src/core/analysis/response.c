/* src/core/analysis/response.c - the receptance H_ji(omega) = [(K - omega^2 M + i omega C)^-1]_ji of node j to a
 * harmonic force at node i (Höschl's dynamic compliance, 003 §10 (10.36), Ex. 29), with its resonances and
 * antiresonances.
 *
 * Why a modal sum first: with the M-normalized shapes, H_ji = sum_k phi_jk phi_ik / (omega_k^2 - omega^2 +
 * i omega c_k), c_k = phi_k^T C phi_k, is exact when C is absent or proportional (Phi^T C Phi diagonal,
 * Rayleigh damping among others) and costs O(n) a frequency. A general C takes a complex LU solve per
 * frequency, held to a work budget.
 *
 * Resonances are the undamped natural frequencies whose modes node i excites and node j sees (a pole's
 * residue, summed over a repeated eigenvalue's modes, not zero). Antiresonances are the zeros of the
 * undamped H_ji(lambda = omega^2), a sum of simple poles: between two poles it is continuous, so its sign
 * changes are bracketed on a grid crowded towards the poles and each is refined by Brent's method; they
 * are located, not read off the samples.
 *
 * Finite through: a term of the modal sum whose textbook form a (dr - i di) / (dr^2 + di^2) would over- or
 * underflow is divided by Smith's rule instead, and a dynamic stiffness K - omega^2 M + i omega C beyond
 * 2^+-256 is scaled by a power of two before its LU; a receptance that is still not finite (and not an
 * undamped system exactly at a resonance) is DP_ENONFINITE, never a NaN on the wire. The stop hook is asked
 * before every point and between the located zeros.
 */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_complex.h>
#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_roots.h>

#include "dashpot/modes.h"

/* points * n^3 beyond which a general-damping response is refused (a few seconds of LU). */
#define DIRECT_WORK_MAX 2e10
#define RESIDUE_TOL 1e-10
#define GROUP_TOL 1e-10
#define BRACKET_SAMPLES 64

void dp_response_free(dp_response *r)
{
    if (r == NULL)
        return;
    free(r->point);
    free(r->resonance);
    free(r->resonance_mode);
    free(r->antiresonance);
    memset(r, 0, sizeof *r);
}

/* The undamped receptance as simple poles: lambda_g (distinct, ascending) with residues a_g. */
typedef struct poles {
    size_t m;
    double *lambda, *a;
    size_t *mode;      /* the first mode of each group */
} poles;

static int gather_poles(const dp_modes *md, size_t i, size_t j, poles *p)
{
    size_t n = md->n;
    p->m = 0;
    p->lambda = malloc(n * sizeof *p->lambda);
    p->a = malloc(n * sizeof *p->a);
    p->mode = malloc(n * sizeof *p->mode);
    if (!p->lambda || !p->a || !p->mode)
        return DP_ENOMEM;
    double amax = 0;
    for (size_t k = 0; k < n; k++)
        amax = fmax(amax, fabs(md->shape[k * n + j] * md->shape[k * n + i]));
    for (size_t k = 0; k < n;) {
        size_t l = k;
        double a = 0, scale = fmax(fabs(md->lambda[k]), 1e-300);
        for (; l < n && fabs(md->lambda[l] - md->lambda[k]) <= GROUP_TOL * scale; l++)
            a += md->shape[l * n + j] * md->shape[l * n + i];
        if (fabs(a) > RESIDUE_TOL * amax) {
            p->lambda[p->m] = md->lambda[k];
            p->a[p->m] = a;
            p->mode[p->m++] = k;
        }
        k = l;
    }
    return DP_OK;
}

static double undamped_h(double lambda, void *ctx)
{
    const poles *p = ctx;
    double h = 0;
    for (size_t g = 0; g < p->m; g++)
        h += p->a[g] / (p->lambda[g] - lambda);
    return h;
}

static double brent(poles *p, double a, double b)
{
    gsl_function f = { undamped_h, p };
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (s == NULL || gsl_root_fsolver_set(s, &f, a, b) != GSL_SUCCESS) {
        gsl_root_fsolver_free(s);
        return 0.5 * (a + b);
    }
    double r = 0.5 * (a + b);
    for (int it = 0; it < 200; it++) {
        if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS)
            break;
        r = gsl_root_fsolver_root(s);
        double lo = gsl_root_fsolver_x_lower(s), hi = gsl_root_fsolver_x_upper(s);
        if (gsl_root_test_interval(lo, hi, 0, 4e-16) == GSL_SUCCESS)
            break;
    }
    gsl_root_fsolver_free(s);
    return r;
}

/* The zeros of the undamped H in (a, b), an interval free of poles (ends may be poles or range ends). */
static int zeros_between(poles *p, double a, double b, double *out, size_t *nout, size_t cap)
{
    double prev_l = a, prev_h = NAN;
    for (int s = 0; s <= BRACKET_SAMPLES; s++) {
        double t = (double)s / BRACKET_SAMPLES, l = a + (b - a) * 0.5 * (1 - cos(M_PI * t));
        double h = undamped_h(l, p);
        if (!isfinite(h) || (s > 0 && l <= prev_l)) /* a pole at the end, or no room left */
            continue;
        if (h == 0 && *nout < cap)
            out[(*nout)++] = l;
        else if (isfinite(prev_h) && prev_h != 0 && (prev_h < 0) != (h < 0) && *nout < cap)
            out[(*nout)++] = brent(p, prev_l, l);
        prev_l = l;
        prev_h = h;
    }
    return DP_OK;
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* Resonances and antiresonances of the undamped system inside [from, to]. */
static int locate(const dp_modes *md, size_t i, size_t j, double from, double to, const dp_stop *stop,
                  dp_response *out)
{
    poles p = { 0 };
    int s = gather_poles(md, i, j, &p);
    size_t cap = p.m + 4; /* H = (polynomial of degree < m in lambda) / (product of m poles) */
    out->resonance = malloc((p.m + 1) * sizeof *out->resonance);
    out->resonance_mode = malloc((p.m + 1) * sizeof *out->resonance_mode);
    double *z = malloc(cap * sizeof *z);
    if (s == DP_OK && (!out->resonance || !out->resonance_mode || !z))
        s = DP_ENOMEM;
    for (size_t g = 0; s == DP_OK && g < p.m; g++) {
        double w = sqrt(p.lambda[g]);
        if (w >= from && w <= to && p.lambda[g] > 0) {
            out->resonance[out->nres] = w;
            out->resonance_mode[out->nres++] = p.mode[g];
        }
    }
    size_t nz = 0;
    double lo = from * from, hi = to * to;
    for (size_t g = 0; s == DP_OK && p.m > 0 && g <= p.m; g++) {
        if (dp_stop_now(stop)) {
            s = DP_ECANCEL;
            break;
        }
        double a = g == 0 ? lo : fmax(lo, p.lambda[g - 1]), b = g == p.m ? hi : fmin(hi, p.lambda[g]);
        if (b > a)
            zeros_between(&p, a, b, z, &nz, cap);
    }
    if (s == DP_OK) {
        qsort(z, nz, sizeof *z, cmp_double);
        for (size_t k = 0; k < nz; k++)
            z[k] = sqrt(fmax(z[k], 0));
        out->antiresonance = z;
        out->nanti = nz;
        z = NULL;
    }
    free(z);
    free(p.lambda);
    free(p.a);
    free(p.mode);
    return s;
}

/* c_k = phi_k^T C phi_k (0 without C). */
static int modal_c(size_t n, const double *C, const dp_modes *md, double *c)
{
    for (size_t k = 0; k < n; k++) {
        c[k] = 0;
        if (!md->damped)
            continue;
        const double *phi = md->shape + k * n;
        for (size_t r = 0; r < n; r++) {
            double row = 0;
            for (size_t q = 0; q < n; q++)
                row += C[r * n + q] * phi[q];
            c[k] += phi[r] * row;
        }
    }
    return DP_OK;
}

static void set_point(dp_response_point *pt, double omega, double re, double im)
{
    pt->omega = omega;
    pt->re = re;
    pt->im = im;
    int finite = isfinite(re) && isfinite(im);
    pt->magnitude = finite ? hypot(re, im) : NAN;
    pt->phase = finite ? atan2(im, re) : NAN;
    if (finite && pt->phase == -M_PI)
        pt->phase = M_PI;
}

/* re + i im += a / (dr + i di): the textbook form when it stays in range (the common case, bit for bit as
 * always), Smith's rule when dr^2 + di^2 or a dr would over- or underflow. */
static void add_term(double a, double dr, double di, double *re, double *im)
{
    double d2 = dr * dr + di * di, tr = a * dr / d2, ti = a * di / d2;
    if (isfinite(d2) && d2 >= DBL_MIN && isfinite(tr) && isfinite(ti)) {
        *re += tr;
        *im -= ti;
    } else if (fabs(dr) >= fabs(di)) {
        double r = di / dr, den = dr + di * r;
        *re += a / den;
        *im -= a * r / den;
    } else {
        double r = dr / di, den = di + dr * r;
        *re += a * r / den;
        *im -= a / den;
    }
}

static void modal_point(const dp_modes *md, const double *c, size_t i, size_t j, double w, dp_response_point *pt)
{
    size_t n = md->n;
    double re = 0, im = 0;
    for (size_t k = 0; k < n; k++) {
        double a = md->shape[k * n + j] * md->shape[k * n + i];
        if (a == 0)
            continue;
        double dr = md->lambda[k] - w * w, di = w * c[k];
        if (dr == 0 && di == 0) { /* undamped, exactly at a resonance (or omega = 0 with a rigid mode) */
            re = INFINITY;
            break;
        }
        add_term(a, dr, di, &re, &im);
    }
    set_point(pt, w, re, im);
}

/* The largest entries of M, K, C: the scale of the dynamic stiffness at each frequency. */
typedef struct scales {
    double m, k, c;
} scales;

/* The power of two the dynamic stiffness at w is divided by: 0 when it is within 2^+-256 (bit for bit as
 * always), otherwise the exponent of its largest entry, found without forming it. */
static int dynamic_scale(const scales *sc, double w)
{
    double big = sc->k + w * (w * sc->m) + w * sc->c;
    if (isfinite(big) && big <= 0x1p256 && big >= 0x1p-256)
        return 0;
    int e = INT_MIN / 4, ew = w > 0 && isfinite(w) ? ilogb(w) : 0;
    if (sc->k > 0)
        e = ilogb(sc->k);
    if (sc->m > 0 && w > 0 && ilogb(sc->m) + 2 * ew > e)
        e = ilogb(sc->m) + 2 * ew;
    if (sc->c > 0 && w > 0 && ilogb(sc->c) + ew > e)
        e = ilogb(sc->c) + ew;
    return e == INT_MIN / 4 ? 0 : e;
}

static int direct_point(size_t n, const double *M, const double *K, const double *C, const scales *sc, size_t i,
                        size_t j, double w, gsl_matrix_complex *A, gsl_vector_complex *x, gsl_permutation *perm,
                        dp_response_point *pt)
{
    int p = dynamic_scale(sc, w);
    for (size_t r = 0; r < n; r++)
        for (size_t q = 0; q < n; q++) {
            size_t rq = r * n + q;
            double re = p == 0 ? K[rq] - w * w * M[rq] : ldexp(K[rq], -p) - w * (w * ldexp(M[rq], -p));
            double im = p == 0 ? w * C[rq] : w * ldexp(C[rq], -p);
            gsl_matrix_complex_set(A, r, q, gsl_complex_rect(re, im));
        }
    int sign;
    gsl_vector_complex_set_basis(x, i);
    if (gsl_linalg_complex_LU_decomp(A, perm, &sign) != GSL_SUCCESS ||
        gsl_linalg_complex_LU_svx(A, perm, x) != GSL_SUCCESS) {
        set_point(pt, w, INFINITY, 0);
        return DP_OK;
    }
    gsl_complex h = gsl_vector_complex_get(x, j);
    set_point(pt, w, ldexp(GSL_REAL(h), -p), ldexp(GSL_IMAG(h), -p));
    return isfinite(pt->re) && isfinite(pt->im) ? DP_OK : DP_ENONFINITE;
}

static double largest(size_t n, const double *A)
{
    double a = 0;
    for (size_t k = 0; A && k < n * n; k++)
        a = fmax(a, fabs(A[k]));
    return a;
}

/* A modal point is infinite only at an exact undamped resonance; anything else not finite is an overflow. */
static int modal_finite(const dp_response_point *pt)
{
    return (isfinite(pt->re) && isfinite(pt->im)) || (pt->re == INFINITY && pt->im == 0);
}

static int sample(size_t n, const double *M, const double *K, const double *C, const dp_modes *md, size_t i,
                  size_t j, double from, double to, size_t points, int log_spacing, const dp_stop *stop,
                  dp_response *out)
{
    int direct = md->damped && !md->proportional;
    if (direct && (double)points * n * n * n > DIRECT_WORK_MAX)
        return DP_ELIMIT;
    const scales sc = { largest(n, M), largest(n, K), direct ? largest(n, C) : 0 };
    double *c = malloc(n * sizeof *c);
    gsl_matrix_complex *A = direct ? gsl_matrix_complex_alloc(n, n) : NULL;
    gsl_vector_complex *x = direct ? gsl_vector_complex_alloc(n) : NULL;
    gsl_permutation *perm = direct ? gsl_permutation_alloc(n) : NULL;
    int s = c && (!direct || (A && x && perm)) ? modal_c(n, C, md, c) : DP_ENOMEM;
    for (size_t k = 0; s == DP_OK && k < n; k++)
        s = isfinite(c[k]) ? DP_OK : DP_ENONFINITE;
    for (size_t k = 0; s == DP_OK && k < points; k++) {
        if (dp_stop_now(stop)) {
            s = DP_ECANCEL;
            break;
        }
        double t = points == 1 ? 0 : (double)k / (double)(points - 1);
        double ratio = to / from, w = !log_spacing ? from + (to - from) * t
                                    : isfinite(ratio) ? from * pow(ratio, t) /* as always */
                                                      : exp(log(from) + t * (log(to) - log(from)));
        if (k + 1 == points)
            w = to;
        if (direct)
            s = direct_point(n, M, K, C, &sc, i, j, w, A, x, perm, &out->point[k]);
        else {
            modal_point(md, c, i, j, w, &out->point[k]);
            s = modal_finite(&out->point[k]) ? DP_OK : DP_ENONFINITE;
        }
    }
    gsl_permutation_free(perm);
    gsl_vector_complex_free(x);
    gsl_matrix_complex_free(A);
    free(c);
    return s;
}

int dp_response_solve(size_t n, const double *M, const double *K, const double *C, const dp_modes *modes,
                      size_t i, size_t j, double from, double to, size_t points, int log_spacing,
                      dp_response *out)
{
    return dp_response_solve_until(n, M, K, C, modes, i, j, from, to, points, log_spacing, NULL, out);
}

int dp_response_solve_until(size_t n, const double *M, const double *K, const double *C, const dp_modes *modes,
                            size_t i, size_t j, double from, double to, size_t points, int log_spacing,
                            const dp_stop *stop, dp_response *out)
{
    memset(out, 0, sizeof *out);
    if (i >= n || j >= n || !(from >= 0) || !(to >= from) || points == 0 || (log_spacing && !(from > 0)))
        return DP_EINVAL;
    out->point = malloc(points * sizeof *out->point);
    if (out->point == NULL)
        return DP_ENOMEM;
    out->npoints = points;
    int s = sample(n, M, K, C, modes, i, j, from, to, points, log_spacing, stop, out);
    return s ? s : locate(modes, i, j, from, to, stop, out);
}
