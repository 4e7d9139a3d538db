/* src/core/analysis/hurwitz.c - is a real polynomial Hurwitz? Two independent tests and an honest verdict.
 *
 * Test 1 (thesis Thm 1.1, Hurwitz): a0 z^n + ... + an with a0 > 0 has every root in Re z < 0 iff every leading
 * principal minor D_k of H_ij = a_(2i-j) (a_k = 0 outside 0..n) is positive. Each D_k is computed by Gaussian
 * elimination with partial pivoting and carries a rounding bound, so "D_k > 0" is only claimed beyond it.
 * Test 2: the roots (GSL gsl_poly_complex_solve: QR on the balanced companion matrix), each with an
 * a-posteriori error radius from the Taylor expansion of p about the computed root.
 * Near the boundary (a root within rounding of the imaginary axis) the tests may not decide; the verdict
 * then says so instead of guessing (dp_poly_analyse in stability.h).
 */
#include <complex.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_poly.h>

#include "dashpot/stability.h"

#define NMAX DP_STAB_MAX_DEGREE

/* GSL workspaces by degree, allocated when a degree is first solved: a request analyses one law, and
 * allocating all nine up front was half the cost of a small POST /v1/stability. */
struct dp_poly_ws {
    gsl_poly_complex_workspace *qr[NMAX + 1];    /* by degree (n + 1 coefficients), 2 .. NMAX */
};

const char *dp_verdict_name(dp_verdict v)
{
    switch (v) {
    case DP_VERDICT_STABLE: return "asymptotically stable";
    case DP_VERDICT_MARGINAL: return "marginally stable";
    case DP_VERDICT_UNSTABLE: return "unstable";
    case DP_VERDICT_BOUNDARY: return "near boundary";
    case DP_VERDICT_ILL_POSED: return "ill-posed";
    default: return "undecided";
    }
}

char dp_verdict_letter(dp_verdict v)
{
    static const char letters[] = "SMUBI?";
    return (unsigned)v < sizeof letters - 1 ? letters[v] : '?';
}

dp_poly_ws *dp_poly_ws_alloc(void)
{
    return calloc(1, sizeof(dp_poly_ws));
}

void dp_poly_ws_free(dp_poly_ws *w)
{
    if (w == NULL)
        return;
    for (int n = 0; n <= NMAX; n++)
        if (w->qr[n] != NULL)
            gsl_poly_complex_workspace_free(w->qr[n]);
    free(w);
}

static int finite_all(const double *a, int n)
{
    for (int i = 0; i <= n; i++)
        if (!isfinite(a[i]))
            return 0;
    return 1;
}

/* ---- test 1: Hurwitz minors ---- */

/* Determinant of the k x k row-major matrix m (destroyed) by elimination with partial pivoting; *growth is
 * max |entry of U| / max |entry of m| (>= 1), the factor by which the backward error can exceed k eps. */
static double det_gepp(double *m, int k, double *growth)
{
    double amax = 0.0, umax = 0.0, det = 1.0;
    for (int i = 0; i < k * k; i++)
        amax = fmax(amax, fabs(m[i]));
    for (int c = 0; c < k; c++) {
        int p = c;
        for (int r = c + 1; r < k; r++)
            if (fabs(m[r * k + c]) > fabs(m[p * k + c]))
                p = r;
        if (m[p * k + c] == 0.0) {
            *growth = 1.0;
            return 0.0;
        }
        if (p != c) {
            for (int j = 0; j < k; j++) {
                double t = m[c * k + j];
                m[c * k + j] = m[p * k + j];
                m[p * k + j] = t;
            }
            det = -det;
        }
        for (int r = c + 1; r < k; r++) {
            double f = m[r * k + c] / m[c * k + c];
            for (int j = c; j < k; j++)
                m[r * k + j] -= f * m[c * k + j];
        }
        for (int j = c; j < k; j++)
            umax = fmax(umax, fabs(m[c * k + j]));
        det *= m[c * k + c];
    }
    *growth = amax > 0.0 ? fmax(1.0, umax / amax) : 1.0;
    return det;
}

int dp_poly_hurwitz_minors(const double *a, int n, double *minor, double *tol)
{
    if (n < 1 || n > NMAX || a[0] == 0.0 || !finite_all(a, n))
        return DP_EINVAL;
    double m[NMAX * NMAX];
    for (int k = 1; k <= n; k++) {
        double rows = 1.0, growth;
        for (int i = 1; i <= k; i++) {
            double norm2 = 0.0;
            for (int j = 1; j <= k; j++) {
                int idx = 2 * i - j;
                double h = (idx < 0 || idx > n) ? 0.0 : a[idx];
                m[(i - 1) * k + (j - 1)] = h;
                norm2 += h * h;
            }
            rows *= sqrt(norm2);
        }
        minor[k - 1] = det_gepp(m, k, &growth);
        /* A computed det is the exact det of H + dH with |dH_i| <= ~ k eps growth |H_i| row by row (each
         * coefficient also carries one rounding from m lambda + mu); by Hadamard the det then moves by at most
         * k * that * prod |H_i|. The factor 8 covers the constants of the elimination error bound. */
        tol[k - 1] = 8.0 * (k + 1) * DBL_EPSILON * growth * rows;
    }
    return DP_OK;
}

