/* src/json/lcs_json.c - the linear complementarity system document (docs/lcs.md) for dp_spec_parse:
 *
 *     "model": {"lcs": {"A": n x n, "B": n x m, "C": m x n, "D": m x m, "p": n, "q": m}, "laws": [m laws]},
 *     "initial": {"x": [n numbers]}
 *
 * n from A's rows, m from the law list; D, p, q default to zero. An entry of p may be a forcing object
 * (constant, harmonic, table, sum: the one-mass model's "forcing"), a source in time. A law is {"law": "complementarity"}
 * (0 <= u ⊥ w >= 0), {"law": "interval", "min": lo, "max": hi} (w ∈ -N_[lo,hi](u)), or a graph law
 * -w ∈ G(u): {"law": "graph", "points": [[u, F], ...]} (the one-mass model's graph parser), {"law": "coulomb",
 * "phi0"} or {"law": "rope", "k", "length"} (its builders).
 *
 * Its own file for the parts only an LCS has (its matrices and sizes, its law list); its forcings and graph
 * laws are read by laws_json.c, so they get the same messages as anywhere else in a document.
 */
#include <stdio.h>
#include <stdlib.h>

#include "dashpot/lcs.h"
#include "spec_parts.h"

/* Sizes of an LCS document: checking a spec factors I - hθA (n^3) and solves an LCP of up to 2m rows, so a
 * request stays within milliseconds. */
#define LCS_MAX_STATES 200
#define LCS_MAX_COMPONENTS (DP_LCP_MAX / 2)

int js_is_lcs(const cJSON *o)
{
    return cJSON_IsObject(o) && cJSON_GetObjectItemCaseSensitive(o, "lcs") != NULL;
}

/* v as `rows` rows of `cols` numbers, row-major into out; what names the sizes in messages. */
static void lcs_matrix(ctx *c, const cJSON *v, const at *p, size_t rows, size_t cols, const char *what,
                       double *out)
{
    size_t r = cJSON_IsArray(v) ? (size_t)cJSON_GetArraySize(v) : 0;
    if (!cJSON_IsArray(v) || r != rows) {
        jw_fail(c, p, "must be %s: an array of %zu rows of %zu numbers, got %s%s", what, rows, cols,
             cJSON_IsArray(v) ? "an array of another length" : jb_type_name(v), "");
        return;
    }
    size_t i = 0;
    for (const cJSON *row = v->child; row; row = row->next, i++) {
        const at q = { p, NULL, i };
        size_t k = cJSON_IsArray(row) ? (size_t)cJSON_GetArraySize(row) : 0;
        if (!cJSON_IsArray(row) || k != cols) {
            jw_fail(c, &q, "must be a row of %zu numbers (%s), got %s", cols, what,
                 cJSON_IsArray(row) ? "another length" : jb_type_name(row));
            continue;
        }
        size_t j = 0;
        for (const cJSON *x = row->child; x; x = x->next, j++) {
            const at e = { &q, NULL, j };
            jw_check_num(c, x, &e, &ANY, 0, &out[i * cols + j]);
        }
    }
}

static void lcs_vector(ctx *c, const cJSON *v, const at *p, size_t n, const char *what, double *out)
{
    size_t k = cJSON_IsArray(v) ? (size_t)cJSON_GetArraySize(v) : 0;
    if (!cJSON_IsArray(v) || k != n) {
        jw_fail(c, p, "must be an array of %zu numbers (%s), got %s", n, what,
             cJSON_IsArray(v) ? "another length" : jb_type_name(v));
        return;
    }
    size_t i = 0;
    for (const cJSON *x = v->child; x; x = x->next, i++) {
        const at e = { p, NULL, i };
        jw_check_num(c, x, &e, &ANY, 0, &out[i]);
    }
}

/* "p": n entries, each a number or a forcing object ({"kind": "harmonic", ...}: a source in time). */
static void lcs_offsets(ctx *c, const cJSON *v, const at *p, dp_lcs_model *lm)
{
    size_t k = cJSON_IsArray(v) ? (size_t)cJSON_GetArraySize(v) : 0, i = 0;
    if (!cJSON_IsArray(v) || k != lm->n) {
        jw_fail(c, p, "must be an array of %zu entries (one per state), each a number or a forcing object, got %s",
             lm->n, cJSON_IsArray(v) ? "another length" : jb_type_name(v));
        return;
    }
    for (const cJSON *x = v->child; x; x = x->next, i++) {
        const at e = { p, NULL, i };
        if (!cJSON_IsObject(x)) {
            jw_check_num(c, x, &e, &ANY, 0, &lm->p[i]);
            continue;
        }
        if (lm->pf == NULL && (lm->pf = calloc(lm->n, sizeof *lm->pf)) == NULL) {
            c->nomem = 1;
            return;
        }
        js_parse_forcing(c, x, &e, &lm->pf[i], 1);
    }
}

