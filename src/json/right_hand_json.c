/* src/json/right_hand_json.c - the right-hand friction models (docs/systems.md §6) for dp_spec_parse:
 * {"kind": "piston-hinge", "m1", "m2", "J_C", "r", "alpha", "f1", "f2", "g"} and {"kind": "painleve-rod",
 * "m", "length", "mu", "restitution", "g"}, with "initial": {"x": [q0, q1], "v": [q0', q1']} (the rod may add
 * its end's height and upward rate as a third entry: a rod that starts in the air).
 *
 * Its own file for what only these models have; it reads with the walker (walk.h) so that a bad field gets
 * the same message and pointer as anywhere else. The cross-field rules are in
 * src/core/rules/right_hand_check.c.
 */
#include <stdlib.h>

#include "dashpot/right_hand.h"
#include "spec_parts.h"

static const range ALPHA = { 0, M_PI / 2, 0, " in [0, pi/2] (radians)" };
static const range RESTITUTION = { 0, 1, 0, " in [0, 1]" };

/* A model with a "kind" is one of these (the one-mass model and networks have none). */
int js_is_right_hand(const cJSON *o)
{
    return cJSON_IsObject(o) && cJSON_GetObjectItemCaseSensitive(o, "kind") != NULL;
}

void js_parse_right_hand(ctx *c, const cJSON *o, const at *ptr, dp_spec *s)
{
    static const char *const piston[] = { "kind", "m1", "m2", "J_C", "r", "alpha", "f1", "f2", "g", NULL };
    static const char *const rod[] = { "kind", "m", "length", "mu", "restitution", "g", NULL };
    static const char *const kinds[] = { "piston-hinge", "painleve-rod", NULL };
    int kind = jw_get_enum(c, o, ptr, "kind", kinds, -1);
    if (kind < 0)
        return;
    dp_right_hand_model *m = calloc(1, sizeof *m);
    s->x0v = calloc(3, sizeof *s->x0v);   /* the rod's third entry: its end's height and rate, 0 if not given */
    s->v0v = calloc(3, sizeof *s->v0v);
    if (m == NULL || s->x0v == NULL || s->v0v == NULL) {
        free(m);
        c->nomem = 1;
        return;
    }
    s->rh = m;
    s->solver.kind = DP_SOLVER_RIGHT_HAND;
    s->solver.rtol = 1e-10, s->solver.atol = 1e-12;
    m->g = 9.81;
    if (kind == DP_RIGHT_HAND_ROD) {
        m->kind = DP_RIGHT_HAND_ROD;
        jw_check_keys(c, o, ptr, rod, "kind", "painleve-rod");
        jw_get_num(c, o, ptr, "m", &POSITIVE, 1, 0, &m->m);
        jw_get_num(c, o, ptr, "length", &POSITIVE, 1, 0, &m->length);
        jw_get_num(c, o, ptr, "mu", &NONNEG, 1, 0, &m->mu);
        jw_get_num(c, o, ptr, "restitution", &RESTITUTION, 0, 0, &m->e);
    } else {
        m->kind = DP_RIGHT_HAND_PISTON_HINGE;
        jw_check_keys(c, o, ptr, piston, "kind", "piston-hinge");
        jw_get_num(c, o, ptr, "m1", &POSITIVE, 1, 0, &m->m1);
        jw_get_num(c, o, ptr, "m2", &POSITIVE, 1, 0, &m->m2);
        jw_get_num(c, o, ptr, "J_C", &NONNEG, 0, 0, &m->J_C);
        jw_get_num(c, o, ptr, "r", &POSITIVE, 1, 0, &m->r);
        jw_get_num(c, o, ptr, "alpha", &ALPHA, 1, 0, &m->alpha);
        jw_get_num(c, o, ptr, "f1", &NONNEG, 1, 0, &m->f1);
        jw_get_num(c, o, ptr, "f2", &NONNEG, 0, 0, &m->f2);
    }
    jw_get_num(c, o, ptr, "g", &POSITIVE, 0, 0, &m->g);
}

/* Two finite numbers [q0, q1] into out (or three, when `three` allows: the rod's end off the floor). */
static void parse_pair_of(ctx *c, const cJSON *v, const at *p, const char *names, int three, double *out)
{
    int n = cJSON_IsArray(v) ? cJSON_GetArraySize(v) : -1;
    if (n != 2 && !(three && n == 3)) {
        const char *count = three ? "2 or 3" : "2";
        if (n >= 0)
            jw_fail(c, p, "must be an array of %s numbers %s, got %d", count, names, n);
        else
            jw_fail(c, p, "must be an array of %s numbers %s, got %s", count, names, jb_type_name(v));
        return;
    }
    size_t i = 0;
    for (const cJSON *el = v->child; el; el = el->next, i++) {
        const at q = { p, NULL, i };
        jw_check_num(c, el, &q, &ANY, 0, &out[i]);
    }
}

void js_parse_right_hand_initial(ctx *c, const cJSON *o, const at *ptr, dp_spec *s)
{
    static const char *const keys[] = { "x", "v", NULL };
    at p;
    if (!jw_want_object(c, o, ptr))
        return;
    jw_check_keys(c, o, ptr, keys, NULL, NULL);
    if (s->rh == NULL)
        return;                 /* the model's own error says what is wrong */
    int rod = s->rh->kind == DP_RIGHT_HAND_ROD;
    const cJSON *v = jw_member(c, o, ptr, "x", NULL, &p);
    if (v != NULL)
        parse_pair_of(c, v, &p, rod ? "[x_A, theta] or [x_A, theta, y_A]" : "[x, beta]", rod, s->x0v);
    if ((v = jw_member(c, o, ptr, "v", NULL, &p)) != NULL)
        parse_pair_of(c, v, &p, rod ? "[x_A', theta'] or [x_A', theta', y_A']" : "[x', beta']", rod, s->v0v);
}

/* /v1/wellposedness for these models: parsed as strictly as a run's, then the theorems of Matrosov &
 * Finogenko 1995 at the initial state (src/core/analysis/right_hand_wp.c). */
int js_right_hand_wellposedness(ctx *c, const cJSON *root, const cJSON *model, const at *mp, dp_wp_report *rep)
{
    dp_spec spec;
    dp_spec_init(&spec);
    c->lenient = 0;
    js_parse_right_hand(c, model, mp, &spec);
    at p;
    const cJSON *v = jw_member(c, root, NULL, "initial", NULL, &p);
    if (v != NULL && spec.rh != NULL)
        js_parse_right_hand_initial(c, v, &p, &spec);
    int s = c->nomem ? DP_ENOMEM : c->nerr ? DP_EINVAL : DP_OK;
    if (s == DP_OK) {
        size_t before = c->errs->n + c->errs->dropped;
        dp_right_hand_check(&spec, c->errs);
        s = c->errs->n + c->errs->dropped > before ? DP_EINVAL : DP_OK;
    }
    if (s == DP_OK)
        dp_right_hand_wellposedness(spec.rh, spec.x0v, spec.v0v, rep);
    dp_spec_clear(&spec);
    return s;
}
