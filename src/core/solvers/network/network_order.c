/* src/core/solvers/network/network_order.c - the nodes of a network renumbered to keep W's band narrow (reverse
 * Cuthill-McKee).
 *
 * A step costs O(n p^2) with p the half-bandwidth of W = M + h theta C + h^2 theta^2 K, which is the largest
 * |a - b| over the elements between two nodes and the matrices' off-diagonal nonzeros. So the user's
 * numbering decides the cost: a ring of n masses numbered around it has p = n - 1 (dense), the same ring
 * numbered back and forth has p = 2. Reverse Cuthill-McKee (a breadth-first search from a node of low degree,
 * neighbours by rising degree, the order reversed) finds such a numbering in O(nodes + edges).
 *
 * The run relabels its own copy of the network (spec.net, the initial state) when that at least halves p,
 * and keeps the user's numbering for everything it writes (network_output.c maps the rows back). Where the
 * numbering is already good nothing changes, so runs stay bit for bit what they were.
 */
#include <stdlib.h>
#include <string.h>

#include "dashpot/status.h"
#include "solvers/network/network_run.h"

/* The graph of the nodes' couplings in compressed rows: off-diagonal nonzeros of M, K, C and elements. */
typedef struct coupling {
    size_t n;
    size_t *start, *adj;   /* node i's neighbours: adj[start[i] .. start[i+1]) (repeats allowed) */
} coupling;

static void coupling_free(coupling *g)
{
    free(g->start), free(g->adj);
}

/* Calls add(i, j) for every coupling of two different nodes. */
static void each_coupling(const dp_network *net, void (*add)(void *, size_t, size_t), void *ctx)
{
    size_t n = net->n;
    const double *mats[3] = { net->M, net->K, net->C };
    for (int m = 0; m < 3; m++)
        for (size_t i = 0; mats[m] && i < n; i++)
            for (size_t j = i + 1; j < n; j++)
                if (mats[m][i * n + j] != 0)
                    add(ctx, i, j);
    for (size_t e = 0; e < net->nel; e++)
        if (net->el[e].a >= 0 && net->el[e].b >= 0 && net->el[e].a != net->el[e].b)
            add(ctx, (size_t)net->el[e].a, (size_t)net->el[e].b);
}

static void count_pair(void *ctx, size_t i, size_t j)
{
    coupling *g = ctx;
    g->start[i + 1]++, g->start[j + 1]++;
}

static void put_pair(void *ctx, size_t i, size_t j)
{
    coupling *g = ctx;   /* start[] holds each row's next free slot while filling */
    g->adj[g->start[i]++] = j, g->adj[g->start[j]++] = i;
}

static int coupling_build(const dp_network *net, coupling *g)
{
    size_t n = net->n;
    g->n = n;
    g->adj = NULL;
    if ((g->start = calloc(n + 1, sizeof *g->start)) == NULL)
        return DP_ENOMEM;
    each_coupling(net, count_pair, g);
    for (size_t i = 0; i < n; i++)
        g->start[i + 1] += g->start[i];
    if ((g->adj = malloc((g->start[n] ? g->start[n] : 1) * sizeof *g->adj)) == NULL)
        return DP_ENOMEM;
    each_coupling(net, put_pair, g);
    for (size_t i = n; i > 0; i--)      /* the fill moved each row's start to the next one's */
        g->start[i] = g->start[i - 1];
    g->start[0] = 0;
    return DP_OK;
}

static size_t degree(const coupling *g, size_t i)
{
    return g->start[i + 1] - g->start[i];
}

/* Half-bandwidth of the numbering pos (user node -> internal), or of the user's own (pos NULL). */
static size_t half_bandwidth(const coupling *g, const size_t *pos)
{
    size_t p = 0;
    for (size_t i = 0; i < g->n; i++)
        for (size_t k = g->start[i]; k < g->start[i + 1]; k++) {
            size_t a = pos ? pos[i] : i, b = pos ? pos[g->adj[k]] : g->adj[k];
            size_t d = a > b ? a - b : b - a;
            p = d > p ? d : p;
        }
    return p;
}

/* The nodes by rising degree, ties by index (a counting sort), into `by_degree`: the next component's root
 * is the first of them not yet seen, found in one pass over all components together. */
