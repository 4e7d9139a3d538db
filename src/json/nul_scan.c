/* src/json/nul_scan.c - finds a NUL character inside a JSON string and says where, as a JSON Pointer.
 *
 * cJSON decodes "\u0000" (and copies a raw NUL byte) into C strings, which end there: "linear\u0000xx"
 * would be read as "linear" and a key "ma\u0000ss" as "ma". No document field may hold a NUL, so the
 * body reader (body.c) refuses one, naming the value (or, for a key, the object holding it). This walks the
 * text of a document cJSON has already accepted (so its syntax is known good) once, keeping the path to the
 * current value; it costs a pass over the bytes, no allocation.
 */
#include <stdio.h>
#include <string.h>

#include "nul_scan.h"
#include "pointer.h"

typedef struct frame {
    int object;                  /* 1: object (key holds the current member's name), 0: array */
    size_t index;
    char key[DP_POINTER_MAX];
} frame;

/* The pointer of the first `depth` frames, built as jp_text builds any other (pointer.c). */
static void pointer(char *p, const frame *st, int depth)
{
    size_t n = 0;
    p[0] = '\0';
    for (int i = 0; i < depth; i++)
        n = st[i].object ? jp_append_key(p, n, st[i].key) : jp_append_index(p, n, st[i].index);
}

static int hex4(const char *s, unsigned *v)
{
    *v = 0;
    for (int i = 0; i < 4; i++) {
        char c = s[i];
        int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (d < 0)
            return 0;
        *v = *v * 16 + (unsigned)d;
    }
    return 1;
}

/* Scans the string starting after its opening quote at s[*i]; copies its text (escapes other than \u kept
 * as the character they stand for, \u as '?' except NUL) into out when out != NULL. Returns 1 if it holds a
 * NUL. *i ends after the closing quote. */
static int string(const char *s, size_t len, size_t *i, char *out, size_t cap)
{
    int nul = 0;
    size_t o = 0;
    while (*i < len && s[*i] != '"') {
        char c = s[(*i)++];
        unsigned u = 1;
        if (c == '\\' && *i < len) {
            char e = s[(*i)++];
            c = e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e == 'b' ? '\b' : e == 'f' ? '\f' : e;
            if (e == 'u' && *i + 4 <= len && hex4(s + *i, &u)) {
                *i += 4;
                c = u < 0x80 ? (char)u : '?';
            }
        }
        if (c == '\0')
            nul = 1;
        else if (out && o + 1 < cap)
            out[o++] = c;
    }
    (*i)++;
    if (out)
        out[o] = '\0';
    return nul;
}

int dp_json_find_nul(const char *s, size_t len, char ptr[DP_POINTER_MAX], int *in_key)
{
    frame st[DP_NUL_SCAN_DEPTH];
    int depth = 0, expect_key = 0;
    for (size_t i = 0; i < len;) {
        char c = s[i];
        if (c == '{' || c == '[') {
            if (depth == DP_NUL_SCAN_DEPTH)
                return 0; /* deeper than any parser accepts: they refuse it themselves */
            st[depth] = (frame){ .object = c == '{' };
            expect_key = c == '{';
            depth++, i++;
        } else if (c == '}' || c == ']') {
            depth--, i++;
        } else if (c == ',') {
            if (depth > 0 && !st[depth - 1].object)
                st[depth - 1].index++;
            expect_key = depth > 0 && st[depth - 1].object;
            i++;
        } else if (c == '"') {
            i++;
            if (expect_key) {
                frame *f = &st[depth - 1];
                int nul = string(s, len, &i, f->key, sizeof f->key);
                expect_key = 0;
                if (nul) {
                    pointer(ptr, st, depth - 1); /* the object holding the key */
                    *in_key = 1;
                    return 1;
                }
            } else if (string(s, len, &i, NULL, 0)) {
                pointer(ptr, st, depth);
                *in_key = 0;
                return 1;
            }
        } else {
            i++;
        }
    }
    return 0;
}
