/* src/json/modes_json.c - POST /v1/modes and /v1/response (and the CLI's modes/response): the request into
 * dense M, K, C (dp_network_linear_parts, so the linear analysis sees exactly the network the solvers see),
 * the options of a linear analysis, and the answers as JSON, NDJSON or CSV.
 *
 * Why this file reads the model itself: a linear analysis needs only each element's ends, its linear
 * spring k and viscous c, and whether anything else is on it (then it is left out and listed). Those are
 * filled into a dp_network as the network parser would, so dp_network_linear_parts and
 * dp_network_nonlinear_elements decide what is linear; the nonlinear laws' own parameters are not checked
 * here (a simulation of the same document checks them).
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "dashpot/json.h"
#include "dashpot/modes.h"
#include "dashpot/modes_json.h"
#include "body.h"
#include "dashpot/network.h"

/* A JSON Pointer into out[DP_POINTER_MAX], cut short if ever longer (ours are not). */
static void ptrf(char *out, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static void ptrf(char *out, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out, DP_POINTER_MAX, fmt, ap);
    va_end(ap);
}

typedef struct request {
    dp_network net;
    double *M, *K, *C;
    const char *pM, *pK, *pC;        /* where a bad matrix came from */
    double alpha, beta;              /* Rayleigh damping added to C */
    long force_node, response_node;
    double from, to;
    long points;
    int log_spacing;
} request;

static void request_clear(request *r)
{
    free(r->net.mass);
    free(r->net.M);
    free(r->net.K);
    free(r->net.C);
    free(r->net.el);
    free(r->M);
    free(r->K);
    free(r->C);
}

/* ---- reading ---------------------------------------------------------------------------------------- */

static const char *type_name(const cJSON *v)
{
    return v == NULL ? "nothing" : cJSON_IsNumber(v) ? "a number" : cJSON_IsString(v) ? "a string" :
           cJSON_IsArray(v) ? "an array" : cJSON_IsObject(v) ? "an object" : cJSON_IsBool(v) ? "a boolean" : "null";
}

/* Unknown members of o are errors (a repeated one is the body reader's, body.c). */
static void check_keys(const cJSON *o, const char *ptr, const char *const *keys, const char *list, dp_errors *e)
{
    for (const cJSON *m = o->child; m; m = m->next) {
        int known = 0;
        for (const char *const *k = keys; *k; k++)
            known |= strcmp(*k, m->string) == 0;
        if (!known)
            dp_errors_add(e, ptr, "unknown key \"%.60s\"; expected one of: %s", m->string, list);
    }
}

/* A finite number in [lo, hi]; `*out` is left alone when absent and not required. 1 when usable. */
static int get_number(const cJSON *o, const char *ptr, const char *key, double lo, double hi, int required,
                      double *out, dp_errors *e)
{
    char p[DP_POINTER_MAX];
    ptrf(p, "%s/%s", ptr, key);
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    if (v == NULL) {
        if (required)
            dp_errors_add(e, p, "missing required key \"%s\" (a finite number in [%g, %g])", key, lo, hi);
        return !required;
    }
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble) || v->valuedouble < lo || v->valuedouble > hi) {
        dp_errors_add(e, p, "must be a finite number in [%g, %g], got %s", lo, hi,
                      cJSON_IsNumber(v) ? "a number outside it" : type_name(v));
        return 0;
    }
    *out = v->valuedouble;
    return 1;
}

static int get_index(const cJSON *o, const char *ptr, const char *key, size_t n, long *out, dp_errors *e)
{
    double x = -1;
    if (!get_number(o, ptr, key, 0, n > 0 ? (double)n - 1 : 0, 1, &x, e))
        return 0;
    if (x != floor(x)) {
        dp_errors_add(e, ptr, "\"%s\" must be a node index (an integer in [0, %zu])", key, n - 1);
        return 0;
    }
    *out = (long)x;
    return 1;
}

