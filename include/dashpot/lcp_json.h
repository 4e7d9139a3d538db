/* include/dashpot/lcp_json.h - one linear complementarity problem on the wire (POST /v1/lcp, `dashpot lcp`):
 * one entry point, so the daemon and the CLI accept and answer exactly alike (docs/lcs.md).
 *
 * Request:  {"M": [[...], ...], "q": [...]}             w = M z + q, 0 <= z ⊥ w >= 0, M at most DP_LCP_MAX rows
 * Answer:   {"m", "lemke": {"outcome": "solved"|"ray"|"inaccurate"|"pivot-limit", "z", "w", "pivots", "residual"},
 *            "solutions": [{"z", "w"}...] | null, "singular_bases", "count",
 *            "theory": {"p_matrix": true|false|null, "minor_witness", "mu", "positive_definite_symmetric_part",
 *                       "positive_semidefinite", "lipschitz"}, "verdict"}
 * "solutions" lists every isolated solution (all 2^m complementary bases) when m <= DP_LCP_ENUM_MAX; it
 * also answers when Lemke takes its pivot limit. Every decision is invariant under the problem's units
 * (lcp.h; docs/lcs.md, "Scaling, tolerances and limits").
 */
#ifndef DASHPOT_LCP_JSON_H
#define DASHPOT_LCP_JSON_H

#include <stddef.h>
#include "dashpot/encode.h"
#include "dashpot/status.h"

/* Parses body[0..len), solves and appends the JSON answer to `out`. DP_OK, DP_ESYNTAX, DP_EINVAL (errors by
 * JSON Pointer; a solution beyond the doubles at /q), DP_ELIMIT (Lemke's pivot limit with m > DP_LCP_ENUM_MAX,
 * at /M), DP_ENOMEM; on failure `out` is as it was. */
int dp_lcp_respond(const char *body, size_t len, dp_buf *out, dp_errors *errs);

/* The same, polling `stop` (may be NULL) through the pivots and the enumeration; DP_ECANCEL once it said
 * stop. */
int dp_lcp_respond_until(const char *body, size_t len, const dp_stop *stop, dp_buf *out, dp_errors *errs);

/* The meta line of an LCS run (dp_spec_meta_json's branch for spec->lcs): solver parameters, sizes, laws,
 * and the theory of D and of the step's matrix D + hCWB (P-matrix, µ, Lipschitz bound), with what it means
 * for uniqueness of each step. DP_OK, DP_ENOMEM. */
struct dp_spec;
int dp_lcs_meta_json(const struct dp_spec *s, dp_buf *out);

#endif
