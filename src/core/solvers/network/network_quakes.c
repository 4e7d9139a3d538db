/* src/core/solvers/network/network_quakes.c - the slip-event catalogue of a network run (output.quakes): a
 * Burridge–Knopoff chain is studied by its events, catalogued as Carlson & Langer 1989 and Mori & Kawamura
 * 2005 catalogue theirs (docs/quakes.md has the definition and its sources).
 *
 * A quake is a connected slip episode of friction elements (those that can stick). It starts when an
 * element starts to slip with no slipping neighbour in a quake; an element that starts to slip while a
 * neighbour of a quake slips (at the start or the end of that (sub-)step) joins that quake, and two quakes it
 * joins merge: the earlier one's start and hypocentre survive (at the same instant, the lower hypocentre's).
 * A quake ends when all its elements stick again. Neighbours: two friction elements that share a node (the
 * ground does not count) or whose nodes are joined by an element with a spring.
 *
 * Each element belongs to at most one live quake, the one of its latest slip: an element that starts to slip
 * apart from its earlier quake, which goes on elsewhere, moves to the new one (the earlier keeps its slip, no
 * longer counts it), so no element is counted twice when quakes merge. Its slip over a (sub-)step,
 * |du - v_b dt| with du the elongation's change as the step moved it (the theta-rule's own displacement),
 * goes to its quake when the element slipped at the step's start or end. So the moments add up to the total
 * slip of every element.
 * Merging relabels the smaller quake's members (a list through `next`, `prev`): O(members log members) in
 * all. Memory: per element its quake, its list links and its last elongation; per node its friction
 * elements and spring neighbours; one slot per live quake, at most one per element. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "solvers/network/network_quakes.h"
#include "solvers/network/network_run.h"

typedef struct quake_slot {
    double t, moment, peak;
    size_t hypocentre, size, nslip, first, last;
    long head, tail;          /* its members, linked through dp_quakes.next */
    unsigned stamp;           /* scratch: collected as a candidate at this stamp */
} quake_slot;

struct dp_quakes {
    size_t n, nel;
    unsigned char *fric;      /* per element: it can stick */
    size_t *fn_off, *fn_el;   /* per node: the friction elements at it */
    size_t *sn_off, *sn_node; /* per node: the nodes a spring element joins it to */
    long *q, *next, *prev;    /* per element: its live quake's slot (-1: none), the next and previous member */
    double *u_last, t_last;   /* per element: the elongation at the last call, and its time */
    quake_slot *slot;
    long *free_slot, *cand;   /* the free slots (a stack); scratch: a start's candidate quakes */
    size_t nfree, ncand;
    dp_quake *out;            /* the quakes a call ended, for the run to hand out (at most one per element) */
    size_t nout;
    unsigned stamp;
    int done;
};

void network_quakes_free(dp_quakes *q)
{
    if (q == NULL)
        return;
    void *p[] = { q->fric, q->fn_off, q->fn_el, q->sn_off, q->sn_node, q->q, q->next, q->prev, q->u_last, q->slot,
                  q->free_slot, q->cand, q->out };
    for (size_t i = 0; i < sizeof p / sizeof *p; i++)
        free(p[i]);
    free(q);
}

/* Node -> list in CSR form from (node, item) pairs given twice: once to count, once to fill. */
static void csr_add(size_t *off, size_t *item, size_t node, size_t what, int fill)
{
    if (fill)
        item[off[node]++] = what;
    else
        off[node + 1]++;
}

static void adjacency(dp_quakes *q, const dp_network *net, int fill)
{
    for (size_t i = 0; i < net->nel; i++) {
        const dp_element *e = &net->el[i];
        if (q->fric[i] && e->a >= 0)
            csr_add(q->fn_off, q->fn_el, (size_t)e->a, i, fill);
        if (q->fric[i] && e->b >= 0)
            csr_add(q->fn_off, q->fn_el, (size_t)e->b, i, fill);
        if (e->has_spring && e->a >= 0 && e->b >= 0) {
            csr_add(q->sn_off, q->sn_node, (size_t)e->a, (size_t)e->b, fill);
            csr_add(q->sn_off, q->sn_node, (size_t)e->b, (size_t)e->a, fill);
        }
    }
}

