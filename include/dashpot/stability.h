/* include/dashpot/stability.h - stability of linear fully implicit laws (Babováková 2012, chapter 1).
 *
 * A law  sum_i lambda_i F_V^(i) = sum_j mu_j x^(j)  closes  m x'' + F_V = 0.  With the Laplace variable z its
 * characteristic polynomial is  p(z) = m z^2 lambda(z) + mu(z)  (docs/mathematics.md section 2). The analysis gives
 * the roots (companion matrix, GSL), the spectral abscissa, the leading principal minors of the Hurwitz matrix
 * H_ij = a_(2i-j) (thesis Thm 1.1), a verdict that holds only when the two tests agree within rounding, the
 * closed-form conditions (1.10), (1.12), (1.14) when the law has the shape of thesis model 1.2, 1.3 or 1.4,
 * the explicit first-order state matrix ((1.9), (1.11), (1.13)) and, when the leading coefficient vanishes
 * (a DAE), the pencil E z' = A z with its finite and infinite generalized eigenvalues.
 *
 * The polynomial part (dp_poly_*) knows nothing about oscillators, so an n-degree-of-freedom chain can feed
 * it det(M z^2 + ...) later. Nothing here allocates except the workspace and the map.
 */
#ifndef DASHPOT_STABILITY_H
#define DASHPOT_STABILITY_H

#include <stddef.h>
#include "dashpot/status.h"

/* Highest derivative order accepted in lambda and in mu (9 coefficients each), so p has degree <= 10. */
#define DP_STAB_MAX_ORDER 8
#define DP_STAB_MAX_DEGREE (DP_STAB_MAX_ORDER + 2)
/* Magnitude limits that keep every Hurwitz minor (a product of up to 10 rows) and every companion entry
 * far from overflow and underflow: |coefficient| <= 1e12, nonzero |coefficient| >= 1e-12, mass in
 * [1e-12, 1e12]. Then |a_k| <= 2e24 and a product of ten rows stays below 1e260. */
#define DP_STAB_COEF_MAX 1e12
#define DP_STAB_COEF_MIN 1e-12

/* Verdicts, from the most to the least favourable. */
typedef enum dp_verdict {
    DP_VERDICT_STABLE = 0,   /* asymptotically stable: every root has Re z < 0 (certain beyond rounding) */
    DP_VERDICT_MARGINAL,     /* roots on the imaginary axis (within rounding), all simple; the rest Re z < 0 */
    DP_VERDICT_UNSTABLE,     /* a root with Re z > 0, or a multiple root on the axis */
    DP_VERDICT_BOUNDARY,     /* the tests disagree within rounding: too near the boundary to say */
    DP_VERDICT_ILL_POSED,    /* p is identically zero: a singular pencil, x is not determined */
    DP_VERDICT_UNDECIDED     /* used only for one test's own opinion: "within rounding, cannot tell" */
} dp_verdict;

/* "asymptotically stable", "marginally stable", "unstable", "near boundary", "ill-posed", "undecided". */
const char *dp_verdict_name(dp_verdict v);
/* One letter per verdict for maps: S M U B I ?. */
char dp_verdict_letter(dp_verdict v);

/* ---- polynomials: a[0] z^n + a[1] z^(n-1) + ... + a[n], highest power first (thesis (1.1)) ---- */

/* Leading principal minors D_1..D_n of the Hurwitz matrix of a (a[0] != 0, 1 <= n <= DP_STAB_MAX_DEGREE)
 * into minor[0..n-1], and for each an absolute rounding bound into tol[0..n-1] (Gaussian elimination with
 * partial pivoting: backward error ~ k eps growth, times Hadamard's product of row norms). The polynomial is
 * used as given (multiply by -1 first if a[0] < 0). Returns DP_OK or DP_EINVAL (n out of range, a[0] = 0,
 * non-finite input); outputs are untouched on error. */
int dp_poly_hurwitz_minors(const double *a, int n, double *minor, double *tol);

/* The Hurwitz test's own opinion from minors and tolerances: STABLE (all D_k > tol_k), UNSTABLE (some
 * D_k < -tol_k: then a root lies in Re z > 0, since the closure of the Hurwitz set has every D_k >= 0),
 * otherwise UNDECIDED. n = 0 (a nonzero constant) is STABLE: there is no mode at all. */
