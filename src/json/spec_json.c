/* src/json/spec_json.c - dp_spec_parse (json.h): a simulation spec document (README.md, api/openapi.yaml)
 * into a dp_spec, every bad field reported with its JSON Pointer (RFC 6901) and what was expected; and the
 * model of a well-posedness request (dp_model_parse_lenient, dp_wellposedness_parse).
 *
 * Three passes: the body reader (body.c) bounds the nesting and has cJSON build the tree; a walk that never
 * stops at the first error fills the spec (walk.h; the laws, networks, LCSs and right-hand models in the
 * files of spec_parts.h). Only a document without field errors reaches the core's dp_model_prepare and
 * dp_spec_check, whose cross-field rules need the whole spec.
 *
 * This file holds the document itself: its root, the one-mass model, the initial state, the solver and the
 * output; it calls into the parts, they never into it.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "dashpot/json.h"
#include "dashpot/lcs.h"
#include "spec_parts.h"

static const range THETA = { 0.5, 1, 0, " in [0.5, 1]" };
static const range BETA = { 0, 0.5, 1, " in (0, 0.5]" };
static const range GAMMA = { 0.5, 1, 0, " in [0.5, 1]" };
static const range Z_RANGE = { 1, 1000000, 0, " in [1, 1000000]" };
/* 2^53: past it not every integer is a double, and it still fits a long on LP64. */
static const range EVERY = { 1, 9007199254740992.0, 0, " >= 1 (at most 2^53)" };

static void parse_model(ctx *c, const cJSON *o, const at *ptr, dp_model *m)
{
    static const char *const keys[] = { "mass", "spring", "damper", "forcing", "contact", NULL };
    at p;
    if (!jw_want_object(c, o, ptr))
        return;
    jw_check_keys(c, o, ptr, keys, NULL, NULL);
    jw_get_num(c, o, ptr, "mass", &POSITIVE, 1, 0, &m->mass);
    const cJSON *ct = jw_member(c, o, ptr, "contact", NULL, &p);
    if (ct != NULL)
        m->has_contact = 1, js_parse_contact(c, ct, &p, &m->contact);
    const cJSON *v = jw_member(c, o, ptr, "spring", "an object with a \"law\"", &p);
    if (v != NULL)
        js_parse_spring(c, v, &p, &m->spring);
    if ((v = jw_member(c, o, ptr, "damper", "an object with a \"law\"", &p)) != NULL)
        js_parse_damper(c, v, &p, &m->damper);
    if ((v = jw_member(c, o, ptr, "forcing", NULL, &p)) != NULL)
        js_parse_forcing(c, v, &p, &m->forcing, 1);
}

static void parse_initial(ctx *c, const cJSON *o, const at *ptr, dp_spec *s)
{
    static const char *const keys[] = { "x", "v", NULL };
    if (!jw_want_object(c, o, ptr))
        return;
    jw_check_keys(c, o, ptr, keys, NULL, NULL);
    jw_get_num(c, o, ptr, "x", &ANY, 0, 0, &s->x0);
    jw_get_num(c, o, ptr, "v", &ANY, 0, 0, &s->v0);
}

/* The regularized solver's "n" (scheme PC) or "k" (scheme PI): a number > 0 or, for a convergence study, a
 * strictly increasing array of 1..DP_SPEC_MAX_NLIST of them. The other scheme's key is an error. */
