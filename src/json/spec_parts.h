/* src/json/spec_parts.h - internal: the parts of a simulation spec document (dp_spec_parse, spec_json.c)
 * that live in files of their own, and what they share with it:
 *   laws_json.c        springs, dampers, forcings, contacts, graph points, and the tagged-object table
 *                      ({"law": name, params...}) they are read by;
 *   network_json.c     a network of masses and elements (also read by modes_json.c for /v1/modes and
 *                      /v1/response, so a network is parsed by one parser);
 *   lcs_json.c         a linear complementarity system;
 *   right_hand_json.c  the right-hand friction models.
 * Each reads with the walker (walk.h) and writes into the dp_spec being built. spec_json.c calls into them,
 * they never into it.
 */
#ifndef DASHPOT_JSON_SPEC_PARTS_H
#define DASHPOT_JSON_SPEC_PARTS_H

#include <stddef.h>

#include "dashpot/json.h"
#include "walk.h"

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

#define NUM(st, field, r, req) { #field, offsetof(st, field), &(r), (req) }

/* ---- laws_json.c ---- */

/* Object o whose member `tag` picks one of `vs` (nv of them; `def` when absent, < 0: required): its keys
 * checked (tag, the variant's params and extras, `common`), its params stored into `base`; the variant, or
 * NULL when o is no object or the tag is bad (its other members are then not checked). */
const variant *js_parse_tagged(ctx *c, const cJSON *o, const at *ptr, const char *tag, int def,
                               const variant *vs, size_t nv, const char *const *common, void *base);

/* o["points"] into new arrays *y, *f of *n entries (caller frees them, also on failure); 1 when the list is
 * valid. A table (strictly increasing t) needs >= 1 point, a graph >= 2. */
int js_parse_points(ctx *c, const cJSON *o, const at *ptr, const char *yname, int table, size_t *n,
                    double **y, double **f);

/* A law table's row (dashpot/model.h) as a variant: its members with their bounds, "points" for a user graph;
 * and the optional members that o leaves out set to their defaults. */
void js_law_variant(const dp_law_row *row, variant *v);
void js_law_defaults(const dp_law_row *row, const cJSON *o, void *base);

/* o["points"] as a user graph into g (raw when c->lenient). */
void js_parse_graph(ctx *c, const cJSON *o, const at *ptr, const char *yname, dp_graph *g);

void js_parse_spring(ctx *c, const cJSON *o, const at *ptr, dp_spring *s);
void js_parse_damper(ctx *c, const cJSON *o, const at *ptr, dp_damper *d);

/* A forcing at nesting `depth` (the model's own is 1); _with: its object may also hold the members `common`
 * (a network load's "node"), read by its caller. */
void js_parse_forcing(ctx *c, const cJSON *o, const at *ptr, dp_forcing *f, int depth);
void js_parse_forcing_with(ctx *c, const cJSON *o, const at *ptr, dp_forcing *f, int depth,
                           const char *const *common);

void js_parse_contact(ctx *c, const cJSON *o, const at *ptr, dp_contact *ct);

/* ---- network_json.c ---- */

/* Whether a model object is a network document ("masses" or "mass_matrix"). */
int js_is_network(const cJSON *o);

/* The network model o (an object) into s->net, with s->x0v and s->v0v sized for its nodes. */
void js_parse_network(ctx *c, const cJSON *o, const at *ptr, dp_spec *s);

/* "initial": {"x": [n], "v": [n]} of a network. */
void js_parse_network_initial(ctx *c, const cJSON *o, const at *ptr, dp_spec *s);

/* output.nodes / output.elements: indices into [0, n) (networks only). */
void js_parse_columns(ctx *c, const cJSON *o, const at *ptr, const char *key, const char *noun,
                      const dp_spec *s, size_t n, size_t **out, size_t *count);

/* output.quakes: a boolean, for networks only (the rules check the network has friction). */
void js_parse_quakes(ctx *c, const cJSON *o, const at *ptr, dp_spec *s);

/* ---- lcs_json.c ---- */

int js_is_lcs(const cJSON *o);
void js_parse_lcs(ctx *c, const cJSON *o, const at *ptr, dp_spec *s);
void js_parse_lcs_initial(ctx *c, const cJSON *o, const at *ptr, dp_spec *s);

/* ---- right_hand_json.c ---- */

int js_is_right_hand(const cJSON *o);
void js_parse_right_hand(ctx *c, const cJSON *o, const at *ptr, dp_spec *s);
void js_parse_right_hand_initial(ctx *c, const cJSON *o, const at *ptr, dp_spec *s);

/* /v1/wellposedness for a right-hand model: parsed as strictly as a run's, then the theorems at the initial
 * state. */
int js_right_hand_wellposedness(ctx *c, const cJSON *root, const cJSON *model, const at *mp, dp_wp_report *rep);

#endif
