/* src/core/solvers/network/network_contact_lean.c - a network of one node whose one element is a rigid
 * contact (Newton restitution) with at most a linear spring and a linear damper beside it: the bouncing ball.
 * Stepped with Moreau-Jean's rule without located events ("events": "none"), so that its step is
 * the general network step (network_stepping.c, network_contact.c, network/network_step.c) written out for
 * n = 1: the same floating-point operations in the same order, so the same answers bit for bit, without the
 * band matrices, the forest and the active-set bookkeeping that cost a general step some 250 ns for one node.
 *
 * What the general step does for this network, and what is reproduced here:
 *  - Moreau-Jean's arming (Moreau 1988, Jean 1999; Siconos' MoreauJeanOSI): the contact is armed for the
 *    step where g + h/2 g' <= 0, its cone at v_c = -e g' (network_run_contacts_arm_mj);
 *  - the right side M v - h (1-theta) C v - h K (x + h theta (1-theta) v) + h f(t + theta h) + h c v_b b;
 *  - the convex step problem with one element, free on the line (not armed), or the cone at v_c: the
 *    primal-dual active-set pass of network_step.c from the previous velocity, where the element is either
 *    free on a piece of slope 0 and force 0 (v = rhs / L / L, L = sqrt(W): GSL's band Cholesky of a 1 x 1
 *    band and its two triangular solves) or fixed at the cone's vertex (v = v_c through the forest's
 *    potentials, its multiplier from the residual), with the same rounding tolerance on the multiplier;
 *  - x += h ((1-theta) v + theta v+), the impact event, the element's forces.
 * Every +0 or -0 the general path adds to a number (which turns -0 into +0) is kept. Anything outside
 * these two assignments (a NaN, a pass that does not settle within the general path's twelve updates, a
 * factor that is not positive) is handed to the general solve itself.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "solvers/network/network_run.h"

/* The element's state in the step's active-set pass: free on the piece above lo (the whole line when lo is
 * -inf), or fixed at the cone's vertex z = fz with multiplier lam. */
typedef struct lean_state {
    int fixed;
    double lo;          /* FREE: the piece's lower end */
    double zref;        /* FREE: where the piece was taken */
    double fz;          /* FIXED: the vertex */
    double lam, lam_err;
} lean_state;

/* The start assignment at the previous velocity (assign_start, start_inside_piece, start_lawless); 0 when
 * z is not finite (the general path decides). */
static int lean_start(const dp_network_step_element *e, double z, lean_state *s)
{
    if (!isfinite(z))
        return 0;
    if (e->A == NULL) {
        *s = (lean_state){ .fixed = 0, .lo = -INFINITY, .zref = z };
        return 1;
    }
    double y = z - e->vb;
    if (y > 0)          /* inside the cone's right piece: free above its vertex */
        *s = (lean_state){ .fixed = 0, .lo = 0 + e->vb, .zref = z };
    else if (y == 0)    /* on the vertex */
        *s = (lean_state){ .fixed = 1, .fz = z };
    else                /* beyond the vertical ray: fixed at the domain's end */
        *s = (lean_state){ .fixed = 1, .fz = 0 + e->vb };
    return 1;
}

/* The minimizer of the assignment (effective_rhs, the forest's potentials, solve_assignment); 0 when the
 * factor is not positive. */
static int lean_solve(const dp_network_step_element *e, const lean_state *s, double h, double rhs, double W,
                      double *vs, double *rhs_eff)
{
    if (s->fixed) {
        *rhs_eff = rhs;
        double pot = e->b >= 0 ? (s->fz + 0) - 0 : (0 - 0) - s->fz;   /* join: the ground stays the root */
        double c = (0 + pot) - 0;                                      /* find, index_forest */
        *vs = 0 + c;
        return 1;
    }
    double g = h * (0 - 0 * s->zref);   /* h (lam0 - slope zref), both 0 on these pieces */
    double r = rhs;
    if (e->a >= 0)
        r += g;
    if (e->b >= 0)
        r -= g;
    *rhs_eff = r;
    double R = 0 + W;                   /* the reduced matrix of one free node: H = W */
    if (!(R > 0))
        return 0;
    double L = sqrt(R), c = 0, res = W * c;
    double y = 0 + (r - res);
    y = y / L;                          /* L z = b, then L^T x = z */
    y = y / L;
    *vs = y + c;
    return 1;
}

/* multipliers() and bulk_update() for the one element: 1 when the assignment changed, 0 when it holds, -1
 * for a multiplier that is not a number (the general path decides). */
