/* src/core/analysis/modes.c - natural modes and damped eigenvalues of M x'' + C x' + K x = 0 (docs/systems.md §2).
 *
 * Why two routes for the undamped problem: a chain of masses has a diagonal M and a tridiagonal K, and
 * then M^-1/2 K M^-1/2 is a symmetric tridiagonal matrix whose eigenpairs bisection and inverse iteration
 * find in O(n^2) (tridiag.c); a dense generalized solver (GSL's gensymmv phases: Cholesky, standardization,
 * symmv, back-transformation, O(n^3) whatever the structure) is used for everything else. The damped problem
 * goes through the first-order form [0 I; -M^-1 K -M^-1 C], whose eigenvalues come in conjugate pairs; one
 * of each pair is kept.
 *
 * Why the scaling: every matrix handed to an eigensolver is finite and within 2^+-256 of 1, because GSL's
 * balancing and QR loops have no iteration cap and never end on an infinity, and the chain solver squares
 * its entries. A derived matrix beyond that is formed again from the entries' mantissas and exponents,
 * scaled by a power of two (exact), and the eigenvalues scaled back; what still leaves the finite numbers
 * (an omega^2 beyond DBL_MAX) is an error naming the member that made it so (opts->member).
 *
 * A mode is rigid when its own strain energy is round-off of the energy terms acting on it: with psi the
 * shape scaled to max |psi_i| = 1, |psi^T K psi| <= 1e-12 |psi|^T |K| |psi|. Each mode is measured on the
 * stiffness it feels, not on K's largest entry, so a soft mode beside a stiff spring keeps its omega.
 */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_blas.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>

#include "dashpot/modes.h"
#include "base/tridiag.h"

#define RIGID_TOL 1e-12    /* ~4500 eps: a rigid mode's psi^T K psi is a cancellation of n terms of |K| */
#define SYMMETRY_TOL 1e-12
#define SCALE_EXP 256      /* a derived matrix whose largest entry is beyond 2^+-256 is scaled (header) */
#define NO_EXP (INT_MIN / 4) /* the exponent of 0 */

/* What one solve works on: the matrices, where they came from, the stop hook, the errors. */
typedef struct job {
    size_t n;
    const double *M, *K, *C;
    const dp_modes_opts *o;
    dp_errors *errs;
    int m_diagonal;
} job;

void dp_modes_free(dp_modes *m)
{
    if (m == NULL)
        return;
    free(m->lambda);
    free(m->shape);
    free(m->rigid);
    free(m->participation);
    free(m->modal_damping);
    free(m->eig);
    memset(m, 0, sizeof *m);
}

static int stopped(const job *jb)
{
    return dp_stop_now(jb->o->stop);
}

