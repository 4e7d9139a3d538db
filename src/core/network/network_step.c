/* src/core/network/network_step.c - the network's theta-step solved exactly: a primal active-set method over the
 * pieces of the element graphs (network_step.h).
 *
 * Every element is either *fixed* at a vertex of its graph Sigma_e (z_e held, its force a multiplier in the
 * vertex's interval: a sticking friction element, a taut rope) or *free* on one affine piece
 * lambda = lam0 + slope (z - zref) between two vertices. For a given assignment the optimality conditions
 * are linear; the fixed constraints z_e = b_e^T v = const join nodes into a forest (incidence vectors are
 * independent exactly when they form no cycle), so they are eliminated by contracting the forest: each tree
 * becomes one unknown (or none, if it holds the ground), and the reduced matrix keeps the band of W.
 *
 * One iteration: solve for the assignment's minimizer, walk towards it and stop at the first vertex a free
 * element meets (it becomes fixed); at the minimizer, release one fixed element whose multiplier left its
 * interval. The objective falls strictly between minimizers, so no assignment repeats and the method ends
 * after finitely many iterations with the exact minimizer: a sticking element sticks to rounding, no creep.
 * Degenerate ties are broken by the lowest index; an iteration cap turns a cycle into DP_ESOLVE, never into
 * a silent wrong answer.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>

#include "dashpot/status.h"
#include "base/band.h"
#include "base/lower_bound.h"
#include "network/network_step.h"

enum { FREE = 0, FIXED = 1 };
enum { HELD_MEMO = 4 };   /* held solves remembered: a root search's two ends and the last evaluations */
enum { SRC_NONE = 0, SRC_A = 1, SRC_S = 2 };
enum { SPARES = 2 };      /* factors kept beside the current one */

/* A vertex of Sigma_e in z, remembered with the graph vertex it comes from so that the force interval is
 * read at that vertex exactly (u + h z need not round back to it). */
typedef struct vertex {
    double z;
    int src;
    double y;
} vertex;

/* A held solve remembered (dp_network_step_solve_frozen): its inputs beside the assignment, and what it gave. */
typedef struct held_memo {
    int used, status;
    unsigned long long stamp;
    double h;
    double *rhs, *u, *W;             /* n, ne, n (p+1): W is rebuilt for every length (the caller's) */
    double *v, *margin;              /* n, ne */
    double *lam, *lam_err;           /* ne: the fixed elements' multipliers it left */
    dp_network_step_forces *f;       /* ne */
} held_memo;

/* A factor kept for a structure other than the current one (dp_network_step's spare). */
typedef struct kept_factor {
    double *R;
    size_t cap, pr;
    int ok;
    double h;
    unsigned char *st;
    double *slope;
    unsigned long long stamp;   /* when it was last the current factor */
} kept_factor;

typedef struct elem_state {
    int st;
    vertex fix;           /* FIXED: where */
    vertex lo, hi;        /* FREE: the piece's ends (z = -/+INFINITY on an end ray) */
    double zref, lam0, slope;
    double lam;           /* FIXED: the multiplier of the last solve */
    double lam_err;       /* its rounding: eps times the forces it was computed from, over h */
} elem_state;

struct dp_network_step {
    size_t n, p, ne;
    const dp_network_step_element *el;
    double *W, *H;        /* band storage n x (p+1) */
    const double *Hm;     /* the step's matrix W + h sum_free slope b b^T: H, or W itself when no free
                             element adds to it (Coulomb elements, flat pieces) */
    double *R;            /* reduced band storage, capacity n x (p+1) grown on demand */
    size_t R_cap, nr, pr;
    size_t R_max;         /* the most doubles R may grow to (0: no bound) */
    int factored;         /* R holds the factor of the structure in fac_st, fac_slope, for h_factored */
    double h_factored;
    unsigned char *fac_st;
    double *fac_slope;
    /* Factors kept beside R (`spare`), of the structures factored before it: a step whose active-set pass
     * starts from one assignment and ends on another alternates between structures, each factored again
     * every step otherwise (resting contacts re-armed at a vertex -e g' whose sign alternates start free
     * one step and fixed the next, then all end fixed: three structures in turn). Only factors of W itself
     * (no free slope adds to it) are kept there, so H stays the current factor's. W_fac is the W they all
     * were formed from: after dp_network_step_W_changed they hold while W has the same bytes (Moreau-Jean's
     * arming calls it whenever a contact is armed or disarmed, which leaves W as it was). They are extras
     * within R_max: dropped when R must grow into their room. */
    kept_factor spare[SPARES];
    double *W_fac;
    int W_dirty;
    unsigned long long fac_clock;
    elem_state *es;
    /* The elements whose state may differ from the pattern buffer last saved or restored (`synced`): a held
     * solve of event location changes a few (the fixed ones' multipliers, a switch), and restoring those
     * alone keeps a restore proportional to them instead of to the network. `all_dirty`: any may differ. */
    const void *synced;
    unsigned char *dirty;
    size_t *dirty_list, ndirty;
    int all_dirty;
    /* parent, pot, kidx, c and nr hold build_forest's result for the current fixed elements (no element
     * fixed, freed or moved since): a held solve of event location then reuses them */
    int forest_ok;
    /* The fixed elements (key_fixed) and their vertices (key_z, by their bits) whose forest kidx, c and nr
     * hold since the active-set pass last indexed one (key_ok; any other indexing clears it). Those
     * depend on nothing else (the joins from a reset in the elements' order, then the index), and the
     * union-find's partition is theirs whenever the fixed elements are: a pass whose fixed elements are
     * the last pass's (a chain whose stuck blocks stay stuck) keeps the index instead of joining and
     * indexing the same forest again. */
    unsigned char *key_fixed;
    double *key_z;
    int key_ok;
    /* Event location evaluates a held step at the same length more than once (a root search's ends, then
     * the root again to take the state there): with the assignment the buffer `memo_for` holds and the same
     * elements (memo_el), the same h, W, rhs and u give the same bits, so the answer is copied. */
    held_memo memo[HELD_MEMO];
    dp_network_step_element *memo_el;
    const void *memo_for;
    unsigned long long memo_clock;
    int memo_el_ok, memo_el_ep;
    long *parent;         /* union-find over nodes and the ground (index n), with potentials */
    double *pot;
    long *kidx;           /* reduced unknown of each node's tree, -1 when the tree holds the ground */
    double *c;            /* v_i = y[kidx] + c_i */
    double *rhs_eff, *y, *vs, *d, *res;
    double *res_err;      /* the residuals' rounding, for the multipliers' (multipliers) */
    long *head, *next_edge, *deg; /* the fixed forest's adjacency, for the multipliers */
    size_t *queue;
    /* relaxation: gamma per element (NULL: none), linearized at zk as g0 + g1 (z - zk) */
    const dp_relaxation *const *gamma;
    double theta;
    double *zk, *g0, *g1, *gshift;
    /* held solves over blocks of a chain (dp_network_step_blocks): the elements of each node in their order
     * (inc_start, inc_el: built once), each node's velocity in the blocks (vloc) and the blocks' reduced
     * system (loc_*: right side, factor, unknowns) */
    size_t *inc_start, *inc_el;
    unsigned long long *blk_mark, blk_gen;   /* per node: the blocks call that last covered it */
    double *vloc, *loc_rhs, *loc_R, *loc_y;
    /* the stop hook's poll (network_step.h), asked after every solve with the work done since the last one */
    dp_network_step_poll_fn poll;
    void *poll_ctx;
    unsigned long long work;
};

dp_network_step *dp_network_step_alloc(size_t n, size_t p, size_t ne, const dp_network_step_element *el)
{
    dp_network_step *w = calloc(1, sizeof *w);
    if (w == NULL)
        return NULL;
    w->n = n, w->p = p, w->ne = ne, w->el = el;
    size_t band = n * (p + 1), m = ne ? ne : 1;
    w->W = calloc(band, sizeof *w->W);
    w->H = calloc(band, sizeof *w->H);
    w->Hm = w->H;
    w->R = calloc(band, sizeof *w->R);
    w->R_cap = band;
    w->es = calloc(m, sizeof *w->es);
    w->dirty = calloc(m, 1);
    w->dirty_list = calloc(m, sizeof *w->dirty_list);
    w->all_dirty = 1;
    w->parent = calloc(n + 1, sizeof *w->parent);
    w->pot = calloc(n + 1, sizeof *w->pot);
    w->kidx = calloc(n + 1, sizeof *w->kidx);
    w->c = calloc(n + 1, sizeof *w->c);
    w->rhs_eff = calloc(n, sizeof *w->rhs_eff);
    w->y = calloc(n, sizeof *w->y);
    w->vs = calloc(n, sizeof *w->vs);
    w->d = calloc(n, sizeof *w->d);
    w->res = calloc(n + 1, sizeof *w->res);
    w->res_err = calloc(n + 1, sizeof *w->res_err);
    w->head = calloc(n + 1, sizeof *w->head);
    w->next_edge = calloc(2 * m, sizeof *w->next_edge);
    w->deg = calloc(n + 1, sizeof *w->deg);
    w->queue = calloc(n + 1, sizeof *w->queue);
    w->zk = calloc(m, sizeof *w->zk);
    w->g0 = calloc(m, sizeof *w->g0);
    w->g1 = calloc(m, sizeof *w->g1);
    w->gshift = calloc(m, sizeof *w->gshift);
    w->fac_st = calloc(m, 1);
    w->fac_slope = calloc(m, sizeof *w->fac_slope);
    w->key_fixed = calloc(m, 1);
    w->key_z = calloc(m, sizeof *w->key_z);
    if (!w->key_fixed || !w->key_z || !w->dirty || !w->dirty_list || !w->zk || !w->g0 || !w->g1 || !w->gshift || !w->fac_st || !w->fac_slope ||
        !w->W || !w->H || !w->R || !w->es || !w->parent || !w->pot || !w->kidx || !w->c || !w->rhs_eff ||
        !w->y || !w->vs || !w->d || !w->res || !w->res_err || !w->head || !w->next_edge || !w->deg || !w->queue) {
        dp_network_step_free(w);
        return NULL;
    }
    return w;
}

static void memo_free(dp_network_step *w);
static void drop_spares(dp_network_step *w);

