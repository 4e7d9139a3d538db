/* src/core/right_hand/right_hand.c - the acceleration problem of friction with motion-dependent normal force (Matrosov & Finogenko 1995
 * (1.1)/(1.3)) solved exactly by enumeration, and the paper's conditions (1.2), (2.3), (6.2)-(6.4).
 *
 * For one mode combination (each friction coordinate stuck, or sliding/starting with sign sigma) the
 * unknowns are q'' on the free coordinates F and the friction magnitudes lambda_k >= 0 of the sliding ones:
 *     A_FF q''_F = b_F - sum_k sigma_k lambda_k e_k,   so  q'' = u + sum_k lambda_k z_k  (affine in lambda),
 *     lambda_k = f_k eps_k (W_k q'' + w_k)     for an affine N_k, eps_k = sgn N_k enumerated (linear),
 *     lambda_p = f_p ||W_p q'' + w_p||          for the hinge's N2: squared, a quadratic in lambda_p.
 * Each root is kept if lambda >= 0 and, where the coordinate rests, the stick force lies in the cone
 * (|Q_s| <= f_s |N_s|) or the start goes the way its friction opposes (sigma q_s'' > 0). Every combination
 * is tried, so no solution and several solutions are both seen: Painlevé's inconsistency and
 * indeterminacy. The paper's contraction (Section 2) proves uniqueness where (2.3) holds; the enumeration
 * needs no such hypothesis, and (2.3)'s margin is reported beside it (dp_right_hand_conditions_at).
 */
#include <math.h>
#include <string.h>

#include "dashpot/right_hand.h"

/* Relative tolerances: rounding of a 2x2 solve of well-scaled data is ~1e-15; the cone and start tests
 * accept 1e-10 of the force scale so that a state exactly on the cone (the paper's set N1) counts as
 * stuck, and two candidates closer than 1e-9 of their size are one solution (a stick and a start that
 * meet on the cone boundary). */
#define TOL_FORCE 1e-10
#define TOL_SAME 1e-9
#define TOL_DET 1e-13

typedef struct cand {
    double qdd[2], lam[2];
} cand;

typedef struct prob {
    const dp_right_hand_frame *fr;
    const double *qd;
    const dp_right_hand_mode *mode;
    int check_rest;
    double u[2], z[2][2];   /* q'' = u + sum_k lam_k z[k] */
    double fscale;
    dp_right_hand_result *res;
} prob;

static int sigma_of(dp_right_hand_mode m)
{
    return m == DP_RIGHT_HAND_SLIP_POS ? 1 : m == DP_RIGHT_HAND_SLIP_NEG ? -1 : 0;
}

/* The affine normal force vector of coordinate s at q'' (d = 1 or 2 entries). */
static void normal_vec(const dp_right_hand_frame *fr, int s, const double qdd[2], double v[2])
{
    for (int r = 0; r < fr->ndim[s]; r++)
        v[r] = fr->W[s][r][0] * qdd[0] + fr->W[s][r][1] * qdd[1] + fr->w[s][r];
}

/* N_s as reported: signed for an affine reaction, the length for a vector one. */
static double normal_of(const dp_right_hand_frame *fr, int s, const double qdd[2])
{
    double v[2];
    normal_vec(fr, s, qdd, v);
    return fr->ndim[s] == 1 ? v[0] : hypot(v[0], v[1]);
}

/* u and z_k: A_FF x = rhs on the free (non-stuck) coordinates, zero on the stuck ones. */
static void free_solve(const dp_right_hand_frame *fr, const dp_right_hand_mode *mode, const double rhs[2], double x[2])
{
    int f0 = mode[0] != DP_RIGHT_HAND_STICK, f1 = mode[1] != DP_RIGHT_HAND_STICK;
    x[0] = x[1] = 0;
    if (f0 && f1) {
        double det = fr->A[0][0] * fr->A[1][1] - fr->A[0][1] * fr->A[1][0]; /* A is positive definite */
        x[0] = (fr->A[1][1] * rhs[0] - fr->A[0][1] * rhs[1]) / det;
        x[1] = (fr->A[0][0] * rhs[1] - fr->A[1][0] * rhs[0]) / det;
    } else if (f0) {
        x[0] = rhs[0] / fr->A[0][0];
    } else if (f1) {
        x[1] = rhs[1] / fr->A[1][1];
    }
}

