/* src/json/spec_json.c - dp_spec_parse (json.h): a simulation spec document (architecture.md, "The wire
 * contract") into a dp_spec, every bad field reported with its JSON Pointer (RFC 6901) and what was expected.
 *
 * Three passes: a bracket scan bounds the nesting before cJSON recurses; cJSON builds the tree; a walk that
 * never stops at the first error fills the spec. Only a document without field errors reaches the core's
 * dp_model_prepare and dp_spec_check, whose cross-field rules need the whole spec.
 *
 * The walk carries where it is as a chain of (parent, key or index) on the stack (`at`); the pointer text
 * and the "expected ..." wording are written only when an error is reported. Building them for every member
 * up front (snprintf per member) was most of what parsing a valid spec cost.
 *
 * Message format: the pointer names the place; the message says what was expected and, where it helps, what
 * was found: "must be a finite number > 0, got -1", "unknown law \"colomb\"; expected one of: none, ...",
 * "unknown key \"foo\"; expected one of: mass, spring, damper, forcing", "missing required key \"mass\"
 * (a finite number > 0)", "malformed JSON near byte 17".
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "dashpot/json.h"
#include "body.h"

/* The walk's state: where errors go, how many this parse added, whether an allocation failed. */
typedef struct ctx {
    dp_errors *errs;
    size_t nerr;
    int nomem;
    int lenient;   /* well-posedness requests: user graphs may be non-monotone or have gaps (null) */
} ctx;

/* An accepted interval for a number, with the words that describe it in messages. */
typedef struct range {
    double lo, hi;
    int lo_open;          /* lo itself excluded */
    const char *text;     /* appended to "a finite number" / "an integer" */
} range;

static const range ANY = { -INFINITY, INFINITY, 0, "" };
static const range POSITIVE = { 0, INFINITY, 1, " > 0" };
static const range NONNEG = { 0, INFINITY, 0, " >= 0" };
static const range ABOVE_ONE = { 1, INFINITY, 1, " > 1" };
static const range THETA = { 0.5, 1, 0, " in [0.5, 1]" };
static const range BETA = { 0, 0.5, 1, " in (0, 0.5]" };
static const range GAMMA = { 0.5, 1, 0, " in [0.5, 1]" };
static const range Z_RANGE = { 1, 1000000, 0, " in [1, 1000000]" };
/* 2^53: past it not every integer is a double, and it still fits a long on LP64. */
static const range EVERY = { 1, 9007199254740992.0, 0, " >= 1 (at most 2^53)" };

#define MAX_KEYS 12       /* valid keys of any one object of the schema */

/* A number-valued member stored at byte offset `off` of the struct being filled. */
typedef struct param {
    const char *key;
    size_t off;
    const range *r;
    int required;
} param;

/* One value of a tag ("law", "kind"): its enum value, its numeric members, other members its caller reads. */
typedef struct variant {
    const char *name;
    int id;
    param params[5];              /* ends at key == NULL */
    const char *extra[6];         /* ends at NULL */
} variant;

/* Where a value sits: its parent (NULL: the document itself) and its member name, or its index in an
 * array when key is NULL. Lives on the walk's stack; rendered as a JSON Pointer only for an error. */
typedef struct at {
    const struct at *up;
    const char *key;
    size_t index;
} at;

/* ---- errors, pointers, displayed values ------------------------------------------------------------- */

/* Drops a UTF-8 sequence cut short at the end of s[0..n), so a truncated string stays valid UTF-8. */
static size_t utf8_trim(const char *s, size_t n)
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

/* out = parent + "/" + key with ~ and / escaped (RFC 6901 §3); cut to DP_POINTER_MAX on a character. */
static void ptr_key(char out[DP_POINTER_MAX], const char *parent, const char *key)
{
    size_t n = (size_t)snprintf(out, DP_POINTER_MAX, "%s/", parent);
    if (n >= DP_POINTER_MAX)
        return;
    const char *k = key;
    for (; *k && n + 3 <= DP_POINTER_MAX; k++) {
        if (*k == '~' || *k == '/') {
            out[n++] = '~';
            out[n++] = *k == '~' ? '0' : '1';
        } else {
            out[n++] = *k;
        }
    }
    out[*k ? utf8_trim(out, n) : n] = '\0';
}

static void ptr_index(char out[DP_POINTER_MAX], const char *parent, size_t i)
{
    /* Only digits can be cut here (the parent is already valid); the check just uses the result. */
    if (snprintf(out, DP_POINTER_MAX, "%s/%zu", parent, i) >= DP_POINTER_MAX)
        out[DP_POINTER_MAX - 1] = '\0';
}

/* The JSON Pointer of `a`, built level by level exactly as each level's text would be on its own. */
static void ptr_text(const at *a, char out[DP_POINTER_MAX])
{
    char up[DP_POINTER_MAX];
    if (a == NULL) {
        out[0] = '\0';
        return;
    }
    ptr_text(a->up, up);
    if (a->key != NULL)
        ptr_key(out, up, a->key);
    else
        ptr_index(out, up, a->index);
}

