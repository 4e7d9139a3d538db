/* src/core/solvers/network/network_grounded_chain.c - a network of masses on linear springs and linear
 * dampers whose set-valued laws each tie one node to the ground: rigid contacts (Newton restitution; a stop
 * chain, Moreau 1988, Jean 1999, Siconos' MoreauJeanOSI) and Coulomb dampers on a belt (a friction chain, the
 * Burridge-Knopoff chain of Carlson & Langer 1989), stepped without located events ("events": "none"). Its
 * step is the general network step (network_stepping.c, network_contact.c, network/network_step.c, the
 * elements' forces, phases and stick-slip events of network_stepping.c and network_output.c) written out for
 * such networks at half-bandwidth at most one after the run's own node ordering: the same floating-point
 * operations in the same order, so the same answers bit for bit, without the graphs, the union-find forest,
 * the active-set bookkeeping and the per-element dispatch that make most of a general step's cost.
 *
 * Why it is exact: every set-valued law joins its node to the ground, so the fixed forest is a set of nodes
 * held at their laws' vertices (each its own tree with the ground), the free nodes are singleton trees
 * numbered in node order, and the contracted matrix R is W restricted to the free nodes (tridiagonal, or
 * diagonal where no two free neighbours are coupled). A law is free on one piece of its graph, or fixed at
 * its vertex with its multiplier read off its node's residual: a contact free above its cone's vertex (or on
 * the whole line when it is not armed), a Coulomb damper free on a flat piece +-phi0 of phi0 Sgn(z - v_b) on
 * either side of the belt's speed (Babovakova 2012; Prazak & Rajagopal 2016), both fixed at the vertex with
 * the interval (-inf, 0] or [-phi0, phi0]. That is the primal-dual active-set pass of network_step.c from
 * the previous velocity's assignment, with its forest potentials ((z + 0) - 0, then 0 + pot, then - 0), its
 * rounding tolerance on the multipliers and its +0 and -0 kept. The lean ball (network_contact_lean.c) is the
 * same pass for one node.
 *
 * The held nodes cut R into independent stretches of free nodes: a stretch's couplings to the nodes beyond
 * it are +0 and its right side is never -0, so its factor and both sweeps give the numbers the whole band's
 * give. An update that changes a few laws (many blocks of a long chain stick or slip in one step) is
 * therefore solved again only on the stretches around them, and the factor made again only there.
 *
 * Anything outside this (a NaN, a pass that does not settle in the general path's twelve updates, a pivot
 * that is not positive) hands the step to the general solve itself; a network whose ordering leaves a wider
 * band, or two set-valued laws on one node, runs the general advance.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/band.h"
#include "solvers/network/network_run.h"

/* A set-valued law's state in the step's active-set pass (network_step.c's elem_state), one per entry `act`
 * of the step's problem, in the order of their nodes: free on the piece (lo, hi) of force lam0 (the whole
 * line when not armed), or fixed at the vertex fz with multiplier lam. The law's constants: its force on the
 * piece right and left of its vertex (a contact: +0 right, fixed when its start lies left), and its force
 * interval [flo, fhi] at the vertex with the magnitudes its tolerance adds (aflo, afhi: 0 for an infinite
 * end). */
typedef struct chain_law {
    size_t node, act;
    int up;             /* the law is [ground, node] (z = v), else [node, ground] (z = -v) */
    int cone;           /* a contact: beyond its vertical ray the start is fixed at the vertex */
    int fixed;
    double lo, hi, zref, lam0, fz, lam, lam_err;
    double fr, fl, flo, fhi, aflo, afhi;
} chain_law;

/* An element with a linear part or a set-valued law, for its forces (network_run_element_forces): the
 * others' are +0 throughout. act: its entry in the step's problem, or -1. */
typedef struct chain_element {
    size_t i;
    long a, b, act;
    double k, c, vb;
} chain_element;

/* A Coulomb element's phase to set after each step (network_run_element_phases). */
typedef struct chain_friction {
    size_t i, act;
} chain_friction;

struct network_chain {
    size_t n, nlaw, nlin, nfric;
    chain_law *law;     /* per entry of the step's problem, in node order (one law a node) */
    chain_element *lin; /* the elements with a spring or a damper of nonzero coefficient, or a law */
    chain_friction *fric;
    size_t *changed;    /* per Coulomb element: the elements whose phase a step changed */
    unsigned char *was; /* and their phases before it */
    long *law_at;       /* per node: its law, or -1 */
    unsigned char *held, *fac_held;   /* per node: held to the ground now / in R's factor */
    size_t nfree;       /* the free nodes: the reduced system's unknowns */
    size_t *dirty, ndirty;   /* the nodes whose law the last update changed, or whose hold R's factor lacks */
    size_t *rlo, *rhi;  /* stretches of nodes to assemble, factor and solve again (chain_ranges) */
    unsigned long long handed;   /* steps the general solve decided */
    int factored;       /* L, off hold R's factor for fac_held of W = fac_W built for step fac_h (prepare's
                         * reuse): per free node its pivot and its scaled coupling to the next node */
    double fac_h;
    const double *fac_W;
    double *c, *rhs_eff, *y, *L, *off;   /* per node; y: the reduced right side and solution, by node */
};

