/* src/core/analysis/modes.c - natural modes and damped eigenvalues of M x'' + C x' + K x = 0 (docs/systems.md §2).
 *
 * Why two routes for the undamped problem: a chain of masses has a diagonal M and a tridiagonal K, and
 * then M^-1/2 K M^-1/2 is a symmetric tridiagonal matrix whose eigenpairs bisection and inverse iteration
 * find in O(n^2) (tridiag.c); a dense generalized solver (GSL's gensymmv, which is O(n^3) whatever the
 * structure) is used for everything else. The damped problem goes through the first-order form [0 I; -M^-1 K -M^-1 C], whose
 * eigenvalues come in conjugate pairs; one of each pair is kept.
 *
 * A mode is rigid when K phi vanishes to round-off (|lambda| ||M phi|| <= 1e-12 ||K||_F ||phi||): a
 * criterion on K's own scale, so that a soft but real mode of a badly scaled system is not taken for one.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>

#include "dashpot/modes.h"
#include "base/tridiag.h"

#define RIGID_TOL 1e-12
#define SYMMETRY_TOL 1e-12

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

static double max_abs(size_t n, const double *A)
{
    double a = 0;
    for (size_t k = 0; k < n * n; k++)
        a = a > fabs(A[k]) ? a : fabs(A[k]); /* not fmax: a libm call per entry */
    return a;
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

static int solve_chain(size_t n, const double *M, const double *K, dp_modes *out)
{
    double *d = malloc(n * sizeof *d), *e = malloc(n * sizeof *e);
    int s = d && e ? DP_OK : DP_ENOMEM;
    if (s == DP_OK) {
        for (size_t i = 0; i < n; i++) {
            d[i] = K[i * n + i] / M[i * n + i];
            e[i] = i + 1 < n ? K[i * n + i + 1] / sqrt(M[i * n + i] * M[(i + 1) * n + i + 1]) : 0;
        }
        if (dp_tridiag_eigen(n, d, e, out->lambda, out->shape) != 0)
            s = DP_ENOMEM;
        for (size_t k = 0; s == DP_OK && k < n; k++) /* y = M^1/2 phi: phi_i = y_i / sqrt(m_i), M-normalized */
            for (size_t i = 0; i < n; i++)
                out->shape[k * n + i] /= sqrt(M[i * n + i]);
    }
    free(d);
    free(e);
    return s;
}

