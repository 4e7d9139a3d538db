/* src/core/analysis/network_wellposedness.c - what the theory guarantees for a network (docs/systems.md §1).
 *
 * With M positive definite, K and C positive semidefinite, every element graph maximal monotone and every
 * relaxation gamma Lipschitz, the network is M x'' + C x' + K x + B^T A(B x', B x) - B^T gamma(B x') = f(t):
 * a Lipschitz perturbation of a maximal monotone operator on (x, v) in the energy inner product, so a
 * solution exists and is unique for every initial state in the domain (Brezis 1973, Thm 3.1; for one mass
 * Pražák & Rajagopal 2016, Thms 2, 3). dp_network_check refuses what breaks these hypotheses (a power relaxation, a static
 * threshold above the kinetic one), so the report names them as checked.
 */
#include <stdio.h>
#include <string.h>

#include "dashpot/network.h"
#include "dashpot/wellposedness.h"

static void check(dp_wp_report *r, const char *name, const char *detail)
{
    dp_wp_check *c = &r->check[r->nchecks++];
    c->name = name;
    c->holds = 1;
    snprintf(c->detail, sizeof c->detail, "%s", detail);
}

void dp_network_wellposedness(const dp_network *net, dp_wp_report *rep)
{
    memset(rep, 0, sizeof *rep);
    rep->framework = "network";
    char d[DP_WP_TEXT];
    snprintf(d, sizeof d, "%zu nodes: %s", net->n, net->M ? "mass matrix checked by Cholesky" : "positive masses");
    check(rep, "M symmetric positive definite", d);
    check(rep, "K, C symmetric positive semidefinite", "the matrices' smallest eigenvalues are >= 0; element "
          "springs and viscous dampers add k b b^T, c b b^T");
    long static_at = -1;
    for (size_t i = 0; i < net->nel && static_at < 0; i++) {
        const dp_damper *dm = &net->el[i].damper;
        if (net->el[i].has_damper && dp_damper_static(dm) > dp_damper_kinetic(dm))
            static_at = (long)i;
    }
    size_t ep = 0;
    for (size_t i = 0; i < net->nel; i++)
        ep += net->el[i].has_spring && dp_spring_plastic(&net->el[i].spring);
    if (ep)   /* a Jenkins element with its force as a state: F' in k u' - N(F), a stop operator (docs/systems.md §3) */
        snprintf(d, sizeof d, "%zu elements, each a monotone piecewise-linear graph (one-mass laws); %zu "
                 "elastoplastic, each with its force as a state (F' in k u' - N_K(F), K = [-F_y, F_y]: a maximal "
                 "monotone stop operator in the product F G / k)", net->nel, ep);
    else
        snprintf(d, sizeof d, "%zu elements, each a monotone piecewise-linear graph (one-mass laws)", net->nel);
    check(rep, "element graphs maximal monotone", d);
    if (static_at >= 0) {   /* the static threshold above the kinetic one: not monotone (Pražák & Rajagopal 2016, section 4) */
        const dp_damper *dm = &net->el[static_at].damper;
        dp_wp_check *c = &rep->check[rep->nchecks - 1];
        c->holds = 0;
        snprintf(c->detail, sizeof c->detail, "element %ld: generalized Coulomb with phi1 = %g > phi0 = %g is not "
                 "monotone (its force drops as it starts to slip); the solver follows the rest branch",
                 static_at, dp_damper_static(dm), dp_damper_kinetic(dm));
    }
    size_t relaxed = 0;
    for (size_t i = 0; i < net->nel; i++)
        relaxed += net->el[i].has_damper && net->el[i].damper.relaxation.kind != DP_RELAX_NONE;
    snprintf(d, sizeof d, "%zu elements with relaxation, each rational or linear (globally Lipschitz); each step "
             "is checked against W - h theta sum L b b^T > 0", relaxed);
    check(rep, "relaxation gamma Lipschitz", d);
    const char *thm = "maximal monotone evolution inclusion (Brezis 1973, Thm 3.1; Pražák & Rajagopal 2016, Thms 2-3 for one mass)";
    size_t rigid = 0, soft = 0, other = 0;   /* other: elements with a law that is not linear, contacts aside */
    for (size_t i = 0; i < net->nel; i++) {
        const dp_element *e = &net->el[i];
        if (e->has_contact)
            e->contact.compliance > 0 ? soft++ : rigid++;
        other += !dp_element_laws_linear(e);
    }
    if (rigid + soft) {
        snprintf(d, sizeof d, "%zu rigid contacts (Newton's law, restitution in [0, 1], so no impact gains energy), "
                 "%zu compliant ones (a monotone spring graph, covered by the theorem above)", rigid, soft);
        check(rep, "contacts: restitution in [0, 1]", d);
    }
    if (rigid && static_at < 0) {   /* Moreau's sweeping process of second order with Newton's impact law */
        rep->existence = (dp_wp_verdict){ .guaranteed = 1, .theorem = "measure differential inclusion with "
            "Newton's impact law (Moreau 1988; Monteiro Marques 1993; Paoli-Schatzman 2002: Moreau-Jean's scheme "
            "converges to a solution)" };
        snprintf(rep->existence.reason, DP_WP_TEXT, "all hypotheses hold, each contact's restitution in [0, 1]");
        int unique = rigid == 1 && soft == 0 && other == 0;
        rep->uniqueness = (dp_wp_verdict){ .guaranteed = unique, .theorem = unique ? "Ballard 2000: one "
            "unilateral constraint and analytic data (linear elements; the forcing must be analytic too)" : NULL };
        snprintf(rep->uniqueness.reason, DP_WP_TEXT, unique ? "one rigid contact, every other law linear" :
                 rigid > 1 ? "several rigid contacts: where they close at the same instant Newton's law is one "
                             "choice of outcome (Moreau's), and the motion need not depend continuously on the "
                             "initial state (Newton's cradle); beyond analytic data uniqueness can fail even for "
                             "one (Schatzman 1978)" :
                 "a rigid contact with set-valued or piecewise-linear laws: the data are not analytic, and "
                 "uniqueness can fail (Schatzman 1978); Ballard 2000 needs analytic data");
        return;
    }
    if (static_at >= 0) {
        rep->existence = (dp_wp_verdict){ .guaranteed = 0 };
        rep->uniqueness = (dp_wp_verdict){ .guaranteed = 0 };
        snprintf(rep->existence.reason, DP_WP_TEXT, "fails: element graphs maximal monotone");
        snprintf(rep->uniqueness.reason, DP_WP_TEXT, "fails: element graphs maximal monotone");
        rep->counterexample = "Pražák & Rajagopal 2016, section 4, (24)-(25): with the load at phi1 from rest both rest and "
                              "x = (phi1 - phi0)(1 - cos t) solve (for one mass; the network follows rest)";
        return;
    }
    rep->existence = (dp_wp_verdict){ .guaranteed = 1, .theorem = thm };
    rep->uniqueness = (dp_wp_verdict){ .guaranteed = 1, .theorem = thm };
    snprintf(rep->existence.reason, DP_WP_TEXT, "all hypotheses hold");
    snprintf(rep->uniqueness.reason, DP_WP_TEXT, "all hypotheses hold; each theta-step is strictly convex");
}
