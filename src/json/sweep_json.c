/* src/json/sweep_json.c - the sweep document (sweep_json.h, docs/sweep.md): its parse through the one walker,
 * so a bad member is named by its JSON Pointer into the sweep document as on every route, and each run's
 * lone simulate document, the base with the run's values put at the vary pointers (RFC 6901).
 *
 * A run is its substituted base printed and parsed by dp_spec_parse, exactly as `dashpot simulate` and
 * POST /v1/simulate read it (cJSON prints every number so that it reads back to the same double), so a run is
 * the same computation as the lone run of that document, and its errors point into the base.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "dashpot/json.h"
#include "dashpot/sweep_json.h"
#include "walk.h"

struct dp_sweep_doc {
    cJSON *root;
    const cJSON *base;
    dp_sweep_grid grid;
    dp_sweep_plan plan;
    size_t shard_i, shard_n;
    size_t *only, nonly;   /* "runs": the grid indices to run, in order (NULL: all of the shard) */
    size_t *order, norder; /* the indices this document runs */
};

static const range COUNT = { 1, DP_SWEEP_MAX_RUNS, 0, " in [1, 10000]" };
static const range SECTION_COUNT = { 1, DP_SWEEP_MAX_SECTION, 0, " in [1, 1000]" };
static const range INDEX = { 0, 1e9, 0, " >= 0" };

/* ---- JSON Pointers into the base ---- */

/* The next reference token of pointer p (after its '/') unescaped into tok; returns the rest, or NULL when
 * the token is malformed (a '~' not followed by 0 or 1) or too long. */
static const char *token(const char *p, char *tok, size_t cap)
{
    size_t n = 0;
    for (p++; *p && *p != '/'; p++) {
        char c = *p;
        if (c == '~') {
            if (p[1] != '0' && p[1] != '1')
                return NULL;
            c = *++p == '0' ? '~' : '/';
        }
        if (n + 1 >= cap)
            return NULL;
        tok[n++] = c;
    }
    tok[n] = '\0';
    return p;
}

/* An array index token: digits, no leading zero (RFC 6901 section 4); -1 otherwise. */
static long array_index(const char *tok)
{
    if (!*tok || (tok[0] == '0' && tok[1]) || strlen(tok) > 9)
        return -1;
    for (const char *c = tok; *c; c++)
        if (*c < '0' || *c > '9')
            return -1;
    return atol(tok);
}

/* Resolves pointer p in doc to the parent container of its target and the target's token: 0, or -1 with a
 * reason. The target itself may be missing from an object (it is added, as RFC 6902's "add"). */
static int resolve(cJSON *doc, const char *p, cJSON **parent, char *last, size_t cap, const char **why)
{
    if (p[0] != '/') {
        *why = "must be a JSON Pointer into the base document, starting with \"/\"";
        return -1;
    }
    cJSON *cur = doc;
    while (1) {
        const char *rest = token(p, last, cap);
        if (rest == NULL) {
            *why = "is not a JSON Pointer (RFC 6901): \"~\" must be followed by 0 or 1";
            return -1;
        }
        if (*rest == '\0') {
            *parent = cur;
            if (cJSON_IsObject(cur))
                return 0;
            long i = array_index(last);
            if (cJSON_IsArray(cur) && i >= 0 && i < cJSON_GetArraySize(cur))
                return 0;
            *why = cJSON_IsArray(cur) ? "names no member of the base document (an array index past its end)"
                                      : "names no member of the base document (its parent is no object or array)";
            return -1;
        }
        cJSON *next = NULL;
        if (cJSON_IsObject(cur))
            next = cJSON_GetObjectItemCaseSensitive(cur, last);
        else if (cJSON_IsArray(cur) && array_index(last) >= 0)
            next = cJSON_GetArrayItem(cur, (int)array_index(last));
        if (next == NULL) {
            *why = "names no member of the base document (a parent along the way is missing)";
            return -1;
        }
        cur = next;
        p = rest;
    }
}