dp_verdict dp_poly_hurwitz_verdict(const double *minor, const double *tol, int n);

typedef struct dp_poly_ws dp_poly_ws;

/* A workspace for dp_poly_roots/dp_poly_analyse of any degree up to DP_STAB_MAX_DEGREE (GSL's, allocated per
 * degree on first use: those functions may also return DP_ENOMEM); NULL if out of memory. Free with
 * dp_poly_ws_free (accepts NULL). One per thread. */
dp_poly_ws *dp_poly_ws_alloc(void);
void dp_poly_ws_free(dp_poly_ws *w);

/* Roots of a (a[0] != 0, degree n <= DP_STAB_MAX_DEGREE) into re/im[0..n-1], and for each an a-posteriori
 * error radius err[i] (smallest r at which one Taylor term of p about the root outweighs the residual plus the
 * rounding of the evaluation). Roots at zero from trailing zero coefficients are exact. Returns DP_OK,
 * DP_EINVAL, DP_ESOLVE (QR did not converge; outputs undefined). */
int dp_poly_roots(dp_poly_ws *w, const double *a, int n, double *re, double *im, double *err);

/* Everything about one polynomial. */
typedef struct dp_poly_report {
    int degree;                              /* n after dropping leading zeros; -1: p identically zero */
    double a[DP_STAB_MAX_DEGREE + 1];        /* a[0..n], a[0] > 0 (sign normalised) */
    double root_re[DP_STAB_MAX_DEGREE], root_im[DP_STAB_MAX_DEGREE], root_err[DP_STAB_MAX_DEGREE];
    double minor[DP_STAB_MAX_DEGREE], minor_tol[DP_STAB_MAX_DEGREE];
    int has_abscissa;                        /* 0 when there is no root (degree <= 0) */
    double abscissa, abscissa_err;           /* max Re z and the error radius of that root */
    dp_verdict by_hurwitz, by_roots, verdict;
    int near_boundary;                       /* one of the tests could not decide within rounding */
} dp_poly_report;

/* Analyses a[0..n] (highest first; leading zeros allowed and dropped; n <= DP_STAB_MAX_DEGREE). The verdict:
 * both tests certain and agreeing -> that verdict; one certain, the other undecided -> the certain one
 * (near_boundary set); both undecided -> MARGINAL if the roots near the axis are simple and well separated and
 * every other root is certainly stable, else BOUNDARY; certain and contradicting -> BOUNDARY. A root at zero
 * from a[n] == 0 is exact: two or more of them are UNSTABLE, one is MARGINAL when the rest is stable.
 * Returns DP_OK, DP_EINVAL (n out of range or non-finite), DP_ESOLVE. */
int dp_poly_analyse(dp_poly_ws *w, const double *a, int n, dp_poly_report *r);

/* The verdict alone, as fast as it can be had: Hurwitz minors first; the roots only when the minors cannot
 * decide. Same answer as dp_poly_analyse. abscissa may be NULL (else it is computed too, needing the roots). */
int dp_poly_verdict(dp_poly_ws *w, const double *a, int n, dp_verdict *v, double *abscissa, int *has_abscissa);

/* ---- laws ---- */

typedef struct dp_law {
    double mass;
    int nlambda, nmu;                        /* coefficient counts, 1 .. DP_STAB_MAX_ORDER + 1 */
    double lambda[DP_STAB_MAX_ORDER + 1];    /* lambda[i] multiplies F_V^(i) */
    double mu[DP_STAB_MAX_ORDER + 1];        /* mu[j] multiplies x^(j) */
} dp_law;

/* Checks a law against the documented limits, adding located errors under `ptr` ("" for a bare law:
 * "/mass", "/law/lambda/3"). Returns DP_OK, DP_EINVAL (non-finite, mass <= 0, empty arrays) or DP_ELIMIT
 * (order above DP_STAB_MAX_ORDER, magnitudes outside [DP_STAB_COEF_MIN, DP_STAB_COEF_MAX]). */
int dp_law_check(const dp_law *law, const char *ptr, dp_errors *errs);

/* Nominal degree max(nlambda + 1, nmu - 1): the order of the system as written. */
int dp_law_degree(const dp_law *law);

