/* src/core/analysis/stability.c - stability of a linear fully implicit law sum lambda_i F_V^(i) = sum mu_j x^(j)
 * closing m x'' + F_V = 0 (thesis chapter 1; docs/mathematics.md section 2).
 *
 * Laplace: F_V = -m z^2 x, so p(z) = m z^2 lambda(z) + mu(z). Using x^(j) = -F_V^(j-2)/m for j >= 2 the law
 * becomes c(D) F_V = mu_0 x + mu_1 x' with c_k = lambda_k + mu_(k+2)/m = p_(k+2)/m, which gives the explicit
 * state matrix of thesis (1.9), (1.11), (1.13) in the variables (x, x', F_V, ..., F_V^(s-1)) when the leading
 * coefficient is nonzero, and the pencil E w' = A w of the same variables when it vanishes (a DAE).
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>

#include "dashpot/stability.h"

#define NMAX DP_STAB_MAX_DEGREE
#define DIMMAX (DP_STAB_MAX_DEGREE + 1)    /* the pencil has at least 3 variables */

/* GSL workspaces by dimension, allocated when a dimension is first used, and only those of the solver used
 * (state_ws, pencil_ws): one analysis needs one dimension and one solver, and allocating all eleven of both
 * up front (~130 mallocs) was most of a small POST /v1/stability. */
struct dp_stability_ws {
    dp_poly_ws *poly;
    gsl_eigen_nonsymm_workspace *ns[DIMMAX + 1];
    gsl_eigen_gen_workspace *gen[DIMMAX + 1];
    gsl_matrix *m1[DIMMAX + 1], *m2[DIMMAX + 1];
    gsl_vector_complex *eval[DIMMAX + 1];
    gsl_vector *beta[DIMMAX + 1];
};

dp_stability_ws *dp_stability_ws_alloc(void)
{
    dp_stability_ws *w = calloc(1, sizeof *w);
    if (w == NULL)
        return NULL;
    if ((w->poly = dp_poly_ws_alloc()) == NULL) {
        free(w);
        return NULL;
    }
    return w;
}

/* The state matrix's workspaces of dimension d (1 .. DIMMAX), allocated on first use: nonsymmetric
 * eigensolver, matrix, eigenvalues. DP_OK or DP_ENOMEM (what was allocated stays, for the next call or
 * dp_stability_ws_free). */
static int state_ws(dp_stability_ws *w, int d)
{
    size_t n = (size_t)d;
    if (!w->ns[d] && (w->ns[d] = gsl_eigen_nonsymm_alloc(n)) != NULL)
        gsl_eigen_nonsymm_params(0, 1, w->ns[d]); /* balancing makes the eigenvalues of a badly scaled
                                                     companion-like matrix accurate */
    if (!w->m1[d])
        w->m1[d] = gsl_matrix_alloc(n, n);
    if (!w->eval[d])
        w->eval[d] = gsl_vector_complex_alloc(n);
    return w->ns[d] && w->m1[d] && w->eval[d] ? DP_OK : DP_ENOMEM;
}

/* The pencil's workspaces of dimension d, likewise: QZ, two matrices, alpha and beta. */
static int pencil_ws(dp_stability_ws *w, int d)
{
    size_t n = (size_t)d;
    if (!w->gen[d])
        w->gen[d] = gsl_eigen_gen_alloc(n);
    if (!w->m1[d])
        w->m1[d] = gsl_matrix_alloc(n, n);
    if (!w->m2[d])
        w->m2[d] = gsl_matrix_alloc(n, n);
    if (!w->eval[d])
        w->eval[d] = gsl_vector_complex_alloc(n);
    if (!w->beta[d])
        w->beta[d] = gsl_vector_alloc(n);
    return w->gen[d] && w->m1[d] && w->m2[d] && w->eval[d] && w->beta[d] ? DP_OK : DP_ENOMEM;
}

void dp_stability_ws_free(dp_stability_ws *w)
{
    if (w == NULL)
        return;
    dp_poly_ws_free(w->poly);
    for (int d = 1; d <= DIMMAX; d++) {
        if (w->ns[d]) gsl_eigen_nonsymm_free(w->ns[d]);
        if (w->gen[d]) gsl_eigen_gen_free(w->gen[d]);
        if (w->m1[d]) gsl_matrix_free(w->m1[d]);
        if (w->m2[d]) gsl_matrix_free(w->m2[d]);
        if (w->eval[d]) gsl_vector_complex_free(w->eval[d]);
        if (w->beta[d]) gsl_vector_free(w->beta[d]);
    }
    free(w);
}