/* o[key] as an n x n matrix (n from the masses, or *n == 0: from this matrix). NULL when absent. */
static double *get_matrix(const cJSON *o, const char *ptr, const char *key, size_t *n, dp_errors *e)
{
    char p[DP_POINTER_MAX], q[DP_POINTER_MAX];
    ptrf(p, "%s/%s", ptr, key);
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(o, key);
    if (a == NULL)
        return NULL;
    size_t rows = cJSON_IsArray(a) ? (size_t)cJSON_GetArraySize(a) : 0;
    size_t want = *n ? *n : rows;
    if (!cJSON_IsArray(a) || rows == 0 || rows != want || rows > DP_NETWORK_MAX_MATRIX_NODES) {
        dp_errors_add(e, p, "must be an array of %zu rows (a square matrix of at most %d nodes), got %s%s", want,
                      DP_NETWORK_MAX_MATRIX_NODES, cJSON_IsArray(a) ? "" : type_name(a),
                      cJSON_IsArray(a) ? "another number of rows" : "");
        return NULL;
    }
    double *A = malloc(rows * rows * sizeof *A);
    if (A == NULL)
        return NULL;
    size_t i = 0, bad = 0;
    for (const cJSON *r = a->child; r; r = r->next, i++) {
        ptrf(q, "%s/%zu", p, i);
        if (!cJSON_IsArray(r) || (size_t)cJSON_GetArraySize(r) != rows) {
            dp_errors_add(e, q, "must be a row of %zu numbers", rows);
            bad++;
            continue;
        }
        size_t j = 0;
        for (const cJSON *x = r->child; x; x = x->next, j++) {
            if (!cJSON_IsNumber(x) || !isfinite(x->valuedouble)) {
                ptrf(q, "%s/%zu/%zu", p, i, j);
                dp_errors_add(e, q, "must be a finite number, got %s", type_name(x));
                bad++;
            } else
                A[i * rows + j] = x->valuedouble;
        }
    }
    if (bad) {
        free(A);
        return NULL;
    }
    *n = rows;
    return A;
}

/* One end of an element: "ground" or a node index. */
static int get_end(const cJSON *v, const char *p, size_t n, long *end, dp_errors *e)
{
    if (cJSON_IsString(v) && strcmp(v->valuestring, "ground") == 0) {
        *end = DP_GROUND;
        return 1;
    }
    if (cJSON_IsNumber(v) && v->valuedouble >= 0 && v->valuedouble < (double)n && v->valuedouble == floor(v->valuedouble)) {
        *end = (long)v->valuedouble;
        return 1;
    }
    dp_errors_add(e, p, "must be \"ground\" or a node index in [0, %zu]", n - 1);
    return 0;
}

static const char *law_of(const cJSON *o, const char *p, const char *const *laws, const char *list, dp_errors *e,
                          int *id)
{
    const cJSON *l = cJSON_GetObjectItemCaseSensitive(o, "law");
    for (int i = 0; laws[i] && cJSON_IsString(l); i++)
        if (strcmp(l->valuestring, laws[i]) == 0) {
            *id = i;
            return laws[i];
        }
    char q[DP_POINTER_MAX];
    ptrf(q, "%s/law", p);
    dp_errors_add(e, q, "must be one of: %s", list);
    return NULL;
}

/* The spring and damper of an element: what is linear in them, and a law that marks the rest. */
static void parse_laws(const cJSON *el, const char *p, dp_element *x, dp_errors *e)
{
    static const char *const springs[] = { "linear", "rope", "graph", "elastoplastic", NULL };
    static const char *const dampers[] = { "none", "linear", "coulomb", "bingham", "generalized-coulomb", "graph", NULL };
    char q[DP_POINTER_MAX];
    const cJSON *s = cJSON_GetObjectItemCaseSensitive(el, "spring"), *d = cJSON_GetObjectItemCaseSensitive(el, "damper");
    int id;
    ptrf(q, "%s/spring", p);
    if (s && (!cJSON_IsObject(s) ? (dp_errors_add(e, q, "must be an object"), 0) : 1) &&
        law_of(s, q, springs, "linear, rope, graph, elastoplastic", e, &id)) {
        x->has_spring = 1;
        x->spring.law = id == 0 ? DP_SPRING_LINEAR : DP_SPRING_GRAPH; /* anything but linear is left out */
        if (id == 0)
            get_number(s, q, "k", 0, INFINITY, 1, &x->spring.k, e);
    }
    ptrf(q, "%s/damper", p);
    if (d && (!cJSON_IsObject(d) ? (dp_errors_add(e, q, "must be an object"), 0) : 1) &&
        law_of(d, q, dampers, "none, linear, coulomb, bingham, generalized-coulomb, graph", e, &id)) {
        static const dp_damper_law ids[] = { DP_DAMPER_NONE, DP_DAMPER_LINEAR, DP_DAMPER_COULOMB, DP_DAMPER_BINGHAM,
                                             DP_DAMPER_GENERALIZED_COULOMB, DP_DAMPER_GRAPH };
        x->has_damper = 1;
        x->damper.law = ids[id];
        if (id == 1 || id == 3) /* linear and Bingham: their viscous c is linear */
            get_number(d, q, "c", 0, INFINITY, 1, &x->damper.c, e);
        const cJSON *relax = cJSON_GetObjectItemCaseSensitive(d, "relaxation");
        if (relax && !cJSON_IsNull(relax))
            x->damper.relaxation.kind = DP_RELAX_RATIONAL; /* left out: only its presence matters here */
    }
    if (cJSON_GetObjectItemCaseSensitive(el, "contact"))
        x->has_spring = 1, x->spring.law = DP_SPRING_GRAPH; /* a contact is set-valued: left out */
}

