/* src/json/network_json.c - the network document (docs/systems.md §1): masses or a mass matrix, optional
 * stiffness and damping matrices, elements with their ends and the one-mass laws, loads per node, array
 * initial states, and the columns to write.
 *
 * Its own file because every route that takes a network reads it here: simulate and wellposedness (through
 * spec_json.c) and the linear analyses (modes_json.c); an element's spring, damper and contact are read by
 * the code that reads the one-mass ones (laws_json.c). So a network is accepted or refused alike everywhere,
 * with one list of law names.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "spec_parts.h"

static const range INDEX_ANY = { 0, 9007199254740992.0, 0, " >= 0" };

/* An integer index of a node or an element (`noun`) in [0, n). */
static int parse_index(ctx *c, const cJSON *v, const at *p, size_t n, const char *noun, size_t *out)
{
    double x;
    if (!jw_check_num(c, v, p, &INDEX_ANY, 1, &x))
        return 0;
    if (!(x < (double)n)) {
        jw_fail(c, p, "must be %s index in [0, %zu], got %.0f", noun, n - 1, x);
        return 0;
    }
    *out = (size_t)x;
    return 1;
}

/* Exactly n numbers in r into out. */
static void parse_vector(ctx *c, const cJSON *v, const at *p, size_t n, const range *r, double *out)
{
    char what[64];
    snprintf(what, sizeof what, "an array of %zu numbers (one per node)", n);
    size_t m = cJSON_IsArray(v) ? (size_t)cJSON_GetArraySize(v) : 0;
    if (!cJSON_IsArray(v) || m != n) {
        if (cJSON_IsArray(v))
            jw_fail(c, p, "must be %s, got %zu", what, m);
        else
            jw_fail(c, p, "must be %s, got %s", what, jb_type_name(v));
        return;
    }
    size_t i = 0;
    for (const cJSON *el = v->child; el; el = el->next, i++) {
        const at q = { p, NULL, i };
        jw_check_num(c, el, &q, r, 0, &out[i]);
    }
}

/* An n x n matrix as n rows of n numbers, row-major into a new array. */
static double *parse_matrix(ctx *c, const cJSON *v, const at *p, size_t n)
{
    char what[80];
    snprintf(what, sizeof what, "an array of %zu rows (one per node)", n);
    size_t m = cJSON_IsArray(v) ? (size_t)cJSON_GetArraySize(v) : 0;
    if (!cJSON_IsArray(v) || m != n) {
        if (cJSON_IsArray(v))
            jw_fail(c, p, "must be %s, got %zu", what, m);
        else
            jw_fail(c, p, "must be %s, got %s", what, jb_type_name(v));
        return NULL;
    }
    double *A = calloc(n * n, sizeof *A);
    if (A == NULL) {
        c->nomem = 1;
        return NULL;
    }
    size_t i = 0;
    for (const cJSON *row = v->child; row; row = row->next, i++) {
        const at q = { p, NULL, i };
        parse_vector(c, row, &q, n, &ANY, A + i * n);
    }
    return A;
}

/* An end of an element: "ground" or a node index. */
static void parse_end(ctx *c, const cJSON *v, const at *p, size_t n, long *out)
{
    size_t i;
    if (cJSON_IsString(v) && strcmp(v->valuestring, "ground") == 0)
        *out = DP_GROUND;
    else if (cJSON_IsNumber(v) && parse_index(c, v, p, n, "a node", &i))
        *out = (long)i;
    else if (!cJSON_IsNumber(v))
        jw_fail(c, p, "must be \"ground\" or a node index in [0, %zu], got %s", n - 1, jb_type_name(v));
}

static void parse_element(ctx *c, const cJSON *o, const at *ptr, size_t n, dp_element *e)
{
    static const char *const keys[] = { "between", "spring", "damper", "contact", NULL };
    at p;
    if (!jw_want_object(c, o, ptr))
        return;
    jw_check_keys(c, o, ptr, keys, NULL, NULL);
    const cJSON *b = jw_member(c, o, ptr, "between", "[end, end], each \"ground\" or a node index", &p);
    if (b != NULL) {
        if (!cJSON_IsArray(b) || cJSON_GetArraySize(b) != 2) {
            jw_fail(c, &p, "must be [end, end], each \"ground\" or a node index");
        } else {
            const at q0 = { &p, NULL, 0 }, q1 = { &p, NULL, 1 };
            parse_end(c, b->child, &q0, n, &e->a);
            parse_end(c, b->child->next, &q1, n, &e->b);
        }
    }
    const cJSON *v = jw_member(c, o, ptr, "spring", NULL, &p);
    if (v != NULL)
        e->has_spring = 1, js_parse_spring(c, v, &p, &e->spring);
    if ((v = jw_member(c, o, ptr, "damper", NULL, &p)) != NULL)
        e->has_damper = 1, js_parse_damper(c, v, &p, &e->damper);
    if ((v = jw_member(c, o, ptr, "contact", NULL, &p)) != NULL)
        e->has_contact = 1, js_parse_contact(c, v, &p, &e->contact);
    if (!e->has_spring && !e->has_damper && !e->has_contact)
        jw_fail(c, ptr, "an element needs a \"spring\", a \"damper\" or a \"contact\" (or several)");
}