/* An error about scale at the member that makes row `row` of matrix `which` what it is. */
static void blame(const job *jb, char which, size_t row, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static void blame(const job *jb, char which, size_t row, const char *fmt, ...)
{
    const dp_modes_opts *o = jb->o;
    const char *whole = which == 'M' ? o->pointer_M : which == 'K' ? o->pointer_K : o->pointer_C;
    char ptr[DP_POINTER_MAX], msg[DP_MESSAGE_MAX];
    snprintf(ptr, sizeof ptr, "%s", whole ? whole : "");
    if (o->member != NULL)
        o->member(o->ctx, which, row, ptr, sizeof ptr);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    dp_errors_add(jb->errs, ptr, "%s", msg);
}

/* The binary exponent of |x| (ilogb), NO_EXP for 0. */
static int exponent(double x)
{
    return x == 0 || !isfinite(x) ? NO_EXP : ilogb(x);
}

/* The node whose time scale is the shortest, and what makes it so: for omega^2 ~ K_ii / M_ii ('K' or
 * 'M', the one further from 1 in exponent), or with `damped` also for C_ii / M_ii ('C'). *log2_rate is
 * the exponent of that rate (1/s). */
static void culprit(const job *jb, int damped, char *which, size_t *row, int *log2_rate)
{
    int best = NO_EXP;
    *which = 'M';
    *row = 0;
    for (size_t i = 0; i < jb->n; i++) {
        int em = exponent(jb->M[i * jb->n + i]), ek = exponent(jb->K[i * jb->n + i]);
        int ec = damped && jb->C ? exponent(jb->C[i * jb->n + i]) : NO_EXP;
        int rk = ek == NO_EXP ? NO_EXP : (ek - em) / 2, rc = ec == NO_EXP ? NO_EXP : ec - em;
        int r = rk > rc ? rk : rc;
        if (r > best || (i == 0 && r == NO_EXP)) {
            best = r;
            *row = i;
            int ex = rk >= rc ? ek : ec;
            *which = ex != NO_EXP && abs(ex) >= abs(em) ? (rk >= rc ? 'K' : 'C') : 'M';
        }
    }
    *log2_rate = best;
}

static void blame_scale(const job *jb, int damped, const char *what)
{
    char which;
    size_t row;
    int rate;
    culprit(jb, damped, &which, &row, &rate);
    blame(jb, which, row, "%s leaves the double-precision numbers: the %s scale overflows (node %zu's rate "
          "is about 2^%d /s)", what, which == 'M' ? "mass" : which == 'K' ? "stiffness" : "damping", row, rate);
}

static double max_abs(size_t n, const double *A)
{
    double a = 0;
    for (size_t k = 0; k < n * n; k++)
        a = a > fabs(A[k]) ? a : fabs(A[k]); /* not fmax: a libm call per entry */
    return a;
}

/* Every entry finite and the largest within 2^+-SCALE_EXP (or all zero): safe for GSL's loops. */
static int moderate(size_t count, const double *a)
{
    double big = 0;
    for (size_t k = 0; k < count; k++) {
        if (!isfinite(a[k]))
            return 0;
        big = big > fabs(a[k]) ? big : fabs(a[k]);
    }
    return big == 0 || (big <= 0x1p256 && big >= 0x1p-256);
}

/* Finite and symmetric to round-off; otherwise an error at `ptr`. */
static int check_symmetric(size_t n, const double *A, const char *ptr, const char *what, dp_errors *errs)
{
    double tol = SYMMETRY_TOL * max_abs(n, A);
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j <= i; j++) {
            double a = A[i * n + j], b = A[j * n + i];
            if (!isfinite(a) || !isfinite(b)) {
                dp_errors_add(errs, ptr, "the %s matrix has a non-finite entry at (%zu, %zu)", what, i, j);
                return DP_EINVAL;
            }
            if (fabs(a - b) > tol) {
                dp_errors_add(errs, ptr, "the %s matrix is not symmetric: entry (%zu, %zu) = %g but (%zu, %zu) = %g",
                              what, i, j, a, j, i, b);
                return DP_EINVAL;
            }
        }
    return DP_OK;
}

static int is_zero(size_t n, const double *A)
{
    return A == NULL || max_abs(n, A) == 0;
}

static int m_diagonal(size_t n, const double *M)
{
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            if (i != j && M[i * n + j] != 0)
                return 0;
    return 1;
}

/* M diagonal and K zero beyond the first off-diagonals. */
static int is_chain(size_t n, const double *M, const double *K)
{
    if (!m_diagonal(n, M))
        return 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            if ((i > j + 1 || j > i + 1) && K[i * n + j] != 0)
                return 0;
    return 1;
}

/* k / sqrt(ma mb) (mb = ma on the diagonal: k / ma) as a mantissa and a binary exponent, which no entry of
 * the extended range over- or underflows. */
static double chain_entry(double k, double ma, double mb, int diagonal, int *ex)
{
    int ek, ea, eb;
    double fk = frexp(k, &ek), fa = frexp(ma, &ea), fb = frexp(mb, &eb);
    if (k == 0) {
        *ex = NO_EXP;
        return 0;
    }
    if (diagonal) {
        *ex = ek - ea;
        return fk / fa;
    }
    int sum = ea + eb;
    double prod = fa * fb;
    if (sum % 2 != 0)
        prod *= 2, sum -= 1;
    *ex = ek - sum / 2;
    return fk / sqrt(prod);
}

