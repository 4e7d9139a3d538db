/* src/http/lcp.c - POST /v1/lcp: one linear complementarity problem w = Mz + q, 0 <= z ⊥ w >= 0, solved by
 * Lemke's method, its solutions enumerated when it is small, and the uniqueness theory (docs/lcs.md).
 *
 * The work is dp_lcp_respond (src/json/lcp_json.c), shared with `dashpot lcp`; this file only negotiates the
 * media type and maps failures to problem documents.
 */
#include "dashpot/lcp_json.h"
#include "http.h"

enum MHD_Result handle_lcp(struct MHD_Connection *c, request *r)
{
    return respond_json_answer(c, r, dp_lcp_respond);
}