/* Offsets from counts (fill = 0 pass) and back to starts after the fill pass moved them on. */
static void csr_prefix(size_t *off, size_t n)
{
    for (size_t i = 0; i < n; i++)
        off[i + 1] += off[i];
}

static void csr_unshift(size_t *off, size_t n)
{
    for (size_t i = n; i > 0; i--)
        off[i] = off[i - 1];
    off[0] = 0;
}

static int build(dp_quakes *q, const struct dp_network_run *nr)
{
    size_t n = q->n, ne = q->nel ? q->nel : 1;
    q->fric = calloc(ne, 1);
    q->fn_off = calloc(n + 1, sizeof *q->fn_off), q->sn_off = calloc(n + 1, sizeof *q->sn_off);
    q->q = malloc(ne * sizeof *q->q), q->next = malloc(ne * sizeof *q->next);
    q->prev = malloc(ne * sizeof *q->prev);
    q->u_last = calloc(ne, sizeof *q->u_last);
    q->slot = calloc(ne, sizeof *q->slot);
    q->free_slot = malloc(ne * sizeof *q->free_slot), q->cand = malloc(ne * sizeof *q->cand);
    q->out = malloc(ne * sizeof *q->out);
    if (!q->fric || !q->fn_off || !q->sn_off || !q->q || !q->next || !q->prev || !q->u_last || !q->slot ||
        !q->free_slot || !q->cand || !q->out)
        return DP_ENOMEM;
    for (size_t i = 0; i < q->nel; i++)
        q->fric[i] = nr->can_stick[i], q->q[i] = -1, q->next[i] = q->prev[i] = -1;
    for (size_t s = 0; s < ne; s++)
        q->free_slot[q->nfree++] = (long)(ne - 1 - s);
    adjacency(q, nr->net, 0);
    csr_prefix(q->fn_off, n), csr_prefix(q->sn_off, n);
    q->fn_el = malloc((q->fn_off[n] ? q->fn_off[n] : 1) * sizeof *q->fn_el);
    q->sn_node = malloc((q->sn_off[n] ? q->sn_off[n] : 1) * sizeof *q->sn_node);
    if (!q->fn_el || !q->sn_node)
        return DP_ENOMEM;
    adjacency(q, nr->net, 1);
    csr_unshift(q->fn_off, n), csr_unshift(q->sn_off, n);
    return DP_OK;
}

static double elongation(const struct dp_network_run *nr, size_t i)
{
    return network_run_rel(nr->net->el[i].a, nr->net->el[i].b, nr->x);
}

static double belt(const struct dp_network_run *nr, size_t i)
{
    const dp_element *e = &nr->net->el[i];
    return e->has_damper ? e->damper.belt_velocity : 0;
}

/* ---- quakes: new, merged, ended ------------------------------------------------------------------------ */

static long slot_new(dp_quakes *q, double t, size_t hypocentre)
{
    long s = q->free_slot[--q->nfree];   /* live quakes <= elements that slip: a slot is always free */
    q->slot[s] = (quake_slot){ .t = t, .hypocentre = hypocentre, .first = hypocentre, .last = hypocentre,
                               .head = -1, .tail = -1 };
    return s;
}

static void member_add(dp_quakes *q, long s, size_t i)
{
    quake_slot *k = &q->slot[s];
    q->q[i] = s, q->next[i] = -1, q->prev[i] = k->tail;
    if (k->tail >= 0)
        q->next[k->tail] = (long)i;
    else
        k->head = (long)i;
    k->tail = (long)i;
    k->size++;
    k->first = i < k->first ? i : k->first;
    k->last = i > k->last ? i : k->last;
}

