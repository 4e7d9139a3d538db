/* src/json/walk.h - internal: the document walker every route's parser uses (walk.c).
 *
 * A parser walks the cJSON tree the body reader made (body.h), carrying where it is as a chain of `at` on
 * the stack (pointer.h): the pointer text and the "expected ..." wording are written only when an error is
 * reported (building them for every member up front was most of what parsing a valid spec cost). It never
 * stops at the first error: every bad member is reported at its JSON Pointer, in the same words on every
 * route, and counted in the walk's ctx so the parser knows whether the document is valid.
 *
 * Message format: the pointer names the place; the message says what was expected and, where it helps, what
 * was found: "must be a finite number > 0, got -1", "unknown law \"colomb\"; expected one of: none, ...",
 * "unknown key \"foo\"; expected one of: mass, spring, damper, forcing", "missing required key \"mass\"
 * (a finite number > 0)".
 */
#ifndef DASHPOT_JSON_WALK_H
#define DASHPOT_JSON_WALK_H

#include <math.h>
#include <stddef.h>
#include <cjson/cJSON.h>

#include "dashpot/status.h"
#include "body.h"
#include "pointer.h"

/* The walk's state: where errors go, how many this parse added, whether an allocation failed. */
typedef struct ctx {
    dp_errors *errs;
    size_t nerr;
    int nomem;
    int lenient;   /* well-posedness requests: user graphs may be non-monotone or have gaps (null) */
} ctx;

/* An accepted interval for a number, with the words that describe it in messages. */
typedef struct range {
    double lo, hi;
    int lo_open;          /* lo itself excluded */
    const char *text;     /* appended to "a finite number" / "an integer" */
} range;

static const range ANY = { -INFINITY, INFINITY, 0, "" };
static const range POSITIVE = { 0, INFINITY, 1, " > 0" };
static const range NONNEG = { 0, INFINITY, 0, " >= 0" };

/* The body text[0..len) read by dp_body_read (body.h) into a tree, or NULL with its status in *status. The
 * errors the reader found in a tree (a NUL in a string, a repeated key) are counted in c, so the walk goes
 * on to report the rest and the parse fails. */
cJSON *jw_read(ctx *c, const char *text, size_t len, int *status);

/* One error at `where`, counted. */
void jw_fail(ctx *c, const at *where, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* The shortest of %.15g / %.17g that reads back as v, so 0.1 shows as "0.1" and nothing is misreported. */
const char *jw_num_text(double v, char buf[32]);

/* "a, b, c" from a NULL-terminated list. */
const char *jw_joined(const char *const *names, char *buf, size_t cap);

/* Member `key` of object o (its place into p), or NULL; when absent and `what` is set, that is an error
 * ("missing required key \"key\" (what)"). */
const cJSON *jw_member(ctx *c, const cJSON *o, const at *ptr, const char *key, const char *what, at *p);

/* 1 when v is an object; else 0 and "must be an object, got ...". */
int jw_want_object(ctx *c, const cJSON *v, const at *ptr);

/* v as a finite number in r (an integer when `integral`) into *out; 0 and an error otherwise. */
int jw_check_num(ctx *c, const cJSON *v, const at *ptr, const range *r, int integral, double *out);

/* Numeric member `key` of o; *out untouched when it is absent (the default stays; an error when required)
 * or invalid. Returns 1 when set. */
int jw_get_num(ctx *c, const cJSON *o, const at *ptr, const char *key, const range *r, int required,
               int integral, double *out);

/* Boolean member `key` of o into *out when present. */
void jw_get_bool(ctx *c, const cJSON *o, const at *ptr, const char *key, int *out);

/* Index of the string member `key` in `names`; `def` when absent (-1 and an error when def < 0), -1 and an
 * error when it is not one of them. */
int jw_get_enum(ctx *c, const cJSON *o, const at *ptr, const char *key, const char *const *names, int def);

/* Reports every member of o that is not in `keys` (NULL-terminated; a repeated member is the body reader's).
 * With a tag, the list is qualified (" for law \"coulomb\"": tag "law", its value "coulomb"). */
void jw_check_keys(ctx *c, const cJSON *o, const at *ptr, const char *const *keys, const char *tag,
                   const char *value);

/* v as an array of 1..max items: its size, or 0 with an error ("must be WHAT, got ..."). */
size_t jw_array_size(ctx *c, const cJSON *v, const at *p, size_t max, const char *what);

#endif
