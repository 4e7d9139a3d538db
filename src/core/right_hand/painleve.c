/* src/core/right_hand/painleve.c - the two models of friction with motion-dependent normal force (docs/systems.md §6) as
 * frames A q'' = b + Q with their normal reactions affine in q'' (right_hand.h).
 *
 * Piston-hinge (Matrosov & Finogenko 1995, §6, with the corrections of docs/systems.md: beta'^2 in N1, beta'' in N2). Tube Ox
 * inclined at alpha, e_x up the tube, n its upward normal; the body's centre C = B + r sin(beta) e_x
 * - r cos(beta) n, so with m = m1 + m2, J = J_C + m2 r^2:
 *     T = m x'^2/2 + m2 r cos(beta) x' beta' + J beta'^2/2,   V = m g x sin(alpha) - m2 g r cos(alpha + beta)
 *     m x'' + m2 r cos(beta) beta'' = m2 r beta'^2 sin(beta) - m g sin(alpha) + Q1
 *     m2 r cos(beta) x'' + J beta'' = -m2 g r sin(alpha + beta) + Q2
 * The tube's reaction is the n-component of the whole system's momentum balance, the hinge's the body's:
 *     N1 = m2 r (beta'' sin(beta) + beta'^2 cos(beta)) + m g cos(alpha)
 *     N2 = m2 (x'' + r beta'' cos(beta) - r beta'^2 sin(beta) + g sin(alpha),
 *              r beta'' sin(beta) + r beta'^2 cos(beta) + g cos(alpha))      (|N2| its length)
 *
 * Painlevé's rod: uniform, mass m, length 2l, I = m l^2/3 about its centre G, end A on the floor at x_A,
 * theta the angle to the floor, G = (x_A + l cos(theta), l sin(theta)) while A touches the floor:
 *     T = m (x_A'^2 - 2 l sin(theta) x_A' theta' + l^2 theta'^2)/2 + I theta'^2/2,   V = m g l sin(theta)
 *     m x_A'' - m l sin(theta) theta'' = m l cos(theta) theta'^2 + F            (F: friction at A, Q1 = F)
 *     -m l sin(theta) x_A'' + (4/3) m l^2 theta'' = -m g l cos(theta)           (F does no work on theta)
 * and the floor's reaction from G's vertical motion, m y_G'' = N - m g:
 *     N = m l cos(theta) theta'' - m l sin(theta) theta'^2 + m g.
 * Sliding with sgn x_A' = s, eliminating theta'' gives N (1 + 3cos^2 + 3 s mu sin cos) = m (g - l sin theta'^2)
 * (for N > 0), so the coefficient vanishes, and Painlevé's paradoxes appear, only when mu >= min over theta of
 * (1 + 3 cos^2)/(3 sin cos) = (tan^2 + 4)/(3 tan) = 4/3, at tan(theta) = 2. The floor is unilateral: a
 * contact solution needs N >= 0, and leaving the floor (N = 0, free flight: x_A'' = l cos theta'^2,
 * theta'' = 0, y_A'' = l sin theta'^2 - g) is a candidate when g - l sin theta'^2 < 0. With
 * B = 1 + 3cos^2 - 3 mu sin cos (sliding x_A' < 0): B < 0 and g - l sin theta'^2 > 0 leave no candidate
 * (inconsistency), B < 0 and g - l sin theta'^2 < 0 two (indeterminacy: contact with N > 0, and lift-off):
 * Painlevé's classical cases.
 */
#include <math.h>
#include <string.h>

#include "dashpot/right_hand.h"

static void piston_frame(const dp_right_hand_model *p, const double q[2], const double qd[2], dp_right_hand_frame *fr)
{
    double s = sin(q[1]), c = cos(q[1]), w2 = qd[1] * qd[1];
    double m = p->m1 + p->m2, J = p->J_C + p->m2 * p->r * p->r, mr = p->m2 * p->r;
    double sa = sin(p->alpha), ca = cos(p->alpha);
    fr->A[0][0] = m, fr->A[0][1] = fr->A[1][0] = mr * c, fr->A[1][1] = J;
    fr->b[0] = mr * w2 * s - m * p->g * sa;
    fr->b[1] = -mr * p->g * sin(p->alpha + q[1]);
    fr->f[0] = p->f1, fr->f[1] = p->f2;
    fr->ndim[0] = 1;
    fr->W[0][0][0] = 0, fr->W[0][0][1] = mr * s;
    fr->w[0][0] = mr * w2 * c + m * p->g * ca;
    fr->ndim[1] = 2;
    fr->W[1][0][0] = p->m2, fr->W[1][0][1] = mr * c;
    fr->w[1][0] = p->m2 * (-p->r * w2 * s + p->g * sa);
    fr->W[1][1][0] = 0, fr->W[1][1][1] = mr * s;
    fr->w[1][1] = p->m2 * (p->r * w2 * c + p->g * ca);
}