dp_poly_ws *dp_stability_ws_poly(dp_stability_ws *w)
{
    return w->poly;
}

/* ---- the law ---- */

static int coef_ok(double v)
{
    return isfinite(v) && fabs(v) <= DP_STAB_COEF_MAX && (v == 0.0 || fabs(v) >= DP_STAB_COEF_MIN);
}

static int check_array(const double *c, int n, const char *ptr, const char *name, dp_errors *errs)
{
    char p[DP_POINTER_MAX];
    int s = DP_OK;
    if (n < 1 || n > DP_STAB_MAX_ORDER + 1) {
        snprintf(p, sizeof p, "%s/law/%s", ptr, name);
        dp_errors_add(errs, p, n < 1 ? "expected at least one coefficient"
                                     : "at most %d coefficients (derivative order <= %d)",
                      DP_STAB_MAX_ORDER + 1, DP_STAB_MAX_ORDER);
        return n < 1 ? DP_EINVAL : DP_ELIMIT;
    }
    for (int i = 0; i < n; i++) {
        if (coef_ok(c[i]))
            continue;
        snprintf(p, sizeof p, "%s/law/%s/%d", ptr, name, i);
        if (!isfinite(c[i])) {
            dp_errors_add(errs, p, "expected a finite number");
            s = DP_EINVAL;
        } else {
            dp_errors_add(errs, p, "expected 0 or a magnitude in [%g, %g]", DP_STAB_COEF_MIN, DP_STAB_COEF_MAX);
            if (s == DP_OK)
                s = DP_ELIMIT;
        }
    }
    return s;
}

int dp_law_check(const dp_law *law, const char *ptr, dp_errors *errs)
{
    char p[DP_POINTER_MAX];
    int s = DP_OK;
    if (!isfinite(law->mass) || law->mass <= 0.0) {
        snprintf(p, sizeof p, "%s/mass", ptr);
        dp_errors_add(errs, p, "expected a finite number > 0");
        s = DP_EINVAL;
    } else if (law->mass < DP_STAB_COEF_MIN || law->mass > DP_STAB_COEF_MAX) {
        snprintf(p, sizeof p, "%s/mass", ptr);
        dp_errors_add(errs, p, "expected a mass in [%g, %g]", DP_STAB_COEF_MIN, DP_STAB_COEF_MAX);
        s = DP_ELIMIT;
    }
    int sl = check_array(law->lambda, law->nlambda, ptr, "lambda", errs);
    int sm = check_array(law->mu, law->nmu, ptr, "mu", errs);
    /* EINVAL (a wrong value) outranks ELIMIT (a value beyond a documented limit). */
    int all[3] = { s, sl, sm };
    for (int i = 0; i < 3; i++)
        if (all[i] == DP_EINVAL || (all[i] == DP_ELIMIT && s == DP_OK))
            s = all[i];
    return s;
}

int dp_law_degree(const dp_law *law)
{
    int a = law->nlambda + 1, b = law->nmu - 1;
    return a > b ? a : b;
}

/* p_k, ascending: p_0 = mu_0, p_1 = mu_1, p_k = m lambda_(k-2) + mu_k. */
static void charpoly_ascending(const dp_law *law, double *p, int n)
{
    for (int k = 0; k <= n; k++) {
        double l = (k >= 2 && k - 2 < law->nlambda) ? law->lambda[k - 2] : 0.0;
        double u = k < law->nmu ? law->mu[k] : 0.0;
        double ml = law->mass * l, v = fma(law->mass, l, u);
        /* m lambda + mu within one rounding of its terms of zero: the data cannot tell it from 0 (e.g.
         * m = 3, lambda = 0.1, mu = -0.3 leaves 2.8e-17); keep it exactly 0 so the degree stays honest. */
        if (fabs(v) <= 2.0 * DBL_EPSILON * fmax(fabs(ml), fabs(u)))
            v = 0.0;
        p[k] = v;
    }
}

