/* src/core/rules/network_check.c - the rules a network document must meet before it is stepped (docs/systems.md §1).
 *
 * The step's matrix W = M + h theta C + h^2 theta^2 K must be positive definite and the element laws
 * maximal monotone for the step to be one strictly convex problem: so M must be positive definite, K and C
 * positive semidefinite (checked with GSL's Cholesky and symmetric eigensolver), every initial state inside
 * its graphs' domains. What the network stepping does not do yet is refused by name, never run wrongly.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>

#include "dashpot/newmark.h"

#include "dashpot/spec.h"
#include "rules/rules.h"

/* Whether the n x n matrix A is symmetric to rounding; the first asymmetric pair in *i, *j. */
static int symmetric(const double *A, size_t n, size_t *i, size_t *j)
{
    for (*i = 0; *i < n; (*i)++)
        for (*j = *i + 1; *j < n; (*j)++) {
            double a = A[*i * n + *j], b = A[*j * n + *i];
            if (fabs(a - b) > 1e-12 * (fabs(a) + fabs(b)))
                return 0;
        }
    return 1;
}

/* The smallest eigenvalue of the symmetric matrix A (NAN when out of memory), and its largest magnitude. */
static double min_eigenvalue(const double *A, size_t n, double *scale)
{
    gsl_matrix *m = gsl_matrix_alloc(n, n);
    gsl_vector *ev = gsl_vector_alloc(n);
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc(n);
    double lo = NAN;
    *scale = 0;
    if (m && ev && ws) {
        memcpy(m->data, A, n * n * sizeof *A);
        if (gsl_eigen_symm(m, ev, ws) == 0) {
            lo = gsl_vector_min(ev);
            *scale = fmax(fabs(lo), fabs(gsl_vector_max(ev)));
        }
    }
    gsl_eigen_symm_free(ws);
    gsl_vector_free(ev);
    gsl_matrix_free(m);
    return lo;
}

static void check_matrix(const double *A, size_t n, const char *ptr, int definite, dp_errors *e)
{
    size_t i, j;
    if (A == NULL)
        return;
    if (!symmetric(A, n, &i, &j)) {
        dp_errors_add(e, ptr, "must be symmetric: entry [%zu][%zu] = %g but [%zu][%zu] = %g", i, j, A[i * n + j],
                      j, i, A[j * n + i]);
        return;
    }
    double scale, lo = min_eigenvalue(A, n, &scale);
    if (definite && !(lo > 1e-14 * scale))
        dp_errors_add(e, ptr, "must be positive definite: its smallest eigenvalue is %.6g", lo);
    else if (!definite && !(lo >= -1e-12 * scale))
        dp_errors_add(e, ptr, "must be positive semidefinite: its smallest eigenvalue is %.6g", lo);
}

/* The pointer of element i's member `rest` ("/contact/distance", "" for the element): a one-mass document
 * made into a network names its own members (/model/contact, /model/spring). */
static void el_ptr(char *p, size_t cap, const dp_spec *s, size_t i, const char *rest)
{
    if (s->net->one_mass_doc)
        snprintf(p, cap, "/model%s", rest);
    else
        snprintf(p, cap, "/model/elements/%zu%s", i, rest);
}

/* A contact (network_contact.c): the initial state must respect it, the element's spring must leave it
 * something to do, and its solver must step it. */
static void check_contact(const dp_spec *s, size_t i, double u, dp_errors *e)
{
    const dp_element *el = &s->net->el[i];
    const dp_contact *c = &el->contact;
    char p[DP_POINTER_MAX];
    if (u < c->distance && c->compliance == 0) {   /* a compliant one may start pressed: a spring compressed */
        if (s->net->one_mass_doc)
            snprintf(p, sizeof p, "/initial/x");
        else
            snprintf(p, sizeof p, "/initial/x/%ld", el->b >= 0 ? el->b : el->a);
        dp_errors_add(e, p, "element %zu's contact needs its elongation u = x_b - x_a >= %g (its distance), but "
                      "the initial state has u = %.17g: the ends start inside the stop", i, c->distance, u);
    }
    const dp_graph *g = el->has_spring ? &el->spring.graph : NULL;
    el_ptr(p, sizeof p, s, i, "/contact/distance");
    if (g && g->n && g->right[0] == 0 && g->y[g->n - 1] < c->distance)
        dp_errors_add(e, p, "the element's spring allows no elongation above %g, the contact none below %g: no "
                      "state satisfies both", g->y[g->n - 1], c->distance);
    else if (g && g->n && g->left[0] == 0 && g->y[0] >= c->distance)
        dp_errors_add(e, p, "the element's spring already forbids elongations below %g, so the contact (>= %g) "
                      "could never act: drop it, or raise its distance", g->y[0], c->distance);
    el_ptr(p, sizeof p, s, i, "/contact");
    if (s->solver.kind == DP_SOLVER_NEWMARK)
        dp_errors_add(e, p, "contacts are stepped by the stick-slip solver (Moreau-Jean) or, compliant, by the "
                      "regularized one; the newmark solver has no impact law");
    else if (s->solver.kind == DP_SOLVER_REGULARIZED && c->compliance == 0)
        dp_errors_add(e, p, "a rigid contact makes the velocity jump, which the regularized ODE cannot: give it a "
                      "\"compliance\" (its Yosida approximation, force k max(d - u, 0)), or use the stick-slip "
                      "solver");
}

