/* src/core/right_hand/rod_flight.c - Painlevé's rod off the floor and back on it: the free flight in closed form,
 * its landing located by safe advances, and the impact at the landing end (docs/right-hand.md).
 *
 * Flight: a uniform rod (mass m, length 2l, I = m l^2/3 about its centre G) under gravity alone: G on a
 * parabola, theta turning uniformly. The end A = G - l (cos theta, sin theta) (B = G + l (...)) has the height
 *     y(tau) = yG0 + vy tau - g tau^2/2 -+ l sin(theta0 + omega tau),
 * whose third derivative is bounded by l |omega|^3. The landing is the first zero of an end's height: from a
 * time where the height y is >= 0, its Taylor polynomial with that bound, p(s) = y + y' s + y'' s^2/2
 * - l|omega|^3 s^3/6, lies below the height, so no end reaches the floor before p's first positive root; the
 * search advances by that root (found on p's monotone pieces by bisection, its lower end kept), which
 * converges to a simple landing to third order and never steps over a grazing one. While G is higher than l
 * no end can touch: the parabola's closed form skips that part.
 *
 * Impact: Stronge's energetic coefficient of restitution with Coulomb friction (Stronge 2000, Impact
 * Mechanics, ch. 4-5), the contact velocity integrated along the normal impulse p after Routh: with the
 * Delassus matrix W of the end A (its velocity's change per unit impulse), constant through the impulse,
 *     slip s = sgn v_T:  dP_T = -mu s dp,                v' = W (-mu s, 1)
 *     stick (|W_TN| <= mu W_TT):  dP_T = -(W_TN/W_TT) dp,  v_T' = 0
 * and the slip, when it stops, sticks or reverses. Compression ends where v_N = 0 (the normal impulse's work
 * W_c < 0); restitution goes on until the normal work in it is -e^2 W_c. For the rod W_TT = (1 + 3 sin^2)/m,
 * W_NN = (1 + 3 cos^2)/m, W_TN = -3 sin cos/m: det W = 4/m^2 > 0, so a slip that pushes the end down (Painlevé's
 * B = 1 + 3cos^2 - 3 mu sin cos < 0 while sliding backwards) always stops within the impulse (it decelerates)
 * and the impulse ends. Friction opposes the slip throughout and the normal work is (1 - e^2) W_c <= 0: the
 * impact never gains energy, which Newton's kinematic coefficient with friction can (Kane & Levinson's
 * example; Stronge 2000, §4.4).
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "dashpot/right_hand.h"

void dp_right_hand_flight_start(const dp_right_hand_model *m, double t0, const dp_right_hand_rod_state *s,
                                dp_right_hand_flight *f)
{
    double l = m->length / 2, sn = sin(s->theta), cs = cos(s->theta);
    *f = (dp_right_hand_flight){ .t0 = t0, .xG = s->x + l * cs, .yG = s->y + l * sn, .vx = s->xd - l * sn * s->thetad,
                                 .vy = s->yd + l * cs * s->thetad, .theta = s->theta, .omega = s->thetad };
}

void dp_right_hand_flight_at(const dp_right_hand_model *m, const dp_right_hand_flight *f, double t,
                             dp_right_hand_rod_state *s, double *xdd)
{
    double l = m->length / 2, tau = t - f->t0, th = f->theta + f->omega * tau, sn = sin(th), cs = cos(th);
    s->theta = th, s->thetad = f->omega;
    s->x = f->xG + f->vx * tau - l * cs;
    s->y = f->yG + f->vy * tau - 0.5 * m->g * tau * tau - l * sn;
    s->xd = f->vx + l * sn * f->omega;
    s->yd = f->vy - m->g * tau - l * cs * f->omega;
    if (xdd)
        *xdd = l * cs * f->omega * f->omega;
}

static double cubic(const double a[4], double s)
{
    return a[0] + s * (a[1] + s * (a[2] - s * a[3]));
}

/* The root of a monotone piece [lo, hi] of p with p(lo) >= 0 >= p(hi): bisection, its lower end returned. */
static double bisect(const double a[4], double lo, double hi)
{
    for (int i = 0; i < 1100; i++) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi)
            break;
        if (cubic(a, mid) > 0)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* sup{S : p > 0 on (0, S)} for p(s) = a0 + a1 s + a2 s^2 - a3 s^3 with a0 >= 0, a3 >= 0 (a2 < 0 when
 * a3 = 0): p's positive critical points cut (0, inf) into monotone pieces, walked in order. */