/* ---- the active-set pass ------------------------------------------------------------------------------ */

static double chain_rel(const chain_law *k, const double *v)
{
    return k->up ? v[k->node] - 0 : 0 - v[k->node];
}

static void chain_free_on(chain_law *k, double lo, double hi, double lam0, double zref)
{
    k->fixed = 0, k->lo = lo, k->hi = hi, k->lam0 = lam0, k->zref = zref;
}

/* The start assignment at the previous velocity (start_inside_piece, start_lawless, assign_start); 0 when z
 * is not finite (the general path decides). On a flat piece the force is f0 + 0 (y - y0), f0 itself. */
static int chain_start(const dp_network_step_element *e, chain_law *k, double z)
{
    if (!isfinite(z))
        return 0;
    k->lam = k->lam_err = 0;
    if (e->A == NULL) {
        chain_free_on(k, -INFINITY, INFINITY, 0, z);
        return 1;
    }
    double y = z - e->vb;
    if (y > 0)          /* on the right piece: free above its vertex */
        chain_free_on(k, 0 + e->vb, INFINITY, k->fr, z);
    else if (y == 0)    /* on the vertex */
        k->fixed = 1, k->fz = z;
    else if (k->cone)   /* beyond the vertical ray: fixed at the domain's end */
        k->fixed = 1, k->fz = 0 + e->vb;
    else                /* on the left piece: free below its vertex */
        chain_free_on(k, -INFINITY, 0 + e->vb, k->fl, z);
    return 1;
}

/* Node i's part of the assignment's system: held to the ground at its law's vertex (fixed_forest and
 * index_forest: the potential (z + 0) - 0 or (0 - 0) - z, found as 0 + pot, the ground's - 0), or an
 * unknown of its own at potential +0 with its right side (effective_rhs: a free law's g = h (lam0 - slope
 * zref) = h lam0, slope +0 and zref finite, taken from the node's entry for [ground, node], added for [node,
 * ground]: x - +0 = x keeps a -0, x + +0 turns it into +0). Returns whether it is held. */
static int chain_node(const chain_law *k, double rhs, double h, double *c, double *re)
{
    *c = 0, *re = rhs;
    if (k == NULL)
        return 0;
    if (k->fixed) {
        double pot = k->up ? (k->fz + 0) - 0 : (0 - 0) - k->fz;
        *c = (0 + pot) - 0;
        return 1;
    }
    double g = h * k->lam0;
    *re = k->up ? rhs - g : rhs + g;
    return 0;
}

static const chain_law *chain_law_at(const struct network_chain *ch, size_t i)
{
    return ch->law_at[i] >= 0 ? &ch->law[ch->law_at[i]] : NULL;
}

/* The assignment's system in one sweep over the nodes: each node's potential c, right side and whether it is
 * held, and for the free ones the reduced right side y = T^T (rhs_eff - W c) (solve_assignment: W c in
 * dp_band_symv's order, row i's diagonal term plus row i-1's, then row i+1's, lagging a node behind; y from
 * +0, so never -0), kept by node. Returns the number of unknowns; the nodes whose hold differs from R's
 * factor's into ch->dirty; *whole: there is no factor to keep. */
static size_t chain_assemble(struct network_chain *ch, const double *W, size_t p, const double *rhs, double h,
                             int *whole)
{
    size_t n = ch->n, nr = 0;
    double *c = ch->c, *re = ch->rhs_eff, *y = ch->y, carry = 0;
    unsigned char *held = ch->held;
    const chain_law *k = ch->law, *kend = ch->law + ch->nlaw;   /* in node order */
    ch->ndirty = 0;
    for (size_t i = 0; i < n; i++) {
        const chain_law *at = k < kend && k->node == i ? k++ : NULL;
        held[i] = (unsigned char)chain_node(at, rhs[i], h, &c[i], &re[i]);
        nr += !held[i];
        if (held[i] != ch->fac_held[i])
            ch->dirty[ch->ndirty++] = i;
        if (p == 0) {
            if (!held[i])
                y[i] = 0 + (re[i] - W[i] * c[i]);
            continue;
        }
        if (i == 0) {
            carry = W[0] * c[0];
            continue;
        }
        double a = W[2 * (i - 1) + 1], res = carry + a * c[i];   /* row i-1 of W c */
        carry = W[2 * i] * c[i] + a * c[i - 1];
        if (!held[i - 1])
            y[i - 1] = 0 + (re[i - 1] - res);
    }
    if (p == 1 && !held[n - 1])
        y[n - 1] = 0 + (re[n - 1] - carry);
    *whole = !ch->factored;
    return nr;
}

/* The same for nodes lo..hi (their neighbours' potentials as they stand), row i of W c summed as
 * dp_band_symv sums it. */
