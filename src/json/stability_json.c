/* src/json/stability_json.c - POST /v1/stability and `dashpot stability`: request parsing with located
 * errors, and the analysis / map encoded as JSON or CSV (SVG: stability_svg.c).
 *
 * The request mirrors dp_law (stability.h): {"mass", "law": {"lambda", "mu"}, "map"?}. Every field is
 * checked here for type and shape with the walker every route uses (walk.h), then by the core (dp_law_check,
 * dp_map_axis_check) for domain and limits, so that each error names its JSON Pointer. The wire format is
 * documented in docs/stability.md.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "dashpot/stability.h"
#include "dashpot/stability_json.h"
#include "stability_out.h"
#include "walk.h"

typedef struct request {
    dp_law law;
    int has_map;
    dp_map_axis x, y;
} request;

/* The walk (walk.h) and the request's status: DP_EINVAL (any error of the walk) outranks DP_ELIMIT (a
 * documented limit, from the coefficient count or the core's checks) outranks DP_OK. */
typedef struct pctx {
    ctx w;
    int status;
} pctx;

static void merge(pctx *c, int s)
{
    if (s == DP_EINVAL || s == DP_ENOMEM || (s != DP_OK && c->status == DP_OK))
        c->status = s;
}

/* The status so far, the walk's errors counted in. */
static int status(pctx *c)
{
    merge(c, c->w.nerr > 0 ? DP_EINVAL : DP_OK);
    return c->status;
}

/* ---- parsing ---- */

/* law[key]: 1..DP_STAB_MAX_ORDER + 1 finite numbers, lowest derivative first. */
static void get_coefs(pctx *c, const cJSON *law, const at *pl, const char *key, double *dst, int *n)
{
    at p;
    const cJSON *a = jw_member(&c->w, law, pl, key, "an array of numbers, lowest derivative first", &p);
    *n = 0;
    if (a == NULL)
        return;
    if (!cJSON_IsArray(a)) {
        jw_fail(&c->w, &p, "must be an array of numbers, lowest derivative first, got %s", jb_type_name(a));
        return;
    }
    int count = cJSON_GetArraySize(a);
    if (count == 0) {
        jw_fail(&c->w, &p, "must be an array of at least one number (lowest derivative first), got an empty "
                "array");
        return;
    }
    if (count > DP_STAB_MAX_ORDER + 1) {
        char ptr[DP_POINTER_MAX];
        jp_text(&p, ptr);
        dp_errors_add(c->w.errs, ptr, "at most %d coefficients (derivative order <= %d)", DP_STAB_MAX_ORDER + 1,
                      DP_STAB_MAX_ORDER);
        merge(c, DP_ELIMIT);
        return;
    }
    int i = 0;
    for (const cJSON *e = a->child; e != NULL; e = e->next, i++) {
        const at q = { &p, NULL, (size_t)i };
        jw_check_num(&c->w, e, &q, &ANY, 0, &dst[i]);
    }
    *n = count;
}

static void parse_axis(pctx *c, const cJSON *o, const at *pa, const dp_law *law, dp_map_axis *ax)
{
    static const char *const keys[] = { "param", "from", "to", "steps", NULL };
    if (!jw_want_object(&c->w, o, pa))
        return;
    jw_check_keys(&c->w, o, pa, keys, NULL, NULL);
    int before = status(c);
    size_t nerr = c->w.nerr;
    at p;
    char what[96], sb[64];
    snprintf(what, sizeof what, "\"mass\", \"lambda[i]\" or \"mu[j]\" with i, j in 0..%d", DP_STAB_MAX_ORDER);
    const cJSON *v = jw_member(&c->w, o, pa, "param", what, &p);
    if (v != NULL && !cJSON_IsString(v))
        jw_fail(&c->w, &p, "must be %s, got %s", what, jb_type_name(v));
    else if (v != NULL && dp_param_parse(v->valuestring, &ax->kind, &ax->index) != 0)
        jw_fail(&c->w, &p, "must be %s, got \"%s\"", what, jb_shown(v->valuestring, sb));
    jw_get_num(&c->w, o, pa, "from", &ANY, 1, 0, &ax->from);
    jw_get_num(&c->w, o, pa, "to", &ANY, 1, 0, &ax->to);
    double steps = 0;
    jw_get_num(&c->w, o, pa, "steps", &ANY, 1, 1, &steps);
    ax->steps = steps < 0 ? -1 : steps > DP_STAB_MAP_MAX_STEPS ? DP_STAB_MAP_MAX_STEPS + 1 : (int)steps;
    if (c->w.nerr == nerr && before == DP_OK) {
        char ptr[DP_POINTER_MAX];
        jp_text(pa, ptr);
        merge(c, dp_map_axis_check(ax, law, ptr, c->w.errs));
    }
}