void dp_network_step_free(dp_network_step *w)
{
    if (w == NULL)
        return;
    memo_free(w);
    free(w->W), free(w->H), free(w->R), free(w->es), free(w->dirty), free(w->dirty_list), free(w->parent), free(w->pot), free(w->kidx);
    free(w->c), free(w->rhs_eff), free(w->y), free(w->vs), free(w->d), free(w->res), free(w->res_err), free(w->head);
    free(w->next_edge), free(w->deg), free(w->queue);
    free(w->zk), free(w->g0), free(w->g1), free(w->gshift), free(w->fac_st), free(w->fac_slope);
    drop_spares(w);
    free(w->key_fixed), free(w->key_z);
    free(w->inc_start), free(w->inc_el), free(w->blk_mark), free(w->vloc), free(w->loc_rhs), free(w->loc_R), free(w->loc_y);
    free(w);
}

/* Element i's values (a multiplier, a piece's force) are about to change: remembered for the next pattern
 * save or restore. Past a quarter of the elements a whole copy is as cheap, and the list stops. */
static void touch_values(dp_network_step *w, size_t i)
{
    if (w->all_dirty || w->dirty[i])
        return;
    if (w->ndirty >= w->ne / 4 + 1) {
        w->all_dirty = 1;
        return;
    }
    w->dirty[i] = 1;
    w->dirty_list[w->ndirty++] = i;
}

/* Element i is about to be fixed, freed or moved to another piece: the forest of the fixed ones with it. */
static void touch(dp_network_step *w, size_t i)
{
    touch_values(w, i);
    w->forest_ok = 0;
}

/* Every element's state may change (a whole solve's start assignment). */
static void touch_all(dp_network_step *w)
{
    w->all_dirty = 1;
    w->forest_ok = 0;
}

/* Nothing remembered holds any more (the poll, the limit, the relaxation or the buffer changed). */
static void memo_forget(dp_network_step *w)
{
    for (int k = 0; k < HELD_MEMO; k++)
        w->memo[k].used = 0;
}

void dp_network_step_set_poll(dp_network_step *w, dp_network_step_poll_fn poll, void *ctx)
{
    memo_forget(w);
    w->poll = poll;
    w->poll_ctx = ctx;
}

/* Hands the work counted so far to the poll: 1 when the caller must end the step with DP_ECANCEL. */
static int polled_stop_units(dp_network_step *w)
{
    if (w->poll == NULL)
        return 0;
    unsigned long long units = w->work;
    w->work = 0;
    return w->poll(w->poll_ctx, units) != 0;
}

/* Counts a solve of the current assignment (a pass over W's band and the elements) and asks the poll. */
static int polled_stop(dp_network_step *w)
{
    w->work += w->n * (w->p + 1) + w->ne;
    return polled_stop_units(w);
}

void dp_network_step_limit(dp_network_step *w, size_t max_doubles)
{
    memo_forget(w);
    w->R_max = max_doubles;
}

size_t dp_network_step_reduced_need(const dp_network_step *w)
{
    return w->nr * (w->pr + 1);
}

void dp_network_step_relaxation(dp_network_step *w, const dp_relaxation *const *gamma, double theta)
{
    memo_forget(w);
    w->gamma = gamma;
    w->theta = theta;
}

double *dp_network_step_W(dp_network_step *w)
{
    return w->W;
}

void dp_network_step_W_changed(dp_network_step *w)
{
    w->W_dirty = 1;   /* prepare compares W with the W its factors were formed from */
}

/* ---- the graphs Sigma_e ------------------------------------------------------------------------------ */

/* End index of an element in the union-find (the ground is n). */
static size_t end_index(const dp_network_step *w, long e)
{
    return e < 0 ? w->n : (size_t)e;
}

static double rel_velocity(const dp_network_step_element *e, const double *v)
{
    return (e->b >= 0 ? v[e->b] : 0) - (e->a >= 0 ? v[e->a] : 0);
}

/* The argument of A and S at z, each read exactly at a remembered vertex. */
static double arg_A(const dp_network_step_element *e, const vertex *at)
{
    return at->src == SRC_A ? at->y : at->z - e->vb;
}

/* The spring graph's argument is u + beta z, beta = h (graph springs) or h theta (elastoplastic), and its
 * force enters Sigma with the weight 1 or theta: factors of exactly 1 keep graph springs bit for bit. */
static double s_beta(const dp_network_step_element *e, double h)
{
    return e->ep_theta > 0 ? h * e->ep_theta : h;
}

static double s_weight(const dp_network_step_element *e)
{
    return e->ep_theta > 0 && !e->s_whole ? e->ep_theta : 1;
}

static double arg_S(const dp_network_step_element *e, double u, double h, const vertex *at)
{
    return at->src == SRC_S ? at->y : u + s_beta(e, h) * at->z;
}

/* The piece of Sigma_e leaving `at` towards dir: slope in z, force there, the next vertex. */
static int sigma_piece(const dp_network_step *w, size_t i, double u, double h, const vertex *at, int dir,
                       double *slope, double *f, vertex *next)
{
    const dp_network_step_element *e = &w->el[i];
    dp_graph_piece_t pc;
    *slope = 0, *f = 0;
    next->z = dir * INFINITY, next->src = SRC_NONE, next->y = 0;
    if (e->A) {
        dp_graph_piece(e->A, arg_A(e, at), dir, &pc);
        if (pc.blocked)
            return 0;
        *slope += pc.slope, *f += pc.f;
        if (isfinite(pc.next))
            *next = (vertex){ pc.next + e->vb, SRC_A, pc.next };
    }
    if (e->S) {
        double beta = s_beta(e, h), wt = s_weight(e);
        dp_graph_piece(e->S, arg_S(e, u, h, at), dir, &pc);
        if (pc.blocked)
            return 0;
        *slope += wt * (beta * pc.slope), *f += wt * pc.f;
        double z = (pc.next - u) / beta;
        if (isfinite(pc.next) && (dir > 0 ? z < next->z : z > next->z))
            *next = (vertex){ z, SRC_S, pc.next };
    }
    *slope -= w->g1[i];                                  /* the relaxation, linearized */
    *f -= w->g0[i] + w->g1[i] * (at->z - w->zk[i]);
    return 1;
}

/* The force interval of Sigma_e at a vertex. */
static void sigma_interval(const dp_network_step *w, size_t i, double u, double h, const vertex *at, double *lo,
                           double *hi)
{
    const dp_network_step_element *e = &w->el[i];
    double l, r, g = w->g0[i] + w->g1[i] * (at->z - w->zk[i]);
    *lo = *hi = -g;
    if (e->A) {
        dp_graph_force(e->A, arg_A(e, at), &l, &r);
        *lo += l, *hi += r;
    }
    if (e->S) {
        double wt = s_weight(e);
        dp_graph_force(e->S, arg_S(e, u, h, at), &l, &r);
        *lo += wt * l, *hi += wt * r;
    }
}

/* Puts element i free on the piece leaving `at` towards dir; 0 if the domain ends there. */
static int set_free(dp_network_step *w, size_t i, double u, double h, const vertex *at, int dir)
{
    elem_state *s = &w->es[i];
    double slope, f;
    vertex nx;
    if (!sigma_piece(w, i, u, h, at, dir, &slope, &f, &nx))
        return 0;
    touch(w, i);
    s->st = FREE;
    s->zref = at->z, s->lam0 = f, s->slope = slope;
    if (dir > 0)
        s->lo = *at, s->hi = nx;
    else
        s->lo = nx, s->hi = *at;
    return 1;
}

/* ---- the fixed forest -------------------------------------------------------------------------------- */

/* Root of i with path compression; pot[i] becomes v_i - v_root. */
static long find(dp_network_step *w, long i)
{
    long r = i;
    double acc = 0;
    while (w->parent[r] != r)
        acc += w->pot[r], r = w->parent[r];
    /* second pass: point every node on the path at the root with its full potential */
    while (w->parent[i] != i) {
        long up = w->parent[i];
        double pi = w->pot[i];
        w->parent[i] = r, w->pot[i] = acc;
        acc -= pi;
        i = up;
    }
    return r;
}

/* Adds the constraint v_b - v_a = z; 0 when it closes a cycle (dependent on those already in). */
static int join(dp_network_step *w, const dp_network_step_element *e, double z)
{
    long a = (long)end_index(w, e->a), b = (long)end_index(w, e->b);
    long ra = find(w, a), rb = find(w, b);
    if (ra == rb)
        return 0;
    double pa = w->pot[a], pb = w->pot[b];
    /* v_rb + pb - v_ra - pa = z; the ground stays a root */
    if (ra == (long)w->n) {
        w->parent[rb] = ra, w->pot[rb] = z + pa - pb;
    } else {
        w->parent[ra] = rb, w->pot[ra] = pb - pa - z;
    }
    return 1;
}

static void forest_reset(dp_network_step *w)
{
    for (size_t i = 0; i <= w->n; i++)
        w->parent[i] = (long)i, w->pot[i] = 0;
}

static void index_forest(dp_network_step *w);

/* Builds the forest of the fixed elements and the map node -> reduced unknown. */
static void build_forest(dp_network_step *w)
{
    forest_reset(w);
    for (size_t i = 0; i < w->ne; i++)
        if (w->es[i].st == FIXED)
            join(w, &w->el[i], w->es[i].fix.z);
    index_forest(w);
    w->forest_ok = 1;
}

/* The map node -> reduced unknown of the forest just joined. */
static void index_forest(dp_network_step *w)
{
    w->key_ok = 0;   /* the active-set pass keeps its key after indexing (pass_forest) */
    long ground = find(w, (long)w->n);
    size_t nr = 0;
    for (size_t i = 0; i <= w->n; i++)
        w->kidx[i] = -2;
    for (size_t i = 0; i < w->n; i++) {
        long r = find(w, (long)i);
        w->c[i] = w->pot[i];
        if (r == ground) {
            w->kidx[i] = -1;
            w->c[i] -= w->pot[w->n]; /* v_ground = 0 */
        } else {
            if (w->kidx[r] == -2)
                w->kidx[r] = (long)nr++;
            w->kidx[i] = w->kidx[r];
        }
    }
    w->nr = nr;
}

/* ---- the reduced system ------------------------------------------------------------------------------ */

/* rhs_eff = rhs - h sum_free (lam0 - slope zref) b. */
static void effective_rhs(dp_network_step *w, double h, const double *rhs)
{
    memcpy(w->rhs_eff, rhs, w->n * sizeof *rhs);
    for (size_t i = 0; i < w->ne; i++) {
        const elem_state *s = &w->es[i];
        const dp_network_step_element *e = &w->el[i];
        if (s->st != FREE)
            continue;
        double g = h * (s->lam0 - s->slope * s->zref);
        if (e->a >= 0)
            w->rhs_eff[e->a] += g;
        if (e->b >= 0)
            w->rhs_eff[e->b] -= g;
    }
}