static void chain_assemble_range(struct network_chain *ch, const double *W, size_t p, const double *rhs, double h,
                                 size_t lo, size_t hi)
{
    size_t n = ch->n;
    double *c = ch->c, *re = ch->rhs_eff;
    for (size_t i = lo; i <= hi; i++)
        ch->held[i] = (unsigned char)chain_node(chain_law_at(ch, i), rhs[i], h, &c[i], &re[i]);
    for (size_t i = lo; i <= hi; i++) {
        if (ch->held[i])
            continue;
        double res;
        if (p == 0)
            res = W[i] * c[i];
        else if (i == 0)
            res = W[0] * c[0] + W[1] * c[1];
        else if (i + 1 < n)
            res = (W[2 * i] * c[i] + W[2 * (i - 1) + 1] * c[i - 1]) + W[2 * i + 1] * c[i + 1];
        else
            res = W[2 * i] * c[i] + W[2 * (i - 1) + 1] * c[i - 1];
        ch->y[i] = 0 + (re[i] - res);
    }
}

/* The held nodes on either side of each node of `list` (sorted), or the chain's ends: the stretch whose free
 * nodes a change at the node couples, with the held nodes whose multipliers they enter. Overlapping
 * stretches merged into ch->rlo, ch->rhi; returns how many. */
static size_t chain_ranges(struct network_chain *ch, const size_t *list, size_t m)
{
    size_t nr = 0;
    for (size_t j = 0; j < m; j++) {
        size_t i = list[j], lo = i, hi = i;
        while (lo > 0 && !(lo < i && ch->held[lo]))
            lo--;
        while (hi + 1 < ch->n && !(hi > i && ch->held[hi]))
            hi++;
        if (nr && lo <= ch->rhi[nr - 1])
            ch->rhi[nr - 1] = hi > ch->rhi[nr - 1] ? hi : ch->rhi[nr - 1];
        else
            ch->rlo[nr] = lo, ch->rhi[nr++] = hi;
    }
    return nr;
}

/* factor_reduced over nodes lo..hi: R = W on the free nodes, factored as base/band.c's bidiagonal Cholesky
 * (GSL's: the pivot's square root, the coupling scaled by its inverse, the next pivot less its square), kept
 * by node. A free node whose neighbour below is held or outside starts afresh: R couples consecutive
 * unknowns with +0 there, whose scaled coupling +0 leaves the next pivot as it is (x + +0 (-1 +0) = x); at
 * half-bandwidth 0 GSL's pivots are the same square roots. 0 when a pivot is not positive. */
static int chain_factor_range(struct network_chain *ch, const double *W, size_t p, size_t lo, size_t hi)
{
    size_t n = ch->n;
    for (size_t i = lo; i <= hi; i++) {
        ch->fac_held[i] = ch->held[i];
        if (ch->held[i])
            continue;
        double d = W[i * (p + 1)];
        if (i > lo && !ch->held[i - 1])
            d += ch->off[i - 1] * (-1.0 * ch->off[i - 1]);
        if (!(d > 0))
            return 0;
        ch->L[i] = sqrt(d);
        double a = p == 1 && i + 1 < n && !ch->held[i + 1] ? W[2 * i + 1] : 0;
        ch->off[i] = a != 0 ? (1.0 / ch->L[i]) * a : 0;
    }
    return 1;
}

/* R's factor for the current hold: kept where it holds (prepare's reuse), made again around the nodes whose
 * hold changed, or throughout. 0 when a pivot is not positive. */
static int chain_factor(struct network_chain *ch, const double *W, size_t p, int whole)
{
    size_t m = whole ? 0 : chain_ranges(ch, ch->dirty, ch->ndirty);
    if (whole || m > ch->n / 8) {
        ch->factored = chain_factor_range(ch, W, p, 0, ch->n - 1);
        return ch->factored;
    }
    for (size_t r = 0; r < m; r++)
        if (!chain_factor_range(ch, W, p, ch->rlo[r], ch->rhi[r]))
            return ch->factored = 0;
    return 1;
}

/* R y = T^T (rhs_eff - W c) over nodes lo..hi by the bidiagonal sweeps (or a diagonal factor's two), the
 * backward one giving v = T y + c node by node on its way. Where a free node's neighbour is held or outside,
 * the coupling is +0 and y is never -0: y - +0 y' = y, so a stretch of free nodes is solved as the whole
 * band solves it. */
static void chain_solve_range(struct network_chain *ch, size_t lo, size_t hi, double *vs)
{
    const double *L = ch->L, *off = ch->off;
    const unsigned char *held = ch->held;
    double *y = ch->y;
    for (size_t i = lo; i <= hi; i++)
        if (!held[i])
            y[i] = i > lo && !held[i - 1] ? (y[i] - off[i - 1] * y[i - 1]) / L[i] : y[i] / L[i];
    for (size_t i = hi + 1; i-- > lo;) {
        if (held[i]) {
            vs[i] = 0 + ch->c[i];
            continue;
        }
        y[i] = i < hi && !held[i + 1] ? (y[i] - off[i] * y[i + 1]) / L[i] : y[i] / L[i];
        vs[i] = y[i] + ch->c[i];
    }
}

