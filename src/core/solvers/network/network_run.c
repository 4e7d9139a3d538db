/* src/core/solvers/network/network_run.c - the stick-slip solver on a network: theta-steps solved exactly by
 * network_step.c, samples as rows over the chosen columns, a phase change per element as an event.
 *
 * The linear parts are weighted exactly as the one-mass scheme weights them (docs/mathematics.md §4):
 *     W = M + h theta C + h^2 theta^2 K,
 *     rhs = M v - h (1-theta) C v - h K (x + h theta (1-theta) v) + h f(t + theta h) + h sum_e c_e v_b,e b_e,
 * and the graphs at the step's end (springs at u + h z, as the one-mass step takes them), so a network of
 * one node and one element [ground, 0] is the one-mass model step for step. Events are resolved to the
 * step: a phase change is reported at the end of the step that made it.
 *
 * An elastoplastic (Jenkins) spring is weighted like a linear one, (1-theta) F + theta F+, with F+ the
 * return mapping at u+ = u + h ((1-theta) u' + theta z+) (the position update's own u+): its graph in z+
 * has two vertices that move with the plastic offset p, rewritten in place before each step and p moved
 * after it. While elastic it is exactly the linear spring's theta-scheme (second order at theta = 1/2).
 * Its vertices move with the step, so networks with one are stepped with events resolved to the step.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>

#include "base/band.h"
#include "rules/rules.h"
#include "solvers/network/network_run.h"
#include "network/newmark_step.h"
#include "base/root.h"
#include "solvers/network/network_quakes.h"



static size_t bandwidth(const dp_network *net)
{
    size_t n = net->n, p = 0;
    const double *mats[3] = { net->M, net->K, net->C };
    for (int m = 0; m < 3; m++)
        if (mats[m])
            for (size_t i = 0; i < n; i++)
                for (size_t j = i + p + 1; j < n; j++)
                    if (mats[m][i * n + j] != 0)
                        p = j - i;
    for (size_t e = 0; e < net->nel; e++)
        if (net->el[e].a >= 0 && net->el[e].b >= 0 && (size_t)labs(net->el[e].a - net->el[e].b) > p)
            p = (size_t)labs(net->el[e].a - net->el[e].b);
    return p;
}

/* ---- allocation ------------------------------------------------------------------------------------- */

/* Band matrices of n (p+1) doubles a run holds: M, K, C and the step's W, H and factor R; the impact
 * problem's W, H, R with contacts; the step bound's check with relaxation; Newmark's K^ and M's factor. */
static double band_matrices(const dp_run *r)
{
    const dp_network *net = r->spec.net;
    int contacts = 0, relaxed = 0;
    for (size_t i = 0; i < net->nel; i++) {
        contacts |= net->el[i].has_contact || network_run_spring_split(r->state, &net->el[i]);
        relaxed |= net->el[i].has_damper && net->el[i].damper.relaxation.kind != DP_RELAX_NONE;
    }
    return 6 + 3 * contacts + relaxed + 2 * (r->spec.solver.kind == DP_SOLVER_NEWMARK);
}

/* The run's working memory in bytes (include/dashpot/network.h): the band matrices, and per node and per
 * element what the run and its step keep (about 40 doubles a node, 90 an element with its active-set
 * state, saved assignment and forces). */
static double run_bytes(const dp_run *r, size_t p)
{
    const dp_network *net = r->spec.net;
    double n = (double)net->n, band = n * ((double)p + 1);
    return 8 * (band_matrices(r) * band + 40 * n + 90 * (double)net->nel);
}

/* Refuses a run whose working memory would pass DP_NETWORK_MAX_RUN_BYTES, before it allocates any; else
 * bounds the step's contracted factor by what is left of it. */
static int check_run_bytes(dp_run *r, size_t p)
{
    struct dp_network_run *nr = r->state;
    double need = run_bytes(r, p), mib = 1024.0 * 1024.0;
    if (need <= DP_NETWORK_MAX_RUN_BYTES)
        return DP_OK;
    int coupled = 0;
    for (size_t i = 0; i < nr->net->nel; i++)
        coupled |= nr->net->el[i].a >= 0 && nr->net->el[i].b >= 0;
    snprintf(r->error_pointer, sizeof r->error_pointer, coupled ? "/model/elements" : "/model");
    return dp_run_fail(r, DP_ELIMIT, "the network's step would need about %.0f MiB of working memory, over the "
                       "limit of %.0f MiB per run: %zu nodes at half-bandwidth %zu after reordering make %.0f band "
                       "matrices of n (p+1) numbers; couple fewer distant nodes, or split the network",
                       need / mib, DP_NETWORK_MAX_RUN_BYTES / mib, nr->n, p, band_matrices(r));
}

/* The most doubles the step's contracted factor may take: its own band plus what the limit leaves. */
static size_t reduced_limit(const dp_run *r, size_t p)
{
    double n = (double)r->spec.net->n, band = n * ((double)p + 1);
    return (size_t)(band + (DP_NETWORK_MAX_RUN_BYTES - run_bytes(r, p)) / 8);
}

