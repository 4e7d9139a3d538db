/* src/core/solvers/network/network_stepping.c - one exact step of a network run (docs/systems.md §2): the
 * step's right-hand side, W = M + h theta C + h^2 theta^2 K, the active-set solve of network/network_step.c,
 * the velocity taken from it and each element's forces and phase after it. Below the located step
 * (network_events.c) and the run (network_run.c), which both step through it; above the contacts. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/band.h"
#include "solvers/network/network_run.h"

/* The elastoplastic springs after a step: each one's return map at its new elongation, its step graph moved
 * with its offset where it slid. */
void network_run_ep_update(struct dp_network_run *nr)
{
    if (!nr->has_ep)
        return;
    for (size_t i = 0; i < nr->nel; i++) {
        if (nr->ep_graph[i] == NULL)
            continue;
        const dp_element *e = &nr->net->el[i];
        int flow;
        nr->ep_flow_prev[i] = nr->ep_flow[i];
        nr->ep_F[i] = dp_elastoplastic_return(&e->spring, network_run_rel(e->a, e->b, nr->x), &nr->ep_p[i], &flow);
        nr->ep_flow[i] = (signed char)flow;
        if (flow)
            dp_elastoplastic_graph(&e->spring, nr->ep_p[i], 1, nr->ep_graph[i]);
    }
}

int network_run_step_poll(void *run, unsigned long long units)
{
    dp_run *r = run;
    struct dp_network_run *nr = r->state;
    nr->work += units;
    if (network_run_cancelled(r))
        return 1;
    if (!dp_run_stopped(r, nr->work))
        return 0;
    if (network_run_cancelled(r))
        return 1;
    nr->yield = 1;   /* the hook asked for a yield: only between steps */
    return 0;
}

/* Entry e of W = M + h theta C + h^2 theta^2 K in band storage. */
static double W_entry(const struct dp_network_run *nr, size_t e, double h)
{
    double th = nr->theta;
    return nr->M[e] + h * th * nr->C[e] + h * h * th * th * nr->K[e];
}

void network_run_build_W(struct dp_network_run *nr, double h)
{
    size_t len = nr->n * (nr->p + 1);
    double *W = dp_network_step_W(nr->ws);
    for (size_t i = 0; i < len; i++)
        W[i] = W_entry(nr, i, h);
    dp_network_step_W_changed(nr->ws);
    nr->h_W = h;
}

/* ---- the state's forces and rows ------------------------------------------------------------------- */

/* Element i's forces and phase from the step's solution or (not stepped) the initial state. Kept out of the
 * loop below, which runs for every element after every step: its common case reads a handful of arrays the
 * loop holds in locals (a store of a phase byte may alias anything, so fields read through nr are read again
 * after each one). */
static int element_forces_set(struct dp_network_run *nr, size_t i, long k, int stepped, double u, double z,
                                        double vb, double *fs, double *fd)
{
    double lo, hi;
    int rest = z == vb;
    if (k >= 0 && nr->ep_graph[i]) {   /* the return mapping's force, not the step's weighted one */
        *fs = nr->ep_F[i];
        if (stepped && nr->act[k].A)   /* without a damper the split's rounding is not a force */
            *fd += nr->force[k].a, rest = nr->force[k].at_rest;
        else if (nr->act[k].A) {
            dp_graph_force(nr->act[k].A, z - vb, &lo, &hi);
            *fd += fmin(fmax(0.0, lo), hi);
        }
    } else if (k >= 0 && stepped) {
        const dp_network_step_forces *f = &nr->force[k];
        *fs += network_run_smooth_force(nr, (size_t)k, f->s), *fd += f->a, rest = f->at_rest;
    } else if (k >= 0) {
        if (nr->act[k].S) {
            dp_graph_force(nr->act[k].S, u, &lo, &hi);
            *fs += fmin(fmax(0.0, lo), hi);
        }
        if (nr->act[k].A) {
            dp_graph_force(nr->act[k].A, z - vb, &lo, &hi);
            *fd += fmin(fmax(0.0, lo), hi);
        }
    }
    const dp_element *e = &nr->net->el[i];
    if (e->has_damper && e->damper.relaxation.kind != DP_RELAX_NONE)
        *fd -= dp_relaxation_eval(&e->damper.relaxation, z - vb);
    return rest;
}

/* Each element's forces and phase at the current state; `stepped`: after a step (forces from its
 * solution), else the initial state (set-valued forces taken closest to zero). */