static void parse_map(pctx *c, const cJSON *o, const at *pm, request *r)
{
    static const char *const keys[] = { "x", "y", NULL };
    static const char *const axis = "an object {\"param\", \"from\", \"to\", \"steps\"}";
    if (!jw_want_object(&c->w, o, pm))
        return;
    r->has_map = 1;
    jw_check_keys(&c->w, o, pm, keys, NULL, NULL);
    at px, py;
    const cJSON *x = jw_member(&c->w, o, pm, "x", axis, &px), *y = jw_member(&c->w, o, pm, "y", axis, &py);
    if (x != NULL)
        parse_axis(c, x, &px, &r->law, &r->x);
    if (y != NULL)
        parse_axis(c, y, &py, &r->law, &r->y);
    if (status(c) == DP_OK && r->x.kind == r->y.kind && r->x.index == r->y.index) {
        const at pp = { &py, "param", 0 };
        jw_fail(&c->w, &pp, "the two axes sweep the same coefficient");
    }
}

static void parse_request(pctx *c, const cJSON *root, request *r)
{
    static const char *const keys[] = { "mass", "law", "map", NULL }, *const law_keys[] = { "lambda", "mu", NULL };
    memset(r, 0, sizeof *r);
    jw_check_keys(&c->w, root, NULL, keys, NULL, NULL);
    int have_mass = jw_get_num(&c->w, root, NULL, "mass", &ANY, 1, 0, &r->law.mass);
    at pl, pm;
    const cJSON *law = jw_member(&c->w, root, NULL, "law", "an object {\"lambda\": [...], \"mu\": [...]}", &pl);
    if (law == NULL || !jw_want_object(&c->w, law, &pl))
        return;
    jw_check_keys(&c->w, law, &pl, law_keys, NULL, NULL);
    get_coefs(c, law, &pl, "lambda", r->law.lambda, &r->law.nlambda);
    get_coefs(c, law, &pl, "mu", r->law.mu, &r->law.nmu);
    if (!have_mass || status(c) != DP_OK)
        return;
    merge(c, dp_law_check(&r->law, "", c->w.errs));
    const cJSON *map = jw_member(&c->w, root, NULL, "map", NULL, &pm);
    if (map != NULL && c->status == DP_OK)
        parse_map(c, map, &pm, r);
}

/* ---- the analysis as JSON ---- */

static void numbers(stab_out *o, const double *x, int n)
{
    stab_put(o, "[");
    for (int i = 0; i < n; i++) {
        if (i)
            stab_put(o, ",");
        stab_num(o, x[i]);
    }
    stab_put(o, "]");
}

static void complexes(stab_out *o, const double *re, const double *im, const double *err, int n)
{
    stab_put(o, "[");
    for (int i = 0; i < n; i++) {
        stab_put(o, i ? ",{\"re\":" : "{\"re\":");
        stab_num(o, re[i]);
        stab_put(o, ",\"im\":");
        stab_num(o, im[i]);
        if (err != NULL) {
            stab_put(o, ",\"error\":");
            stab_num(o, err[i]);
        }
        stab_put(o, "}");
    }
    stab_put(o, "]");
}

static void matrix(stab_out *o, const double *m, int dim)
{
    stab_put(o, "[");
    for (int i = 0; i < dim; i++) {
        if (i)
            stab_put(o, ",");
        numbers(o, m + i * dim, dim);
    }
    stab_put(o, "]");
}

/* (x, x', F_V, F_V', F_V'', F_V^(3), ...) for the first dim variables. */
static void variables(stab_out *o, int dim)
{
    static const char *const first[] = { "x", "x'", "F_V", "F_V'", "F_V''" };
    stab_put(o, "[");
    for (int i = 0; i < dim; i++) {
        if (i)
            stab_put(o, ",");
        if (i < 5) {
            stab_str(o, first[i]);
            continue;
        }
        stab_put(o, "\"F_V^(");
        stab_int(o, i - 2);
        stab_put(o, ")\"");
    }
    stab_put(o, "]");
}

