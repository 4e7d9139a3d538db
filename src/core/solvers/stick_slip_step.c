/* src/core/solvers/stick_slip_step.c - one step of the stick-slip theta-method (docs/mathematics.md §4), with
 * no events: the closed form (Moreau's soft threshold) and the general inclusion. Shared by the stepper
 * (stick_slip.c) and event location (event_location.c), which splits a step at its phase changes: both call
 * down into this file, so neither calls the other back. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "solvers/stick_slip_step.h"

/* ---- the closed form ------------------------------------------------------------------------------ */

/* The affine map (v, x, F) -> u of a step of length h, folded once per step length:
 * u = [m v - h(1-theta) c v + h c v_b - h k (x + h theta (1-theta) v) + h F] / W - v_b. */
void dp_ss_coef_init(const dp_ss_law *L, double h, dp_ss_coef *c)
{
    double th = L->theta;
    c->W = L->m + h * th * L->c + h * h * th * th * L->k;
    double iW = 1 / c->W;
    c->cv = (L->m - h * (1 - th) * L->c - h * h * L->k * th * (1 - th)) * iW;
    c->cx = -h * L->k * iW;
    c->cf = h * iW;
    c->c0 = h * L->c * L->vb * iW - L->vb;
    c->thr = h * L->tau * iW;
    c->thr_s = h * L->tau_s * iW;
}

/* Advances s by a step of length h whose free velocity u and coefficients c are known, with the Moreau
 * rule; returns the friction's mean force over the step. */
double dp_ss_moreau_from(const dp_ss_law *L, step_state *s, double h, double u, const dp_ss_coef *c)
{
    double dir = sgn(s->v - L->vb), w, r;
    if (dir != 0 && u * dir > c->thr) {
        w = u - c->thr * dir;               /* slip goes on */
        r = L->tau * dir;
    } else if (L->can_stick && fabs(u) <= c->thr_s) {
        w = 0;                              /* stick: exactly at the belt's speed */
        r = u * c->W / h;
    } else {
        w = u - c->thr * sgn(u);            /* slip from rest or reversal */
        r = L->tau * sgn(u);
    }
    double v1 = L->vb + w;
    s->x += h * ((1 - L->theta) * s->v + L->theta * v1);
    s->v = v1;
    s->t += h;
    s->phase = !L->can_stick ? DP_PHASE_NONE : w == 0 ? DP_PHASE_STICK : DP_PHASE_SLIP;
    return r;
}

double dp_ss_moreau(const dp_ss_law *L, step_state *s, double h)
{
    dp_ss_coef c;
    double u = free_velocity(L, s->t, h, s->x, s->v, &c);
    return dp_ss_moreau_from(L, s, h, u, &c);
}

/* ---- the general inclusion ------------------------------------------------------------------------- */

/* The inclusion of a step of length h from s (docs/mathematics.md §4, "Exact form of the step"). */
dp_inclusion dp_ss_step_inclusion(const dp_ss_law *L, const step_state *s, double h)
{
    double th = L->theta;
    return (dp_inclusion){
        .W = L->m + h * th * L->c + h * h * th * th * L->k,
        .b = L->m * s->v - h * (1 - th) * L->c * s->v + h * L->c * L->vb
           - h * L->k * (s->x + h * th * (1 - th) * s->v) + h * dp_forcing_eval(L->F, s->t + th * h),
        .h = h, .A = L->A, .a_shift = L->vb, .S = L->S, .s_x = s->x, .s_h = h,
        .gamma = L->gamma, .g_theta = th, .g_shift = (1 - th) * s->v - L->vb, .hint = L->kink_hint,
    };
}

dp_inclusion dp_ss_run_inclusion(const dp_run *r, const step_state *s, double h)
{
    double th = r->law.theta;
    dp_inclusion p = dp_ss_step_inclusion(&r->law, s, h);
    if (r->ep) {   /* theta-weighted: the step graph is theta S (dp_elastoplastic_graph), its argument x+ */
        p.s_x = s->x + h * (1 - th) * s->v, p.s_h = h * th;
        p.b -= h * (1 - th) * r->ep_F;
    }
    return p;
}