static int lean_update(const dp_network_step_element *e, lean_state *s, double h, double rhs_eff, double W,
                       double vs)
{
    if (s->fixed) {
        double Hv = W * vs;
        double res_err = 8 * DBL_EPSILON * (fabs(rhs_eff) + fabs(Hv)), res = rhs_eff - Hv;
        double sign = e->b == 0 ? 1 : -1;
        s->lam = res / (h * sign);
        s->lam_err = res_err / h;
        if (isnan(s->lam))
            return -1;
        double lam = s->lam, tol = 1e-12 * (1 + fabs(lam) + 0 + 0) + s->lam_err;
        if (lam >= -INFINITY - tol && lam <= 0 + tol)
            return 0;
        /* released onto the cone's right piece from its vertex */
        *s = (lean_state){ .fixed = 0, .lo = s->fz, .zref = s->fz };
        return 1;
    }
    double z = network_run_rel(e->a, e->b, &vs);
    if (!(z < s->lo))
        return 0;
    *s = (lean_state){ .fixed = 1, .fz = s->lo };   /* follow: fixed at the vertex below */
    return 1;
}

/* The element's forces as report() gives them. */
static void lean_report(const dp_network_step_element *e, const lean_state *s, double v, dp_network_step_forces *f)
{
    double z = network_run_rel(e->a, e->b, &v);
    if (s->fixed) {
        double lambda = s->lam;
        lambda += 0 + 0 * (s->fz - 0);
        *f = (dp_network_step_forces){ .z = e->vb, .lambda = lambda, .a = lambda - 0, .s = 0, .at_rest = 1 };
    } else {
        double lambda = 0 + 0 * (z - s->zref);
        lambda += 0 + 0 * (z - 0);
        *f = (dp_network_step_forces){ .z = z, .lambda = lambda, .a = lambda - 0, .s = 0, .at_rest = 0 };
    }
}

/* dp_network_step_solve for the one element: v1 and the force; DP_ECANCEL when the poll said stop, 1 when
 * the general solve must decide. */
static int lean_step_solve(dp_run *r, double h, double rhs)
{
    struct dp_network_run *nr = r->state;
    const dp_network_step_element *e = &nr->act[0];
    double W = dp_network_step_W(nr->ws)[0], vs = 0, rhs_eff = 0;
    lean_state s;
    if (!lean_start(e, network_run_rel(e->a, e->b, nr->v), &s))
        return 1;
    unsigned long long iters = 0;
    for (int it = 0; it < 12; it++) {
        iters++;
        if (!lean_solve(e, &s, h, rhs, W, &vs, &rhs_eff))
            return 1;
        /* the solve's work as polled_stop counts it: W's band and the element, and R's factor at every free
         * solve (the general workspace counts it only when it factors anew, so the stop hook may be asked a
         * few steps apart from there; what is computed and recorded is the same) */
        if (network_run_poll_lean(r, nr, 2 + !s.fixed))
            return DP_ECANCEL;
        int changed = lean_update(e, &s, h, rhs_eff, W, vs);
        if (changed < 0)
            return 1;
        if (!changed) {
            r->sum.iterations += iters;
            nr->v1[0] = vs;
            lean_report(e, &s, vs, &nr->force[0]);
            return DP_OK;
        }
    }
    return 1;
}

/* The run's constants, read once per block: the linear parts, the contact's law, the element's direction. */
typedef struct lean_consts {
    double M, C, K, k, c, theta, distance, restitution, belt;
    int has_damper;
    int up;             /* the element is [ground, 0] (u = x), else [0, ground] (u = -x) */
} lean_consts;

static void lean_consts_of(const struct dp_network_run *nr, lean_consts *k)
{
    const dp_element *e = &nr->net->el[0];
    *k = (lean_consts){ .M = nr->M[0], .C = nr->C[0], .K = nr->K[0], .k = nr->k[0], .c = nr->c[0],
                        .theta = nr->theta, .distance = e->contact.distance,
                        .restitution = e->contact.restitution, .has_damper = e->has_damper,
                        .belt = e->has_damper ? e->damper.belt_velocity : 0, .up = e->b == 0 };
}

/* network_run_rel for the element: x_b - x_a with the ground at 0, operation for operation. */
static inline double lean_rel(const lean_consts *k, double x)
{
    return k->up ? x - 0 : 0 - x;
}

