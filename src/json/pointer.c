/* src/json/pointer.c - JSON Pointers (RFC 6901) for every error the JSON layer reports: one escaping of
 * "~" and "/" in member names, one cut at DP_POINTER_MAX (on a character, so the text stays UTF-8). */
#include <stdio.h>
#include <string.h>

#include "pointer.h"

size_t jp_utf8_trim(const char *s, size_t n)
{
    size_t i = n;
    while (i > 0 && ((unsigned char)s[i - 1] & 0xC0) == 0x80)
        i--;
    if (i == 0 || (unsigned char)s[i - 1] < 0xC0)
        return n;                                  /* ends in ASCII or a sequence with all its bytes */
    unsigned char lead = (unsigned char)s[i - 1];
    size_t need = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : 2;
    return n - (i - 1) >= need ? n : i - 1;
}

size_t jp_append_key(char p[DP_POINTER_MAX], size_t n, const char *key)
{
    if (n + 1 >= DP_POINTER_MAX)
        return n;
    p[n++] = '/';
    const char *k = key;
    for (; *k && n + 3 <= DP_POINTER_MAX; k++) {
        if (*k == '~' || *k == '/') {
            p[n++] = '~';
            p[n++] = *k == '~' ? '0' : '1';
        } else {
            p[n++] = *k;
        }
    }
    n = *k ? jp_utf8_trim(p, n) : n;
    p[n] = '\0';
    return n;
}

size_t jp_append_index(char p[DP_POINTER_MAX], size_t n, size_t i)
{
    /* Only digits can be cut here (the parent is already valid). */
    int w = snprintf(p + n, DP_POINTER_MAX - n, "/%zu", i);
    if (w < 0 || n + (size_t)w >= DP_POINTER_MAX)
        return DP_POINTER_MAX - 1;
    return n + (size_t)w;
}

/* The pointer of `a` into out, returning its length: its parent's, then its own token. */
static size_t text(const at *a, char out[DP_POINTER_MAX])
{
    if (a == NULL) {
        out[0] = '\0';
        return 0;
    }
    size_t n = text(a->up, out);
    return a->key != NULL ? jp_append_key(out, n, a->key) : jp_append_index(out, n, a->index);
}

void jp_text(const at *a, char out[DP_POINTER_MAX])
{
    text(a, out);
}