static void law_echo(stab_out *o, const dp_law *law)
{
    stab_put(o, "\"mass\":");
    stab_num(o, law->mass);
    stab_put(o, ",\"law\":{\"lambda\":");
    numbers(o, law->lambda, law->nlambda);
    stab_put(o, ",\"mu\":");
    numbers(o, law->mu, law->nmu);
    stab_put(o, "}");
}

static void named(stab_out *o, const char *key, double v, int comma)
{
    stab_put(o, comma ? ",\"" : "\"");
    stab_put(o, key);
    stab_put(o, "\":");
    stab_num(o, v);
}

static void closed_form(stab_out *o, const dp_closed_form *cf, double m)
{
    if (cf->model == DP_MODEL_NONE) {
        stab_put(o, "null");
        return;
    }
    stab_put(o, "{\"name\":\"");
    stab_put(o, cf->name);
    stab_put(o, "\",\"condition\":\"");
    stab_put(o, cf->condition);
    stab_put(o, "\",\"expression\":");
    stab_str(o, cf->expression);
    stab_put(o, ",\"parameters\":{");
    named(o, "m", m, 0);
    if (cf->model == DP_MODEL_1_2)
        named(o, "lambda", cf->lambda1, 1);
    else {
        named(o, "lambda1", cf->lambda1, 1);
        named(o, "lambda2", cf->lambda2, 1);
    }
    named(o, "mu1", cf->mu1, 1);
    named(o, "mu2", cf->mu2, 1);
    if (cf->model == DP_MODEL_1_4)
        named(o, "mu3", cf->mu3, 1);
    stab_put(o, "}");
    named(o, "value", cf->value, 1);
    named(o, "tolerance", cf->tolerance, 1);
    stab_put(o, cf->applies ? ",\"applies\":true,\"verdict\":" : ",\"applies\":false,\"verdict\":");
    if (cf->applies)
        stab_str(o, dp_verdict_name(cf->verdict));
    else
        stab_put(o, "null");
    stab_put(o, "}");
}

static void margin(stab_out *o, const dp_poly_report *r)
{
    stab_put(o, "{\"value\":");
    if (r->has_abscissa)
        stab_num(o, -r->abscissa);
    else
        stab_put(o, "null");
    named(o, "tolerance", r->abscissa_err, 1);
    stab_put(o, r->near_boundary ? ",\"near_boundary\":true,\"by_hurwitz\":\"" : ",\"near_boundary\":false,\"by_hurwitz\":\"");
    stab_put(o, dp_verdict_name(r->by_hurwitz));
    stab_put(o, "\",\"by_roots\":\"");
    stab_put(o, dp_verdict_name(r->by_roots));
    stab_put(o, "\",\"hurwitz_tolerances\":");
    numbers(o, r->minor_tol, r->degree > 0 ? r->degree : 0);
    stab_put(o, "}");
}

static void state_or_pencil(stab_out *o, const dp_stability *st)
{
    static const char *const eq[] = { NULL, "(1.9)", "(1.11)", "(1.13)" };
    const dp_state_matrix *s = &st->state;
    const dp_pencil *pc = &st->pencil;
    if (st->dae) {
        stab_put(o, ",\"state_matrix\":null,\"pencil\":{\"variables\":");
        variables(o, pc->dim);
        stab_put(o, ",\"E\":");
        matrix(o, pc->e, pc->dim);
        stab_put(o, ",\"A\":");
        matrix(o, pc->a, pc->dim);
        stab_put(o, ",\"finite_eigenvalues\":");
        complexes(o, pc->fin_re, pc->fin_im, NULL, pc->nfinite);
        stab_put(o, ",\"infinite_eigenvalues\":");
        stab_int(o, pc->ninfinite);
        stab_put(o, pc->singular ? ",\"singular\":true,\"deviation\":" : ",\"singular\":false,\"deviation\":");
        if (pc->deviation >= 0)
            stab_num(o, pc->deviation);
        else
            stab_put(o, "null");
        stab_put(o, "}");
        return;
    }
    stab_put(o, ",\"state_matrix\":{\"equation\":");
    const char *e = eq[st->closed.model];
    stab_put(o, e ? "\"" : "null");
    stab_put(o, e ? e : "");
    stab_put(o, e ? "\"" : "");
    stab_put(o, ",\"variables\":");
    variables(o, s->dim);
    stab_put(o, ",\"rows\":");
    matrix(o, s->s, s->dim);
    stab_put(o, ",\"eigenvalues\":");
    complexes(o, s->eig_re, s->eig_im, NULL, s->dim);
    named(o, "deviation", s->deviation, 1);
    stab_put(o, "},\"pencil\":null");
}

