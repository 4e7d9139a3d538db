/* src/core/laws/law_table.c - the law table: one entry per spring law and per damper law, with its name, its
 * members, its graph builder and every property the solvers, the rules and the front ends decide by
 * (dashpot/model.h says what each means). It exists so that a law's properties are written once: before it,
 * the same rules ("the viscous part of linear or Bingham", "the closed form applies") were spelled out at each
 * place that needed them, and a new law took the closed-form path of the stick-slip solver unless every one
 * of those places was found.
 *
 * Springs live in the (x, F_s) plane, dampers in the (v - v_b, F_c) plane (docs/mathematics.md §1). A damper's
 * graph holds only the part a solver must treat implicitly as a set: Coulomb's and Bingham's stick interval;
 * a viscous part c stays a number so that the theta-method can weight it (docs/mathematics.md §4).
 */
#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <stddef.h>

#include "dashpot/model.h"
#include "dashpot/status.h"
#include "laws/law_table.h"

/* 0 means "no field": the law's own enum sits there. */
static_assert(offsetof(dp_spring, law) == 0, "dp_law_field 0 must be no member");
static_assert(offsetof(dp_damper, law) == 0, "dp_law_field 0 must be no member");

static const double RIGHT[2] = { 1, 0 };  /* horizontal ray: force constant */
static const double UP[2] = { 0, 1 };     /* vertical ray: force unbounded at a fixed position */

static int line_graph(dp_graph *g, double slope)
{
    double y = 0, f = 0, d[2] = { 1, slope };
    return dp_graph_init(g, 1, &y, &f, d, d);
}

int dp_threshold_graph(dp_graph *g, double phi)
{
    if (phi == 0)
        return line_graph(g, 0);
    double y[2] = { 0, 0 }, f[2] = { -phi, phi };
    return dp_graph_init(g, 2, y, f, RIGHT, RIGHT);
}

/* Babováková 2012, Fig. 1: F_s = k x while slack; at x = L the rope takes any extra tension. */
int dp_rope_graph(dp_graph *g, double k, double length)
{
    double y = length, f = k * length, left[2] = { 1, k };
    return dp_graph_init(g, 1, &y, &f, left, UP);
}

/* ---- springs ------------------------------------------------------------------------------------------ */

static int spring_linear(dp_spring *s)
{
    dp_graph_clear(&s->graph);
    return line_graph(&s->graph, s->k);
}

static int spring_rope(dp_spring *s)
{
    dp_graph_clear(&s->graph);
    return dp_rope_graph(&s->graph, s->k, s->length);
}

static int spring_user(dp_spring *s)
{
    return s->graph.n > 0 ? DP_OK : DP_EINVAL;
}

/* The graph at the initial offset: vertices (p -/+ F_y/k, -/+F_y), horizontal rays (elastoplastic.c moves it). */
static int spring_elastoplastic(dp_spring *s)
{
    dp_graph_clear(&s->graph);
    if (!(s->k > 0 && s->yield > 0 && isfinite(s->offset)))
        return DP_EINVAL;
    double y[2] = { s->offset - s->yield / s->k, s->offset + s->yield / s->k }, f[2] = { -s->yield, s->yield };
    return dp_graph_init(&s->graph, 2, y, f, RIGHT, RIGHT);
}

#define SPRING(f, b, req) { #f, offsetof(dp_spring, f), DP_MEMBER_##b, req, 0 }

const dp_spring_law_info dp_spring_laws[] = {
    [DP_SPRING_LINEAR] = {
        .row = { DP_SPRING_LINEAR, "linear", { SPRING(k, NONNEG, 1) }, NULL },
        .build = spring_linear, .linear = 1, .locate = 1, .locate_network = 1, .elastic = offsetof(dp_spring, k),
    },
    [DP_SPRING_ROPE] = {
        .row = { DP_SPRING_ROPE, "rope", { SPRING(k, NONNEG, 1), SPRING(length, ANY, 1) }, NULL },
        /* on networks with events located: a linear spring and the contact u <= L (network_contact.c) */
        .build = spring_rope, .locate = 1, .locate_network = 1, .x_max = offsetof(dp_spring, length),
        .elastic = offsetof(dp_spring, k),
    },
    [DP_SPRING_GRAPH] = {
        .row = { DP_SPRING_GRAPH, "graph", { { NULL } }, "x" },
        .build = spring_user, .locate = 1,
    },
    [DP_SPRING_ELASTOPLASTIC] = {   /* Höschl 1983 §15; yield and unload located by one mass (event_location.c)
                                     * and by networks (network_events.c: the graph redrawn at each event) */
        .row = { DP_SPRING_ELASTOPLASTIC, "elastoplastic",
                 { SPRING(k, POSITIVE, 1), SPRING(yield, POSITIVE, 1), SPRING(offset, ANY, 0) }, NULL },
        .build = spring_elastoplastic, .plastic = 1, .locate = 1, .locate_network = 1, .elastic = offsetof(dp_spring, k),
    },
};
static_assert(sizeof dp_spring_laws / sizeof dp_spring_laws[0] == DP_SPRING_LAW_COUNT,
              "every spring law has its entry");