/* Puts x at the resolved place (replacing or adding). 0, or -1 when out of memory. */
static int put_value(cJSON *parent, const char *last, double x)
{
    cJSON *num = cJSON_CreateNumber(x);
    if (num == NULL)
        return -1;
    if (cJSON_IsArray(parent))
        return cJSON_ReplaceItemInArray(parent, (int)array_index(last), num) ? 0 : -1;
    if (cJSON_GetObjectItemCaseSensitive(parent, last) != NULL)
        return cJSON_ReplaceItemInObjectCaseSensitive(parent, last, num) ? 0 : -1;
    return cJSON_AddItemToObject(parent, last, num) ? 0 : (cJSON_Delete(num), -1);
}

/* ---- the document ---- */

static void parse_values(ctx *c, const cJSON *v, const at *p, dp_sweep_axis *a)
{
    size_t n = jw_array_size(c, v, p, DP_SWEEP_MAX_RUNS, "an array of 1 to 10000 finite numbers");
    if (n == 0 || (a->values = malloc(n * sizeof *a->values)) == NULL) {
        c->nomem |= n > 0;
        return;
    }
    a->n = n;
    size_t i = 0;
    for (const cJSON *e = v->child; e; e = e->next, i++) {
        at q = { p, NULL, i };
        jw_check_num(c, e, &q, &ANY, 0, &a->values[i]);
    }
}

static void parse_range(ctx *c, const cJSON *o, const at *p, dp_sweep_axis *a)
{
    static const char *const scales[] = { "linear", "log", NULL };
    double from = 0, to = 0, count = 0;
    size_t before = c->nerr;
    jw_get_num(c, o, p, "from", &ANY, 1, 0, &from);
    jw_get_num(c, o, p, "to", &ANY, 1, 0, &to);
    jw_get_num(c, o, p, "count", &COUNT, 1, 1, &count);
    int log_scale = jw_get_enum(c, o, p, "scale", scales, 0);
    if (log_scale == 1 && c->nerr == before && !(from > 0 && to > 0)) {
        at q = { p, from > 0 ? "to" : "from", 0 };
        jw_fail(c, &q, "must be > 0 on a log scale");
    }
    if (c->nerr == before && log_scale >= 0 && dp_sweep_axis_fill(a, from, to, (size_t)count, log_scale) != DP_OK)
        c->nomem = 1;
}

static void parse_axis(ctx *c, const cJSON *o, const at *p, cJSON *base, dp_sweep_axis *a)
{
    static const char *const keys[] = { "pointer", "values", "from", "to", "count", "scale", NULL };
    if (!jw_want_object(c, o, p))
        return;
    jw_check_keys(c, o, p, keys, NULL, NULL);
    at q;
    const cJSON *ptr = jw_member(c, o, p, "pointer", "a JSON Pointer into the base, e.g. \"/model/mass\"", &q);
    if (ptr != NULL && !cJSON_IsString(ptr)) {
        jw_fail(c, &q, "must be a string (a JSON Pointer), got %s", jb_type_name(ptr));
    } else if (ptr != NULL) {
        cJSON *parent;
        char last[DP_POINTER_MAX];
        const char *why;
        if (strlen(ptr->valuestring) >= DP_POINTER_MAX)
            jw_fail(c, &q, "is longer than %d bytes", DP_POINTER_MAX - 1);
        else if (resolve(base, ptr->valuestring, &parent, last, sizeof last, &why) != 0)
            jw_fail(c, &q, "%s", why);
        else if (cJSON_IsArray(parent) ? !cJSON_IsNumber(cJSON_GetArrayItem(parent, (int)array_index(last)))
                                       : cJSON_GetObjectItemCaseSensitive(parent, last) != NULL &&
                                             !cJSON_IsNumber(cJSON_GetObjectItemCaseSensitive(parent, last)))
            jw_fail(c, &q, "names a member of the base that is not a number; a sweep varies numbers");
        else
            snprintf(a->pointer, sizeof a->pointer, "%s", ptr->valuestring);
    }
    const cJSON *values = jw_member(c, o, p, "values", NULL, &q);
    int ranged = cJSON_GetObjectItemCaseSensitive(o, "from") || cJSON_GetObjectItemCaseSensitive(o, "to") ||
                 cJSON_GetObjectItemCaseSensitive(o, "count");
    if (values != NULL && ranged)
        jw_fail(c, p, "takes either \"values\" or \"from\", \"to\" and \"count\", not both");
    else if (values != NULL)
        parse_values(c, values, &q, a);
    else if (ranged)
        parse_range(c, o, p, a);
    else
        jw_fail(c, p, "needs \"values\" (an array of numbers) or \"from\", \"to\" and \"count\"");
}