/* report() for law k as its state stands: z at the step's end (the vertex's v_b for a fixed law, at rest),
 * the force (the graphs' part lam0 + 0 (z - zref), or the multiplier, plus the relaxation's 0 + 0 (z - z_k)),
 * all of it the damper's. */
static void chain_report(const chain_law *k, double vb, double z, dp_network_step_forces *f)
{
    if (k->fixed) {
        double lambda = k->lam;
        lambda += 0 + 0 * (k->fz - 0);
        *f = (dp_network_step_forces){ .z = vb, .lambda = lambda, .a = lambda - 0, .s = 0, .at_rest = 1 };
    } else {
        double lambda = k->lam0 + 0 * (z - k->zref);
        lambda += 0 + 0 * (z - 0);
        *f = (dp_network_step_forces){ .z = z, .lambda = lambda, .a = lambda - 0, .s = 0, .at_rest = 0 };
    }
}

/* multipliers(), bulk_update() and, for the laws it leaves as they were, report() in one pass over the laws
 * of nodes lo..hi (a fixed law's multiplier is read off its own node's residual, which no update changes; the
 * report stands when nothing changed): the nodes whose law changed appended to ch->dirty, or -1 for a
 * multiplier that is not a number (the general path decides). A free law whose z left its piece is fixed at
 * the vertex it crossed (follow: every vertex has a force interval); a fixed one whose multiplier left its
 * interval (inside(): the rounding tolerance of its terms) is freed onto the piece on that side. */
static int chain_update(struct network_chain *ch, const dp_network_step_element *act, const double *W, size_t p,
                        double h, const double *vs, dp_network_step_forces *f, size_t lo, size_t hi)
{
    size_t l = ch->nlaw;   /* the first law at lo or above */
    for (size_t i = lo; l == ch->nlaw && i <= hi; i++)
        l = ch->law_at[i] >= 0 ? (size_t)ch->law_at[i] : l;
    for (; l < ch->nlaw && ch->law[l].node <= hi; l++) {
        chain_law *k = &ch->law[l];
        size_t i = k->node;
        double z = chain_rel(k, vs);
        if (!k->fixed) {
            if (z > k->hi || z < k->lo) {
                k->fixed = 1, k->fz = z > k->hi ? k->hi : k->lo;
                ch->held[i] = 1, ch->dirty[ch->ndirty++] = i, ch->nfree--;
            } else {
                chain_report(k, 0, z, &f[k->act]);
            }
            continue;
        }
        double Hv = dp_band_row(W + i * (p + 1), p, vs, i, ch->n);
        double res_err = 8 * DBL_EPSILON * (fabs(ch->rhs_eff[i]) + fabs(Hv)), res = ch->rhs_eff[i] - Hv;
        double sign = k->up ? 1 : -1, lam = res / (h * sign);
        k->lam = lam, k->lam_err = res_err / h;
        if (isnan(lam))
            return -1;
        double tol = 1e-12 * (1 + fabs(lam) + k->aflo + k->afhi) + k->lam_err;
        if (lam >= k->flo - tol && lam <= k->fhi + tol) {
            chain_report(k, act[k->act].vb, z, &f[k->act]);
            continue;
        }
        if (lam > k->fhi)   /* released onto the piece above the vertex, or below it */
            chain_free_on(k, k->fz, INFINITY, k->fr, k->fz);
        else
            chain_free_on(k, -INFINITY, k->fz, k->fl, k->fz);
        ch->held[i] = 0, ch->dirty[ch->ndirty++] = i, ch->nfree++;
    }
    return 0;
}

/* The first solve of a step: the whole system, R's factor kept where the hold is the one it was made for. */
static int chain_first_solve(struct network_chain *ch, const double *W, size_t p, const double *rhs, double h,
                             double *vs)
{
    int whole;
    ch->nfree = chain_assemble(ch, W, p, rhs, h, &whole);
    if ((whole || ch->ndirty) && !chain_factor(ch, W, p, whole))
        return 0;
    chain_solve_range(ch, 0, ch->n - 1, vs);
    return 1;
}

/* A later solve: only the stretches around the laws the last update changed (ch->dirty) are assembled,
 * factored and solved again; elsewhere the system, its factor and its solution are the same numbers. Their
 * count into *m (ch->rlo, ch->rhi). */
static int chain_next_solve(struct network_chain *ch, const double *W, size_t p, const double *rhs, double h,
                            double *vs, size_t *m)
{
    *m = chain_ranges(ch, ch->dirty, ch->ndirty);
    for (size_t r = 0; r < *m; r++) {
        chain_assemble_range(ch, W, p, rhs, h, ch->rlo[r], ch->rhi[r]);
        if (!chain_factor_range(ch, W, p, ch->rlo[r], ch->rhi[r]))
            return ch->factored = 0;
        chain_solve_range(ch, ch->rlo[r], ch->rhi[r], vs);
    }
    return 1;
}