void network_run_element_forces(struct dp_network_run *nr, int stepped)
{
    const dp_element *el = nr->net->el;
    const double *x = nr->x, *v = nr->v, *kk = nr->k, *cc = nr->c, *vbs = nr->vb;
    const long *act_of = nr->act_of;
    const unsigned char *can_stick = nr->can_stick;
    const dp_network_step_forces *force = nr->force;
    double *Fs = nr->Fs, *Fd = nr->Fd;
    unsigned char *phase = nr->phase;
    /* the plain case (no elastoplastic, sloped, relaxed spring anywhere) is the loop's own */
    int plain = !nr->has_ep && !nr->has_smooth && !nr->relaxed;
    for (size_t i = 0, nel = nr->nel; i < nel; i++) {
        const dp_element *e = &el[i];
        double u = network_run_rel(e->a, e->b, x), z = network_run_rel(e->a, e->b, v), vb = vbs[i];
        /* no linear part: 0, not the -0 of 0 * (a negative elongation) */
        double fs = kk[i] != 0 ? kk[i] * u : 0, fd = cc[i] != 0 ? cc[i] * (z - vb) : 0;
        long k = act_of[i];
        int rest;
        if (plain && k >= 0 && stepped)
            fs += force[k].s, fd += force[k].a, rest = force[k].at_rest;
        else if (plain && k < 0)
            rest = z == vb;
        else
            rest = element_forces_set(nr, i, k, stepped, u, z, vb, &fs, &fd);
        Fs[i] = fs, Fd[i] = fd;
        phase[i] = !can_stick[i] ? DP_PHASE_NONE : rest ? DP_PHASE_STICK : DP_PHASE_SLIP;
    }
    for (size_t k = 0; nr->jump && k < nr->nact_el; k++) {   /* a split graph's jumps: their own entries */
        if (!nr->jump[k])
            continue;
        size_t i = nr->act_el[k];
        double u = network_run_rel(nr->act[k].a, nr->act[k].b, nr->x), lo, hi;
        dp_graph_force(nr->act[k].S, u, &lo, &hi);
        nr->Fs[i] += stepped ? nr->force[k].s : fmin(fmax(0.0, lo), hi);
    }
    network_run_contacts_forces(nr, stepped);
}

int network_run_element_phases(struct dp_network_run *nr)
{
    if (nr->has_ep || nr->has_smooth || nr->relaxed || nr->jump || nr->nc)
        return 0;
    const dp_element *el = nr->net->el;
    const double *x = nr->x, *v = nr->v, *vbs = nr->vb;
    const long *act_of = nr->act_of;
    const unsigned char *can_stick = nr->can_stick;
    const dp_network_step_forces *force = nr->force;
    double xm = 0, vm = 0;
    for (size_t i = 0, n = nr->n; i < n; i++) {   /* network_run_state_finite's test, and the largest */
        double ax = fabs(x[i]), av = fabs(v[i]);
        if (!(ax < 1e300 && av < 1e300))
            return 0;
        xm = ax > xm ? ax : xm, vm = av > vm ? av : vm;
    }
    /* |F_s| <= |k u| + |s|, |F_d| <= |c (z - v_b)| + |a|: each part below 1e300 */
    if (!network_run_forces_bounded(nr, xm, vm))
        return 0;
    unsigned char *phase = nr->phase;
    for (size_t i = 0, nel = nr->nel; i < nel; i++) {
        long k = act_of[i];
        int rest;
        if (k >= 0) {
            if (!(fabs(force[k].s) < 1e300 && fabs(force[k].a) < 1e300))
                return 0;   /* the phases set so far are set again by the forces' pass */
            rest = force[k].at_rest;
        } else {
            rest = network_run_rel(el[i].a, el[i].b, v) == vbs[i];
        }
        phase[i] = !can_stick[i] ? DP_PHASE_NONE : rest ? DP_PHASE_STICK : DP_PHASE_SLIP;
    }
    return 1;
}

/* ---- stepping --------------------------------------------------------------------------------------- */

/* Generalized Coulomb (the rest branch, as one mass takes it): an element at rest at the step's start, or
 * one whose kinetic solution reverses, is held by its static interval [-phi1, phi1] if that holds it; one
 * that slips under the static graph has broken away and steps on its kinetic graph (phi0). Each pass
 * moves at least one element for good, so this ends after at most 2 x elements solves. */