static void parse_elements(const cJSON *model, request *r, dp_errors *e)
{
    static const char *const keys[] = { "between", "spring", "damper", "contact", NULL };
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(model, "elements");
    if (a == NULL)
        return;
    size_t n = r->net.n, m = cJSON_IsArray(a) ? (size_t)cJSON_GetArraySize(a) : 0;
    if (!cJSON_IsArray(a) || m > DP_NETWORK_MAX_ELEMENTS) {
        dp_errors_add(e, "/model/elements", "must be an array of at most %d elements", DP_NETWORK_MAX_ELEMENTS);
        return;
    }
    r->net.el = calloc(m ? m : 1, sizeof *r->net.el);
    if (r->net.el == NULL)
        return;
    size_t i = 0;
    char p[DP_POINTER_MAX], q[DP_POINTER_MAX];
    for (const cJSON *el = a->child; el; el = el->next, i++) {
        ptrf(p, "/model/elements/%zu", i);
        dp_element *x = &r->net.el[r->net.nel++];
        if (!cJSON_IsObject(el)) {
            dp_errors_add(e, p, "must be an object with \"between\" and a spring, damper or contact");
            continue;
        }
        check_keys(el, p, keys, "between, spring, damper, contact", e);
        const cJSON *b = cJSON_GetObjectItemCaseSensitive(el, "between");
        ptrf(q, "%s/between", p);
        if (!cJSON_IsArray(b) || cJSON_GetArraySize(b) != 2)
            dp_errors_add(e, q, "must be a pair [a, b] of node indices or \"ground\"");
        else {
            char q0[DP_POINTER_MAX], q1[DP_POINTER_MAX];
            ptrf(q0, "%s/0", q);
            ptrf(q1, "%s/1", q);
            if (get_end(b->child, q0, n, &x->a, e) & get_end(b->child->next, q1, n, &x->b, e) && x->a == x->b)
                dp_errors_add(e, q, "joins an end to itself");
        }
        if (!cJSON_GetObjectItemCaseSensitive(el, "spring") && !cJSON_GetObjectItemCaseSensitive(el, "damper") &&
            !cJSON_GetObjectItemCaseSensitive(el, "contact"))
            dp_errors_add(e, p, "needs at least one of \"spring\", \"damper\", \"contact\"");
        parse_laws(el, p, x, e);
    }
}