dp_verdict dp_poly_hurwitz_verdict(const double *minor, const double *tol, int n)
{
    int undecided = 0;
    for (int k = 0; k < n; k++) {
        if (minor[k] < -tol[k])
            return DP_VERDICT_UNSTABLE;
        if (!(minor[k] > tol[k]))
            undecided = 1;
    }
    return undecided ? DP_VERDICT_UNDECIDED : DP_VERDICT_STABLE;
}

/* ---- test 2: roots ---- */

/* Error radius of a computed root z of a[0..n]: with c_k = p^(k)(z)/k! the Taylor coefficients about z and
 * r0 = |c_0| + (rounding of evaluating p near z, 4 (n+1) eps sum |a_i| |z|^(n-i)), the true root sits where
 * some term |c_k| r^k can balance r0: r = min_k (r0/|c_k|)^(1/k). k = 1 is Newton's correction for a simple
 * root; larger k take over inside clusters (a double root is only known to ~sqrt(eps)). */
static double root_radius(const double *a, int n, double complex z)
{
    double complex b[NMAX + 1];
    double az = cabs(z), s = 0.0;
    for (int i = 0; i <= n; i++) {
        b[i] = a[i];
        s = s * az + fabs(a[i]);
    }
    double r0 = 0.0, r = INFINITY;
    for (int k = 0, m = n; k <= n; k++, m--) {
        for (int i = 1; i <= m; i++)
            b[i] += b[i - 1] * z;
        double ck = cabs(b[m]);
        if (k == 0)
            r0 = ck + 4.0 * (n + 1) * DBL_EPSILON * s;
        else if (ck > 0.0)
            r = fmin(r, k == 1 ? r0 / ck : pow(r0 / ck, 1.0 / k));
    }
    return r;
}

int dp_poly_roots(dp_poly_ws *w, const double *a, int n, double *re, double *im, double *err)
{
    if (n < 0 || n > NMAX || a[0] == 0.0 || !finite_all(a, n))
        return DP_EINVAL;
    int zeros = 0;
    while (zeros < n && a[n - zeros] == 0.0) {     /* exact roots at 0: p = z^zeros q(z) */
        re[n - 1 - zeros] = im[n - 1 - zeros] = err[n - 1 - zeros] = 0.0;
        zeros++;
    }
    int d = n - zeros;
    if (d == 1) {
        re[0] = -a[1] / a[0];
        im[0] = 0.0;
    } else if (d >= 2) {
        double asc[NMAX + 1], z[2 * NMAX];
        for (int i = 0; i <= d; i++)
            asc[i] = a[d - i];
        if (w->qr[d] == NULL && (w->qr[d] = gsl_poly_complex_workspace_alloc((size_t)d + 1)) == NULL)
            return DP_ENOMEM;
        if (gsl_poly_complex_solve(asc, (size_t)d + 1, w->qr[d], z) != GSL_SUCCESS)
            return DP_ESOLVE;
        for (int i = 0; i < d; i++) {
            re[i] = z[2 * i];
            im[i] = z[2 * i + 1];
        }
    }
    for (int i = 0; i < d; i++) {
        if (!isfinite(re[i]) || !isfinite(im[i]))
            return DP_ESOLVE;
        err[i] = root_radius(a, n, re[i] + im[i] * I); /* finite parts: exact (CMPLX is GCC-only in glibc) */
    }
    return DP_OK;
}

/* The roots' own opinion. *marginal_ok: every root is either certainly left or on the axis within its radius,
 * and the ones on the axis are simple (their discs do not overlap). */
static dp_verdict roots_verdict(const dp_poly_report *r, int *marginal_ok)
{
    int n = r->degree, right = 0, undecided = 0;
    *marginal_ok = 1;
    for (int i = 0; i < n; i++) {
        double x = r->root_re[i], e = r->root_err[i];
        if (x - e > 0.0)
            right = 1;
        else if (!(x + e < 0.0)) {
            undecided = 1;
            for (int j = 0; j < n; j++) {
                double dx = x - r->root_re[j], dy = r->root_im[i] - r->root_im[j];
                if (j != i && fabs(r->root_re[j]) <= r->root_err[j] && hypot(dx, dy) <= e + r->root_err[j])
                    *marginal_ok = 0;
            }
        }
    }
    if (right) {
        *marginal_ok = 0;
        return DP_VERDICT_UNSTABLE;
    }
    return undecided ? DP_VERDICT_UNDECIDED : DP_VERDICT_STABLE;
}