/* dp_network_step_solve for the chain (pdas from assign_start): v1 and the laws' forces; DP_ECANCEL when the
 * poll said stop, 1 when the general solve must decide. */
static int chain_step_solve(dp_run *r, struct network_chain *ch, double h)
{
    struct dp_network_run *nr = r->state;
    const double *W = dp_network_step_W(nr->ws);
    size_t p = nr->p, n = ch->n;
    for (size_t c = 0; c < ch->nlaw; c++)
        if (!chain_start(&nr->act[ch->law[c].act], &ch->law[c], chain_rel(&ch->law[c], nr->v)))
            return 1;
    if (h != ch->fac_h || W != ch->fac_W)   /* W rebuilt for another step length */
        ch->factored = 0, ch->fac_h = h, ch->fac_W = W;
    unsigned long long iters = 0;
    for (int it = 0; it < 12; it++) {
        iters++;
        size_t m = 1;
        int ok = it == 0 ? chain_first_solve(ch, W, p, nr->rhs, h, nr->v1)
                         : chain_next_solve(ch, W, p, nr->rhs, h, nr->v1, &m);
        if (!ok)
            return 1;
        /* the solve's work as polled_stop counts it, and the factor's at every solve (the general workspace
         * counts it only when it factors anew: the stop hook may be asked a few steps apart from there) */
        if (network_run_poll_lean(r, nr, n * (p + 1) + ch->nlaw + ch->nfree * (p + 1) * (p + 1)))
            return DP_ECANCEL;
        ch->ndirty = 0;
        for (size_t k = 0; k < m; k++)
            if (chain_update(ch, nr->act, W, p, h, nr->v1, nr->force, it ? ch->rlo[k] : 0, it ? ch->rhi[k] : n - 1))
                return 1;
        if (ch->ndirty == 0) {
            r->sum.iterations += iters;
            return DP_OK;
        }
    }
    return 1;
}

/* ---- the run ------------------------------------------------------------------------------------------ */

/* Moreau-Jean's arming (network_run_contacts_arm_mj) for the chain's contacts, none behind another: the
 * step's entries after the elements' own laws. */
static void chain_arm(struct dp_network_run *nr, const struct network_chain *ch, double h)
{
    int changed = 0;
    for (size_t l = 0; nr->nc && l < ch->nlaw; l++) {   /* a friction chain has none */
        const chain_law *k = &ch->law[l];
        if (!k->cone)
            continue;
        size_t c = k->act - nr->nact_el;
        double g = chain_rel(k, nr->x) - nr->ct[c].law.distance, gd = chain_rel(k, nr->v);
        if (fabs(gd) < DBL_MIN)
            gd = 0;
        int was = nr->ct_on[c], on = g + 0.5 * h * gd <= 0;
        dp_network_step_element *a = &nr->act[nr->nact_el + c];
        changed |= (a->A != NULL) != on;
        a->A = on ? &nr->cone : NULL;
        a->vb = on ? -nr->ct[c].law.restitution * gd : 0;
        nr->ct_on[c] = (unsigned char)on;
        nr->ct_pre[c] = was ? 0 : gd;
    }
    if (changed)   /* the general workspace's factor cache, for a step it takes over */
        dp_network_step_W_changed(nr->ws);
}

/* network_run_element_forces after a step for the chain's elements: the linear parts' forces plus their
 * laws' parts from the step (the others stay +0), the contacts' multipliers (network_run_contacts_forces).
 * Returns whether those forces are finite (network_run_state_finite's second half). */
static int chain_forces(struct dp_network_run *nr, const struct network_chain *ch)
{
    int finite = 1;
    for (size_t j = 0; j < ch->nlin; j++) {
        const chain_element *e = &ch->lin[j];
        double u = network_run_rel(e->a, e->b, nr->x), z = network_run_rel(e->a, e->b, nr->v);
        double fs = e->k != 0 ? e->k * u : 0, fd = e->c != 0 ? e->c * (z - e->vb) : 0;
        if (e->act >= 0)
            fs += nr->force[e->act].s, fd += nr->force[e->act].a;
        nr->Fs[e->i] = fs, nr->Fd[e->i] = fd;
        finite &= isfinite(fs) && isfinite(fd);
    }
    for (size_t c = 0; c < nr->nc; c++)
        nr->Fn[nr->ct_el[c]] = nr->ct_on[c] ? nr->force[nr->nact_el + c].lambda : 0;
    return finite;
}

/* network_run_state_finite: the positions and velocities, and the forces' check (`forces`). */
static int chain_finite(const struct dp_network_run *nr, int forces)
{
    for (size_t i = 0; forces && i < nr->n; i++)
        if (!(fabs(nr->x[i]) < 1e300 && fabs(nr->v[i]) < 1e300))
            return 0;
    return forces;
}

/* network_run_state_finite for a step that writes no row, without forming the forces: the positions and
 * velocities checked as it checks them (`state`, their largest magnitudes xm, vm), and the forces shown
 * finite by network_run_forces_bounded (a Coulomb element's F_d adds its force, finite: `laws`). -1 when the
 * bound does not show it: the forces are formed and checked. */