/* GSL's generalized symmetric route; M positive definite was checked by the caller's Cholesky. */
static int solve_dense(size_t n, const double *M, const double *K, dp_modes *out)
{
    gsl_matrix *A = gsl_matrix_alloc(n, n), *B = gsl_matrix_alloc(n, n), *V = gsl_matrix_alloc(n, n);
    gsl_vector *w = gsl_vector_alloc(n);
    gsl_eigen_gensymmv_workspace *ws = gsl_eigen_gensymmv_alloc(n);
    int s = A && B && V && w && ws ? DP_OK : DP_ENOMEM;
    if (s == DP_OK) {
        memcpy(A->data, K, n * n * sizeof *K);
        memcpy(B->data, M, n * n * sizeof *M);
        if (gsl_eigen_gensymmv(A, B, w, V, ws) != GSL_SUCCESS ||
            gsl_eigen_gensymmv_sort(w, V, GSL_EIGEN_SORT_VAL_ASC) != GSL_SUCCESS)
            s = DP_ESOLVE;
    }
    for (size_t k = 0; s == DP_OK && k < n; k++) {
        out->lambda[k] = gsl_vector_get(w, k);
        for (size_t i = 0; i < n; i++)
            out->shape[k * n + i] = gsl_matrix_get(V, i, k);
    }
    gsl_eigen_gensymmv_free(ws);
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

/* M-normalization (again, for round-off), the sign convention, the rigid flags, the participation factors,
 * and the check that K has no negative mode. */
static int finish_shapes(size_t n, const double *M, int m_diagonal, const double *K, const char *pK,
                         dp_modes *out, dp_errors *errs)
{
    double knorm = sqrt(dot(n * n, K, K));
    double *Mphi = malloc(n * sizeof *Mphi);
    if (Mphi == NULL)
        return DP_ENOMEM;
    int s = DP_OK;
    for (size_t k = 0; k < n && s == DP_OK; k++) {
        double *phi = out->shape + k * n;
        matvec(n, M, m_diagonal, phi, Mphi);
        double scale = sqrt(dot(n, phi, Mphi)), part = 0;
        for (size_t i = 0; i < n; i++)
            phi[i] /= scale;
        scale *= fix_sign(n, phi);
        for (size_t i = 0; i < n; i++) {
            Mphi[i] /= scale;
            part += Mphi[i];
        }
        out->participation[k] = part;
        out->rigid[k] = fabs(out->lambda[k]) * sqrt(dot(n, Mphi, Mphi)) <= RIGID_TOL * knorm * sqrt(dot(n, phi, phi));
        if (out->rigid[k])
            out->lambda[k] = 0;
        else if (out->lambda[k] < 0) {
            dp_errors_add(errs, pK, "the stiffness is not positive semidefinite: it has a mode with omega^2 = %g < 0",
                          out->lambda[k]);
            s = DP_EINVAL;
        }
    }
    free(Mphi);
    return s;
}

/* C positive semidefinite (its smallest eigenvalue not below round-off of its largest). */
static int check_psd(size_t n, const double *C, const char *ptr, dp_errors *errs)
{
    gsl_matrix *A = gsl_matrix_alloc(n, n);
    gsl_vector *w = gsl_vector_alloc(n);
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc(n);
    int s = A && w && ws ? DP_OK : DP_ENOMEM;
    if (s == DP_OK) {
        memcpy(A->data, C, n * n * sizeof *C);
        if (gsl_eigen_symm(A, w, ws) != GSL_SUCCESS)
            s = DP_ESOLVE;
        else if (gsl_vector_min(w) < -RIGID_TOL * fmax(fabs(gsl_vector_max(w)), fabs(gsl_vector_min(w)))) {
            dp_errors_add(errs, ptr, "the damping matrix is not positive semidefinite (an eigenvalue %g < 0)",
                          gsl_vector_min(w));
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
static int modal_damping(size_t n, const double *C, dp_modes *out)
{
    out->proportional = 1;
    if (C == NULL) {
        for (size_t k = 0; k < n; k++)
            out->modal_damping[k] = NAN;
        return DP_OK;
    }
    double *CPhi = malloc(n * n * sizeof *CPhi), diag_max = 0, off_max = 0;
    if (CPhi == NULL)
        return DP_ENOMEM;
    for (size_t k = 0; k < n; k++)
        matvec(n, C, 0, out->shape + k * n, CPhi + k * n);
    for (size_t k = 0; k < n; k++) {
        double ckk = dot(n, out->shape + k * n, CPhi + k * n);
        diag_max = fmax(diag_max, fabs(ckk));
        out->modal_damping[k] = out->rigid[k] ? NAN : ckk / (2 * sqrt(out->lambda[k]));
        for (size_t l = 0; l < k; l++)
            off_max = fmax(off_max, fabs(dot(n, out->shape + l * n, CPhi + k * n)));
    }
    out->proportional = off_max <= 1e-9 * diag_max;
    free(CPhi);
    return DP_OK;
}

static int cmp_eig(const void *a, const void *b)
{
    const dp_damped_eig *x = a, *y = b;
    double mx = hypot(x->re, x->im), my = hypot(y->re, y->im);
    return mx < my ? -1 : mx > my ? 1 : (x->re > y->re) - (x->re < y->re);
}

/* The first-order form z' = A z, A = [0 I; -M^-1 K  -M^-1 C], by GSL's nonsymmetric eigensolver. */
static int damped_eigs(size_t n, const double *M, const double *K, const double *C, dp_modes *out)
{
    size_t N = 2 * n;
    gsl_matrix *L = gsl_matrix_alloc(n, n), *R = gsl_matrix_alloc(n, 2 * n), *A = gsl_matrix_calloc(N, N);
    gsl_vector_complex *w = gsl_vector_complex_alloc(N);
    gsl_eigen_nonsymm_workspace *ws = gsl_eigen_nonsymm_alloc(N);
    out->eig = malloc(N * sizeof *out->eig);
    int s = L && R && A && w && ws && out->eig ? DP_OK : DP_ENOMEM;
    if (s == DP_OK) {
        memcpy(L->data, M, n * n * sizeof *M);
        for (size_t i = 0; i < n; i++)
            for (size_t j = 0; j < n; j++) {
                gsl_matrix_set(R, i, j, K[i * n + j]);
                gsl_matrix_set(R, i, n + j, C[i * n + j]);
            }
        if (gsl_linalg_cholesky_decomp1(L) != GSL_SUCCESS)
            s = DP_ESOLVE;
        for (size_t c = 0; s == DP_OK && c < N; c++) {
            gsl_vector_view col = gsl_matrix_column(R, c);
            if (gsl_linalg_cholesky_svx(L, &col.vector) != GSL_SUCCESS)
                s = DP_ESOLVE;
        }
    }
    if (s == DP_OK) {
        for (size_t i = 0; i < n; i++) {
            gsl_matrix_set(A, i, n + i, 1.0);
            for (size_t c = 0; c < N; c++)
                gsl_matrix_set(A, n + i, c, -gsl_matrix_get(R, i, c));
        }
        gsl_eigen_nonsymm_params(0, 1, ws); /* balance: M^-1 K of a badly scaled system spans decades */
        if (gsl_eigen_nonsymm(A, w, ws) != GSL_SUCCESS)
            s = DP_ESOLVE;
    }
    for (size_t k = 0; s == DP_OK && k < N; k++) {
        gsl_complex z = gsl_vector_complex_get(w, k);
        double re = GSL_REAL(z), im = GSL_IMAG(z), mag = hypot(re, im);
        if (im < 0 || !isfinite(mag))
            continue;
        double zeta = mag > 0 ? -re / mag : NAN;
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

static int check_inputs(size_t n, const double *M, const double *K, const double *C, const char *pM,
                        const char *pK, const char *pC, dp_errors *errs)
{
    int s = check_symmetric(n, M, pM, "mass", errs);
    s = s ? s : check_symmetric(n, K, pK, "stiffness", errs);
    s = s || C == NULL ? s : check_symmetric(n, C, pC, "damping", errs);
    if (s != DP_OK)
        return s;
    if (m_diagonal(n, M)) { /* a chain's masses: no O(n^3) factorization to say they are positive */
        for (size_t i = 0; i < n && s == DP_OK; i++)
            if (!(M[i * n + i] > 0)) {
                dp_errors_add(errs, pM, "the mass matrix is not positive definite (entry %zu is %g)", i, M[i * n + i]);
                s = DP_EINVAL;
            }
    } else {
        gsl_matrix *L = gsl_matrix_alloc(n, n);
        if (L == NULL)
            return DP_ENOMEM;
        memcpy(L->data, M, n * n * sizeof *M);
        if (gsl_linalg_cholesky_decomp1(L) != GSL_SUCCESS) {
            dp_errors_add(errs, pM, "the mass matrix is not positive definite");
            s = DP_EINVAL;
        }
        gsl_matrix_free(L);
    }
    return s || is_zero(n, C) ? s : check_psd(n, C, pC, errs);
}

int dp_modes_solve(size_t n, const double *M, const double *K, const double *C, const char *pointer_M,
                   const char *pointer_K, const char *pointer_C, dp_modes *out, dp_errors *errs)
{
    memset(out, 0, sizeof *out);
    if (n == 0 || n > DP_MODES_MAX_NODES) {
        dp_errors_add(errs, "", "a linear analysis takes 1 to %d nodes, not %zu", DP_MODES_MAX_NODES, n);
        return n == 0 ? DP_EINVAL : DP_ELIMIT;
    }
    int damped = !is_zero(n, C);
    if (damped && n > DP_MODES_MAX_DAMPED_NODES) {
        dp_errors_add(errs, pointer_C, "damped eigenvalues are computed for up to %d nodes, not %zu",
                      DP_MODES_MAX_DAMPED_NODES, n);
        return DP_ELIMIT;
    }
    int s = check_inputs(n, M, K, C, pointer_M, pointer_K, pointer_C, errs);
    if (s != DP_OK)
        return s;
    out->n = n;
    out->lambda = malloc(n * sizeof *out->lambda);
    out->shape = malloc(n * n * sizeof *out->shape);
    out->rigid = malloc(n * sizeof *out->rigid);
    out->participation = malloc(n * sizeof *out->participation);
    out->modal_damping = malloc(n * sizeof *out->modal_damping);
    if (!out->lambda || !out->shape || !out->rigid || !out->participation || !out->modal_damping)
        return DP_ENOMEM;
    out->tridiagonal = is_chain(n, M, K);
    if (!out->tridiagonal && n > DP_MODES_MAX_DENSE_NODES) {
        dp_errors_add(errs, pointer_K, "a network that is not a chain (diagonal masses, tridiagonal stiffness) is "
                      "solved densely, for up to %d nodes, not %zu", DP_MODES_MAX_DENSE_NODES, n);
        return DP_ELIMIT;
    }
    s = out->tridiagonal ? solve_chain(n, M, K, out) : solve_dense(n, M, K, out);
    s = s ? s : finish_shapes(n, M, m_diagonal(n, M), K, pointer_K, out, errs);
    s = s ? s : modal_damping(n, damped ? C : NULL, out);
    if (s != DP_OK)
        return s;
    out->damped = damped;
    return damped ? damped_eigs(n, M, K, C, out) : DP_OK;
}