/* Whether some free element's piece adds h slope b b^T to W. */
static int slopes_add(const dp_network_step *w, double h)
{
    for (size_t i = 0; i < w->ne; i++)
        if (w->es[i].st == FREE && h * w->es[i].slope != 0)
            return 1;
    return 0;
}

/* H = W + h sum_free slope b b^T; Hm is W itself when that sum is empty (no copy of the band). */
static void assemble_H(dp_network_step *w, double h)
{
    size_t p1 = w->p + 1;
    w->Hm = w->W;
    if (!slopes_add(w, h))
        return;
    w->Hm = w->H;
    memcpy(w->H, w->W, w->n * p1 * sizeof *w->H);
    for (size_t i = 0; i < w->ne; i++) {
        const elem_state *s = &w->es[i];
        const dp_network_step_element *e = &w->el[i];
        double k = h * s->slope;
        if (s->st != FREE || k == 0)
            continue;
        if (e->a >= 0)
            w->H[(size_t)e->a * p1] += k;
        if (e->b >= 0)
            w->H[(size_t)e->b * p1] += k;
        if (e->a >= 0 && e->b >= 0) {
            size_t lo = (size_t)(e->a < e->b ? e->a : e->b), d = (size_t)labs(e->b - e->a);
            w->H[lo * p1 + d] -= k;
        }
    }
}

/* The doubles the spares and W_fac take. */
static size_t spares_size(const dp_network_step *w)
{
    size_t size = w->W_fac ? w->n * (w->p + 1) : 0;
    for (int k = 0; k < SPARES; k++)
        size += w->spare[k].cap;
    return size;
}

static int reduced_storage(dp_network_step *w)
{
    size_t need = w->nr * (w->pr + 1);
    if (w->R_max && need > w->R_max)
        return DP_ELIMIT;
    if (w->R_max && need + spares_size(w) > w->R_max)
        drop_spares(w);   /* R needs their room */
    if (need > w->R_cap) {
        double *R = realloc(w->R, need * sizeof *R);
        if (R == NULL)
            return DP_ENOMEM;
        w->R = R, w->R_cap = need;
    }
    memset(w->R, 0, need * sizeof *w->R);
    return DP_OK;
}

/* Whether the assignment's structure (which elements are fixed, the free ones' slopes) is the one of a
 * factor's st and slope: H and R depend on nothing else, so a quiet step reuses them. */
static int same_structure(const dp_network_step *w, const unsigned char *st, const double *slope)
{
    for (size_t i = 0; i < w->ne; i++) {
        const elem_state *s = &w->es[i];
        if (st[i] != s->st || (s->st == FREE && slope[i] != s->slope))
            return 0;
    }
    return 1;
}

static void drop_spares(dp_network_step *w)
{
    for (int k = 0; k < SPARES; k++) {
        kept_factor *f = &w->spare[k];
        free(f->R), free(f->st), free(f->slope);
        *f = (kept_factor){ 0 };
    }
    free(w->W_fac);
    w->W_fac = NULL;
}

/* A spare to keep the current factor in: an empty one, else the least recently current; its storage taken
 * where R_max leaves room beside R's (NULL when it does not). W_fac holds the current W from then on. */
static kept_factor *spare_slot(dp_network_step *w)
{
    size_t band = w->n * (w->p + 1), m = w->ne ? w->ne : 1;
    kept_factor *f = &w->spare[0];
    for (int k = 1; k < SPARES; k++)
        if (!w->spare[k].ok ? f->ok : w->spare[k].stamp < f->stamp && f->ok)
            f = &w->spare[k];
    if (f->R != NULL)
        return f;
    if (w->R_max && w->R_cap + spares_size(w) + band + (w->W_fac ? 0 : band) > w->R_max)
        return NULL;
    if (w->W_fac == NULL && (w->W_fac = malloc(band * sizeof *w->W_fac)) != NULL)
        memcpy(w->W_fac, w->W, band * sizeof *w->W);
    f->R = malloc(band * sizeof *f->R), f->st = malloc(m), f->slope = malloc(m * sizeof *f->slope);
    if (!w->W_fac || !f->R || !f->st || !f->slope) {
        drop_spares(w);
        return NULL;
    }
    f->cap = band, f->ok = 0;
    return f;
}

/* The current factor and spare f change places (the current one kept only as a factor of W). */
static void swap_spare(dp_network_step *w, kept_factor *f)
{
    kept_factor cur = { w->R, w->R_cap, w->pr, w->factored && w->Hm == w->W, w->h_factored, w->fac_st, w->fac_slope,
                        ++w->fac_clock };
    w->R = f->R, w->R_cap = f->cap, w->pr = f->pr, w->factored = f->ok, w->h_factored = f->h;
    w->fac_st = f->st, w->fac_slope = f->slope;
    *f = cur;
}

/* After dp_network_step_W_changed: the factors hold if W has the bytes they were formed from. */
static void check_W(dp_network_step *w)
{
    size_t bytes = w->n * (w->p + 1) * sizeof *w->W;
    w->W_dirty = 0;
    if (w->W_fac != NULL && memcmp(w->W_fac, w->W, bytes) == 0)
        return;
    w->factored = 0;
    for (int k = 0; k < SPARES; k++)
        w->spare[k].ok = 0;
    if (w->W_fac != NULL)
        memcpy(w->W_fac, w->W, bytes);
}

/* The spare that holds the current structure's factor for h, or NULL. */
static kept_factor *spare_for(dp_network_step *w, double h)
{
    for (int k = 0; k < SPARES; k++)
        if (w->spare[k].ok && h == w->spare[k].h && same_structure(w, w->spare[k].st, w->spare[k].slope))
            return &w->spare[k];
    return NULL;
}

static int factor_reduced(dp_network_step *w);

/* rhs_eff for the current assignment; H and R's factor only where the structure changed (build_forest must
 * have run: R is over its trees): the current factor's, else a spare's, else a new one, the current going
 * to a spare where it is a factor of W. */
static int prepare(dp_network_step *w, double h, const double *rhs)
{
    effective_rhs(w, h, rhs);
    if (w->W_dirty)
        check_W(w);
    if (w->factored && h == w->h_factored && same_structure(w, w->fac_st, w->fac_slope))
        return DP_OK;
    kept_factor *f = spare_for(w, h);
    if (f != NULL) {
        swap_spare(w, f);
        w->Hm = w->W;   /* the spares hold factors of W only */
        return DP_OK;
    }
    if (w->factored && w->Hm == w->W && (f = spare_slot(w)) != NULL)
        swap_spare(w, f);   /* the current factor kept; the spare's storage is overwritten */
    assemble_H(w, h);
    int s = factor_reduced(w);
    w->factored = s == DP_OK;
    w->h_factored = h;
    for (size_t i = 0; s == DP_OK && i < w->ne; i++)
        w->fac_st[i] = (unsigned char)w->es[i].st, w->fac_slope[i] = w->es[i].slope;
    return s;
}

/* R = T^T H T in band storage, factored (Cholesky). */
/* A factorization of more multiply-adds than this (a few milliseconds) is done by polled_cholesky, which
 * asks the poll as it goes: GSL's takes seconds at the widest band the memory limit lets through (1600
 * nodes coupled all to all: 3 s), and a stop must not wait for it. Below it GSL's, bit for bit as always. */
#define LONG_FACTOR (1u << 22)

/* R = L L^T in GSL's band storage (row j holds L(j+d, j), d = 0..q-1), column by column as LAPACK's dpbtf2:
 * the pivot's square root, the column scaled by its inverse, the trailing band updated by the column's outer
 * product. The poll is asked every LONG_FACTOR multiply-adds; DP_ECANCEL when it says stop, DP_ESOLVE when
 * R is not positive definite. */
static int polled_cholesky(dp_network_step *w, size_t q)
{
    size_t n = w->nr, p = q - 1, done = 0;
    double *R = w->R;
    for (size_t j = 0; j < n; j++) {
        double *col = R + j * q, ajj = col[0];
        if (!(ajj > 0))
            return DP_ESOLVE;
        ajj = sqrt(ajj);
        col[0] = ajj;
        size_t kn = n - 1 - j < p ? n - 1 - j : p;
        double inv = 1 / ajj;
        for (size_t d = 1; d <= kn; d++)
            col[d] *= inv;
        for (size_t a = 1; a <= kn; a++) {
            double *row = R + (j + a) * q, la = col[a];
            for (size_t b = a; b <= kn; b++)
                row[b - a] -= la * col[b];
        }
        done += kn * kn / 2 + 1;
        if (done > LONG_FACTOR) {
            w->work += done, done = 0;
            if (polled_stop_units(w))
                return DP_ECANCEL;
        }
    }
    w->work += done;
    return DP_OK;
}

static int factor_reduced(dp_network_step *w)
{
    size_t n = w->n, p1 = w->p + 1, pr = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t d = 1; d < p1 && i + d < n; d++) {
            long ki = w->kidx[i], kj = w->kidx[i + d];
            if (w->Hm[i * p1 + d] != 0 && ki >= 0 && kj >= 0 && (size_t)labs(ki - kj) > pr)
                pr = (size_t)labs(ki - kj);
        }
    w->pr = pr;
    if (w->nr == 0)
        return DP_OK;
    int s = reduced_storage(w);
    if (s != DP_OK)
        return s;
    size_t q = pr + 1;
    for (size_t i = 0; i < n; i++) {
        long ki = w->kidx[i];
        if (ki < 0)
            continue;
        w->R[(size_t)ki * q] += w->Hm[i * p1];
        for (size_t d = 1; d < p1 && i + d < n; d++) {
            long kj = w->kidx[i + d];
            double h = w->Hm[i * p1 + d];
            if (kj < 0 || h == 0)
                continue;
            if (kj == ki)
                w->R[(size_t)ki * q] += 2 * h;
            else if (kj > ki)
                w->R[(size_t)ki * q + (size_t)(kj - ki)] += h;
            else
                w->R[(size_t)kj * q + (size_t)(ki - kj)] += h;
        }
    }
    if (w->poll != NULL && w->nr * q * q > LONG_FACTOR)
        return polled_cholesky(w, q);
    w->work += w->nr * q * q;      /* the band Cholesky's multiply-adds, to within a factor of two */
    return dp_band_cholesky(w->R, w->nr, pr);
}

/* y = H x for the symmetric band H. */
static void band_mul(const dp_network_step *w, const double *x, double *y)
{
    dp_band_symv(w->Hm, w->n, w->p, x, y);
}