static void parse_model(const cJSON *doc, request *r, dp_errors *e)
{
    static const char *const keys[] = { "masses", "mass_matrix", "stiffness_matrix", "damping_matrix", "elements",
                                        "forcing", NULL };
    const cJSON *model = cJSON_GetObjectItemCaseSensitive(doc, "model");
    if (!cJSON_IsObject(model)) {
        dp_errors_add(e, "/model", model ? "must be an object" : "missing required key \"model\" (a network)");
        return;
    }
    check_keys(model, "/model", keys, "masses, mass_matrix, stiffness_matrix, damping_matrix, elements, forcing", e);
    const cJSON *ms = cJSON_GetObjectItemCaseSensitive(model, "masses");
    int has_mm = cJSON_GetObjectItemCaseSensitive(model, "mass_matrix") != NULL;
    if ((ms != NULL) == has_mm) {
        dp_errors_add(e, "/model", "needs exactly one of \"masses\" (a list) and \"mass_matrix\"");
        return;
    }
    size_t n = 0;
    r->pM = ms ? "/model/masses" : "/model/mass_matrix";
    if (ms) {
        n = cJSON_IsArray(ms) ? (size_t)cJSON_GetArraySize(ms) : 0;
        if (n == 0 || n > DP_MODES_MAX_NODES) {
            dp_errors_add(e, r->pM, "must be an array of 1 to %d masses", DP_MODES_MAX_NODES);
            return;
        }
        r->net.mass = malloc(n * sizeof *r->net.mass);
        size_t i = 0;
        for (const cJSON *x = ms->child; x && r->net.mass; x = x->next, i++) {
            char p[DP_POINTER_MAX];
            ptrf(p, "/model/masses/%zu", i);
            if (!cJSON_IsNumber(x) || !isfinite(x->valuedouble) || x->valuedouble <= 0)
                dp_errors_add(e, p, "must be a finite number > 0");
            else
                r->net.mass[i] = x->valuedouble;
        }
    } else if ((r->net.M = get_matrix(model, "/model", "mass_matrix", &n, e)) == NULL)
        return;
    r->net.n = n;
    r->net.K = get_matrix(model, "/model", "stiffness_matrix", &n, e);
    r->net.C = get_matrix(model, "/model", "damping_matrix", &n, e);
    parse_elements(model, r, e);
    const cJSON *f = cJSON_GetObjectItemCaseSensitive(model, "forcing");
    if (f && !cJSON_IsArray(f))
        dp_errors_add(e, "/model/forcing", "must be an array (a linear analysis does not use it)");
    int els = r->net.nel > 0;
    r->pK = r->net.K ? "/model/stiffness_matrix" : els ? "/model/elements" : "/model";
    r->pC = r->net.C ? "/model/damping_matrix" : els ? "/model/elements" : "/damping/rayleigh";
}

static void parse_damping(const cJSON *doc, request *r, dp_errors *e)
{
    static const char *const keys[] = { "rayleigh", NULL }, *const rk[] = { "alpha", "beta", NULL };
    const cJSON *d = cJSON_GetObjectItemCaseSensitive(doc, "damping");
    if (d == NULL)
        return;
    if (!cJSON_IsObject(d)) {
        dp_errors_add(e, "/damping", "must be an object {\"rayleigh\": {\"alpha\", \"beta\"}}");
        return;
    }
    check_keys(d, "/damping", keys, "rayleigh", e);
    const cJSON *ray = cJSON_GetObjectItemCaseSensitive(d, "rayleigh");
    if (!cJSON_IsObject(ray)) {
        dp_errors_add(e, "/damping/rayleigh", "must be an object {\"alpha\": a, \"beta\": b}");
        return;
    }
    check_keys(ray, "/damping/rayleigh", rk, "alpha, beta", e);
    get_number(ray, "/damping/rayleigh", "alpha", 0, 1e12, 0, &r->alpha, e);
    get_number(ray, "/damping/rayleigh", "beta", 0, 1e12, 0, &r->beta, e);
}

static void parse_range(const cJSON *doc, request *r, dp_errors *e)
{
    static const char *const keys[] = { "from", "to", "points", "spacing", NULL };
    const cJSON *o = cJSON_GetObjectItemCaseSensitive(doc, "omega");
    if (!cJSON_IsObject(o)) {
        dp_errors_add(e, "/omega", o ? "must be an object {\"from\", \"to\", \"points\"}"
                                     : "missing required key \"omega\" ({\"from\", \"to\", \"points\"} in rad/s)");
        return;
    }
    check_keys(o, "/omega", keys, "from, to, points, spacing", e);
    double pts = 0;
    int ok = get_number(o, "/omega", "from", 0, 1e15, 1, &r->from, e);
    ok &= get_number(o, "/omega", "to", 0, 1e15, 1, &r->to, e);
    if (get_number(o, "/omega", "points", 1, DP_RESPONSE_MAX_POINTS, 1, &pts, e)) {
        if (pts != floor(pts))
            dp_errors_add(e, "/omega/points", "must be an integer in [1, %d]", DP_RESPONSE_MAX_POINTS);
        r->points = (long)pts;
    }
    const cJSON *sp = cJSON_GetObjectItemCaseSensitive(o, "spacing");
    if (sp && !(cJSON_IsString(sp) && (strcmp(sp->valuestring, "linear") == 0 || strcmp(sp->valuestring, "log") == 0)))
        dp_errors_add(e, "/omega/spacing", "must be \"linear\" or \"log\"");
    r->log_spacing = sp && cJSON_IsString(sp) && strcmp(sp->valuestring, "log") == 0;
    if (ok && r->to < r->from)
        dp_errors_add(e, "/omega/to", "the range is reversed: to = %g is below from = %g", r->to, r->from);
    else if (ok && r->to == r->from && r->points > 1)
        dp_errors_add(e, "/omega/to", "the range is empty (from = to) but %ld points were asked for", r->points);
    if (ok && r->log_spacing && r->from <= 0)
        dp_errors_add(e, "/omega/from", "must be > 0 with \"spacing\": \"log\"");
}


