/* src/json/laws_json.c - the laws and loads every model is built from, as a document gives them: springs,
 * dampers (with their relaxation), forcings, contacts, the point lists of graph laws and tables, and the
 * tagged-object table they are read by ({"law": name, params...}: js_parse_tagged and the `variant` rows).
 *
 * Its own file because the one-mass model (spec_json.c), a network's elements (network_json.c) and an LCS's
 * laws (lcs_json.c) all read these with this code, so a spring is accepted or refused in the same words
 * wherever it sits.
 */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "spec_parts.h"

static const range ABOVE_ONE = { 1, INFINITY, 1, " > 1" };

/* ---- tagged objects: {"law": name, params...} -------------------------------------------------------- */

/* Parses object o whose member `tag` picks one of `vs` (nv of them; `def` when absent, < 0: required).
 * Checks its keys (tag, the variant's params and extras, `common`), stores the params into `base` and
 * returns the variant, or NULL when o is no object or the tag is bad (its other members are then not
 * checked: which keys are valid depends on the tag). */
const variant *js_parse_tagged(ctx *c, const cJSON *o, const at *ptr, const char *tag, int def,
                                   const variant *vs, size_t nv, const char *const *common, void *base)
{
    const char *names[8], *keys[MAX_KEYS];
    size_t nk = 0;
    if (!jw_want_object(c, o, ptr))
        return NULL;
    for (size_t i = 0; i < nv; i++)
        names[i] = vs[i].name;
    names[nv] = NULL;
    int i = jw_get_enum(c, o, ptr, tag, names, def);
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
    jw_check_keys(c, o, ptr, keys, tag, v->name);
    for (const param *pa = v->params; pa->key; pa++)
        jw_get_num(c, o, ptr, pa->key, pa->r, pa->required, 0, (double *)((char *)base + pa->off));
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
            jw_fail(c, p, "must have exactly 2 elements [%s, F], got %d", yname, n);
        else
            jw_fail(c, p, "must be a pair [%s, F] of numbers, got %s", yname, jb_type_name(el));
        return 0;
    }
    at q0 = { p, NULL, 0 }, q1 = { p, NULL, 1 };
    int ok = jw_check_num(c, el->child, &q0, &ANY, 0, y);
    return jw_check_num(c, el->child->next, &q1, &ANY, 0, f) && ok;
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
            jw_fail(c, p, "t must be strictly increasing: %s after %s", jw_num_text(y[i], a), jw_num_text(y[i - 1], b));
        if (table)
            continue;
        if (y[i] < y[i - 1])
            jw_fail(c, p, "%s must be non-decreasing: %s after %s", yname, jw_num_text(y[i], a), jw_num_text(y[i - 1], b));
        if (f[i] < f[i - 1])
            jw_fail(c, p, "F must be non-decreasing: %s after %s", jw_num_text(f[i], a), jw_num_text(f[i - 1], b));
        if (y[i] == y[i - 1] && f[i] == f[i - 1])
            jw_fail(c, p, "repeats the previous point (%s, %s)", jw_num_text(y[i], a), jw_num_text(f[i], b));
    }
}

/* o["points"] into new arrays *y, *f of *n entries (caller frees them, also on failure). Returns 1 when
 * the list is valid. A table needs >= 1 point, a graph >= 2. */