static void rod_frame(const dp_right_hand_model *p, const double q[2], const double qd[2], dp_right_hand_frame *fr)
{
    double s = sin(q[1]), c = cos(q[1]), w2 = qd[1] * qd[1], l = p->length / 2, m = p->m;
    fr->A[0][0] = m, fr->A[0][1] = fr->A[1][0] = -m * l * s, fr->A[1][1] = 4.0 / 3.0 * m * l * l;
    fr->b[0] = m * l * c * w2;
    fr->b[1] = -m * p->g * l * c;
    fr->f[0] = p->mu, fr->f[1] = 0;
    fr->ndim[0] = 1, fr->ndim[1] = 1;
    fr->unilateral[0] = 1;
    fr->W[0][0][0] = 0, fr->W[0][0][1] = m * l * c;
    fr->w[0][0] = m * p->g - m * l * s * w2;
}

void dp_right_hand_frame_at(const dp_right_hand_model *m, const double q[2], const double qd[2], dp_right_hand_frame *fr)
{
    memset(fr, 0, sizeof *fr);
    if (m->kind == DP_RIGHT_HAND_ROD)
        rod_frame(m, q, qd, fr);
    else
        piston_frame(m, q, qd, fr);
    for (int s = 0; s < 2; s++)
        fr->fric[s] = fr->f[s] > 0;
}

const char *dp_right_hand_kind_name(dp_right_hand_kind k)
{
    return k == DP_RIGHT_HAND_ROD ? "painleve-rod" : "piston-hinge";
}

static int bad(const char **key, const char **why, const char *k, const char *w)
{
    *key = k, *why = w;
    return 0;
}

int dp_right_hand_model_valid(const dp_right_hand_model *m, const char **key, const char **why)
{
    if (!(m->g > 0 && isfinite(m->g)))
        return bad(key, why, "g", "must be a finite number > 0 (without gravity the normal forces vanish)");
    if (m->kind == DP_RIGHT_HAND_ROD) {
        if (!(m->m > 0 && isfinite(m->m)))
            return bad(key, why, "m", "must be a finite number > 0");
        if (!(m->length > 0 && isfinite(m->length)))
            return bad(key, why, "length", "must be a finite number > 0");
        if (!(m->mu >= 0 && isfinite(m->mu)))
            return bad(key, why, "mu", "must be a finite number >= 0");
        if (!(m->e >= 0 && m->e <= 1))
            return bad(key, why, "restitution", "must be in [0, 1] (Stronge's energetic coefficient: 0 plastic, 1 elastic)");
        return 1;
    }
    if (!(m->m1 > 0 && isfinite(m->m1)))
        return bad(key, why, "m1", "must be a finite number > 0");
    if (!(m->m2 > 0 && isfinite(m->m2)))
        return bad(key, why, "m2", "must be a finite number > 0");
    if (!(m->J_C >= 0 && isfinite(m->J_C)))
        return bad(key, why, "J_C", "must be a finite number >= 0");
    if (!(m->r > 0 && isfinite(m->r)))
        return bad(key, why, "r", "must be a finite number > 0 (the hinge at the centre carries no pendulum)");
    if (!(m->alpha >= 0 && m->alpha <= M_PI / 2))
        return bad(key, why, "alpha", "must be in [0, pi/2] (the tube's inclination to the horizontal)");
    if (!(m->f1 >= 0 && isfinite(m->f1)))
        return bad(key, why, "f1", "must be a finite number >= 0");
    if (!(m->f2 >= 0 && isfinite(m->f2)))
        return bad(key, why, "f2", "must be a finite number >= 0 (a length: the hinge pin's friction arm)");
    return 1;
}
