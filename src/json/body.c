/* src/json/body.c - the one reader of request bodies: bytes into a cJSON tree, for every route and the CLI.
 *
 * Why one: each route used to read its body its own way, so the same fault got different words (or none:
 * /v1/lcp took a repeated key or a NUL in a key silently). Here, once for all:
 *   - nesting deeper than DP_JSON_MAX_DEPTH and NUL bytes outside strings are refused in one pass over the
 *     bytes before cJSON recurses (cJSON would skip a NUL between tokens as whitespace);
 *   - cJSON builds the tree; anything but JSON whitespace after the document is malformed;
 *   - a malformed document is described at its line and column (and byte, which the browser editor marks),
 *     with a hint for the usual slips: NaN or Infinity, single quotes, a trailing comma, a comment, an
 *     unquoted key, a misspelled literal, a missing comma, a document cut short. The description comes from
 *     a strict walk of the text (syntax_fault), run only when cJSON has refused it, so valid bodies cost
 *     nothing more; its token rules are cJSON's own (numbers read by strtod, "nullx" read as null then x),
 *     so it finds the fault cJSON stopped at rather than one cJSON would have let pass;
 *   - the document must be an object; a NUL inside a string or key (cJSON would cut the string there) and a
 *     repeated key at any level (cJSON keeps both, and lookups take the first) are errors at their pointers.
 */
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body.h"
#include "nul_scan.h"
#include "pointer.h"

/* ---- before cJSON: nesting and NUL bytes ------------------------------------------------------------ */

/* The offset where the text first nests deeper than DP_JSON_MAX_DEPTH (*nul = 0) or holds a NUL byte outside
 * a string (*nul = 1), or len. Brackets inside strings do not count; a stray closer never lowers the depth
 * below 0, so no prefix can buy extra depth for cJSON. A NUL inside a string is left to nul_scan.c, which
 * names the string. */
static size_t prescan(const char *s, size_t len, int *nul)
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
                return *nul = 0, i;
        } else if ((ch == ']' || ch == '}') && depth > 0) {
            depth--;
        } else if (ch == '\0') {
            return *nul = 1, i;
        }
    }
    return len;
}

/* ---- where: line and column ------------------------------------------------------------------------- */

/* The 1-based line and column of byte pos: lines end at \n, columns count characters (UTF-8 continuation
 * bytes are not counted), so an editor shows the same place. */
static void line_col(const char *s, size_t pos, size_t *line, size_t *col)
{
    *line = 1, *col = 1;
    for (size_t i = 0; i < pos; i++) {
        if (s[i] == '\n')
            (*line)++, *col = 1;
        else if (((unsigned char)s[i] & 0xC0) != 0x80)
            (*col)++;
    }
}

/* ---- what is wrong: a strict walk of a text cJSON refused ------------------------------------------- */

typedef struct syn {
    const char *s;
    size_t len, pos;        /* the text, and where its first fault is */
    char why[200];          /* what is wrong there */
} syn;

static int found(syn *y, size_t pos, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

static int found(syn *y, size_t pos, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(y->why, sizeof y->why, fmt, ap);
    va_end(ap);
    y->pos = pos;
    return 1;
}

/* The byte at s[i] for a message: 'x' when printable ASCII, else its code. */
static const char *byte_text(const syn *y, size_t i, char buf[16])
{
    unsigned char c = (unsigned char)y->s[i];
    if (c >= 0x21 && c < 0x7F)
        snprintf(buf, 16, "'%c'", c);
    else
        snprintf(buf, 16, "byte 0x%02X", c);
    return buf;
}

static int is_word_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '$';
}

/* The word starting at s[i] (letters, digits, _ and $), at most 40 bytes, into buf. */
static const char *word_at(const syn *y, size_t i, char buf[48])
{
    size_t n = 0;
    while (i + n < y->len && n < 40 && is_word_char(y->s[i + n]))
        n++;
    memcpy(buf, y->s + i, n);
    snprintf(buf + n, 48 - n, "%s", i + n < y->len && is_word_char(y->s[i + n]) ? "..." : "");
    return buf;
}

/* Whether the text at i begins with the literal w (case-sensitive), within the body's length: the body is
 * not NUL-terminated (a fuzzer's "fal" would read past it). */
