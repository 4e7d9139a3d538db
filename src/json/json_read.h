/* src/json/json_read.h - internal: the JSON layer's one reader of request bodies (json_read.c). */
#ifndef DASHPOT_JSON_JSON_READ_H
#define DASHPOT_JSON_JSON_READ_H

#include <stddef.h>
#include <cjson/cJSON.h>

#include "dashpot/json.h"

/* The cJSON tree of text[0..len), or NULL with one error at "" ("malformed JSON near byte N", or nested deeper
 * than DP_JSON_MAX_DEPTH, refused before cJSON recurses); *nomem set when out of memory. */
cJSON *dp_json_read(const char *text, size_t len, dp_errors *errs, int *nomem);

/* A NUL inside a string of the (already read) text: one located error, returns 1; else 0. */
int dp_json_refuse_nul(dp_errors *errs, const char *text, size_t len);

#endif