static int same(const double a[2], const double b[2])
{
    double sc = 1 + fmax(fmax(fabs(a[0]), fabs(a[1])), fmax(fabs(b[0]), fabs(b[1])));
    return fabs(a[0] - b[0]) <= TOL_SAME * sc && fabs(a[1] - b[1]) <= TOL_SAME * sc;
}

/* Checks a candidate of the current mode and records it when it is a new solution. */
static void accept(prob *p, const cand *c)
{
    const dp_right_hand_frame *fr = p->fr;
    double tol = TOL_FORCE * p->fscale;
    dp_right_hand_sol s = { .qdd = { c->qdd[0], c->qdd[1] } };
    for (int k = 0; k < 2; k++) {
        s.mode[k] = p->mode[k];
        s.N[k] = normal_of(fr, k, c->qdd); /* the rod's second is identically 0 */
        if (fr->unilateral[k] && s.N[k] < -tol)
            return;                          /* a floor cannot pull */
        int sg = sigma_of(p->mode[k]);
        if (sg != 0) {
            if (c->lam[k] < -tol)
                return;                      /* eps_k disagrees with the sign of N_k */
            s.Q[k] = -sg * fmax(c->lam[k], 0);
            if (p->qd[k] == 0 && !(sg * c->qdd[k] > 0))
                return;                      /* a start against its own friction (in a phase too: its first
                                              * instant, where the velocity is still 0) */
        } else if (p->mode[k] == DP_RIGHT_HAND_STICK) {
            s.Q[k] = fr->A[k][0] * c->qdd[0] + fr->A[k][1] * c->qdd[1] - fr->b[k];
            if (p->check_rest && fabs(s.Q[k]) > fr->f[k] * fabs(s.N[k]) + tol)
                return;                      /* the force needed to hold is outside the cone */
        }
    }
    dp_right_hand_result *r = p->res;
    for (int i = 0; i < r->n && i < DP_RIGHT_HAND_MAX_SOL; i++)
        if (same(r->sol[i].qdd, s.qdd))
            return;
    if (r->n < DP_RIGHT_HAND_MAX_SOL)
        r->sol[r->n] = s;
    r->n++;
}

static void at_lambda(const prob *p, const double lam[2], cand *c)
{
    c->lam[0] = lam[0], c->lam[1] = lam[1];
    for (int i = 0; i < 2; i++)
        c->qdd[i] = p->u[i] + lam[0] * p->z[0][i] + lam[1] * p->z[1][i];
}

/* All sliding reactions affine: lambda_k - f_k eps_k W_k.(sum_j lambda_j z_j) = f_k eps_k (W_k.u + w_k). */
static void solve_linear(prob *p, const int *K, int nk, const int eps[2])
{
    const dp_right_hand_frame *fr = p->fr;
    double G[2][2] = { { 1, 0 }, { 0, 1 } }, h[2] = { 0, 0 }, lam[2] = { 0, 0 };
    for (int a = 0; a < nk; a++) {
        int k = K[a];
        double fe = fr->f[k] * eps[a];
        for (int b = 0; b < nk; b++)
            G[a][b] -= fe * (fr->W[k][0][0] * p->z[K[b]][0] + fr->W[k][0][1] * p->z[K[b]][1]);
        h[a] = fe * (fr->W[k][0][0] * p->u[0] + fr->W[k][0][1] * p->u[1] + fr->w[k][0]);
    }
    double hs = 1 + fabs(h[0]) + fabs(h[1]);
    if (nk == 1) {
        if (fabs(G[0][0]) <= TOL_DET) {
            if (fabs(h[0]) <= TOL_FORCE * p->fscale * fr->f[K[0]] + TOL_DET * hs)
                p->res->continuum = 1;
            return;
        }
        lam[K[0]] = h[0] / G[0][0];
    } else if (nk == 2) {
        double det = G[0][0] * G[1][1] - G[0][1] * G[1][0];
        if (fabs(det) <= TOL_DET) {
            p->res->continuum |= fabs(h[0]) + fabs(h[1]) <= TOL_DET * hs;
            return;
        }
        lam[K[0]] = (G[1][1] * h[0] - G[0][1] * h[1]) / det;
        lam[K[1]] = (G[0][0] * h[1] - G[1][0] * h[0]) / det;
    }
    cand c;
    at_lambda(p, lam, &c);
    accept(p, &c);
}