/* d, e of T = M^-1/2 K M^-1/2 by the plain formula; when that is not moderate(), again from mantissas and
 * exponents scaled by 2^-P, P the largest exponent (*P: the power of two the eigenvalues are to take). */
static void chain_matrix(size_t n, const double *M, const double *K, double *d, double *e, int *P)
{
    for (size_t i = 0; i < n; i++) {
        d[i] = K[i * n + i] / M[i * n + i];
        e[i] = i + 1 < n ? K[i * n + i + 1] / sqrt(M[i * n + i] * M[(i + 1) * n + i + 1]) : 0;
    }
    *P = 0;
    if (moderate(n, d) && moderate(n, e))
        return;
    int top = NO_EXP;
    for (size_t i = 0; i < n; i++) {
        int a, b = NO_EXP;
        chain_entry(K[i * n + i], M[i * n + i], M[i * n + i], 1, &a);
        if (i + 1 < n)
            chain_entry(K[i * n + i + 1], M[i * n + i], M[(i + 1) * n + i + 1], 0, &b);
        top = a > top ? a : top;
        top = b > top ? b : top;
    }
    *P = top == NO_EXP ? 0 : top;
    for (size_t i = 0; i < n; i++) {
        int a, b = NO_EXP;
        double md = chain_entry(K[i * n + i], M[i * n + i], M[i * n + i], 1, &a), me = 0;
        if (i + 1 < n)
            me = chain_entry(K[i * n + i + 1], M[i * n + i], M[(i + 1) * n + i + 1], 0, &b);
        d[i] = a == NO_EXP ? 0 : ldexp(md, a - *P);
        e[i] = b == NO_EXP ? 0 : ldexp(me, b - *P);
    }
}

static int solve_chain(const job *jb, dp_modes *out, int *P)
{
    size_t n = jb->n;
    const double *M = jb->M;
    double *d = malloc(n * sizeof *d), *e = malloc(n * sizeof *e);
    int s = d && e ? DP_OK : DP_ENOMEM;
    if (s == DP_OK) {
        chain_matrix(n, M, jb->K, d, e, P);
        int t = dp_tridiag_eigen_until(n, d, e, out->lambda, out->shape, jb->o->stop);
        s = t == -2 ? DP_ECANCEL : t != 0 ? DP_ENOMEM : DP_OK;
        for (size_t k = 0; s == DP_OK && k < n; k++) /* y = M^1/2 phi: phi_i = y_i / sqrt(m_i), M-normalized */
            for (size_t i = 0; i < n; i++)
                out->shape[k * n + i] /= sqrt(M[i * n + i]);
    }
    free(d);
    free(e);
    return s;
}

/* A = L^-1 K L^-T with M = L L^T, as GSL's gensymmv forms it, into A (L into B). */
static int standardize(size_t n, const double *M, const double *K, int scale_m, int scale_k, gsl_matrix *A,
                       gsl_matrix *B)
{
    for (size_t k = 0; k < n * n; k++) {
        A->data[k] = ldexp(K[k], -scale_k);
        B->data[k] = ldexp(M[k], -scale_m);
    }
    if (gsl_linalg_cholesky_decomp(B) != GSL_SUCCESS)
        return DP_ESOLVE;
    return gsl_eigen_gensymm_standardize(A, B) == GSL_SUCCESS ? DP_OK : DP_ESOLVE;
}

/* GSL's generalized symmetric route, phase by phase (gensymmv's own calls), polling the stop hook between
 * them; the standardized matrix scaled when it is not moderate(). M positive definite was checked. */