static void fail(ctx *c, const at *where, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

static void fail(ctx *c, const at *where, const char *fmt, ...)
{
    char msg[DP_MESSAGE_MAX], ptr[DP_POINTER_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    ptr_text(where, ptr);
    dp_errors_add(c->errs, ptr, "%s", msg);
    c->nerr++;
}

/* A user string fit for a message: at most 48 bytes (then "..."), control characters as '?'. */
static const char *shown(const char *s, char buf[64])
{
    size_t n = 0;
    for (; s[n] && n < 48; n++)
        buf[n] = (unsigned char)s[n] < 0x20 ? '?' : s[n];
    if (s[n]) {
        n = utf8_trim(buf, n);
        memcpy(buf + n, "...", 3);
        n += 3;
    }
    buf[n] = '\0';
    return buf;
}

/* The shortest of %.15g / %.17g that reads back as v, so 0.1 shows as "0.1" and nothing is misreported. */
static const char *num_text(double v, char buf[32])
{
    snprintf(buf, 32, "%.15g", v);
    if (strtod(buf, NULL) != v)
        snprintf(buf, 32, "%.17g", v);
    return buf;
}

static const char *type_name(const cJSON *v)
{
    if (cJSON_IsNumber(v)) return "a number";
    if (cJSON_IsString(v)) return "a string";
    if (cJSON_IsBool(v)) return "a boolean";
    if (cJSON_IsNull(v)) return "null";
    if (cJSON_IsArray(v)) return "an array";
    if (cJSON_IsObject(v)) return "an object";
    return "an unknown value";
}

/* "a, b, c" from a NULL-terminated list. */
static const char *joined(const char *const *names, char *buf, size_t cap)
{
    size_t n = 0;
    buf[0] = '\0';
    for (size_t i = 0; names[i] && n < cap; i++)
        n += (size_t)snprintf(buf + n, cap - n, "%s%s", i ? ", " : "", names[i]);
    return buf;
}

/* ---- typed members ---------------------------------------------------------------------------------- */

/* Member `key` of object o (its place into p), or NULL; when absent and `what` is set, that is an error. */
static const cJSON *member(ctx *c, const cJSON *o, const at *ptr, const char *key, const char *what, at *p)
{
    *p = (at){ ptr, key, 0 };
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    if (v == NULL && what != NULL)
        fail(c, p, "missing required key \"%s\" (%s)", key, what);
    return v;
}

static int want_object(ctx *c, const cJSON *v, const at *ptr)
{
    if (cJSON_IsObject(v))
        return 1;
    fail(c, ptr, "must be an object, got %s", type_name(v));
    return 0;
}

static int in_range(double x, const range *r)
{
    return x >= r->lo && x <= r->hi && !(r->lo_open && x == r->lo);
}

/* v as a finite number in r (an integer when `integral`) into *out; 0 and an error otherwise. */
static int check_num(ctx *c, const cJSON *v, const at *ptr, const range *r, int integral, double *out)
{
    const char *what = integral ? "an integer" : "a finite number";
    char nb[32];
    if (!cJSON_IsNumber(v)) {
        fail(c, ptr, "must be %s%s, got %s", what, r->text, type_name(v));
        return 0;
    }
    double x = v->valuedouble;
    if (!isfinite(x)) {
        fail(c, ptr, "must be %s%s, got a literal too large for a double", what, r->text);
        return 0;
    }
    if ((integral && x != floor(x)) || !in_range(x, r)) {
        fail(c, ptr, "must be %s%s, got %s", what, r->text, num_text(x, nb));
        return 0;
    }
    *out = x;
    return 1;
}

/* Numeric member; *out untouched when it is absent (the default stays) or invalid. Returns 1 when set. */
static int get_num(ctx *c, const cJSON *o, const at *ptr, const char *key, const range *r, int required,
                   int integral, double *out)
{
    at p;
    const cJSON *v = member(c, o, ptr, key, NULL, &p);
    if (v == NULL && required) {
        char what[64];
        snprintf(what, sizeof what, "%s%s", integral ? "an integer" : "a finite number", r->text);
        fail(c, &p, "missing required key \"%s\" (%s)", key, what);
    }
    return v != NULL && check_num(c, v, &p, r, integral, out);
}

static void get_bool(ctx *c, const cJSON *o, const at *ptr, const char *key, int *out)
{
    at p;
    const cJSON *v = member(c, o, ptr, key, NULL, &p);
    if (v == NULL)
        return;
    if (cJSON_IsBool(v))
        *out = cJSON_IsTrue(v);
    else
        fail(c, &p, "must be true or false, got %s", type_name(v));
}

/* Index of the string member `key` in `names`; `def` when absent (-1 and an error when def < 0), -1 and an
 * error when it is not one of them. */
static int get_enum(ctx *c, const cJSON *o, const at *ptr, const char *key, const char *const *names,
                    int def)
{
    char list[256], sb[64];
    at p;
    const cJSON *v = member(c, o, ptr, key, NULL, &p);
    if (v == NULL && def < 0) {
        char what[300];
        snprintf(what, sizeof what, "one of: %s", joined(names, list, sizeof list));
        fail(c, &p, "missing required key \"%s\" (%s)", key, what);
    }
    if (v == NULL)
        return def;
    if (!cJSON_IsString(v)) {
        fail(c, &p, "must be a string, one of: %s; got %s", joined(names, list, sizeof list), type_name(v));
        return -1;
    }
    for (int i = 0; names[i]; i++)
        if (strcmp(v->valuestring, names[i]) == 0)
            return i;
    fail(c, &p, "unknown %s \"%s\"; expected one of: %s", key, shown(v->valuestring, sb),
         joined(names, list, sizeof list));
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
static void check_keys(ctx *c, const cJSON *o, const at *ptr, const char *const *keys, const char *tag,
                       const char *value)
{
    char list[256], sb[64], why[96];
    for (const cJSON *m = o->child; m; m = m->next) {
        at p = { ptr, m->string, 0 };
        if (key_index(keys, m->string) < 0) {
            why[0] = '\0';
            if (tag != NULL)
                snprintf(why, sizeof why, " for %s \"%s\"", tag, value);
            fail(c, &p, "unknown key \"%s\"%s; expected one of: %s", shown(m->string, sb), why,
                 joined(keys, list, sizeof list));
        }
    }
}

/* ---- tagged objects: {"law": name, params...} -------------------------------------------------------- */

/* Parses object o whose member `tag` picks one of `vs` (nv of them; `def` when absent, < 0: required).
 * Checks its keys (tag, the variant's params and extras, `common`), stores the params into `base` and
 * returns the variant, or NULL when o is no object or the tag is bad (its other members are then not
 * checked: which keys are valid depends on the tag). */
static const variant *parse_tagged(ctx *c, const cJSON *o, const at *ptr, const char *tag, int def,
                                   const variant *vs, size_t nv, const char *const *common, void *base)
{
    const char *names[8], *keys[MAX_KEYS];
    size_t nk = 0;
    if (!want_object(c, o, ptr))
        return NULL;
    for (size_t i = 0; i < nv; i++)
        names[i] = vs[i].name;
    names[nv] = NULL;
    int i = get_enum(c, o, ptr, tag, names, def);
    if (i < 0)
        return NULL;
    const variant *v = &vs[i];
    keys[nk++] = tag;
    for (const param *pa = v->params; pa->key; pa++)
        keys[nk++] = pa->key;
    for (const char *const *e = v->extra; *e; e++)
        keys[nk++] = *e;
    for (const char *const *e = common; e && *e; e++)
        keys[nk++] = *e;
    keys[nk] = NULL;
    check_keys(c, o, ptr, keys, tag, v->name);
    for (const param *pa = v->params; pa->key; pa++)
        get_num(c, o, ptr, pa->key, pa->r, pa->required, 0, (double *)((char *)base + pa->off));
    return v;
}

/* ---- point lists ------------------------------------------------------------------------------------ */

/* One element of a point list: an array of exactly two finite numbers. */
static int parse_pair(ctx *c, const cJSON *el, const at *p, const char *yname, double *y, double *f)
{
    int n = cJSON_GetArraySize(el);
    if (c->lenient && cJSON_IsNull(el)) { /* a gap: the curve is broken here */
        *y = *f = NAN;
        return 1;
    }
    if (!cJSON_IsArray(el) || n != 2) {
        if (cJSON_IsArray(el))
            fail(c, p, "must have exactly 2 elements [%s, F], got %d", yname, n);
        else
            fail(c, p, "must be a pair [%s, F] of numbers, got %s", yname, type_name(el));
        return 0;
    }
    at q0 = { p, NULL, 0 }, q1 = { p, NULL, 1 };
    int ok = check_num(c, el->child, &q0, &ANY, 0, y);
    return check_num(c, el->child->next, &q1, &ANY, 0, f) && ok;
}

/* Order rules between consecutive points: a graph is non-decreasing in both coordinates without repeated
 * points (so its first and last segments, which become the end rays, are never degenerate); a table has
 * strictly increasing t. */
static void check_order(ctx *c, const at *ptr, const char *yname, int table, size_t n, const double *y,
                        const double *f)
{
    char a[32], b[32];
    for (size_t i = 1; i < n; i++) {
        const at pi = { ptr, NULL, i }, *p = &pi;
        if (table && y[i] <= y[i - 1])
            fail(c, p, "t must be strictly increasing: %s after %s", num_text(y[i], a), num_text(y[i - 1], b));
        if (table)
            continue;
        if (y[i] < y[i - 1])
            fail(c, p, "%s must be non-decreasing: %s after %s", yname, num_text(y[i], a), num_text(y[i - 1], b));
        if (f[i] < f[i - 1])
            fail(c, p, "F must be non-decreasing: %s after %s", num_text(f[i], a), num_text(f[i - 1], b));
        if (y[i] == y[i - 1] && f[i] == f[i - 1])
            fail(c, p, "repeats the previous point (%s, %s)", num_text(y[i], a), num_text(f[i], b));
    }
}

/* o["points"] into new arrays *y, *f of *n entries (caller frees them, also on failure). Returns 1 when
 * the list is valid. A table needs >= 1 point, a graph >= 2. */
static int parse_points(ctx *c, const cJSON *o, const at *ptr, const char *yname, int table, size_t *n,
                        double **y, double **f)
{
    char what[96];
    size_t lo = table ? 1 : 2;
    at pp, *p = &pp;
    const cJSON *a = member(c, o, ptr, "points", NULL, p);
    size_t count = cJSON_IsArray(a) ? (size_t)cJSON_GetArraySize(a) : 0;
    if (a == NULL || !cJSON_IsArray(a) || count < lo || count > DP_GRAPH_MAX_POINTS) {
        snprintf(what, sizeof what, "an array of %zu..%d [%s, F] pairs", lo, DP_GRAPH_MAX_POINTS, yname);
        if (a == NULL)
            fail(c, p, "missing required key \"points\" (%s)", what);
        else if (cJSON_IsArray(a))
            fail(c, p, "must be %s, got %zu", what, count);
        else
            fail(c, p, "must be %s, got %s", what, type_name(a));
        return 0;
    }
    *y = malloc(count * sizeof **y);
    *f = malloc(count * sizeof **f);
    if (*y == NULL || *f == NULL) {
        c->nomem = 1;
        return 0;
    }
    size_t before = c->nerr, i = 0;
    for (const cJSON *el = a->child; el; el = el->next, i++) {
        at q = { p, NULL, i };
        parse_pair(c, el, &q, yname, &(*y)[i], &(*f)[i]);
    }
    if (c->nerr == before && !c->lenient)
        check_order(c, p, yname, table, count, *y, *f);
    if (c->nerr == before && c->lenient && (isnan((*y)[0]) || isnan((*y)[count - 1])))
        fail(c, p, "a gap (null) must lie between two points");
    *n = count;
    return c->nerr == before;
}

/* o["points"] as a user graph into g (dp_graph_init_points copies the arrays). */
static void parse_graph(ctx *c, const cJSON *o, const at *ptr, const char *yname, dp_graph *g)
{
    double *y = NULL, *f = NULL;
    size_t n = 0;
    if (parse_points(c, o, ptr, yname, 0, &n, &y, &f)) {
        int s = c->lenient ? dp_graph_init_raw(g, n, y, f) : dp_graph_init_points(g, n, y, f);
        const at p = { ptr, "points", 0 };
        if (s == DP_ENOMEM)
            c->nomem = 1;
        else if (s != DP_OK)
            fail(c, &p, "does not make a monotone graph (non-decreasing %s and F, end segments not degenerate)",
                 yname);
    }
    free(y);
    free(f);
}

/* ---- the schema ------------------------------------------------------------------------------------- */

#define NUM(st, field, r, req) { #field, offsetof(st, field), &(r), (req) }

static void parse_spring(ctx *c, const cJSON *o, const at *ptr, dp_spring *s)
{
    static const variant laws[] = {
        { "linear", DP_SPRING_LINEAR, { NUM(dp_spring, k, NONNEG, 1) }, { NULL } },
        { "rope", DP_SPRING_ROPE, { NUM(dp_spring, k, NONNEG, 1), NUM(dp_spring, length, ANY, 1) }, { NULL } },
        { "graph", DP_SPRING_GRAPH, { { NULL } }, { "points", NULL } },
        { "elastoplastic", DP_SPRING_ELASTOPLASTIC, { NUM(dp_spring, k, POSITIVE, 1), NUM(dp_spring, yield, POSITIVE, 1),
          NUM(dp_spring, offset, ANY, 0) }, { NULL } },
    };
    const variant *v = parse_tagged(c, o, ptr, "law", -1, laws, 4, NULL, s);
    if (v == NULL)
        return;
    s->law = (dp_spring_law)v->id;
    if (s->law == DP_SPRING_GRAPH)
        parse_graph(c, o, ptr, "x", &s->graph);
}

static void parse_relaxation(ctx *c, const cJSON *o, const at *ptr, dp_relaxation *r)
{
    static const variant kinds[] = {
        { "rational", DP_RELAX_RATIONAL,
          { NUM(dp_relaxation, a, NONNEG, 1), NUM(dp_relaxation, b, POSITIVE, 1) }, { NULL } },
        { "linear", DP_RELAX_LINEAR, { NUM(dp_relaxation, L, ANY, 1) }, { NULL } },
        { "power", DP_RELAX_POWER, { NUM(dp_relaxation, N, ABOVE_ONE, 1) }, { NULL } },
    };
    const variant *v = parse_tagged(c, o, ptr, "kind", -1, kinds, 3, NULL, r);
    if (v != NULL)
        r->kind = (dp_relaxation_kind)v->id;
}

static void parse_damper(ctx *c, const cJSON *o, const at *ptr, dp_damper *d)
{
    static const variant laws[] = {
        { "none", DP_DAMPER_NONE, { { NULL } }, { NULL } },
        { "linear", DP_DAMPER_LINEAR, { NUM(dp_damper, c, NONNEG, 1) }, { NULL } },
        { "coulomb", DP_DAMPER_COULOMB, { NUM(dp_damper, phi0, NONNEG, 1) }, { NULL } },
        { "bingham", DP_DAMPER_BINGHAM, { NUM(dp_damper, tau, NONNEG, 1), NUM(dp_damper, c, NONNEG, 1) },
          { NULL } },
        { "generalized-coulomb", DP_DAMPER_GENERALIZED_COULOMB,
          { NUM(dp_damper, phi0, NONNEG, 1), NUM(dp_damper, phi1, NONNEG, 1) }, { NULL } },
        { "graph", DP_DAMPER_GRAPH, { { NULL } }, { "points", NULL } },
    };
    static const char *const common[] = { "relaxation", "belt_velocity", NULL };
    size_t before = c->nerr;
    const variant *v = parse_tagged(c, o, ptr, "law", -1, laws, 6, common, d);
    if (v == NULL)
        return;
    d->law = (dp_damper_law)v->id;
    char a[32], b[32];
    at p = { ptr, "phi1", 0 };
    if (d->law == DP_DAMPER_GENERALIZED_COULOMB && c->nerr == before && d->phi1 < d->phi0) {
        fail(c, &p, "must be >= phi0 (%s), got %s", num_text(d->phi0, a), num_text(d->phi1, b));
    }
    if (d->law == DP_DAMPER_GRAPH)
        parse_graph(c, o, ptr, "v", &d->graph);
    get_num(c, o, ptr, "belt_velocity", &ANY, 0, 0, &d->belt_velocity);
    const cJSON *r = member(c, o, ptr, "relaxation", NULL, &p);
    if (r != NULL)
        parse_relaxation(c, r, &p, &d->relaxation);
}

static void parse_forcing(ctx *c, const cJSON *o, const at *ptr, dp_forcing *f, int depth);

/* o["terms"]: 1..DP_FORCING_MAX_TERMS forcings one level deeper, into a calloc'd f->terms. */
static void parse_terms(ctx *c, const cJSON *o, const at *ptr, dp_forcing *f, int depth)
{
    char what[64];
    snprintf(what, sizeof what, "an array of 1..%d forcings", DP_FORCING_MAX_TERMS);
    at pp, *p = &pp;
    const cJSON *a = member(c, o, ptr, "terms", what, p);
    if (a == NULL)
        return;
    if (depth >= DP_FORCING_MAX_DEPTH) {
        fail(c, p, "sums nest at most %d deep", DP_FORCING_MAX_DEPTH);
        return;
    }
    int n = cJSON_IsArray(a) ? cJSON_GetArraySize(a) : 0;
    if (!cJSON_IsArray(a) || n < 1 || n > DP_FORCING_MAX_TERMS) {
        if (cJSON_IsArray(a))
            fail(c, p, "must be %s, got %d", what, n);
        else
            fail(c, p, "must be %s, got %s", what, type_name(a));
        return;
    }
    f->terms = calloc((size_t)n, sizeof *f->terms);
    if (f->terms == NULL) {
        c->nomem = 1;
        return;
    }
    f->nterms = (size_t)n;
    size_t i = 0;
    for (const cJSON *el = a->child; el; el = el->next, i++) {
        at q = { p, NULL, i };
        parse_forcing(c, el, &q, &f->terms[i], depth + 1);
    }
}

static void parse_forcing_with(ctx *c, const cJSON *o, const at *ptr, dp_forcing *f, int depth,
                               const char *const *common);

/* A forcing at nesting `depth` (the model's own is 1). */
static void parse_forcing(ctx *c, const cJSON *o, const at *ptr, dp_forcing *f, int depth)
{
    parse_forcing_with(c, o, ptr, f, depth, NULL);
}

/* A forcing whose object may also hold the members `common` (a network load's "node"), read by its caller. */
static void parse_forcing_with(ctx *c, const cJSON *o, const at *ptr, dp_forcing *f, int depth,
                               const char *const *common)
{
    static const variant kinds[] = {
        { "constant", DP_FORCING_CONSTANT, { NUM(dp_forcing, value, ANY, 1) }, { NULL } },
        { "harmonic", DP_FORCING_HARMONIC,
          { NUM(dp_forcing, amplitude, ANY, 1), NUM(dp_forcing, omega, ANY, 1), NUM(dp_forcing, phase, ANY, 0) },
          { NULL } },
        { "table", DP_FORCING_TABLE, { { NULL } }, { "points", NULL } },
        { "sum", DP_FORCING_SUM, { { NULL } }, { "terms", NULL } },
    };
    const variant *v = parse_tagged(c, o, ptr, "kind", -1, kinds, 4, common, f);
    if (v == NULL)
        return;
    f->kind = (dp_forcing_kind)v->id;
    if (f->kind == DP_FORCING_SUM)
        parse_terms(c, o, ptr, f, depth);
    if (f->kind != DP_FORCING_TABLE)
        return;
    size_t n = 0;
    double *t = NULL, *F = NULL;
    int ok = parse_points(c, o, ptr, "t", 1, &n, &t, &F);
    f->t = t;          /* owned by f from here on, freed by dp_forcing_clear */
    f->F = F;
    f->n = ok ? n : 0;
}

static const range RESTITUTION = { 0, 1, 0, " in [0, 1]" };

/* {"distance": d, "restitution": e} (rigid, e default 0) or {"distance": d, "compliance": k} (compliant). */
static void parse_contact(ctx *c, const cJSON *o, const at *ptr, dp_contact *ct)
{
    static const char *const keys[] = { "distance", "restitution", "compliance", NULL };
    if (!want_object(c, o, ptr))
        return;
    check_keys(c, o, ptr, keys, NULL, NULL);
    get_num(c, o, ptr, "distance", &ANY, 1, 0, &ct->distance);
    int rigid = get_num(c, o, ptr, "restitution", &RESTITUTION, 0, 0, &ct->restitution);
    int soft = get_num(c, o, ptr, "compliance", &POSITIVE, 0, 0, &ct->compliance);
    if (rigid && soft) {
        at p = { ptr, "compliance", 0 };
        fail(c, &p, "a contact is rigid (\"restitution\") or compliant (\"compliance\"), not both: a compliant "
                    "contact rebounds through its spring");
    }
}

static void parse_model(ctx *c, const cJSON *o, const at *ptr, dp_model *m)
{
    static const char *const keys[] = { "mass", "spring", "damper", "forcing", "contact", NULL };
    at p;
    if (!want_object(c, o, ptr))
        return;
    check_keys(c, o, ptr, keys, NULL, NULL);
    get_num(c, o, ptr, "mass", &POSITIVE, 1, 0, &m->mass);
    const cJSON *ct = member(c, o, ptr, "contact", NULL, &p);
    if (ct != NULL)
        m->has_contact = 1, parse_contact(c, ct, &p, &m->contact);
    const cJSON *v = member(c, o, ptr, "spring", "an object with a \"law\"", &p);
    if (v != NULL)
        parse_spring(c, v, &p, &m->spring);
    if ((v = member(c, o, ptr, "damper", "an object with a \"law\"", &p)) != NULL)
        parse_damper(c, v, &p, &m->damper);
    if ((v = member(c, o, ptr, "forcing", NULL, &p)) != NULL)
        parse_forcing(c, v, &p, &m->forcing, 1);
}

static void parse_initial(ctx *c, const cJSON *o, const at *ptr, dp_spec *s)
{
    static const char *const keys[] = { "x", "v", NULL };
    if (!want_object(c, o, ptr))
        return;
    check_keys(c, o, ptr, keys, NULL, NULL);
    get_num(c, o, ptr, "x", &ANY, 0, 0, &s->x0);
    get_num(c, o, ptr, "v", &ANY, 0, 0, &s->v0);
}

/* The regularized solver's "n" (scheme PC) or "k" (scheme PI): a number > 0 or, for a convergence study, a
 * strictly increasing array of 1..DP_SPEC_MAX_NLIST of them. The other scheme's key is an error. */
static void parse_nlist(ctx *c, const cJSON *o, const at *ptr, dp_solver_spec *s)
{
    int pi = s->scheme == DP_SCHEME_PI;
    const char *key = pi ? "k" : "n", *other = pi ? "n" : "k";
    char what[96], a[32], b[32];
    at pp, *p = &pp;
    if (member(c, o, ptr, other, NULL, p) != NULL)
        fail(c, p, "\"%s\" belongs to scheme %s; scheme %s takes \"%s\"", other, pi ? "PC" : "PI",
             pi ? "PI" : "PC", key);
    const cJSON *v = member(c, o, ptr, key, NULL, p);
    double x;
    if (v == NULL)
        return;
    if (cJSON_IsNumber(v)) {
        if (check_num(c, v, p, &POSITIVE, 0, &x))
            s->n_list[0] = x, s->n_count = 1;
        return;
    }
    int n = cJSON_IsArray(v) ? cJSON_GetArraySize(v) : 0;
    snprintf(what, sizeof what, "a finite number > 0 or an array of 1..%d of them", DP_SPEC_MAX_NLIST);
    if (!cJSON_IsArray(v) || n < 1 || n > DP_SPEC_MAX_NLIST) {
        if (cJSON_IsArray(v))
            fail(c, p, "must be %s, got %d elements", what, n);
        else
            fail(c, p, "must be %s, got %s", what, type_name(v));
        return;
    }
    size_t before = c->nerr, i = 0;
    for (const cJSON *el = v->child; el; el = el->next, i++) {
        const at q = { p, NULL, i };
        if (check_num(c, el, &q, &POSITIVE, 0, &s->n_list[i]) && i > 0 && !(s->n_list[i] > s->n_list[i - 1]))
            fail(c, &q, "must be strictly increasing: %s after %s", num_text(s->n_list[i], a),
                 num_text(s->n_list[i - 1], b));
    }
    if (c->nerr == before)
        s->n_count = (size_t)n;
}

static void parse_solver(ctx *c, const cJSON *o, const at *ptr, dp_solver_spec *s)
{
    static const variant kinds[] = {
        { "stick-slip", DP_SOLVER_STICK_SLIP,
          { NUM(dp_solver_spec, dt, POSITIVE, 0), NUM(dp_solver_spec, t_end, POSITIVE, 0),
            NUM(dp_solver_spec, theta, THETA, 0), NUM(dp_solver_spec, eps, POSITIVE, 0) },
          { "variant", "Z", "events", "branch", NULL } },
        { "analytic", DP_SOLVER_ANALYTIC,
          { NUM(dp_solver_spec, t_end, POSITIVE, 0), NUM(dp_solver_spec, dt, POSITIVE, 0) }, { NULL } },
        { "regularized", DP_SOLVER_REGULARIZED,
          { NUM(dp_solver_spec, t_end, POSITIVE, 0), NUM(dp_solver_spec, dt, POSITIVE, 0),
            NUM(dp_solver_spec, rtol, NONNEG, 0), NUM(dp_solver_spec, atol, NONNEG, 0) },
          { "scheme", "n", "k", "stepper", NULL } },
        { "newmark", DP_SOLVER_NEWMARK,
          { NUM(dp_solver_spec, dt, POSITIVE, 0), NUM(dp_solver_spec, t_end, POSITIVE, 0),
            NUM(dp_solver_spec, beta, BETA, 0), NUM(dp_solver_spec, gamma, GAMMA, 0) }, { NULL } },
        { "right-hand", DP_SOLVER_RIGHT_HAND,
          { NUM(dp_solver_spec, t_end, POSITIVE, 0), NUM(dp_solver_spec, dt, POSITIVE, 0),
            NUM(dp_solver_spec, rtol, POSITIVE, 0), NUM(dp_solver_spec, atol, POSITIVE, 0) }, { NULL } },
    };
    static const char *const variants[] = { "exact", "thesis", NULL };
    static const char *const events[] = { "locate", "none", NULL };
    static const char *const branches[] = { "rest", "motion", NULL };
    static const char *const schemes[] = { "PC", "PI", NULL };
    static const char *const steppers[] = { "msbdf", "rk4imp", "bsimp", "rkf45", "rkck", "rk8pd", NULL };
    int def = s->kind == DP_SOLVER_RIGHT_HAND ? DP_SOLVER_RIGHT_HAND : DP_SOLVER_STICK_SLIP;
    const variant *v = parse_tagged(c, o, ptr, "kind", def, kinds, 5, NULL, s);
    if (v == NULL)
        return;
    s->kind = (dp_solver_kind)v->id;
    int i;
    if (s->kind == DP_SOLVER_REGULARIZED) {
        if ((i = get_enum(c, o, ptr, "scheme", schemes, (int)s->scheme)) >= 0)
            s->scheme = (dp_scheme)i;
        if ((i = get_enum(c, o, ptr, "stepper", steppers, (int)s->stepper)) >= 0)
            s->stepper = (dp_stepper)i;
        parse_nlist(c, o, ptr, s);
    }
    if (s->kind != DP_SOLVER_STICK_SLIP)
        return;
    i = get_enum(c, o, ptr, "variant", variants, (int)s->variant);
    if (i >= 0)
        s->variant = (dp_variant)i;
    if ((i = get_enum(c, o, ptr, "events", events, (int)s->events)) >= 0)
        s->events = (dp_events_mode)i;
    if ((i = get_enum(c, o, ptr, "branch", branches, (int)s->branch)) >= 0)
        s->branch = (dp_branch)i;
    double z;
    if (get_num(c, o, ptr, "Z", &Z_RANGE, 0, 1, &z))
        s->Z = (int)z;
}

/* "max_samples": N, a sample budget for clients that draw rather than store (the browser page asks for about
 * its canvas width): every = ceil(steps / (N - 1)), so floor(steps/every) + 1 samples plus the final one when
 * every does not divide steps come to at most N. Needs the solver parsed first (dt, t_end). */
static const range MAX_SAMPLES = { 2, 9007199254740992.0, 0, " >= 2 (at most 2^53)" };

static void sample_budget(ctx *c, const cJSON *o, const at *ptr, const dp_spec *s, dp_output_spec *out)
{
    double budget;
    if (!get_num(c, o, ptr, "max_samples", &MAX_SAMPLES, 0, 1, &budget))
        return;
    if (cJSON_GetObjectItemCaseSensitive(o, "every") != NULL) {
        at p = { ptr, "max_samples", 0 };
        fail(c, &p, "give either every or max_samples, not both");
        return;
    }
    if (s->solver.dt > 0 && isfinite(s->solver.t_end) && s->solver.t_end > 0) {
        double every = ceil(dp_spec_steps(s) / (budget - 1));
        out->every = every < 1 ? 1 : every > 9007199254740992.0 ? 9007199254740992L : (long)every;
    }
}

#include "network_json.inc"
#include "lcs_json.inc"
#include "right_hand_json.inc"

static void parse_output(ctx *c, const cJSON *o, const at *ptr, dp_spec *s)
{
    static const char *const keys[] = { "every", "max_samples", "samples", "events", "nodes", "elements", NULL };
    dp_output_spec *out = &s->output;
    if (!want_object(c, o, ptr))
        return;
    check_keys(c, o, ptr, keys, NULL, NULL);
    double every;
    if (get_num(c, o, ptr, "every", &EVERY, 0, 1, &every))
        out->every = (long)every;
    sample_budget(c, o, ptr, s, out);
    get_bool(c, o, ptr, "samples", &out->samples);
    get_bool(c, o, ptr, "events", &out->events);
    parse_columns(c, o, ptr, "nodes", "a node", s, s->net ? s->net->n : 0, &out->nodes, &out->nnodes);
    parse_columns(c, o, ptr, "elements", "an element", s, s->net ? s->net->nel : 0, &out->elements,
                  &out->nelements);
}

/* A one-mass document with a contact is the network it is: one node of its mass, one element [ground, 0]
 * with its spring, damper and contact, its forcing on node 0 (the laws are moved, not copied). */
static int one_mass_as_network(dp_spec *s)
{
    dp_network *net = calloc(1, sizeof *net);
    if (net == NULL)
        return DP_ENOMEM;
    s->net = net;
    net->n = 1, net->nel = 1, net->one_mass_doc = 1;
    net->mass = malloc(sizeof *net->mass);
    net->el = calloc(1, sizeof *net->el);
    s->x0v = malloc(sizeof *s->x0v), s->v0v = malloc(sizeof *s->v0v);
    int forced = s->model.forcing.kind != DP_FORCING_NONE;
    net->force = forced ? calloc(1, sizeof *net->force) : NULL;
    if (!net->mass || !net->el || !s->x0v || !s->v0v || (forced && !net->force))
        return DP_ENOMEM;
    net->mass[0] = s->model.mass, s->x0v[0] = s->x0, s->v0v[0] = s->v0;
    net->el[0] = (dp_element){ .a = DP_GROUND, .b = 0, .has_spring = 1, .has_damper = 1, .has_contact = 1,
                               .spring = s->model.spring, .damper = s->model.damper, .contact = s->model.contact };
    if (forced)
        net->force[0] = (dp_node_forcing){ .node = 0, .f = s->model.forcing }, net->nforce = 1;
    memset(&s->model.spring, 0, sizeof s->model.spring);
    memset(&s->model.damper, 0, sizeof s->model.damper);
    memset(&s->model.forcing, 0, sizeof s->model.forcing);
    return DP_OK;
}

/* The whole document o (an object: body.c); its own keys are not checked again when keys_checked. */
static void parse_root(ctx *c, const cJSON *o, dp_spec *s, int keys_checked)
{
    static const char *const keys[] = { "model", "initial", "solver", "output", NULL };
    at p;
    if (!keys_checked)
        check_keys(c, o, NULL, keys, NULL, NULL);
    const cJSON *v = member(c, o, NULL, "model", "an object with mass, spring and damper", &p);
    int rh = v != NULL && !is_network(v) && is_right_hand(v); /* its own initial state, even if the model is bad */
    if (v != NULL && is_network(v))
        parse_network(c, v, &p, s);
    else if (v != NULL && is_lcs(v))
        parse_lcs(c, v, &p, s);
    else if (rh)
        parse_right_hand(c, v, &p, s);
    else if (v != NULL)
        parse_model(c, v, &p, &s->model);
    if ((v = member(c, o, NULL, "initial", NULL, &p)) != NULL && s->lcs != NULL)
        parse_lcs_initial(c, v, &p, s);
    else if (v != NULL && is_lcs(cJSON_GetObjectItemCaseSensitive(o, "model")))
        ; /* the LCS model was invalid: its errors are reported, its initial state cannot be sized */
    else if (v != NULL && rh)
        parse_right_hand_initial(c, v, &p, s);
    else if (v != NULL && s->net == NULL)
        parse_initial(c, v, &p, s);
    else if (v != NULL && s->net->n > 0)
        parse_network_initial(c, v, &p, s);
    if ((v = member(c, o, NULL, "solver", NULL, &p)) != NULL)
        parse_solver(c, v, &p, &s->solver);
    if ((v = member(c, o, NULL, "output", NULL, &p)) != NULL)
        parse_output(c, v, &p, s);
    if (s->net == NULL && s->model.has_contact && !c->nerr && !c->nomem && one_mass_as_network(s) != DP_OK)
        c->nomem = 1;
}

/* ---- syntax ----------------------------------------------------------------------------------------- */




/* The document's tree, or NULL with the status in *s (body.c); the errors the reader found in a tree (a NUL
 * in a string, a repeated key) are counted, so the walk goes on to report the rest and the parse fails. */
static cJSON *read_document(ctx *c, const char *text, size_t len, int *s)
{
    size_t before = c->errs->n + c->errs->dropped;
    cJSON *root;
    *s = dp_body_read(text, len, c->errs, &root);
    c->nerr += c->errs->n + c->errs->dropped - before;
    return root;
}

/* A spec from the document's tree (read by read_document into c), then prepared and checked. */
static int spec_from_tree(ctx *c, const cJSON *root, double max_steps, dp_spec *spec, int keys_checked)
{
    dp_errors *errs = c->errs;
    parse_root(c, root, spec, keys_checked);
    if (c->nomem)
        return DP_ENOMEM;
    if (c->nerr > 0)
        return DP_EINVAL;
    int s = spec->rh ? DP_OK : spec->net ? dp_network_prepare(spec->net) : spec->lcs ? DP_OK : dp_model_prepare(&spec->model);
    if (s == DP_ENOMEM)
        return s;
    if (s != DP_OK) {
        const at model = { NULL, "model", 0 };
        fail(c, &model, "the model's graphs could not be built (%s)", dp_strerror(s));
        return DP_EINVAL;
    }
    /* DP_SPEC_MAX_STEPS is a hard ceiling; front ends may only lower it. */
    if (!(max_steps > 0) || max_steps > DP_SPEC_MAX_STEPS)
        max_steps = DP_SPEC_MAX_STEPS;
    return dp_spec_check(spec, max_steps, errs);
}

int dp_spec_parse(const char *text, size_t len, double max_steps, dp_spec *spec, dp_errors *errs)
{
    ctx c = { errs, 0, 0 };
    int read;
    cJSON *root = read_document(&c, text, len, &read);
    if (root == NULL)
        return read;
    int s = spec_from_tree(&c, root, max_steps, spec, 0);
    cJSON_Delete(root);
    return s;
}

/* The "model" member of a document that may be a whole simulation spec: only its model is read. */
static const cJSON *model_member(ctx *c, const cJSON *root, at *p)
{
    static const char *const keys[] = { "model", "initial", "solver", "output", NULL };
    check_keys(c, root, NULL, keys, NULL, NULL);
    return member(c, root, NULL, "model", "an object with mass, spring and damper", p);
}

/* A one-mass model read leniently (non-monotone user graphs and gaps kept raw, for analysis only). */
static int lenient_model(ctx *c, const cJSON *v, const at *p, dp_model *model)
{
    if (v != NULL)
        parse_model(c, v, p, model);
    if (c->nomem)
        return DP_ENOMEM;
    if (c->nerr > 0)
        return DP_EINVAL;
    return dp_model_prepare(model);
}

int dp_model_parse_lenient(const char *text, size_t len, dp_model *model, dp_errors *errs)
{
    ctx c = { errs, 0, 0, 1 };
    at p;
    int read;
    cJSON *root = read_document(&c, text, len, &read);
    if (root == NULL)
        return read;
    int s = lenient_model(&c, model_member(&c, root, &p), &p, model);
    cJSON_Delete(root);
    return s;
}

/* A network's report: parsed as strictly as a run's (its laws are graphs the solver could take), then its
 * checks (dp_network_check). */
static int network_report(ctx *c, const cJSON *root, const cJSON *v, const at *p, dp_wp_report *rep)
{
    dp_spec spec;
    dp_spec_init(&spec);
    c->lenient = 0;
    parse_network(c, v, p, &spec);
    /* the initial state, where given, is checked against the laws' domains and the contacts (else 0) */
    at pi = { NULL, "initial", 0 };
    const cJSON *init = cJSON_GetObjectItemCaseSensitive(root, "initial");
    if (init != NULL && !c->nerr && spec.net != NULL)
        parse_network_initial(c, init, &pi, &spec);
    int s = c->nomem ? DP_ENOMEM : c->nerr ? DP_EINVAL : dp_network_prepare(spec.net);
    if (s == DP_OK) {
        size_t before = c->errs->n + c->errs->dropped;
        dp_network_check(&spec, c->errs);
        s = c->errs->n + c->errs->dropped > before ? DP_EINVAL : DP_OK;
    }
    if (s == DP_OK)
        dp_network_wellposedness(spec.net, rep);
    dp_spec_clear(&spec);
    return s;
}

int dp_wellposedness_parse(const char *text, size_t len, dp_wp_report *rep, dp_errors *errs)
{
    ctx c = { errs, 0, 0, 1 };
    at p;
    int read;
    cJSON *root = read_document(&c, text, len, &read);
    if (root == NULL)
        return read;
    const cJSON *v = model_member(&c, root, &p);
    int s;
    if (v != NULL && is_right_hand(v)) {
        s = right_hand_wellposedness(&c, root, v, &p, rep);
    } else if (v != NULL && is_lcs(v)) {   /* an LCS: checked as a run's spec, its theory from the step's matrix */
        dp_spec spec;
        dp_spec_init(&spec);
        c.lenient = 0;
        s = spec_from_tree(&c, root, 0, &spec, 1);
        s = s == DP_OK ? dp_lcs_wellposedness(&spec, rep) : s;
        dp_spec_clear(&spec);
    } else if (v != NULL && is_network(v)) {
        s = network_report(&c, root, v, &p, rep);
    } else if (v != NULL && cJSON_GetObjectItemCaseSensitive(v, "contact") != NULL) {
        dp_spec spec;   /* a one-mass document with a contact: the one-node network it runs as */
        dp_spec_init(&spec);
        c.lenient = 0;
        s = spec_from_tree(&c, root, 0, &spec, 1);
        if (s == DP_OK)
            dp_network_wellposedness(spec.net, rep);
        dp_spec_clear(&spec);
    } else {
        dp_model m = { 0 };
        if ((s = lenient_model(&c, v, &p, &m)) == DP_OK)
            dp_wellposedness(&m, rep);
        dp_model_clear(&m);
    }
    cJSON_Delete(root);
    return s;
}