static int alloc_all(struct dp_network_run *nr)
{
    /* arrays over the convex problem's elements hold every element's laws and then every contact */
    size_t n = nr->n, ne = nr->nel ? nr->nel : 1, na = ne, band = n * (nr->p + 1);
    for (size_t i = 0; i < nr->nel; i++) {   /* a bound rope's u <= L is one more contact, a graph's stops one
                                              * each, its jumps an entry each */
        const dp_element *e = &nr->net->el[i];
        na += e->has_contact + network_run_spring_stops(nr, e);
        nr->njump += network_run_spring_split(nr, e) ? dp_spring_graph_jumps(&e->spring, NULL, NULL) : 0;
    }
    na += nr->njump;
    if (nr->njump && ((nr->jump = calloc(na, 1)) == NULL || (nr->jump_S = calloc(nr->njump, sizeof *nr->jump_S)) == NULL))
        return DP_ENOMEM;
    nr->M = calloc(band, sizeof(double));
    nr->K = calloc(band, sizeof(double));
    nr->C = calloc(band, sizeof(double));
    nr->act = calloc(na, sizeof *nr->act);
    nr->act_of = calloc(ne, sizeof *nr->act_of);
    nr->act_el = calloc(na, sizeof *nr->act_el);
    nr->gamma = calloc(na, sizeof *nr->gamma);
    nr->static_A = calloc(na, sizeof *nr->static_A);
    nr->held = calloc(na, 1);
    nr->broke = calloc(na, 1);
    nr->k = calloc(ne, sizeof(double));
    nr->c = calloc(ne, sizeof(double));
    nr->vb = calloc(ne, sizeof(double));
    nr->x = calloc(n, sizeof(double));
    nr->v = calloc(n, sizeof(double));
    nr->v1 = calloc(n, sizeof(double));
    nr->rhs = calloc(n, sizeof(double));
    nr->tmp = calloc(n, sizeof(double));
    nr->u = calloc(na, sizeof(double));
    nr->force = calloc(na, sizeof *nr->force);
    nr->Fs = calloc(ne, sizeof(double));
    nr->Fd = calloc(ne, sizeof(double));
    nr->phase = calloc(ne, 1);
    nr->phase_prev = calloc(ne, 1);
    nr->can_stick = calloc(ne, 1);
    nr->all_nodes = calloc(n, sizeof(size_t));
    nr->all_elements = calloc(ne, sizeof(size_t));
    nr->ep_p = calloc(ne, sizeof(double));
    nr->ep_F = calloc(ne, sizeof(double));
    nr->ep_flow = calloc(ne, 1);
    nr->ep_flow_prev = calloc(ne, 1);
    nr->ep_graph = calloc(ne, sizeof *nr->ep_graph);
    nr->ep_cols = calloc(ne, sizeof *nr->ep_cols);
    if (!nr->ep_p || !nr->ep_F || !nr->ep_flow || !nr->ep_flow_prev || !nr->ep_graph || !nr->ep_cols)
        return DP_ENOMEM;
    return nr->M && nr->K && nr->C && nr->act && nr->act_of && nr->act_el && nr->gamma && nr->static_A && nr->held && nr->broke && nr->k && nr->c && nr->vb && nr->x && nr->v && nr->v1 &&
           nr->rhs && nr->tmp && nr->u && nr->force && nr->Fs && nr->Fd && nr->phase && nr->phase_prev && nr->can_stick &&
           nr->all_nodes && nr->all_elements ? DP_OK : DP_ENOMEM;
}

/* B += w b b^T in band storage for an element's incidence vector b. */
static void band_add_incidence(double *B, size_t p, long a, long b, double w)
{
    if (w != 0)
        dp_band_add_incidence(B, p, a, b, w);
}

static int is_ep(const dp_element *e)
{
    return e->has_spring && dp_spring_plastic(&e->spring);
}

/* The elastoplastic springs' state at the initial elongations (an elongation past yield moves the offset
 * there, as the return mapping would), their step graphs (the run's own copies) at that offset. */
static void ep_init(struct dp_network_run *nr, dp_network *net, const double *x0)
{
    for (size_t i = 0; i < nr->nel; i++) {
        dp_element *e = &net->el[i];
        if (!is_ep(e))
            continue;
        int flow;
        nr->has_ep = 1;
        nr->ep_p[i] = e->spring.offset;
        nr->ep_F[i] = dp_elastoplastic_return(&e->spring, network_run_rel(e->a, e->b, x0), &nr->ep_p[i], &flow);
        nr->ep_graph[i] = &e->spring.graph;
        dp_elastoplastic_graph(&e->spring, nr->ep_p[i], 1, nr->ep_graph[i]);
    }
}

/* Element i's split graph's jumps, an entry each after its own (network_step.h, s_whole): the step graph 0
 * below y, [0, J] at y, J above, at the trapezoid's elongation u + h ((1 - theta) u' + theta z) with weight 1
 * (constant off its vertex, a reaction of the whole step at it). *used counts the jump graphs built. */