/* The whole request; M, K, C assembled when there are no field errors. */
static int parse_request(const char *body, size_t len, int response, request *r, dp_errors *e)
{
    static const char *const keys[] = { "model", "damping", "force_node", "response_node", "omega", "initial",
                                        "solver", "output", NULL };
    memset(r, 0, sizeof *r);
    size_t before = e->n + e->dropped;
    cJSON *doc;
    int read = dp_body_read(body, len, e, &doc);
    if (doc == NULL)
        return read;
    check_keys(doc, "", keys, "model, damping, force_node, response_node, omega (initial, solver, output ignored)", e);
    parse_model(doc, r, e);
    parse_damping(doc, r, e);
    if (response && r->net.n > 0) {
        get_index(doc, "", "force_node", r->net.n, &r->force_node, e);
        get_index(doc, "", "response_node", r->net.n, &r->response_node, e);
        parse_range(doc, r, e);
    }
    cJSON_Delete(doc);
    if (e->n + e->dropped > before || r->net.n == 0)
        return e->n + e->dropped > before ? DP_EINVAL : DP_ENOMEM;
    size_t n = r->net.n;
    r->M = malloc(n * n * sizeof *r->M);
    r->K = malloc(n * n * sizeof *r->K);
    r->C = malloc(n * n * sizeof *r->C);
    if (!r->M || !r->K || !r->C)
        return DP_ENOMEM;
    dp_network_linear_parts(&r->net, r->M, r->K, r->C);
    for (size_t k = 0; k < n * n; k++)
        r->C[k] += r->alpha * r->M[k] + r->beta * r->K[k];
    return DP_OK;
}

/* ---- writing ---------------------------------------------------------------------------------------- */

static int put(dp_buf *b, const char *s)
{
    return dp_buf_append(b, s, strlen(s));
}

/* ",key:number" (no comma when key starts with '{' context: pass first) ; NaN and infinities as null. */
static int put_num(dp_buf *b, const char *key, double x)
{
    char t[96];
    int n = key ? snprintf(t, 48, "\"%s\":", key) : 0;
    if (n < 0 || n >= 48)
        return DP_ENOMEM;
    if (!isfinite(x))
        return dp_buf_append(b, t, (size_t)n) ? DP_ENOMEM : put(b, "null");
    return dp_buf_append(b, t, (size_t)n + dp_format_double(t + n, x));
}

static int put_left_out(dp_buf *b, const request *r)
{
    size_t *idx = malloc((r->net.nel ? r->net.nel : 1) * sizeof *idx);
    if (idx == NULL)
        return DP_ENOMEM;
    size_t m = dp_network_nonlinear_elements(&r->net, idx);
    int s = put(b, "\"left_out\":[");
    for (size_t k = 0; k < m && s == DP_OK; k++) {
        char t[32];
        snprintf(t, sizeof t, "%s%zu", k ? "," : "", idx[k]);
        s = put(b, t);
    }
    free(idx);
    return s ? s : put(b, "]");
}

