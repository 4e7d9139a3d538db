/* src/core/rules/quakes_rules.c - the rules of output.quakes, the slip-event catalogue (docs/quakes.md): a
 * quake is made of friction elements' exact sticking and slipping, so the catalogue needs a network, some
 * element that can stick, and the stick-slip solver (the regularized and Newmark solvers never stick). */
#include "dashpot/network.h"
#include "rules/rules.h"

void dp_quakes_check(const dp_spec *s, dp_errors *e)
{
    if (!s->output.quakes)
        return;
    const dp_network *net = s->net;
    if (net == NULL || net->one_mass_doc) {
        dp_errors_add(e, "/output/quakes", "quakes are catalogued only for a network (\"masses\" or "
                      "\"mass_matrix\") with friction, not for a one-mass document");
        return;
    }
    if (s->solver.kind != DP_SOLVER_STICK_SLIP) {
        dp_errors_add(e, "/output/quakes", "quakes need the stick-slip solver: the regularized and newmark "
                      "solvers never stick, so no slip episode ends");
        return;
    }
    for (size_t i = 0; i < net->nel; i++)
        if (dp_element_can_stick(&net->el[i]))
            return;
    dp_errors_add(e, "/output/quakes", "quakes need friction: no element of this network can stick (a coulomb, "
                  "generalized-coulomb or bingham damper, or a graph damper with a vertical piece at its belt "
                  "speed)");
}