static void parse_vary(ctx *c, const cJSON *v, const at *p, cJSON *base, dp_sweep_grid *g)
{
    size_t n = jw_array_size(c, v, p, DP_SWEEP_MAX_AXES, "an array of one or two parameters");
    size_t i = 0;
    for (const cJSON *e = n ? v->child : NULL; e; e = e->next, i++) {
        at q = { p, NULL, i };
        parse_axis(c, e, &q, base, &g->axis[i]);
        g->naxes = i + 1;
    }
    if (n == 2 && g->axis[0].pointer[0] && strcmp(g->axis[0].pointer, g->axis[1].pointer) == 0) {
        at q1 = { p, NULL, 1 }, q = { &q1, "pointer", 0 };
        jw_fail(c, &q, "is the same parameter as /vary/0/pointer");
    }
    double runs = 1;
    for (size_t k = 0; k < g->naxes; k++)
        runs *= (double)g->axis[k].n;
    if (n > 0 && runs > DP_SWEEP_MAX_RUNS)
        jw_fail(c, p, "makes a grid of %.0f runs; a sweep has at most %d", runs, DP_SWEEP_MAX_RUNS);
}

static void parse_section(ctx *c, const cJSON *o, const at *p, dp_sweep_plan *plan)
{
    static const char *const keys[] = { "period", "event", "count", NULL };
    static const char *const events[] = { "stick", "slip", "yield", "unload", "impact", NULL };
    if (!jw_want_object(c, o, p))
        return;
    jw_check_keys(c, o, p, keys, NULL, NULL);
    double count = 100;
    jw_get_num(c, o, p, "count", &SECTION_COUNT, 0, 1, &count);
    plan->section_count = (size_t)count;
    int has_period = jw_get_num(c, o, p, "period", &POSITIVE, 0, 0, &plan->section_period);
    int ev = cJSON_GetObjectItemCaseSensitive(o, "event") ? jw_get_enum(c, o, p, "event", events, 0) : -1;
    if (has_period && ev >= 0)
        jw_fail(c, p, "takes either \"period\" or \"event\", not both");
    else if (has_period)
        plan->section = DP_SECTION_PERIOD;
    else if (ev >= 0)
        plan->section = DP_SECTION_EVENT, plan->section_event = (dp_event_kind)(ev + 1);
    else if (!cJSON_GetObjectItemCaseSensitive(o, "period") && !cJSON_GetObjectItemCaseSensitive(o, "event"))
        jw_fail(c, p, "needs \"period\" (a finite number > 0) or \"event\" (stick, slip, yield, unload, impact)");
}

static void parse_features(ctx *c, const cJSON *v, const at *p, unsigned *bits)
{
    size_t n = jw_array_size(c, v, p, 64, "an array of feature names");
    size_t i = 0;
    *bits = n ? 0 : *bits;
    for (const cJSON *e = n ? v->child : NULL; e; e = e->next, i++) {
        at q = { p, NULL, i };
        int f = cJSON_IsString(e) ? dp_feature_from_name(e->valuestring) : -1;
        if (f < 0)
            jw_fail(c, &q, "must be one of: x_max, x_min, v_max, v_min, amplitude, period, stick_fraction");
        else
            *bits |= 1u << f;
    }
}

