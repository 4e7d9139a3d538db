/* src/json/pointer.h - internal: where a value sits in a request document, and its JSON Pointer (RFC 6901).
 *
 * One writer of pointers for the whole JSON layer, so that a member named "a/b~c" is "/a~1b~0c" whichever
 * route reports it: the body reader (NULs, repeated keys), the document walker (walk.h) and the parsers. */
#ifndef DASHPOT_JSON_POINTER_H
#define DASHPOT_JSON_POINTER_H

#include <stddef.h>

#include "dashpot/status.h"

/* Where a value sits: its parent (NULL: the document itself) and its member name, or its index in an
 * array when key is NULL. Lives on a walk's stack; rendered as a JSON Pointer only for an error. */
typedef struct at {
    const struct at *up;
    const char *key;
    size_t index;
} at;

/* The JSON Pointer of `a` into out ("" for the document), built level by level. A pointer longer than
 * DP_POINTER_MAX - 1 bytes is cut on a character (never inside a UTF-8 sequence or an escape). */
void jp_text(const at *a, char out[DP_POINTER_MAX]);

/* Appends "/" + key (~ as ~0, / as ~1) to the pointer p of length n (< DP_POINTER_MAX), cut as jp_text does;
 * returns the new length. */
size_t jp_append_key(char p[DP_POINTER_MAX], size_t n, const char *key);

/* Appends "/" + i; returns the new length. */
size_t jp_append_index(char p[DP_POINTER_MAX], size_t n, size_t i);

/* The length of s[0..n) without a UTF-8 sequence cut short at its end. */
size_t jp_utf8_trim(const char *s, size_t n);

#endif
