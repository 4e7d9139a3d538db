/* src/json/json_read.c - reading a request body as JSON for every parser of the JSON layer (simulation specs,
 * well-posedness, stability, modes): the nesting bounded before cJSON recurses, nothing after the document,
 * and a NUL inside a string refused with its pointer (cJSON would cut the string there). One reader, so
 * every route refuses the same documents with the same words. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "json_read.h"
#include "nul_scan.h"

/* Byte offset where the text first nests deeper than DP_JSON_MAX_DEPTH, or len. Brackets inside strings do
 * not count; a stray closer never lowers the depth below 0, so no prefix can buy extra depth for cJSON. */
static size_t too_deep(const char *s, size_t len)
{
    int depth = 0, in_string = 0;
    for (size_t i = 0; i < len; i++) {
        char ch = s[i];
        if (in_string) {
            if (ch == '\\')
                i++;
            else if (ch == '"')
                in_string = 0;
        } else if (ch == '"') {
            in_string = 1;
        } else if (ch == '[' || ch == '{') {
            if (++depth > DP_JSON_MAX_DEPTH)
                return i;
        } else if ((ch == ']' || ch == '}') && depth > 0) {
            depth--;
        }
    }
    return len;
}

/* The cJSON tree of text[0..len), or NULL with the DP_ESYNTAX error added (*nomem set when no copy could be
 * made). cJSON reads a NUL-terminated copy: its BOM check peeks 3 bytes regardless of the length. Trailing
 * bytes other than JSON whitespace (a NUL among them) make the document malformed. */
cJSON *dp_json_read(const char *text, size_t len, dp_errors *errs, int *nomem)
{
    size_t deep = too_deep(text, len);
    if (deep < len) {
        dp_errors_add(errs, "", "malformed JSON near byte %zu: nested deeper than %d levels", deep,
                      DP_JSON_MAX_DEPTH);
        return NULL;
    }
    char *buf = len < SIZE_MAX ? malloc(len + 1) : NULL;
    if (buf == NULL) {
        *nomem = 1;
        return NULL;
    }
    if (len > 0)
        memcpy(buf, text, len);
    buf[len] = '\0';
    const char *end = NULL;
    const char *why = len == 0 ? " (empty document)" : "";
    cJSON *root = cJSON_ParseWithLengthOpts(buf, len, &end, 0);
    if (root != NULL) {
        end += strspn(end, " \t\r\n");
        if (end != buf + len) {
            cJSON_Delete(root);
            root = NULL;
            why = " (data after the document)";
        }
    }
    if (root == NULL)
        dp_errors_add(errs, "", "malformed JSON near byte %zu%s", end ? (size_t)(end - buf) : 0, why);
    free(buf);
    return root;
}

/* A NUL inside a string (cJSON would cut the string there, nul_scan.c): one located error; returns 1 if so. */
int dp_json_refuse_nul(dp_errors *errs, const char *text, size_t len)
{
    char ptr[DP_POINTER_MAX];
    int in_key = 0;
    if (!dp_json_find_nul(text, len, ptr, sizeof ptr, &in_key))
        return 0;
    dp_errors_add(errs, ptr, "%s contains a NUL character (\\u0000), which no field may hold",
                  in_key ? "a key of this object" : "this string");
    return 1;
}