static int jump_entries(struct dp_network_run *nr, size_t i, size_t *used)
{
    const dp_element *e = &nr->net->el[i];
    size_t n = dp_spring_graph_jumps(&e->spring, NULL, NULL);
    double *y = malloc((n ? n : 1) * sizeof *y), *J = malloc((n ? n : 1) * sizeof *J);
    int st = y && J ? DP_OK : DP_ENOMEM;
    if (st == DP_OK)
        dp_spring_graph_jumps(&e->spring, y, J);
    for (size_t j = 0; st == DP_OK && j < n; j++) {
        const double flat[2] = { 1, 0 }, yy[2] = { y[j], y[j] }, ff[2] = { 0, J[j] };
        dp_graph *g = &nr->jump_S[(*used)++];
        if ((st = dp_graph_init(g, 2, yy, ff, flat, flat)) != DP_OK)
            break;
        nr->jump[nr->nact] = 1;
        nr->act_el[nr->nact] = i;
        nr->act[nr->nact++] = (dp_network_step_element){ .a = e->a, .b = e->b, .S = g, .ep_theta = nr->theta,
                                                         .s_whole = 1 };
    }
    free(y), free(J);
    return st;
}

/* Element i's bounded graph's sloped part into stop_S (allocated for every element on first use). */
static int stop_part(struct dp_network_run *nr, size_t i)
{
    if (nr->stop_S == NULL && (nr->stop_S = calloc(nr->nel, sizeof *nr->stop_S)) == NULL)
        return DP_ENOMEM;
    return dp_spring_bounded_part(&nr->net->el[i].spring, &nr->stop_S[i]) == DP_OK ? DP_OK : DP_ENOMEM;
}

/* The linear parts straight into band storage (a dense n x n copy would not fit a chain of 10^4 blocks);
 * the elements' nonlinear laws into the convex problem's list. */
static int setup_laws(struct dp_network_run *nr)
{
    size_t jumps = 0;
    const dp_network *net = nr->net;
    size_t n = nr->n, p = nr->p;
    if (net->M)
        dp_band_from_dense(net->M, n, p, nr->M);
    else
        for (size_t i = 0; i < n; i++)
            nr->M[i * (p + 1)] = net->mass[i];
    if (net->K)
        dp_band_from_dense(net->K, n, p, nr->K);
    if (net->C)
        dp_band_from_dense(net->C, n, p, nr->C);
    for (size_t i = 0; i < nr->nel; i++) {
        const dp_element *e = &nr->net->el[i];
        int rope = network_run_spring_split(nr, e);   /* k in K, u <= L a contact (network_contact.c) */
        const dp_graph *S = rope ? NULL : &e->spring.graph;
        int split = rope && e->spring.law != DP_SPRING_ROPE;
        if (split) {   /* a split graph: its sloped part here, its jumps entries after, its stops contacts */
            if (stop_part(nr, i) != DP_OK)
                return DP_ENOMEM;
            S = &nr->stop_S[i], rope = 0;
        }
        int lin_spring = !e->has_spring || dp_spring_linear(&e->spring) || rope;
        nr->k[i] = rope ? e->spring.k : e->has_spring ? dp_spring_stiffness(&e->spring) : 0;
        nr->c[i] = e->has_damper ? dp_damper_viscous(&e->damper) : 0;
        nr->vb[i] = e->has_damper ? e->damper.belt_velocity : 0;
        nr->kmax = fmax(nr->kmax, fabs(nr->k[i])), nr->cmax = fmax(nr->cmax, fabs(nr->c[i]));
        nr->vbmax = fmax(nr->vbmax, fabs(nr->vb[i]));
        nr->belt_viscous |= e->has_damper && nr->c[i] != 0 && e->damper.belt_velocity != 0;
        int set_damper = e->has_damper && (!dp_damper_linear(&e->damper)
                                           || e->damper.relaxation.kind != DP_RELAX_NONE);
        nr->can_stick[i] = (unsigned char)dp_element_can_stick(e);
        nr->act_of[i] = -1;
        band_add_incidence(nr->K, p, e->a, e->b, nr->k[i]);
        band_add_incidence(nr->C, p, e->a, e->b, nr->c[i]);
        if (!set_damper && lin_spring)
            continue;
        if (e->has_damper && e->damper.relaxation.kind != DP_RELAX_NONE)
            nr->gamma[nr->nact] = &e->damper.relaxation, nr->relaxed = 1;
        if (e->has_damper && dp_damper_static(&e->damper) > dp_damper_kinetic(&e->damper)) {
            dp_graph g = { 0 };   /* the stick interval at the static threshold */
            if (dp_damper_static_graph(&e->damper, &g) != DP_OK)
                return DP_ENOMEM;
            nr->static_A[nr->nact] = g;
            nr->has_static = 1;
        }
        nr->act_of[i] = (long)nr->nact;
        nr->act_el[nr->nact] = i;
        nr->act[nr->nact++] = (dp_network_step_element){ .a = e->a, .b = e->b, .A = set_damper ? &e->damper.graph : NULL,
                                             .S = lin_spring ? NULL : S,
                                             .vb = e->has_damper ? e->damper.belt_velocity : 0,
                                             .ep_theta = is_ep(e) ? nr->theta : 0 };
        if (split && jump_entries(nr, i, &jumps) != DP_OK)
            return DP_ENOMEM;
    }
    return network_run_contacts_setup(nr);
}