static int degree_order(const coupling *g, size_t *by_degree)
{
    size_t n = g->n, top = 0;
    for (size_t i = 0; i < n; i++)
        top = degree(g, i) > top ? degree(g, i) : top;
    size_t *first = calloc(top + 2, sizeof *first);
    if (first == NULL)
        return DP_ENOMEM;
    for (size_t i = 0; i < n; i++)
        first[degree(g, i) + 1]++;
    for (size_t d = 0; d <= top; d++)
        first[d + 1] += first[d];
    for (size_t i = 0; i < n; i++)
        by_degree[first[degree(g, i)]++] = i;
    free(first);
    return DP_OK;
}

/* Cuthill-McKee order into `order` (internal -> user): each component from its lowest-degree node (the
 * lowest index among equals), breadth first, the neighbours of a node taken by rising degree (insertion
 * sort: degrees are small). */
static int cuthill_mckee(const coupling *g, size_t *order, unsigned char *seen)
{
    size_t n = g->n, filled = 0, next_root = 0;
    size_t *by_degree = malloc((n ? n : 1) * sizeof *by_degree);
    if (by_degree == NULL || degree_order(g, by_degree) != DP_OK) {
        free(by_degree);
        return DP_ENOMEM;
    }
    memset(seen, 0, n);
    while (filled < n) {
        while (seen[by_degree[next_root]])
            next_root++;
        size_t root = by_degree[next_root];
        order[filled++] = root, seen[root] = 1;
        for (size_t head = filled - 1; head < filled; head++) {
            size_t i = order[head], first = filled;
            for (size_t k = g->start[i]; k < g->start[i + 1]; k++) {
                size_t j = g->adj[k];
                if (seen[j])
                    continue;
                seen[j] = 1;
                size_t at = filled++;
                while (at > first && degree(g, order[at - 1]) > degree(g, j))
                    order[at] = order[at - 1], at--;
                order[at] = j;
            }
        }
    }
    free(by_degree);
    return DP_OK;
}

/* Relabels the network's nodes in place: user node u becomes pos[u]. */
static int relabel(dp_network *net, double *x0, double *v0, const size_t *order, const size_t *pos)
{
    size_t n = net->n, room = net->M || net->K || net->C ? n * n : n;
    double *tmp = malloc(room * sizeof *tmp), *vec = tmp;
    if (tmp == NULL)
        return DP_ENOMEM;
    double *mats[3] = { net->M, net->K, net->C };
    for (int m = 0; m < 3; m++) {
        if (mats[m] == NULL)
            continue;
        for (size_t i = 0; i < n; i++)
            for (size_t j = 0; j < n; j++)
                tmp[i * n + j] = mats[m][order[i] * n + order[j]];
        memcpy(mats[m], tmp, n * n * sizeof *tmp);
    }
    double *vecs[3] = { net->mass, x0, v0 };
    for (int k = 0; k < 3; k++) {
        if (vecs[k] == NULL)
            continue;
        for (size_t i = 0; i < n; i++)
            vec[i] = vecs[k][order[i]];
        memcpy(vecs[k], vec, n * sizeof *vec);
    }
    free(tmp);
    for (size_t e = 0; e < net->nel; e++) {
        dp_element *el = &net->el[e];
        el->a = el->a >= 0 ? (long)pos[el->a] : el->a;
        el->b = el->b >= 0 ? (long)pos[el->b] : el->b;
    }
    for (size_t f = 0; f < net->nforce; f++)
        net->force[f].node = pos[net->force[f].node];
    return DP_OK;
}

int network_run_reorder(struct dp_network_run *nr, dp_network *net, double *x0, double *v0)
{
    size_t n = net->n;
    if (n < 3)
        return DP_OK;
    coupling g = { 0 };
    size_t *order = malloc(n * sizeof *order), *pos = malloc(n * sizeof *pos);
    unsigned char *seen = malloc(n);
    int s = order && pos && seen ? coupling_build(net, &g) : DP_ENOMEM;
    if (s == DP_OK)
        s = cuthill_mckee(&g, order, seen);
    if (s == DP_OK) {
        for (size_t i = 0; i < n / 2; i++) {    /* reversed: the fill-in of the factor is smaller */
            size_t t = order[i];
            order[i] = order[n - 1 - i], order[n - 1 - i] = t;
        }
        for (size_t i = 0; i < n; i++)
            pos[order[i]] = i;
        size_t before = half_bandwidth(&g, NULL), after = half_bandwidth(&g, pos);
        if (2 * after <= before && (s = relabel(net, x0, v0, order, pos)) == DP_OK) {
            nr->node_pos = pos;    /* the rows read node u at pos[u] */
            pos = NULL;
        }
    }
    coupling_free(&g);
    free(order), free(pos), free(seen);
    return s;
}