static void analysis_json(stab_out *o, const dp_law *law, const dp_stability *st)
{
    const dp_poly_report *r = &st->poly;
    int d = r->degree > 0 ? r->degree : 0;
    stab_put(o, "{");
    law_echo(o, law);
    stab_put(o, ",\"polynomial\":{\"coefficients\":");
    numbers(o, st->coef, st->nominal_degree + 1);
    stab_put(o, ",\"nominal_degree\":");
    stab_int(o, st->nominal_degree);
    stab_put(o, ",\"degree\":");
    if (r->degree >= 0)
        stab_int(o, r->degree);
    else
        stab_put(o, "null");
    stab_put(o, "}");
    stab_put(o, ",\"roots\":");
    complexes(o, r->root_re, r->root_im, r->root_err, d);
    stab_put(o, ",\"spectral_abscissa\":");
    if (r->has_abscissa)
        stab_num(o, r->abscissa);
    else
        stab_put(o, "null");
    stab_put(o, ",\"hurwitz_minors\":");
    numbers(o, r->minor, d);
    stab_put(o, ",\"verdict\":");
    stab_str(o, dp_verdict_name(st->verdict));
    stab_put(o, ",\"margin\":");
    margin(o, r);
    stab_put(o, ",\"model\":");
    closed_form(o, &st->closed, law->mass);
    state_or_pencil(o, st);
    stab_put(o, "}\n");
}

/* ---- maps as JSON and CSV ---- */

static void axis_json(stab_out *o, const dp_map_axis *ax)
{
    char name[32];
    dp_param_name(ax->kind, ax->index, name, sizeof name);
    stab_printf(o, "{\"param\":\"%s\"", name);
    named(o, "from", ax->from, 1);
    named(o, "to", ax->to, 1);
    stab_printf(o, ",\"steps\":%d}", ax->steps);
}

static void map_counts(stab_out *o, const dp_map *map)
{
    size_t count[DP_VERDICT_UNDECIDED + 1] = { 0 };
    for (size_t k = 0; k < map->nx * map->ny; k++)
        count[map->verdict[k] <= DP_VERDICT_UNDECIDED ? map->verdict[k] : DP_VERDICT_UNDECIDED]++;
    stab_put(o, "\"legend\":{");
    for (int v = 0; v < DP_VERDICT_UNDECIDED; v++)
        stab_printf(o, "%s\"%c\":\"%s\"", v ? "," : "", dp_verdict_letter(v), dp_verdict_name(v));
    stab_put(o, "},\"counts\":{");
    for (int v = 0; v < DP_VERDICT_UNDECIDED; v++)
        stab_printf(o, "%s\"%c\":%zu", v ? "," : "", dp_verdict_letter(v), count[v]);
    stab_put(o, "}");
}

static void map_json(stab_out *o, const dp_law *law, const dp_map *map)
{
    stab_put(o, "{");
    law_echo(o, law);
    stab_put(o, ",\"map\":{\"x\":");
    axis_json(o, &map->x);
    stab_put(o, ",\"y\":");
    axis_json(o, &map->y);
    stab_put(o, ",\"closed_form\":");
    closed_form(o, &map->closed, law->mass);
    stab_put(o, ",");
    map_counts(o, map);
    stab_put(o, ",\"verdict\":[");
    for (size_t j = 0; j < map->ny && !o->failed; j++) {
        stab_put(o, j ? ",\n\"" : "\n\"");
        for (size_t i = 0; i < map->nx; i++)
            stab_putn(o, &(char){ dp_verdict_letter(map->verdict[j * map->nx + i]) }, 1);
        stab_put(o, "\"");
    }
    stab_put(o, "],\"spectral_abscissa\":[");
    for (size_t j = 0; j < map->ny && !o->failed; j++) {
        stab_put(o, j ? ",\n[" : "\n[");
        for (size_t i = 0, k = j * map->nx; i < map->nx; i++, k++) {
            if (i)
                stab_put(o, ",");
            if (map->has_abscissa[k])
                stab_num(o, map->abscissa[k]);
            else
                stab_put(o, "null");
        }
        stab_put(o, "]");
    }
    stab_put(o, "]}}\n");
}

