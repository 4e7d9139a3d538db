/* src/core/rules/regularized_rules.c - the cross-field rules of the regularized schemes (Pražák & Rajagopal
 * 2016; Babováková 2012, ch. 2): the approximation parameters of a study, the tolerances, and the laws whose
 * regularization is well defined (a maximal monotone damper graph, Lipschitz relaxation). */
#include <math.h>

#include "dashpot/regularized.h"
#include "dashpot/spec.h"

void dp_regularized_check(const dp_spec *s, dp_errors *e)
{
    const dp_solver_spec *sv = &s->solver;
    const dp_damper *d = &s->model.damper;
    const char *np = sv->scheme == DP_SCHEME_PI ? "/solver/k" : "/solver/n";
    if (sv->n_count < 1 || sv->n_count > DP_SPEC_MAX_NLIST)
        dp_errors_add(e, np, "needs 1..%d values, got %zu", DP_SPEC_MAX_NLIST, sv->n_count);
    for (size_t i = 0; i < sv->n_count && i < DP_SPEC_MAX_NLIST; i++) {
        if (!(sv->n_list[i] > 0) || !isfinite(sv->n_list[i]))
            dp_errors_add(e, np, "must be finite numbers > 0, got %g", sv->n_list[i]);
        else if (i > 0 && !(sv->n_list[i] > sv->n_list[i - 1]))
            dp_errors_add(e, np, "a study's values must be strictly increasing: %g after %g", sv->n_list[i],
                          sv->n_list[i - 1]);
    }
    if (!(sv->rtol >= 0 && sv->atol >= 0 && sv->rtol + sv->atol > 0) || !isfinite(sv->rtol + sv->atol))
        dp_errors_add(e, "/solver/rtol", "rtol and atol must be finite, >= 0 and not both 0");
    if ((unsigned)sv->stepper > DP_STEPPER_RK8PD)
        dp_errors_add(e, "/solver/stepper", "unknown stepper");
    const dp_damper_law_info *DL = dp_damper_law_info_of(d->law);
    if (DL && DL->static_threshold)   /* a law with a static threshold, whatever its values */
        dp_errors_add(e, "/model/damper/law", "the regularized schemes need a maximal monotone damper graph "
                      "(Pražák & Rajagopal 2016, Lemma 1); %s (%s > %s) is not monotone", DL->row.name,
                      dp_law_member_key(&DL->row, DL->static_threshold), dp_law_member_key(&DL->row, DL->kinetic));
    if (d->relaxation.kind == DP_RELAX_POWER)
        dp_errors_add(e, "/model/damper/relaxation", "power relaxation is not Lipschitz at 0 (Pražák & Rajagopal 2016, (26)): "
                      "the regularized ODE has no unique solution and no bounded Jacobian");
    else if (sv->scheme == DP_SCHEME_PI && d->relaxation.kind != DP_RELAX_NONE)
        dp_errors_add(e, "/model/damper/relaxation", "scheme PI (thesis ch. 2, x' = g(F_d)) has no relaxation; "
                      "use scheme PC");
}
