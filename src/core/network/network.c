/* src/core/network/network.c - the network model's lifetime and its linear part (docs/systems.md §1).
 *
 * An element's laws are the one-mass model's (model.c builds their graphs), so a network is prepared by
 * preparing each element as a one-mass model would be: one set of law code for both.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/network.h"
#include "dashpot/status.h"

int dp_network_prepare(dp_network *net)
{
    for (size_t i = 0; i < net->nel; i++) {
        dp_element *e = &net->el[i];
        dp_model m = { .mass = 1, .spring = e->spring, .damper = e->damper };
        if (!e->has_spring)
            m.spring.law = DP_SPRING_LINEAR, m.spring.k = 0;
        if (!e->has_damper)
            m.damper.law = DP_DAMPER_NONE;
        int s = dp_model_prepare(&m);
        e->spring = m.spring;   /* the graphs now belong to the element */
        e->damper = m.damper;
        if (s != DP_OK)
            return s;
    }
    return DP_OK;
}

static void element_clear(dp_element *e)
{
    dp_graph_clear(&e->spring.graph);
    dp_graph_clear(&e->damper.graph);
}

void dp_network_free(dp_network *net)
{
    if (net == NULL)
        return;
    for (size_t i = 0; i < net->nel; i++)
        element_clear(&net->el[i]);
    for (size_t i = 0; i < net->nforce; i++)
        dp_forcing_clear(&net->force[i].f);
    free(net->el);
    free(net->force);
    free(net->mass);
    free(net->M);
    free(net->K);
    free(net->C);
    free(net);
}

static int copy_array(double **dst, const double *src, size_t n)
{
    *dst = NULL;
    if (src == NULL)
        return DP_OK;
    *dst = malloc(n * sizeof **dst);
    if (*dst == NULL)
        return DP_ENOMEM;
    memcpy(*dst, src, n * sizeof **dst);
    return DP_OK;
}

dp_network *dp_network_copy(const dp_network *src)
{
    dp_network *d = calloc(1, sizeof *d);
    if (d == NULL)
        return NULL;
    d->n = src->n;
    size_t nn = src->n * src->n;
    int s = copy_array(&d->mass, src->mass, src->n);
    s = s ? s : copy_array(&d->M, src->M, nn);
    s = s ? s : copy_array(&d->K, src->K, nn);
    s = s ? s : copy_array(&d->C, src->C, nn);
    d->el = src->nel ? calloc(src->nel, sizeof *d->el) : NULL;
    d->force = src->nforce ? calloc(src->nforce, sizeof *d->force) : NULL;
    if (s != DP_OK || (src->nel && d->el == NULL) || (src->nforce && d->force == NULL)) {
        dp_network_free(d);
        return NULL;
    }
    for (size_t i = 0; i < src->nel; i++, d->nel++) {
        d->el[i] = src->el[i];
        memset(&d->el[i].spring.graph, 0, sizeof(dp_graph));
        memset(&d->el[i].damper.graph, 0, sizeof(dp_graph));
        if (dp_graph_copy(&d->el[i].spring.graph, &src->el[i].spring.graph) != DP_OK ||
            dp_graph_copy(&d->el[i].damper.graph, &src->el[i].damper.graph) != DP_OK) {
            d->nel++;
            dp_network_free(d);
            return NULL;
        }
    }
    for (size_t i = 0; i < src->nforce; i++, d->nforce++) {
        d->force[i].node = src->force[i].node;
        if (dp_forcing_copy(&d->force[i].f, &src->force[i].f) != DP_OK) {
            dp_network_free(d);
            return NULL;
        }
    }
    return d;
}

int dp_element_can_stick(const dp_element *e)
{
    if (!e->has_damper)
        return 0;
    double lo, hi;
    dp_graph_force(&e->damper.graph, 0, &lo, &hi);
    return hi > lo;
}

/* A += w b b^T for the element's incidence vector b. */
static void add_incidence(double *A, size_t n, const dp_element *e, double w)
{
    if (A == NULL || w == 0)
        return;
    if (e->a >= 0)
        A[(size_t)e->a * n + (size_t)e->a] += w;
    if (e->b >= 0)
        A[(size_t)e->b * n + (size_t)e->b] += w;
    if (e->a >= 0 && e->b >= 0) {
        A[(size_t)e->a * n + (size_t)e->b] -= w;
        A[(size_t)e->b * n + (size_t)e->a] -= w;
    }
}

/* The stiffness an element adds to K_l: a linear spring's k (graph and rope springs stay in the step). */
static double element_k(const dp_element *e)
{
    return e->has_spring ? dp_spring_stiffness(&e->spring) : 0;
}

/* The viscosity an element adds to C_l: its damper's viscous c (linear, Bingham: docs/mathematics.md §4). */
static double element_c(const dp_element *e)
{
    return e->has_damper ? dp_damper_viscous(&e->damper) : 0;
}

static void fill(double *dst, const double *src, size_t nn)
{
    if (dst == NULL)
        return;
    if (src)
        memcpy(dst, src, nn * sizeof *dst);
    else
        memset(dst, 0, nn * sizeof *dst);
}

void dp_network_linear_parts(const dp_network *net, double *M, double *K, double *C)
{
    size_t n = net->n, nn = n * n;
    fill(M, net->M, nn);
    if (M && net->mass)
        for (size_t i = 0; i < n; i++)
            M[i * n + i] = net->mass[i];
    fill(K, net->K, nn);
    fill(C, net->C, nn);
    for (size_t i = 0; i < net->nel; i++) {
        add_incidence(K, n, &net->el[i], element_k(&net->el[i]));
        add_incidence(C, n, &net->el[i], element_c(&net->el[i]));
    }
}

int dp_element_laws_linear(const dp_element *e)
{
    int nonlinear_spring = e->has_spring && !dp_spring_linear(&e->spring);
    int nonlinear_damper = e->has_damper && !dp_damper_linear(&e->damper);
    int relaxed = e->has_damper && e->damper.relaxation.kind != DP_RELAX_NONE;
    return !nonlinear_spring && !nonlinear_damper && !relaxed;
}

size_t dp_network_nonlinear_elements(const dp_network *net, size_t *out)
{
    size_t m = 0;
    for (size_t i = 0; i < net->nel; i++) {
        const dp_element *e = &net->el[i];
        if (!dp_element_laws_linear(e) || e->has_contact) {
            if (out)
                out[m] = i;
            m++;
        }
    }
    return m;
}