static int solve_dense(const job *jb, dp_modes *out, int *P)
{
    size_t n = jb->n;
    gsl_matrix *A = gsl_matrix_alloc(n, n), *B = gsl_matrix_alloc(n, n), *V = gsl_matrix_alloc(n, n);
    gsl_vector *w = gsl_vector_alloc(n);
    gsl_eigen_symmv_workspace *ws = gsl_eigen_symmv_alloc(n);
    int s = A && B && V && w && ws ? DP_OK : DP_ENOMEM;
    *P = 0;
    s = s ? s : standardize(n, jb->M, jb->K, 0, 0, A, B);
    if (s == DP_OK && !moderate(n * n, A->data)) {
        int em = exponent(max_abs(n, jb->M)), ek = exponent(max_abs(n, jb->K));
        if (ek != NO_EXP) {
            s = standardize(n, jb->M, jb->K, em, ek, A, B);
            *P = ek - em;
        }
        if (s == DP_OK && !moderate(n * n, A->data)) {
            blame_scale(jb, 0, "L^-1 K L^-T (M = L L^T)");
            s = DP_EINVAL;
        }
    }
    s = s || !stopped(jb) ? s : DP_ECANCEL;
    if (s == DP_OK && (gsl_eigen_symmv(A, w, V, ws) != GSL_SUCCESS ||
                       gsl_eigen_symmv_sort(w, V, GSL_EIGEN_SORT_VAL_ASC) != GSL_SUCCESS))
        s = DP_ESOLVE;
    s = s || !stopped(jb) ? s : DP_ECANCEL;
    if (s == DP_OK) { /* back-transformation phi = L^-T y */
        gsl_blas_dtrsm(CblasLeft, CblasLower, CblasTrans, CblasNonUnit, 1.0, B, V);
        for (size_t k = 0; k < n; k++) {
            gsl_vector_view col = gsl_matrix_column(V, k);
            gsl_blas_dscal(1.0 / gsl_blas_dnrm2(&col.vector), &col.vector);
        }
    }
    for (size_t k = 0; s == DP_OK && k < n; k++) {
        out->lambda[k] = gsl_vector_get(w, k);
        for (size_t i = 0; i < n; i++)
            out->shape[k * n + i] = gsl_matrix_get(V, i, k);
    }
    gsl_eigen_symmv_free(ws);
    gsl_vector_free(w);
    gsl_matrix_free(V);
    gsl_matrix_free(B);
    gsl_matrix_free(A);
    return s;
}

/* y = A x; O(n) when A is diagonal (the masses of a chain), so a chain's modes stay O(n^2) in all. */
static void matvec(size_t n, const double *A, int diagonal, const double *x, double *y)
{
    for (size_t i = 0; i < n; i++) {
        y[i] = diagonal ? A[i * n + i] * x[i] : 0;
        for (size_t j = 0; !diagonal && j < n; j++)
            y[i] += A[i * n + j] * x[j];
    }
}

static double dot(size_t n, const double *x, const double *y)
{
    double s = 0;
    for (size_t i = 0; i < n; i++)
        s += x[i] * y[i];
    return s;
}

/* The sign convention: the first entry that is not round-off is positive, as Höschl writes his shapes. */
static double fix_sign(size_t n, double *phi)
{
    double big = 0;
    for (size_t i = 0; i < n; i++)
        big = big > fabs(phi[i]) ? big : fabs(phi[i]);
    for (size_t i = 0; i < n; i++)
        if (fabs(phi[i]) > 1e-8 * big) {
            if (phi[i] > 0)
                return 1;
            for (size_t l = 0; l < n; l++)
                phi[l] = -phi[l];
            return -1;
        }
    return 1;
}

/* The rigid test of one mode (header): psi = phi / max |phi_i|, K scaled by 2^-ks (no overflow of the sums);
 * a tridiagonal K is read on its three diagonals only. */
static int is_rigid(size_t n, const double *K, int tridiagonal, int ks, const double *phi)
{
    double big = 0, energy = 0, terms = 0;
    for (size_t i = 0; i < n; i++)
        big = big > fabs(phi[i]) ? big : fabs(phi[i]);
    if (big == 0)
        return 1;
    for (size_t i = 0; i < n; i++) {
        size_t j0 = tridiagonal && i > 0 ? i - 1 : 0, j1 = tridiagonal && i + 2 < n ? i + 2 : n;
        double pi = phi[i] / big;
        for (size_t j = j0; j < j1; j++) {
            double kij = ldexp(K[i * n + j], -ks), t = pi * kij * (phi[j] / big);
            energy += t;
            terms += fabs(t);
        }
    }
    return fabs(energy) <= RIGID_TOL * terms;
}

