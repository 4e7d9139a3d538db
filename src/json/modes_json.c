/* src/json/modes_json.c - POST /v1/modes and /v1/response (and the CLI's modes/response): the request into
 * dense M, K, C (dp_network_linear_parts, so the linear analysis sees exactly the network the solvers see),
 * the options of a linear analysis, and the answers as JSON, NDJSON or CSV.
 *
 * The model is read by the network parser of a simulation (network_json.c, with the body reader and the
 * walker of every route), so a document is accepted or refused here as /v1/simulate would take its model,
 * in the same words; dp_network_linear_parts and dp_network_nonlinear_elements then decide what is linear.
 * What else a linear analysis needs (Rayleigh damping, the nodes and the frequency range of a response) is
 * read here with the same walker.
 *
 * Finite through: M, K and C are checked finite as they are assembled (two finite springs on a node can sum
 * past DBL_MAX, and so can beta K), and every error about scale, here or in the core, names the member
 * that made the row what it is: the mass, the stiffest spring or the most viscous damper on the node, a
 * matrix entry, or Rayleigh's alpha or beta (member_of). The stop hook is handed to the core and polled
 * while the answer is written.
 */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "dashpot/json.h"
#include "dashpot/model.h"
#include "dashpot/modes.h"
#include "dashpot/modes_json.h"
#include "dashpot/network.h"
#include "spec_parts.h"

typedef struct request {
    dp_spec spec;                    /* the network, read as a simulation reads it (spec.net) */
    const dp_network *net;
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
    dp_spec_clear(&r->spec);
    free(r->M);
    free(r->K);
    free(r->C);
}

/* ---- where a row's scale comes from ---------------------------------------------------------------------- */

/* The element member that adds the largest |w| to row `row` of K ('K': a linear spring's k) or of C ('C': a
 * damper's viscous c), into ptr; its |w| (0 when none). */
static double element_member(const dp_network *net, char which, size_t row, char *ptr, size_t cap)
{
    double best = 0;
    for (size_t e = 0; e < net->nel; e++) {
        const dp_element *el = &net->el[e];
        if (el->a != (long)row && el->b != (long)row)
            continue;
        double w = 0;
        const char *key = NULL;
        if (which == 'K' && el->has_spring && dp_spring_linear(&el->spring)) {
            w = dp_spring_stiffness(&el->spring);
            key = "spring/k";
        } else if (which == 'C' && el->has_damper && dp_damper_has_viscous(&el->damper)) {
            const dp_damper_law_info *info = dp_damper_law_info_of(el->damper.law);
            const char *c = info ? dp_law_member_key(&info->row, info->viscous) : NULL;
            w = dp_damper_viscous(&el->damper);
            key = c;
        }
        if (key != NULL && fabs(w) > best) {
            best = fabs(w);
            snprintf(ptr, cap, which == 'K' ? "/model/elements/%zu/%s" : "/model/elements/%zu/damper/%s", e, key);
        }
    }
    return best;
}

/* The member to blame for the scale of row `row` of M, K or C (dp_modes_opts.member): the largest term of
 * the sum that made the diagonal entry. */
static void member_of(void *data, char which, size_t row, char *ptr, size_t cap)
{
    const request *r = data;
    const dp_network *net = r->net;
    size_t n = net->n, ii = row * n + row;
    if (which == 'M') {
        snprintf(ptr, cap, net->mass ? "/model/masses/%zu" : "/model/mass_matrix/%zu/%zu", row, row);
        return;
    }
    const double *own = which == 'K' ? net->K : net->C;
    double best = own ? fabs(own[ii]) : 0;
    if (own)
        snprintf(ptr, cap, which == 'K' ? "/model/stiffness_matrix/%zu/%zu" : "/model/damping_matrix/%zu/%zu", row,
                 row);
    char el[DP_POINTER_MAX];
    double w = element_member(net, which, row, el, sizeof el);
    if (w > best) {
        best = w;
        snprintf(ptr, cap, "%s", el);
    }
    if (which == 'C') { /* Rayleigh's terms, compared by exponent: alpha M or beta K may be what overflows */
        double m = r->M ? fabs(r->M[ii]) : 0, k = r->K ? fabs(r->K[ii]) : 0;
        double la = r->alpha > 0 && m > 0 ? log2(r->alpha) + log2(m) : -INFINITY;
        double lb = r->beta > 0 && k > 0 ? log2(r->beta) + log2(k) : -INFINITY;
        double lbest = best > 0 ? log2(best) : -INFINITY;
        if (la > lbest && la >= lb)
            snprintf(ptr, cap, "/damping/rayleigh/alpha");
        else if (lb > lbest)
            snprintf(ptr, cap, "/damping/rayleigh/beta");
    }
}