/* The minimizer of the current assignment into vs: v = T y + c with R y = T^T (rhs_eff - H c). */
static int solve_assignment(dp_network_step *w)
{
    size_t n = w->n;
    band_mul(w, w->c, w->res);
    memset(w->y, 0, w->nr * sizeof *w->y);
    for (size_t i = 0; i < n; i++)
        if (w->kidx[i] >= 0)
            w->y[w->kidx[i]] += w->rhs_eff[i] - w->res[i];
    if (w->nr && dp_band_cholesky_solve(w->R, w->nr, w->pr, w->y) != DP_OK)
        return DP_ESOLVE;
    for (size_t i = 0; i < n; i++)
        w->vs[i] = (w->kidx[i] >= 0 ? w->y[w->kidx[i]] : 0) + w->c[i];
    return DP_OK;
}

/* The fixed elements' multipliers from the residual h sum_F b_e lambda_e = rhs_eff - H v, peeled off the
 * forest leaf by leaf (each leaf's residual belongs to its one remaining edge). */
static void multipliers(dp_network_step *w, double h)
{
    size_t n = w->n, nq = 0;
    for (size_t i = 0; i <= n; i++)
        w->head[i] = -1, w->deg[i] = 0;
    for (size_t k = 0; k < w->ne; k++) {
        if (w->es[k].st != FIXED)
            continue;
        size_t a = end_index(w, w->el[k].a), b = end_index(w, w->el[k].b);
        w->next_edge[2 * k] = w->head[a], w->head[a] = (long)(2 * k);
        w->next_edge[2 * k + 1] = w->head[b], w->head[b] = (long)(2 * k + 1);
        w->deg[a]++, w->deg[b]++;
        touch_values(w, k);
        w->es[k].lam = NAN;
    }
    for (size_t i = 0; i < n; i++) {   /* residuals on the forest's nodes only: no other is read */
        if (w->deg[i] == 0)
            continue;
        double Hv = dp_band_row(w->Hm + i * (w->p + 1), w->p, w->vs, i, n);
        w->res_err[i] = 8 * DBL_EPSILON * (fabs(w->rhs_eff[i]) + fabs(Hv));   /* eps times its two terms */
        w->res[i] = w->rhs_eff[i] - Hv;
        if (w->deg[i] == 1)
            w->queue[nq++] = i;
    }
    for (size_t qi = 0; qi < nq; qi++) {
        size_t i = w->queue[qi];
        if (w->deg[i] != 1)
            continue;
        long slot = w->head[i];
        while (slot >= 0 && !isnan(w->es[slot / 2].lam) )
            slot = w->next_edge[slot];
        if (slot < 0)
            continue;
        size_t k = (size_t)slot / 2;
        const dp_network_step_element *e = &w->el[k];
        double sign_i = (long)i == e->b ? 1 : -1;   /* b_e's entry at node i */
        double lam = w->res[i] / (h * sign_i);
        w->es[k].lam = lam;
        w->es[k].lam_err = w->res_err[i] / h;
        size_t j = end_index(w, (long)i == e->b ? e->a : e->b);
        w->res[j] -= h * -sign_i * lam;
        if (j < n)
            w->res_err[j] += w->res_err[i];
        w->deg[i]--, w->deg[j]--;
        if (j < n && w->deg[j] == 1)
            w->queue[nq++] = j;
    }
}

/* ---- the active-set iteration ---------------------------------------------------------------------- */

/* Whether a fixed element's multiplier lies in [lo, hi] up to rounding: of the forces involved, and of the
 * multiplier itself, a residual over h (at a step of a billionth of dt that is most of its digits). */
static int inside(const elem_state *s, double lo, double hi)
{
    double lam = s->lam;
    double tol = 1e-12 * (1 + fabs(lam) + (isfinite(lo) ? fabs(lo) : 0) + (isfinite(hi) ? fabs(hi) : 0)) + s->lam_err;
    return lam >= lo - tol && lam <= hi + tol;
}

/* The end of Sigma_e's domain on side dir (+1: z lies above it, -1: below), for a z outside it: the nearer
 * of A's vertical end ray at y + v_b and S's at (y - u)/beta (a rope's length, Babováková 2012), since the
 * domain is where both graphs are defined. Where both end it at the same z, A's vertex (read exactly in A).
 * 0 when neither ends it on that side or the other graph is not defined at that end (an empty domain). */
static int domain_end(const dp_network_step *w, size_t i, double u, double h, int dir, vertex *at)
{
    const dp_network_step_element *e = &w->el[i];
    const dp_graph *A = e->A, *S = e->S;
    int found = 0;
    if (A && (dir > 0 ? A->right[0] : A->left[0]) == 0) {
        size_t k = dir > 0 ? A->n - 1 : 0;
        *at = (vertex){ A->y[k] + e->vb, SRC_A, A->y[k] };
        found = 1;
    }
    if (S && (dir > 0 ? S->right[0] : S->left[0]) == 0) {
        size_t k = dir > 0 ? S->n - 1 : 0;
        double z = (S->y[k] - u) / s_beta(e, h);
        if (!found || (dir > 0 ? z < at->z : z > at->z))
            *at = (vertex){ z, SRC_S, S->y[k] }, found = 1;
    }
    double lo, hi;
    if (!found)
        return 0;
    sigma_interval(w, i, u, h, at, &lo, &hi);
    return !(lo == hi && !isfinite(lo));
}

/* An element with no law in the step (a contact not armed for it): free on the whole line with no force,
 * sigma_piece's sums for it written out. */
static int start_lawless(dp_network_step *w, size_t i, double z)
{
    double s = 0, f = 0;
    s -= w->g1[i];
    f -= w->g0[i] + w->g1[i] * (z - w->zk[i]);
    elem_state *st = &w->es[i];
    st->st = FREE;
    st->zref = z, st->lam0 = f, st->slope = s;
    st->lo = (vertex){ -INFINITY, SRC_NONE, 0 }, st->hi = (vertex){ INFINITY, SRC_NONE, 0 };
    return 1;
}

/* The start assignment of a damper-only element (no spring graph, no relaxation: a Coulomb element on a
 * belt) whose z lies strictly inside its graph's domain and on no vertex: free on the piece holding z, from
 * the vertex below to the one above. What assign_start's general path finds, without its second search and
 * its force interval (single-valued off the vertices); an element with no law at all free on the line. 0
 * when z is not such a point (the general path then decides). */
static int start_inside_piece(dp_network_step *w, size_t i, double z)
{
    const dp_network_step_element *e = &w->el[i];
    const dp_graph *A = e->A;
    if (e->S != NULL || (w->gamma && w->gamma[i]))
        return 0;
    if (A == NULL)
        return isfinite(z) && start_lawless(w, i, z);
    double y = z - e->vb;
    size_t n = A->n, k = dp_lower_bound(A->y, n, y);
    if (!isfinite(y) || (k < n && A->y[k] == y) || (y < A->y[0] && !(A->left[0] > 0)) ||
        (y > A->y[n - 1] && !(A->right[0] > 0)))
        return 0;
    /* the piece towards +1 as dp_graph_piece and sigma_piece form it (y is on no vertex, so the first vertex
     * above it is y[k]), operation for operation: the same slope and force bit for bit */
    double slope, y0, f0, next;
    if (k == n)
        slope = A->right[1] / A->right[0], y0 = A->y[n - 1], f0 = A->f[n - 1], next = INFINITY;
    else if (k == 0)
        slope = A->left[0] > 0 ? A->left[1] / A->left[0] : 0, y0 = A->y[0], f0 = A->f[0], next = A->y[0];
    else
        slope = (A->f[k] - A->f[k - 1]) / (A->y[k] - A->y[k - 1]), y0 = A->y[k - 1], f0 = A->f[k - 1], next = A->y[k];
    double s = 0, f = 0;
    s += slope, f += y == y0 ? f0 : f0 + slope * (y - y0);
    s -= w->g1[i];
    f -= w->g0[i] + w->g1[i] * (z - w->zk[i]);
    elem_state *st = &w->es[i];
    st->st = FREE;
    st->zref = z, st->lam0 = f, st->slope = s;
    st->hi = isfinite(next) ? (vertex){ next + e->vb, SRC_A, next } : (vertex){ INFINITY, SRC_NONE, 0 };
    st->lo = k > 0 ? (vertex){ A->y[k - 1] + e->vb, SRC_A, A->y[k - 1] } : (vertex){ -INFINITY, SRC_NONE, 0 };
    return 1;
}

/* The assignment at a start point v: elements on a vertex of A are fixed there (while independent),
 * others free on the piece holding z; one whose z lies beyond a vertical end of A fixed at that end. 0 when
 * some z lies outside its graph's domain otherwise. */
static int assign_start(dp_network_step *w, double h, const double *u, const double *v)
{
    touch_all(w);
    forest_reset(w);
    for (size_t i = 0; i < w->ne; i++) {
        const dp_network_step_element *e = &w->el[i];
        double z = rel_velocity(e, v), lo, hi, slope, f;
        if (start_inside_piece(w, i, z))
            continue;
        vertex at = { z, SRC_NONE, 0 }, below;
        if (e->A && dp_graph_has_vertex(e->A, z - e->vb))
            at.src = SRC_A, at.y = z - e->vb;
        else if (e->S && dp_graph_has_vertex(e->S, u[i] + s_beta(e, h) * z))
            at.src = SRC_S, at.y = u[i] + s_beta(e, h) * z;
        sigma_interval(w, i, u[i], h, &at, &lo, &hi);
        if (lo == hi && !isfinite(lo)) {
            /* outside the domain (a contact approaching, a rope pulled past its length): fixed at its end, where the
             * first solve puts it; v is then infeasible until the walk reaches a minimizer */
            if (!domain_end(w, i, u[i], h, lo > 0 ? 1 : -1, &at) || !join(w, e, at.z))
                return 0;
            w->es[i].st = FIXED, w->es[i].fix = at;
            continue;
        }
        if (lo < hi && join(w, e, z)) {  /* a vertex with a force interval */
            w->es[i].st = FIXED, w->es[i].fix = at;
            continue;
        }
        if (!set_free(w, i, u[i], h, &at, +1) && !set_free(w, i, u[i], h, &at, -1))
            return 0;
        /* inside a piece (not at a vertex): the piece reaches back to the previous vertex */
        if (at.src == SRC_NONE && sigma_piece(w, i, u[i], h, &at, -1, &slope, &f, &below))
            w->es[i].lo = below;
    }
    return 1;
}

/* The first free element that meets a vertex on the way from v along d, and the fraction t of the way;
 * t = 1 when none does. Elements whose ends the fixed forest already joins cannot move. */
