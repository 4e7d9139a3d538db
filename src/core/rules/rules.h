/* src/core/rules/rules.h - internal: the cross-field rules of each run type, the check member of its type
 * (solvers/run_types.h). Each adds every error it finds to e and returns DP_OK, DP_EINVAL or DP_ELIMIT. */
#ifndef DASHPOT_CORE_RULES_RULES_H
#define DASHPOT_CORE_RULES_RULES_H

#include "dashpot/spec.h"

int dp_rules_stick_slip(const dp_spec *s, double max_steps, dp_errors *e);
int dp_rules_thesis(const dp_spec *s, double max_steps, dp_errors *e);
int dp_rules_analytic(const dp_spec *s, double max_steps, dp_errors *e);
int dp_rules_newmark(const dp_spec *s, double max_steps, dp_errors *e);
int dp_rules_regularized(const dp_spec *s, double max_steps, dp_errors *e);
int dp_rules_network(const dp_spec *s, double max_steps, dp_errors *e);
int dp_rules_right_hand(const dp_spec *s, double max_steps, dp_errors *e);

/* output.quakes: a network with friction on the stick-slip solver (quakes_rules.c); adds errors to e. */
void dp_quakes_check(const dp_spec *s, dp_errors *e);

/* Whether a network document is one mass on one element [ground, 0] with a solver the one-mass run steps. */
int dp_network_is_one_mass(const dp_spec *s);
/* One node, one element: a rigid contact with at most a linear spring and damper, events "none"
 * (Moreau-Jean): stepped by network_contact_lean.c, bit for bit the general network step. */
int dp_network_is_one_node_contact(const dp_spec *s);
/* Masses on linear springs and dampers, rigid contacts and Coulomb dampers from the ground to distinct nodes,
 * events "none" (Moreau-Jean): stepped by network_grounded_chain.c, bit for bit the general network step
 * (where the run's node ordering leaves W tridiagonal). */
int dp_network_is_grounded_chain(const dp_spec *s);

/* The model families a spec may hold beside the one-mass model (rules/spec.c): which one it is, and the
 * length of its initial state x0v, v0v. */
int dp_spec_is_network(const dp_spec *s);
int dp_spec_is_lcs(const dp_spec *s);
int dp_spec_is_right_hand_model(const dp_spec *s);
size_t dp_spec_network_nodes(const dp_spec *s);
size_t dp_spec_right_hand_coordinates(const dp_spec *s);

#endif