static int starts_with(const syn *y, size_t i, const char *w)
{
    size_t n = strlen(w);
    return i + n <= y->len && memcmp(y->s + i, w, n) == 0;
}

static int starts_with_ci(const syn *y, size_t i, const char *w)
{
    size_t n = strlen(w);
    if (i + n > y->len)
        return 0;
    for (size_t k = 0; k < n; k++) {
        char c = y->s[i + k];
        if ((c >= 'A' && c <= 'Z' ? c + 32 : c) != w[k])
            return 0;
    }
    return 1;
}

/* A comment at s[i] ("//", slash-star or "#")? */
static int comment_at(const syn *y, size_t i)
{
    return y->s[i] == '#' || (y->s[i] == '/' && i + 1 < y->len && (y->s[i + 1] == '/' || y->s[i + 1] == '*'));
}

/* What stands at s[i] where a value belongs but none can start: the hint for it. */
static int not_a_value(syn *y, size_t i)
{
    char b[48];
    char c = y->s[i];
    size_t j = i + (c == '-' || c == '+');
    if (starts_with_ci(y, j, "nan") || starts_with_ci(y, j, "inf"))
        return found(y, i, "JSON has no NaN or Infinity; send a number or null");
    if (c == '\'')
        return found(y, i, "JSON strings take double quotes, not single quotes");
    if (comment_at(y, i))
        return found(y, i, "JSON has no comments");
    if (c == '+')
        return found(y, i, "a JSON number has no leading +");
    if (c == '.')
        return found(y, i, "a JSON number needs a digit before its point (0.5, not .5)");
    if (is_word_char(c))
        return found(y, i, "unknown word \"%s\"; JSON's literals are true, false and null", word_at(y, i, b));
    return found(y, i, "expected a value, got %s", byte_text(y, i, b));
}

/* The number at s[i] as cJSON reads it (the characters 0-9 + - e E . as far as they go, then strtod): its
 * length, or 0 with the fault found. */
static size_t number(syn *y, size_t i)
{
    size_t n = 0;
    while (i + n < y->len && y->s[i + n] && strchr("0123456789+-eE.", y->s[i + n]))
        n++;
    if (n == 1 && y->s[i] == '-' && (starts_with_ci(y, i + 1, "nan") || starts_with_ci(y, i + 1, "inf")))
        return found(y, i, "JSON has no NaN or Infinity; send a number or null"), 0;
    char *buf = malloc(n + 1), *end;
    if (buf == NULL)
        return found(y, i, "not valid JSON here"), 0;
    memcpy(buf, y->s + i, n);
    buf[n] = '\0';
    strtod(buf, &end);
    size_t read = (size_t)(end - buf);
    free(buf);
    if (read != n)
        return found(y, i, "\"%.*s%s\" is not a number", n > 40 ? 40 : (int)n, y->s + i, n > 40 ? "..." : ""), 0;
    return n;
}

/* The 4 hex digits at s[i] as cJSON's parse_hex4 reads them: 0 when any is not a hex digit. */
static unsigned hex4(const syn *y, size_t i)
{
    unsigned v = 0;
    for (size_t k = 0; k < 4; k++) {
        char c = y->s[i + k];
        int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (d < 0)
            return 0;
        v = v * 16 + (unsigned)d;
    }
    return v;
}

/* The string whose opening quote is s[i]: the offset after its closing quote, or 0 with the fault found.
 * As cJSON reads one: its end is the first quote not after a backslash, then its escapes are decoded: one
 * of \" \\ \/ \b \f \n \r \t, or \u and 4 characters (taken as 0 when they are not all hex digits, as
 * cJSON takes them) where a UTF-16 surrogate comes in a high-low pair. Other bytes (control characters,
 * invalid UTF-8) are taken as they are. */
