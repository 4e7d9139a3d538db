/* include/dashpot/sweep_json.h - a sweep on the wire (POST /v1/sweep, `dashpot sweep`): the document, the
 * substitution of a grid point into its base, and the lines of the answer, shared by the daemon and the CLI
 * so that both accept and answer alike (docs/sweep.md).
 *
 * Document: {"base": {a simulate document},
 *            "vary": [{"pointer": "/model/forcing/omega", "values": [...]}
 *                   | {"pointer", "from", "to", "count", "scale": "linear"|"log"}]   (one or two),
 *            "record": {"after", "features": [...], "section": {"period"|"event", "count"}, "node", "element"},
 *            "shard": {"index", "count"}, "runs": [indices]}                                  (optional)
 * Lines:    {"type":"meta",...}, {"type":"run","index","values","features","section"} per run (or the run's
 *            problem: "status", "title", "detail", "errors" by pointer into the base), {"type":"summary",...}.
 */
#ifndef DASHPOT_SWEEP_JSON_H
#define DASHPOT_SWEEP_JSON_H

#include <stddef.h>
#include "dashpot/encode.h"
#include "dashpot/sweep.h"

typedef struct dp_sweep_doc dp_sweep_doc;

/* Parses and checks a sweep document: DP_OK (*out to be freed with dp_sweep_doc_free), DP_ESYNTAX, DP_EINVAL
 * (errors by JSON Pointer into the sweep document), DP_ELIMIT, DP_ENOMEM. The base is checked only as an
 * object here: each run's substituted base is parsed by dp_sweep_doc_spec. */
int dp_sweep_parse(const char *text, size_t len, dp_sweep_doc **out, dp_errors *errs);
void dp_sweep_doc_free(dp_sweep_doc *doc);

/* Restricts the runs to shard i of n (dp_sweep_shard_owns), replacing the document's "shard". */
void dp_sweep_doc_set_shard(dp_sweep_doc *doc, size_t i, size_t n);
/* How many runs this document runs (its shard or "runs" of the grid), and the grid index of the k-th. */
size_t dp_sweep_doc_count(const dp_sweep_doc *doc);
size_t dp_sweep_doc_index(const dp_sweep_doc *doc, size_t k);
const dp_sweep_grid *dp_sweep_doc_grid(const dp_sweep_doc *doc);
const dp_sweep_plan *dp_sweep_doc_plan(const dp_sweep_doc *doc);

/* The spec of run `index`: the base with the run's values at the vary pointers, parsed by dp_spec_parse
 * (`spec` dp_spec_init'ed; errors point into the base document). */
int dp_sweep_doc_spec(const dp_sweep_doc *doc, size_t index, double max_steps, dp_spec *spec, dp_errors *errs);
/* The same substituted base as a JSON text (malloc'd, NUL-terminated): the lone simulate document of the run. */
char *dp_sweep_doc_text(const dp_sweep_doc *doc, size_t index);

/* The lines, each one JSON object without a newline, appended to out. DP_OK or DP_ENOMEM. */
int dp_sweep_meta_json(const dp_sweep_doc *doc, double max_steps, dp_buf *out);
int dp_sweep_run_json(const dp_sweep_doc *doc, size_t index, const dp_features *f, dp_buf *out);
/* A run that failed: its status (dp_status_http), and its errors by pointer into the base or a detail. */
int dp_sweep_failed_json(const dp_sweep_doc *doc, size_t index, int status, const char *detail,
                         const dp_errors *errs, dp_buf *out);

/* ---- running a sweep's runs in order, one block at a time (the daemon's slices, the CLI's threads) ---- */

typedef struct dp_sweep_exec dp_sweep_exec;

typedef struct dp_sweep_totals {
    size_t completed, failed;
    unsigned long long steps;
} dp_sweep_totals;

/* An executor of the runs k = first, first + stride, ... < dp_sweep_doc_count(doc), each held to max_steps;
 * `budget` (may be NULL; shared by the executors of one sweep) counts the steps of the runs begun, and a
 * run that would take it past `budget_max` ends the sweep (DP_ELIMIT). NULL when out of memory. */
dp_sweep_exec *dp_sweep_exec_new(const dp_sweep_doc *doc, size_t first, size_t stride, double max_steps,
                                 _Atomic unsigned long long *budget, double budget_max);
void dp_sweep_exec_set_stop(dp_sweep_exec *x, dp_stop_fn stop, void *ctx);
/* Does one block of work. Returns DP_MORE (and *line set when a run's line, done or failed, was appended to
 * out), DP_DONE when every run is done, DP_ECANCEL when the stop hook said stop, DP_ELIMIT when the budget is
 * spent, DP_ENOMEM; `why` then says what (static, or the run's error text). */
int dp_sweep_exec_next(dp_sweep_exec *x, dp_buf *out, int *line, const char **why);
const dp_sweep_totals *dp_sweep_exec_totals(const dp_sweep_exec *x);
void dp_sweep_exec_free(dp_sweep_exec *x);

/* The summary line: {"type":"summary","runs","completed","failed","steps"}. */
int dp_sweep_summary_json(size_t runs, const dp_sweep_totals *t, dp_buf *out);

#endif