/* The sign of phi^T K phi (K scaled by 2^-ks). */
static int rayleigh_sign(size_t n, const double *K, int ks, const double *phi)
{
    double big = 0, energy = 0;
    for (size_t i = 0; i < n; i++)
        big = big > fabs(phi[i]) ? big : fabs(phi[i]);
    for (size_t i = 0; big > 0 && i < n; i++)
        for (size_t j = 0; j < n; j++)
            energy += (phi[i] / big) * ldexp(K[i * n + j], -ks) * (phi[j] / big);
    return (energy > 0) - (energy < 0);
}

/* One mode: M-normalization (again, for round-off), the sign convention, the participation factor, the
 * rigid flag, omega^2 scaled back by 2^P, and the check that K has no negative mode. */
static int finish_mode(const job *jb, dp_modes *out, size_t k, int P, int ks, double *Mphi)
{
    size_t n = jb->n;
    double *phi = out->shape + k * n;
    matvec(n, jb->M, jb->m_diagonal, phi, Mphi);
    double scale = sqrt(dot(n, phi, Mphi)), part = 0;
    if (!isfinite(scale) || !(scale > 0)) {
        blame_scale(jb, 0, "a mode's mass phi^T M phi");
        return DP_EINVAL;
    }
    for (size_t i = 0; i < n; i++)
        phi[i] /= scale;
    scale *= fix_sign(n, phi);
    for (size_t i = 0; i < n; i++) {
        Mphi[i] /= scale;
        part += Mphi[i];
    }
    out->participation[k] = part;
    out->rigid[k] = is_rigid(n, jb->K, out->tridiagonal, ks, phi);
    double lambda = ldexp(out->lambda[k], P);
    if (out->rigid[k])
        lambda = 0;
    else if (!isfinite(part)) {
        blame_scale(jb, 0, "a participation factor phi^T M 1");
        return DP_EINVAL;
    } else if (lambda < 0 && rayleigh_sign(n, jb->K, ks, phi) < 0) {
        dp_errors_add(jb->errs, jb->o->pointer_K,
                      "the stiffness is not positive semidefinite: it has a mode with omega^2 = %g < 0", lambda);
        return DP_EINVAL;
    } else if (lambda < 0) { /* phi^T K phi > 0: the eigenvalue, not K, is wrong: scales beyond resolution */
        blame_scale(jb, 0, "omega^2 of a mode (the model's scales span more than double precision resolves)");
        return DP_EINVAL;
    }
    out->lambda[k] = lambda;
    return DP_OK;
}

static int finish_shapes(const job *jb, dp_modes *out, int P)
{
    for (size_t k = 0; k < jb->n; k++) /* the largest first: a lost small one is a consequence of it */
        if (!isfinite(ldexp(out->lambda[k], P))) {
            blame_scale(jb, 0, "omega^2 of a mode");
            return DP_EINVAL;
        }
    double kmax = max_abs(jb->n, jb->K);
    int ks = kmax > 0x1p256 ? exponent(kmax) : 0; /* the rigid test's sums of n^2 terms stay finite */
    double *Mphi = malloc(jb->n * sizeof *Mphi);
    int s = Mphi ? DP_OK : DP_ENOMEM;
    for (size_t k = 0; k < jb->n && s == DP_OK; k++) {
        s = finish_mode(jb, out, k, P, ks, Mphi);
        s = s || (k % 64 != 63 || !stopped(jb)) ? s : DP_ECANCEL;
    }
    free(Mphi);
    return s;
}

/* C positive semidefinite (its smallest eigenvalue not below round-off of its largest); C scaled by an even
 * power of two to max |C_ij| ~ 1 first, so that GSL's QR loop sees moderate() numbers. */