/* The characteristic polynomial m z^2 lambda(z) + mu(z), highest power first, into a[0..n], n =
 * dp_law_degree. a[0] may be zero (a DAE). A coefficient m lambda_k + mu_(k+2) that cancels to within one
 * rounding of its terms is set to exactly zero (the inputs cannot resolve it). Requires a checked law. */
int dp_law_charpoly(const dp_law *law, double *a);

typedef enum dp_thesis_model { DP_MODEL_NONE = 0, DP_MODEL_1_2, DP_MODEL_1_3, DP_MODEL_1_4 } dp_thesis_model;

/* A thesis model recognised by shape (trailing zeros ignored, lambda normalised by lambda_0 != 0):
 * 1.2 lambda order 1, mu order <= 1; 1.3 lambda order 2, mu order <= 1; 1.4 lambda order 2, mu order 2. */
typedef struct dp_closed_form {
    dp_thesis_model model;
    const char *name;           /* "1.2", "1.3", "1.4"; NULL for none */
    const char *condition;      /* "(1.10)", "(1.12)", "(1.14)" */
    const char *expression;     /* the inequality in ASCII, e.g. "mu2 - lambda*mu1 > 0" */
    double lambda1, lambda2, mu1, mu2, mu3;   /* thesis parameters after normalisation (unused ones 0) */
    double value;               /* left side minus right side: > 0 stable */
    double tolerance;           /* |value| <= tolerance is zero within the rounding of the data */
    int applies;                /* every coefficient of p positive, the thesis' assumption; otherwise the
                                   condition alone does not decide */
    dp_verdict verdict;         /* when applies: STABLE (value > tolerance), UNSTABLE (< -tolerance), else
                                   MARGINAL; UNDECIDED when it does not apply */
} dp_closed_form;

/* Recognises the shape and evaluates the condition. Returns 1 if a thesis model was recognised, else 0
 * (cf->model = DP_MODEL_NONE). Requires a checked law. */
int dp_law_closed_form(const dp_law *law, dp_closed_form *cf);

/* The explicit first-order system z' = S z for a law with a nonzero leading coefficient, state
 * (x, x', F_V, F_V', ..., F_V^(s-1)) with s = n - 2, or (x, x') when n = 2 (F_V eliminated) -- for the thesis
 * models exactly (1.9), (1.11), (1.13). Derivatives x^(j), j >= 2, are replaced by -F_V^(j-2)/m. */
typedef struct dp_state_matrix {
    int dim;
    double s[DP_STAB_MAX_DEGREE * DP_STAB_MAX_DEGREE];     /* row-major dim x dim */
    double eig_re[DP_STAB_MAX_DEGREE], eig_im[DP_STAB_MAX_DEGREE];
    double deviation;           /* max over matched pairs |eigenvalue - root| / max(1, |root|) */
} dp_state_matrix;

/* The descriptor form E w' = A w of any law, state (x, x', F_V, ..., F_V^(s-1)), s = max(1, n - 2); the law's
 * row is scaled by m. det(zE - A) = m p(z) (times a sign), so a regular pencil has deg p finite eigenvalues
 * and dim - deg p infinite ones. */
typedef struct dp_pencil {
    int dim;
    double e[(DP_STAB_MAX_DEGREE + 1) * (DP_STAB_MAX_DEGREE + 1)];
    double a[(DP_STAB_MAX_DEGREE + 1) * (DP_STAB_MAX_DEGREE + 1)];
    int nfinite, ninfinite;
    double fin_re[DP_STAB_MAX_DEGREE + 1], fin_im[DP_STAB_MAX_DEGREE + 1];
    int singular;               /* QZ found alpha = beta = 0 (or p is identically zero): ill-posed */
    double deviation;           /* as for the state matrix, finite eigenvalues against the roots; 0 if none,
                                   infinite (not finite: -1) when their count differs from deg p */
} dp_pencil;

/* The whole stability report: the Hurwitz verdict, the roots and the closed forms. */
typedef struct dp_stability {
    int nominal_degree;
    double coef[DP_STAB_MAX_DEGREE + 1];     /* p as written, a[0..nominal_degree], highest first */
    dp_poly_report poly;                      /* the polynomial analysis (trimmed, a[0] > 0) */
    int dae;                                  /* leading coefficient zero: pencil filled, no state matrix */
    dp_state_matrix state;                    /* valid when !dae */
    dp_pencil pencil;                         /* valid when dae */
    dp_closed_form closed;                    /* closed.model == DP_MODEL_NONE when no thesis shape */
    dp_verdict verdict;
} dp_stability;