/* One step through dp_inclusion_solve; returns DP_OK or DP_ESOLVE. */
int dp_ss_inclusion_step(dp_run *r, step_state *s, double h, double *fc, double *fs)
{
    const dp_ss_law *L = &r->law;
    double th = L->theta;
    dp_inclusion p = dp_ss_run_inclusion(r, s, h);
    double w, a, sp;
    if (dp_inclusion_solve(&p, &w, &a, &sp, &r->sum.iterations) != DP_OK)
        return DP_ESOLVE;
    double dir = sgn(s->v - L->vb);
    /* Motion branch: where rest solves the step but a motion in the direction of the free push does too
     * (non-Lipschitz gamma), follow the motion. */
    double push = sgn(p.b - p.W * L->vb);
    if (L->motion && w == L->vb && dir == 0 && push != 0)
        dp_inclusion_solve_side(&p, push, &w, &a, &sp, &r->sum.iterations);
    /* Generalized Coulomb (rest branch): where the motion stops or would start, the static interval
     * [-phi1, phi1] decides whether the mass stays at the belt's speed. */
    if (L->tau_s > L->tau && w != L->vb && (dir == 0 || sgn(w - L->vb) != dir)
        && dp_inclusion_holds_with(&p, L->vb, -L->tau_s, L->tau_s)) {
        double R = (p.b - p.W * L->vb + h * dp_relaxation_eval(L->gamma, th * L->vb + p.g_shift)) / h, lo, hi;
        sp = 0;
        if (L->S) {
            dp_graph_force(L->S, s->x + h * L->vb, &lo, &hi);
            sp = lo;
        }
        w = L->vb;
        a = R - sp;
    }
    s->x += h * ((1 - th) * s->v + th * w);
    s->v = w;
    s->t += h;
    s->phase = !L->can_stick ? DP_PHASE_NONE : w == L->vb ? DP_PHASE_STICK : DP_PHASE_SLIP;
    *fc = a;
    *fs = sp;
    return DP_OK;
}

/* ---- a step that leaves the finite numbers ---------------------------------------------------------- */

/* The number of v and *most farther from 1 in decades (0 counts as 1): the document's scale. */
static void extreme(double v, double *most)
{
    double d = v == 0 || !isfinite(v) ? 0 : fabs(log10(fabs(v)));
    double m = *most == 0 ? 0 : fabs(log10(fabs(*most)));
    if (d > m)
        *most = v;
}

static void forcing_extreme(const dp_forcing *f, double *most)
{
    extreme(f->value, most), extreme(f->amplitude, most), extreme(f->omega, most), extreme(f->phase, most);
    for (size_t i = 0; i < f->n; i++)
        extreme(f->t[i], most), extreme(f->F[i], most);
    for (size_t i = 0; i < f->nterms; i++)
        forcing_extreme(&f->terms[i], most);
}

static void graph_extreme(const dp_graph *g, double *most)
{
    for (size_t i = 0; i < g->n; i++)
        extreme(g->y[i], most), extreme(g->f[i], most);
}

double dp_one_mass_extreme(const dp_spec *s)
{
    const dp_model *m = &s->model;
    const dp_spring *sp = &m->spring;
    const dp_damper *d = &m->damper;
    const dp_relaxation *r = &d->relaxation;
    const double v[] = { s->x0, s->v0, m->mass, sp->k, sp->length, sp->yield, sp->offset, d->c, d->phi0, d->phi1,
                         d->tau, d->belt_velocity, r->a, r->b, r->L, r->N, s->solver.dt, s->solver.t_end };
    double most = 1;
    forcing_extreme(&m->forcing, &most);
    graph_extreme(&sp->graph, &most);
    graph_extreme(&d->graph, &most);
    for (size_t i = 0; i < sizeof v / sizeof *v; i++)
        extreme(v[i], &most);
    return most;
}

int dp_one_mass_nonfinite(dp_run *r, const char *diverged, double t, double x, double v)
{
    char at[96] = "";
    double most = dp_one_mass_extreme(&r->spec);
    if (!(fabs(log10(fabs(most))) >= DP_ONE_MASS_EXTREME_DECADES))
        return dp_run_fail(r, DP_ENONFINITE, "%s", diverged);
    if (isfinite(x) && isfinite(v))
        snprintf(at, sizeof at, " (|x| = %.3g, |v| = %.3g before it)", fabs(x), fabs(v));
    return dp_run_fail(r, DP_ESOLVE, "the step's quantities overflow at t = %.17g%s: the document holds %.3g, "
                       "whose products with its other numbers leave double precision", t, at, most);
}