/* Whether element el's rope (or a graph spring with a vertical piece) takes any theta: with events located
 * the stick-slip solver steps it as its parts, a linear spring (a graph's sloped part, theta-stepped), the
 * rigid contact u <= L (a graph's stops) and a graph's jumps as step elements of their own (network_run.c,
 * network_contact.c). That holds whenever theta < 1 passes the other elements' rules. */
static int split_takes_theta(const dp_spec *s, const dp_element *el)
{
    return el->has_spring && dp_spring_is_split(&el->spring) && s->solver.kind == DP_SOLVER_STICK_SLIP &&
           s->solver.events == DP_EVENTS_LOCATE;
}

static void check_element(const dp_spec *s, size_t i, dp_errors *e)
{
    const dp_element *el = &s->net->el[i];
    char p[DP_POINTER_MAX];
    if (el->a == el->b) {
        el_ptr(p, sizeof p, s, i, "/between");
        dp_errors_add(e, p, "an element must join two different ends");
    }
    double u = (el->b >= 0 ? s->x0v[el->b] : 0) - (el->a >= 0 ? s->x0v[el->a] : 0);
    double z = (el->b >= 0 ? s->v0v[el->b] : 0) - (el->a >= 0 ? s->v0v[el->a] : 0), lo, hi;
    if (el->has_spring && el->spring.graph.n) {
        dp_graph_force(&el->spring.graph, u, &lo, &hi);
        if (lo == hi && !isfinite(lo)) {
            el_ptr(p, sizeof p, s, i, "/spring");
            dp_errors_add(e, p, "the initial elongation %g is outside the spring's domain (a rope's length, a "
                          "vertical end piece)", u);
        }
    }
    if (el->has_damper && el->damper.graph.n) {
        dp_graph_force(&el->damper.graph, z - el->damper.belt_velocity, &lo, &hi);
        if (lo == hi && !isfinite(lo)) {
            el_ptr(p, sizeof p, s, i, "/damper");
            dp_errors_add(e, p, "the initial relative velocity %g is outside the damper graph's domain", z);
        }
    }
    /* a graph of finite slope is theta-stepped (network_smooth.c); one with a vertical piece holds its force
     * as a multiplier, stepped by backward Euler */
    if (el->has_spring && !dp_spring_linear(&el->spring) && !dp_spring_plastic(&el->spring) &&
        !dp_spring_sloped_graph(&el->spring) && s->solver.theta != 1 && !split_takes_theta(s, el)) {
        el_ptr(p, sizeof p, s, i, "/spring");
        dp_errors_add(e, p, "theta < 1 needs springs of finite slope (the %s spring has a vertical piece, stepped "
                      "by backward Euler%s): use theta = 1", dp_spring_law_name(el->spring.law),
                      dp_spring_is_split(&el->spring) ? " without located events" : "");
    }
    if (el->has_contact)
        check_contact(s, i, u, e);
    if (el->has_damper && el->damper.relaxation.kind == DP_RELAX_POWER) {
        el_ptr(p, sizeof p, s, i, "/damper/relaxation");
        dp_errors_add(e, p, "the power relaxation is not Lipschitz at rest, so a network step need not have one "
                      "solution (one mass only, with its branches)");
    }
}