static int setup_columns(struct dp_network_run *nr, const dp_output_spec *o)
{
    for (size_t i = 0; i < nr->n; i++)
        nr->all_nodes[i] = i;
    for (size_t i = 0; i < nr->nel; i++)
        nr->all_elements[i] = i;
    nr->cols.nodes = o->nodes ? o->nnodes : nr->n;
    nr->cols.node = o->nodes ? o->nodes : nr->all_nodes;
    nr->cols.elements = o->elements ? o->nelements : nr->nel;
    nr->cols.element = o->elements ? o->elements : nr->all_elements;
    size_t nn = nr->cols.nodes, ne = nr->cols.elements;
    static const char *const names[] = { "x", "v", "Fs", "Fd", "phase" };
    nr->cols.ngroups = 5;
    for (size_t g = 0; g < 5; g++)
        nr->cols.group[g] = (dp_column_group){ .name = names[g], .n = g < 2 ? nn : ne,
                                               .index = g < 2 ? nr->cols.node : nr->cols.element, .phase = g == 4 };
    nr->row_len = nr->cols.width = 2 * nn + 3 * ne;
    for (size_t j = 0; j < ne; j++)
        if (is_ep(&nr->net->el[nr->cols.element[j]]))
            nr->ep_cols[nr->nep_cols++] = nr->cols.element[j];
    if (nr->nep_cols) {   /* the plastic offsets of the written elastoplastic springs */
        nr->cols.group[nr->cols.ngroups++] = (dp_column_group){ .name = "p", .n = nr->nep_cols,
                                                                .index = nr->ep_cols };
        nr->row_len = nr->cols.width += nr->nep_cols;
    }
    if (nr->nc > nr->nrope) {   /* the contacts' forces (0 for the written elements without one) */
        nr->cols.group[nr->cols.ngroups++] = (dp_column_group){ .name = "Fn", .n = ne, .index = nr->cols.element };
        nr->row_len = nr->cols.width += ne;
    }
    size_t rl = nr->row_len ? nr->row_len : 1;
    nr->final_row = calloc(rl, sizeof(double));
    nr->pending_row = calloc(rl, sizeof(double));
    nr->slots.width = nr->row_len;
    /* the queue grows when a step makes more records than fit (it never drops one); sized for the elements
     * it held ne + 2 rows of row_len numbers, 51 GB for a chain of 20 000 blocks written whole */
    if (dp_row_queue_init(&nr->queue, nr->row_len, 16) != DP_OK)
        return DP_ENOMEM;
    return nr->final_row && nr->pending_row ? DP_OK : DP_ENOMEM;
}

void network_run_free(void *state)
{
    struct dp_network_run *nr = state;
    if (nr == NULL)
        return;
    dp_network_step_free(nr->ws);
    dp_network_regularized_free(nr->reg);
    for (size_t i = 0; nr->static_A && i < nr->nact; i++)
        dp_graph_clear(&nr->static_A[i]);
    dp_nm_free(nr->nm);
    network_run_contacts_free(nr);
    network_run_smooth_free(nr);
    for (size_t i = 0; nr->stop_S && i < nr->nel; i++)
        dp_graph_clear(&nr->stop_S[i]);
    for (size_t j = 0; nr->jump_S && j < nr->njump; j++)
        dp_graph_clear(&nr->jump_S[j]);
    free(nr->stop_S), free(nr->jump_S), free(nr->jump);
    dp_row_queue_clear(&nr->queue);
    network_quakes_free(nr->quakes);
    void *p[] = { nr->nm_ea, nr->nm_eb, nr->nm_ek, nr->nm_F, nr->nm_P, nr->nm_flow, nr->nm_el, nr->ep_p, nr->ep_F, nr->ep_flow, nr->ep_flow_prev, (void *)nr->ep_graph, nr->ep_cols, nr->node_pos, nr->static_A, nr->held, nr->broke, nr->act_el, nr->pattern, nr->margin, nr->roots, nr->end_margin, nr->fails, nr->scale, nr->fixed, nr->cand, nr->fails_at, nr->v1_keep, nr->force_keep, nr->Mv, nr->Cv, nr->Mv_at, nr->couple, nr->blk, nr->blk_W, nr->blk_rhs, nr->M, nr->K, nr->C, nr->act, nr->act_of, (void *)nr->gamma, nr->k, nr->c, nr->vb, nr->x, nr->v, nr->v1, nr->rhs,
                  nr->tmp, nr->u, nr->force, nr->Fs, nr->Fd, nr->phase, nr->phase_prev, nr->can_stick, nr->all_nodes,
                  nr->all_elements, nr->slots.data, nr->final_row, nr->pending_row };
    for (size_t i = 0; i < sizeof p / sizeof *p; i++)
        free(p[i]);
    free(nr);
}

/* ---- the newmark solver ------------------------------------------------------------------------------ */

/* The load at t: the nodes' forcing and the linear dampers' belt terms c v_b b. */
static void nm_load(struct dp_network_run *nr, double t, double *P)
{
    memset(P, 0, nr->n * sizeof *P);
    for (size_t i = 0; i < nr->net->nforce; i++)
        P[nr->net->force[i].node] += dp_forcing_eval(&nr->net->force[i].f, t);
    for (size_t i = 0; i < nr->nel; i++) {
        const dp_element *e = &nr->net->el[i];
        double g = e->has_damper ? nr->c[i] * e->damper.belt_velocity : 0;
        if (g != 0 && e->b >= 0)
            P[e->b] += g;
        if (g != 0 && e->a >= 0)
            P[e->a] -= g;
    }
}

/* The elastoplastic forces and tangent states in the stepper's order. */
static void nm_gather(struct dp_network_run *nr)
{
    for (size_t j = 0; j < nr->nm_nep; j++)
        nr->nm_F[j] = nr->ep_F[nr->nm_el[j]], nr->nm_flow[j] = nr->ep_flow[nr->nm_el[j]];
}