/* Element i (sticking) leaves quake s for another: s keeps its slip and moment, no longer counts it. */
static void member_remove(dp_quakes *q, long s, size_t i)
{
    quake_slot *k = &q->slot[s];
    long p = q->prev[i], n = q->next[i];
    if (p >= 0)
        q->next[p] = n;
    else
        k->head = n;
    if (n >= 0)
        q->prev[n] = p;
    else
        k->tail = p;
    k->size--;
    q->q[i] = -1, q->next[i] = q->prev[i] = -1;
}

/* Quakes a and b as one: the smaller one's members relabelled into the larger one's slot, which takes the
 * earlier start and its hypocentre (the lower hypocentre at the same instant). Returns the slot kept. */
static long merge(dp_quakes *q, long a, long b)
{
    quake_slot *A = &q->slot[a], *B = &q->slot[b];
    if (A->size < B->size) {
        long s = a; a = b; b = s;
        A = &q->slot[a], B = &q->slot[b];
    }
    for (long m = B->head; m >= 0; m = q->next[m])
        q->q[m] = a;
    if (B->head >= 0) {
        q->prev[B->head] = A->tail;
        if (A->tail >= 0)
            q->next[A->tail] = B->head;
        else
            A->head = B->head;
        A->tail = B->tail;
    }
    if (B->t < A->t || (B->t == A->t && B->hypocentre < A->hypocentre))
        A->t = B->t, A->hypocentre = B->hypocentre;
    A->size += B->size, A->nslip += B->nslip, A->moment += B->moment;
    A->peak = fmax(A->peak, B->peak);
    A->first = B->first < A->first ? B->first : A->first;
    A->last = B->last > A->last ? B->last : A->last;
    q->free_slot[q->nfree++] = b;
    return a;
}

static dp_quake as_quake(const quake_slot *k, double t, int open)
{
    return (dp_quake){ .t = k->t, .duration = t - k->t, .moment = k->moment, .peak_rate = k->peak,
                       .size = k->size, .hypocentre = k->hypocentre, .first = k->first, .last = k->last,
                       .open = open };
}

/* Quake s has ended at t: kept for the run to hand out, its members free again, its slot back. */
static void end_quake(dp_quakes *q, long s, double t)
{
    q->out[q->nout++] = as_quake(&q->slot[s], t, 0);
    for (long m = q->slot[s].head, nx; m >= 0; m = nx)
        nx = q->next[m], q->q[m] = -1, q->next[m] = q->prev[m] = -1;
    q->free_slot[q->nfree++] = s;
}

/* ---- an element starts to slip ------------------------------------------------------------------------- */

static int slipping(const struct dp_network_run *nr, const unsigned char *before, size_t j)
{
    return nr->phase[j] == DP_PHASE_SLIP || (before != NULL && before[j] == DP_PHASE_SLIP);
}

static void candidate(dp_quakes *q, long s)
{
    if (s >= 0 && q->slot[s].stamp != q->stamp)
        q->slot[s].stamp = q->stamp, q->cand[q->ncand++] = s;
}

/* The live quakes of element i's slipping neighbours at node p: friction elements at p and at the nodes
 * a spring joins p to. */
static void neighbours_at(dp_quakes *q, const struct dp_network_run *nr, const unsigned char *before, size_t i,
                          size_t p)
{
    for (size_t k = q->fn_off[p]; k < q->fn_off[p + 1]; k++)
        if (q->fn_el[k] != i && slipping(nr, before, q->fn_el[k]))
            candidate(q, q->q[q->fn_el[k]]);
    for (size_t s = q->sn_off[p]; s < q->sn_off[p + 1]; s++) {
        size_t o = q->sn_node[s];
        for (size_t k = q->fn_off[o]; k < q->fn_off[o + 1]; k++)
            if (q->fn_el[k] != i && slipping(nr, before, q->fn_el[k]))
                candidate(q, q->q[q->fn_el[k]]);
    }
}

