/* src/core/base/tridiag.c - all eigenpairs of a symmetric tridiagonal matrix in O(n^2) (plus reorthogonalization
 * inside clusters): the chain route of modes.c.
 *
 * Why not a library: GSL has no tridiagonal eigensolver (its symmv is O(n^3) whatever the structure), and
 * LAPACK's would add a Fortran runtime (and, on Debian, whichever BLAS the alternatives system picks) to
 * every binary. The method is the classical one (LAPACK's dstebz + dstein):
 *   - the matrix splits where an off-diagonal is negligible against its neighbours (relative test);
 *   - eigenvalues by the implicit QL method without vectors (O(n^2) rotations, accurate to eps ||T||),
 *     and those below 1e-6 ||T|| again by bisection on the Sturm count (the inertia of T - x I from its
 *     LDL^T pivots) to a relative tolerance, so the small eigenvalues of a graded matrix (a badly scaled
 *     chain) keep the digits the count gives them; bisection alone if QL does not converge;
 *   - eigenvectors by inverse iteration with a pivoted tridiagonal LU from a fixed pseudo-random start
 *     (one solve when it grows the start as an accurate eigenvalue makes it, up to 3 otherwise), re-orthogonalized (modified Gram-Schmidt) against the vectors of eigenvalues closer than
 *     1e-3 ||T|| in the same block, as dstein does.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/tridiag.h"

#define CLUSTER 1e-3
#define SWEEPS 3

/* Eigenvalues of the block below x (d, e of length m, m - 1). */
static size_t sturm_count(size_t m, const double *d, const double *e, double x, double pivmin)
{
    size_t count = 0;
    double q = d[0] - x;
    for (size_t i = 0;; i++) {
        if (fabs(q) < pivmin)
            q = -pivmin;
        count += q < 0;
        if (i + 1 == m)
            return count;
        q = d[i + 1] - x - e[i] * e[i] / q;
    }
}

/* The k-th smallest eigenvalue of the block in [lo, hi], by bisection to relative accuracy. */
static double bisect(size_t m, const double *d, const double *e, size_t k, double lo, double hi, double pivmin)
{
    for (int it = 0; it < 400; it++) {
        double width = hi - lo, scale = fmax(fabs(lo), fabs(hi));
        if (width <= 2 * DBL_EPSILON * scale || width <= pivmin)
            break;
        double mid = lo > 0 && hi > 4 * lo ? sqrt(lo) * sqrt(hi) : hi < 0 && lo < 4 * hi ? -sqrt(-lo) * sqrt(-hi)
                                                                                     : lo + 0.5 * width;
        if (!(mid > lo && mid < hi))
            break;
        if (sturm_count(m, d, e, mid, pivmin) > k)
            hi = mid;
        else
            lo = mid;
    }
    return lo + 0.5 * (hi - lo);
}

/* sqrt(a^2 + b^2) without hypot's care (a rotation's cost is mostly this), falling back to it on overflow
 * (entries beyond 1e154) or underflow. */
static double radius(double a, double b)
{
    double r = sqrt(a * a + b * b);
    return isfinite(r) && r > 1e-150 ? r : hypot(a, b);
}

/* Eigenvalues of the block (copies d, e; e[m-1] = 0) by the implicit QL method with Wilkinson shifts
 * (Numerical Recipes' tqli without vectors). 0, or -1 when an eigenvalue needs more than 60 sweeps. */
