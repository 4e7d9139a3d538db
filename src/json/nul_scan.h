/* src/json/nul_scan.h - internal: a NUL inside a JSON string (nul_scan.c), for the body reader (body.c). */
#ifndef DASHPOT_JSON_NUL_SCAN_H
#define DASHPOT_JSON_NUL_SCAN_H

#include <stddef.h>

#include "dashpot/status.h"

/* Nesting the scan follows: more than the reader accepts (DP_JSON_MAX_DEPTH). */
#define DP_NUL_SCAN_DEPTH 80

/* In the text of a document cJSON accepted: 1 if a string holds a NUL (a raw byte or \u0000), with the JSON
 * Pointer of that value in ptr, or of the object holding it when the string is a key (*in_key = 1); else 0. */
int dp_json_find_nul(const char *text, size_t len, char ptr[DP_POINTER_MAX], int *in_key);

#endif
