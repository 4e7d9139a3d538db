/* src/core/rules/right_hand_check.c - the cross-field rules of a right-hand friction spec (docs/systems.md §6): its
 * models go with the right-hand solver and it with them; the parameters make a mechanism (masses and
 * lengths > 0, alpha in [0, pi/2], coefficients >= 0, gravity > 0) - the parser checks each number, this
 * restates them for specs built in C. */
#include <math.h>
#include <stdio.h>

#include "dashpot/right_hand.h"
#include "dashpot/spec.h"

void dp_right_hand_check(const dp_spec *s, dp_errors *e)
{
    if (s->rh == NULL) {
        dp_errors_add(e, "/solver/kind", "the right-hand solver takes a model of kind \"piston-hinge\" or "
                      "\"painleve-rod\"");
        return;
    }
    if (s->solver.kind != DP_SOLVER_RIGHT_HAND)
        dp_errors_add(e, "/solver/kind", "a %s model is solved by the solver of kind \"right-hand\"",
                      dp_right_hand_kind_name(s->rh->kind));
    const char *key, *why;
    if (!dp_right_hand_model_valid(s->rh, &key, &why)) {
        char ptr[64];
        snprintf(ptr, sizeof ptr, "/model/%s", key);
        dp_errors_add(e, ptr, "%s", why);
    }
    for (int i = 0; i < 2; i++) {
        if (s->x0v == NULL || !isfinite(s->x0v[i]))
            dp_errors_add(e, "/initial/x", "must be an array of 2 finite numbers");
        if (s->v0v == NULL || !isfinite(s->v0v[i]))
            dp_errors_add(e, "/initial/v", "must be an array of 2 finite numbers");
        if (s->x0v == NULL || s->v0v == NULL)
            break;
    }
    if (!(s->solver.rtol > 0 && s->solver.rtol < 1))
        dp_errors_add(e, "/solver/rtol", "must be in (0, 1), got %g", s->solver.rtol);
    if (s->rh->kind == DP_RIGHT_HAND_ROD && s->x0v && !(s->x0v[1] > 0 && s->x0v[1] < M_PI))
        dp_errors_add(e, "/initial/x/1", "the rod's angle to the floor must be in (0, pi) with its end A on "
                      "the floor and the rod above it, got %g", s->x0v[1]);
}