static int static_solve(dp_run *r, double h)
{
    struct dp_network_run *nr = r->state;
    for (size_t k = 0; k < nr->nact; k++) {
        nr->held[k] = nr->static_A[k].n > 0 && nr->phase[nr->act_el[k]] == DP_PHASE_STICK;
        nr->broke[k] = 0;
    }
    for (size_t pass = 0; pass <= 2 * nr->nact; pass++) {
        for (size_t k = 0; k < nr->nact; k++)
            if (nr->static_A[k].n > 0)
                nr->act[k].A = nr->held[k] ? &nr->static_A[k] : &nr->net->el[nr->act_el[k]].damper.graph;
        dp_network_step_W_changed(nr->ws);
        int s = dp_network_step_solve(nr->ws, h, nr->rhs, nr->u, nr->v, nr->v1, nr->force, &r->sum.iterations);
        if (s != DP_OK)
            return s;
        int changed = 0;
        for (size_t k = 0; k < nr->nact; k++) {
            if (nr->static_A[k].n == 0)
                continue;
            double vb = nr->act[k].vb, z0 = network_run_rel(nr->act[k].a, nr->act[k].b, nr->v) - vb, z1 = nr->force[k].z - vb;
            if (nr->held[k] && !nr->force[k].at_rest) {
                nr->held[k] = 0, nr->broke[k] = 1, changed = 1;
            } else if (!nr->held[k] && !nr->broke[k] && z0 != 0 && z1 != 0 && (z0 > 0) != (z1 > 0)) {
                nr->held[k] = 1, changed = 1;
            }
        }
        if (!changed)
            return DP_OK;
    }
    return DP_ESOLVE;
}

/* The elongation a spring graph with a vertical end ray (a rope's length, a graph's stop) sees: a step that
 * ends held at that end puts x there to rounding only (x + h v), and an elongation past the end by that
 * much leaves the next step no feasible point; it is put back at the end. Further out it is left alone. */
static double in_domain(const dp_graph *S, double u)
{
    if (S == NULL || S->n == 0)
        return u;
    double hi = S->y[S->n - 1], lo = S->y[0];
    if (S->right[0] == 0 && u > hi && u - hi <= 1e-9 * (1 + fabs(hi)))
        return hi;
    if (S->left[0] == 0 && u < lo && lo - u <= 1e-9 * (1 + fabs(lo)))
        return lo;
    return u;
}

/* A theta-weighted spring's force at the step's start: an elastoplastic one's return mapping, else a graph
 * of finite slope's (network_smooth.c). */
static double start_force(const struct dp_network_run *nr, size_t k)
{
    size_t i = nr->act_el[k];
    return k < nr->nact_el && nr->ep_graph[i] ? nr->ep_F[i] : nr->sm_F[k];
}

/* M v into rhs and C v into tmp. A located step solves from one state many times (its held solves), so
 * the products are kept with the velocity they were formed for and copied while it is the same to the
 * bit; copies of the same numbers, so the same right side. */
static void band_products_Mv_Cv(struct dp_network_run *nr)
{
    size_t n = nr->n, bytes = n * sizeof(double);
    if (nr->Mv && nr->Mv_valid && memcmp(nr->Mv_at, nr->v, bytes) == 0) {
        memcpy(nr->rhs, nr->Mv, bytes);
        memcpy(nr->tmp, nr->Cv, bytes);
        return;
    }
    dp_band_symv(nr->M, n, nr->p, nr->v, nr->rhs);
    dp_band_symv(nr->C, n, nr->p, nr->v, nr->tmp);
    if (nr->Mv) {
        memcpy(nr->Mv, nr->rhs, bytes);
        memcpy(nr->Cv, nr->tmp, bytes);
        memcpy(nr->Mv_at, nr->v, bytes);
        nr->Mv_valid = 1;
    }
}

/* The right side of a step of length h from the current state at time t, W for h, and the elongations the
 * spring graphs see (network_step.h for the problem they define). */