static void parse_nlist(ctx *c, const cJSON *o, const at *ptr, dp_solver_spec *s)
{
    int pi = s->scheme == DP_SCHEME_PI;
    const char *key = pi ? "k" : "n", *other = pi ? "n" : "k";
    char what[96], a[32], b[32];
    at pp, *p = &pp;
    if (jw_member(c, o, ptr, other, NULL, p) != NULL)
        jw_fail(c, p, "\"%s\" belongs to scheme %s; scheme %s takes \"%s\"", other, pi ? "PC" : "PI",
             pi ? "PI" : "PC", key);
    const cJSON *v = jw_member(c, o, ptr, key, NULL, p);
    double x;
    if (v == NULL)
        return;
    if (cJSON_IsNumber(v)) {
        if (jw_check_num(c, v, p, &POSITIVE, 0, &x))
            s->n_list[0] = x, s->n_count = 1;
        return;
    }
    int n = cJSON_IsArray(v) ? cJSON_GetArraySize(v) : 0;
    snprintf(what, sizeof what, "a finite number > 0 or an array of 1..%d of them", DP_SPEC_MAX_NLIST);
    if (!cJSON_IsArray(v) || n < 1 || n > DP_SPEC_MAX_NLIST) {
        if (cJSON_IsArray(v))
            jw_fail(c, p, "must be %s, got %d elements", what, n);
        else
            jw_fail(c, p, "must be %s, got %s", what, jb_type_name(v));
        return;
    }
    size_t before = c->nerr, i = 0;
    for (const cJSON *el = v->child; el; el = el->next, i++) {
        const at q = { p, NULL, i };
        if (jw_check_num(c, el, &q, &POSITIVE, 0, &s->n_list[i]) && i > 0 && !(s->n_list[i] > s->n_list[i - 1]))
            jw_fail(c, &q, "must be strictly increasing: %s after %s", jw_num_text(s->n_list[i], a),
                 jw_num_text(s->n_list[i - 1], b));
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
    const variant *v = js_parse_tagged(c, o, ptr, "kind", def, kinds, 5, NULL, s);
    if (v == NULL)
        return;
    s->kind = (dp_solver_kind)v->id;
    int i;
    if (s->kind == DP_SOLVER_REGULARIZED) {
        if ((i = jw_get_enum(c, o, ptr, "scheme", schemes, (int)s->scheme)) >= 0)
            s->scheme = (dp_scheme)i;
        if ((i = jw_get_enum(c, o, ptr, "stepper", steppers, (int)s->stepper)) >= 0)
            s->stepper = (dp_stepper)i;
        parse_nlist(c, o, ptr, s);
    }
    if (s->kind != DP_SOLVER_STICK_SLIP)
        return;
    i = jw_get_enum(c, o, ptr, "variant", variants, (int)s->variant);
    if (i >= 0)
        s->variant = (dp_variant)i;
    if ((i = jw_get_enum(c, o, ptr, "events", events, (int)s->events)) >= 0)
        s->events = (dp_events_mode)i;
    if ((i = jw_get_enum(c, o, ptr, "branch", branches, (int)s->branch)) >= 0)
        s->branch = (dp_branch)i;
    double z;
    if (jw_get_num(c, o, ptr, "Z", &Z_RANGE, 0, 1, &z))
        s->Z = (int)z;
}

/* "max_samples": N, a sample budget for clients that draw rather than store (the browser page asks for about
 * its canvas width): every = ceil(steps / (N - 1)), so floor(steps/every) + 1 samples plus the final one when
 * every does not divide steps come to at most N. Needs the solver parsed first (dt, t_end). */
static const range MAX_SAMPLES = { 2, 9007199254740992.0, 0, " >= 2 (at most 2^53)" };

static void sample_budget(ctx *c, const cJSON *o, const at *ptr, const dp_spec *s, dp_output_spec *out)
{
    double budget;
    if (!jw_get_num(c, o, ptr, "max_samples", &MAX_SAMPLES, 0, 1, &budget))
        return;
    if (cJSON_GetObjectItemCaseSensitive(o, "every") != NULL) {
        at p = { ptr, "max_samples", 0 };
        jw_fail(c, &p, "give either every or max_samples, not both");
        return;
    }
    out->every = dp_spec_every_for(s, budget);
}

static void parse_output(ctx *c, const cJSON *o, const at *ptr, dp_spec *s)
{
    static const char *const keys[] = { "every", "max_samples", "samples", "events", "nodes", "elements", "quakes",
                                        NULL };
    dp_output_spec *out = &s->output;
    if (!jw_want_object(c, o, ptr))
        return;
    jw_check_keys(c, o, ptr, keys, NULL, NULL);
    double every;
    if (jw_get_num(c, o, ptr, "every", &EVERY, 0, 1, &every))
        out->every = (long)every;
    sample_budget(c, o, ptr, s, out);
    jw_get_bool(c, o, ptr, "samples", &out->samples);
    jw_get_bool(c, o, ptr, "events", &out->events);
    js_parse_columns(c, o, ptr, "nodes", "a node", s, s->net ? s->net->n : 0, &out->nodes, &out->nnodes);
    js_parse_columns(c, o, ptr, "elements", "an element", s, s->net ? s->net->nel : 0, &out->elements,
                  &out->nelements);
    js_parse_quakes(c, o, ptr, s);
}

/* A one-mass document with a contact is the network it is: one node of its mass, one element [ground, 0]
 * with its spring, damper and contact, its forcing on node 0 (the laws are moved, not copied). So is one
 * whose graph spring of finite slope, or rope with events located, is stepped below theta = 1
 * (sloped_below_one): the network solver theta-steps the one and locates its kinks (network_smooth.c), and
 * steps the other as a linear spring and the contact u <= L (network_contact.c); the one-mass solver takes
 * backward Euler only for both. */
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
    net->el[0] = (dp_element){ .a = DP_GROUND, .b = 0, .has_spring = 1, .has_damper = 1, .has_contact = s->model.has_contact,
                               .spring = s->model.spring, .damper = s->model.damper, .contact = s->model.contact };
    if (forced)
        net->force[0] = (dp_node_forcing){ .node = 0, .f = s->model.forcing }, net->nforce = 1;
    memset(&s->model.spring, 0, sizeof s->model.spring);
    memset(&s->model.damper, 0, sizeof s->model.damper);
    memset(&s->model.forcing, 0, sizeof s->model.forcing);
    return DP_OK;
}