static dp_verdict combine(dp_verdict h, dp_verdict r, int marginal_ok, int *near)
{
    *near = (h == DP_VERDICT_UNDECIDED || r == DP_VERDICT_UNDECIDED);
    if (h == r)
        return h != DP_VERDICT_UNDECIDED ? h : (marginal_ok ? DP_VERDICT_MARGINAL : DP_VERDICT_BOUNDARY);
    if (h == DP_VERDICT_UNDECIDED)
        return r;
    if (r == DP_VERDICT_UNDECIDED)
        return h;
    *near = 1;                 /* certain and contradicting: the rounding bounds were too optimistic */
    return DP_VERDICT_BOUNDARY;
}

/* Copies a[0..n] into r->a without leading zeros and with a[0] > 0; sets r->degree (-1 for p == 0). */
static void normalise(const double *a, int n, dp_poly_report *r)
{
    int lead = 0;
    while (lead <= n && a[lead] == 0.0)
        lead++;
    r->degree = n - lead;
    double sign = (lead <= n && a[lead] < 0.0) ? -1.0 : 1.0;
    for (int i = 0; i <= r->degree; i++)
        r->a[i] = sign * a[lead + i];
}

static int trailing_zeros(const double *a, int n)
{
    int z = 0;
    while (z < n && a[n - z] == 0.0)
        z++;
    return z;
}

static void set_abscissa(dp_poly_report *r)
{
    r->has_abscissa = r->degree > 0;
    r->abscissa = r->abscissa_err = 0.0;
    for (int i = 0; i < r->degree; i++)
        if (i == 0 || r->root_re[i] > r->abscissa) {
            r->abscissa = r->root_re[i];
            r->abscissa_err = r->root_err[i];
        }
}

/* Degrees -1 and 0 have no roots and no minors. */
static void trivial(dp_poly_report *r)
{
    dp_verdict v = r->degree < 0 ? DP_VERDICT_ILL_POSED : DP_VERDICT_STABLE;
    r->by_hurwitz = r->by_roots = r->verdict = v;
    r->near_boundary = 0;
    r->has_abscissa = 0;
    r->abscissa = r->abscissa_err = 0.0;
}

int dp_poly_analyse(dp_poly_ws *w, const double *a, int n, dp_poly_report *r)
{
    if (n < 0 || n > NMAX || !finite_all(a, n))
        return DP_EINVAL;
    normalise(a, n, r);
    if (r->degree <= 0) {
        trivial(r);
        return DP_OK;
    }
    int s = dp_poly_hurwitz_minors(r->a, r->degree, r->minor, r->minor_tol);
    if (s == DP_OK)
        s = dp_poly_roots(w, r->a, r->degree, r->root_re, r->root_im, r->root_err);
    if (s != DP_OK)
        return s;
    set_abscissa(r);
    int marginal_ok;
    r->by_hurwitz = dp_poly_hurwitz_verdict(r->minor, r->minor_tol, r->degree);
    r->by_roots = roots_verdict(r, &marginal_ok);
    r->verdict = combine(r->by_hurwitz, r->by_roots, marginal_ok, &r->near_boundary);
    if (trailing_zeros(r->a, r->degree) >= 2) {    /* an exact multiple root at 0: x = t solves */
        r->by_roots = r->verdict = DP_VERDICT_UNSTABLE;
        r->near_boundary = 0;
    }
    return DP_OK;
}

int dp_poly_verdict(dp_poly_ws *w, const double *a, int n, dp_verdict *v, double *abscissa, int *has_abscissa)
{
    dp_poly_report r;
    if (abscissa == NULL) {           /* fast path: the minors alone, when they are beyond rounding */
        if (n < 0 || n > NMAX || !finite_all(a, n))
            return DP_EINVAL;
        normalise(a, n, &r);
        if (r.degree >= 1 && trailing_zeros(r.a, r.degree) < 2
            && dp_poly_hurwitz_minors(r.a, r.degree, r.minor, r.minor_tol) == DP_OK) {
            dp_verdict h = dp_poly_hurwitz_verdict(r.minor, r.minor_tol, r.degree);
            if (h != DP_VERDICT_UNDECIDED) {
                *v = h;
                return DP_OK;
            }
        }
    }
    int s = dp_poly_analyse(w, a, n, &r);
    if (s != DP_OK)
        return s;
    *v = r.verdict;
    if (abscissa != NULL)
        *abscissa = r.abscissa;
    if (has_abscissa != NULL)
        *has_abscissa = r.has_abscissa;
    return DP_OK;
}
