/* src/core/lcp/lcs_laws.c - the LCS component laws' table (dashpot/lcs.h): one entry per law kind with its
 * name, its members and its shape, so that the parser's rows, the stepper's pieces and the meta record read
 * one place (docs/lcs.md). Its named graph laws are the one-mass laws' own graphs: Coulomb's stick interval
 * and the rope (law_table.c), in the (u, -w) plane.
 */
#include <assert.h>
#include <stddef.h>

#include "dashpot/lcs.h"
#include "dashpot/status.h"
#include "laws/law_table.h"

static_assert(offsetof(dp_lcs_law, kind) == 0, "dp_law_field 0 must be no member");

static int build_coulomb(dp_lcs_law *l)
{
    return dp_threshold_graph(&l->graph, l->phi0);
}

static int build_rope(dp_lcs_law *l)
{
    return dp_rope_graph(&l->graph, l->k, l->length);
}

#define MEMBER(key, f, b) { key, offsetof(dp_lcs_law, f), DP_MEMBER_##b, 1, 0 }

const dp_lcs_law_info dp_lcs_laws[] = {
    [DP_LCS_COMPLEMENTARITY] = {
        .row = { DP_LCS_COMPLEMENTARITY, "complementarity", { { NULL } }, NULL }, .shape = DP_LCS_SHAPE_CONE,
    },
    [DP_LCS_INTERVAL] = {
        .row = { DP_LCS_INTERVAL, "interval", { MEMBER("min", lo, ANY), MEMBER("max", hi, ANY) }, NULL },
        .shape = DP_LCS_SHAPE_INTERVAL,
    },
    [DP_LCS_GRAPH] = {
        .row = { DP_LCS_GRAPH, "graph", { { NULL } }, "u" }, .shape = DP_LCS_SHAPE_GRAPH,
    },
    [DP_LCS_COULOMB] = {
        .row = { DP_LCS_COULOMB, "coulomb", { MEMBER("phi0", phi0, NONNEG) }, NULL },
        .shape = DP_LCS_SHAPE_GRAPH, .build = build_coulomb,
    },
    [DP_LCS_ROPE] = {
        .row = { DP_LCS_ROPE, "rope", { MEMBER("k", k, NONNEG), MEMBER("length", length, ANY) }, NULL },
        .shape = DP_LCS_SHAPE_GRAPH, .build = build_rope,
    },
};
static_assert(sizeof dp_lcs_laws / sizeof dp_lcs_laws[0] == DP_LCS_LAW_COUNT, "every LCS law has its entry");

const dp_lcs_law_info *dp_lcs_law_info_of(dp_lcs_law_kind kind)
{
    return (unsigned)kind < DP_LCS_LAW_COUNT ? &dp_lcs_laws[kind] : NULL;
}
