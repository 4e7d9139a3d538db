/* src/json/body.h - internal: the one reader of request bodies (body.c), for every route of the JSON layer
 * (simulate, convergence, wellposedness, stability, lcp, modes, response) and so for the CLI, which calls
 * the same entry points. */
#ifndef DASHPOT_JSON_BODY_H
#define DASHPOT_JSON_BODY_H

#include <stddef.h>
#include <cjson/cJSON.h>

#include "dashpot/json.h"

/* Reads text[0..len) (need not be NUL-terminated; NULL with len 0 is the empty document) as one JSON object.
 * Returns
 *   DP_OK       *root is the document, an object; no error added;
 *   DP_EINVAL   with *root set: the object holds a NUL in a string or key, or a repeated key, each added to
 *               errs at its JSON Pointer; the caller walks the tree on to report the rest, then fails;
 *               with *root NULL: the document is no object (one error at "");
 *   DP_ESYNTAX  not JSON (one error at "": "malformed JSON near byte N (line L, column C): what, and a hint"),
 *               nested deeper than DP_JSON_MAX_DEPTH (refused before cJSON recurses), a NUL byte outside
 *               strings, or data after the document;
 *   DP_ENOMEM   out of memory (nothing added).
 * The caller frees *root with cJSON_Delete. */
int dp_body_read(const char *text, size_t len, dp_errors *errs, cJSON **root);

/* How messages name a value's type ("a number", "an array", ...), and a user string fit for a message: at
 * most 48 bytes (then "..."), control characters as '?'. Shared by the reader and the walker (walk.h). */
const char *jb_type_name(const cJSON *v);
const char *jb_shown(const char *s, char buf[64]);

#endif