static int chain_finite_bounded(const struct dp_network_run *nr, int state, double xm, double vm, int laws)
{
    if (!state)
        return 0;
    if (!network_run_forces_bounded(nr, xm, vm))
        return -1;
    return laws;
}

/* The Coulomb elements' phases after a step (at rest: sticking, else slipping), their stick time, and the
 * stick and slip events of those that changed (network_run_step_events, in element order, for the elements
 * whose phase differs from the one before the step; with none it has nothing to write). Returns whether
 * their forces are finite. */
static int chain_phases(dp_run *r, const struct network_chain *ch, double t, double h)
{
    struct dp_network_run *nr = r->state;
    unsigned char *phase = nr->phase;
    const dp_network_step_forces *force = nr->force;
    size_t nchanged = 0;
    int finite = 1;
    for (size_t j = 0; j < ch->nfric; j++) {
        size_t i = ch->fric[j].i, k = ch->fric[j].act;
        unsigned char ph = force[k].at_rest ? DP_PHASE_STICK : DP_PHASE_SLIP;
        finite &= isfinite(force[k].a);
        if (ph == DP_PHASE_STICK)
            r->sum.stick_time += h;
        if (ph == phase[i])
            continue;
        ch->changed[nchanged] = i, ch->was[nchanged++] = phase[i];
        phase[i] = ph;
    }
    if (nchanged) {
        memcpy(nr->phase_prev, phase, nr->nel);
        for (size_t j = 0; j < nchanged; j++)
            nr->phase_prev[ch->changed[j]] = ch->was[j];
        network_run_step_events(r, nr->phase_prev, t + h);
    }
    return finite;
}

/* network_run_step_rhs for a tridiagonal W in one sweep: M v, C v and K (x + h theta (1-theta) v) formed
 * row by row as dp_band_symv's tridiagonal loop forms them (the diagonal term plus row i-1's, then row
 * i+1's), combined as the general right side combines them, the loads added in their order (a constant one
 * read, not dispatched). The same numbers bit for bit, in one pass over the nodes instead of six. The
 * elongations u the laws see are formed only for a step the general solve takes over (chain_handover): with
 * no spring graph in the step, nothing else reads them. */
static void chain_rhs(struct dp_network_run *nr, double t, double h)
{
    size_t n = nr->n;
    if (nr->p != 1 || n < 2 || nr->Mv || nr->belt_viscous) {
        network_run_step_rhs(nr, t, h);
        return;
    }
    if (h != nr->h_W)
        network_run_build_W(nr, h);
    const double *M = nr->M, *C = nr->C, *K = nr->K, *x = nr->x, *v = nr->v;
    double *rhs = nr->rhs, *v1 = nr->v1, th = nr->theta;
    double a1 = h * (1 - th), b1 = h * th * (1 - th);
    v1[0] = x[0] + b1 * v[0];
    double cm = M[0] * v[0], cc = C[0] * v[0], ck = K[0] * v1[0];   /* row i's sums so far */
    for (size_t i = 0; i + 1 < n; i++) {
        v1[i + 1] = x[i + 1] + b1 * v[i + 1];
        double am = M[2 * i + 1], ac = C[2 * i + 1], ak = K[2 * i + 1];
        double ym = cm + am * v[i + 1], yc = cc + ac * v[i + 1], yk = ck + ak * v1[i + 1];
        cm = M[2 * (i + 1)] * v[i + 1] + am * v[i];
        cc = C[2 * (i + 1)] * v[i + 1] + ac * v[i];
        ck = K[2 * (i + 1)] * v1[i + 1] + ak * v1[i];
        double r = ym;
        r -= a1 * yc;
        r -= h * yk;
        rhs[i] = r;
    }
    double r = cm;
    r -= a1 * cc;
    r -= h * ck;
    rhs[n - 1] = r;
    const dp_node_forcing *f = nr->net->force;
    for (size_t i = 0; i < nr->net->nforce; i++)
        rhs[f[i].node] += h * (f[i].f.kind == DP_FORCING_CONSTANT ? f[i].f.value : dp_forcing_eval(&f[i].f, t + th * h));
}

/* The step handed to the general solve, with the elongations network_run_step_rhs gives it. */
static int chain_handover(dp_run *r, struct network_chain *ch, double h)
{
    struct dp_network_run *nr = r->state;
    ch->handed++;
    for (size_t k = 0; k < nr->nact; k++)
        nr->u[k] = network_run_rel(nr->act[k].a, nr->act[k].b, nr->x);
    return dp_network_step_solve(nr->ws, h, nr->rhs, nr->u, nr->v, nr->v1, nr->force, &r->sum.iterations);
}

/* network_run_take_velocity (no elastoplastic or sloped spring to follow it) and network_run_state_finite's
 * test of the positions and velocities on the way, their largest magnitudes into *xm, *vm: 1 when finite. */