static int check_psd(size_t n, const double *C, const char *ptr, dp_errors *errs)
{
    gsl_matrix *A = gsl_matrix_alloc(n, n);
    gsl_vector *w = gsl_vector_alloc(n);
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc(n);
    int s = A && w && ws ? DP_OK : DP_ENOMEM, ec = exponent(max_abs(n, C));
    ec = ec == NO_EXP || abs(ec) < SCALE_EXP ? 0 : ec - ec % 2;
    if (s == DP_OK) {
        for (size_t k = 0; k < n * n; k++)
            A->data[k] = ldexp(C[k], -ec);
        if (gsl_eigen_symm(A, w, ws) != GSL_SUCCESS)
            s = DP_ESOLVE;
        else if (gsl_vector_min(w) < -RIGID_TOL * fmax(fabs(gsl_vector_max(w)), fabs(gsl_vector_min(w)))) {
            dp_errors_add(errs, ptr, "the damping matrix is not positive semidefinite (an eigenvalue %g < 0)",
                          ldexp(gsl_vector_min(w), ec));
            s = DP_EINVAL;
        }
    }
    gsl_eigen_symm_free(ws);
    gsl_vector_free(w);
    gsl_matrix_free(A);
    return s;
}

/* Modal damping ratios phi^T C phi / (2 omega), and whether Phi^T C Phi is diagonal: C Phi once, then
 * the dot products, O(n^3) in all. */
static int modal_damping(const job *jb, const double *C, dp_modes *out)
{
    size_t n = jb->n;
    out->proportional = 1;
    if (C == NULL) {
        for (size_t k = 0; k < n; k++)
            out->modal_damping[k] = NAN;
        return DP_OK;
    }
    double *CPhi = malloc(n * n * sizeof *CPhi), diag_max = 0, off_max = 0;
    if (CPhi == NULL)
        return DP_ENOMEM;
    int s = DP_OK;
    for (size_t k = 0; k < n && s == DP_OK; k++) {
        matvec(n, C, 0, out->shape + k * n, CPhi + k * n);
        s = k % 16 != 15 || !stopped(jb) ? DP_OK : DP_ECANCEL;
    }
    for (size_t k = 0; k < n && s == DP_OK; k++) {
        double ckk = dot(n, out->shape + k * n, CPhi + k * n);
        diag_max = fmax(diag_max, fabs(ckk));
        out->modal_damping[k] = out->rigid[k] ? NAN : ckk / (2 * sqrt(out->lambda[k]));
        for (size_t l = 0; l < k; l++)
            off_max = fmax(off_max, fabs(dot(n, out->shape + l * n, CPhi + k * n)));
        if (!isfinite(ckk) || (!out->rigid[k] && !isfinite(out->modal_damping[k]))) {
            blame_scale(jb, 1, "a modal damping phi^T C phi");
            s = DP_EINVAL;
        }
        s = s || k % 16 != 15 || !stopped(jb) ? s : DP_ECANCEL;
    }
    out->proportional = off_max <= 1e-9 * diag_max;
    free(CPhi);
    return s;
}

static int cmp_eig(const void *a, const void *b)
{
    const dp_damped_eig *x = a, *y = b;
    double mx = hypot(x->re, x->im), my = hypot(y->re, y->im);
    return mx < my ? -1 : mx > my ? 1 : (x->re > y->re) - (x->re < y->re);
}

/* A = [0 I; -M^-1 K  -M^-1 C] for the time scaled by 2^t and the masses by 2^a (lambda = 2^t mu):
 * M 2^-a, K 2^-(a+2t), C 2^-(a+t); t = a = 0 is the plain first-order form. */
static int first_order(size_t n, const double *M, const double *K, const double *C, int a, int t,
                       gsl_matrix *L, gsl_matrix *R, gsl_matrix *A)
{
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) {
            gsl_matrix_set(L, i, j, ldexp(M[i * n + j], -a));
            gsl_matrix_set(R, i, j, ldexp(K[i * n + j], -a - 2 * t));
            gsl_matrix_set(R, i, n + j, ldexp(C[i * n + j], -a - t));
        }
    if (gsl_linalg_cholesky_decomp1(L) != GSL_SUCCESS)
        return DP_ESOLVE;
    for (size_t c = 0; c < 2 * n; c++) {
        gsl_vector_view col = gsl_matrix_column(R, c);
        if (gsl_linalg_cholesky_svx(L, &col.vector) != GSL_SUCCESS)
            return DP_ESOLVE;
    }
    gsl_matrix_set_zero(A);
    for (size_t i = 0; i < n; i++) {
        gsl_matrix_set(A, i, n + i, 1.0);
        for (size_t c = 0; c < 2 * n; c++)
            gsl_matrix_set(A, n + i, c, -gsl_matrix_get(R, i, c));
    }
    return DP_OK;
}