static int newmark_init(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    size_t m = nr->nel ? nr->nel : 1;
    nr->nm_ea = calloc(m, sizeof *nr->nm_ea), nr->nm_eb = calloc(m, sizeof *nr->nm_eb);
    nr->nm_ek = calloc(m, sizeof *nr->nm_ek), nr->nm_F = calloc(m, sizeof *nr->nm_F);
    nr->nm_flow = calloc(m, 1), nr->nm_el = calloc(m, sizeof *nr->nm_el);
    nr->nm_P = calloc(nr->n, sizeof *nr->nm_P);
    if (!nr->nm_ea || !nr->nm_eb || !nr->nm_ek || !nr->nm_F || !nr->nm_flow || !nr->nm_el || !nr->nm_P)
        return DP_ENOMEM;
    for (size_t i = 0; i < nr->nel; i++)
        if (nr->ep_graph[i]) {
            const dp_element *e = &nr->net->el[i];
            nr->nm_ea[nr->nm_nep] = e->a, nr->nm_eb[nr->nm_nep] = e->b, nr->nm_ek[nr->nm_nep] = e->spring.k;
            nr->nm_el[nr->nm_nep++] = i;
        }
    dp_nm *w = nr->nm = dp_nm_alloc(nr->n, nr->p, nr->nm_nep);
    if (w == NULL)
        return DP_ENOMEM;
    w->M = nr->M, w->C = nr->C, w->K = nr->K, w->ea = nr->nm_ea, w->eb = nr->nm_eb, w->ek = nr->nm_ek;
    w->beta = r->spec.solver.beta, w->gamma = r->spec.solver.gamma;
    nm_load(nr, 0, nr->nm_P);
    nm_gather(nr);
    return dp_nm_start(w, nr->x, nr->v, nr->nm_P, nr->nm_F);
}

/* One step of Höschl's incremental form to t + h, the elastoplastic springs' return mappings after it. */
static int newmark_step(dp_run *r, double t, double h)
{
    struct dp_network_run *nr = r->state;
    nm_load(nr, t + h, nr->nm_P);
    nm_gather(nr);
    if (dp_nm_step(nr->nm, h, nr->nm_P, nr->nm_flow, nr->x, nr->v) != DP_OK)
        return DP_ESOLVE;
    network_run_ep_update(nr);
    nm_gather(nr);
    dp_nm_accel(nr->nm, nr->x, nr->v, nr->nm_P, nr->nm_F);
    return DP_OK;
}

/* sup gamma' over the line: the slope that can eat into W's definiteness. */
static double relaxation_rise(const dp_relaxation *g)
{
    if (g->kind == DP_RELAX_LINEAR)
        return g->L > 0 ? g->L : 0;
    return dp_relaxation_lipschitz(g);
}

/* With relaxation the step's problem is strongly monotone while W - h theta sum_e L_e b_e b_e^T is positive
 * definite (the n-DOF form of thesis (4.10), m + h theta c + h^2 theta^2 k > h theta L_gamma for one mass);
 * checked for the nominal and the last step by GSL's band Cholesky. */
static int check_step_bound(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    if (!nr->relaxed)
        return DP_OK;
    size_t len = nr->n * (nr->p + 1);
    double *B = malloc(len * sizeof *B), th = nr->theta;
    if (B == NULL)
        return DP_ENOMEM;
    double hs[2] = { r->h, r->spec.solver.t_end - (double)(r->nsteps - 1) * r->h };
    int ok = 1;
    for (int k = 0; k < 2 && ok; k++) {
        double h = hs[k];
        for (size_t i = 0; i < len; i++)
            B[i] = nr->M[i] + h * th * nr->C[i] + h * h * th * th * nr->K[i];
        for (size_t a = 0; a < nr->nact; a++)
            if (nr->gamma[a])
                band_add_incidence(B, nr->p, nr->act[a].a, nr->act[a].b, -h * th * relaxation_rise(nr->gamma[a]));
        gsl_matrix_view v = gsl_matrix_view_array(B, nr->n, nr->p + 1);
        ok = gsl_linalg_cholesky_band_decomp(&v.matrix) == 0;
    }
    free(B);
    if (ok)
        return DP_OK;
    snprintf(r->error_pointer, sizeof r->error_pointer, "/solver/dt");
    return dp_run_fail(r, DP_EINVAL, "with relaxation a step has one solution only while W - h theta sum_e L_e b_e "
                       "b_e^T is positive definite (thesis (4.10) for n masses); at dt = %g it is not: take a "
                       "smaller dt", r->h);
}

/* The member whose stiffness (K: k = 1) or viscosity (C: k = 0) is largest: the stiffness or damping matrix
 * where it has the largest entry, else the element with the largest k or c. */