int dp_law_charpoly(const dp_law *law, double *a)
{
    int n = dp_law_degree(law);
    if (n > NMAX || law->nlambda < 1 || law->nmu < 1)
        return DP_EINVAL;
    double p[NMAX + 1];
    charpoly_ascending(law, p, n);
    for (int k = 0; k <= n; k++)
        a[k] = p[n - k];
    return DP_OK;
}

/* ---- the thesis models ---- */

static int order_of(const double *c, int n)
{
    while (n > 1 && c[n - 1] == 0.0)
        n--;
    return n - 1;
}

static void closed_value(dp_closed_form *cf, double m)
{
    double l1 = cf->lambda1, l2 = cf->lambda2, u1 = cf->mu1, u2 = cf->mu2, u3 = cf->mu3, scale;
    switch (cf->model) {
    case DP_MODEL_1_2:    /* (1.10) */
        cf->value = u2 - l1 * u1;
        scale = fabs(u2) + fabs(l1 * u1);
        cf->applies = l1 > 0 && u1 > 0 && u2 > 0;
        break;
    case DP_MODEL_1_3:    /* (1.12) */
        cf->value = l1 * m * (u2 - l1 * u1) - l2 * u2 * u2;
        scale = fabs(l1 * m * u2) + fabs(l1 * m * l1 * u1) + fabs(l2 * u2 * u2);
        cf->applies = l1 > 0 && l2 > 0 && u1 > 0 && u2 > 0;
        break;
    default:              /* (1.14); undefined for mu2 = 0, where it does not apply anyway */
        cf->value = u2 != 0.0 ? l1 * (m + u3) - l2 * u2 - l1 * l1 * m * u1 / u2 : 0.0;
        scale = u2 != 0.0 ? fabs(l1 * m) + fabs(l1 * u3) + fabs(l2 * u2) + fabs(l1 * l1 * m * u1 / u2) : 0.0;
        cf->applies = l1 > 0 && l2 > 0 && u1 > 0 && u2 > 0 && m + u3 > 0;
        break;
    }
    /* The inputs and each operation carry a relative rounding of eps: a value within a few eps of the sum
     * of the magnitudes of its terms is zero as far as the data can tell (the thesis' "= 0", the boundary). */
    cf->tolerance = 8.0 * DBL_EPSILON * scale;
    if (!cf->applies)
        cf->verdict = DP_VERDICT_UNDECIDED;
    else
        cf->verdict = cf->value > cf->tolerance ? DP_VERDICT_STABLE
                      : cf->value < -cf->tolerance ? DP_VERDICT_UNSTABLE : DP_VERDICT_MARGINAL;
}

int dp_law_closed_form(const dp_law *law, dp_closed_form *cf)
{
    static const struct { const char *name, *condition, *expression; } info[] = {
        { NULL, NULL, NULL },
        { "1.2", "(1.10)", "mu2 - lambda*mu1 > 0" },
        { "1.3", "(1.12)", "lambda1*m*(mu2 - lambda1*mu1) - lambda2*mu2^2 > 0" },
        { "1.4", "(1.14)", "lambda1*(m + mu3) - lambda2*mu2 - lambda1^2*m*mu1/mu2 > 0" },
    };
    memset(cf, 0, sizeof *cf);
    int ol = order_of(law->lambda, law->nlambda), om = order_of(law->mu, law->nmu);
    double l0 = law->lambda[0];
    if (l0 != 0.0 && ol == 1 && om <= 1)
        cf->model = DP_MODEL_1_2;
    else if (l0 != 0.0 && ol == 2 && om <= 1)
        cf->model = DP_MODEL_1_3;
    else if (l0 != 0.0 && ol == 2 && om == 2)
        cf->model = DP_MODEL_1_4;
    if (cf->model == DP_MODEL_NONE)
        return 0;
    cf->name = info[cf->model].name;
    cf->condition = info[cf->model].condition;
    cf->expression = info[cf->model].expression;
    /* The thesis writes F_V with coefficient 1: divide the law by lambda_0. */
    cf->lambda1 = law->lambda[1] / l0;
    cf->lambda2 = ol == 2 ? law->lambda[2] / l0 : 0.0;
    cf->mu1 = law->mu[0] / l0;
    cf->mu2 = om >= 1 ? law->mu[1] / l0 : 0.0;
    cf->mu3 = om == 2 ? law->mu[2] / l0 : 0.0;
    closed_value(cf, law->mass);
    return 1;
}