static void map_csv(stab_out *o, const dp_map *map)
{
    char xn[32], yn[32];
    dp_param_name(map->x.kind, map->x.index, xn, sizeof xn);
    dp_param_name(map->y.kind, map->y.index, yn, sizeof yn);
    stab_printf(o, "%s,%s,spectral_abscissa,verdict\n", xn, yn);
    for (size_t j = 0; j < map->ny && !o->failed; j++) {
        double y = dp_map_axis_value(&map->y, (int)j);
        for (size_t i = 0, k = j * map->nx; i < map->nx; i++, k++) {
            stab_num(o, dp_map_axis_value(&map->x, (int)i));
            stab_put(o, ",");
            stab_num(o, y);
            stab_put(o, ",");
            if (map->has_abscissa[k])
                stab_num(o, map->abscissa[k]);
            stab_put(o, ",");
            stab_put(o, dp_verdict_name(map->verdict[k]));
            stab_put(o, "\n");
        }
    }
}

/* ---- the entry point ---- */


/* Bytes an analysis answer takes for a law of low order (1.3 KB for the thesis models): reserved at once
 * rather than grown through 256, 512, 1024. */
#define ANALYSIS_BYTES 2000

static int run(dp_stability_ws *w, const request *r, int want, stab_out *o)
{
    int s;
    if (r->has_map) {
        dp_map map;
        s = dp_stability_map(w, &r->law, &r->x, &r->y, &map);
        if (s == DP_OK) {
            if (want == DP_STABILITY_CSV)
                map_csv(o, &map);
            else if (want == DP_STABILITY_SVG)
                stab_map_svg(o, &map);
            else
                map_json(o, &r->law, &map);
        }
        dp_map_clear(&map);
    } else {
        dp_stability *st = malloc(sizeof *st);
        s = st == NULL ? DP_ENOMEM : dp_stability_analyse(w, &r->law, st);
        if (s == DP_OK && dp_buf_reserve(o->b, ANALYSIS_BYTES) != DP_OK)
            s = DP_ENOMEM;
        if (s == DP_OK)
            analysis_json(o, &r->law, st);
        free(st);
    }
    return s == DP_OK && o->failed ? DP_ENOMEM : s;
}

int dp_stability_respond(const char *body, size_t len, int want, dp_buf *out, dp_errors *errs)
{
    dp_stability_ws *w = dp_stability_ws_alloc();
    if (w == NULL) {
        dp_errors_add(errs, "", "%s", dp_strerror(DP_ENOMEM));
        return DP_ENOMEM;
    }
    int s = dp_stability_respond_ws(w, body, len, want, out, errs);
    dp_stability_ws_free(w);
    return s;
}

int dp_stability_respond_ws(dp_stability_ws *w, const char *body, size_t len, int want, dp_buf *out,
                            dp_errors *errs)
{
    pctx c = { { errs, 0, 0, 0 }, DP_OK };
    int read;
    cJSON *root = jw_read(&c.w, body, len, &read);   /* a NUL or a repeated key: counted, the rest still checked */
    if (root == NULL)
        return read;
    request r;
    parse_request(&c, root, &r);
    cJSON_Delete(root);
    if (status(&c) == DP_OK && want != DP_STABILITY_JSON && !r.has_map) {
        const at map = { NULL, "map", 0 };
        jw_fail(&c.w, &map, "CSV and SVG describe a map: add a \"map\" member, or ask for JSON");
    }
    if (status(&c) == DP_OK && (want < DP_STABILITY_JSON || want > DP_STABILITY_SVG))
        jw_fail(&c.w, NULL, "unknown response format %d", want);
    if (status(&c) != DP_OK)
        return c.status;
    size_t before = out->len;
    stab_out o = { out, 0 };
    int s = run(w, &r, want, &o);
    if (s != DP_OK) {
        out->len = before;
        if (out->data != NULL && before < out->cap)
            out->data[before] = '\0';
        dp_errors_add(errs, "", "%s", dp_strerror(s));
    }
    return s;
}