static void parse_record(ctx *c, const cJSON *o, const at *p, dp_sweep_plan *plan)
{
    static const char *const keys[] = { "after", "features", "section", "node", "element", NULL };
    if (!jw_want_object(c, o, p))
        return;
    jw_check_keys(c, o, p, keys, NULL, NULL);
    jw_get_num(c, o, p, "after", &NONNEG, 0, 0, &plan->after);
    double node = 0, element = 0;
    jw_get_num(c, o, p, "node", &INDEX, 0, 1, &node);
    jw_get_num(c, o, p, "element", &INDEX, 0, 1, &element);
    plan->node = (size_t)node;
    plan->element = (size_t)element;
    at q;
    const cJSON *v = jw_member(c, o, p, "features", NULL, &q);
    if (v != NULL)
        parse_features(c, v, &q, &plan->features);
    if ((v = jw_member(c, o, p, "section", NULL, &q)) != NULL)
        parse_section(c, v, &q, plan);
}

static void parse_shard(ctx *c, const cJSON *o, const at *p, dp_sweep_doc *d)
{
    static const char *const keys[] = { "index", "count", NULL };
    if (!jw_want_object(c, o, p))
        return;
    jw_check_keys(c, o, p, keys, NULL, NULL);
    double i = 0, n = 1;
    jw_get_num(c, o, p, "count", &COUNT, 1, 1, &n);
    if (jw_get_num(c, o, p, "index", &INDEX, 1, 1, &i) && i >= n) {
        at q = { p, "index", 0 };
        jw_fail(c, &q, "must be < count (%.0f), got %.0f", n, i);
    }
    d->shard_i = (size_t)i;
    d->shard_n = (size_t)n;
}

static void parse_runs(ctx *c, const cJSON *v, const at *p, dp_sweep_doc *d, size_t runs)
{
    size_t n = jw_array_size(c, v, p, DP_SWEEP_MAX_RUNS, "an array of run indices");
    if (n == 0)
        return;
    unsigned char *seen = calloc(runs ? runs : 1, 1);
    d->only = malloc(n * sizeof *d->only);
    if (seen == NULL || d->only == NULL) {
        free(seen);
        c->nomem = 1;
        return;
    }
    size_t i = 0;
    for (const cJSON *e = v->child; e; e = e->next, i++) {
        at q = { p, NULL, i };
        double x = 0;
        if (!jw_check_num(c, e, &q, &INDEX, 1, &x))
            continue;
        if (x >= (double)runs)
            jw_fail(c, &q, "must be a run of the grid (< %zu), got %.0f", runs, x);
        else if (seen[(size_t)x]++)
            jw_fail(c, &q, "repeats run %.0f", x);
        else
            d->only[d->nonly++] = (size_t)x;
    }
    free(seen);
}

/* The indices this document runs: "runs" (in its order), else the grid's in order, each in the shard. */
static int set_order(dp_sweep_doc *d)
{
    size_t runs = dp_sweep_grid_runs(&d->grid), n = d->only ? d->nonly : runs;
    free(d->order);
    d->norder = 0;
    d->order = malloc((n ? n : 1) * sizeof *d->order);
    if (d->order == NULL)
        return DP_ENOMEM;
    for (size_t k = 0; k < n; k++) {
        size_t index = d->only ? d->only[k] : k;
        if (dp_sweep_shard_owns(index, d->shard_i, d->shard_n))
            d->order[d->norder++] = index;
    }
    return DP_OK;
}

static void parse_root(ctx *c, cJSON *root, dp_sweep_doc *d)
{
    static const char *const keys[] = { "base", "vary", "record", "shard", "runs", NULL };
    jw_check_keys(c, root, NULL, keys, NULL, NULL);
    at p;
    cJSON *base = cJSON_GetObjectItemCaseSensitive(root, "base");
    jw_member(c, root, NULL, "base", "a simulate document", &p);
    if (base != NULL && !jw_want_object(c, base, &p))
        base = NULL;
    d->base = base;
    const cJSON *v = jw_member(c, root, NULL, "vary", "an array of one or two parameters", &p);
    if (v != NULL && base != NULL)
        parse_vary(c, v, &p, base, &d->grid);
    if ((v = jw_member(c, root, NULL, "record", NULL, &p)) != NULL)
        parse_record(c, v, &p, &d->plan);
    if ((v = jw_member(c, root, NULL, "shard", NULL, &p)) != NULL)
        parse_shard(c, v, &p, d);
    if ((v = jw_member(c, root, NULL, "runs", NULL, &p)) != NULL && c->nerr == 0)
        parse_runs(c, v, &p, d, dp_sweep_grid_runs(&d->grid));
    size_t per = d->plan.section != DP_SECTION_NONE ? d->plan.section_count : 0;
    if (c->nerr == 0 && (double)per * (double)dp_sweep_grid_runs(&d->grid) > DP_SWEEP_MAX_SECTION_TOTAL) {
        at q1 = { NULL, "record", 0 }, q2 = { &q1, "section", 0 }, q = { &q2, "count", 0 };
        jw_fail(c, &q, "asks for %zu section points per run of %zu runs; a sweep keeps at most %d in all", per,
                dp_sweep_grid_runs(&d->grid), DP_SWEEP_MAX_SECTION_TOTAL);
    }
}