typedef struct dp_stability_ws dp_stability_ws;

/* A workspace for analyses and maps (GSL workspaces for each size, allocated when a size is first used, so
 * an analysis may also fail with DP_ENOMEM); NULL if out of memory. */
dp_stability_ws *dp_stability_ws_alloc(void);
void dp_stability_ws_free(dp_stability_ws *w);
/* Its polynomial part, for callers that analyse bare polynomials. */
dp_poly_ws *dp_stability_ws_poly(dp_stability_ws *w);

/* Analyses a checked law (dp_law_check). Returns DP_OK, DP_EINVAL (unchecked input), DP_ESOLVE (an eigen
 * solver did not converge); `out` is fully written on DP_OK and unspecified otherwise. */
int dp_stability_analyse(dp_stability_ws *w, const dp_law *law, dp_stability *out);

/* The verdict of a checked law without the report (maps, benchmarks). abscissa/has_abscissa may be NULL. */
int dp_stability_verdict(dp_stability_ws *w, const dp_law *law, dp_verdict *v, double *abscissa,
                         int *has_abscissa);

/* ---- maps over two coefficients ---- */

#define DP_STAB_MAP_MAX_STEPS 2000     /* per axis: 4e6 points, ~10 s of CPU and ~80 MB of JSON at most */

typedef enum dp_param_kind { DP_PARAM_MASS, DP_PARAM_LAMBDA, DP_PARAM_MU } dp_param_kind;

typedef struct dp_map_axis {
    dp_param_kind kind;
    int index;                  /* lambda[index] or mu[index] */
    double from, to;            /* from < to */
    int steps;                  /* points, 2 .. DP_STAB_MAP_MAX_STEPS; value_i = from + (to-from) i/(steps-1) */
} dp_map_axis;

/* Parses "mass", "lambda[i]", "mu[j]". Returns 0 on success, -1 if malformed. */
int dp_param_parse(const char *name, dp_param_kind *kind, int *index);
/* Writes the canonical name ("mu[1]") into out (>= 16 bytes). */
void dp_param_name(dp_param_kind kind, int index, char *out, size_t cap);

/* Checks an axis against the law (index within the array, finite from < to, steps in range, magnitudes as
 * for coefficients, mass positive over the range), errors under ptr ("/map/x"). DP_OK/DP_EINVAL/DP_ELIMIT. */
int dp_map_axis_check(const dp_map_axis *ax, const dp_law *law, const char *ptr, dp_errors *errs);

/* The value of axis point i; |value| < DP_STAB_COEF_MIN is returned as exactly 0 (a grid through zero). */
double dp_map_axis_value(const dp_map_axis *ax, int i);

typedef struct dp_map {
    dp_map_axis x, y;
    size_t nx, ny;
    double *abscissa;           /* ny rows of nx, row-major, y outer */
    unsigned char *has_abscissa;
    unsigned char *verdict;     /* dp_verdict per point */
    dp_closed_form closed;      /* at the base law; model NONE: no closed-form boundary */
    double *closed_value;       /* per point, when closed.model != NONE; NULL otherwise */
    unsigned char *closed_applies;
} dp_map;

/* Fills a map: verdict and spectral abscissa at every grid point (the other coefficients as in `law`), and
 * the closed-form value where the base law has a thesis shape that the swept values keep. Caller-owned `map`
 * is written on DP_OK and holds nothing to free on error. Returns DP_OK, DP_ENOMEM, DP_EINVAL, DP_ESOLVE. */
int dp_stability_map(dp_stability_ws *w, const dp_law *law, const dp_map_axis *x, const dp_map_axis *y,
                     dp_map *map);
void dp_map_clear(dp_map *map);

/* The closed-form boundary value = 0 traced by marching squares over the map grid, as segments in grid
 * coordinates (fractional column, fractional row). Calls emit(ctx, x0, y0, x1, y1) per segment; stops and
 * returns the first nonzero value emit returns, else 0. Cells with a corner where the condition does not
 * apply are skipped. */
int dp_map_boundary(const dp_map *map, int (*emit)(void *ctx, double, double, double, double), void *ctx);

#endif
