/* src/core/analysis/wellposedness.c - existence and uniqueness from the graphs' own properties (docs/mathematics.md §5).
 *
 * (PC), linear spring: Pražák & Rajagopal 2016, Theorem 3 gives existence when A is maximal monotone (6)-(7), coercive (8),
 * gamma continuous with linear growth (5) and F in L^2 (10); Theorem 2 adds uniqueness when gamma is
 * Lipschitz (Babováková 2012, Theorems 3.3, 3.2). (PI), spring and damper as x = f(F_s), x' = g(F_d): Babováková 2012
 * Theorem 2.1 gives existence for continuous non-decreasing f, g with f(0) = g(0) = 0 and the growth
 * (2.6)-(2.7); Theorem 2.2 uniqueness for a constant load (piecewise-linear f meets its structure).
 * Every failed hypothesis comes with a witness a person can check by hand.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/wellposedness.h"

/* A graph built on the stack for laws whose graph the model does not store whole (viscous parts). */
#define LOCAL_MAX 2
typedef struct local_graph { dp_graph g; double y[LOCAL_MAX], f[LOCAL_MAX]; } local_graph;

/* The damper's whole graph A = (v - v_b, F_c): its graph with its viscous part c v added, when it has one
 * (linear, Bingham). NULL for a viscous law whose graph has more vertices than the stack copy holds (no law
 * of the table: the table's test checks it). */
static const dp_graph *damper_graph(const dp_damper *d, local_graph *l)
{
    const dp_graph *g = &d->graph;
    if (!dp_damper_has_viscous(d))
        return g;
    if (g->n > LOCAL_MAX)
        return NULL;
    double c = dp_damper_viscous(d);
    for (size_t i = 0; i < g->n; i++)
        l->y[i] = g->y[i], l->f[i] = g->f[i] + c * g->y[i];
    l->g = (dp_graph){ .n = g->n, .y = l->y, .f = l->f, .left = { g->left[0], g->left[1] + c * g->left[0] },
                       .right = { g->right[0], g->right[1] + c * g->right[0] } };
    return &l->g;
}

static const char *const TOO_BIG = "not checked: a viscous part on a graph of more than two vertices";