static size_t string(syn *y, size_t i)
{
    size_t end = i + 1, line, col;
    char b[16];
    while (end < y->len && y->s[end] != '"')
        end += y->s[end] == '\\' ? 2 : 1;
    if (end >= y->len) {
        line_col(y->s, i, &line, &col);
        return found(y, y->len, "the document ends inside the string opened at line %zu, column %zu", line, col), 0;
    }
    for (size_t k = i + 1; k < end; k++) {
        if (y->s[k] != '\\')
            continue;
        char e = y->s[k + 1];
        if (e != 'u' && strchr("\"\\/bfnrt", e) == NULL)
            return found(y, k, "invalid escape \\ followed by %s; JSON's are \\\" \\\\ \\/ \\b \\f \\n \\r \\t "
                         "\\uXXXX", byte_text(y, k + 1, b)), 0;
        if (e != 'u') {
            k++;
            continue;
        }
        if (end - k < 6)
            return found(y, k, "\\u must be followed by 4 hex digits"), 0;
        unsigned u = hex4(y, k + 2), lo;
        if (u >= 0xDC00 && u <= 0xDFFF)
            return found(y, k, "\\u%.4s is the second half of a UTF-16 surrogate pair, alone", y->s + k + 2), 0;
        if (u >= 0xD800 && u <= 0xDBFF) {
            if (end - k < 12 || y->s[k + 6] != '\\' || y->s[k + 7] != 'u' || (lo = hex4(y, k + 8)) < 0xDC00 ||
                lo > 0xDFFF)
                return found(y, k, "\\u%.4s is the first half of a UTF-16 surrogate pair; the second "
                             "(\\uDC00 to \\uDFFF) must follow", y->s + k + 2), 0;
            k += 6;
        }
        k += 5;
    }
    return end + 1;
}

typedef enum { VALUE, FIRST_KEY, KEY, COLON, AFTER_VALUE, FIRST_ITEM, ITEM } expect;

/* Walks text that cJSON refused, by the JSON grammar with cJSON's tokens, to the first fault: its place
 * and what is wrong there into y. 0 when none is found (cJSON refused something the walk allows; the
 * caller then reports cJSON's own place). */
