/* src/core/lcp/lcs_model.c - the LCS model a spec owns (copy, free) and its spec rules: the stick-slip θ-step,
 * the step count, and an initial state the laws admit (Cibulka 2014, (1.10): at t = 0 some u must give
 * (u, C x0 + D u + q) in the laws; with D = 0 and an ideal diode that is C x0 + q >= 0, a current that
 * does not already flow backwards). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/lcs.h"
#include "dashpot/wellposedness.h"
#include "dashpot/status.h"

void dp_lcs_model_free(dp_lcs_model *lm)
{
    if (lm == NULL)
        return;
    free(lm->A);
    free(lm->B);
    free(lm->C);
    free(lm->D);
    free(lm->p);
    free(lm->q);
    free(lm->x0);
    for (size_t i = 0; lm->law && i < lm->m; i++)
        dp_graph_clear(&lm->law[i].graph);
    free(lm->law);
    if (lm->pf)
        for (size_t i = 0; i < lm->n; i++)
            dp_forcing_clear(&lm->pf[i]);
    free(lm->pf);
    free(lm);
}

static double *dup(const double *a, size_t k, int *fail)
{
    double *d = malloc((k ? k : 1) * sizeof *d);
    if (d == NULL)
        *fail = 1;
    else if (a)
        memcpy(d, a, k * sizeof *d);
    else
        memset(d, 0, (k ? k : 1) * sizeof *d);
    return d;
}

dp_lcs_model *dp_lcs_model_copy(const dp_lcs_model *src)
{
    dp_lcs_model *d = calloc(1, sizeof *d);
    if (d == NULL)
        return NULL;
    size_t n = src->n, m = src->m;
    int fail = 0;
    d->n = n, d->m = m;
    d->A = dup(src->A, n * n, &fail), d->B = dup(src->B, n * m, &fail), d->C = dup(src->C, m * n, &fail);
    d->D = dup(src->D, m * m, &fail), d->p = dup(src->p, n, &fail), d->q = dup(src->q, m, &fail);
    d->x0 = dup(src->x0, n, &fail);
    d->law = calloc(m ? m : 1, sizeof *d->law);
    for (size_t i = 0; d->law && i < m; i++) {
        d->law[i] = src->law[i];
        memset(&d->law[i].graph, 0, sizeof d->law[i].graph);
        if (src->law[i].graph.n > 0)
            fail |= dp_graph_copy(&d->law[i].graph, &src->law[i].graph) != DP_OK;
    }
    if (src->pf && !fail && (d->pf = calloc(n, sizeof *d->pf)) == NULL)
        fail = 1;
    for (size_t i = 0; src->pf && d->pf && i < n; i++)
        fail |= dp_forcing_copy(&d->pf[i], &src->pf[i]) != DP_OK;
    if (fail || d->law == NULL) {
        dp_lcs_model_free(d);
        return NULL;
    }
    return d;
}

dp_lcs dp_lcs_model_system(const dp_lcs_model *lm)
{
    return (dp_lcs){ lm->n, lm->m, lm->A, lm->B, lm->C, lm->D, lm->p, lm->q, lm->law };
}

/* The outcome of the algebraic part at x0 as a located error: the state is to blame only when the laws admit
 * no u there (Lemke's ray) or C x0 + q leaves the doubles; Lemke's own limits name the solver. The status. */
static int initial_error(int s, const dp_lcp_result *res, dp_errors *e)
{
    if (s == DP_ESOLVE && res->outcome == DP_LCP_RAY) {
        dp_errors_add(e, "/initial/x", "the laws admit no u at this state: w = C x + D u + q cannot meet "
                      "them (an ideal diode with D = 0 needs C x + q >= 0: no current flowing backwards)");
        return DP_EINVAL;
    }
    if (s == DP_ESOLVE) {
        dp_errors_add(e, "/solver", "Lemke's method ended the algebraic part at t = 0 on a basis whose answer "
                      "fails its check (relative residual %.3g): D is too ill-conditioned for the rounding",
                      res->residual);
        return DP_EINVAL;
    }
    if (s == DP_ELIMIT) {
        dp_errors_add(e, "/solver", "Lemke's method took its limit of %zu pivots on the algebraic part at t = 0 "
                      "without ending", res->pivots);
        return DP_ELIMIT;
    }
    if (s == DP_ENONFINITE) {
        dp_errors_add(e, "/initial/x", "C x + q, or the u it asks for, is beyond the double range at this state");
        return DP_EINVAL;
    }
    dp_errors_add(e, "/solver", "the algebraic part at t = 0 could not be solved (%s)", dp_strerror(s));
    return s;
}