/* A named law's graph from its entry's builder (the one-mass model's: Coulomb's as the damper's, the rope as
 * the spring's), in the (u, -w) plane. */
static void lcs_named_graph(ctx *c, const at *ptr, dp_lcs_law *law)
{
    int s = dp_lcs_laws[law->kind].build(law);
    if (s == DP_ENOMEM)
        c->nomem = 1;
    else if (s != DP_OK)
        jw_fail(c, ptr, "does not make a monotone graph (%s)", dp_strerror(s));
}

/* {"law": ...}: complementarity, interval, or a graph law -w ∈ G(u) (user points, coulomb, rope). */
static void lcs_law(ctx *c, const cJSON *o, const at *ptr, dp_lcs_law *law)
{
    variant laws[DP_LCS_LAW_COUNT];
    for (size_t i = 0; i < DP_LCS_LAW_COUNT; i++)
        js_law_variant(&dp_lcs_laws[i].row, &laws[i]);
    size_t before = c->nerr;
    const variant *v = js_parse_tagged(c, o, ptr, "law", -1, laws, DP_LCS_LAW_COUNT, NULL, law);
    if (v == NULL)
        return;
    law->kind = (dp_lcs_law_kind)v->id;
    const dp_lcs_law_info *L = &dp_lcs_laws[law->kind];
    js_law_defaults(&L->row, o, law);
    if (L->shape == DP_LCS_SHAPE_INTERVAL && c->nerr == before && !(law->lo <= law->hi)) {
        const dp_law_row *r = &L->row;
        const at p = { ptr, dp_law_member_key(r, offsetof(dp_lcs_law, hi)), 0 };
        jw_fail(c, &p, "must be >= %s = %g, got %g", dp_law_member_key(r, offsetof(dp_lcs_law, lo)), law->lo,
                law->hi);
    } else if (L->row.points) {
        size_t mark = c->nerr;
        js_parse_graph(c, o, ptr, L->row.points, &law->graph);
        const at p = { ptr, "points", 0 };
        if (c->nerr == mark && !c->nomem && !dp_lcs_law_valid(law))
            jw_fail(c, &p, "a piece's slope is not a finite number (the points span too much of the double range)");
    } else if (L->build && c->nerr == before) {
        lcs_named_graph(c, ptr, law);
    }
}

/* The step's LCP must fit Lemke's workspace: a long graph adds two rows per segment. */
static void lcs_rows(ctx *c, const at *ptr, const dp_lcs_model *lm)
{
    size_t rows = 0;
    for (size_t i = 0; i < lm->m; i++)
        rows += dp_lcs_law_rows(&lm->law[i]);
    if (rows > DP_LCP_MAX)
        jw_fail(c, ptr, "the laws make a step's LCP of %zu rows (1 per complementarity, 2 per interval, 1 per "
             "non-vertical end ray and 2 per non-vertical segment between turns of a graph), more than %d", rows, DP_LCP_MAX);
}

/* The sizes: n from A's rows, m from the law list; 0 with an error when either is unusable. */
static int lcs_sizes(ctx *c, const cJSON *model, const cJSON *sys, const at *ptr, const at *psys, size_t *n,
                     size_t *m)
{
    at p;
    const cJSON *a = jw_member(c, sys, psys, "A", "an n x n matrix", &p);
    *n = cJSON_IsArray(a) ? (size_t)cJSON_GetArraySize(a) : 0;
    if (a != NULL && (*n == 0 || *n > LCS_MAX_STATES))
        jw_fail(c, &p, "must be an n x n matrix with 1 <= n <= %d, got %s", LCS_MAX_STATES,
             cJSON_IsArray(a) ? (*n ? "more rows" : "no rows") : jb_type_name(a));
    const cJSON *l = jw_member(c, model, ptr, "laws", "an array of one law per component of u", &p);
    *m = cJSON_IsArray(l) ? (size_t)cJSON_GetArraySize(l) : 0;
    if (l != NULL && (*m == 0 || *m > LCS_MAX_COMPONENTS))
        jw_fail(c, &p, "must be an array of 1 to %d laws (one per component of u), got %s", LCS_MAX_COMPONENTS,
             cJSON_IsArray(l) ? (*m ? "more" : "none") : jb_type_name(l));
    return *n >= 1 && *n <= LCS_MAX_STATES && *m >= 1 && *m <= LCS_MAX_COMPONENTS;
}