/* ---- reading ---------------------------------------------------------------------------------------- */

/* "model": a network, parsed by the network parser of a simulation (network_json.c); the few rules of a
 * linear analysis on top: at most DP_MODES_MAX_NODES nodes, no element joining an end to itself. */
static void parse_model(ctx *c, const cJSON *doc, request *r)
{
    at pm;
    const cJSON *model = jw_member(c, doc, NULL, "model", "a network", &pm);
    if (model == NULL || !jw_want_object(c, model, &pm))
        return;
    if (!js_is_network(model)) {
        jw_fail(c, &pm, "needs exactly one of \"masses\" (a list) and \"mass_matrix\"");
        return;
    }
    size_t before = c->nerr;
    js_parse_network(c, model, &pm, &r->spec);
    const dp_network *net = r->net = r->spec.net;
    if (net == NULL || net->n == 0)
        return;
    int has_masses = cJSON_GetObjectItemCaseSensitive(model, "masses") != NULL;
    r->pM = has_masses ? "/model/masses" : "/model/mass_matrix";
    if (net->n > DP_MODES_MAX_NODES) {
        const at p = { &pm, "masses", 0 };
        jw_fail(c, &p, "a linear analysis takes at most %d nodes, got %zu", DP_MODES_MAX_NODES, net->n);
    }
    for (size_t i = 0; i < net->nel && c->nerr == before; i++)
        if (net->el[i].a == net->el[i].b) {
            const at pe = { &pm, "elements", 0 }, pi = { &pe, NULL, i }, pb = { &pi, "between", 0 };
            jw_fail(c, &pb, "joins an end to itself");
        }
    int els = net->nel > 0;
    r->pK = net->K ? "/model/stiffness_matrix" : els ? "/model/elements" : "/model";
    r->pC = net->C ? "/model/damping_matrix" : els ? "/model/elements" : "/damping/rayleigh";
}

static const range RAYLEIGH = { 0, 1e12, 0, " in [0, 1e12]" };

static void parse_rayleigh(ctx *c, const cJSON *doc, request *r)
{
    static const char *const keys[] = { "rayleigh", NULL }, *const rk[] = { "alpha", "beta", NULL };
    at pd, pr;
    const cJSON *d = jw_member(c, doc, NULL, "damping", NULL, &pd);
    if (d == NULL || !jw_want_object(c, d, &pd))
        return;
    jw_check_keys(c, d, &pd, keys, NULL, NULL);
    const cJSON *ray = jw_member(c, d, &pd, "rayleigh", "an object {\"alpha\": a, \"beta\": b}", &pr);
    if (ray == NULL || !jw_want_object(c, ray, &pr))
        return;
    jw_check_keys(c, ray, &pr, rk, NULL, NULL);
    jw_get_num(c, ray, &pr, "alpha", &RAYLEIGH, 0, 0, &r->alpha);
    jw_get_num(c, ray, &pr, "beta", &RAYLEIGH, 0, 0, &r->beta);
}

/* force_node, response_node: node indices of the network. */
static void parse_nodes(ctx *c, const cJSON *doc, request *r)
{
    char text[48];
    snprintf(text, sizeof text, " in [0, %zu]", r->net->n - 1);
    const range node = { 0, (double)r->net->n - 1, 0, text };
    double x;
    if (jw_get_num(c, doc, NULL, "force_node", &node, 1, 1, &x))
        r->force_node = (long)x;
    if (jw_get_num(c, doc, NULL, "response_node", &node, 1, 1, &x))
        r->response_node = (long)x;
}

static const range OMEGA = { 0, 1e15, 0, " in [0, 1e15]" };
static const range POINTS = { 1, DP_RESPONSE_MAX_POINTS, 0, " in [1, 100000]" };

static void parse_range(ctx *c, const cJSON *doc, request *r)
{
    static const char *const keys[] = { "from", "to", "points", "spacing", NULL };
    static const char *const spacings[] = { "linear", "log", NULL };
    at po;
    const cJSON *o = jw_member(c, doc, NULL, "omega", "{\"from\", \"to\", \"points\"} in rad/s", &po);
    if (o == NULL || !jw_want_object(c, o, &po))
        return;
    jw_check_keys(c, o, &po, keys, NULL, NULL);
    double pts = 0;
    int ok = jw_get_num(c, o, &po, "from", &OMEGA, 1, 0, &r->from);
    ok &= jw_get_num(c, o, &po, "to", &OMEGA, 1, 0, &r->to);
    if (jw_get_num(c, o, &po, "points", &POINTS, 1, 1, &pts))
        r->points = (long)pts;
    r->log_spacing = jw_get_enum(c, o, &po, "spacing", spacings, 0) == 1;
    const at pto = { &po, "to", 0 }, pfrom = { &po, "from", 0 };
    if (ok && r->to < r->from)
        jw_fail(c, &pto, "the range is reversed: to = %g is below from = %g", r->to, r->from);
    else if (ok && r->to == r->from && r->points > 1)
        jw_fail(c, &pto, "the range is empty (from = to) but %ld points were asked for", r->points);
    if (ok && r->log_spacing && r->from <= 0)
        jw_fail(c, &pfrom, "must be > 0 with \"spacing\": \"log\"");
}