static int chain_take_velocity(struct dp_network_run *nr, double h, double *xm, double *vm)
{
    double *x = nr->x, *v = nr->v, th = nr->theta, xmax = 0, vmax = 0;
    const double *v1 = nr->v1;
    int finite = 1;
    for (size_t i = 0, n = nr->n; i < n; i++) {
        x[i] += h * ((1 - th) * v[i] + th * v1[i]);
        v[i] = v1[i];
        double ax = fabs(x[i]), av = fabs(v[i]);
        finite &= ax < 1e300 && av < 1e300;
        xmax = ax > xmax ? ax : xmax, vmax = av > vmax ? av : vmax;
    }
    *xm = xmax, *vm = vmax;
    return finite;
}

/* One Moreau-Jean step (network_run_net_step), the Coulomb elements' phases and events after it, and the
 * elements' forces where a row is written or a bound does not show them finite; *finite: the state's. */
static int chain_step(dp_run *r, struct network_chain *ch, double t, double h, int *finite)
{
    struct dp_network_run *nr = r->state;
    chain_arm(nr, ch, h);
    chain_rhs(nr, t, h);
    int s = chain_step_solve(r, ch, h);
    if (s == 1)   /* the general solve decides */
        s = chain_handover(r, ch, h);
    nr->solved = s == DP_OK;
    if (s != DP_OK)
        return s;
    double xm, vm;
    int state = chain_take_velocity(nr, h, &xm, &vm);
    network_run_contacts_mj_events(r, t, h);
    int laws = chain_phases(r, ch, t, h);
    *finite = network_run_writes_row(r) ? -1 : chain_finite_bounded(nr, state, xm, vm, laws);
    if (*finite < 0)
        *finite = chain_finite(nr, chain_forces(nr, ch));
    return DP_OK;
}

/* network_run_advance's loop with the chain's step. */
static int chain_advance(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    struct network_chain *ch = nr->chain;
    if (ch == NULL)
        return dp_run_network.advance(r);
    if (network_run_reserve_rows(r) != DP_OK)
        return DP_ENOMEM;
    network_run_flush(r);
    int due;
    while (network_run_step_due(r, &due)) {
        double h = dp_run_step_length(r), t = r->cur.t;
        nr->impacts_step = 0;
        int finite = 0, s = chain_step(r, ch, t, h, &finite);
        if (s != DP_OK && network_run_cancelled(r))
            return r->status;
        if (s != DP_OK)
            return dp_run_fail(r, s, "the implicit step at t = %.17g has no solution (%s)", t, dp_strerror(s));
        if ((s = network_run_step_taken(r, finite)) != DP_OK)
            return s;
    }
    return due;
}

static void chain_release(struct network_chain *ch)
{
    if (ch == NULL)
        return;
    void *p[] = { ch->law, ch->lin, ch->fric, ch->changed, ch->was, ch->law_at, ch->held, ch->fac_held, ch->c,
                  ch->rhs_eff, ch->y, ch->L, ch->off, ch->dirty, ch->rlo, ch->rhi };
    for (size_t i = 0; i < sizeof p / sizeof *p; i++)
        free(p[i]);
    free(ch);
}

static void chain_free(void *state)
{
    struct dp_network_run *nr = state;
    if (nr != NULL)
        chain_release(nr->chain);
    network_run_free(state);
}

/* The node entry e ties to the ground, or -1. */
static long grounded_node(const dp_network_step_element *e)
{
    return e->a < 0 && e->b >= 0 ? e->b : e->b < 0 && e->a >= 0 ? e->a : -1;
}

/* Whether A is Coulomb's graph phi Sgn(y), phi > 0 (laws/law_table.c, dp_threshold_graph): the vertices
 * (+0, -phi) and (+0, phi), flat rays. */
static int coulomb_graph(const dp_graph *A)
{
    return A != NULL && A->n == 2 && A->y[0] == 0 && A->y[1] == 0 && !signbit(A->y[0]) && !signbit(A->y[1]) &&
           A->f[1] > 0 && isfinite(A->f[1]) && A->f[0] == -A->f[1] && A->left[0] > 0 && A->left[1] == 0 &&
           A->right[0] > 0 && A->right[1] == 0;
}

/* Entry k's law: a Coulomb element's (k < nact_el) or a rigid contact's; 0 when it is neither, or its node
 * holds another (seen). */
static int chain_law_of(const struct dp_network_run *nr, size_t k, chain_law *law, unsigned char *seen)
{
    const dp_network_step_element *e = &nr->act[k];
    long node = grounded_node(e);
    if (node < 0 || seen[node] || e->S != NULL || e->ep_theta != 0 || nr->gamma[k] != NULL)
        return 0;
    seen[node] = 1;
    *law = (chain_law){ .node = (size_t)node, .act = k, .up = e->a < 0 };
    if (k < nr->nact_el) {
        if (!coulomb_graph(e->A) || nr->static_A[k].n != 0)
            return 0;
        law->fl = e->A->f[0], law->fr = e->A->f[1];
        law->flo = law->fl, law->fhi = law->fr, law->aflo = fabs(law->fl), law->afhi = fabs(law->fr);
        return 1;
    }
    size_t c = k - nr->nact_el;
    if (nr->ct[c].law.compliance != 0 || nr->ct[c].rope || nr->ct_shadow[c])
        return 0;
    law->cone = 1, law->fr = 0, law->flo = -INFINITY, law->fhi = 0;
    return 1;
}

