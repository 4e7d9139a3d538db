/* include/dashpot/json.h - the JSON layer: spec documents in, records out.
 *
 * Parsing validates every field and names each bad one by its JSON Pointer; the encoders write samples,
 * events and summaries as JSON, NDJSON, SSE and CSV with round-trip precision (17 significant digits).
 */
#ifndef DASHPOT_JSON_H
#define DASHPOT_JSON_H

#include <stddef.h>
#include "dashpot/run.h"
#include "dashpot/encode.h"
#include "dashpot/spec.h"
#include "dashpot/wellposedness.h"

/* Max nesting of a spec document; deeper documents are rejected before cJSON recurses. */
#define DP_JSON_MAX_DEPTH 64

/* Parses and validates a simulation spec. `spec` must have been dp_spec_init'ed. On success the model is
 * prepared (graphs built) and the full dp_spec_check has passed with `max_steps` (<= 0: DP_SPEC_MAX_STEPS).
 * Returns DP_OK, DP_ESYNTAX (malformed JSON; one error with pointer ""), DP_EINVAL / DP_ELIMIT (errors
 * listed), DP_ENOMEM. On failure the spec holds nothing that needs freeing beyond dp_spec_clear. */
int dp_spec_parse(const char *text, size_t len, double max_steps, dp_spec *spec, dp_errors *errs);

/* Parses {"model": {...}} (other members of a simulation spec are allowed and ignored) for a well-posedness
 * report: like dp_spec_parse's model, except that user graphs
 * may be non-monotone and may contain gaps (a null between two points), stored raw (dp_graph_init_raw)
 * for analysis only; such a model must never be given to a solver. */
int dp_model_parse_lenient(const char *text, size_t len, dp_model *model, dp_errors *errs);

/* Parses {"model": ...} for a well-posedness report and fills it: a one-mass model leniently (as
 * dp_model_parse_lenient), a network strictly with its checks (dp_network_check). DP_OK, DP_ESYNTAX,
 * DP_EINVAL (errors listed), DP_ENOMEM. */
int dp_wellposedness_parse(const char *text, size_t len, dp_wp_report *rep, dp_errors *errs);

/* Appends the meta object of a run (solver, its parameters, step count, library version, and the model's
 * well-posedness report) as one JSON object to out. Shared by the CLI and the daemon so that both describe
 * a run in the same words. DP_OK or DP_ENOMEM. */
int dp_spec_meta_json(const dp_spec *spec, dp_buf *out);

/* Appends ,"chosen":[...] naming the members dashpot chose for the document (spec->chosen, dp_spec_choose),
 * nothing when there are none; every meta line writes it after "every". 0, or nonzero when out of memory. */
int dp_chosen_json(const dp_spec *spec, dp_buf *out);
/* The meta object of a right-hand friction run (spec->rh set): right_hand_meta.c. */
int dp_right_hand_meta_json(const dp_spec *spec, dp_buf *out);

/* Appends the well-posedness report as a JSON object. DP_OK or DP_ENOMEM. */
int dp_wellposedness_json(const dp_wp_report *r, dp_buf *out);

#define DP_VERSION "0.1.0"

#endif
