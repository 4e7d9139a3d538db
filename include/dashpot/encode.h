/* include/dashpot/encode.h - writing runs as JSON, NDJSON, SSE or CSV into a byte buffer.
 *
 * An encoder is a small state machine the front ends drive block by block, so that a stream of any length
 * is written in memory bounded by one block. Numbers are written with round-trip precision: parsing the
 * text gives back the same double, bit for bit.
 */
#ifndef DASHPOT_ENCODE_H
#define DASHPOT_ENCODE_H

#include <stddef.h>
#include "dashpot/run.h"

typedef struct dp_buf {
    char *data;
    size_t len, cap;
} dp_buf;

/* Makes room for `extra` more bytes. DP_OK or DP_ENOMEM (buffer unchanged). */
int dp_buf_reserve(dp_buf *b, size_t extra);
int dp_buf_append(dp_buf *b, const char *s, size_t n);
void dp_buf_free(dp_buf *b);

/* Writes the shortest-or-17-digit round-trip decimal form of a finite double into out (>= 32 bytes);
 * returns its length. Non-finite input writes "null" (callers never pass one: runs produce none). */
size_t dp_format_double(char *out, double x);

typedef enum dp_format { DP_FORMAT_JSON, DP_FORMAT_NDJSON, DP_FORMAT_SSE, DP_FORMAT_CSV } dp_format;

/* Parses "json", "ndjson", "sse", "csv"; -1 if unknown. */
int dp_format_from_name(const char *name);
const char *dp_format_content_type(dp_format f);

#define DP_ENCODER_MAX_EVENTS 100000

/* A number's shortest decimal digits, as src/json/dtoa.h lays them out (private to the encoder). */
typedef struct dp_decimal {
    unsigned long long lo, hi, head;
} dp_decimal;

/* A number recently written (private to the encoder): its bit pattern and its decimal. */
typedef struct dp_number_text {
    unsigned long long bits;
    dp_decimal decimal;
} dp_number_text;

typedef struct dp_encoder {
    dp_format format;
    int nsamples_written;    /* JSON: a comma is due before the next sample */
    int csv_header_due;      /* CSV of one mass: the header waits for the first sample (a plastic offset adds p) */
    dp_event *events;        /* JSON: events are held until the samples array closes */
    size_t nevents, events_cap;
    unsigned long long events_dropped;
    dp_quake *quakes;        /* JSON: quakes are held likewise (docs/quakes.md) */
    size_t nquakes, quakes_cap;
    unsigned long long quakes_dropped;
    dp_number_text recent[6]; /* the six numbers of the last sample: a repeated value is laid out from its
                                 digits, not converted again (a force constant while slipping, F_s = x when
                                 k = 1) */
    const dp_columns *cols;   /* a network run's columns (dp_encoder_set_columns), NULL for one mass */
} dp_encoder;

void dp_encoder_init(dp_encoder *e, dp_format f);
void dp_encoder_clear(dp_encoder *e);

/* A network run's columns (dp_run_columns), before dp_encoder_begin: rows are written with array members
 * (CSV: one column per node and element), events name their element, the summary's final state is a row.
 * NULL keeps the one-mass layout. The columns must outlive the encoder's use. */
void dp_encoder_set_columns(dp_encoder *e, const dp_columns *cols);

/* The opening: the meta object (`meta_json`, a complete JSON object written by the caller) as the NDJSON
 * meta line, SSE "meta" event, JSON document head, or the CSV header line (meta not written). */
int dp_encoder_begin(dp_encoder *e, dp_buf *b, const char *meta_json);

/* One record. CSV writes samples only. */
int dp_encoder_record(dp_encoder *e, dp_buf *b, const dp_record *r);

/* The closing summary. `extra_json` (may be NULL) is an object's members without braces appended inside
 * the summary object (e.g. wall time). */
int dp_encoder_end(dp_encoder *e, dp_buf *b, const dp_summary *s, const char *extra_json);

/* A failure after the opening went out: a final error line/event (CSV: a "# error" line) so that the
 * stream is never silently cut. JSON: closes the document with an "error" member. `status` is a dp_status
 * (or an HTTP status); the object is {"status": dp_status_http(status), "title": dp_strerror(status),
 * "detail": message}, the members of a problem document. */
int dp_encoder_fail(dp_encoder *e, dp_buf *b, int status, const char *message);

/* The HTTP status a dp_status stands for on the wire (the "status" of error lines and problem documents):
 * DP_ESYNTAX 400; DP_EINVAL, DP_ELIMIT, DP_ESOLVE, DP_ENONFINITE 422; DP_ENOMEM, DP_ECANCEL 503. A value that
 * already is an HTTP status (100..599) is returned unchanged. Never 500: every failure is the request's
 * (422) or a temporary lack of resources (503). */
int dp_status_http(int status);

/* Appends a JSON string literal (with quotes) for s, escaping as RFC 8259 requires. */
int dp_json_quote(dp_buf *b, const char *s);

#endif