static double blocking(dp_network_step *w, const double *v, long *which, int *side)
{
    double t = 1;
    *which = -1;
    for (size_t i = 0; i < w->ne; i++) {
        const elem_state *s = &w->es[i];
        const dp_network_step_element *e = &w->el[i];
        if (s->st != FREE)
            continue;
        if (find(w, (long)end_index(w, e->a)) == find(w, (long)end_index(w, e->b)))
            continue;
        double z = rel_velocity(e, v), dz = rel_velocity(e, w->d), ti;
        if (dz > 0 && isfinite(s->hi.z))
            ti = (s->hi.z - z) / dz;
        else if (dz < 0 && isfinite(s->lo.z))
            ti = (s->lo.z - z) / dz;
        else
            continue;
        if (ti < 0)
            ti = 0;
        if (ti < t) {
            t = ti, *which = (long)i, *side = dz > 0 ? 1 : -1;
        }
    }
    return t;
}

/* Releases the lowest-index fixed element whose multiplier left its interval; 0 when none did. */
static int release(dp_network_step *w, double h, const double *u)
{
    for (size_t i = 0; i < w->ne; i++) {
        elem_state *s = &w->es[i];
        if (s->st != FIXED)
            continue;
        double lo, hi;
        sigma_interval(w, i, u[i], h, &s->fix, &lo, &hi);
        if (inside(s, lo, hi))
            continue;
        vertex at = s->fix;
        if (set_free(w, i, u[i], h, &at, s->lam > hi ? 1 : -1))
            return 1;
    }
    return 0;
}

/* Whether free element i sits exactly at rest (z = v_b, inside A's interval there) between two ends the
 * fixed forest already joins: a stick interval in parallel with a fixed one, which could not be fixed itself
 * (its constraint depends on the others). */
static int parallel_at_rest(dp_network_step *w, size_t i, const dp_network_step_forces *o)
{
    const dp_network_step_element *e = &w->el[i];
    double lo, hi;
    if (w->es[i].st != FREE || e->A == NULL || e->S != NULL || o->z != e->vb || w->g1[i] != 0 || w->g0[i] != 0)
        return 0;
    dp_graph_force(e->A, 0, &lo, &hi);
    return hi > lo && find(w, (long)end_index(w, e->a)) == find(w, (long)end_index(w, e->b));
}

/* A fixed element at rest with the same ends as free element i (either way round), or -1; *sign is +1 when
 * it has i's orientation. */
static long parallel_partner(const dp_network_step *w, size_t i, double *sign)
{
    const dp_network_step_element *e = &w->el[i];
    for (long slot = w->head[end_index(w, e->a)]; slot >= 0; slot = w->next_edge[slot]) {
        size_t j = (size_t)slot / 2;
        const dp_network_step_element *p = &w->el[j];
        if (j == i || p->A == NULL || p->S != NULL || w->es[j].fix.src != SRC_A || w->es[j].fix.y != 0)
            continue;
        if (p->a == e->a && p->b == e->b)
            return *sign = 1, (long)j;
        if (p->a == e->b && p->b == e->a)
            return *sign = -1, (long)j;
    }
    return -1;
}

/* Member k of the parallel group of fixed element j: j itself (sign +1) or a free element at rest marked in
 * it; its interval in j's orientation into [*lo, *hi]. */
static int group_member(const dp_network_step *w, const dp_network_step_forces *f, size_t k, long j, double *lo,
                        double *hi)
{
    double sg = 1, l, r;
    if (k != (size_t)j && !(f[k].at_rest == 2 && parallel_partner(w, k, &sg) == j))
        return 0;
    dp_graph_force(w->el[k].A, 0, &l, &r);
    *lo = sg > 0 ? l : -r, *hi = sg > 0 ? r : -l;
    return (int)sg;
}

/* Where some member's interval is unbounded (a resting contact, the cone (-inf, 0], beside a sticking friction
 * element: Moreau-Jean's plastic impact on a block on a belt), a share in proportion to the width would be
 * inf/inf. Then the bounded members take what they can, the total clamped to the sum of their intervals and
 * to what the unbounded ones leave possible; each unbounded member takes its finite end, and the first
 * unbounded one in the direction of what is left takes the rest. Every share then lies in its interval. */
static void share_unbounded(const dp_network_step *w, dp_network_step_forces *f, long j, double total,
                            double lb, double hb, double lu, double hu)
{
    double tb = fmin(fmax(fmin(fmax(total, lb), hb), total - hu), total - lu);
    double rest = total - tb, anchors = 0, lo, hi;
    int sg;
    for (size_t k = 0; k < w->ne; k++)
        if ((sg = group_member(w, f, k, j, &lo, &hi)) != 0 && !(isfinite(lo) && isfinite(hi)))
            anchors += isfinite(lo) ? lo : isfinite(hi) ? hi : 0;
    double spare = rest - anchors;
    int given = 0;
    for (size_t k = 0; k < w->ne; k++) {
        if ((sg = group_member(w, f, k, j, &lo, &hi)) == 0)
            continue;
        double share;
        if (isfinite(lo) && isfinite(hi)) {
            share = hb > lb ? lo + (tb - lb) * (hi - lo) / (hb - lb) : lo;
        } else {
            share = isfinite(lo) ? lo : isfinite(hi) ? hi : 0;
            if (!given && (spare > 0 ? hi == INFINITY : lo == -INFINITY))
                share += spare, given = 1;
        }
        f[k].lambda = f[k].a = sg * share;
        f[k].at_rest = 1;
    }
}

/* The sums of a parallel group's intervals: the bounded members' [lo, hi], the unbounded ones' [lu, hu]. */
typedef struct group_sum {
    double lo, hi, lu, hu;
    int unbounded;
} group_sum;

static void group_add(group_sum *g, double lo, double hi)
{
    if (isfinite(lo) && isfinite(hi))
        g->lo += lo, g->hi += hi;
    else
        g->lu += lo, g->hu += hi, g->unbounded = 1;
}

/* Parallel stick intervals hold their common force together, but how they split it is not determined by
 * the motion: the split reported gives each its lower bound plus a share of the rest in proportion to its
 * interval's width (so each stays inside its own interval), and all of them stick. */
static void share_parallel(dp_network_step *w, dp_network_step_forces *f)
{
    for (size_t i = 0; i < w->ne; i++) {
        double sign_i, lo, hi;
        long j;
        if (f[i].z != w->el[i].vb)   /* parallel_at_rest's first test, without the call: most elements */
            continue;
        if (!parallel_at_rest(w, i, &f[i]) || (j = parallel_partner(w, i, &sign_i)) < 0)
            continue;
        /* the group: j and every free element at rest parallel to it (in j's orientation) */
        double total = f[j].lambda;
        group_sum g = { 0 };
        group_member(w, f, (size_t)j, j, &lo, &hi);
        group_add(&g, lo, hi);
        for (size_t k = i; k < w->ne; k++) {
            double sg;
            if (parallel_at_rest(w, k, &f[k]) && parallel_partner(w, k, &sg) == j) {
                total += sg * f[k].lambda;
                f[k].at_rest = 2;   /* mark: in this group */
                group_member(w, f, k, j, &lo, &hi);
                group_add(&g, lo, hi);
            }
        }
        if (g.unbounded) {
            share_unbounded(w, f, j, total, g.lo, g.hi, g.lu, g.hu);
            continue;
        }
        double spare = total - g.lo, width = g.hi - g.lo;
        for (size_t k = 0; k < w->ne; k++) {
            int sg = group_member(w, f, k, j, &lo, &hi);
            if (sg == 0)
                continue;
            double share = lo + spare * (hi - lo) / width;
            f[k].lambda = f[k].a = sg * share;
            f[k].at_rest = 1;
        }
    }
}

static void report(dp_network_step *w, double h, const double *u, const double *v, dp_network_step_forces *f)
{
    for (size_t i = 0; i < w->ne; i++) {
        const dp_network_step_element *e = &w->el[i];
        const elem_state *s = &w->es[i];
        dp_network_step_forces *o = &f[i];
        double alo = 0, ahi = 0, slo = 0, shi = 0;
        o->z = rel_velocity(e, v);
        vertex at = s->st == FIXED ? s->fix : (vertex){ o->z, SRC_NONE, 0 };
        o->lambda = s->st == FIXED ? s->lam : s->lam0 + s->slope * (o->z - s->zref);
        o->lambda += w->g0[i] + w->g1[i] * (at.z - w->zk[i]);   /* the graphs' part, without gamma */
        if (e->A && (s->st == FIXED || e->S))   /* a free damper alone: its force is lambda, not at rest */
            dp_graph_force(e->A, arg_A(e, &at), &alo, &ahi);
        if (e->S) {
            dp_graph_force(e->S, arg_S(e, u[i], h, &at), &slo, &shi);
            slo *= s_weight(e), shi *= s_weight(e);
        }
        /* Where both parts are set-valued the split is not unique: the damper takes what it can. */
        if (slo == shi)
            o->s = slo, o->a = o->lambda - slo;
        else if (alo == ahi)
            o->a = alo, o->s = o->lambda - alo;
        else {
            o->a = fmin(fmax(o->lambda - slo, alo), ahi);
            o->s = o->lambda - o->a;
        }
        o->at_rest = s->st == FIXED && e->A && arg_A(e, &at) == 0 && ahi > alo;
        if (o->at_rest)
            o->z = e->vb;
    }
    share_parallel(w, f);
}

/* The piecewise-linear problem (the relaxation frozen in its linearization) from the start point v. */
/* Moves free element i, whose relative velocity z left its piece, to where z lies: fixed at the first
 * vertex with a force interval on the way (or the domain's end), else on the piece holding z. */
static void follow(dp_network_step *w, size_t i, double h, const double *u, double z)
{
    elem_state *s = &w->es[i];
    int dir = z > s->hi.z ? 1 : -1;
    for (int guard = 0; guard < 64; guard++) {
        vertex at = dir > 0 ? s->hi : s->lo;
        double lo, hi;
        sigma_interval(w, i, u[i], h, &at, &lo, &hi);
        if (lo < hi || !set_free(w, i, u[i], h, &at, dir)) {
            touch(w, i);
            s->st = FIXED, s->fix = at;
            return;
        }
        if (dir > 0 ? z <= s->hi.z : z >= s->lo.z)
            return;
    }
}

/* One update of the primal-dual active-set method: every free element whose z left its piece and every
 * fixed one whose multiplier left its interval changes at once (a semismooth Newton step on the
 * piecewise-linear optimality conditions). Returns how many changed: 0 means vs is the exact minimizer. */