/* Moreau-Jean's arming (network_run_contacts_arm_mj) for the one contact. */
static void lean_arm(struct dp_network_run *nr, const lean_consts *k, double h)
{
    dp_network_step_element *a = &nr->act[0];
    double g = lean_rel(k, nr->x[0]) - k->distance, gd = lean_rel(k, nr->v[0]);
    if (fabs(gd) < DBL_MIN)
        gd = 0;
    int was = nr->ct_on[0], on = g + 0.5 * h * gd <= 0;
    int changed = (a->A != NULL) != on;
    a->A = on ? &nr->cone : NULL;
    a->vb = on ? -k->restitution * gd : 0;
    nr->ct_on[0] = (unsigned char)on;
    nr->ct_pre[0] = was ? 0 : gd;
    if (changed)
        dp_network_step_W_changed(nr->ws);
}

/* The right side of the step (network_run_step_rhs for one node); the elongation into u. */
static double lean_rhs(struct dp_network_run *nr, const lean_consts *k, double t, double h)
{
    double th = k->theta, x = nr->x[0], v = nr->v[0];
    if (h != nr->h_W)
        network_run_build_W(nr, h);
    double rhs = k->M * v, tmp = k->C * v;
    rhs -= h * (1 - th) * tmp;
    double xs = x + h * th * (1 - th) * v;
    tmp = k->K * xs;
    rhs -= h * tmp;
    for (size_t i = 0; i < nr->net->nforce; i++)
        rhs += h * dp_forcing_eval(&nr->net->force[i].f, t + th * h);
    double g = k->has_damper ? h * k->c * k->belt : 0;
    if (g != 0 && k->up)
        rhs += g;
    if (g != 0 && !k->up)
        rhs -= g;
    nr->u[0] = lean_rel(k, x);
    return rhs;
}

/* One Moreau-Jean step (network_run_net_step), the element's forces after it (network_run_element_forces). */
static int lean_step(dp_run *r, const lean_consts *k, double t, double h)
{
    struct dp_network_run *nr = r->state;
    lean_arm(nr, k, h);
    double rhs = lean_rhs(nr, k, t, h);
    int s = lean_step_solve(r, h, rhs);
    if (s == 1) {   /* the general solve decides */
        nr->rhs[0] = rhs;
        s = dp_network_step_solve(nr->ws, h, nr->rhs, nr->u, nr->v, nr->v1, nr->force, &r->sum.iterations);
    }
    nr->solved = s == DP_OK;
    if (s != DP_OK)
        return s;
    double th = k->theta, v1 = nr->v1[0];
    double x = nr->x[0] += h * ((1 - th) * nr->v[0] + th * v1);
    nr->v[0] = v1;
    const dp_network_step_forces *f = &nr->force[0];
    int on = nr->ct_on[0];
    if (on && nr->ct_pre[0] < 0 && f->lambda < 0) {
        network_run_impact_event(r, t + h, 0, nr->ct_pre[0], f->z, -h * f->lambda);
        nr->ct_last[0] = nr->ct_before[0] = -INFINITY;
    }
    double u = lean_rel(k, x), z = lean_rel(k, v1);
    nr->Fs[0] = k->k != 0 ? k->k * u : 0;
    nr->Fd[0] = k->c != 0 ? k->c * (z - k->belt) : 0;
    nr->phase[0] = DP_PHASE_NONE;
    nr->Fn[0] = on ? f->lambda : 0;
    return DP_OK;
}

/* network_run_advance's loop with the lean step. */
static int lean_advance(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    if (network_run_reserve_rows(r) != DP_OK)
        return DP_ENOMEM;
    network_run_flush(r);
    lean_consts k;
    lean_consts_of(nr, &k);
    int due;
    while (network_run_step_due(r, &due)) {
        double h = dp_run_step_length(r), t = r->cur.t;
        nr->impacts_step = 0;
        nr->phase_prev[0] = nr->phase[0];
        int s = lean_step(r, &k, t, h);
        if (s != DP_OK && network_run_cancelled(r))
            return r->status;
        if (s != DP_OK)
            return dp_run_fail(r, s, "the implicit step at t = %.17g has no solution (%s)", t, dp_strerror(s));
        /* network_run_state_finite for the one node and element */
        int finite = fabs(nr->x[0]) < 1e300 && fabs(nr->v[0]) < 1e300 && isfinite(nr->Fs[0]) && isfinite(nr->Fd[0]);
        if ((s = network_run_step_taken(r, finite)) != DP_OK)
            return s;
    }
    return due;
}

/* The network run's own set-up, initial probe and first row (network_run.c). */
static int lean_init(dp_run *r)
{
    return dp_run_network.init(r);
}

const dp_run_type dp_run_network_contact_lean = {
    .name = "stick-slip", .variant = "exact", .events_mode = network_run_events_mode, .check = dp_rules_network,
    .init = lean_init, .advance = lean_advance, .pending = network_run_pending, .free = network_run_free,
};