static void largest_member(dp_run *r, int K, char *p, size_t cap)
{
    const struct dp_network_run *nr = r->state;
    const dp_network *net = nr->net;
    const double *A = K ? net->K : net->C, *per = K ? nr->k : nr->c;
    double top = 0, mat = 0;
    size_t at = 0;
    for (size_t i = 0; A && i < net->n * net->n; i++)
        mat = fmax(mat, fabs(A[i]));
    for (size_t i = 0; i < nr->nel; i++)
        if (fabs(per[i]) > top)
            top = fabs(per[i]), at = i;
    if (A && mat >= top)
        snprintf(p, cap, K ? "/model/stiffness_matrix" : "/model/damping_matrix");
    else if (net->one_mass_doc)
        snprintf(p, cap, K ? "/model/spring" : "/model/damper");
    else
        snprintf(p, cap, "/model/elements/%zu/%s", at, K ? "spring" : "damper");
}

/* Every quantity the step forms from the input, checked where it is formed, before the first step: W's band
 * entries (M + h theta C + h^2 theta^2 K) and the right side's weights h K and h (1 - theta) C below the
 * magnitude the state check takes for a divergence, and the first step's right side finite. A stiffness of
 * 1e308 at dt = 0.01 is refused at its member, not streamed into "the solution diverged". */
static int check_step_magnitudes(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    const double big = 1e300, h = r->h, th = nr->theta, *W = dp_network_step_W(nr->ws);
    size_t len = nr->n * (nr->p + 1);
    for (size_t i = 0; i < len; i++) {
        int K = !(fabs(h * nr->K[i]) < big) || !(fabs(h * h * th * th * nr->K[i]) < big);
        int C = !(fabs(h * nr->C[i]) < big);
        if (!K && !C && fabs(W[i]) < big)
            continue;
        largest_member(r, K || !C, r->error_pointer, sizeof r->error_pointer);
        return dp_run_fail(r, DP_EINVAL, "at dt = %g the step's matrix W = M + h theta C + h^2 theta^2 K or its "
                           "right side takes entries of %g or more: beyond what the step can form in doubles; "
                           "take smaller coefficients (change the units) or a smaller dt", h, big);
    }
    network_run_step_rhs(nr, 0, h);
    for (size_t i = 0; i < nr->n; i++)
        if (!(fabs(nr->rhs[i]) < big)) {
            snprintf(r->error_pointer, sizeof r->error_pointer, nr->net->one_mass_doc ? "/initial" : "/initial/x");
            return dp_run_fail(r, DP_EINVAL, "the first step's right side M v - h K x - ... + h f overflows (node "
                               "%zu): the initial state and the loads are too large for the coefficients", i);
        }
    return DP_OK;
}

/* A located run on a chain: which neighbours M, C or K couple, and room for a held solve's blocks (at most
 * three a candidate, merged; their rows of W and of the right side: network_events.c). Not for a network
 * whose held solves read more than the blocks hold (contacts' margins, theta-weighted springs, relaxation, a
 * viscous damper's belt in the right side): nr->couple stays NULL, and they are solved whole. */
static int chain_blocks_setup(struct dp_network_run *nr)
{
    if (nr->nc || nr->has_ep || nr->has_smooth || nr->jump || nr->relaxed || nr->belt_viscous)
        return DP_OK;
    size_t n = nr->n, na = nr->nact ? nr->nact : 1;
    nr->couple = calloc(n, 1);
    nr->blk_cap = 6 * na + 2;
    nr->blk = calloc(nr->blk_cap, sizeof *nr->blk);
    nr->blk_W = calloc(4 * n + 4, sizeof *nr->blk_W);
    nr->blk_rhs = calloc(n + 1, sizeof *nr->blk_rhs);
    if (!nr->couple || !nr->blk || !nr->blk_W || !nr->blk_rhs)
        return DP_ENOMEM;
    for (size_t i = 0; i + 1 < n; i++)
        nr->couple[i] = nr->M[2 * i + 1] != 0 || nr->C[2 * i + 1] != 0 || nr->K[2 * i + 1] != 0;
    return DP_OK;
}

