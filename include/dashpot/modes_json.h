/* include/dashpot/modes_json.h - linear analysis requests and answers on the wire (POST /v1/modes,
 * POST /v1/response, `dashpot modes|response`): one entry point each, so the daemon and the CLI accept and
 * answer exactly alike (docs/modes.md).
 *
 * Request: {"model": {"masses": [...] | "mass_matrix": [[...]...], "stiffness_matrix", "damping_matrix",
 *                     "elements": [...], "forcing": [...]},
 *           "damping": {"rayleigh": {"alpha": a, "beta": b}},                      (optional: C += aM + bK)
 *           "force_node": i, "response_node": j,                                   (response only)
 *           "omega": {"from": w0, "to": w1, "points": n, "spacing": "linear"|"log"}} (response only)
 * A simulation spec's "initial", "solver" and "output" may be present and are ignored.
 */
#ifndef DASHPOT_MODES_JSON_H
#define DASHPOT_MODES_JSON_H

#include <stddef.h>
#include "dashpot/encode.h"
#include "dashpot/status.h"

/* Points of one response curve. */
#define DP_RESPONSE_MAX_POINTS 100000

/* Parses the body[0..len), solves the modes and appends the JSON answer to `out`. DP_OK, DP_ESYNTAX,
 * DP_EINVAL (errors by JSON Pointer), DP_ELIMIT, DP_ESOLVE, DP_ENOMEM; on failure `out` is as it was. */
int dp_modes_respond(const char *body, size_t len, dp_buf *out, dp_errors *errs);

/* The same for a receptance curve, written as DP_FORMAT_JSON, DP_FORMAT_NDJSON or DP_FORMAT_CSV. */
int dp_response_respond(const char *body, size_t len, int format, dp_buf *out, dp_errors *errs);

/* The same two, polling `stop` (may be NULL) through the work; DP_ECANCEL once it said stop. */
int dp_modes_respond_until(const char *body, size_t len, const dp_stop *stop, dp_buf *out, dp_errors *errs);
int dp_response_respond_until(const char *body, size_t len, int format, const dp_stop *stop, dp_buf *out,
                              dp_errors *errs);

#endif