void network_run_step_rhs(struct dp_network_run *nr, double t, double h)
{
    size_t n = nr->n, p = nr->p;
    double th = nr->theta;
    if (h != nr->h_W)
        network_run_build_W(nr, h);
    band_products_Mv_Cv(nr);
    double *rhs = nr->rhs, *tmp = nr->tmp, *v1 = nr->v1, *u = nr->u;
    const double *x = nr->x, *v = nr->v;
    for (size_t i = 0; i < n; i++) {
        rhs[i] -= h * (1 - th) * tmp[i];
        v1[i] = x[i] + h * th * (1 - th) * v[i];
    }
    dp_band_symv(nr->K, n, p, v1, tmp);
    for (size_t i = 0; i < n; i++)
        rhs[i] -= h * tmp[i];
    for (size_t i = 0; i < nr->net->nforce; i++)
        rhs[nr->net->force[i].node] += h * dp_forcing_eval(&nr->net->force[i].f, t + th * h);
    for (size_t i = 0; nr->belt_viscous && i < nr->nel; i++) {   /* without one every term below is +-0 */
        const dp_element *e = &nr->net->el[i];
        double g = e->has_damper ? h * nr->c[i] * e->damper.belt_velocity : 0;
        if (g != 0 && e->b >= 0)
            rhs[e->b] += g;
        if (g != 0 && e->a >= 0)
            rhs[e->a] -= g;
    }
    const dp_network_step_element *act = nr->act;
    for (size_t k = 0, na = nr->nact; k < na; k++)
        u[k] = in_domain(act[k].S, network_run_rel(act[k].a, act[k].b, x));
    if (!nr->has_ep && !nr->has_smooth && !nr->jump)
        return;
    /* theta-weighted spring graphs (elastoplastic, of finite slope, a split graph's jumps): S at
     * u+ = u + h (1-theta) u' + h theta z+, and, but for a jump (its force whole at u+), the force's
     * (1-theta) part known */
    for (size_t k = 0; k < nr->nact; k++) {
        const dp_network_step_element *e = &nr->act[k];
        if (e->ep_theta == 0)
            continue;
        nr->u[k] += h * (1 - th) * network_run_rel(e->a, e->b, nr->v);
        if (e->s_whole)
            continue;
        double g = h * (1 - th) * start_force(nr, k);
        if (e->b >= 0)
            nr->rhs[e->b] -= g;
        if (e->a >= 0)
            nr->rhs[e->a] += g;
    }
}

void network_run_block_rows(const struct dp_network_run *nr, double t, double h, size_t lo, size_t hi, double *Wl,
                            double *rl)
{
    size_t n = nr->n;
    const double *x = nr->x, *v = nr->v, *K = nr->K, th = nr->theta;
    for (size_t r = lo; r <= hi + 1; r++) {   /* row r - 1 */
        double *w = Wl + 2 * (r - lo);
        for (size_t d = 0; d < 2; d++)
            w[d] = r == 0 ? 0 : W_entry(nr, 2 * (r - 1) + d, h);
    }
    double a1 = h * (1 - th), b1 = h * th * (1 - th);
    for (size_t i = lo; i <= hi; i++) {
        double v1m = i > 0 ? x[i - 1] + b1 * v[i - 1] : 0, v10 = x[i] + b1 * v[i];
        double v1p = i + 1 < n ? x[i + 1] + b1 * v[i + 1] : 0, kv = K[2 * i] * v10;
        if (i > 0)
            kv += K[2 * (i - 1) + 1] * v1m;
        if (i + 1 < n)
            kv += K[2 * i + 1] * v1p;
        double r = dp_band_row(nr->M + 2 * i, 1, v, i, n);
        r -= a1 * dp_band_row(nr->C + 2 * i, 1, v, i, n);
        r -= h * kv;
        rl[i - lo] = r;
    }
    for (size_t i = 0; i < nr->net->nforce; i++) {
        size_t node = nr->net->force[i].node;
        if (node >= lo && node <= hi)
            rl[node - lo] += h * dp_forcing_eval(&nr->net->force[i].f, t + th * h);
    }
}

/* x+ = x + h ((1-theta) v + theta v+), v = v+. */
void network_run_take_velocity(struct dp_network_run *nr, double h)
{
    double *x = nr->x, *v = nr->v, th = nr->theta;
    const double *v1 = nr->v1;
    for (size_t i = 0, n = nr->n; i < n; i++) {
        x[i] += h * ((1 - th) * v[i] + th * v1[i]);
        v[i] = v1[i];
    }
    network_run_ep_update(nr);
    network_run_smooth_update(nr);
}

/* The exact solution of a step of length h from time t into v1 and the forces; the state is not moved. */
int network_run_net_step_keep(dp_run *r, double t, double h)
{
    struct dp_network_run *nr = r->state;
    network_run_step_rhs(nr, t, h);
    int s = nr->has_static ? static_solve(r, h)
                           : dp_network_step_solve(nr->ws, h, nr->rhs, nr->u, nr->v, nr->v1, nr->force, &r->sum.iterations);
    nr->solved = s == DP_OK;
    return s;
}

/* One theta-step of length h from time t, solved exactly; contacts armed by Moreau-Jean's rule. */
int network_run_net_step(dp_run *r, double t, double h)
{
    if (network_run_of(r)->nc)
        network_run_contacts_arm_mj(network_run_of(r), h);
    int s = network_run_net_step_keep(r, t, h);
    if (s == DP_OK)
        network_run_take_velocity(network_run_of(r), h);
    if (s == DP_OK && network_run_of(r)->nc)
        network_run_contacts_mj_events(r, t, h);
    return s;
}