/* The state, the laws, the columns and the workspace: what the network run and the one-mass network share. */
int network_run_setup(dp_run *r)
{
    struct dp_network_run *nr = calloc(1, sizeof *nr);
    if (nr == NULL)
        return DP_ENOMEM;
    r->state = nr;
    nr->net = r->spec.net;
    r->cols = &nr->cols;
    nr->n = nr->net->n, nr->nel = nr->net->nel, nr->theta = r->spec.solver.theta;
    int s = network_run_reorder(nr, r->spec.net, r->spec.x0v, r->spec.v0v);
    if (s != DP_OK)
        return s;
    nr->p = bandwidth(nr->net);
    nr->locate = dp_network_locates(&r->spec);
    nr->ropes_bound = nr->locate && r->spec.solver.kind == DP_SOLVER_STICK_SLIP &&
                      !dp_network_is_one_mass(&r->spec);
    if ((s = check_run_bytes(r, nr->p)) != DP_OK)
        return s;
    s = alloc_all(nr);
    s = s ? s : setup_laws(nr);
    s = s ? s : setup_columns(nr, &r->spec.output);
    if (s == DP_OK && (nr->ws = dp_network_step_alloc(nr->n, nr->p, nr->nact, nr->act)) == NULL)
        s = DP_ENOMEM;
    if (s != DP_OK)
        return s;
    if (nr->relaxed)
        dp_network_step_relaxation(nr->ws, nr->gamma, nr->theta);
    dp_network_step_set_poll(nr->ws, network_run_step_poll, r);
    dp_network_step_limit(nr->ws, reduced_limit(r, nr->p));
    if (nr->iws)
        dp_network_step_set_poll(nr->iws, network_run_step_poll, r);
    ep_init(nr, r->spec.net, r->spec.x0v);
    if ((s = network_run_smooth_setup(nr)) != DP_OK)
        return s;
    nr->pattern = malloc(dp_network_step_pattern_bytes(nr->ws));
    nr->margin = calloc(nr->nact ? nr->nact : 1, sizeof *nr->margin);
    nr->roots = calloc(nr->nact ? nr->nact : 1, sizeof *nr->roots);
    size_t na = nr->nact ? nr->nact : 1;
    nr->fails = calloc(na, 1);
    nr->scale = calloc(na, sizeof *nr->scale);
    nr->end_margin = calloc(na, sizeof *nr->end_margin);
    nr->fixed = calloc(na, 1), nr->cand = calloc(na, 1), nr->fails_at = calloc(na, 1);
    nr->v1_keep = calloc(nr->n, sizeof *nr->v1_keep);
    nr->force_keep = calloc(na, sizeof *nr->force_keep);
    if (nr->locate) {   /* the held solves' shared products (network_stepping.c) */
        nr->Mv = calloc(nr->n, sizeof *nr->Mv), nr->Cv = calloc(nr->n, sizeof *nr->Cv);
        nr->Mv_at = calloc(nr->n, sizeof *nr->Mv_at);
        if (nr->Mv == NULL || nr->Cv == NULL || nr->Mv_at == NULL)
            return DP_ENOMEM;
    }
    if (nr->locate && nr->p == 1 && (s = chain_blocks_setup(nr)) != DP_OK)
        return s;
    if (nr->pattern == NULL || nr->margin == NULL || nr->roots == NULL || nr->end_margin == NULL || nr->fails == NULL || nr->scale == NULL ||
        nr->fixed == NULL || nr->cand == NULL || nr->fails_at == NULL || nr->v1_keep == NULL ||
        nr->force_keep == NULL)
        return DP_ENOMEM;
    return check_step_bound(r);
}

/* The network run: its setup, then the initial forces and the first row. */
static int network_run_init(dp_run *r)
{
    int s = network_run_setup(r);
    if (s != DP_OK)
        return s;
    struct dp_network_run *nr = r->state;
    memcpy(nr->x, r->spec.x0v, nr->n * sizeof *nr->x);
    memcpy(nr->v, r->spec.v0v, nr->n * sizeof *nr->v);
    if (r->spec.solver.kind == DP_SOLVER_REGULARIZED) {
        if ((s = dp_network_regularized_init(r)) != DP_OK)
            return s;
        r->countdown = 1;
        network_run_finalize_summary(r);
        network_run_emit_row(r);
        return DP_OK;
    }
    if (r->spec.solver.kind == DP_SOLVER_NEWMARK) {
        if ((s = newmark_init(r)) != DP_OK)
            return s;
        network_run_element_forces(nr, 0);
        r->countdown = 1;
        network_run_finalize_summary(r);
        network_run_emit_row(r);
        return DP_OK;
    }
    network_run_smooth_update(nr);
    network_run_touch_start(nr, r->h);
    network_run_build_W(nr, r->h);
    if ((s = check_step_magnitudes(r)) != DP_OK)
        return s;
    /* The initial forces and phases: an exact step of a billionth of dt from the initial state says which
     * elements the stick intervals hold at t = 0 (one mass: the force needed against the interval) and
     * leaves its assignment for the first located step. */
    double h0 = 1e-9 * r->h;
    if (nr->has_static)   /* the rest branch: an element at rest at t = 0 starts on its static interval */
        network_run_element_forces(nr, 0);
    if (nr->nc)
        network_run_contacts_arm_mj(nr, h0);
    if (network_run_net_step_keep(r, 0, h0) == DP_OK)
        network_run_element_forces(nr, 1);
    else
        network_run_element_forces(nr, 0);
    network_run_contacts_after_probe(nr);
    if (r->spec.output.quakes && (s = network_quakes_begin(nr, r->cur.t)) != DP_OK)
        return s;
    r->countdown = 1;
    for (size_t i = 0; nr->has_ep && i < nr->nel; i++)   /* an initial elongation past yield: sliding */
        if (nr->ep_graph[i] && nr->ep_p[i] != nr->net->el[i].spring.offset)
            nr->ep_flow[i] = nr->ep_p[i] > nr->net->el[i].spring.offset ? 1 : -1;
    network_run_finalize_summary(r);
    network_run_emit_row(r);     /* the initial state: queued, no block yet */
    network_run_plastic_events(r, 0);   /* its yield at t = 0, as one mass writes it */
    return DP_OK;
}