static int syntax_fault(syn *y)
{
    struct { char bracket; size_t at; } open[DP_JSON_MAX_DEPTH + 1];
    int depth = 0;
    expect want = VALUE;
    size_t i = y->len >= 3 && memcmp(y->s, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0, comma = 0, line, col;
    char b[48];
    for (;;) {
        while (i < y->len && (unsigned char)y->s[i] <= 32 && y->s[i] != '\0')
            i++;
        if (i == y->len) {
            if (depth == 0 && want == VALUE)
                return found(y, i, "empty document: send one JSON object");
            if (depth == 0)
                return 0;
            line_col(y->s, open[depth - 1].at, &line, &col);
            return found(y, i, "the document ends early: the %c at line %zu, column %zu is never closed",
                         open[depth - 1].bracket, line, col);
        }
        char c = y->s[i];
        char close = depth > 0 ? (open[depth - 1].bracket == '{' ? '}' : ']') : 0;
        if (comment_at(y, i))
            return found(y, i, "JSON has no comments");
        switch (want) {
        case FIRST_ITEM:
        case ITEM:
        case VALUE:
            if (c == ']' && want == FIRST_ITEM) {
                depth--, i++, want = AFTER_VALUE;
                break;
            }
            if (c == ']' && want == ITEM)
                return found(y, comma, "a trailing comma before ]; remove it");
            if (c == '{' || c == '[') {
                if (depth > DP_JSON_MAX_DEPTH)
                    return 0;
                open[depth].bracket = c, open[depth++].at = i++;
                want = c == '{' ? FIRST_KEY : FIRST_ITEM;
            } else if (c == '"') {
                if ((i = string(y, i)) == 0)
                    return 1;
                want = AFTER_VALUE;
            } else if (c == '-' || (c >= '0' && c <= '9')) {
                size_t n = number(y, i);
                if (n == 0)
                    return 1;
                i += n, want = AFTER_VALUE;
            } else if (starts_with(y, i, "true") || starts_with(y, i, "null")) {
                i += 4, want = AFTER_VALUE;   /* a prefix match, as cJSON's: "nullx" is null, then x */
            } else if (starts_with(y, i, "false")) {
                i += 5, want = AFTER_VALUE;
            } else {
                return not_a_value(y, i);
            }
            break;
        case FIRST_KEY:
        case KEY:
            if (c == '}' && want == FIRST_KEY) {
                depth--, i++, want = AFTER_VALUE;
            } else if (c == '}') {
                return found(y, comma, "a trailing comma before }; remove it");
            } else if (c == '"') {
                if ((i = string(y, i)) == 0)
                    return 1;
                want = COLON;
            } else if (c == '\'') {
                return found(y, i, "JSON keys take double quotes, not single quotes");
            } else if (is_word_char(c)) {
                word_at(y, i, b);
                return found(y, i, "the key %s must be in double quotes: \"%s\"", b, b);
            } else {
                char t[16];
                return found(y, i, "expected a key in double quotes, got %s", byte_text(y, i, t));
            }
            break;
        case COLON:
            if (c != ':') {
                char t[16];
                return found(y, i, "expected : after the key, got %s", byte_text(y, i, t));
            }
            i++, want = VALUE;
            break;
        case AFTER_VALUE:
            if (depth == 0)
                return found(y, i, "data after the document (send one JSON object)");
            if (c == ',') {
                comma = i++;
                want = close == '}' ? KEY : ITEM;
            } else if (c == close) {
                depth--, i++;
            } else if (c == '}' || c == ']') {
                line_col(y->s, open[depth - 1].at, &line, &col);
                return found(y, i, "this %c does not close the %c at line %zu, column %zu", c,
                             open[depth - 1].bracket, line, col);
            } else if (c == '"' || c == '{' || c == '[' || c == '-' || (c >= '0' && c <= '9') || is_word_char(c)) {
                return found(y, i, "a comma is missing between two %s", close == '}' ? "members" : "values");
            } else {
                char t[16];
                return found(y, i, "expected , or %c, got %s", close, byte_text(y, i, t));
            }
            break;
        }
    }
}

/* The one error of a malformed document: its place as byte, line and column, and what is wrong there. */
static void malformed(dp_errors *errs, const char *s, size_t pos, const char *why)
{
    size_t line, col;
    line_col(s, pos, &line, &col);
    dp_errors_add(errs, "", "malformed JSON near byte %zu (line %zu, column %zu): %s", pos, line, col, why);
}

/* ---- after cJSON: the object, its NULs and its repeated keys ---------------------------------------- */

const char *jb_type_name(const cJSON *v)
{
    if (cJSON_IsNumber(v)) return "a number";
    if (cJSON_IsString(v)) return "a string";
    if (cJSON_IsBool(v)) return "a boolean";
    if (cJSON_IsNull(v)) return "null";
    if (cJSON_IsArray(v)) return "an array";
    if (cJSON_IsObject(v)) return "an object";
    return "an unknown value";
}

const char *jb_shown(const char *s, char buf[64])
{
    size_t n = 0;
    for (; s[n] && n < 48; n++)
        buf[n] = (unsigned char)s[n] < 0x20 ? '?' : s[n];
    if (s[n]) {
        n = jp_utf8_trim(buf, n);
        memcpy(buf + n, "...", 3);
        n += 3;
    }
    buf[n] = '\0';
    return buf;
}

typedef struct keyed {
    const char *key;
    size_t index;
} keyed;

static int by_key_then_index(const void *a, const void *b)
{
    const keyed *x = a, *y = b;
    int k = strcmp(x->key, y->key);
    return k ? k : x->index < y->index ? -1 : x->index > y->index;
}

static void repeated(dp_errors *errs, const at *where, const char *key, size_t *count)
{
    char ptr[DP_POINTER_MAX], sb[64];
    const at p = { where, key, 0 };
    jp_text(&p, ptr);
    dp_errors_add(errs, ptr, "duplicate key \"%s\"", jb_shown(key, sb));
    (*count)++;
}

/* Every repeated key of object o (each at its second and later places, in document order). An object of
 * a few members is compared pairwise; a large one sorted, so a hostile body of 10^5 keys costs n log n. */
static int repeated_keys(const cJSON *o, const at *where, dp_errors *errs, size_t *count)
{
    size_t n = 0;
    for (const cJSON *m = o->child; m; m = m->next)
        n++;
    if (n <= 16) {
        for (const cJSON *m = o->child; m; m = m->next)
            for (const cJSON *q = o->child; q != m; q = q->next)
                if (strcmp(q->string, m->string) == 0) {
                    repeated(errs, where, m->string, count);
                    break;
                }
        return DP_OK;
    }
    keyed *k = malloc(n * sizeof *k);
    unsigned char *dup = calloc(n, 1);
    if (k == NULL || dup == NULL) {
        free(k);
        free(dup);
        return DP_ENOMEM;
    }
    size_t i = 0;
    for (const cJSON *m = o->child; m; m = m->next, i++)
        k[i] = (keyed){ m->string, i };
    qsort(k, n, sizeof *k, by_key_then_index);
    for (i = 1; i < n; i++)
        if (strcmp(k[i].key, k[i - 1].key) == 0)
            dup[k[i].index] = 1;
    i = 0;
    for (const cJSON *m = o->child; m; m = m->next, i++)
        if (dup[i])
            repeated(errs, where, m->string, count);
    free(k);
    free(dup);
    return DP_OK;
}

/* Repeated keys in v and everything below it (the nesting is bounded by DP_JSON_MAX_DEPTH). */
static int repeated_below(const cJSON *v, const at *where, dp_errors *errs, size_t *count)
{
    int s = cJSON_IsObject(v) ? repeated_keys(v, where, errs, count) : DP_OK;
    size_t i = 0;
    for (const cJSON *m = v->child; m && s == DP_OK; m = m->next, i++) {
        if (!cJSON_IsObject(m) && !cJSON_IsArray(m))
            continue;
        const at here = { where, cJSON_IsObject(v) ? m->string : NULL, i };
        s = repeated_below(m, &here, errs, count);
    }
    return s;
}

/* ---- the reader ------------------------------------------------------------------------------------- */

int dp_body_read(const char *text, size_t len, dp_errors *errs, cJSON **root)
{
    *root = NULL;
    if (text == NULL)
        text = "", len = 0;
    int nul;
    size_t bad = prescan(text, len, &nul);
    if (bad < len) {
        char why[64];
        snprintf(why, sizeof why, nul ? "a NUL byte outside any string" : "nested deeper than %d levels",
                 DP_JSON_MAX_DEPTH);
        malformed(errs, text, bad, why);
        return DP_ESYNTAX;
    }
    /* cJSON reads a NUL-terminated copy: its BOM check peeks 3 bytes regardless of the length. */
    char *buf = len < SIZE_MAX ? malloc(len + 1) : NULL;
    if (buf == NULL)
        return DP_ENOMEM;
    if (len > 0)
        memcpy(buf, text, len);
    buf[len] = '\0';
    const char *end = NULL;
    cJSON *doc = cJSON_ParseWithLengthOpts(buf, len, &end, 0);
    size_t after = doc != NULL ? (size_t)(end - buf) + strspn(end, " \t\r\n") : 0;
    if (doc != NULL && after != len) {
        cJSON_Delete(doc);
        free(buf);
        malformed(errs, text, after, "data after the document (send one JSON object)");
        return DP_ESYNTAX;
    }
    if (doc == NULL) {
        syn y = { text, len, 0, "" };
        size_t at_cjson = end ? (size_t)(end - buf) : 0;
        free(buf);
        if (!syntax_fault(&y))
            found(&y, at_cjson, "not valid JSON here");
        malformed(errs, text, y.pos, y.why);
        return DP_ESYNTAX;
    }
    free(buf);
    if (!cJSON_IsObject(doc)) {
        dp_errors_add(errs, "", "must be an object, got %s", jb_type_name(doc));
        cJSON_Delete(doc);
        return DP_EINVAL;
    }
    size_t count = 0;
    char ptr[DP_POINTER_MAX];
    int in_key = 0;
    if (dp_json_find_nul(text, len, ptr, &in_key)) {
        dp_errors_add(errs, ptr, "%s contains a NUL character (\\u0000), which no field may hold",
                      in_key ? "a key of this object" : "this string");
        count++;
    }
    if (repeated_below(doc, NULL, errs, &count) != DP_OK) {
        cJSON_Delete(doc);
        return DP_ENOMEM;
    }
    *root = doc;
    return count ? DP_EINVAL : DP_OK;
}
