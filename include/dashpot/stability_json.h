/* include/dashpot/stability_json.h - stability requests and responses on the wire (POST /v1/stability and
 * `dashpot stability`): one entry point, so the daemon and the CLI accept and answer exactly alike.
 *
 * Request:  {"mass": m, "law": {"lambda": [l0, l1, ...], "mu": [u0, u1, ...]},
 *            "map": {"x": {"param": "mu[1]", "from": a, "to": b, "steps": n}, "y": {...}}}   ("map" optional)
 * The response fields are described in docs/stability.md.
 */
#ifndef DASHPOT_STABILITY_JSON_H
#define DASHPOT_STABILITY_JSON_H

#include <stddef.h>
#include "dashpot/encode.h"
#include "dashpot/stability.h"
#include "dashpot/status.h"

typedef enum dp_stability_want {
    DP_STABILITY_JSON = 0,   /* application/json: the analysis, or the map when the request has one */
    DP_STABILITY_CSV = 1,    /* text/csv: a map only, one line per grid point */
    DP_STABILITY_SVG = 2     /* image/svg+xml: a map only, heat map of the spectral abscissa */
} dp_stability_want;

/* Parses the request body[0..len) (need not be NUL-terminated), validates every field, runs the analysis or
 * the map and appends the response body to `out` (zero-initialised or holding earlier text; free it with
 * dp_buf_free). Returns
 *   DP_OK       the body was appended;
 *   DP_ESYNTAX  malformed JSON (one error, pointer "");
 *   DP_EINVAL   a field is missing, mistyped, non-finite, out of its domain or unknown; or CSV/SVG was asked
 *               for without a "map" (errors located by JSON Pointer);
 *   DP_ELIMIT   a documented limit is exceeded (order > 8, magnitudes beyond 1e12, more than 2000 steps);
 *   DP_ENOMEM   out of memory;
 *   DP_ESOLVE   an eigen solver did not converge (not seen in practice; dp_status_http maps it to 422).
 * On any failure `out` is left as it was (its length restored) and errs says why. */
int dp_stability_respond(const char *body, size_t len, int want, dp_buf *out, dp_errors *errs);

/* The same with the caller's workspace (dp_stability_ws_alloc; used by one thread at a time, reusable for
 * any number of requests): a server that keeps a few skips allocating GSL's workspaces per request. The
 * answers are the same bytes either way. */
int dp_stability_respond_ws(dp_stability_ws *w, const char *body, size_t len, int want, dp_buf *out,
                            dp_errors *errs);

#endif