int js_parse_points(ctx *c, const cJSON *o, const at *ptr, const char *yname, int table, size_t *n,
                        double **y, double **f)
{
    char what[96];
    size_t lo = table ? 1 : 2;
    at pp, *p = &pp;
    const cJSON *a = jw_member(c, o, ptr, "points", NULL, p);
    size_t count = cJSON_IsArray(a) ? (size_t)cJSON_GetArraySize(a) : 0;
    if (a == NULL || !cJSON_IsArray(a) || count < lo || count > DP_GRAPH_MAX_POINTS) {
        snprintf(what, sizeof what, "an array of %zu..%d [%s, F] pairs", lo, DP_GRAPH_MAX_POINTS, yname);
        if (a == NULL)
            jw_fail(c, p, "missing required key \"points\" (%s)", what);
        else if (cJSON_IsArray(a))
            jw_fail(c, p, "must be %s, got %zu", what, count);
        else
            jw_fail(c, p, "must be %s, got %s", what, jb_type_name(a));
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
        jw_fail(c, p, "a gap (null) must lie between two points");
    *n = count;
    return c->nerr == before;
}

/* o["points"] as a user graph into g (dp_graph_init_points copies the arrays). */
void js_parse_graph(ctx *c, const cJSON *o, const at *ptr, const char *yname, dp_graph *g)
{
    double *y = NULL, *f = NULL;
    size_t n = 0;
    if (js_parse_points(c, o, ptr, yname, 0, &n, &y, &f)) {
        int s = c->lenient ? dp_graph_init_raw(g, n, y, f) : dp_graph_init_points(g, n, y, f);
        const at p = { ptr, "points", 0 };
        if (s == DP_ENOMEM)
            c->nomem = 1;
        else if (s != DP_OK)
            jw_fail(c, &p, "does not make a monotone graph (non-decreasing %s and F, end segments not degenerate)",
                 yname);
    }
    free(y);
    free(f);
}

/* ---- the schema ------------------------------------------------------------------------------------- */

void js_law_variant(const dp_law_row *row, variant *v)
{
    static const range *const bounds[] = { [DP_MEMBER_ANY] = &ANY, [DP_MEMBER_NONNEG] = &NONNEG,
                                           [DP_MEMBER_POSITIVE] = &POSITIVE };
    *v = (variant){ row->name, row->law, { { NULL } }, { row->points ? "points" : NULL, NULL } };
    for (size_t i = 0; row->members[i].key; i++) {
        const dp_law_member *m = &row->members[i];
        v->params[i] = (param){ m->key, m->offset, bounds[m->bound], m->required };
    }
}

void js_law_defaults(const dp_law_row *row, const cJSON *o, void *base)
{
    for (const dp_law_member *m = row->members; m->key; m++)
        if (!m->required && cJSON_GetObjectItemCaseSensitive(o, m->key) == NULL)
            *(double *)((char *)base + m->offset) = m->def;
}

void js_parse_spring(ctx *c, const cJSON *o, const at *ptr, dp_spring *s)
{
    variant laws[DP_SPRING_LAW_COUNT];
    for (size_t i = 0; i < DP_SPRING_LAW_COUNT; i++)
        js_law_variant(&dp_spring_laws[i].row, &laws[i]);
    const variant *v = js_parse_tagged(c, o, ptr, "law", -1, laws, DP_SPRING_LAW_COUNT, NULL, s);
    if (v == NULL)
        return;
    s->law = (dp_spring_law)v->id;
    const dp_law_row *row = &dp_spring_laws[s->law].row;
    js_law_defaults(row, o, s);
    if (row->points)
        js_parse_graph(c, o, ptr, row->points, &s->graph);
}

static void parse_relaxation(ctx *c, const cJSON *o, const at *ptr, dp_relaxation *r)
{
    static const variant kinds[] = {
        { "rational", DP_RELAX_RATIONAL,
          { NUM(dp_relaxation, a, NONNEG, 1), NUM(dp_relaxation, b, POSITIVE, 1) }, { NULL } },
        { "linear", DP_RELAX_LINEAR, { NUM(dp_relaxation, L, ANY, 1) }, { NULL } },
        { "power", DP_RELAX_POWER, { NUM(dp_relaxation, N, ABOVE_ONE, 1) }, { NULL } },
    };
    const variant *v = js_parse_tagged(c, o, ptr, "kind", -1, kinds, 3, NULL, r);
    if (v != NULL)
        r->kind = (dp_relaxation_kind)v->id;
}

void js_parse_damper(ctx *c, const cJSON *o, const at *ptr, dp_damper *d)
{
    variant laws[DP_DAMPER_LAW_COUNT];
    for (size_t i = 0; i < DP_DAMPER_LAW_COUNT; i++)
        js_law_variant(&dp_damper_laws[i].row, &laws[i]);
    static const char *const common[] = { "relaxation", "belt_velocity", NULL };
    size_t before = c->nerr;
    const variant *v = js_parse_tagged(c, o, ptr, "law", -1, laws, DP_DAMPER_LAW_COUNT, common, d);
    if (v == NULL)
        return;
    d->law = (dp_damper_law)v->id;
    const dp_damper_law_info *L = &dp_damper_laws[d->law];
    js_law_defaults(&L->row, o, d);
    char a[32], b[32];
    at p = { ptr, dp_law_member_key(&L->row, L->static_threshold), 0 };
    /* a static threshold is at least the kinetic one (generalized Coulomb's phi1 >= phi0) */
    if (L->static_threshold && c->nerr == before && dp_damper_static(d) < dp_damper_kinetic(d)) {
        jw_fail(c, &p, "must be >= %s (%s), got %s", dp_law_member_key(&L->row, L->kinetic),
                jw_num_text(dp_damper_kinetic(d), a), jw_num_text(dp_damper_static(d), b));
    }
    if (L->row.points)
        js_parse_graph(c, o, ptr, L->row.points, &d->graph);
    jw_get_num(c, o, ptr, "belt_velocity", &ANY, 0, 0, &d->belt_velocity);
    const cJSON *r = jw_member(c, o, ptr, "relaxation", NULL, &p);
    if (r != NULL)
        parse_relaxation(c, r, &p, &d->relaxation);
}

/* o["terms"]: 1..DP_FORCING_MAX_TERMS forcings one level deeper, into a calloc'd f->terms. */
static void parse_terms(ctx *c, const cJSON *o, const at *ptr, dp_forcing *f, int depth)
{
    char what[64];
    snprintf(what, sizeof what, "an array of 1..%d forcings", DP_FORCING_MAX_TERMS);
    at pp, *p = &pp;
    const cJSON *a = jw_member(c, o, ptr, "terms", what, p);
    if (a == NULL)
        return;
    if (depth >= DP_FORCING_MAX_DEPTH) {
        jw_fail(c, p, "sums nest at most %d deep", DP_FORCING_MAX_DEPTH);
        return;
    }
    int n = cJSON_IsArray(a) ? cJSON_GetArraySize(a) : 0;
    if (!cJSON_IsArray(a) || n < 1 || n > DP_FORCING_MAX_TERMS) {
        if (cJSON_IsArray(a))
            jw_fail(c, p, "must be %s, got %d", what, n);
        else
            jw_fail(c, p, "must be %s, got %s", what, jb_type_name(a));
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
        js_parse_forcing(c, el, &q, &f->terms[i], depth + 1);
    }
}

/* A forcing at nesting `depth` (the model's own is 1). */
void js_parse_forcing(ctx *c, const cJSON *o, const at *ptr, dp_forcing *f, int depth)
{
    js_parse_forcing_with(c, o, ptr, f, depth, NULL);
}

/* A forcing whose object may also hold the members `common` (a network load's "node"), read by its caller. */
void js_parse_forcing_with(ctx *c, const cJSON *o, const at *ptr, dp_forcing *f, int depth,
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
    const variant *v = js_parse_tagged(c, o, ptr, "kind", -1, kinds, 4, common, f);
    if (v == NULL)
        return;
    f->kind = (dp_forcing_kind)v->id;
    if (f->kind == DP_FORCING_SUM)
        parse_terms(c, o, ptr, f, depth);
    if (f->kind != DP_FORCING_TABLE)
        return;
    size_t n = 0;
    double *t = NULL, *F = NULL;
    int ok = js_parse_points(c, o, ptr, "t", 1, &n, &t, &F);
    f->t = t;          /* owned by f from here on, freed by dp_forcing_clear */
    f->F = F;
    f->n = ok ? n : 0;
}

static const range RESTITUTION = { 0, 1, 0, " in [0, 1]" };

/* {"distance": d, "restitution": e} (rigid, e default 0) or {"distance": d, "compliance": k} (compliant). */
void js_parse_contact(ctx *c, const cJSON *o, const at *ptr, dp_contact *ct)
{
    static const char *const keys[] = { "distance", "restitution", "compliance", NULL };
    if (!jw_want_object(c, o, ptr))
        return;
    jw_check_keys(c, o, ptr, keys, NULL, NULL);
    jw_get_num(c, o, ptr, "distance", &ANY, 1, 0, &ct->distance);
    int rigid = jw_get_num(c, o, ptr, "restitution", &RESTITUTION, 0, 0, &ct->restitution);
    int soft = jw_get_num(c, o, ptr, "compliance", &POSITIVE, 0, 0, &ct->compliance);
    if (rigid && soft) {
        at p = { ptr, "compliance", 0 };
        jw_fail(c, &p, "a contact is rigid (\"restitution\") or compliant (\"compliance\"), not both: a compliant "
                    "contact rebounds through its spring");
    }
}