static size_t bulk_update(dp_network_step *w, double h, const double *u)
{
    size_t changed = 0;
    for (size_t i = 0; i < w->ne; i++) {
        elem_state *s = &w->es[i];
        if (s->st == FREE) {
            double z = rel_velocity(&w->el[i], w->vs);
            if (z > s->hi.z || z < s->lo.z)
                follow(w, i, h, u, z), changed++;
        } else {
            double lo, hi;
            sigma_interval(w, i, u[i], h, &s->fix, &lo, &hi);
            if (!inside(s, lo, hi)) {
                vertex at = s->fix;
                if (set_free(w, i, u[i], h, &at, s->lam > hi ? 1 : -1))
                    changed++;
            }
        }
    }
    return changed;
}

/* Whether the fixed elements still form a forest (bulk updates may close a cycle); each element's part of
 * the key (pass_forest) on the way. */
static int fixed_forest(dp_network_step *w)
{
    w->forest_ok = 0;   /* joined here, indexed by the caller */
    w->key_ok = 0;
    forest_reset(w);
    for (size_t i = 0; i < w->ne; i++) {
        int fx = w->es[i].st == FIXED;
        w->key_fixed[i] = (unsigned char)fx, w->key_z[i] = w->es[i].fix.z;
        if (fx && !join(w, &w->el[i], w->es[i].fix.z))
            return 0;
    }
    return 1;
}

/* Whether a and b have the same bits (a vertex's z: -0 and 0 differ in a forest's potentials). */
static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* The forest of the fixed elements and its index for an iteration of the active-set pass: as fixed_forest
 * and index_forest would give them, kept when the fixed elements and their vertices are those of the last
 * one (the union-find then holds their partition: joined by assign_start, or unchanged since). 0 when the
 * fixed elements close a cycle. */
static int pass_forest(dp_network_step *w)
{
    int same = w->key_ok;
    for (size_t i = 0; same && i < w->ne; i++) {
        int fx = w->es[i].st == FIXED;
        same = fx == w->key_fixed[i] && (!fx || same_bits(w->es[i].fix.z, w->key_z[i]));
    }
    if (same) {
        w->forest_ok = 0;   /* as fixed_forest leaves it: not build_forest's compression */
        return 1;
    }
    if (!fixed_forest(w))
        return 0;
    index_forest(w);
    w->key_ok = 1;
    return 1;
}

/* The primal-dual active-set method from the warm start: usually the answer in one to three solves, with no
 * guarantee of termination outside M-matrix structure; DP_OK with v the minimizer, DP_ECANCEL when the poll
 * said stop, or 1 when it did not settle (the caller then runs the primal method, which always ends). */
static int pdas(dp_network_step *w, double h, const double *rhs, const double *u, double *v, unsigned long long *iters)
{
    for (int it = 0; it < 12; it++) {
        if (!pass_forest(w))   /* the fixed forest and its index, as build_forest would give them */
            return 1;
        (*iters)++;
        if (prepare(w, h, rhs) != DP_OK || solve_assignment(w) != DP_OK)
            return 1;
        if (polled_stop(w))
            return DP_ECANCEL;
        multipliers(w, h);
        if (bulk_update(w, h, u) == 0) {
            memcpy(v, w->vs, w->n * sizeof *v);
            return DP_OK;
        }
    }
    return 1;
}

static int solve_pl(dp_network_step *w, double h, const double *rhs, const double *u, double *v,
                    unsigned long long *iters)
{
    size_t n = w->n;
    if (!assign_start(w, h, u, v)) {
        memset(v, 0, n * sizeof *v);
        if (!assign_start(w, h, u, v))
            return DP_ESOLVE;
    }
    int fast = pdas(w, h, rhs, u, v, iters);
    if (fast == DP_OK || fast == DP_ECANCEL)
        return fast;
    /* the primal active-set method: from a point of the domain, the objective falls strictly between
     * minimizers of assignments, so it ends; this is the guarantee behind the fast path above */
    if (!assign_start(w, h, u, v)) {
        memset(v, 0, n * sizeof *v);
        if (!assign_start(w, h, u, v))
            return DP_ESOLVE;
    }
    size_t cap = 64 + 8 * w->ne;
    for (size_t it = 0; it < cap; it++) {
        (*iters)++;
        build_forest(w);
        int s = prepare(w, h, rhs);
        s = s ? s : solve_assignment(w);
        if (s != DP_OK)
            return s;
        if (polled_stop(w))
            return DP_ECANCEL;
        for (size_t i = 0; i < n; i++)
            w->d[i] = w->vs[i] - v[i];
        long which;
        int side = 0;
        double t = blocking(w, v, &which, &side);
        if (which < 0) {
            memcpy(v, w->vs, n * sizeof *v);
            multipliers(w, h);
            if (!release(w, h, u))
                return DP_OK;
            continue;
        }
        for (size_t i = 0; i < n; i++)
            v[i] += t * w->d[i];
        elem_state *b = &w->es[which];
        touch(w, (size_t)which);
        b->st = FIXED;
        b->fix = side > 0 ? b->hi : b->lo;
    }
    return DP_ESOLVE;
}

static double zmax_change(const dp_network_step *w, const double *v)
{
    double worst = 0;
    for (size_t i = 0; i < w->ne; i++)
        if (w->gamma[i]) {
            double z = rel_velocity(&w->el[i], v);
            worst = fmax(worst, fabs(z - w->zk[i]) / (1 + fabs(z)));
        }
    return worst;
}

int dp_network_step_solve(dp_network_step *w, double h, const double *rhs, const double *u, const double *v_guess,
                 double *v, dp_network_step_forces *f, unsigned long long *iters)
{
    memcpy(v, v_guess, w->n * sizeof *v);
    if (w->gamma == NULL) {
        int s = solve_pl(w, h, rhs, u, v, iters);
        if (s == DP_OK)
            report(w, h, u, v, f);
        return s;
    }
    double th = w->theta;
    for (size_t i = 0; i < w->ne; i++) {
        w->zk[i] = rel_velocity(&w->el[i], v_guess);
        w->gshift[i] = (1 - th) * w->zk[i] - w->el[i].vb;
    }
    /* Newton-Josephy: gamma linearized at the last iterate, each linearized step solved exactly; the
     * iterates settle on the active set and then converge quadratically to rounding. */
    for (int it = 0; it < 100; it++) {
        for (size_t i = 0; i < w->ne; i++) {
            if (w->gamma[i] == NULL)
                continue;
            double arg = th * w->zk[i] + w->gshift[i];
            w->g0[i] = dp_relaxation_eval(w->gamma[i], arg);
            w->g1[i] = th * dp_relaxation_slope(w->gamma[i], arg);
        }
        int s = solve_pl(w, h, rhs, u, v, iters);
        if (s != DP_OK)
            return s;
        double change = zmax_change(w, v);
        for (size_t i = 0; i < w->ne; i++)
            w->zk[i] = rel_velocity(&w->el[i], v);
        if (change <= 1e-14) {
            report(w, h, u, v, f);
            return DP_OK;
        }
    }
    return DP_ESOLVE;
}

/* ---- the assignment held: event location ------------------------------------------------------------- */

size_t dp_network_step_pattern_bytes(const dp_network_step *w)
{
    return (w->ne ? w->ne : 1) * sizeof *w->es;
}

/* After a save or restore the state and the buffer agree: nothing is dirty, `buf` is the one synced. */
static void synced(dp_network_step *w, const void *buf)
{
    for (size_t k = 0; k < w->ndirty; k++)
        w->dirty[w->dirty_list[k]] = 0;
    w->ndirty = 0, w->all_dirty = 0, w->synced = buf;
}

/* Both copy only the elements that may differ (all of them unless buf is the buffer last synced). */
void dp_network_step_pattern_save(dp_network_step *w, void *buf)
{
    memo_forget(w);   /* the buffer's assignment changes */
    elem_state *to = buf;
    if (buf != w->synced || w->all_dirty)
        memcpy(to, w->es, w->ne * sizeof *w->es);
    else
        for (size_t k = 0; k < w->ndirty; k++)
            to[w->dirty_list[k]] = w->es[w->dirty_list[k]];
    synced(w, buf);
}

/* Whether restoring `to` over `from` fixes, frees or moves a fixed element (the forest changes). */
static int moves_fixed(const elem_state *from, const elem_state *to)
{
    return from->st != to->st || (to->st == FIXED && memcmp(&from->fix.z, &to->fix.z, sizeof to->fix.z) != 0);
}

void dp_network_step_pattern_restore(dp_network_step *w, const void *buf)
{
    const elem_state *from = buf;
    if (buf != w->synced || w->all_dirty) {
        memcpy(w->es, from, w->ne * sizeof *w->es);
        w->forest_ok = 0;
    } else {
        for (size_t k = 0; k < w->ndirty; k++) {
            size_t i = w->dirty_list[k];
            if (moves_fixed(&w->es[i], &from[i]))
                w->forest_ok = 0;
            w->es[i] = from[i];
        }
    }
    synced(w, buf);
}

void dp_network_step_relaxation_start(dp_network_step *w, const double *v_start)
{
    for (size_t i = 0; w->gamma && i < w->ne; i++) {
        w->zk[i] = rel_velocity(&w->el[i], v_start);
        w->gshift[i] = (1 - w->theta) * w->zk[i] - w->el[i].vb;
    }
}

/* With relaxation, a held step's free elements keep their pieces (gamma is smooth: no vertex moves) but take
 * their slope and force again at the current linearization, as a whole solve's start does (set_free); a
 * spring graph's piece (an elastoplastic spring, a graph of finite slope, a compliant contact) keeps its
 * graph vertices, whose z = (y - u) / beta (beta = h, or h theta when theta-weighted) move with h and u. */
static void refresh_free(dp_network_step *w, double h, const double *u)
{
    for (size_t i = 0; i < w->ne; i++) {
        elem_state *s = &w->es[i];
        int ep = w->el[i].S != NULL;   /* a spring graph: its vertices' z move with h and u */
        if (s->st != FREE || (!ep && (w->gamma == NULL || w->gamma[i] == NULL)))
            continue;
        if (ep && s->lo.src == SRC_S)
            s->lo.z = (s->lo.y - u[i]) / s_beta(&w->el[i], h);
        if (ep && s->hi.src == SRC_S)
            s->hi.z = (s->hi.y - u[i]) / s_beta(&w->el[i], h);
        int dir = isfinite(s->lo.z) ? 1 : -1;
        vertex at = isfinite(s->lo.z) ? s->lo : isfinite(s->hi.z) ? s->hi : (vertex){ s->zref, SRC_NONE, 0 }, nx;
        double slope, f;
        touch_values(w, i);   /* the same piece: its vertices, hence the forest, stay */
        if (sigma_piece(w, i, u[i], h, &at, dir, &slope, &f, &nx))
            s->zref = at.z, s->lam0 = f, s->slope = slope;
    }
}