static int ql_values(size_t m, double *d, double *e)
{
    for (size_t l = 0; l < m; l++) {
        int iter = 0;
        size_t k;
        do {
            for (k = l; k + 1 < m; k++) {
                double dd = fabs(d[k]) + fabs(d[k + 1]);
                if (fabs(e[k]) <= DBL_EPSILON * dd)
                    break;
            }
            if (k == l)
                break;
            if (iter++ == 60)
                return -1;
            double g = (d[l + 1] - d[l]) / (2 * e[l]), r = radius(g, 1.0);
            g = d[k] - d[l] + e[l] / (g + (g >= 0 ? r : -r));
            double s = 1, c = 1, p = 0;
            int underflow = 0;
            for (size_t i = k; i-- > l;) {
                double f = s * e[i], b = c * e[i];
                e[i + 1] = r = radius(f, g);
                if (r == 0) {
                    d[i + 1] -= p;
                    e[k] = 0;
                    underflow = 1;
                    break;
                }
                s = f / r;
                c = g / r;
                g = d[i + 1] - p;
                r = (d[i] - g) * s + 2 * c * b;
                d[i + 1] = g + (p = s * r);
                g = c * r - b;
            }
            if (underflow)
                continue;
            d[l] -= p;
            e[l] = g;
            e[k] = 0;
        } while (1);
    }
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Eigenvalues of the k-th block into lw (ascending); work holds 2m doubles. */
static void block_values(size_t m, const double *d, const double *e, double pivmin, double *lw, double *work)
{
    double lo = INFINITY, hi = -INFINITY, norm = 0;
    for (size_t i = 0; i < m; i++) {
        double r = (i > 0 ? fabs(e[i - 1]) : 0) + (i + 1 < m ? fabs(e[i]) : 0);
        lo = fmin(lo, d[i] - r);
        hi = fmax(hi, d[i] + r);
        norm = fmax(norm, fabs(d[i]) + r);
    }
    if (m == 1) { /* exact */
        lw[0] = d[0];
        return;
    }
    double pad = 2 * DBL_EPSILON * fmax(fabs(lo), fabs(hi)) + pivmin;
    lo -= pad, hi += pad;
    double *dc = work, *ec = work + m;
    for (size_t i = 0; i < m; i++) {
        dc[i] = d[i];
        ec[i] = i + 1 < m ? e[i] : 0;
    }
    int ql = ql_values(m, dc, ec);
    if (ql == 0) {
        qsort(dc, m, sizeof *dc, cmp_double);
        memcpy(lw, dc, m * sizeof *lw);
    }
    for (size_t k = 0; k < m; k++)
        if (ql != 0 || fabs(lw[k]) < 1e-6 * norm)
            lw[k] = bisect(m, d, e, k, lo, hi, pivmin);
}

/* The pivoted LU of T - lambda I (LAPACK's dgttrf) into w (4m doubles + m bytes), pivots below `tiny`
 * raised to it (lambda is an eigenvalue: the matrix is singular to working precision); the diagonal of U
 * is stored inverted, so that each solve multiplies. */
static void shifted_factor(size_t m, const double *d, const double *e, double lambda, double tiny, double *w)
{
    double *dl = w, *dd = w + m, *du = w + 2 * m, *du2 = w + 3 * m;
    unsigned char *swap = (unsigned char *)(w + 4 * m);
    for (size_t i = 0; i < m; i++) {
        dd[i] = d[i] - lambda;
        dl[i] = du[i] = i + 1 < m ? e[i] : 0;
        du2[i] = 0;
    }
    for (size_t i = 0; i + 1 < m; i++) {
        if (fabs(dd[i]) >= fabs(dl[i])) {
            if (fabs(dd[i]) < tiny)
                dd[i] = dd[i] < 0 ? -tiny : tiny;
            double f = dl[i] / dd[i];
            dl[i] = f;
            dd[i + 1] -= f * du[i];
            swap[i] = 0;
        } else {
            double f = dd[i] / dl[i], t = du[i];
            dd[i] = dl[i];
            dl[i] = f;
            du[i] = dd[i + 1];
            dd[i + 1] = t - f * dd[i + 1];
            if (i + 2 < m) {
                du2[i] = du[i + 1];
                du[i + 1] = -f * du[i + 1];
            }
            swap[i] = 1;
        }
    }
    for (size_t i = 0; i < m; i++)
        dd[i] = 1 / (fabs(dd[i]) < tiny ? (dd[i] < 0 ? -tiny : tiny) : dd[i]);
}

/* Solves (T - lambda I) y = b in place with shifted_factor's w (dgttrs). */
static void shifted_solve(size_t m, const double *w, double *b)
{
    const double *dl = w, *rdd = w + m, *du = w + 2 * m, *du2 = w + 3 * m;
    const unsigned char *swap = (const unsigned char *)(w + 4 * m);
    for (size_t i = 0; i + 1 < m; i++) {
        if (!swap[i])
            b[i + 1] -= dl[i] * b[i];
        else {
            double t = b[i];
            b[i] = b[i + 1];
            b[i + 1] = t - dl[i] * b[i];
        }
    }
    for (size_t i = m; i-- > 0;) {
        double s = b[i];
        if (i + 1 < m)
            s -= du[i] * b[i + 1];
        if (i + 2 < m)
            s -= du2[i] * b[i + 2];
        b[i] = s * rdd[i];
    }
}

/* Scales x to unit length; returns its largest entry before (the growth of an inverse-iteration solve). */
static double normalize(size_t m, double *x)
{
    double big = 0, s = 0;
    for (size_t i = 0; i < m; i++)
        big = big > fabs(x[i]) ? big : fabs(x[i]);
    if (big == 0 || !isfinite(big)) { /* cannot happen with raised pivots; a unit vector keeps it defined */
        for (size_t i = 0; i < m; i++)
            x[i] = i == 0;
        return 0;
    }
    double r = 1 / big;
    for (size_t i = 0; i < m; i++) {
        x[i] *= r;
        s += x[i] * x[i];
    }
    r = 1 / sqrt(s);
    for (size_t i = 0; i < m; i++)
        x[i] *= r;
    return big;
}

static int cmp_rank(const void *a, const void *b, const double *w)
{
    size_t i = *(const size_t *)a, j = *(const size_t *)b;
    return w[i] < w[j] ? -1 : w[i] > w[j] ? 1 : (i > j) - (i < j);
}

/* Insertion-free merge sort of the indices by eigenvalue (stable; qsort has no context argument in C17). */
static void sort_ranks(size_t *idx, size_t *tmp, size_t n, const double *w)
{
    if (n < 2)
        return;
    size_t h = n / 2;
    sort_ranks(idx, tmp, h, w);
    sort_ranks(idx + h, tmp, n - h, w);
    size_t a = 0, b = h, k = 0;
    while (a < h || b < n)
        tmp[k++] = b >= n || (a < h && cmp_rank(&idx[a], &idx[b], w) <= 0) ? idx[a++] : idx[b++];
    memcpy(idx, tmp, n * sizeof *idx);
}

/* Eigenvectors of one block [b0, b0 + m) by inverse iteration, into the rows of Z its eigenvalues rank. */
static int block_vectors(size_t n, size_t b0, size_t m, const double *d, const double *e, const double *w,
                         const size_t *rank, double norm, double *work, double *Z, const dp_stop *stop)
{
    double tiny = DBL_EPSILON * fmax(norm, DBL_MIN);
    for (size_t k = 0; k < m; k++) {
        if (dp_stop_now(stop))
            return -2;
        double *z = Z + rank[b0 + k] * n + b0, lambda = w[b0 + k];
        unsigned long long seed = 0x9E3779B97F4A7C15ull * (k + 1);
        for (size_t i = 0; i < m; i++) { /* a fixed pseudo-random start: no global state, same answer always */
            seed = seed * 6364136223846793005ull + 1442695040888963407ull;
            z[i] = (double)(seed >> 11) / 9007199254740992.0 - 0.5;
        }
        shifted_factor(m, d + b0, e + b0, lambda, tiny, work);
        for (int sweep = 0; sweep < SWEEPS; sweep++) {
            shifted_solve(m, work, z);
            for (size_t j = k; j-- > 0 && lambda - w[b0 + j] <= CLUSTER * norm;) {
                const double *q = Z + rank[b0 + j] * n + b0;
                double s = 0;
                for (size_t i = 0; i < m; i++)
                    s += q[i] * z[i];
                for (size_t i = 0; i < m; i++)
                    z[i] -= s * q[i];
            }
            /* a solve that grew the start by ~1/(sqrt(m) tiny) has landed on the eigenvector (dstein's test,
             * loosened by 1e4): a second sweep would not move it */
            if (normalize(m, z) * tiny * sqrt((double)m) >= 1e-4)
                break;
        }
    }
    return 0;
}

int dp_tridiag_eigen(size_t n, const double *d, const double *e, double *w, double *Z)
{
    return dp_tridiag_eigen_until(n, d, e, w, Z, NULL);
}

int dp_tridiag_eigen_until(size_t n, const double *d, const double *e, double *w, double *Z, const dp_stop *stop)
{
    size_t *block_end = malloc(n * sizeof *block_end), *idx = malloc(n * sizeof *idx),
           *tmp = malloc(n * sizeof *tmp), *rank = malloc(n * sizeof *rank);
    double *lw = calloc(n ? n : 1, sizeof *lw), *work = malloc(5 * n * sizeof *work);
    if (!block_end || !idx || !tmp || !rank || !lw || !work) {
        free(block_end), free(idx), free(tmp), free(rank), free(lw), free(work);
        return -1;
    }
    memset(Z, 0, n * n * sizeof *Z);
    double emax2 = 0;
    for (size_t i = 0; i + 1 < n; i++)
        emax2 = fmax(emax2, e[i] * e[i]);
    double pivmin = DBL_MIN * fmax(1, emax2);
    /* blocks, their eigenvalues in lw (ascending within each block) */
    int s = 0;
    for (size_t b0 = 0; b0 < n;) {
        if (dp_stop_now(stop)) {
            s = -2;
            break;
        }
        size_t b1 = b0 + 1;
        while (b1 < n && fabs(e[b1 - 1]) > DBL_EPSILON * sqrt(fabs(d[b1 - 1])) * sqrt(fabs(d[b1])) && e[b1 - 1] != 0)
            b1++;
        block_values(b1 - b0, d + b0, e + b0, pivmin, lw + b0, work);
        for (size_t k = b0; k < b1; k++)
            block_end[k] = b1;
        b0 = b1;
    }
    if (s != 0) {
        free(block_end), free(idx), free(tmp), free(rank), free(lw), free(work);
        return s;
    }
    for (size_t i = 0; i < n; i++)
        idx[i] = i;
    sort_ranks(idx, tmp, n, lw);
    for (size_t r = 0; r < n; r++) {
        rank[idx[r]] = r;
        w[r] = lw[idx[r]];
    }
    for (size_t b0 = 0; b0 < n && s == 0; b0 = block_end[b0]) {
        size_t m = block_end[b0] - b0;
        double norm = 0;
        for (size_t i = b0; i < b0 + m; i++)
            norm = fmax(norm, fabs(d[i]) + (i > b0 ? fabs(e[i - 1]) : 0) + (i + 1 < b0 + m ? fabs(e[i]) : 0));
        s = block_vectors(n, b0, m, d, e, lw, rank, norm, work, Z, stop);
    }
    free(block_end), free(idx), free(tmp), free(rank), free(lw), free(work);
    return s;
}