static void parse_elements(ctx *c, const cJSON *v, const at *p, dp_network *net)
{
    char what[64];
    snprintf(what, sizeof what, "an array of at most %d elements", DP_NETWORK_MAX_ELEMENTS);
    size_t m = cJSON_IsArray(v) ? (size_t)cJSON_GetArraySize(v) : 0;
    if (!cJSON_IsArray(v) || m > DP_NETWORK_MAX_ELEMENTS) {
        if (cJSON_IsArray(v))
            jw_fail(c, p, "must be %s: %zu is over the limit", what, m);
        else
            jw_fail(c, p, "must be %s, got %s", what, jb_type_name(v));
        return;
    }
    if (m == 0)
        return;
    if ((net->el = calloc(m, sizeof *net->el)) == NULL) {
        c->nomem = 1;
        return;
    }
    net->nel = m;
    size_t i = 0;
    for (const cJSON *el = v->child; el; el = el->next, i++) {
        const at q = { p, NULL, i };
        parse_element(c, el, &q, net->n, &net->el[i]);
    }
}

static void parse_node_forcings(ctx *c, const cJSON *v, const at *p, dp_network *net)
{
    static const char *const common[] = { "node", NULL };
    if (cJSON_IsArray(v) && cJSON_GetArraySize(v) == 0)
        return;              /* no loads, as when the member is left out */
    size_t m = jw_array_size(c, v, p, 4 * (size_t)DP_NETWORK_MAX_NODES, "an array of loads {\"node\", \"kind\", ...}");
    if (m == 0)
        return;
    if ((net->force = calloc(m, sizeof *net->force)) == NULL) {
        c->nomem = 1;
        return;
    }
    net->nforce = m;
    size_t i = 0;
    for (const cJSON *el = v->child; el; el = el->next, i++) {
        const at q = { p, NULL, i };
        at pn;
        if (!jw_want_object(c, el, &q))
            continue;
        const cJSON *node = jw_member(c, el, &q, "node", "the index of the node it loads", &pn);
        if (node != NULL)
            parse_index(c, node, &pn, net->n, "a node", &net->force[i].node);
        js_parse_forcing_with(c, el, &q, &net->force[i].f, 1, common);
    }
}

/* The number of nodes: the length of "masses" or the rows of "mass_matrix" (exactly one of them). */
static size_t network_size(ctx *c, const cJSON *o, const at *ptr, dp_network *net)
{
    char what[64];
    snprintf(what, sizeof what, "an array of 1..%d masses", DP_NETWORK_MAX_NODES);
    at p, q;
    const cJSON *m = jw_member(c, o, ptr, "masses", NULL, &p), *mm = jw_member(c, o, ptr, "mass_matrix", NULL, &q);
    if (m != NULL && mm != NULL) {
        jw_fail(c, &q, "give \"masses\" or \"mass_matrix\", not both");
        return 0;
    }
    if (m != NULL) {
        size_t n = jw_array_size(c, m, &p, DP_NETWORK_MAX_NODES, what);
        if (n && (net->mass = calloc(n, sizeof *net->mass)) == NULL)
            c->nomem = 1;
        if (n && net->mass)
            parse_vector(c, m, &p, n, &POSITIVE, net->mass);
        return net->mass ? n : 0;
    }
    snprintf(what, sizeof what, "an array of 1..%d rows", DP_NETWORK_MAX_MATRIX_NODES);
    size_t n = jw_array_size(c, mm, &q, DP_NETWORK_MAX_MATRIX_NODES, what);
    if (n)
        net->M = parse_matrix(c, mm, &q, n);
    return net->M ? n : 0;
}

/* Whether a model object is a network document. */
int js_is_network(const cJSON *o)
{
    return cJSON_IsObject(o) && (cJSON_GetObjectItemCaseSensitive(o, "masses") != NULL ||
                                 cJSON_GetObjectItemCaseSensitive(o, "mass_matrix") != NULL);
}

