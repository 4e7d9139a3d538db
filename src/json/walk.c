/* src/json/walk.c - the document walker (walk.h): typed members looked up by name, unknown members refused,
 * numbers checked against their ranges, every error collected at its JSON Pointer, for the parser of every
 * route. One walker, so that a mistyped number or an unknown key is worded alike on /v1/simulate,
 * /v1/stability, /v1/lcp, /v1/modes, /v1/response and /v1/wellposedness.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body.h"
#include "walk.h"

cJSON *jw_read(ctx *c, const char *text, size_t len, int *status)
{
    size_t before = c->errs->n + c->errs->dropped;
    cJSON *root;
    *status = dp_body_read(text, len, c->errs, &root);
    c->nerr += c->errs->n + c->errs->dropped - before;
    return root;
}

void jw_fail(ctx *c, const at *where, const char *fmt, ...)
{
    char msg[DP_MESSAGE_MAX], ptr[DP_POINTER_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    jp_text(where, ptr);
    dp_errors_add(c->errs, ptr, "%s", msg);
    c->nerr++;
}

/* The shortest of %.15g / %.17g that reads back as v, so 0.1 shows as "0.1" and nothing is misreported. */
const char *jw_num_text(double v, char buf[32])
{
    snprintf(buf, 32, "%.15g", v);
    if (strtod(buf, NULL) != v)
        snprintf(buf, 32, "%.17g", v);
    return buf;
}

/* "a, b, c" from a NULL-terminated list. */
const char *jw_joined(const char *const *names, char *buf, size_t cap)
{
    size_t n = 0;
    buf[0] = '\0';
    for (size_t i = 0; names[i] && n < cap; i++)
        n += (size_t)snprintf(buf + n, cap - n, "%s%s", i ? ", " : "", names[i]);
    return buf;
}

/* ---- typed members ---------------------------------------------------------------------------------- */

/* Member `key` of object o (its place into p), or NULL; when absent and `what` is set, that is an error. */
const cJSON *jw_member(ctx *c, const cJSON *o, const at *ptr, const char *key, const char *what, at *p)
{
    *p = (at){ ptr, key, 0 };
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    if (v == NULL && what != NULL)
        jw_fail(c, p, "missing required key \"%s\" (%s)", key, what);
    return v;
}

int jw_want_object(ctx *c, const cJSON *v, const at *ptr)
{
    if (cJSON_IsObject(v))
        return 1;
    jw_fail(c, ptr, "must be an object, got %s", jb_type_name(v));
    return 0;
}

static int in_range(double x, const range *r)
{
    return x >= r->lo && x <= r->hi && !(r->lo_open && x == r->lo);
}

/* v as a finite number in r (an integer when `integral`) into *out; 0 and an error otherwise. */
int jw_check_num(ctx *c, const cJSON *v, const at *ptr, const range *r, int integral, double *out)
{
    const char *what = integral ? "an integer" : "a finite number";
    char nb[32];
    if (!cJSON_IsNumber(v)) {
        jw_fail(c, ptr, "must be %s%s, got %s", what, r->text, jb_type_name(v));
        return 0;
    }
    double x = v->valuedouble;
    if (!isfinite(x)) {
        jw_fail(c, ptr, "must be %s%s, got a literal too large for a double", what, r->text);
        return 0;
    }
    if ((integral && x != floor(x)) || !in_range(x, r)) {
        jw_fail(c, ptr, "must be %s%s, got %s", what, r->text, jw_num_text(x, nb));
        return 0;
    }
    *out = x;
    return 1;
}

/* Numeric member; *out untouched when it is absent (the default stays) or invalid. Returns 1 when set. */
int jw_get_num(ctx *c, const cJSON *o, const at *ptr, const char *key, const range *r, int required,
                   int integral, double *out)
{
    at p;
    const cJSON *v = jw_member(c, o, ptr, key, NULL, &p);
    if (v == NULL && required) {
        char what[64];
        snprintf(what, sizeof what, "%s%s", integral ? "an integer" : "a finite number", r->text);
        jw_fail(c, &p, "missing required key \"%s\" (%s)", key, what);
    }
    return v != NULL && jw_check_num(c, v, &p, r, integral, out);
}

void jw_get_bool(ctx *c, const cJSON *o, const at *ptr, const char *key, int *out)
{
    at p;
    const cJSON *v = jw_member(c, o, ptr, key, NULL, &p);
    if (v == NULL)
        return;
    if (cJSON_IsBool(v))
        *out = cJSON_IsTrue(v);
    else
        jw_fail(c, &p, "must be true or false, got %s", jb_type_name(v));
}

/* Index of the string member `key` in `names`; `def` when absent (-1 and an error when def < 0), -1 and an
 * error when it is not one of them. */
int jw_get_enum(ctx *c, const cJSON *o, const at *ptr, const char *key, const char *const *names,
                    int def)
{
    char list[256], sb[64];
    at p;
    const cJSON *v = jw_member(c, o, ptr, key, NULL, &p);
    if (v == NULL && def < 0) {
        char what[300];
        snprintf(what, sizeof what, "one of: %s", jw_joined(names, list, sizeof list));
        jw_fail(c, &p, "missing required key \"%s\" (%s)", key, what);
    }
    if (v == NULL)
        return def;
    if (!cJSON_IsString(v)) {
        jw_fail(c, &p, "must be a string, one of: %s; got %s", jw_joined(names, list, sizeof list), jb_type_name(v));
        return -1;
    }
    for (int i = 0; names[i]; i++)
        if (strcmp(v->valuestring, names[i]) == 0)
            return i;
    jw_fail(c, &p, "unknown %s \"%s\"; expected one of: %s", key, jb_shown(v->valuestring, sb),
         jw_joined(names, list, sizeof list));
    return -1;
}

static int key_index(const char *const *keys, const char *k)
{
    for (int i = 0; keys[i]; i++)
        if (strcmp(keys[i], k) == 0)
            return i;
    return -1;
}

/* Reports every member of o that is not in `keys` (a repeated one is the body reader's, body.c). With a tag,
 * the list is qualified (" for law \"coulomb\"": tag "law", its value "coulomb"). O(members x keys): no
 * quadratic blow-up on a hostile document. */
void jw_check_keys(ctx *c, const cJSON *o, const at *ptr, const char *const *keys, const char *tag,
                       const char *value)
{
    char list[256], sb[64], why[96];
    for (const cJSON *m = o->child; m; m = m->next) {
        at p = { ptr, m->string, 0 };
        if (key_index(keys, m->string) < 0) {
            why[0] = '\0';
            if (tag != NULL)
                snprintf(why, sizeof why, " for %s \"%s\"", tag, value);
            jw_fail(c, &p, "unknown key \"%s\"%s; expected one of: %s", jb_shown(m->string, sb), why,
                 jw_joined(keys, list, sizeof list));
        }
    }
}

/* An array of 1..max items; its size, or 0 with an error. */
size_t jw_array_size(ctx *c, const cJSON *v, const at *p, size_t max, const char *what)
{
    size_t n = cJSON_IsArray(v) ? (size_t)cJSON_GetArraySize(v) : 0;
    if (!cJSON_IsArray(v))
        jw_fail(c, p, "must be %s, got %s", what, jb_type_name(v));
    else if (n > max)
        jw_fail(c, p, "must be %s: %zu is over the limit of %zu", what, n, max);
    else if (n == 0)
        jw_fail(c, p, "must be %s, got an empty array", what);
    return cJSON_IsArray(v) && n <= max ? n : 0;
}