/* ---- explicit state matrix and pencil ---- */

/* Reorders the eigenvalues re/im[0..n-1] to pair with the roots greedily by distance (so both lists read in
 * the same order) and returns the largest |eigenvalue - root| / max(1, |root|). */
static double match_roots(const dp_poly_report *r, double *re, double *im, int n)
{
    double wr[DIMMAX], wi[DIMMAX], worst = 0.0;
    int used[DIMMAX] = { 0 }, m = n < r->degree ? n : r->degree;
    memcpy(wr, re, (size_t)n * sizeof *re);
    memcpy(wi, im, (size_t)n * sizeof *im);
    for (int i = 0; i < m; i++) {
        int best = 0;
        double bd = INFINITY;
        for (int j = 0; j < n; j++) {
            double d = hypot(wr[j] - r->root_re[i], wi[j] - r->root_im[i]);
            if (!used[j] && d < bd) {
                bd = d;
                best = j;
            }
        }
        used[best] = 1;
        re[i] = wr[best];
        im[i] = wi[best];
        worst = fmax(worst, bd / fmax(1.0, hypot(r->root_re[i], r->root_im[i])));
    }
    for (int j = 0, k = m; j < n; j++)       /* eigenvalues without a root partner go last */
        if (!used[j]) {
            re[k] = wr[j];
            im[k++] = wi[j];
        }
    return n == r->degree ? worst : INFINITY;
}

static void fill_state(const dp_law *law, const double *p, int n, dp_state_matrix *sm)
{
    double m = law->mass, *s = sm->s;
    sm->dim = n;
    memset(s, 0, sizeof sm->s);
    s[0 * n + 1] = 1.0;                               /* x' = y */
    if (n == 2) {                                     /* F_V = (mu0 x + mu1 y)/c0 eliminated: m c0 = p2 */
        s[1 * n + 0] = -p[0] / p[2];
        s[1 * n + 1] = -p[1] / p[2];
        return;
    }
    s[1 * n + 2] = -1.0 / m;                          /* y' = -F_V/m */
    for (int k = 0; k + 3 < n; k++)                   /* (F_V^(k))' = F_V^(k+1) */
        s[(k + 2) * n + k + 3] = 1.0;
    double *last = s + (n - 1) * n;                   /* c_s F^(s)= mu0 x + mu1 y - sum c_k F^(k) */
    last[0] = m * p[0] / p[n];
    last[1] = m * p[1] / p[n];
    for (int k = 0; k + 2 < n; k++)
        last[k + 2] = -p[k + 2] / p[n];
}

static int state_matrix(dp_stability_ws *w, const dp_law *law, const double *p, int n, dp_stability *out)
{
    dp_state_matrix *sm = &out->state;
    fill_state(law, p, n, sm);
    if (state_ws(w, n) != DP_OK)
        return DP_ENOMEM;
    gsl_matrix *a = w->m1[n];
    for (int i = 0; i < n * n; i++)
        a->data[(i / n) * a->tda + i % n] = sm->s[i];
    if (gsl_eigen_nonsymm(a, w->eval[n], w->ns[n]) != GSL_SUCCESS)
        return DP_ESOLVE;
    for (int i = 0; i < n; i++) {
        gsl_complex z = gsl_vector_complex_get(w->eval[n], (size_t)i);
        sm->eig_re[i] = GSL_REAL(z);
        sm->eig_im[i] = GSL_IMAG(z);
    }
    sm->deviation = match_roots(&out->poly, sm->eig_re, sm->eig_im, n);
    return isfinite(sm->deviation) ? DP_OK : DP_ESOLVE;
}

static void fill_pencil(const dp_law *law, const double *p, int n, dp_pencil *pc)
{
    int dim = n > 3 ? n : 3, s = dim - 2, last = dim - 1;
    double m = law->mass, *e = pc->e, *a = pc->a;
    pc->dim = dim;
    memset(e, 0, sizeof pc->e);
    memset(a, 0, sizeof pc->a);
    e[0] = 1.0, a[1] = 1.0;                                    /* x' = y */
    e[dim + 1] = m, a[dim + 2] = -1.0;                         /* m y' = -F_V */
    for (int k = 0; k < s - 1; k++)                            /* (F^(k))' = F^(k+1) */
        e[(k + 2) * dim + k + 2] = 1.0, a[(k + 2) * dim + k + 3] = 1.0;
    e[last * dim + last] = s + 2 <= n ? p[s + 2] : 0.0;        /* m c_s F^(s) = m mu0 x + m mu1 y - ... */
    a[last * dim + 0] = m * p[0];
    a[last * dim + 1] = m * p[1];
    for (int k = 0; k < s; k++)
        a[last * dim + k + 2] = -(k + 2 <= n ? p[k + 2] : 0.0);
}