static int by_node(const void *a, const void *b)
{
    size_t x = ((const chain_law *)a)->node, y = ((const chain_law *)b)->node;
    return (x > y) - (x < y);
}

/* The elements whose forces a row needs (a linear part or a law) and the Coulomb elements' phases. */
static void chain_elements(struct dp_network_run *nr, struct network_chain *ch)
{
    for (size_t i = 0; i < nr->nel; i++) {
        const dp_element *e = &nr->net->el[i];
        long k = nr->act_of[i];
        if (nr->k[i] == 0 && nr->c[i] == 0 && k < 0)
            continue;
        chain_element *l = &ch->lin[ch->nlin++];
        *l = (chain_element){ .i = i, .a = e->a, .b = e->b, .act = k, .k = nr->k[i], .c = nr->c[i],
                              .vb = e->has_damper ? e->damper.belt_velocity : 0 };
        if (k >= 0 && nr->can_stick[i])
            ch->fric[ch->nfric++] = (chain_friction){ .i = i, .act = (size_t)k };
    }
}

/* The workspace, where the run's ordering left W tridiagonal (or diagonal) and every set-valued law in the
 * step's problem is a Coulomb element's or a rigid contact's joining the ground to a node of its own; else
 * none (the general advance). */
static int chain_setup(struct dp_network_run *nr)
{
    if (nr->p > 1 || nr->nact != nr->nact_el + nr->nc || nr->nrope != 0 || nr->locate || nr->relaxed ||
        nr->has_static || nr->has_ep || nr->has_smooth || nr->jump != NULL || nr->stop_S != NULL)
        return DP_OK;
    size_t n = nr->n, na = nr->nact;
    struct network_chain *ch = calloc(1, sizeof *ch);
    if (ch == NULL)
        return DP_ENOMEM;
    nr->chain = ch;
    ch->n = n, ch->nlaw = na;
    ch->law = calloc(na ? na : 1, sizeof *ch->law);
    ch->law_at = calloc(n, sizeof *ch->law_at);
    ch->dirty = calloc(n, sizeof *ch->dirty);
    ch->rlo = calloc(n, sizeof *ch->rlo), ch->rhi = calloc(n, sizeof *ch->rhi);
    double **d[] = { &ch->c, &ch->rhs_eff, &ch->y, &ch->L, &ch->off };
    for (size_t i = 0; i < sizeof d / sizeof *d; i++)
        *d[i] = calloc(n + 1, sizeof(double));
    size_t ne = nr->nel ? nr->nel : 1;
    ch->lin = calloc(ne, sizeof *ch->lin), ch->fric = calloc(ne, sizeof *ch->fric);
    ch->changed = calloc(ne, sizeof *ch->changed), ch->was = calloc(ne, 1);
    ch->held = calloc(n, 1), ch->fac_held = calloc(n, 1);
    unsigned char *seen = calloc(n, 1);
    if (!ch->law || !ch->law_at || !ch->dirty || !ch->rlo || !ch->rhi || !ch->c || !ch->rhs_eff || !ch->y ||
        !ch->L || !ch->off || !ch->lin ||
        !ch->fric || !ch->changed || !ch->was || !ch->held || !ch->fac_held || !seen) {
        free(seen);
        return DP_ENOMEM;
    }
    int ok = 1;
    for (size_t k = 0; ok && k < na; k++)
        ok = chain_law_of(nr, k, &ch->law[k], seen);
    free(seen);
    if (!ok) {   /* not such a chain after all: the general advance */
        nr->chain = NULL;
        chain_release(ch);
        return DP_OK;
    }
    qsort(ch->law, na, sizeof *ch->law, by_node);
    for (size_t i = 0; i < n; i++)
        ch->law_at[i] = -1;
    for (size_t k = 0; k < na; k++)
        ch->law_at[ch->law[k].node] = (long)k;
    chain_elements(nr, ch);
    return DP_OK;
}

long long network_chain_handed(const struct dp_network_run *nr)
{
    return nr->chain ? (long long)nr->chain->handed : -1;
}

/* The network run's own set-up, initial probe and first row (network_run.c), then the chain's workspace. */
static int chain_init(dp_run *r)
{
    int s = dp_run_network.init(r);
    return s != DP_OK ? s : chain_setup(r->state);
}

const dp_run_type dp_run_network_grounded_chain = {
    .name = "stick-slip", .variant = "exact", .events_mode = network_run_events_mode, .check = dp_rules_network,
    .init = chain_init, .advance = chain_advance, .pending = network_run_pending, .free = chain_free,
};