/* M, K, C finite as assembled (sums of finite members can overflow), and the total mass with them. */
static int check_assembled(request *r, dp_errors *e)
{
    size_t n = r->net->n;
    const double *const mats[3] = { r->M, r->K, r->C };
    static const char names[3] = { 'M', 'K', 'C' };
    static const char *const words[3] = { "mass", "stiffness", "damping" };
    double total = 0;
    for (size_t k = 0; k < n * n; k++)
        total += r->M[k];
    for (int m = 0; m < 3; m++)
        for (size_t k = 0; k < n * n; k++) {
            if (isfinite(mats[m][k]))
                continue;
            size_t row = k / n, col = k % n;
            size_t at_row = !isfinite(mats[m][col * n + col]) && isfinite(mats[m][row * n + row]) ? col : row;
            char ptr[DP_POINTER_MAX];
            member_of(r, names[m], at_row, ptr, sizeof ptr);
            dp_errors_add(e, ptr, "the %s matrix's entry (%zu, %zu) leaves the double-precision numbers: the %s "
                          "scale overflows (its terms sum past %g)", words[m], row, col, words[m], DBL_MAX);
            return DP_EINVAL;
        }
    if (!isfinite(total)) {
        size_t big = 0;
        for (size_t i = 0; i < n; i++)
            big = r->M[i * n + i] > r->M[big * n + big] ? i : big;
        char ptr[DP_POINTER_MAX];
        member_of(r, 'M', big, ptr, sizeof ptr);
        dp_errors_add(e, ptr, "the total mass leaves the double-precision numbers: the mass scale overflows");
        return DP_EINVAL;
    }
    return DP_OK;
}

/* The whole request, read and walked as every route's body (body.h, walk.h); M, K, C assembled when there
 * are no field errors. */
static int parse_request(const char *body, size_t len, int response, request *r, dp_errors *e)
{
    static const char *const keys[] = { "model", "damping", "force_node", "response_node", "omega", "initial",
                                        "solver", "output", NULL };
    memset(r, 0, sizeof *r);
    dp_spec_init(&r->spec);
    ctx c = { e, 0, 0, 0 };
    int read;
    cJSON *doc = jw_read(&c, body, len, &read);
    if (doc == NULL)
        return read;
    jw_check_keys(&c, doc, NULL, keys, NULL, NULL);
    parse_model(&c, doc, r);
    parse_rayleigh(&c, doc, r);
    if (response && r->net != NULL && r->net->n > 0) {
        parse_nodes(&c, doc, r);
        parse_range(&c, doc, r);
    }
    cJSON_Delete(doc);
    if (c.nomem)
        return DP_ENOMEM;
    if (c.nerr > 0 || r->net == NULL || r->net->n == 0)
        return c.nerr > 0 ? DP_EINVAL : DP_ENOMEM;
    size_t n = r->net->n;
    r->M = malloc(n * n * sizeof *r->M);
    r->K = malloc(n * n * sizeof *r->K);
    r->C = malloc(n * n * sizeof *r->C);
    if (!r->M || !r->K || !r->C)
        return DP_ENOMEM;
    dp_network_linear_parts(r->net, r->M, r->K, r->C);
    for (size_t k = 0; k < n * n; k++)
        r->C[k] += r->alpha * r->M[k] + r->beta * r->K[k];
    return check_assembled(r, e);
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
    size_t *idx = malloc((r->net->nel ? r->net->nel : 1) * sizeof *idx);
    if (idx == NULL)
        return DP_ENOMEM;
    size_t m = dp_network_nonlinear_elements(r->net, idx);
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

static int modes_json(const request *r, const dp_modes *md, const dp_stop *stop, dp_buf *b)
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
    for (size_t k = 0; k < md->n && s == DP_OK; k++) {
        s = put_mode(b, md, k); /* n numbers a mode: 2000 modes of 2000 nodes are 4e6 numbers to write */
        s = s || k % 64 != 63 || !dp_stop_now(stop) ? s : DP_ECANCEL;
    }
    s = s ? s : put(b, "]");
    s = s || !md->damped ? s : put_damped(b, md);
    return s ? s : put(b, "}\n");
}