/* The check below runs while the document is read, before the run has a stop hook or a wall limit (in the
 * daemon, on a connection thread): it may do CHECK_POLLS of Lemke's polls of work (each ~2^21 multiply-adds
 * or their worth, ~50 ms in all). A problem that needs more is left undecided here, and the run's first step,
 * under its stop hook, decides it: Murty's 250-component matrix as D took 9.8 s to reach the pivot limit in
 * this check. */
#define CHECK_POLLS 50

static int check_budget(void *ctx)
{
    unsigned *polls = ctx;
    return ++*polls > CHECK_POLLS;
}

/* Is there a u for x0? The algebraic part alone (h = 0) at x0, by Lemke, within the budget above. The status
 * (DP_OK also when the budget ran out). */
static int check_initial(const dp_lcs_model *lm, dp_errors *e)
{
    dp_lcs sys = dp_lcs_model_system(lm);
    int s;
    const char *where, *why;
    dp_lcs_stepper *st = dp_lcs_stepper_alloc_why(&sys, 0.0, 1.0, &s, &where, &why);
    if (st == NULL) {
        dp_errors_add(e, where[0] ? where : "/model/lcs", "%s", why);
        return s;
    }
    double *x = malloc(lm->n * sizeof *x), *u = malloc(lm->m * sizeof *u), *w = malloc(lm->m * sizeof *w);
    dp_lcp_result res;
    if (x && u && w) {
        memcpy(x, lm->x0, lm->n * sizeof *x);
        unsigned polls = 0;
        dp_stop budget = { check_budget, &polls };
        s = dp_lcs_step_until(st, x, u, w, &res, &budget);
        s = s == DP_OK || s == DP_ECANCEL ? DP_OK : initial_error(s, &res, e);
    } else {
        s = DP_ENOMEM;
    }
    free(x);
    free(u);
    free(w);
    dp_lcs_stepper_free(st);
    return s;
}

int dp_lcs_check(const dp_spec *s, double max_steps, dp_errors *e)
{
    size_t before = e->n + e->dropped;
    const dp_lcs_model *lm = s->lcs;
    if (s->solver.kind != DP_SOLVER_STICK_SLIP)
        dp_errors_add(e, "/solver/kind", "an LCS model runs on the \"stick-slip\" θ-step (one LCP per step)");
    else if (s->solver.variant != DP_VARIANT_EXACT)
        dp_errors_add(e, "/solver/variant", "an LCS model runs on the \"exact\" variant");
    if (e->n + e->dropped > before)
        return DP_EINVAL;
    int st = check_initial(lm, e);
    if (st == DP_ENOMEM || st == DP_ELIMIT)
        return st;
    dp_lcs sys = dp_lcs_model_system(lm);
    const char *where, *why;
    int sa;
    dp_lcs_stepper *step = dp_lcs_stepper_alloc_why(&sys, s->solver.dt, s->solver.theta, &sa, &where, &why);
    if (step == NULL && sa == DP_ENOMEM)
        return DP_ENOMEM;
    if (step == NULL)
        dp_errors_add(e, where[0] ? where : "/model/lcs", "%s", why);
    dp_lcs_stepper_free(step);
    if (e->n + e->dropped > before)
        return DP_EINVAL;
    if (max_steps <= 0 || max_steps > DP_SPEC_MAX_STEPS)
        max_steps = DP_SPEC_MAX_STEPS;
    double n = s->solver.t_end / s->solver.dt;
    if (!(n * (double)(lm->n + lm->m) <= max_steps)) {
        dp_errors_add(e, "/solver/dt", "t_end/dt = %.6g steps of %zu states and %zu components exceed the limit "
                      "of %.6g node-steps per run", n, lm->n, lm->m, max_steps);
        return DP_ELIMIT;
    }
    return DP_OK;
}

