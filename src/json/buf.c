/* src/json/buf.c - the growable byte buffer of the encoders (dp_buf, encode.h) and JSON string quoting.
 *
 * The data stays NUL-terminated one byte past len whenever it is non-NULL, so a finished buffer can be used
 * as a C string; growth doubles, so appending n bytes one piece at a time costs O(n).
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/encode.h"

int dp_buf_reserve(dp_buf *b, size_t extra)
{
    if (extra >= SIZE_MAX / 2 - b->len)
        return DP_ENOMEM;
    size_t need = b->len + extra + 1; /* + the terminating NUL */
    if (need <= b->cap)
        return DP_OK;
    size_t cap = b->cap ? b->cap : 256;
    while (cap < need)
        cap *= 2;
    char *d = realloc(b->data, cap);
    if (d == NULL)
        return DP_ENOMEM;
    b->data = d;
    b->cap = cap;
    return DP_OK;
}

int dp_buf_append(dp_buf *b, const char *s, size_t n)
{
    if (dp_buf_reserve(b, n) != DP_OK)
        return DP_ENOMEM;
    memcpy(b->data + b->len, s, n);
    b->len += n;
    b->data[b->len] = '\0';
    return DP_OK;
}

void dp_buf_free(dp_buf *b)
{
    if (b == NULL)
        return;
    free(b->data);
    b->data = NULL;
    b->len = b->cap = 0;
}

/* RFC 8259 section 7: '"', '\\' and the controls U+0000..U+001F must be escaped; the short forms where they
 * exist, \u00XX otherwise. Other bytes (UTF-8 included) pass through unchanged. DEL and "</" are escaped
 * too (\u007f, <\/) so that the text is also safe inside HTML <script> and on a terminal. */
static size_t escape(char *p, unsigned char c, unsigned char prev)
{
    static const char hex[] = "0123456789abcdef";
    switch (c) {
    case '"': memcpy(p, "\\\"", 2); return 2;
    case '\\': memcpy(p, "\\\\", 2); return 2;
    case '\n': memcpy(p, "\\n", 2); return 2;
    case '\r': memcpy(p, "\\r", 2); return 2;
    case '\t': memcpy(p, "\\t", 2); return 2;
    case '\b': memcpy(p, "\\b", 2); return 2;
    case '\f': memcpy(p, "\\f", 2); return 2;
    case '/':
        if (prev == '<') {
            memcpy(p, "\\/", 2);
            return 2;
        }
        break;
    default:
        if (c < 0x20 || c == 0x7f) {
            memcpy(p, "\\u00", 4);
            p[4] = hex[c >> 4];
            p[5] = hex[c & 15];
            return 6;
        }
    }
    *p = (char)c;
    return 1;
}

/* Bytes that escape() may change, one bit each: the controls, '"' and '/' (the latter only after '<') in
 * the first word, '\\' and DEL in the second. */
static const uint64_t SPECIAL[4] = { 0xffffffffull | 1ull << '"' | 1ull << '/', 1ull << ('\\' - 64) | 1ull << 63, 0, 0 };

static int special(unsigned char c)
{
    return (int)(SPECIAL[c >> 6] >> (c & 63)) & 1;
}

int dp_json_quote(dp_buf *b, const char *s)
{
    size_t n = s ? strlen(s) : 0;
    if (n > SIZE_MAX / 8 || dp_buf_reserve(b, 6 * n + 2) != DP_OK) /* worst case: every byte as \u00XX */
        return DP_ENOMEM;
    char *p = b->data + b->len;
    *p++ = '"';
    /* Runs of plain bytes are copied whole; the rest go through escape() one by one. */
    for (size_t i = 0, j; i < n; i = j + 1) {
        for (j = i; j < n && !special((unsigned char)s[j]); j++)
            ;
        memcpy(p, s + i, j - i);
        p += j - i;
        if (j == n)
            break;
        p += escape(p, (unsigned char)s[j], j ? (unsigned char)s[j - 1] : 0);
    }
    *p++ = '"';
    b->len = (size_t)(p - b->data);
    b->data[b->len] = '\0';
    return DP_OK;
}