static void start_slip(dp_quakes *q, const struct dp_network_run *nr, const unsigned char *before, size_t i,
                       double t)
{
    const dp_element *e = &nr->net->el[i];
    q->stamp++, q->ncand = 0;
    if (q->stamp == 0) {     /* wrapped: no slot may keep a stale stamp */
        for (size_t s = 0; s < (q->nel ? q->nel : 1); s++)
            q->slot[s].stamp = 0;
        q->stamp = 1;
    }
    if (e->a >= 0)
        neighbours_at(q, nr, before, i, (size_t)e->a);
    if (e->b >= 0)
        neighbours_at(q, nr, before, i, (size_t)e->b);
    long s = q->ncand ? q->cand[0] : slot_new(q, t, i);
    for (size_t c = 1; c < q->ncand; c++)
        s = merge(q, s, q->cand[c]);
    if (q->q[i] != s) {
        if (q->q[i] >= 0)    /* still in an earlier quake that goes on elsewhere: it moves to this one */
            member_remove(q, q->q[i], i);
        member_add(q, s, i);
    }
    q->slot[s].nslip++;
}

/* ---- the run's calls ----------------------------------------------------------------------------------- */

int network_quakes_begin(struct dp_network_run *nr, double t)
{
    dp_quakes *q = calloc(1, sizeof *q);
    if (q == NULL)
        return DP_ENOMEM;
    nr->quakes = q;
    q->n = nr->n, q->nel = nr->nel;
    int s = build(q, nr);
    if (s != DP_OK)
        return s;
    q->t_last = t;
    for (size_t i = 0; i < q->nel; i++) {
        q->u_last[i] = elongation(nr, i);
        if (q->fric[i] && nr->phase[i] == DP_PHASE_SLIP)
            start_slip(q, nr, NULL, i, t);
    }
    return DP_OK;
}

size_t network_quakes_step(struct dp_network_run *nr, const unsigned char *before, double t,
                           const dp_quake **ended)
{
    dp_quakes *q = nr->quakes;
    if (q == NULL)
        return 0;
    q->nout = 0;
    *ended = q->out;
    double dt = t - q->t_last;
    for (size_t i = 0; i < q->nel; i++)
        if (q->fric[i] && nr->phase[i] == DP_PHASE_SLIP && before[i] != DP_PHASE_SLIP)
            start_slip(q, nr, before, i, t);
    for (size_t i = 0; i < q->nel; i++) {
        if (!q->fric[i])
            continue;
        double u = elongation(nr, i), vb = belt(nr, i);
        if (slipping(nr, before, i)) {
            quake_slot *k = &q->slot[q->q[i]];
            k->moment += fabs((u - q->u_last[i]) - vb * dt);
            if (nr->phase[i] == DP_PHASE_SLIP)
                k->peak = fmax(k->peak, fabs(network_run_rel(nr->net->el[i].a, nr->net->el[i].b, nr->v) - vb));
        }
        q->u_last[i] = u;
    }
    q->t_last = t;
    for (size_t i = 0; i < q->nel; i++) {
        if (!q->fric[i] || before[i] != DP_PHASE_SLIP || nr->phase[i] == DP_PHASE_SLIP)
            continue;
        long s = q->q[i];
        if (--q->slot[s].nslip == 0)
            end_quake(q, s, t);
    }
    return q->nout;
}

static int by_start(const void *pa, const void *pb)
{
    const dp_quake *a = pa, *b = pb;
    if (a->t != b->t)
        return a->t < b->t ? -1 : 1;
    return a->hypocentre < b->hypocentre ? -1 : a->hypocentre > b->hypocentre;
}

size_t network_quakes_finish(struct dp_network_run *nr, double t, const dp_quake **open)
{
    dp_quakes *q = nr->quakes;
    if (q == NULL || q->done)
        return 0;
    q->done = 1;
    q->nout = 0;
    for (size_t i = 0; i < q->nel; i++) {
        long s = q->q[i];
        if (s >= 0 && q->slot[s].head == (long)i)    /* once per quake: at its list's head */
            q->out[q->nout++] = as_quake(&q->slot[s], t, 1);
    }
    qsort(q->out, q->nout, sizeof *q->out, by_start);
    *open = q->out;
    return q->nout;
}