/* The hinge's reaction sliding: q'' = u0 + lam_p d0 (+ lam_k from its affine relation lam_k = a0 + a1 lam_p),
 * lam_p = f ||W (u0 + lam_p d0) + w||, squared: (1 - f^2|D|^2) lam^2 - 2 f^2 (a.D) lam - f^2 |a|^2 = 0. */
static void solve_quadratic(prob *p, int pc, int k, double a0, double a1)
{
    const dp_right_hand_frame *fr = p->fr;
    double u0[2], d0[2], a[2], D[2], f = fr->f[pc];
    for (int i = 0; i < 2; i++) {
        u0[i] = p->u[i] + (k >= 0 ? a0 * p->z[k][i] : 0);
        d0[i] = p->z[pc][i] + (k >= 0 ? a1 * p->z[k][i] : 0);
    }
    for (int r = 0; r < 2; r++) {
        a[r] = fr->W[pc][r][0] * u0[0] + fr->W[pc][r][1] * u0[1] + fr->w[pc][r];
        D[r] = fr->W[pc][r][0] * d0[0] + fr->W[pc][r][1] * d0[1];
    }
    double q2 = 1 - f * f * (D[0] * D[0] + D[1] * D[1]), q1 = -2 * f * f * (a[0] * D[0] + a[1] * D[1]);
    double q0 = -f * f * (a[0] * a[0] + a[1] * a[1]);
    double roots[2];
    int nr = 0;
    double sc = fabs(q1) + fabs(q0) + 1;
    if (fabs(q2) <= TOL_DET) {
        if (fabs(q1) > TOL_DET * sc)
            roots[nr++] = -q0 / q1;
        else if (fabs(q0) <= TOL_DET * sc)
            p->res->continuum = 1;
    } else {
        double disc = q1 * q1 - 4 * q2 * q0;
        if (disc < 0 && disc > -1e-14 * (q1 * q1 + fabs(4 * q2 * q0)))
            disc = 0;
        if (disc >= 0) {
            double t = -0.5 * (q1 + copysign(sqrt(disc), q1));
            roots[nr++] = t / q2;
            if (t != 0)
                roots[nr++] = q0 / t;
        }
    }
    for (int i = 0; i < nr; i++) {
        double lam[2] = { 0, 0 };
        lam[pc] = roots[i];
        if (k >= 0)
            lam[k] = a0 + a1 * roots[i];
        cand c;
        at_lambda(p, lam, &c);
        accept(p, &c);
    }
}

/* One mode combination with one choice of signs eps for its affine sliding reactions. */
static void solve_signs(prob *p, const int *K, int nk, const int eps[2])
{
    const dp_right_hand_frame *fr = p->fr;
    int pc = -1, lin[2], nl = 0, le[2];
    for (int a = 0; a < nk; a++) {
        if (fr->ndim[K[a]] == 2)
            pc = K[a];
        else
            le[nl] = eps[a], lin[nl++] = K[a];
    }
    if (pc < 0) {
        solve_linear(p, lin, nl, le);
        return;
    }
    if (nl == 0) {
        solve_quadratic(p, pc, -1, 0, 0);
        return;
    }
    /* lam_k (1 - f e W_k.z_k) - f e (W_k.z_p) lam_p = f e (W_k.u + w_k): lam_k affine in lam_p */
    int k = lin[0];
    double fe = fr->f[k] * le[0];
    double g = 1 - fe * (fr->W[k][0][0] * p->z[k][0] + fr->W[k][0][1] * p->z[k][1]);
    double gp = fe * (fr->W[k][0][0] * p->z[pc][0] + fr->W[k][0][1] * p->z[pc][1]);
    double h = fe * (fr->W[k][0][0] * p->u[0] + fr->W[k][0][1] * p->u[1] + fr->w[k][0]);
    if (fabs(g) <= TOL_DET) {
        p->res->continuum = 1; /* lam_k free along a line: degenerate, reported as such */
        return;
    }
    solve_quadratic(p, pc, k, h / g, gp / g);
}