/* The first-order form, scaled in time when the plain one is not moderate() (GSL's balancing never ends on
 * an infinity), by GSL's nonsymmetric eigensolver (its Francis iteration is capped: GSL_EMAXITER). */
static int damped_eigs(const job *jb, dp_modes *out)
{
    size_t n = jb->n, N = 2 * n;
    gsl_matrix *L = gsl_matrix_alloc(n, n), *R = gsl_matrix_alloc(n, 2 * n), *A = gsl_matrix_alloc(N, N);
    gsl_vector_complex *w = gsl_vector_complex_alloc(N);
    gsl_eigen_nonsymm_workspace *ws = gsl_eigen_nonsymm_alloc(N);
    out->eig = malloc(N * sizeof *out->eig);
    int s = L && R && A && w && ws && out->eig ? DP_OK : DP_ENOMEM, t = 0;
    s = s ? s : first_order(n, jb->M, jb->K, jb->C, 0, 0, L, R, A);
    if (s == DP_OK && !moderate(N * N, A->data)) {
        char which;
        size_t row;
        culprit(jb, 1, &which, &row, &t);
        t = t == NO_EXP ? 0 : t;
        s = first_order(n, jb->M, jb->K, jb->C, exponent(max_abs(n, jb->M)), t, L, R, A);
        if (s == DP_OK && !moderate(N * N, A->data)) {
            blame_scale(jb, 1, "the first-order matrix [0 I; -M^-1 K -M^-1 C]");
            s = DP_EINVAL;
        }
    }
    s = s || !stopped(jb) ? s : DP_ECANCEL;
    if (s == DP_OK) {
        gsl_eigen_nonsymm_params(0, 1, ws); /* balance: M^-1 K of a badly scaled system spans decades */
        if (gsl_eigen_nonsymm(A, w, ws) != GSL_SUCCESS) { /* GSL_EMAXITER: its Francis iteration's cap */
            char which;
            size_t row;
            int rate;
            culprit(jb, 1, &which, &row, &rate);
            blame(jb, which, row, "the damped eigenvalues did not converge (GSL's Francis iteration reached its cap)%s",
                  t != 0 ? ": the model's time scales span more than double precision resolves" : "");
            s = DP_EINVAL;
        }
    }
    for (size_t k = 0; s == DP_OK && k < N; k++) {
        gsl_complex z = gsl_vector_complex_get(w, k);
        double re = ldexp(GSL_REAL(z), t), im = ldexp(GSL_IMAG(z), t), mag = hypot(re, im);
        if (!isfinite(mag)) {
            blame_scale(jb, 1, "a damped eigenvalue");
            s = DP_EINVAL;
        }
        if (s != DP_OK || im < 0)
            continue;
        re = re > 0 ? 0 : re; /* M, K, C semidefinite: Re lambda <= 0, a positive one is round-off (eps |lambda|) */
        double zeta = mag > 0 ? (re == 0 ? 0 : -re / mag) : NAN;
        out->eig[out->ndamped++] = (dp_damped_eig){ re, im, zeta };
    }
    if (s == DP_OK)
        qsort(out->eig, out->ndamped, sizeof *out->eig, cmp_eig);
    gsl_eigen_nonsymm_free(ws);
    gsl_vector_complex_free(w);
    gsl_matrix_free(A);
    gsl_matrix_free(R);
    gsl_matrix_free(L);
    return s;
}

