/* src/core/laws/law_table.h - internal: the named laws' graph builders that other law families reuse (an LCS
 * component's coulomb and rope laws are the one-mass damper's and spring's, docs/lcs.md). The table itself is
 * public (dashpot/model.h): the front ends read its names and members. */
#ifndef DASHPOT_CORE_LAW_TABLE_H
#define DASHPOT_CORE_LAW_TABLE_H

#include "dashpot/graph.h"

/* The stick interval [-phi, phi] at zero, flat beyond (Coulomb's law); the zero line when phi is 0. */
int dp_threshold_graph(dp_graph *g, double phi);
/* A spring k in parallel with an inextensible rope of length L: slope k up to x = L, vertical there. */
int dp_rope_graph(dp_graph *g, double k, double length);

#endif