static void solve_mode(const dp_right_hand_frame *fr, const double qd[2], const dp_right_hand_mode mode[2], int check_rest,
                       double fscale, dp_right_hand_result *res)
{
    prob p = { .fr = fr, .qd = qd, .mode = mode, .check_rest = check_rest, .fscale = fscale, .res = res };
    free_solve(fr, mode, fr->b, p.u);
    int K[2], nk = 0;
    for (int k = 0; k < 2; k++) {
        double e[2] = { 0, 0 };
        int sg = sigma_of(mode[k]);
        if (sg == 0)
            continue;
        e[k] = -sg;
        free_solve(fr, mode, e, p.z[k]);
        K[nk++] = k;
    }
    /* signs of the affine sliding reactions: 2^(their number) choices */
    int naff = 0;
    for (int a = 0; a < nk; a++)
        naff += fr->ndim[K[a]] == 1;
    for (int bits = 0; bits < (1 << naff); bits++) {
        int eps[2] = { 1, 1 }, j = 0, pulls = 0;
        for (int a = 0; a < nk; a++)
            if (fr->ndim[K[a]] == 1) {
                eps[a] = (bits >> j++) & 1 ? -1 : 1;
                pulls |= eps[a] < 0 && fr->unilateral[K[a]];
            }
        if (!pulls)
            solve_signs(&p, K, nk, eps);
    }
}

static double force_scale(const dp_right_hand_frame *fr)
{
    double s = 1;
    for (int k = 0; k < 2; k++) {
        s += fabs(fr->b[k]);
        for (int r = 0; r < fr->ndim[k]; r++)
            s += fabs(fr->w[k][r]);
    }
    return s;
}

/* The rod's free flight from the floor (painleve.c): a candidate when it lifts A, g - l sin theta'^2 < 0.
 * A contact solution with the same accelerations (N = 0 to the tolerance) is that same motion: it becomes
 * the lift-off rather than a second solution. */
static void liftoff(const dp_right_hand_model *m, const double q[2], const double qd[2], dp_right_hand_result *res)
{
    double l = m->length / 2, up = m->m * (l * sin(q[1]) * qd[1] * qd[1] - m->g);
    if (!(up > 0))
        return;
    dp_right_hand_sol s = { .qdd = { l * cos(q[1]) * qd[1] * qd[1], 0 }, .mode = { DP_RIGHT_HAND_FREE, DP_RIGHT_HAND_FREE },
                    .liftoff = 1 };
    for (int i = 0; i < res->n && i < DP_RIGHT_HAND_MAX_SOL; i++)
        if (same(res->sol[i].qdd, s.qdd)) {
            res->sol[i].liftoff = 1;
            return;
        }
    if (res->n < DP_RIGHT_HAND_MAX_SOL)
        res->sol[res->n] = s;
    res->n++;
}

double dp_right_hand_force_tol(const dp_right_hand_frame *fr)
{
    return TOL_FORCE * force_scale(fr);
}

void dp_right_hand_solve(const dp_right_hand_model *m, const double q[2], const double qd[2], const dp_right_hand_mode *fixed,
                 dp_right_hand_result *res)
{
    dp_right_hand_frame fr;
    dp_right_hand_frame_at(m, q, qd, &fr);
    memset(res, 0, sizeof *res);
    double fs = force_scale(&fr);
    if (fixed) {
        solve_mode(&fr, qd, fixed, 0, fs, res);
        return;
    }
    dp_right_hand_mode opts[2][3];
    int nopt[2];
    for (int s = 0; s < 2; s++) {
        if (!fr.fric[s])
            opts[s][0] = DP_RIGHT_HAND_FREE, nopt[s] = 1;
        else if (qd[s] != 0)
            opts[s][0] = qd[s] > 0 ? DP_RIGHT_HAND_SLIP_POS : DP_RIGHT_HAND_SLIP_NEG, nopt[s] = 1;
        else
            opts[s][0] = DP_RIGHT_HAND_STICK, opts[s][1] = DP_RIGHT_HAND_SLIP_POS, opts[s][2] = DP_RIGHT_HAND_SLIP_NEG, nopt[s] = 3;
    }
    for (int i = 0; i < nopt[0]; i++)
        for (int j = 0; j < nopt[1]; j++) {
            dp_right_hand_mode md[2] = { opts[0][i], opts[1][j] };
            solve_mode(&fr, qd, md, 1, fs, res);
        }
    if (m->kind == DP_RIGHT_HAND_ROD)
        liftoff(m, q, qd, res);
}