static int solve_modes(request *r, int response, const dp_stop *stop, dp_modes *md, dp_errors *e)
{
    int damped = 0;
    for (size_t k = 0; k < r->net->n * r->net->n; k++)
        damped |= r->C[k] != 0;
    const dp_modes_opts o = { r->pM, r->pK, r->pC, member_of, r, response, stop };
    return dp_modes_solve_until(r->net->n, r->M, r->K, damped ? r->C : NULL, &o, md, e);
}

static void say_stopped(int s, dp_errors *e)
{
    if (s == DP_ECANCEL)
        dp_errors_add(e, "", "the analysis was stopped before it ended (time limit, client gone or shutdown)");
}

int dp_modes_respond(const char *body, size_t len, dp_buf *out, dp_errors *errs)
{
    return dp_modes_respond_until(body, len, NULL, out, errs);
}

int dp_modes_respond_until(const char *body, size_t len, const dp_stop *stop, dp_buf *out, dp_errors *errs)
{
    request r;
    dp_modes md = { 0 };
    size_t mark = out->len;
    int s = parse_request(body, len, 0, &r, errs);
    s = s || !dp_stop_now(stop) ? s : DP_ECANCEL;
    s = s ? s : solve_modes(&r, 0, stop, &md, errs);
    s = s ? s : modes_json(&r, &md, stop, out);
    say_stopped(s, errs);
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

static int response_write(const request *r, const dp_modes *md, const dp_response *rs, int format,
                          const dp_stop *stop, dp_buf *b)
{
    int s = DP_OK;
    if (format == DP_FORMAT_CSV)
        s = put(b, "omega,magnitude,phase\n");
    else {
        s = put(b, format == DP_FORMAT_NDJSON ? "{\"type\":\"meta\"," : "{");
        s = s ? s : response_head(r, md, rs, b);
        s = s ? s : put(b, format == DP_FORMAT_NDJSON ? "}\n" : ",\"rows\":[\n");
    }
    for (size_t k = 0; k < rs->npoints && s == DP_OK; k++) {
        s = put_point(b, &rs->point[k], format, k == 0);
        s = s || k % 4096 != 4095 || !dp_stop_now(stop) ? s : DP_ECANCEL;
    }
    if (s == DP_OK && format == DP_FORMAT_JSON)
        s = put(b, "]}\n");
    return s;
}

int dp_response_respond(const char *body, size_t len, int format, dp_buf *out, dp_errors *errs)
{
    return dp_response_respond_until(body, len, format, NULL, out, errs);
}

/* The core's failures of a response curve, located. */
static void say_response(int s, request *r, dp_errors *errs)
{
    char ptr[DP_POINTER_MAX];
    if (s == DP_ELIMIT)
        dp_errors_add(errs, "/omega/points", "with non-proportional damping each point is a complex solve of "
                      "%zu nodes; ask for fewer points (at most about 2e10 / n^3)", r->net->n);
    else if (s == DP_EINVAL)
        dp_errors_add(errs, "/omega", "not a valid range");
    else if (s == DP_ENONFINITE) {
        member_of(r, 'M', (size_t)r->force_node, ptr, sizeof ptr);
        dp_errors_add(errs, ptr, "the receptance leaves the double-precision numbers: the mass scale overflows "
                      "(a unit force moves node %ld by more than %g)", r->response_node, DBL_MAX);
    }
}

int dp_response_respond_until(const char *body, size_t len, int format, const dp_stop *stop, dp_buf *out,
                              dp_errors *errs)
{
    request r;
    dp_modes md = { 0 };
    dp_response rs = { 0 };
    size_t mark = out->len;
    int s = parse_request(body, len, 1, &r, errs);
    s = s || !dp_stop_now(stop) ? s : DP_ECANCEL;
    s = s ? s : solve_modes(&r, 1, stop, &md, errs);
    if (s == DP_OK) {
        s = dp_response_solve_until(r.net->n, r.M, r.K, r.C, &md, (size_t)r.force_node, (size_t)r.response_node,
                                    r.from, r.to, (size_t)r.points, r.log_spacing, stop, &rs);
        say_response(s, &r, errs);
        if (s == DP_ENONFINITE)
            s = DP_EINVAL;
    }
    s = s ? s : response_write(&r, &md, &rs, format, stop, out);
    say_stopped(s, errs);
    if (s != DP_OK)
        out->len = mark;
    dp_response_free(&rs);
    dp_modes_free(&md);
    request_clear(&r);
    return s;
}