void js_parse_lcs(ctx *c, const cJSON *o, const at *ptr, dp_spec *s)
{
    static const char *const keys[] = { "lcs", "laws", NULL };
    static const char *const skeys[] = { "A", "B", "C", "D", "p", "q", NULL };
    at ps, p;
    jw_check_keys(c, o, ptr, keys, NULL, NULL);
    const cJSON *sys = jw_member(c, o, ptr, "lcs", NULL, &ps);
    if (!jw_want_object(c, sys, &ps))
        return;
    jw_check_keys(c, sys, &ps, skeys, NULL, NULL);
    size_t n, m;
    if (!lcs_sizes(c, o, sys, ptr, &ps, &n, &m))
        return;
    dp_lcs_model *lm = calloc(1, sizeof *lm);
    if (lm == NULL || (s->lcs = lm, 0) || !(lm->A = calloc(n * n, sizeof(double))) ||
        !(lm->B = calloc(n * m, sizeof(double))) || !(lm->C = calloc(m * n, sizeof(double))) ||
        !(lm->D = calloc(m * m, sizeof(double))) || !(lm->p = calloc(n, sizeof(double))) ||
        !(lm->q = calloc(m, sizeof(double))) || !(lm->x0 = calloc(n, sizeof(double))) ||
        !(lm->law = calloc(m, sizeof *lm->law))) {
        c->nomem = 1;
        return;
    }
    lm->n = n, lm->m = m;
    char wa[48], wb[48], wc[48], wd[48], wq[48];
    snprintf(wa, sizeof wa, "n x n, n = %zu", n);
    snprintf(wb, sizeof wb, "n x m, n = %zu, m = %zu laws", n, m);
    snprintf(wc, sizeof wc, "m x n, m = %zu laws, n = %zu", m, n);
    snprintf(wd, sizeof wd, "m x m, m = %zu laws", m);
    snprintf(wq, sizeof wq, "one per law, m = %zu", m);
    const cJSON *v = jw_member(c, sys, &ps, "A", NULL, &p);
    lcs_matrix(c, v, &p, n, n, wa, lm->A);
    if ((v = jw_member(c, sys, &ps, "B", "an n x m matrix", &p)) != NULL)
        lcs_matrix(c, v, &p, n, m, wb, lm->B);
    if ((v = jw_member(c, sys, &ps, "C", "an m x n matrix", &p)) != NULL)
        lcs_matrix(c, v, &p, m, n, wc, lm->C);
    if ((v = jw_member(c, sys, &ps, "D", NULL, &p)) != NULL)
        lcs_matrix(c, v, &p, m, m, wd, lm->D);
    if ((v = jw_member(c, sys, &ps, "p", NULL, &p)) != NULL)
        lcs_offsets(c, v, &p, lm);
    if ((v = jw_member(c, sys, &ps, "q", NULL, &p)) != NULL)
        lcs_vector(c, v, &p, m, wq, lm->q);
    const cJSON *laws = jw_member(c, o, ptr, "laws", NULL, &p);
    size_t i = 0;
    for (const cJSON *l = laws->child; l; l = l->next, i++) {
        const at q = { &p, NULL, i };
        lcs_law(c, l, &q, &lm->law[i]);
    }
    lcs_rows(c, &p, lm);
}

void js_parse_lcs_initial(ctx *c, const cJSON *o, const at *ptr, dp_spec *s)
{
    static const char *const keys[] = { "x", NULL };
    at p;
    if (!jw_want_object(c, o, ptr))
        return;
    jw_check_keys(c, o, ptr, keys, NULL, NULL);
    const cJSON *v = jw_member(c, o, ptr, "x", NULL, &p);
    char what[48];
    snprintf(what, sizeof what, "one per state, n = %zu", s->lcs->n);
    if (v != NULL)
        lcs_vector(c, v, &p, s->lcs->n, what, s->lcs->x0);
}