/* The regularized scheme on networks (network_regularized.c): (PCn), one n, a dense Jacobian. */
static void check_regularized(const dp_spec *s, dp_errors *e)
{
    const dp_solver_spec *sv = &s->solver;
    char p[DP_POINTER_MAX];
    for (size_t i = 0; i < s->net->nel; i++)
        if (s->net->el[i].has_spring && dp_spring_plastic(&s->net->el[i].spring)) {
            el_ptr(p, sizeof p, s, i, "/spring/law");
            dp_errors_add(e, p, "the %s spring has memory (its plastic offset), which the regularized "
                          "scheme's memoryless laws do not: use the stick-slip or the newmark solver",
                          dp_spring_law_name(s->net->el[i].spring.law));
        }
    if (sv->scheme != DP_SCHEME_PC)
        dp_errors_add(e, "/solver/scheme", "networks take scheme PC (Yosida dampers); PI is for one mass");
    if (sv->n_count != 1)
        dp_errors_add(e, "/solver/n", "networks take one n per run (a convergence study is for one mass)");
    if (s->net->n > DP_NETWORK_MAX_MATRIX_NODES)
        dp_errors_add(e, "/model/masses", "the regularized scheme integrates a dense Jacobian: at most %d nodes, "
                      "got %zu (the stick-slip solver takes up to %d)", DP_NETWORK_MAX_MATRIX_NODES, s->net->n,
                      DP_NETWORK_MAX_NODES);
    if (!(sv->rtol >= 0 && sv->atol >= 0 && sv->rtol + sv->atol > 0) || !isfinite(sv->rtol + sv->atol))
        dp_errors_add(e, "/solver/rtol", "rtol and atol must be finite, >= 0 and not both 0");
}

/* The solvers take a state of magnitude 1e300 or more for a divergence (network_run_state_finite): an
 * initial state that large is refused at its member, not streamed into a "diverged" line. */
#define STATE_MAX 1e300

static void check_initial_magnitude(const dp_spec *s, dp_errors *e)
{
    const double *vec[2] = { s->x0v, s->v0v };
    for (int k = 0; k < 2; k++)
        for (size_t i = 0; vec[k] && i < s->net->n; i++) {
            if (fabs(vec[k][i]) < STATE_MAX)
                continue;
            char p[DP_POINTER_MAX];
            if (s->net->one_mass_doc)
                snprintf(p, sizeof p, "/initial/%s", k ? "v" : "x");
            else
                snprintf(p, sizeof p, "/initial/%s/%zu", k ? "v" : "x", i);
            dp_errors_add(e, p, "%g is beyond the magnitudes the solvers step (below %g): the state would be "
                          "taken for a divergence", vec[k][i], STATE_MAX);
            break;
        }
}

void dp_network_check(const dp_spec *s, dp_errors *e)
{
    const dp_network *net = s->net;
    size_t n = net->n;
    check_initial_magnitude(s, e);
    if (net->M)
        check_matrix(net->M, n, "/model/mass_matrix", 1, e);
    check_matrix(net->K, n, "/model/stiffness_matrix", 0, e);
    check_matrix(net->C, n, "/model/damping_matrix", 0, e);
    for (size_t i = 0; i < net->nel; i++)
        check_element(s, i, e);
    if (s->solver.kind == DP_SOLVER_REGULARIZED)
        check_regularized(s, e);
    else if (s->solver.kind == DP_SOLVER_NEWMARK)
        dp_newmark_check(s, e);
    else if (s->solver.kind != DP_SOLVER_STICK_SLIP)
        dp_errors_add(e, "/solver/kind", "networks take the stick-slip, the regularized or the newmark solver (the "
                      "analytic closed form is for one mass)");
    else if (s->solver.variant != DP_VARIANT_EXACT)
        dp_errors_add(e, "/solver/variant", "networks take the exact variant only (the thesis' algorithm is for "
                      "one mass)");
    else if (s->solver.branch != DP_BRANCH_REST)
        dp_errors_add(e, "/solver/branch", "networks follow the rest branch only");
}

/* One mass on one element [ground, 0], stepped by the one-mass solver (solvers/network/network_one_mass.c):
 * the same answers, bit for bit, at the one-mass solver's speed. */