int dp_sweep_parse(const char *text, size_t len, dp_sweep_doc **out, dp_errors *errs)
{
    *out = NULL;
    ctx c = { errs, 0, 0, 0 };
    int read;
    cJSON *root = jw_read(&c, text, len, &read);
    if (root == NULL)
        return read;
    dp_sweep_doc *d = calloc(1, sizeof *d);
    if (d == NULL) {
        cJSON_Delete(root);
        return DP_ENOMEM;
    }
    d->root = root;
    d->shard_n = 1;
    dp_sweep_plan_init(&d->plan);
    parse_root(&c, root, d);
    int s = c.nomem ? DP_ENOMEM : c.nerr || read != DP_OK ? DP_EINVAL : set_order(d);
    if (s != DP_OK) {
        dp_sweep_doc_free(d);
        return s;
    }
    *out = d;
    return DP_OK;
}

void dp_sweep_doc_free(dp_sweep_doc *d)
{
    if (d == NULL)
        return;
    cJSON_Delete(d->root);
    dp_sweep_grid_clear(&d->grid);
    free(d->only);
    free(d->order);
    free(d);
}

void dp_sweep_doc_set_shard(dp_sweep_doc *d, size_t i, size_t n)
{
    d->shard_i = i;
    d->shard_n = n ? n : 1;
    if (set_order(d) != DP_OK)
        d->norder = 0; /* out of memory: nothing to run, and the caller's count says so */
}

size_t dp_sweep_doc_count(const dp_sweep_doc *d)
{
    return d->norder;
}

size_t dp_sweep_doc_index(const dp_sweep_doc *d, size_t k)
{
    return d->order[k];
}

const dp_sweep_grid *dp_sweep_doc_grid(const dp_sweep_doc *d)
{
    return &d->grid;
}

const dp_sweep_plan *dp_sweep_doc_plan(const dp_sweep_doc *d)
{
    return &d->plan;
}

char *dp_sweep_doc_text(const dp_sweep_doc *d, size_t index)
{
    cJSON *copy = cJSON_Duplicate(d->base, 1);
    if (copy == NULL)
        return NULL;
    double values[DP_SWEEP_MAX_AXES];
    dp_sweep_grid_values(&d->grid, index, values);
    for (size_t k = 0; k < d->grid.naxes; k++) {
        cJSON *parent;
        char last[DP_POINTER_MAX];
        const char *why;
        /* resolved once when parsed; the copy has the same shape */
        if (resolve(copy, d->grid.axis[k].pointer, &parent, last, sizeof last, &why) != 0 ||
            put_value(parent, last, values[k]) != 0) {
            cJSON_Delete(copy);
            return NULL;
        }
    }
    char *text = cJSON_PrintUnformatted(copy);
    cJSON_Delete(copy);
    return text;
}

int dp_sweep_doc_spec(const dp_sweep_doc *d, size_t index, double max_steps, dp_spec *spec, dp_errors *errs)
{
    char *text = dp_sweep_doc_text(d, index);
    if (text == NULL)
        return DP_ENOMEM;
    int s = dp_spec_parse(text, strlen(text), max_steps, spec, errs);
    free(text);
    return s;
}