static double first_root(const double a[4])
{
    if (a[0] == 0 && !(a[1] > 0 || (a[1] == 0 && a[2] > 0)))
        return 0;                                   /* p < 0 right after 0 */
    double c[3];
    int nc = 0;
    if (a[3] == 0) {
        if (a[1] > 0)
            c[nc++] = -a[1] / (2 * a[2]);
    } else {
        double disc = a[2] * a[2] + 3 * a[3] * a[1];   /* p' = a1 + 2 a2 s - 3 a3 s^2 */
        if (disc > 0) {
            double q = a[2] + copysign(sqrt(disc), a[2]), r[2] = { q / (3 * a[3]), q != 0 ? -a[1] / q : 0 };
            if (r[0] > r[1])
                r[0] = r[1], r[1] = q / (3 * a[3]);
            for (int i = 0; i < 2; i++)
                if (r[i] > 0)
                    c[nc++] = r[i];
        }
    }
    double u = 0;
    for (int i = 0; i < nc; i++) {
        if (!(cubic(a, c[i]) > 0))
            return bisect(a, u, c[i]);
        u = c[i];
    }
    /* past the last critical point p decreases to -inf: beyond Fujiwara's bound of its roots it is < 0 */
    double v = a[3] > 0 ? 2 * fmax(fmax(fabs(a[2]) / a[3], sqrt(fabs(a[1]) / a[3])), cbrt(a[0] / (2 * a[3])))
                        : 2 * fmax(fabs(a[1] / a[2]), sqrt(a[0] / (2 * fabs(a[2]))));
    v = fmax(v, 2 * u);
    for (int i = 0; i < 64 && cubic(a, v) > 0; i++)
        v = 2 * v + DBL_MIN;
    if (!isfinite(v))
        return INFINITY;
    return bisect(a, u, v);
}

/* Time from tau until G, falling past the height l, reaches it: no end can touch before. */
static double above(const dp_right_hand_model *m, const dp_right_hand_flight *f, double tau, double l)
{
    double yG = f->yG + f->vy * tau - 0.5 * m->g * tau * tau, vy = f->vy - m->g * tau;
    if (!(yG > l))
        return 0;
    return (vy + hypot(vy, sqrt(2 * m->g) * sqrt(yG - l))) / m->g;
}

int dp_right_hand_flight_landing(const dp_right_hand_model *m, const dp_right_hand_flight *f, double *t, double t_max,
                                 unsigned long budget, unsigned long *used, int *end)
{
    double l = m->length / 2, w = f->omega, tau = *t - f->t0, taumax = t_max - f->t0;
    double a3 = l * fabs(w) * w * w / 6;
    *used = 0;
    if (!isfinite(a3))
        return DP_FLIGHT_OVERFLOW;
    while (*used < budget) {
        ++*used;
        tau += above(m, f, tau, l);
        if (tau >= taumax) {
            *t = t_max;
            return DP_FLIGHT_ON;
        }
        double th = f->theta + w * tau, sn = sin(th), cs = cos(th);
        double yG = f->yG + f->vy * tau - 0.5 * m->g * tau * tau, vy = f->vy - m->g * tau, s = INFINITY, sa = 0;
        double hr = 1e-15 * (fabs(yG) + l);  /* the heights' rounding */
        int which = 0, away = 1;
        for (int k = 0; k < 2; k++) {       /* A (k = 0) is below G by l sin theta, B above */
            double sg = k ? 1 : -1, y = yG + sg * l * sn, y1 = vy + sg * l * w * cs, y2 = -m->g - sg * l * w * w * sn;
            if (!isfinite(y) || !isfinite(y1) || !isfinite(y2))
                return DP_FLIGHT_OVERFLOW;
            double a[4] = { fmax(y, 0), y1, y2 / 2, a3 }, r = first_root(a);
            /* an end leaving, or whose dip y1^2/(2 y2) before it rises is below its height's rounding (the
             * lift-off's first instant, where y1 is 0 to rounding), does not land here */
            if (r < s) {
                s = r, which = k, away = y1 > 0 || (y2 > 0 && y1 * y1 <= 2 * y2 * hr);
                a[0] += hr;
                sa = first_root(a);              /* where it would be below the floor by more than rounding */
            }
        }
        if (tau + s >= taumax) {
            *t = t_max;
            return DP_FLIGHT_ON;
        }
        double tol = 1e-15 * fmax(fabs(f->t0 + tau), fabs(tau));
        if (s <= tol || tau + s == tau) {
            if (!away) {
                *t = f->t0 + tau, *end = which;
                return DP_FLIGHT_LANDS;
            }
            s = fmax(sa, fmax(tol, 4 * DBL_EPSILON * fabs(tau))); /* leaving the floor: nothing lands this close */
        }
        tau += s;
    }
    *t = f->t0 + tau;
    return DP_FLIGHT_BUDGET;
}

double dp_right_hand_rod_kinetic(const dp_right_hand_model *m, const dp_right_hand_rod_state *s)
{
    double l = m->length / 2, sn = sin(s->theta), cs = cos(s->theta);
    double vx = s->xd - l * sn * s->thetad, vy = s->yd + l * cs * s->thetad;
    return 0.5 * m->m * (vx * vx + vy * vy) + 0.5 * (m->m * l * l / 3) * s->thetad * s->thetad;
}