/* d|N_s|/dq''_v at q'' (for a vector reaction of length 0, the largest value over its directions). */
static double dnorm(const dp_right_hand_frame *fr, int s, const double qdd[2], int v)
{
    double nv[2];
    normal_vec(fr, s, qdd, nv);
    if (fr->ndim[s] == 1)
        return (nv[0] < 0 ? -1 : 1) * fr->W[s][0][v];
    double len = hypot(nv[0], nv[1]);
    if (len == 0)
        return hypot(fr->W[s][0][v], fr->W[s][1][v]);
    return (nv[0] * fr->W[s][0][v] + nv[1] * fr->W[s][1][v]) / len;
}

/* (2.3) with F_s = a_ss^-1 [-f_s |N_s| Delta_s - Q_s^T0] and the frictionless coordinates eliminated:
 * a_ss dF_s/dq''_v = -[a_sv gamma_sv + f_s Delta_s d_v|N_s| - sum_j (a_sj + f_s Delta_s d_j|N_s|) sum_i
 * at_ji a_iv] (j, i frictionless, at the inverse of their block). The paper prints the Delta terms with
 * the opposite sign; this form is the one whose contraction the enumeration confirms (docs/right-hand.md). */
static double cond23(const dp_right_hand_frame *fr, const dp_right_hand_sol *sol)
{
    int kstar = fr->fric[0] + fr->fric[1];
    double margin = INFINITY;
    for (int s = 0; s < 2; s++) {
        if (!fr->fric[s])
            continue;
        double delta;
        if (sol->mode[s] == DP_RIGHT_HAND_STICK) {
            if (fabs(sol->Q[s]) < fr->f[s] * fabs(sol->N[s]) * (1 - TOL_SAME))
                continue;                     /* strictly inside the cone: not in (2.3) */
            delta = sol->Q[s] > 0 ? -1 : 1;
        } else {
            delta = sol->mode[s] == DP_RIGHT_HAND_SLIP_POS ? 1 : -1;
        }
        double fd = fr->f[s] * delta, bound = fr->A[s][s] / kstar;
        for (int v = 0; v < 2; v++) {
            if (!fr->fric[v])
                continue;
            double J = (s != v ? fr->A[s][v] : 0) + fd * dnorm(fr, s, sol->qdd, v);
            for (int j = 0; j < 2; j++)
                if (!fr->fric[j]) /* two coordinates: the frictionless block is 1x1 */
                    J -= (fr->A[s][j] + fd * dnorm(fr, s, sol->qdd, j)) * fr->A[j][v] / fr->A[j][j];
            margin = fmin(margin, bound - fabs(J));
        }
    }
    return isfinite(margin) ? margin : fmin(fr->A[0][0], fr->A[1][1]);
}

void dp_right_hand_conditions_at(const dp_right_hand_model *m, const double q[2], const double qd[2], const dp_right_hand_sol *sol,
                         dp_right_hand_conditions *c)
{
    dp_right_hand_frame fr;
    dp_right_hand_frame_at(m, q, qd, &fr);
    double tol = TOL_FORCE * force_scale(&fr);
    c->c12 = INFINITY;
    c->in_A = 1;
    for (int s = 0; s < 2; s++) {
        if (!fr.fric[s])
            continue;
        c->c12 = fmin(c->c12, fr.A[s][s] - fr.f[s] * fabs(dnorm(&fr, s, sol->qdd, s)));
        if (qd[s] == 0 && sol->mode[s] == DP_RIGHT_HAND_STICK && fabs(sol->N[s]) <= tol &&
            fabs(sol->Q[s]) >= fr.f[s] * fabs(sol->N[s]) - tol)
            c->in_A = 0;                      /* on the cone (set N1) with N_s = 0 */
    }
    if (!isfinite(c->c12))
        c->c12 = fmin(fr.A[0][0], fr.A[1][1]); /* no friction: vacuous, reported as the smallest a_ss */
    c->c23 = cond23(&fr, sol);
    if (m->kind == DP_RIGHT_HAND_ROD) {
        c->c62 = c->c63 = c->c64 = NAN;
        return;
    }
    double sb = fabs(sin(q[1])), cb = fabs(cos(q[1]));
    double J = m->J_C + m->m2 * m->r * m->r, mm = m->m1 + m->m2, mr = m->m2 * m->r;
    c->c62 = J - m->f2 * mr * (cb + sb);
    c->c63 = J / (sqrt(2) * mr) - m->f2;
    c->c64 = fmin(fmin(mm / 2 - mr * (cb + m->f1 * sb), J / 2 - m->m2 * (m->r * cb + m->f2)),
                  J / 2 - mr * m->f2 * (cb + sb));
}
