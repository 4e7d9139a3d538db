/* include/dashpot/json.h - the JSON layer: spec documents in, records out.
 *
 * Parsing validates every field and names each bad one by its JSON Pointer; the encoders write samples,
 * events and summaries as JSON, NDJSON, SSE and CSV with round-trip precision (17 significant digits).
 */
#ifndef DASHPOT_JSON_H
#define DASHPOT_JSON_H

#include <stddef.h>
#include "dashpot/run.h"
#include "dashpot/spec.h"

/* Max nesting of a spec document; deeper documents are rejected before cJSON recurses. */
#define DP_JSON_MAX_DEPTH 64

/* Parses and validates a simulation spec. `spec` must have been dp_spec_init'ed. On success the model is
 * prepared (graphs built) and the full dp_spec_check has passed with `max_steps` (<= 0: DP_SPEC_MAX_STEPS).
 * Returns DP_OK, DP_ESYNTAX (malformed JSON; one error with pointer ""), DP_EINVAL / DP_ELIMIT (errors
 * listed), DP_ENOMEM. On failure the spec holds nothing that needs freeing beyond dp_spec_clear. */
int dp_spec_parse(const char *text, size_t len, double max_steps, dp_spec *spec, dp_errors *errs);

/* Writes the meta object of a run (solver, its parameters, step count, library version) as one JSON object
 * into out (NUL-terminated, truncated to cap). Returns the length it needed, like snprintf. Shared by the
 * CLI and the daemon so that both describe a run in the same words. */
size_t dp_spec_meta_json(const dp_spec *spec, char *out, size_t cap);

#define DP_VERSION "0.1.0"

#endif