static int check_inputs(const job *jb)
{
    size_t n = jb->n;
    const dp_modes_opts *o = jb->o;
    int s = check_symmetric(n, jb->M, o->pointer_M, "mass", jb->errs);
    s = s ? s : check_symmetric(n, jb->K, o->pointer_K, "stiffness", jb->errs);
    s = s || jb->C == NULL ? s : check_symmetric(n, jb->C, o->pointer_C, "damping", jb->errs);
    if (s != DP_OK)
        return s;
    if (jb->m_diagonal) { /* a chain's masses: no O(n^3) factorization to say they are positive */
        for (size_t i = 0; i < n && s == DP_OK; i++)
            if (!(jb->M[i * n + i] > 0)) {
                dp_errors_add(jb->errs, o->pointer_M, "the mass matrix is not positive definite (entry %zu is %g)", i,
                              jb->M[i * n + i]);
                s = DP_EINVAL;
            }
    } else {
        gsl_matrix *L = gsl_matrix_alloc(n, n);
        if (L == NULL)
            return DP_ENOMEM;
        int em = exponent(max_abs(n, jb->M));
        for (size_t k = 0; k < n * n; k++) /* scaled, so that the sums of squares stay finite */
            L->data[k] = ldexp(jb->M[k], -em);
        if (gsl_linalg_cholesky_decomp1(L) != GSL_SUCCESS) {
            dp_errors_add(jb->errs, o->pointer_M, "the mass matrix is not positive definite");
            s = DP_EINVAL;
        }
        gsl_matrix_free(L);
    }
    return s || is_zero(n, jb->C) ? s : check_psd(n, jb->C, o->pointer_C, jb->errs);
}

static int alloc_modes(size_t n, dp_modes *out)
{
    out->n = n;
    out->lambda = malloc(n * sizeof *out->lambda);
    out->shape = malloc(n * n * sizeof *out->shape);
    out->rigid = malloc(n * sizeof *out->rigid);
    out->participation = malloc(n * sizeof *out->participation);
    out->modal_damping = malloc(n * sizeof *out->modal_damping);
    return out->lambda && out->shape && out->rigid && out->participation && out->modal_damping ? DP_OK : DP_ENOMEM;
}

int dp_modes_solve(size_t n, const double *M, const double *K, const double *C, const char *pointer_M,
                   const char *pointer_K, const char *pointer_C, dp_modes *out, dp_errors *errs)
{
    const dp_modes_opts o = { pointer_M, pointer_K, pointer_C, NULL, NULL, 0, NULL };
    return dp_modes_solve_until(n, M, K, C, &o, out, errs);
}

int dp_modes_solve_until(size_t n, const double *M, const double *K, const double *C, const dp_modes_opts *opts,
                         dp_modes *out, dp_errors *errs)
{
    memset(out, 0, sizeof *out);
    if (n == 0 || n > DP_MODES_MAX_NODES) {
        dp_errors_add(errs, "", "a linear analysis takes 1 to %d nodes, not %zu", DP_MODES_MAX_NODES, n);
        return n == 0 ? DP_EINVAL : DP_ELIMIT;
    }
    int damped = !is_zero(n, C);
    if (damped && n > DP_MODES_MAX_DAMPED_NODES) {
        dp_errors_add(errs, opts->pointer_C, "damped eigenvalues are computed for up to %d nodes, not %zu",
                      DP_MODES_MAX_DAMPED_NODES, n);
        return DP_ELIMIT;
    }
    const job jb = { n, M, K, damped ? C : NULL, opts, errs, m_diagonal(n, M) };
    int s = check_inputs(&jb);
    s = s ? s : alloc_modes(n, out);
    if (s != DP_OK)
        return s;
    out->tridiagonal = is_chain(n, M, K);
    if (!out->tridiagonal && n > DP_MODES_MAX_DENSE_NODES) {
        dp_errors_add(errs, opts->pointer_K, "a network that is not a chain (diagonal masses, tridiagonal stiffness) is "
                      "solved densely, for up to %d nodes, not %zu", DP_MODES_MAX_DENSE_NODES, n);
        return DP_ELIMIT;
    }
    int P = 0;
    s = stopped(&jb) ? DP_ECANCEL : DP_OK;
    s = s ? s : out->tridiagonal ? solve_chain(&jb, out, &P) : solve_dense(&jb, out, &P);
    s = s ? s : finish_shapes(&jb, out, P);
    s = s ? s : modal_damping(&jb, jb.C, out);
    if (s != DP_OK)
        return s;
    out->damped = damped;
    s = stopped(&jb) ? DP_ECANCEL : DP_OK;
    return s || !damped || opts->skip_damped ? s : damped_eigs(&jb, out);
}