/* The held assignment's linear solve; with relaxation Newton-Josephy's iterations on gamma from the start
 * velocity (dp_network_step_relaxation_start), as dp_network_step_solve, the assignment held throughout. */
static int solve_held(dp_network_step *w, double h, const double *rhs, const double *u, int refresh)
{
    double th = w->theta;
    for (int it = 0; it < 100; it++) {
        for (size_t i = 0; w->gamma && i < w->ne; i++) {
            if (w->gamma[i] == NULL)
                continue;
            double arg = th * w->zk[i] + w->gshift[i];
            w->g0[i] = dp_relaxation_eval(w->gamma[i], arg);
            w->g1[i] = th * dp_relaxation_slope(w->gamma[i], arg);
        }
        if (refresh)   /* not when neither relaxation nor a spring graph is there to refresh */
            refresh_free(w, h, u);
        if (!w->forest_ok)   /* held: the fixed elements are those of the last held solve, unless restored */
            build_forest(w);
        int s = prepare(w, h, rhs);
        s = s ? s : solve_assignment(w);
        if (s != DP_OK || w->gamma == NULL)
            return s;
        double change = zmax_change(w, w->vs);
        for (size_t i = 0; i < w->ne; i++)
            w->zk[i] = rel_velocity(&w->el[i], w->vs);
        if (change <= 1e-14)
            return DP_OK;
    }
    return DP_ESOLVE;
}

/* ---- held solves remembered ------------------------------------------------------------------------- */

static void memo_free(dp_network_step *w)
{
    for (int k = 0; k < HELD_MEMO; k++) {
        held_memo *m = &w->memo[k];
        free(m->rhs), free(m->u), free(m->W), free(m->v), free(m->margin), free(m->lam), free(m->lam_err), free(m->f);
    }
    free(w->memo_el);
}

/* Whether a held solve now may be remembered or replayed: the assignment is exactly the buffer's (nothing
 * changed since the restore), the elements are those remembered with, and nothing outside rhs, u and h
 * enters it (no relaxation, whose linearization is the caller's start velocity; no spring graph, whose
 * vertices' z move with h and u, and an elastoplastic one's graph is redrawn in place). */
static int memo_applies(dp_network_step *w)
{
    if (w->gamma != NULL || w->synced == NULL || w->ndirty != 0 || w->all_dirty || w->ne == 0)
        return 0;
    if (w->memo_for != w->synced)
        memo_forget(w), w->memo_for = w->synced;
    size_t bytes = w->ne * sizeof *w->el;
    if (!w->memo_el_ok || memcmp(w->memo_el, w->el, bytes) != 0) {
        memo_forget(w);
        if (w->memo_el == NULL && (w->memo_el = malloc(bytes)) == NULL)
            return 0;
        memcpy(w->memo_el, w->el, bytes);
        w->memo_el_ok = 1, w->memo_el_ep = 0;
        for (size_t i = 0; i < w->ne; i++)
            w->memo_el_ep |= w->el[i].S != NULL;   /* a spring graph's vertices move with h and u (refresh_free) */
    }
    return !w->memo_el_ep;
}

static held_memo *memo_find(dp_network_step *w, double h, const double *rhs, const double *u)
{
    for (int k = 0; k < HELD_MEMO; k++) {
        held_memo *m = &w->memo[k];
        if (m->used && memcmp(&m->h, &h, sizeof h) == 0 && memcmp(m->rhs, rhs, w->n * sizeof *rhs) == 0 &&
            memcmp(m->u, u, w->ne * sizeof *u) == 0 && memcmp(m->W, w->W, w->n * (w->p + 1) * sizeof *w->W) == 0) {
            m->stamp = ++w->memo_clock;
            return m;
        }
    }
    return NULL;
}

/* Remembers the solve just done (the least recently used entry goes); nothing when memory runs short. */
static void memo_keep(dp_network_step *w, int status, double h, const double *rhs, const double *u,
                      const double *v, const dp_network_step_forces *f, const double *margin)
{
    held_memo *m = &w->memo[0];
    for (int k = 1; k < HELD_MEMO; k++)
        if (!w->memo[k].used ? m->used : w->memo[k].stamp < m->stamp && m->used)
            m = &w->memo[k];
    size_t n = w->n, ne = w->ne;
    if (m->rhs == NULL) {
        m->rhs = malloc(n * sizeof *m->rhs), m->v = malloc(n * sizeof *m->v);
        m->W = malloc(n * (w->p + 1) * sizeof *m->W);
        m->u = malloc(ne * sizeof *m->u), m->margin = malloc(ne * sizeof *m->margin);
        m->lam = malloc(ne * sizeof *m->lam), m->lam_err = malloc(ne * sizeof *m->lam_err);
        m->f = malloc(ne * sizeof *m->f);
    }
    m->used = 0;
    if (!m->rhs || !m->W || !m->v || !m->u || !m->margin || !m->lam || !m->lam_err || !m->f)
        return;
    m->status = status, m->h = h, m->stamp = ++w->memo_clock;
    memcpy(m->rhs, rhs, n * sizeof *rhs);
    memcpy(m->u, u, ne * sizeof *u);
    memcpy(m->W, w->W, n * (w->p + 1) * sizeof *w->W);
    if (status == DP_OK) {
        memcpy(m->v, v, n * sizeof *v);
        memcpy(m->f, f, ne * sizeof *f);
        memcpy(m->margin, margin, ne * sizeof *margin);
        for (size_t i = 0; i < ne; i++)
            m->lam[i] = w->es[i].lam, m->lam_err[i] = w->es[i].lam_err;
    }
    m->used = 1;
}

/* The remembered solve's answer, and its multipliers back in the fixed elements, as the solve left them. */
static int memo_replay(dp_network_step *w, const held_memo *m, double *v, dp_network_step_forces *f, double *margin)
{
    if (m->status != DP_OK)
        return m->status;
    if (polled_stop(w))
        return DP_ECANCEL;
    memcpy(v, m->v, w->n * sizeof *v);
    memcpy(w->vs, m->v, w->n * sizeof *v);
    memcpy(f, m->f, w->ne * sizeof *f);
    memcpy(margin, m->margin, w->ne * sizeof *margin);
    for (size_t i = 0; i < w->ne; i++)
        if (w->es[i].st == FIXED) {
            touch_values(w, i);
            w->es[i].lam = m->lam[i], w->es[i].lam_err = m->lam_err[i];
        }
    return DP_OK;
}

int dp_network_step_solve_frozen(dp_network_step *w, double h, const double *rhs, const double *u, double *v, dp_network_step_forces *f,
                        double *margin)
{
    int keep = memo_applies(w);
    const held_memo *m = keep ? memo_find(w, h, rhs, u) : NULL;
    if (m != NULL)
        return memo_replay(w, m, v, f, margin);
    int s = solve_held(w, h, rhs, u, !keep);
    if (s != DP_OK) {
        if (keep && s == DP_ESOLVE)   /* not a stop, nor a lack of memory: those are not the inputs' */
            memo_keep(w, s, h, rhs, u, NULL, NULL, NULL);
        return s;
    }
    if (polled_stop(w))
        return DP_ECANCEL;
    memcpy(v, w->vs, w->n * sizeof *v);
    multipliers(w, h);
    for (size_t i = 0; i < w->ne; i++) {
        const elem_state *e = &w->es[i];
        if (e->st == FREE) {
            double z = rel_velocity(&w->el[i], v);
            margin[i] = fmin(z - e->lo.z, e->hi.z - z);     /* -inf + x stays finite-safe: fmin */
        } else {
            double lo, hi;
            sigma_interval(w, i, u[i], h, &e->fix, &lo, &hi);
            margin[i] = fmin(e->lam - lo, hi - e->lam);
        }
    }
    report(w, h, u, v, f);
    if (keep)
        memo_keep(w, DP_OK, h, rhs, u, v, f, margin);
    return DP_OK;
}

/* A spring graph's vertex is the same where its graph point is (its z moves with h and u). */
static int same_vertex(const vertex *a, const vertex *b)
{
    return a->src == SRC_S ? b->src == SRC_S && a->y == b->y : a->z == b->z;
}

int dp_network_step_pattern_same(const dp_network_step *w, const void *buf)
{
    const elem_state *old = buf;
    for (size_t i = 0; i < w->ne; i++) {
        const elem_state *a = &w->es[i], *b = &old[i];
        if (a->st != b->st)
            return 0;
        if (a->st == FIXED ? !same_vertex(&a->fix, &b->fix) : !same_vertex(&a->lo, &b->lo) || !same_vertex(&a->hi, &b->hi))
            return 0;
    }
    return 1;
}

void dp_network_step_fix_end(dp_network_step *w, size_t i, const double *v)
{
    elem_state *s = &w->es[i];
    if (s->st == FIXED)
        return;
    double z = rel_velocity(&w->el[i], v);
    touch(w, i);
    s->fix = fabs(z - s->lo.z) <= fabs(s->hi.z - z) ? s->lo : s->hi;
    s->st = FIXED;
}

int dp_network_step_violation(const dp_network_step *w, size_t i, double h, const double *u)
{
    const elem_state *s = &w->es[i];
    double lo, hi;
    if (s->st != FIXED)
        return 0;
    sigma_interval(w, i, u[i], h, &s->fix, &lo, &hi);
    if (s->lam > hi || s->lam < lo)
        return s->lam > hi ? 1 : -1;
    /* at a located release the force is at a bound to rounding: the nearer one (an end ray's is infinite) */
    return !isfinite(hi) ? -1 : !isfinite(lo) ? 1 : s->lam - lo > hi - s->lam ? 1 : -1;
}

int dp_network_step_fixed(const dp_network_step *w, size_t i)
{
    return w->es[i].st == FIXED;
}

int dp_network_step_at_rest(const dp_network_step *w, size_t i)
{
    const elem_state *s = &w->es[i];
    const dp_network_step_element *e = &w->el[i];
    double lo, hi;
    if (s->st != FIXED || e->A == NULL || arg_A(e, &s->fix) != 0)
        return 0;
    dp_graph_force(e->A, 0, &lo, &hi);
    return hi > lo;
}