static int put_mode(dp_buf *b, const dp_modes *md, size_t k)
{
    size_t n = md->n;
    double w = md->rigid[k] ? 0 : sqrt(md->lambda[k]);
    char t[64];
    snprintf(t, sizeof t, "%s{\"mode\":%zu,", k ? ",\n" : "", k);
    int s = put(b, t);
    s = s ? s : put_num(b, "omega", w);
    s = s ? s : put(b, ",");
    s = s ? s : put_num(b, "frequency", w / (2 * M_PI));
    s = s ? s : put(b, ",");
    s = s ? s : put_num(b, "period", md->rigid[k] ? NAN : 2 * M_PI / w);
    s = s ? s : put(b, md->rigid[k] ? ",\"rigid\":true," : ",\"rigid\":false,");
    s = s ? s : put_num(b, "damping_ratio", md->modal_damping[k]);
    s = s ? s : put(b, ",");
    s = s ? s : put_num(b, "participation", md->participation[k]);
    s = s ? s : put(b, ",");
    s = s ? s : put_num(b, "effective_mass", md->participation[k] * md->participation[k]);
    s = s ? s : put(b, ",\"shape\":[");
    for (size_t i = 0; i < n && s == DP_OK; i++) {
        s = i ? put(b, ",") : DP_OK;
        s = s ? s : put_num(b, NULL, md->shape[k * n + i]);
    }
    return s ? s : put(b, "]}");
}

static int put_damped(dp_buf *b, const dp_modes *md)
{
    int s = put(b, md->proportional ? ",\"proportional_damping\":true" : ",\"proportional_damping\":false");
    s = s ? s : put(b, ",\"damped\":[");
    for (size_t k = 0; k < md->ndamped && s == DP_OK; k++) {
        const dp_damped_eig *z = &md->eig[k];
        s = put(b, k ? ",\n{" : "{");
        s = s ? s : put_num(b, "re", z->re);
        s = s ? s : put(b, ",");
        s = s ? s : put_num(b, "im", z->im);
        s = s ? s : put(b, ",");
        s = s ? s : put_num(b, "omega_n", hypot(z->re, z->im));
        s = s ? s : put(b, ",");
        s = s ? s : put_num(b, "damping_ratio", z->damping_ratio);
        s = s ? s : put(b, "}");
    }
    return s ? s : put(b, "]");
}

static int modes_json(const request *r, const dp_modes *md, dp_buf *b)
{
    double total = 0;
    for (size_t k = 0; k < md->n * md->n; k++)
        total += r->M[k];
    char t[96];
    snprintf(t, sizeof t, "{\"nodes\":%zu,\"method\":\"%s\",", md->n, md->tridiagonal ? "tridiagonal" : "dense");
    int s = put(b, t);
    s = s ? s : put_num(b, "total_mass", total);
    s = s ? s : put(b, ",");
    s = s ? s : put_left_out(b, r);
    s = s ? s : put(b, ",\"modes\":[\n");
    for (size_t k = 0; k < md->n && s == DP_OK; k++)
        s = put_mode(b, md, k);
    s = s ? s : put(b, "]");
    s = s || !md->damped ? s : put_damped(b, md);
    return s ? s : put(b, "}\n");
}

static int solve_modes(request *r, dp_modes *md, dp_errors *e)
{
    int damped = 0;
    for (size_t k = 0; k < r->net.n * r->net.n; k++)
        damped |= r->C[k] != 0;
    return dp_modes_solve(r->net.n, r->M, r->K, damped ? r->C : NULL, r->pM, r->pK, r->pC, md, e);
}

int dp_modes_respond(const char *body, size_t len, dp_buf *out, dp_errors *errs)
{
    request r;
    dp_modes md = { 0 };
    size_t mark = out->len;
    int s = parse_request(body, len, 0, &r, errs);
    s = s ? s : solve_modes(&r, &md, errs);
    s = s ? s : modes_json(&r, &md, out);
    if (s != DP_OK)
        out->len = mark;
    dp_modes_free(&md);
    request_clear(&r);
    return s;
}

/* ---- the response curve ------------------------------------------------------------------------------- */

static int put_list(dp_buf *b, const char *key, const double *w, const size_t *mode, size_t m)
{
    char t[64];
    snprintf(t, sizeof t, ",\"%s\":[", key);
    int s = put(b, t);
    for (size_t k = 0; k < m && s == DP_OK; k++) {
        s = put(b, k ? ",{" : "{");
        s = s ? s : put_num(b, "omega", w[k]);
        s = s ? s : put(b, ",");
        s = s ? s : put_num(b, "frequency", w[k] / (2 * M_PI));
        if (mode) {
            snprintf(t, sizeof t, ",\"mode\":%zu", mode[k]);
            s = s ? s : put(b, t);
        }
        s = s ? s : put(b, "}");
    }
    return s ? s : put(b, "]");
}