static int network_run_advance(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    if (nr->reg)
        return dp_network_regularized_advance(r);
    if (network_run_reserve_rows(r) != DP_OK)
        return DP_ENOMEM;
    network_run_flush(r);
    int due;
    while (network_run_step_due(r, &due)) {
        double h = dp_run_step_length(r), t = r->cur.t;
        int s, bounded = 0;
        nr->impacts_step = 0;
        if (nr->nm) {
            if ((s = newmark_step(r, t, h)) == DP_OK) {
                network_run_element_forces(nr, 0);
                network_run_plastic_events(r, t + h);
            }
        } else if (nr->locate && nr->solved) {
            s = network_run_located_step(r, t, h);
        } else {
            memcpy(nr->phase_prev, nr->phase, nr->nel);
            if ((s = network_run_net_step(r, t, h)) == DP_OK) {
                /* the forces only for a row (phases and a bound for the others) */
                bounded = !network_run_writes_row(r) && network_run_element_phases(nr);
                if (!bounded)
                    network_run_element_forces(nr, 1);
                network_run_step_events(r, nr->phase_prev, t + h);
                network_run_plastic_events(r, t + h);
                network_run_stick_time(r, nr->phase, h);
            }
        }
        if (s != DP_OK && network_run_cancelled(r))
            return r->status;     /* stopped inside the step: its message says when */
        if (s == DP_ELIMIT)
            return dp_run_fail(r, s, "the step at t = %.17g fixes elements whose trees interleave: its contracted "
                               "matrix would need %.0f MiB, past the limit of %.0f MiB per run", t,
                               8.0 * (double)dp_network_step_reduced_need(nr->ws) / (1024.0 * 1024.0),
                               DP_NETWORK_MAX_RUN_BYTES / (1024.0 * 1024.0));
        if (s != DP_OK)
            return dp_run_fail(r, s, "the implicit step at t = %.17g has no solution (%s)", t, dp_strerror(s));
        if ((s = network_run_step_taken(r, bounded || network_run_state_finite(nr))) != DP_OK)
            return s;
    }
    return due;
}

int network_run_step_taken(dp_run *r, int finite)
{
    r->n++;
    r->cur.t = r->n < r->nsteps ? (double)r->n * r->h : r->spec.solver.t_end;
    size_t sm = finite ? 0 : network_run_smooth_overflow(network_run_of(r));
    if (sm)
        return dp_run_fail(r, DP_ENONFINITE, "element %zu's spring force overflows at t = %.17g: its graph's "
                           "slope times the elongation passes the largest double", sm - 1, r->cur.t);
    if (!finite)
        return dp_run_fail(r, DP_ENONFINITE, "the solution diverged at t = %.17g", r->cur.t);
    r->sum.steps = r->n;
    if (r->n >= r->nsteps) {
        r->finished = 1;
        network_run_finalize_summary(r);
    }
    if (--r->countdown <= 0 || r->n >= r->nsteps)
        network_run_emit_row(r);
    return DP_OK;
}

/* Whether the element's laws let their events be located (their entries' locate, or locate_network on a
 * network of more than one mass). */
static int element_locates(const dp_element *e, int network)
{
    const dp_spring_law_info *SL = dp_spring_law_info_of(e->spring.law);
    const dp_damper_law_info *DL = dp_damper_law_info_of(e->damper.law);
    int spring = !e->has_spring || (SL && (network ? SL->locate_network : SL->locate)) ||
                 (network && (dp_spring_sloped_graph(&e->spring) || dp_spring_is_split(&e->spring)));
    return spring && (!e->has_damper || (DL && DL->locate));
}

/* Location holds an assignment over shorter steps: a spring graph with a vertical piece holds its force as
 * a multiplier at a vertex whose z moves with the step's length, so it is stepped without it; a graph of
 * finite slope is held on its piece (network_smooth.c); a static threshold is held on the graph of its
 * phase, relaxation iterated in the held step (network_events.c); a rope is then a linear spring and the
 * contact u <= L (network_contact.c), whose going taut is an event. */
int dp_network_locates(const dp_spec *s)
{
    if (dp_network_is_one_mass(s))   /* the one-mass solver locates every damper that can stick */
        return s->solver.events == DP_EVENTS_LOCATE && dp_element_can_stick(&s->net->el[0]) &&
               element_locates(&s->net->el[0], 0);
    int sticky = 0;
    for (size_t i = 0; i < s->net->nel; i++) {
        const dp_element *e = &s->net->el[i];
        sticky |= e->has_contact;   /* a compliant one's touch and separation too (network_smooth.c) */
        if (!element_locates(e, 1))
            return 0;
        sticky |= dp_element_can_stick(e) || is_ep(e);   /* a slider sticks and slides too */
        /* a graph's kinks, stops and jumps, a rope going taut */
        sticky |= e->has_spring && !dp_spring_linear(&e->spring);
    }
    return sticky && s->solver.events == DP_EVENTS_LOCATE;
}

int network_run_pending(const dp_run *r)
{
    return dp_row_queue_waiting(&network_run_of(r)->queue);
}

const char *network_run_events_mode(const dp_spec *s)
{
    return dp_network_locates(s) ? "locate" : s->solver.events == DP_EVENTS_NONE ? "none" : "step";
}

/* One run of the network for its three solvers: init and advance follow the solver's kind. */
const dp_run_type dp_run_network = {
    .name = "stick-slip", .variant = "exact", .events_mode = network_run_events_mode, .check = dp_rules_network,
    .init = network_run_init, .advance = network_run_advance, .pending = network_run_pending,
    .free = network_run_free,
};

const dp_run_type dp_run_network_regularized = {
    .name = "regularized", .check = dp_rules_network, .init = network_run_init, .advance = network_run_advance,
    .pending = network_run_pending, .free = network_run_free,
};

const dp_run_type dp_run_network_newmark = {
    .name = "newmark", .check = dp_rules_network, .init = network_run_init, .advance = network_run_advance,
    .pending = network_run_pending, .free = network_run_free,
};