void js_parse_network(ctx *c, const cJSON *o, const at *ptr, dp_spec *s)
{
    static const char *const keys[] = { "masses", "mass_matrix", "stiffness_matrix", "damping_matrix",
                                        "elements", "forcing", NULL };
    at p;
    jw_check_keys(c, o, ptr, keys, NULL, NULL);
    dp_network *net = calloc(1, sizeof *net);
    if (net == NULL) {
        c->nomem = 1;
        return;
    }
    s->net = net;
    net->n = network_size(c, o, ptr, net);
    if (net->n == 0)
        return;
    char limit[96];
    snprintf(limit, sizeof limit, "full matrices are taken up to %d nodes", DP_NETWORK_MAX_MATRIX_NODES);
    const cJSON *v = jw_member(c, o, ptr, "stiffness_matrix", NULL, &p);
    if (v != NULL && net->n > DP_NETWORK_MAX_MATRIX_NODES)
        jw_fail(c, &p, "%s", limit);
    else if (v != NULL)
        net->K = parse_matrix(c, v, &p, net->n);
    if ((v = jw_member(c, o, ptr, "damping_matrix", NULL, &p)) != NULL && net->n > DP_NETWORK_MAX_MATRIX_NODES)
        jw_fail(c, &p, "%s", limit);
    else if (v != NULL)
        net->C = parse_matrix(c, v, &p, net->n);
    if ((v = jw_member(c, o, ptr, "elements", NULL, &p)) != NULL)
        parse_elements(c, v, &p, net);
    if ((v = jw_member(c, o, ptr, "forcing", NULL, &p)) != NULL)
        parse_node_forcings(c, v, &p, net);
    s->x0v = calloc(net->n, sizeof *s->x0v);
    s->v0v = calloc(net->n, sizeof *s->v0v);
    if (s->x0v == NULL || s->v0v == NULL)
        c->nomem = 1;
}

void js_parse_network_initial(ctx *c, const cJSON *o, const at *ptr, dp_spec *s)
{
    static const char *const keys[] = { "x", "v", NULL };
    at p;
    if (!jw_want_object(c, o, ptr))
        return;
    jw_check_keys(c, o, ptr, keys, NULL, NULL);
    const cJSON *v = jw_member(c, o, ptr, "x", NULL, &p);
    if (v != NULL)
        parse_vector(c, v, &p, s->net->n, &ANY, s->x0v);
    if ((v = jw_member(c, o, ptr, "v", NULL, &p)) != NULL)
        parse_vector(c, v, &p, s->net->n, &ANY, s->v0v);
}

/* output.nodes / output.elements: indices into [0, n) (networks only). */
void js_parse_columns(ctx *c, const cJSON *o, const at *ptr, const char *key, const char *noun,
                          const dp_spec *s, size_t n, size_t **out, size_t *count)
{
    at p;
    const cJSON *v = jw_member(c, o, ptr, key, NULL, &p);
    if (v == NULL)
        return;
    if (s->net == NULL) {
        jw_fail(c, &p, "%s are chosen only for a network (\"masses\" or \"mass_matrix\")", key);
        return;
    }
    if (s->net->n == 0)
        return;              /* the model's own error says why there are no nodes */
    if (n == 0) {
        jw_fail(c, &p, "the network has no %ss to choose", noun + 3);
        return;
    }
    char what[64];
    snprintf(what, sizeof what, "an array of 1..%zu indices", n);
    size_t m = jw_array_size(c, v, &p, n, what);
    if (m == 0)
        return;
    if ((*out = calloc(m, sizeof **out)) == NULL) {
        c->nomem = 1;
        return;
    }
    *count = m;
    size_t i = 0;
    for (const cJSON *el = v->child; el; el = el->next, i++) {
        const at q = { &p, NULL, i };
        parse_index(c, el, &q, n, noun, &(*out)[i]);
    }
}

/* output.quakes: the slip-event catalogue (docs/quakes.md) of a network; a one-mass document has one block
 * and no neighbours, so it is refused rather than ignored. */
void js_parse_quakes(ctx *c, const cJSON *o, const at *ptr, dp_spec *s)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, "quakes");
    if (v == NULL)
        return;
    if (s->net == NULL && cJSON_IsTrue(v)) {
        const at p = { ptr, "quakes", 0 };
        jw_fail(c, &p, "quakes are catalogued only for a network (\"masses\" or \"mass_matrix\") with friction");
        return;
    }
    jw_get_bool(c, o, ptr, "quakes", &s->output.quakes);
}