/* ---- dampers ------------------------------------------------------------------------------------------ */

static int damper_line(dp_damper *d)        /* none, linear: the viscous part alone, out of the graph */
{
    dp_graph_clear(&d->graph);
    return line_graph(&d->graph, 0);
}

static int damper_coulomb(dp_damper *d)     /* coulomb and generalized-coulomb: the kinetic threshold phi0 */
{
    dp_graph_clear(&d->graph);
    return dp_threshold_graph(&d->graph, d->phi0);
}

static int damper_bingham(dp_damper *d)
{
    dp_graph_clear(&d->graph);
    return dp_threshold_graph(&d->graph, d->tau);
}

static int damper_user(dp_damper *d)
{
    return d->graph.n > 0 ? DP_OK : DP_EINVAL;
}

#define DAMPER(f, b, req) { #f, offsetof(dp_damper, f), DP_MEMBER_##b, req, 0 }
#define FIELD(f) offsetof(dp_damper, f)

/* closed_form: a linear spring with these and no relaxation make each step the soft threshold
 * v+ = v_b + sgn(u) max(|u| - h tau / W, 0) (stick_slip.c); a user graph is stepped by its own pieces. */
const dp_damper_law_info dp_damper_laws[] = {
    [DP_DAMPER_NONE] = {
        .row = { DP_DAMPER_NONE, "none", { { NULL } }, NULL },
        .build = damper_line, .closed_form = 1, .linear = 1, .locate = 1, .analytic = 1,
    },
    [DP_DAMPER_LINEAR] = {
        .row = { DP_DAMPER_LINEAR, "linear", { DAMPER(c, NONNEG, 1) }, NULL },
        .build = damper_line, .viscous = FIELD(c), .closed_form = 1, .linear = 1, .locate = 1,
    },
    [DP_DAMPER_COULOMB] = {         /* Babováková 2012 (C); Pražák & Rajagopal 2016 (9) */
        .row = { DP_DAMPER_COULOMB, "coulomb", { DAMPER(phi0, NONNEG, 1) }, NULL },
        .build = damper_coulomb, .kinetic = FIELD(phi0), .closed_form = 1, .locate = 1, .analytic = 1,
        .thesis = 1,
    },
    [DP_DAMPER_BINGHAM] = {         /* Babováková 2012, Fig. 2: yield stress tau, then viscous c */
        .row = { DP_DAMPER_BINGHAM, "bingham", { DAMPER(tau, NONNEG, 1), DAMPER(c, NONNEG, 1) }, NULL },
        .build = damper_bingham, .viscous = FIELD(c), .kinetic = FIELD(tau), .closed_form = 1, .locate = 1,
    },
    [DP_DAMPER_GENERALIZED_COULOMB] = {   /* Pražák & Rajagopal 2016 §4: static phi1 >= kinetic phi0 */
        .row = { DP_DAMPER_GENERALIZED_COULOMB, "generalized-coulomb",
                 { DAMPER(phi0, NONNEG, 1), DAMPER(phi1, NONNEG, 1) }, NULL },
        .build = damper_coulomb, .kinetic = FIELD(phi0), .static_threshold = FIELD(phi1), .closed_form = 1,
        .locate = 1,
    },
    [DP_DAMPER_GRAPH] = {
        .row = { DP_DAMPER_GRAPH, "graph", { { NULL } }, "v" },
        .build = damper_user, .locate = 1,
    },
};
static_assert(sizeof dp_damper_laws / sizeof dp_damper_laws[0] == DP_DAMPER_LAW_COUNT,
              "every damper law has its entry");

/* ---- reads -------------------------------------------------------------------------------------------- */

const dp_spring_law_info *dp_spring_law_info_of(dp_spring_law law)
{
    return (unsigned)law < DP_SPRING_LAW_COUNT ? &dp_spring_laws[law] : NULL;
}

const dp_damper_law_info *dp_damper_law_info_of(dp_damper_law law)
{
    return (unsigned)law < DP_DAMPER_LAW_COUNT ? &dp_damper_laws[law] : NULL;
}

double dp_law_field_value(const void *base, dp_law_field f)
{
    return *(const double *)((const char *)base + f);
}

double dp_spring_stiffness(const dp_spring *s)
{
    return dp_spring_linear(s) ? s->k : 0;
}

int dp_spring_linear(const dp_spring *s)
{
    const dp_spring_law_info *L = dp_spring_law_info_of(s->law);
    return L && L->linear;
}

int dp_spring_plastic(const dp_spring *s)
{
    const dp_spring_law_info *L = dp_spring_law_info_of(s->law);
    return L && L->plastic;
}

int dp_spring_sloped_graph(const dp_spring *s)
{
    return s->law == DP_SPRING_GRAPH && s->graph.n > 0 && isfinite(dp_graph_lipschitz(&s->graph));
}

/* The vertices of a split graph's sloped part: [*i0, *i1], the last of the leading vertices at a vertical
 * left end and the first of the trailing ones at a vertical right end; 0 if the graph has no vertical
 * piece, or nothing but (its domain a point). */