int dp_network_is_one_mass(const dp_spec *s)
{
    const dp_network *n = s->net;
    if (n == NULL || n->n != 1 || n->nel != 1 || n->mass == NULL || n->M || n->K || n->C)
        return 0;
    if (n->el[0].a != DP_GROUND || n->el[0].b != 0 || n->nforce > DP_FORCING_MAX_TERMS || n->el[0].has_contact)
        return 0;
    /* a plastic (elastoplastic) spring steps on the network solver, which writes its "p" columns; so does
     * a block whose quakes are catalogued (network_quakes.c), a rope with events located (its going taut
     * located, network_contact.c), and a graph spring below theta = 1, which the network theta-steps
     * (network_smooth.c) where the one-mass solver takes backward Euler only */
    if (split_takes_theta(s, &n->el[0]))
        return 0;
    int graph_theta = n->el[0].has_spring && !dp_spring_linear(&n->el[0].spring) && s->solver.theta != 1;
    return s->solver.kind == DP_SOLVER_STICK_SLIP && !dp_spring_plastic(&n->el[0].spring) && !s->output.quakes &&
           !graph_theta;
}

/* One node and one element between it and the ground, a rigid contact (Newton restitution) with at most a
 * linear spring and a linear damper that cannot stick, stepped by Moreau-Jean's rule (events "none"):
 * the bouncing ball, stepped by solvers/network/network_contact_lean.c, the general network step written out
 * for one node (the same answers, bit for bit). */
int dp_network_is_one_node_contact(const dp_spec *s)
{
    const dp_network *n = s->net;
    if (n == NULL || n->n != 1 || n->nel != 1 || s->solver.kind != DP_SOLVER_STICK_SLIP || s->output.quakes)
        return 0;
    const dp_element *e = &n->el[0];
    int ends = (e->a == DP_GROUND && e->b == 0) || (e->a == 0 && e->b == DP_GROUND);
    if (!ends || !e->has_contact || e->contact.compliance != 0)
        return 0;
    if (e->has_spring && (!dp_spring_linear(&e->spring) || dp_spring_plastic(&e->spring)))
        return 0;
    if (e->has_damper && (!dp_damper_linear(&e->damper) || e->damper.relaxation.kind != DP_RELAX_NONE))
        return 0;
    /* events "none": Moreau-Jean's rule (with "locate" a contact's impact is located inside its step) */
    return !dp_element_can_stick(e) && s->solver.events == DP_EVENTS_NONE;
}

/* Whether element e's laws are a grounded chain's: at most a linear spring, a linear damper without relaxation
 * or a Coulomb damper (phi0 > 0, on any belt; not generalized Coulomb's static threshold, no relaxation),
 * and a rigid contact; a Coulomb damper or a contact joins the ground to a node that no other such law holds
 * (seen: the nodes held so far). *laws counts them. */
static int chain_element(const dp_element *e, unsigned char *seen, int *laws)
{
    if (e->has_spring && (!dp_spring_linear(&e->spring) || dp_spring_plastic(&e->spring)))
        return 0;
    int coulomb = e->has_damper && e->damper.law == DP_DAMPER_COULOMB && dp_element_can_stick(e);
    if (e->has_damper && (!(dp_damper_linear(&e->damper) || coulomb) ||
                          e->damper.relaxation.kind != DP_RELAX_NONE))
        return 0;
    if (dp_element_can_stick(e) && !coulomb)
        return 0;
    if (e->has_contact && e->contact.compliance != 0)
        return 0;
    int held = coulomb + e->has_contact;
    if (held == 0)
        return 1;
    long node = e->a == DP_GROUND ? e->b : e->b == DP_GROUND ? e->a : -1;
    if (held > 1 || node < 0 || seen[node])
        return 0;
    seen[node] = 1, (*laws)++;
    return 1;
}

/* A network of masses on linear springs and dampers whose only set-valued laws are rigid contacts and
 * Coulomb dampers from the ground to distinct nodes (a stop chain, a friction chain, Burridge-Knopoff's),
 * stepped by Moreau-Jean's rule (events "none"): stepped by solvers/network/network_grounded_chain.c, the
 * general network step written out (the same answers, bit for bit), where the run's node ordering leaves W
 * tridiagonal. */
int dp_network_is_grounded_chain(const dp_spec *s)
{
    const dp_network *n = s->net;
    if (n == NULL || n->n == 0 || s->solver.kind != DP_SOLVER_STICK_SLIP || s->output.quakes ||
        s->solver.events != DP_EVENTS_NONE)
        return 0;
    unsigned char *seen = calloc(n->n, 1);
    int ok = seen != NULL, laws = 0;
    for (size_t i = 0; ok && i < n->nel; i++)
        ok = chain_element(&n->el[i], seen, &laws);
    free(seen);
    return ok && laws > 0;
}