static int sloped_below_one(const dp_spec *s)
{
    const dp_spring *sp = &s->model.spring;
    int rope = dp_spring_is_split(sp) && s->solver.events == DP_EVENTS_LOCATE;   /* a spring and a contact */
    return s->solver.kind == DP_SOLVER_STICK_SLIP && s->solver.variant == DP_VARIANT_EXACT &&
           s->solver.branch == DP_BRANCH_REST && s->solver.theta != 1 && (dp_spring_sloped_graph(sp) || rope);
}

/* The whole document o (an object: body.c); its own keys are not checked again when keys_checked. */
static void parse_root(ctx *c, const cJSON *o, dp_spec *s, int keys_checked)
{
    static const char *const keys[] = { "model", "initial", "solver", "output", NULL };
    at p;
    if (!keys_checked)
        jw_check_keys(c, o, NULL, keys, NULL, NULL);
    const cJSON *v = jw_member(c, o, NULL, "model", "an object with mass, spring and damper", &p);
    int rh = v != NULL && !js_is_network(v) && js_is_right_hand(v); /* its own initial state, even if the model is bad */
    if (v != NULL && js_is_network(v))
        js_parse_network(c, v, &p, s);
    else if (v != NULL && js_is_lcs(v))
        js_parse_lcs(c, v, &p, s);
    else if (rh)
        js_parse_right_hand(c, v, &p, s);
    else if (v != NULL)
        parse_model(c, v, &p, &s->model);
    if ((v = jw_member(c, o, NULL, "initial", NULL, &p)) != NULL && s->lcs != NULL)
        js_parse_lcs_initial(c, v, &p, s);
    else if (v != NULL && js_is_lcs(cJSON_GetObjectItemCaseSensitive(o, "model")))
        ; /* the LCS model was invalid: its errors are reported, its initial state cannot be sized */
    else if (v != NULL && rh)
        js_parse_right_hand_initial(c, v, &p, s);
    else if (v != NULL && s->net == NULL)
        parse_initial(c, v, &p, s);
    else if (v != NULL && s->net->n > 0)
        js_parse_network_initial(c, v, &p, s);
    if ((v = jw_member(c, o, NULL, "solver", NULL, &p)) != NULL)
        parse_solver(c, v, &p, &s->solver);
    if ((v = jw_member(c, o, NULL, "output", NULL, &p)) != NULL)
        parse_output(c, v, &p, s);
    int as_network = s->model.has_contact || (!rh && s->lcs == NULL && sloped_below_one(s));
    if (s->net == NULL && as_network && !c->nerr && !c->nomem && one_mass_as_network(s) != DP_OK)
        c->nomem = 1;
}

/* ---- the entry points ------------------------------------------------------------------------------ */

/* A spec from the document's tree (read by jw_read into c), then prepared and checked. */
/* Whether the document's object `member` has `key` (the member itself may be absent). */
static int has(const cJSON *root, const char *member, const char *key)
{
    const cJSON *o = cJSON_GetObjectItemCaseSensitive(root, member);
    return cJSON_IsObject(o) && cJSON_GetObjectItemCaseSensitive(o, key) != NULL;
}

/* What the document leaves for dashpot to choose (dp_spec_choose): theta, and every unless max_samples or
 * every is given. */
static unsigned left_out(const cJSON *root)
{
    unsigned which = 0;
    if (!has(root, "solver", "theta"))
        which |= DP_CHOSEN_THETA;
    if (!has(root, "output", "every") && !has(root, "output", "max_samples"))
        which |= DP_CHOSEN_EVERY;
    return which;
}