static int bounded_span(const dp_graph *g, size_t *i0, size_t *i1)
{
    if (g->n < 2)
        return 0;
    int lo = g->left[0] == 0, hi = g->right[0] == 0, inside = 0;
    size_t a = 0, b = g->n - 1;
    while (lo && a + 1 < g->n && g->y[a + 1] == g->y[0])
        a++;
    while (hi && b > 0 && g->y[b - 1] == g->y[g->n - 1])
        b--;
    if (b <= a)
        return 0;
    for (size_t j = a; j < b; j++)
        inside |= !(g->y[j + 1] > g->y[j]);
    if (!(lo || hi || inside))
        return 0;
    *i0 = a, *i1 = b;
    return 1;
}

int dp_spring_bounded_graph(const dp_spring *s, double *lo, double *hi)
{
    size_t a, b;
    if (s->law != DP_SPRING_GRAPH || !bounded_span(&s->graph, &a, &b))
        return 0;
    *lo = s->graph.left[0] == 0 ? s->graph.y[a] : -INFINITY;
    *hi = s->graph.right[0] == 0 ? s->graph.y[b] : INFINITY;
    return 1;
}

size_t dp_spring_graph_jumps(const dp_spring *s, double *y, double *J)
{
    const dp_graph *g = &s->graph;
    size_t a, b, n = 0;
    if (s->law != DP_SPRING_GRAPH || !bounded_span(g, &a, &b))
        return 0;
    for (size_t j = a; j < b; j++)
        if (g->y[j + 1] == g->y[j] && g->f[j + 1] > g->f[j]) {
            if (y)
                y[n] = g->y[j], J[n] = g->f[j + 1] - g->f[j];
            n++;
        }
    return n;
}

int dp_spring_bounded_part(const dp_spring *s, dp_graph *part)
{
    const dp_graph *g = &s->graph;
    size_t a, b;
    if (s->law != DP_SPRING_GRAPH || !bounded_span(g, &a, &b))
        return DP_EINVAL;
    double *y = malloc((b - a + 1) * sizeof *y), *f = malloc((b - a + 1) * sizeof *f), drop = 0;
    if (y == NULL || f == NULL) {
        free(y), free(f);
        return DP_ENOMEM;
    }
    size_t m = 0;
    for (size_t j = a; j <= b; j++) {
        if (m > 0 && g->y[j] == y[m - 1]) {   /* a jump inside: its height leaves the sloped part */
            drop += g->f[j] - g->f[j - 1];
            continue;
        }
        y[m] = g->y[j], f[m] = g->f[j] - drop, m++;
    }
    double left[2] = { g->left[0], g->left[1] }, right[2] = { g->right[0], g->right[1] };
    int st = DP_EINVAL;
    if (m >= 2) {
        if (left[0] == 0)
            left[0] = y[1] - y[0], left[1] = f[1] - f[0];
        if (right[0] == 0)
            right[0] = y[m - 1] - y[m - 2], right[1] = f[m - 1] - f[m - 2];
        st = dp_graph_init(part, m, y, f, left, right);
    }
    free(y), free(f);
    return st;
}

double dp_damper_viscous(const dp_damper *d)
{
    return dp_damper_has_viscous(d) ? dp_law_field_value(d, dp_damper_laws[d->law].viscous) : 0;
}

int dp_damper_has_viscous(const dp_damper *d)
{
    const dp_damper_law_info *L = dp_damper_law_info_of(d->law);
    return L && L->viscous;
}

double dp_damper_kinetic(const dp_damper *d)
{
    const dp_damper_law_info *L = dp_damper_law_info_of(d->law);
    return L && L->kinetic ? dp_law_field_value(d, L->kinetic) : 0;
}

double dp_damper_static(const dp_damper *d)
{
    const dp_damper_law_info *L = dp_damper_law_info_of(d->law);
    return L && L->static_threshold ? dp_law_field_value(d, L->static_threshold) : dp_damper_kinetic(d);
}

int dp_damper_linear(const dp_damper *d)
{
    const dp_damper_law_info *L = dp_damper_law_info_of(d->law);
    return L && L->linear;
}

int dp_damper_closed_form(const dp_damper *d)
{
    const dp_damper_law_info *L = dp_damper_law_info_of(d->law);
    return L && L->closed_form;
}

int dp_damper_static_graph(const dp_damper *d, dp_graph *g)
{
    return dp_threshold_graph(g, dp_damper_static(d));
}

const char *dp_law_member_key(const dp_law_row *row, dp_law_field f)
{
    for (const dp_law_member *m = row->members; f && m->key; m++)
        if (m->offset == f)
            return m->key;
    return NULL;
}

const char *dp_spring_law_name(dp_spring_law law)
{
    const dp_spring_law_info *L = dp_spring_law_info_of(law);
    return L ? L->row.name : "?";
}

const char *dp_damper_law_name(dp_damper_law law)
{
    const dp_damper_law_info *L = dp_damper_law_info_of(law);
    return L ? L->row.name : "?";
}

int dp_spring_is_split(const dp_spring *s)
{
    double lo, hi;
    return s->law == DP_SPRING_ROPE || dp_spring_bounded_graph(s, &lo, &hi);
}