static double frob(const double *x, int dim)
{
    double s = 0.0;
    for (int i = 0; i < dim * dim; i++)
        s = hypot(s, x[i]);
    return s;
}

static int pencil(dp_stability_ws *w, const dp_law *law, const double *p, int n, const dp_poly_report *r,
                  dp_pencil *pc)
{
    fill_pencil(law, p, n, pc);
    int d = pc->dim;
    if (pencil_ws(w, d) != DP_OK)
        return DP_ENOMEM;
    gsl_matrix *a = w->m1[d], *e = w->m2[d];
    for (int i = 0; i < d * d; i++) {
        a->data[(i / d) * a->tda + i % d] = pc->a[i];
        e->data[(i / d) * e->tda + i % d] = pc->e[i];
    }
    /* QZ on A x = z E x; beta = 0 marks an infinite eigenvalue, alpha = beta = 0 a singular pencil. The
     * thresholds are backward-error sized: QZ is exact for a pencil perturbed by ~ dim eps ||.||. */
    double ta = 16.0 * d * DBL_EPSILON * frob(pc->a, d), tb = 16.0 * d * DBL_EPSILON * frob(pc->e, d);
    if (gsl_eigen_gen(a, e, w->eval[d], w->beta[d], w->gen[d]) != GSL_SUCCESS)
        return DP_ESOLVE;
    pc->nfinite = pc->ninfinite = pc->singular = 0;
    for (int i = 0; i < d; i++) {
        gsl_complex al = gsl_vector_complex_get(w->eval[d], (size_t)i);
        double be = gsl_vector_get(w->beta[d], (size_t)i), aa = hypot(GSL_REAL(al), GSL_IMAG(al));
        if (fabs(be) <= tb && aa <= ta)
            pc->singular = 1;
        else if (fabs(be) <= tb || !isfinite(aa / be))
            pc->ninfinite++;
        else {
            pc->fin_re[pc->nfinite] = GSL_REAL(al) / be;
            pc->fin_im[pc->nfinite++] = GSL_IMAG(al) / be;
        }
    }
    pc->deviation = pc->nfinite == r->degree ? match_roots(r, pc->fin_re, pc->fin_im, pc->nfinite) : -1.0;
    return DP_OK;
}

/* ---- the report ---- */

int dp_stability_analyse(dp_stability_ws *w, const dp_law *law, dp_stability *out)
{
    if (dp_law_check(law, "", NULL) != DP_OK)
        return DP_EINVAL;
    memset(out, 0, sizeof *out);
    int n = out->nominal_degree = dp_law_degree(law);
    double p[NMAX + 1];
    charpoly_ascending(law, p, n);
    for (int k = 0; k <= n; k++)
        out->coef[k] = p[n - k];
    int s = dp_poly_analyse(w->poly, out->coef, n, &out->poly);
    if (s != DP_OK)
        return s;
    out->dae = p[n] == 0.0;
    s = out->dae ? pencil(w, law, p, n, &out->poly, &out->pencil) : state_matrix(w, law, p, n, out);
    if (s != DP_OK)
        return s;
    if (out->poly.degree < 0)
        out->pencil.singular = 1;
    dp_law_closed_form(law, &out->closed);
    out->verdict = out->pencil.singular ? DP_VERDICT_ILL_POSED : out->poly.verdict;
    return DP_OK;
}

int dp_stability_verdict(dp_stability_ws *w, const dp_law *law, dp_verdict *v, double *abscissa,
                         int *has_abscissa)
{
    double a[NMAX + 1];
    int s = dp_law_charpoly(law, a);
    if (s != DP_OK)
        return s;
    return dp_poly_verdict(w->poly, a, dp_law_degree(law), v, abscissa, has_abscissa);
}