/* The head: everything but the rows, as members of one object (no closing brace). */
static int response_head(const request *r, const dp_modes *md, const dp_response *rs, dp_buf *b)
{
    char t[160];
    snprintf(t, sizeof t, "\"force_node\":%ld,\"response_node\":%ld,\"method\":\"%s\",\"omega\":{", r->force_node,
             r->response_node, md->damped && !md->proportional ? "direct" : "modal");
    int s = put(b, t);
    s = s ? s : put_num(b, "from", r->from);
    s = s ? s : put(b, ",");
    s = s ? s : put_num(b, "to", r->to);
    snprintf(t, sizeof t, ",\"points\":%ld,\"spacing\":\"%s\"},", r->points, r->log_spacing ? "log" : "linear");
    s = s ? s : put(b, t);
    s = s ? s : put_left_out(b, r);
    s = s ? s : put_list(b, "resonances", rs->resonance, rs->resonance_mode, rs->nres);
    return s ? s : put_list(b, "antiresonances", rs->antiresonance, NULL, rs->nanti);
}

static int put_point(dp_buf *b, const dp_response_point *p, int format, int first)
{
    if (format == DP_FORMAT_CSV) {
        char t[112];
        size_t n = dp_format_double(t, p->omega);
        t[n++] = ',';
        if (isfinite(p->magnitude)) {
            n += dp_format_double(t + n, p->magnitude);
            t[n++] = ',';
            n += dp_format_double(t + n, p->phase);
        } else
            t[n++] = ',';
        t[n++] = '\n';
        return dp_buf_append(b, t, n);
    }
    int s = put(b, format == DP_FORMAT_NDJSON ? "{\"type\":\"point\"," : first ? "{" : ",\n{");
    s = s ? s : put_num(b, "omega", p->omega);
    s = s ? s : put(b, ",");
    s = s ? s : put_num(b, "magnitude", p->magnitude);
    s = s ? s : put(b, ",");
    s = s ? s : put_num(b, "phase", p->phase);
    return s ? s : put(b, format == DP_FORMAT_NDJSON ? "}\n" : "}");
}

static int response_write(const request *r, const dp_modes *md, const dp_response *rs, int format, dp_buf *b)
{
    int s = DP_OK;
    if (format == DP_FORMAT_CSV)
        s = put(b, "omega,magnitude,phase\n");
    else {
        s = put(b, format == DP_FORMAT_NDJSON ? "{\"type\":\"meta\"," : "{");
        s = s ? s : response_head(r, md, rs, b);
        s = s ? s : put(b, format == DP_FORMAT_NDJSON ? "}\n" : ",\"rows\":[\n");
    }
    for (size_t k = 0; k < rs->npoints && s == DP_OK; k++)
        s = put_point(b, &rs->point[k], format, k == 0);
    if (s == DP_OK && format == DP_FORMAT_JSON)
        s = put(b, "]}\n");
    return s;
}

int dp_response_respond(const char *body, size_t len, int format, dp_buf *out, dp_errors *errs)
{
    request r;
    dp_modes md = { 0 };
    dp_response rs = { 0 };
    size_t mark = out->len;
    int s = parse_request(body, len, 1, &r, errs);
    s = s ? s : solve_modes(&r, &md, errs);
    if (s == DP_OK) {
        s = dp_response_solve(r.net.n, r.M, r.K, r.C, &md, (size_t)r.force_node, (size_t)r.response_node, r.from,
                              r.to, (size_t)r.points, r.log_spacing, &rs);
        if (s == DP_ELIMIT)
            dp_errors_add(errs, "/omega/points", "with non-proportional damping each point is a complex solve of "
                          "%zu nodes; ask for fewer points (at most about 2e10 / n^3)", r.net.n);
        else if (s == DP_EINVAL)
            dp_errors_add(errs, "/omega", "not a valid range");
    }
    s = s ? s : response_write(&r, &md, &rs, format, out);
    if (s != DP_OK)
        out->len = mark;
    dp_response_free(&rs);
    dp_modes_free(&md);
    request_clear(&r);
    return s;
}