/* Routh's integration of one impact: the Delassus matrix, the slip regime and the velocities on the way. */
typedef struct routh {
    double Wtt, Wnn, Wtn, mu;
    int reg;                 /* 0 stick, +1 / -1 slip with v_T of that sign */
    double vt, vn, Pt, Pn, wt;
} routh;

/* dP_T/dp and the velocities' rates of the regime. */
static void rates(const routh *r, double *rt, double *at, double *an)
{
    *rt = r->reg == 0 ? -r->Wtn / r->Wtt : -r->mu * r->reg;
    *at = r->reg == 0 ? 0 : r->Wtt * *rt + r->Wtn;
    *an = r->Wtn * *rt + r->Wnn;
}

/* The regime at v_T = 0: stick when the cone holds it, else the slip the coupling drives. */
static int rest_regime(const routh *r)
{
    return fabs(r->Wtn) <= r->mu * r->Wtt ? 0 : r->Wtn > 0 ? 1 : -1;
}

/* Moves p by d in the current regime; returns the normal work of the piece. */
static double advance(routh *r, double d)
{
    double rt, at, an;
    rates(r, &rt, &at, &an);
    double work = r->vn * d + 0.5 * an * d * d;
    r->wt += rt * d * (r->vt + 0.5 * at * d);
    r->vt += at * d, r->vn += an * d, r->Pt += rt * d, r->Pn += d;
    return work;
}

/* The length of p until the slip stops (v_T = 0), or INFINITY. */
static double slip_stop(const routh *r)
{
    double rt, at, an;
    rates(r, &rt, &at, &an);
    return r->reg != 0 && r->reg * at < 0 ? -r->vt / at : INFINITY;
}

/* After a piece that ended where the slip stops: v_T = 0 and the next regime. */
static void stopped(routh *r)
{
    r->vt = 0;
    r->reg = rest_regime(r);
}

/* Compression: until v_N = 0; returns its normal work (<= 0), or NAN when it cannot end. */
static double compress(routh *r)
{
    double work = 0;
    for (int i = 0; i < 8 && r->vn < 0; i++) {
        double rt, at, an;
        rates(r, &rt, &at, &an);
        double ds = slip_stop(r), de = an > 0 ? -r->vn / an : INFINITY;
        if (!isfinite(ds) && !isfinite(de))
            return NAN;
        if (ds < de) {
            work += advance(r, ds);
            stopped(r);
        } else {
            work += advance(r, de);
            r->vn = 0;
        }
    }
    return r->vn < 0 ? NAN : work;
}

/* Restitution: until the normal work in it reaches R (or v_N comes back to 0: the end stays down). */
static double restitute(routh *r, double R)
{
    double work = 0;
    for (int i = 0; i < 8 && work < R; i++) {
        double rt, at, an;
        rates(r, &rt, &at, &an);
        double left = R - work, disc = r->vn * r->vn + 2 * an * left, de;
        if (disc >= 0 && r->vn + sqrt(disc) > 0)
            de = 2 * left / (r->vn + sqrt(disc));      /* v_N d + a_N d^2/2 = left, its first root */
        else
            de = an < 0 ? -r->vn / an : INFINITY;      /* the work peaks where v_N returns to 0 */
        double ds = slip_stop(r);
        if (!isfinite(ds) && !isfinite(de)) {
            r->vn = fmax(r->vn, 0);                    /* v_N = 0 and no rate: the work cannot grow */
            break;
        }
        if (ds < de) {
            work += advance(r, ds);
            stopped(r);
        } else {
            int full = disc >= 0;
            work += advance(r, de);
            if (!full) {
                r->vn = 0;
                break;
            }
            work = R;
        }
    }
    return work;
}

int dp_right_hand_rod_impact(const dp_right_hand_model *m, double theta, double xd, double yd, double thetad, double e,
                             dp_right_hand_impact *out)
{
    double sn = sin(theta), cs = cos(theta), l = m->length / 2;
    routh r = { .Wtt = (1 + 3 * sn * sn) / m->m, .Wnn = (1 + 3 * cs * cs) / m->m, .Wtn = -3 * sn * cs / m->m,
                .mu = m->mu, .vt = xd, .vn = yd };
    r.reg = xd > 0 ? 1 : xd < 0 ? -1 : rest_regime(&r);
    memset(out, 0, sizeof *out);
    out->vt0 = xd, out->vn0 = yd;
    double wc = compress(&r);
    if (isnan(wc))
        return 0;
    double wr = e > 0 ? restitute(&r, -e * e * wc) : 0;
    if (r.reg == 0)
        r.vt = 0;
    out->vt = r.vt, out->vn = fmax(r.vn, 0), out->Pt = r.Pt, out->Pn = r.Pn;
    out->work_c = wc, out->work_r = wr, out->work_t = r.wt;
    out->stick = r.reg == 0;
    /* theta' from the angular impulse about G: the impulse at A = G - l (cos, sin) */
    out->thetad = thetad + 3 * (sn * r.Pt - cs * r.Pn) / (m->m * l);
    return 1;
}
