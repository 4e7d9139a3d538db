/* src/core/rules/newmark_rules.c - the cross-field rules of the Newmark solver (Höschl 1983, §15): its
 * parameters' ranges and the laws it steps (linear and elastoplastic springs, linear dampers). */
#include <stdio.h>

#include "dashpot/newmark.h"

static void check_laws(const dp_spring *sp, int has_spring, const dp_damper *d, int has_damper, const char *at,
                       dp_errors *e)
{
    char p[DP_POINTER_MAX];
    if (has_spring && !dp_spring_linear(sp) && !dp_spring_plastic(sp)) {
        snprintf(p, sizeof p, "%s/spring/law", at);
        dp_errors_add(e, p, "the newmark solver takes linear and elastoplastic springs; a %s spring is stepped by "
                      "the stick-slip solver", dp_spring_law_name(sp->law));
    }
    if (has_damper && !dp_damper_linear(d)) {
        snprintf(p, sizeof p, "%s/damper/law", at);
        dp_errors_add(e, p, "the newmark solver takes linear dampers only: a %s damper is set-valued (it can "
                      "stick), which only the stick-slip solver steps exactly: use \"kind\": \"stick-slip\"",
                      dp_damper_law_name(d->law));
    } else if (has_damper && d->relaxation.kind != DP_RELAX_NONE) {
        snprintf(p, sizeof p, "%s/damper/relaxation", at);
        dp_errors_add(e, p, "the newmark solver takes linear dampers without relaxation: use the stick-slip "
                      "solver");
    }
}

void dp_newmark_check(const dp_spec *s, dp_errors *e)
{
    const dp_solver_spec *sv = &s->solver;
    if (!(sv->beta > 0 && sv->beta <= 0.5))
        dp_errors_add(e, "/solver/beta", "must be in (0, 0.5], got %g", sv->beta);
    if (!(sv->gamma >= 0.5 && sv->gamma <= 1))
        dp_errors_add(e, "/solver/gamma", "must be in [0.5, 1], got %g", sv->gamma);
    if (s->net == NULL) {
        check_laws(&s->model.spring, 1, &s->model.damper, 1, "/model", e);
        return;
    }
    if (s->net->n > DP_NETWORK_MAX_MATRIX_NODES)
        dp_errors_add(e, "/model/masses", "the newmark solver reports the stability limit of the highest mode from "
                      "a dense eigenproblem: at most %d nodes, got %zu", DP_NETWORK_MAX_MATRIX_NODES, s->net->n);
    for (size_t i = 0; i < s->net->nel; i++) {
        char at[64];
        const dp_element *el = &s->net->el[i];
        snprintf(at, sizeof at, "/model/elements/%zu", i);
        check_laws(&el->spring, el->has_spring, &el->damper, el->has_damper, at, e);
    }
}