/* ---- what Cibulka 2014's theory says about an LCS (/v1/wellposedness) ------------------------------------ */

static const char *const TH23 = "Cibulka 2014, Theorem 2.3 with Lemma 2.5 (D's symmetric part positive definite: u = s(x) "
                                "is Lipschitz, and x' = A x + B s(x) + p a Lipschitz ODE)";

/* Appends a check; its detail is written by the caller into the returned slot. */
static char *add_check(dp_wp_report *rep, const char *name, int holds)
{
    dp_wp_check *c = &rep->check[rep->nchecks++];
    c->name = name;
    c->holds = holds;
    return c->detail;
}

int dp_lcs_wellposedness(const dp_spec *s, dp_wp_report *rep)
{
    const dp_lcs_model *lm = s->lcs;
    memset(rep, 0, sizeof *rep);
    rep->framework = "LCS";
    gsl_matrix_const_view D = gsl_matrix_const_view_array(lm->D, lm->m, lm->m);
    dp_lcp_theory td, ts;
    int st = dp_lcp_theory_of(&D.matrix, &td);
    if (st != DP_OK)
        return st;
    dp_lcs sys = dp_lcs_model_system(lm);
    dp_lcs_stepper *step = dp_lcs_stepper_alloc(&sys, s->solver.dt, s->solver.theta, &st);
    if (step == NULL)
        return st;
    st = dp_lcp_theory_of(dp_lcs_step_matrix(step), &ts);
    dp_lcs_stepper_free(step);
    if (st != DP_OK)
        return st;
    char *d = add_check(rep, "the laws are maximal monotone (complementarity and intervals: normal cones of convex "
                        "sets, Cibulka 2014, Proposition 1.7 for their product; graph laws: monotone curves unbounded "
                        "at both ends)", 1);
    snprintf(d, DP_WP_TEXT, "holds for every law this model takes");
    d = add_check(rep, "D has a positive definite symmetric part (Cibulka 2014, Lemma 2.5)", td.pd_symmetric);
    snprintf(d, DP_WP_TEXT, td.pd_symmetric ? "mu = lambda_min((D + D^T)/2) = %.6g > 0: u is Lipschitz in x"
                                            : "mu = lambda_min((D + D^T)/2) = %.6g, not > 0", td.mu);
    d = add_check(rep, "the step's matrix D + hCWB is a P-matrix (one u per step)", ts.p_matrix == 1);
    if (ts.p_matrix == 1)
        snprintf(d, DP_WP_TEXT, "its mu = %.6g; at dt = %.6g every step has exactly one u", ts.mu, s->solver.dt);
    else if (ts.p_matrix == 0)
        snprintf(d, DP_WP_TEXT, "a principal minor is %.6g <= 0 at dt = %.6g: a step may have several u or none",
                 ts.minor, s->solver.dt);
    else
        snprintf(d, DP_WP_TEXT, "undecided (more than %d components) at dt = %.6g", DP_LCP_ENUM_MAX, s->solver.dt);
    dp_wp_verdict *ex = &rep->existence, *un = &rep->uniqueness;
    ex->guaranteed = un->guaranteed = td.pd_symmetric;
    ex->theorem = un->theorem = td.pd_symmetric ? TH23 : NULL;
    if (td.pd_symmetric)
        snprintf(ex->reason, sizeof ex->reason, "all hypotheses hold");
    else
        snprintf(ex->reason, sizeof ex->reason, "D's symmetric part is not positive definite (mu = %.6g): Cibulka 2014's "
                 "reduction to an ODE does not apply (ideal diodes have D = 0); the θ-step %s", td.mu,
                 ts.p_matrix == 1 ? "is well defined (its matrix is a P-matrix)" : "may have several u or none");
    memcpy(un->reason, ex->reason, sizeof un->reason);
    return DP_OK;
}