/* The member of the document a pointer names, or NULL when a part of it is absent (a default). */
static const cJSON *resolve(const cJSON *root, const char *ptr, size_t len)
{
    const cJSON *v = root;
    char tok[DP_POINTER_MAX];
    for (size_t i = 0; i < len && v != NULL;) {
        size_t n = 0;
        for (i++; i < len && ptr[i] != '/'; i++)   /* one reference token, ~1 as / and ~0 as ~ */
            tok[n++] = ptr[i] == '~' && i + 1 < len && (ptr[i + 1] == '0' || ptr[i + 1] == '1')
                       ? (ptr[++i] == '1' ? '/' : '~') : ptr[i];
        tok[n] = 0;
        char *end;
        unsigned long k = strtoul(tok, &end, 10);
        v = cJSON_IsArray(v) ? (n > 0 && *end == 0 ? cJSON_GetArrayItem(v, (int)k) : NULL)
                             : cJSON_GetObjectItemCaseSensitive(v, tok);
    }
    return v;
}

/* The rules speak of the spec, whose defaults the document need not hold (a rod's initial.x): an error at a
 * member the document lacks is moved to its nearest ancestor the document has, and names the default. */
static void point_at_present(const cJSON *root, dp_errors *e, size_t from)
{
    for (size_t i = from; i < e->n; i++) {
        dp_error *it = &e->item[i];
        size_t len = strlen(it->pointer), cut = len;
        while (cut > 0 && resolve(root, it->pointer, cut) == NULL)
            while (cut > 0 && it->pointer[--cut] != '/')
                ;
        if (cut == len)
            continue;
        size_t m = strlen(it->message);
        snprintf(it->message + m, sizeof it->message - m, " (%s is absent: its default)", it->pointer);
        it->pointer[cut] = 0;
    }
}

static int spec_from_tree(ctx *c, const cJSON *root, double max_steps, dp_spec *spec, int keys_checked)
{
    dp_errors *errs = c->errs;
    parse_root(c, root, spec, keys_checked);
    if (c->nomem)
        return DP_ENOMEM;
    if (c->nerr > 0)
        return DP_EINVAL;
    dp_spec_choose(spec, left_out(root));
    int s = spec->rh ? DP_OK : spec->net ? dp_network_prepare(spec->net) : spec->lcs ? DP_OK : dp_model_prepare(&spec->model);
    if (s == DP_ENOMEM)
        return s;
    if (s != DP_OK) {
        const at model = { NULL, "model", 0 };
        jw_fail(c, &model, "the model's graphs could not be built (%s)", dp_strerror(s));
        return DP_EINVAL;
    }
    /* DP_SPEC_MAX_STEPS is a hard ceiling; front ends may only lower it. */
    if (!(max_steps > 0) || max_steps > DP_SPEC_MAX_STEPS)
        max_steps = DP_SPEC_MAX_STEPS;
    size_t before = errs->n;
    int st = dp_spec_check(spec, max_steps, errs);
    point_at_present(root, errs, before);
    return st;
}

int dp_spec_parse(const char *text, size_t len, double max_steps, dp_spec *spec, dp_errors *errs)
{
    ctx c = { errs, 0, 0 };
    int read;
    cJSON *root = jw_read(&c, text, len, &read);
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
    jw_check_keys(c, root, NULL, keys, NULL, NULL);
    return jw_member(c, root, NULL, "model", "an object with mass, spring and damper", p);
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
    cJSON *root = jw_read(&c, text, len, &read);
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
    js_parse_network(c, v, p, &spec);
    /* the initial state, where given, is checked against the laws' domains and the contacts (else 0) */
    at pi = { NULL, "initial", 0 };
    const cJSON *init = cJSON_GetObjectItemCaseSensitive(root, "initial");
    if (init != NULL && !c->nerr && spec.net != NULL)
        js_parse_network_initial(c, init, &pi, &spec);
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
    cJSON *root = jw_read(&c, text, len, &read);
    if (root == NULL)
        return read;
    const cJSON *v = model_member(&c, root, &p);
    int s;
    if (v != NULL && js_is_right_hand(v)) {
        s = js_right_hand_wellposedness(&c, root, v, &p, rep);
    } else if (v != NULL && js_is_lcs(v)) {   /* an LCS: checked as a run's spec, its theory from the step's matrix */
        dp_spec spec;
        dp_spec_init(&spec);
        c.lenient = 0;
        s = spec_from_tree(&c, root, 0, &spec, 1);
        s = s == DP_OK ? dp_lcs_wellposedness(&spec, rep) : s;
        dp_spec_clear(&spec);
    } else if (v != NULL && js_is_network(v)) {
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