void dp_network_step_slip(dp_network_step *w, size_t i, double h, const double *u, int dir)
{
    vertex at = w->es[i].fix;
    set_free(w, i, u[i], h, &at, dir);
}

/* ---- held solves over blocks of a chain ----------------------------------------------------------------
 *
 * A root search of event location asks a held step's margins for a few candidates only. On a chain (half-
 * bandwidth one) whose fixed elements each hold one node to the ground, those nodes split the contracted
 * system into segments that do not couple (nor do two nodes that no spring, damper or mass couples): a
 * candidate's margin needs its ends' segments only, and a fixed one's its node's two neighbours'. Solved
 * alone, a segment gives its velocities bit for bit as the whole solve does: the factor's entries across a
 * zero coupling are zero, the pivots the same, and the sweeps differ at most by the sign of a zero (x - 0 y),
 * which the potential's +0 or the forest's c then removes; the multipliers and margins follow. */

/* The blocks' workspace, made at the first call: the elements of each node in the elements' order
 * (effective_rhs adds their terms in that order), and the blocks' marks, velocities and reduced system. */
static int blocks_workspace(dp_network_step *w)
{
    if (w->inc_start != NULL)
        return 1;
    size_t n = w->n, *start = calloc(n + 2, sizeof *start), *el = malloc((2 * w->ne + 1) * sizeof *el);
    double *vl = calloc(n + 1, sizeof *vl), *rl = calloc(n + 1, sizeof *rl), *Rl = calloc(2 * n + 2, sizeof *Rl);
    double *yl = calloc(n + 1, sizeof *yl);
    unsigned long long *mark = calloc(n + 1, sizeof *mark);
    if (!start || !el || !vl || !rl || !Rl || !yl || !mark) {
        free(start), free(el), free(vl), free(rl), free(Rl), free(yl), free(mark);
        return 0;
    }
    w->blk_mark = mark;
    for (size_t k = 0; k < w->ne; k++) {
        if (w->el[k].a >= 0)
            start[w->el[k].a + 2]++;
        if (w->el[k].b >= 0)
            start[w->el[k].b + 2]++;
    }
    for (size_t i = 2; i <= n + 1; i++)
        start[i] += start[i - 1];
    for (size_t k = 0; k < w->ne; k++) {   /* start[i + 1] runs as node i's cursor, then is its end */
        if (w->el[k].a >= 0)
            el[start[w->el[k].a + 1]++] = k;
        if (w->el[k].b >= 0)
            el[start[w->el[k].b + 1]++] = k;
    }
    w->inc_start = start, w->inc_el = el, w->vloc = vl, w->loc_rhs = rl, w->loc_R = Rl, w->loc_y = yl;
    return 1;
}

/* Node i's one fixed element when it holds i to the ground and is i's only fixed one; -1 when i has none;
 * -2 otherwise (not a chain's held node: the blocks do not apply). */
static long held_by(const dp_network_step *w, size_t i)
{
    long k = -1;
    for (size_t j = w->inc_start[i]; j < w->inc_start[i + 1]; j++) {
        size_t e = w->inc_el[j];
        if (w->es[e].st != FIXED)
            continue;
        if (k >= 0 || (w->el[e].a >= 0 && w->el[e].b >= 0))
            return -2;
        k = (long)e;
    }
    return k;
}

/* The segment of free node j (the run of free nodes coupled to it, `couple[i]`: nodes i and i+1 are
 * coupled in W), with the held nodes that bound it, into blk as [lo, hi]. */
static void segment(const dp_network_step *w, size_t j, const unsigned char *couple, size_t *blk)
{
    size_t lo = j, hi = j;
    while (lo > 0 && w->kidx[lo - 1] >= 0 && couple[lo - 1])
        lo--;
    while (hi + 1 < w->n && w->kidx[hi + 1] >= 0 && couple[hi])
        hi++;
    blk[0] = lo > 0 && w->kidx[lo - 1] < 0 ? lo - 1 : lo;
    blk[1] = hi + 1 < w->n && w->kidx[hi + 1] < 0 ? hi + 1 : hi;
}

static int block_cmp(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return x < y ? -1 : x > y;
}

size_t dp_network_step_blocks(dp_network_step *w, const unsigned char *cand, const unsigned char *couple,
                              size_t *blk, size_t cap)
{
    if (w->p != 1 || w->gamma != NULL || !w->forest_ok || couple == NULL || !blocks_workspace(w))
        return 0;
    size_t nb = 0;
    w->blk_gen++;
    for (size_t k = 0; k < w->ne; k++) {
        if (!cand[k])
            continue;
        const dp_network_step_element *e = &w->el[k];
        long seeds[3] = { e->a, e->b, -1 };
        if (w->es[k].st == FIXED) {   /* its node and both neighbours */
            if (e->a >= 0 && e->b >= 0)
                return 0;
            long i = e->a >= 0 ? e->a : e->b;
            seeds[0] = i - 1, seeds[1] = i, seeds[2] = i + 1 < (long)w->n ? i + 1 : -1;
        }
        for (int s = 0; s < 3; s++) {
            if (seeds[s] < 0 || w->blk_mark[seeds[s]] == w->blk_gen)
                continue;   /* no seed, or in a block already (a segment is walked once) */
            if (nb + 1 >= cap)
                return 0;
            size_t j = (size_t)seeds[s];
            if (w->kidx[j] >= 0)
                segment(w, j, couple, blk + 2 * nb);
            else
                blk[2 * nb] = blk[2 * nb + 1] = j;
            for (size_t i = blk[2 * nb]; i <= blk[2 * nb + 1]; i++)
                w->blk_mark[i] = w->blk_gen;
            nb++;
        }
    }
    qsort(blk, nb, 2 * sizeof *blk, block_cmp);
    size_t m = 0;
    for (size_t b = 0; b < nb; b++) {   /* merged where they overlap or touch */
        if (m > 0 && blk[2 * b] <= blk[2 * m - 1] + 1) {
            if (blk[2 * b + 1] > blk[2 * m - 1])
                blk[2 * m - 1] = blk[2 * b + 1];
            continue;
        }
        blk[2 * m] = blk[2 * b], blk[2 * m + 1] = blk[2 * b + 1], m++;
    }
    return m;
}

/* One block [lo, hi]: the effective right side, the reduced system of its free nodes (consecutive unknowns)
 * factored and solved, every node's velocity into vloc. 0 when it is not a chain's block (or not positive). */
static int block_solve(dp_network_step *w, double h, size_t lo, size_t hi, const double *Wl, const double *rl)
{
    size_t n = w->n, m = 0;
    long k0 = -1;
    for (size_t i = lo; i <= hi; i++) {
        double r = rl[i - lo];
        for (size_t j = w->inc_start[i]; j < w->inc_start[i + 1]; j++) {   /* effective_rhs */
            size_t e = w->inc_el[j];
            const elem_state *st = &w->es[e];
            if (st->st != FREE)
                continue;
            if (h * st->slope != 0 || w->el[e].S != NULL)
                return 0;   /* H is not W here */
            double g = h * (st->lam0 - st->slope * st->zref);
            r = (long)i == w->el[e].a ? r + g : r - g;
        }
        w->loc_rhs[i] = r;
        if (w->kidx[i] < 0) {
            if (held_by(w, i) == -2)
                return 0;
            continue;
        }
        if (k0 < 0)
            k0 = w->kidx[i];
        if (w->kidx[i] != k0 + (long)m || held_by(w, i) != -1)
            return 0;
        double *R = w->loc_R + 2 * m, y = 0, a = Wl[2 * (i + 1 - lo) + 1];
        R[0] = 0, R[1] = 0;
        R[0] += Wl[2 * (i + 1 - lo)];
        if (i + 1 <= hi && w->kidx[i + 1] >= 0 && a != 0)
            R[1] += a;
        y += w->loc_rhs[i] - dp_band_row(Wl + 2 * (i + 1 - lo), 1, w->c, i, n);
        w->loc_y[m++] = y;
    }
    size_t q = m > 1;   /* one unknown: a 1 x 1 band, as the whole factor takes a lone one */
    if (m > 0 && (dp_band_cholesky(w->loc_R, m, q) != DP_OK || dp_band_cholesky_solve(w->loc_R, m, q, w->loc_y) != DP_OK))
        return 0;
    for (size_t i = lo; i <= hi; i++)
        w->vloc[i] = (w->kidx[i] >= 0 ? w->loc_y[w->kidx[i] - k0] : 0) + w->c[i];
    return 1;
}

int dp_network_step_solve_blocks(dp_network_step *w, double h, const size_t *blk, size_t nb, const double *Wl,
                                 const double *rl, const double *u, const unsigned char *cand, double *margin)
{
    size_t off = 0, work = 0;
    for (size_t b = 0; b < nb; b++) {
        size_t lo = blk[2 * b], hi = blk[2 * b + 1];
        if (!block_solve(w, h, lo, hi, Wl + 2 * off + 2 * b, rl + off))
            return 0;
        off += hi - lo + 1, work += 3 * (hi - lo + 1);
    }
    off = 0;
    for (size_t b = 0; b < nb; b++) {   /* the fixed candidates' multipliers (a leaf of the ground's star) */
        size_t lo = blk[2 * b], hi = blk[2 * b + 1];
        for (size_t i = lo; i <= hi; i++) {
            long k = w->kidx[i] < 0 ? held_by(w, i) : -1;
            if (k < 0 || !cand[k])
                continue;
            const dp_network_step_element *e = &w->el[k];
            double Hv = dp_band_row(Wl + 2 * (off + b) + 2 * (i + 1 - lo), 1, w->vloc, i, w->n), r = w->loc_rhs[i];
            double sign_i = (long)i == e->b ? 1 : -1;
            touch_values(w, (size_t)k);
            w->es[k].lam = (r - Hv) / (h * sign_i);
            w->es[k].lam_err = 8 * DBL_EPSILON * (fabs(r) + fabs(Hv)) / h;
        }
        off += hi - lo + 1;
    }
    for (size_t k = 0; k < w->ne; k++) {   /* the candidates' margins, as dp_network_step_solve_frozen's */
        if (!cand[k])
            continue;
        const elem_state *e = &w->es[k];
        if (e->st == FREE) {
            double z = rel_velocity(&w->el[k], w->vloc);
            margin[k] = fmin(z - e->lo.z, e->hi.z - z);
        } else {
            double lo, hi;
            sigma_interval(w, k, u[k], h, &e->fix, &lo, &hi);
            margin[k] = fmin(e->lam - lo, hi - e->lam);
        }
    }
    w->work += work;
    return polled_stop_units(w) ? -1 : 1;
}