static void add_check(dp_wp_report *r, const char *name, int holds, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* Copies s into out[0..cap) as snprintf(out, cap, "%s", s) would, cut short the same way, without printf:
 * the report is written for every run's meta line. */
static void text(char *out, size_t cap, const char *s)
{
    size_t n = strlen(s);
    n = n < cap ? n : cap - 1;
    memcpy(out, s, n);
    out[n] = '\0';
}

static void add_check(dp_wp_report *r, const char *name, int holds, const char *fmt, ...)
{
    if (r->nchecks == DP_WP_MAX_CHECKS)
        return;
    dp_wp_check *c = &r->check[r->nchecks++];
    c->name = name;
    c->holds = holds;
    va_list ap;
    va_start(ap, fmt);
    if (strcmp(fmt, "%s") == 0)              /* most details: a text made elsewhere, or a fixed one */
        text(c->detail, sizeof c->detail, va_arg(ap, const char *));
    else if (strchr(fmt, '%') == NULL)
        text(c->detail, sizeof c->detail, fmt);
    else
        vsnprintf(c->detail, sizeof c->detail, fmt, ap);
    va_end(ap);
}

/* x with the fewest significant digits that read back as x (0.1, not 0.10000000000000001), as every other
 * number dashpot prints. */
static void shortest(char *out, size_t cap, double x)
{
    for (int digits = 1; digits <= 17; digits++) {
        snprintf(out, cap, "%.*g", digits, x);
        if (strtod(out, NULL) == x)
            return;
    }
}

/* The same as a value, for "%s" in a witness's format: N(x) lives until the end of the full expression
 * (C11 6.2.4p8, a temporary with an array member). */
typedef struct number_text { char s[32]; } number_text;

static number_text number(double x)
{
    number_text t;
    shortest(t.s, sizeof t.s, x);
    return t;
}
#define N(x) (number(x).s)

/* prefix + x, shortest, as a check's detail. Integers below 10^15 (what k and most constants are) are
 * written by hand, the same digits; the rest by shortest(). */

static void add_number(dp_wp_report *r, const char *name, int holds, const char *prefix, double x)
{
    char t[DP_WP_TEXT];
    size_t n = strlen(prefix);
    memcpy(t, prefix, n);
    if (x == floor(x) && fabs(x) < 1e15) {
        char d[24], *p = d + sizeof d;
        unsigned long long u = (unsigned long long)fabs(x);
        *--p = '\0';
        do
            *--p = (char)('0' + u % 10);
        while ((u /= 10) != 0);
        if (signbit(x))
            *--p = '-'; /* -0 too, as printf writes it */
        memcpy(t + n, p, (size_t)(d + sizeof d - p));
    } else {
        shortest(t + n, sizeof t - n, x);
    }
    add_check(r, name, holds, "%s", t);
}

/* ---- properties of one graph (NaN rows of a raw graph mark gaps) ------------------------------------- */

/* 1 if monotone; else writes a witness: two points with (y1 - y2)(F1 - F2) < 0. */
static int monotone(const dp_graph *g, const char *yn, char *why, size_t cap)
{
    size_t prev = 0;
    for (size_t i = 1; i < g->n; i++) {
        if (isnan(g->y[i]))
            continue;
        if (g->y[i] < g->y[prev] || g->f[i] < g->f[prev]) {
            for (size_t j = 0; j < i; j++) {
                if (!isnan(g->y[j]) && (g->y[i] - g->y[j]) * (g->f[i] - g->f[j]) < 0) {
                    snprintf(why, cap, "points (%s, F) = (%s, %s) and (%s, %s) have "
                             "(%s1 - %s2)(F1 - F2) < 0", yn, N(g->y[j]), N(g->f[j]), N(g->y[i]), N(g->f[i]), yn, yn);
                    return 0;
                }
            }
            snprintf(why, cap, "the curve turns back at point %zu (%s, %s)", i, N(g->y[i]), N(g->f[i]));
            return 0;
        }
        prev = i;
    }
    snprintf(why, cap, "non-decreasing in both %s and F", yn);
    return 1;
}

/* 1 if the curve has no gap; else the gap as a witness. */
static int no_gap(const dp_graph *g, char *why, size_t cap)
{
    for (size_t i = 1; i + 1 < g->n; i++) {
        if (isnan(g->y[i])) {
            const size_t a = i - 1, b = i + 1;
            snprintf(why, cap, "gap between (%s, %s) and (%s, %s): the point (%s, %s) "
                     "can be added without breaking monotonicity", N(g->y[a]), N(g->f[a]), N(g->y[b]), N(g->f[b]),
                     N((g->y[a] + g->y[b]) / 2), N((g->f[a] + g->f[b]) / 2));
            return 0;
        }
    }
    text(why, cap, "a connected curve unbounded at both ends (rotated by 45 degrees it is the graph of "
         "a 1-Lipschitz function, Pražák & Rajagopal 2016, Lemma 1)");
    return 1;
}

/* Coercivity (8): F v >= c2 F^2 - c3 on A. Bounded parts are absorbed by c3; only the rays matter. */
static int coercive(const dp_graph *g, char *why, size_t cap)
{
    size_t n = g->n;
    if (g->right[0] == 0 || g->left[0] == 0) {
        double y = g->right[0] == 0 ? g->y[n - 1] : g->y[0];
        snprintf(why, cap, "F is unbounded at the fixed velocity v = %s, so F v grows like |F| while "
                 "c2 F^2 grows faster", N(y));
        return 0;
    }
    if ((g->right[1] == 0 && g->f[n - 1] < 0) || (g->left[1] == 0 && g->f[0] > 0)) {
        int r = g->right[1] == 0 && g->f[n - 1] < 0;
        snprintf(why, cap, "F stays %s for every v %s %s, so F v -> -infinity", N(r ? g->f[n - 1] : g->f[0]),
                 r ? ">" : "<", N(r ? g->y[n - 1] : g->y[0]));
        return 0;
    }
    text(why, cap, "F grows at most linearly with v and has the sign of v far out");
    return 1;
}

/* x = f(F): a function of F with the growth (2.6) (c1|u| - c2 <= |f(u)| <= c3(|u| + 1)). */
static int function_of_force(const dp_graph *g, const char *yn, char *why, size_t cap)
{
    for (size_t i = 1; i < g->n; i++)
        if (!isnan(g->y[i]) && !isnan(g->y[i - 1]) && g->f[i] == g->f[i - 1] && g->y[i] > g->y[i - 1]) {
            snprintf(why, cap, "F = %s for every %s in [%s, %s]: %s is not a function of F", N(g->f[i]), yn,
                     N(g->y[i - 1]), N(g->y[i]), yn);
            return 0;
        }
    if (g->right[1] == 0 || g->left[1] == 0) {
        int r = g->right[1] == 0;
        snprintf(why, cap, "F = %s for every %s %s %s: %s is not a function of F", N(r ? g->f[g->n - 1] : g->f[0]),
                 yn, r ? ">" : "<", N(r ? g->y[g->n - 1] : g->y[0]), yn);
        return 0;
    }
    snprintf(why, cap, "%s is a continuous non-decreasing function of F", yn);
    return 1;
}

static int growth(const dp_graph *g, const char *yn, char *why, size_t cap)
{
    if (g->right[0] == 0 || g->left[0] == 0) {
        int r = g->right[0] == 0;
        snprintf(why, cap, "%s = %s for every F %s %s: |f(u)| >= c1|u| - c2 fails as |u| -> infinity", yn,
                 N(r ? g->y[g->n - 1] : g->y[0]), r ? ">=" : "<=", N(r ? g->f[g->n - 1] : g->f[0]));
        return 0;
    }
    snprintf(why, cap, "%s grows linearly in F at both ends", yn);
    return 1;
}

static int through_origin(const dp_graph *g, const char *yn, char *why, size_t cap)
{
    double lo, hi;
    dp_graph_kinematic(g, 0, &lo, &hi);
    if (lo <= 0 && 0 <= hi) {
        snprintf(why, cap, "%s = 0 at F = 0", yn);
        return 1;
    }
    snprintf(why, cap, "at F = 0 the graph has %s in [%s, %s], not 0", yn, N(lo), N(hi));
    return 0;
}

/* ---- the two frameworks ------------------------------------------------------------------------------ */

static void relaxation_checks(dp_wp_report *r, const dp_relaxation *g)
{
    add_check(r, "gamma continuous with |gamma(u)| <= c1(1 + |u|) (Pražák & Rajagopal 2016, (5))", 1, "%s",
              g->kind == DP_RELAX_NONE ? "gamma = 0" : g->kind == DP_RELAX_POWER
              ? "N |u|^(1-1/N) sgn u is continuous for N > 1 and grows sublinearly"
              : "continuous, at most linear growth");
    double L = dp_relaxation_lipschitz(g);
    if (isfinite(L))
        add_number(r, "gamma Lipschitz", 1, "L_gamma = ", L);
    else /* power law: gamma(u)/u = N u^(-1/N) is unbounded near 0 */
        add_check(r, "gamma Lipschitz", 0, "gamma(u)/u = %.6g at u = 1e-6 and %.6g at u = 1e-12: unbounded as "
                  "u -> 0", dp_relaxation_eval(g, 1e-6) / 1e-6, dp_relaxation_eval(g, 1e-12) / 1e-12);
}

static void framework_pc(const dp_model *m, dp_wp_report *r)
{
    char why[DP_WP_TEXT];
    local_graph l;
    const dp_damper *d = &m->damper;
    r->framework = "PC";
    if (dp_spring_plastic(&m->spring))   /* Jenkins: the stop operator (docs/systems.md §3) */
        add_check(r, "elastoplastic spring F_s = k (x - p), |F_s| <= F_y, p' in N(F_s) (Höschl 1983, section 15)",
                  m->spring.k > 0 && m->spring.yield > 0, "k = %s, F_y = %s: with F_s as a state, F_s' in k x' - "
                  "N_[-F_y, F_y](F_s) makes (x', F_s) a maximal monotone evolution inclusion in the energy product "
                  "m v w + F G / k", N(m->spring.k), N(m->spring.yield));
    else
        add_number(r, "linear spring F_s = k x (Pražák & Rajagopal 2016, (1))", 1, "k = ", m->spring.k);
    const dp_graph *A = damper_graph(d, &l);
    if (dp_damper_static(d) > dp_damper_kinetic(d)) {
        add_check(r, "A monotone (Pražák & Rajagopal 2016, (6))", 0, "points (v, F) = (0, %s) and (1, %s) have (v1 - v2)"
                  "(F1 - F2) < 0: the static threshold phi1 exceeds the dynamic phi0", N(dp_damper_static(d)),
                  N(dp_damper_kinetic(d)));
        add_check(r, "A maximal (Pražák & Rajagopal 2016, (7))", 0, "not applicable: A is not monotone");
        add_check(r, "A coercive (Pražák & Rajagopal 2016, (8))", 1, "|F| <= phi1 is bounded");
    } else {
        int mono = A && monotone(A, "v", why, sizeof why);
        if (A == NULL)
            text(why, sizeof why, TOO_BIG);
        add_check(r, "A monotone (Pražák & Rajagopal 2016, (6))", mono, "%s", why);
        if (mono) {
            add_check(r, "A maximal (Pražák & Rajagopal 2016, (7))", no_gap(A, why, sizeof why), "%s", why);
            add_check(r, "A coercive (Pražák & Rajagopal 2016, (8))", coercive(A, why, sizeof why), "%s", why);
        } else {
            add_check(r, "A maximal (Pražák & Rajagopal 2016, (7))", 0, "not applicable: A is not monotone");
            add_check(r, "A coercive (Pražák & Rajagopal 2016, (8))", 0, "not applicable: A is not monotone");
        }
    }
    relaxation_checks(r, &d->relaxation);
    add_check(r, "F in L^2(0, T) (Pražák & Rajagopal 2016, (10))", 1, "every forcing kind is bounded and piecewise continuous");
}

static void framework_pi(const dp_model *m, dp_wp_report *r)
{
    char why[DP_WP_TEXT];
    local_graph l;
    r->framework = "PI";
    const struct { const dp_graph *g; const char *y, *mono, *fn, *zero, *grow; } part[2] = {
        { &m->spring.graph, "x", "f continuous and non-decreasing (Babováková 2012, (PI))", "x = f(F_s) a function",
          "f(0) = 0", "growth of f (Babováková 2012, (2.6))" },
        { damper_graph(&m->damper, &l), "v", "g continuous and non-decreasing (Babováková 2012, (PI))",
          "x' = g(F_d) a function", "g(0) = 0", "growth of g (Babováková 2012, (2.7))" },
    };
    for (int i = 0; i < 2; i++) {
        const dp_graph *g = part[i].g;
        int ok = i == 0 || !(dp_damper_static(&m->damper) > dp_damper_kinetic(&m->damper));
        if (ok && g == NULL)
            ok = 0, text(why, sizeof why, TOO_BIG);
        else if (ok)
            ok = monotone(g, part[i].y, why, sizeof why) && no_gap(g, why, sizeof why);
        else
            text(why, sizeof why, "generalized Coulomb (phi1 > phi0) is not monotone");
        add_check(r, part[i].mono, ok, "%s", why);
        if (!ok)
            continue;
        add_check(r, part[i].fn, function_of_force(g, part[i].y, why, sizeof why), "%s", why);
        add_check(r, part[i].zero, through_origin(g, part[i].y, why, sizeof why), "%s", why);
        add_check(r, part[i].grow, growth(g, part[i].y, why, sizeof why), "%s", why);
    }
    int relaxed = m->damper.relaxation.kind != DP_RELAX_NONE;
    add_check(r, "no relaxation (Babováková 2012, (PI) has none)", !relaxed, "%s", relaxed
              ? "(PI) has no relaxation term; (PC) would cover it but needs a linear spring" : "gamma = 0");
    add_check(r, "F in L^2(0, T) (Babováková 2012, Theorem 2.1)", 1, "every forcing kind is bounded and piecewise "
              "continuous");
}

/* Joins the names of the failing checks (skipping `skip`) into why; returns how many failed. */
static int failures(const dp_wp_report *r, const char *skip, char *why, size_t cap)
{
    int n = 0;
    size_t len = 0;
    why[0] = '\0';
    for (size_t i = 0; i < r->nchecks; i++) {
        if (r->check[i].holds || (skip && strcmp(r->check[i].name, skip) == 0))
            continue;
        if (strncmp(r->check[i].detail, "not applicable", 14) == 0) /* follows from a failure already named */
            continue;
        int w = snprintf(why + len, cap - len, "%s%s", n ? "; " : "fails: ", r->check[i].name);
        len = w > 0 && len + (size_t)w < cap ? len + (size_t)w : cap - 1;
        n++;
    }
    if (n == 0)
        text(why, cap, "all hypotheses hold");
    return n;
}

void dp_wellposedness(const dp_model *m, dp_wp_report *r)
{
    memset(r, 0, sizeof *r);
    int ep = dp_spring_plastic(&m->spring), pc = dp_spring_linear(&m->spring) || ep;
    if (pc)
        framework_pc(m, r);
    else
        framework_pi(m, r);
    double F0;
    int constant = dp_forcing_is_constant(&m->forcing, &F0);
    if (!pc)
        add_check(r, "constant load (Babováková 2012, Theorem 2.2)", constant, "%s", constant ? "F is constant"
                  : "F varies in time: Theorem 2.2 covers constant loads only");
    r->existence.guaranteed = failures(r, pc ? "gamma Lipschitz" : "constant load (Babováková 2012, Theorem 2.2)",
                                       r->existence.reason, sizeof r->existence.reason) == 0;
    r->uniqueness.guaranteed = failures(r, NULL, r->uniqueness.reason, sizeof r->uniqueness.reason) == 0;
    if (ep) {
        static const char *const brezis = "maximal monotone evolution inclusion in (x', F_s) (Brezis 1973, Thm 3.1; "
                                          "the Jenkins element is a stop operator)";
        r->existence.theorem = r->existence.guaranteed ? brezis : NULL;
        r->uniqueness.theorem = r->uniqueness.guaranteed ? brezis : NULL;
    } else if (pc) {
        r->existence.theorem = r->existence.guaranteed ? "Pražák & Rajagopal 2016, Theorem 3 (Babováková 2012, Theorem 3.3)" : NULL;
        r->uniqueness.theorem = r->uniqueness.guaranteed ? "Pražák & Rajagopal 2016, Theorem 2 (Babováková 2012, Theorem 3.2)" : NULL;
    } else {
        r->existence.theorem = r->existence.guaranteed ? "Babováková 2012, Theorem 2.1" : NULL;
        r->uniqueness.theorem = r->uniqueness.guaranteed ? "Babováková 2012, Theorem 2.2" : NULL;
    }
    if (dp_damper_static(&m->damper) > dp_damper_kinetic(&m->damper))
        r->counterexample = "Pražák & Rajagopal 2016, section 4, (24)-(25): with F = phi1 from rest both x = 0 and "
                            "x = (phi1 - phi0)(1 - cos t) solve";
    else if (m->damper.relaxation.kind == DP_RELAX_POWER)
        r->counterexample = "Pražák & Rajagopal 2016, section 4, (26)-(27): with F = phi0 from rest both x = 0 and a solution "
                            "leaving rest like t^(N+1)/(N+1) solve";
}
