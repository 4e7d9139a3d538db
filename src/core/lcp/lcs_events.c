/* src/core/lcp/lcs_events.c - a linear complementarity system's mode changes as events located inside a step
 * (docs/lcs.md, "Mode changes are events").
 *
 * A diode that starts or stops conducting changes the system's mode: the laws then hold other quantities (the
 * current instead of the voltage), and the solution's derivative jumps. The θ-step sees such a switch only as
 * a step whose end is in another mode, and the part of the step before the switch is then stepped with the
 * wrong mode, which costs θ = 1/2 its second order (as a stick-slip step that is not split at the instant the
 * mass sticks: solvers/event_location.c). So a step that changes a mode is split where the change happens,
 * and each part is a θ-step within one mode.
 *
 * Where: each boundary between two modes of a component has a margin read from the step's LCP, z - w of one
 * complementary pair (lcs.c), whose sign says the side and which Lemke's settled answer makes exact. As a
 * function of a sub-step's length s from the step's start it is continuous and changes sign at the switch,
 * with a kink there (z on one side, -w on the other); each side is scaled to 1 at its end of the bracket and
 * the earliest root of their minimum over the components that changed is found by the safeguarded Illinois
 * iteration of base/root.c, each evaluation one sub-step (the step's data are those of the system at s). The
 * step goes to the root, the components that are on their boundary there change mode, and the rest of the
 * step is taken again from there, until a rest of the step keeps every mode.
 *
 * A multiplier's side (an ideal diode that blocks with D = 0: u holds w = 0) is read at the step's θ-point,
 * not its end: the θ-step's u is then u's mean over the step (Moreau–Jean's impulse over h). Its margin σ
 * into the step is therefore read from a sub-step of σ/θ, and a change in the step's last (1 - θ) h, which
 * the nominal step's mean does not show, is foreseen by extrapolating the last two steps' margins and
 * confirmed by a sub-step of h/θ. Without that the switch would be dated up to (1 - θ) h late.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/root.h"
#include "dashpot/lcs.h"
#include "dashpot/status.h"

/* A step is split at most this often; past it the remaining changes are dated at the step's end. Every split
 * costs a root search, so this bounds a step's work when a system chatters between modes. */
#define SPLITS_MAX 32
/* Components whose scaled margin at the located instant is within this of the boundary change there too
 * (switches at one instant, as a bridge's diodes, are found once; the margins are scaled to 1 across the
 * bracket, so this is a relative distance in time well below any step's resolution). */
#define TOGETHER 1e-9
/* A change is located to this fraction of its step (or a few ulps of t, when that is more: instant()): far
 * below the step's own error, and no sub-step is much shorter (its LCP's matrix is O(length) when D = 0). */
#define SHORTEST 1e-12
/* A sub-step this short (a fraction of the rest) whose LCP fails is taken for a change at once (least_at). */
#define IMMEDIATE 1e-6
/* The stop hook is asked once every this many sub-steps, besides inside Lemke's pivots. */
#define STOP_EVERY 64

struct dp_lcs_locator {
    dp_lcs sys;                 /* the caller's (its arrays outlive the locator) */
    const dp_forcing *pf;       /* NULL, or n forcings added to p */
    dp_lcs_stepper *probe;      /* the sub-steps: discretized again at each length */
    size_t n, m, nb;
    const size_t *first;        /* component i's boundaries: first[i] .. first[i+1] - 1 */
    double theta;
    int *mode, *mode0;          /* each component's mode (-1: not known yet), and at the step's start */
    double *mg, *mt, *mn, *ms;  /* margins at the current state, a trial's end, the nominal step's end, a probe's */
    double *ml, *me, *mp;       /* a probe's of length σ/θ, the trial's of length rest/θ, the last nominal step's */
    int mp_ok;                  /* mp is the nominal margins of the step just before, which kept every mode */
    double *xc, *uc, *wc;       /* the current state: the step's start, then each located change */
    double *xt, *ut, *wt;       /* a trial: the rest of the step from the current state */
    double *xn, *un, *wn;       /* the nominal step's end */
    double *xs, *us, *ws;       /* a probe */
    double *pt;                 /* p at a sub-step's θ-point */
    int *cross;                 /* per component: +1 or -1 when its mode changed in the trial (the direction) */
    int *lag;                   /* per component that changed: the side it leaves is a multiplier's (θ-point) */
    double *pos, *neg;          /* per component: its crossing margin's size on either side, at the bracket's ends */
    dp_lcs_event *ev;
    size_t nev, evcap;
    unsigned long long substeps;
};

void dp_lcs_locator_free(dp_lcs_locator *lc)
{
    if (lc == NULL)
        return;
    dp_lcs_stepper_free(lc->probe);
    void *own[] = { lc->mode, lc->mode0, lc->mg, lc->mt, lc->mn, lc->ms, lc->ml, lc->me, lc->mp, lc->lag, lc->xc, lc->uc, lc->wc, lc->xt, lc->ut, lc->wt, lc->xn, lc->un, lc->wn,
                    lc->xs, lc->us, lc->ws, lc->pt, lc->cross, lc->pos, lc->neg, lc->ev };
    for (size_t i = 0; i < sizeof own / sizeof own[0]; i++)
        free(own[i]);
    free(lc);
}

static double *doubles(size_t k)
{
    return malloc((k ? k : 1) * sizeof(double));
}

dp_lcs_locator *dp_lcs_locator_alloc(const dp_lcs *sys, const dp_forcing *pf, double h, double theta, int *status)
{
    dp_lcs_locator *lc = calloc(1, sizeof *lc);
    if (lc == NULL) {
        *status = DP_ENOMEM;
        return NULL;
    }
    lc->probe = dp_lcs_stepper_alloc(sys, h, theta, status);
    if (lc->probe == NULL) {
        free(lc);
        return NULL;
    }
    size_t n = sys->n, m = sys->m;
    lc->sys = *sys, lc->pf = pf, lc->n = n, lc->m = m, lc->theta = theta;
    lc->nb = dp_lcs_boundaries(lc->probe, &lc->first);
    lc->mode = calloc(m, sizeof *lc->mode), lc->mode0 = calloc(m, sizeof *lc->mode0);
    lc->cross = calloc(m, sizeof *lc->cross), lc->lag = calloc(m, sizeof *lc->lag);
    lc->ml = doubles(lc->nb), lc->me = doubles(lc->nb), lc->mp = doubles(lc->nb);
    lc->mg = doubles(lc->nb), lc->mt = doubles(lc->nb), lc->mn = doubles(lc->nb), lc->ms = doubles(lc->nb);
    lc->xc = doubles(n), lc->uc = doubles(m), lc->wc = doubles(m);
    lc->xt = doubles(n), lc->ut = doubles(m), lc->wt = doubles(m), lc->xn = doubles(n), lc->un = doubles(m);
    lc->wn = doubles(m), lc->xs = doubles(n), lc->us = doubles(m), lc->ws = doubles(m), lc->pt = doubles(n);
    lc->pos = doubles(m), lc->neg = doubles(m);
    lc->evcap = 8, lc->ev = malloc(lc->evcap * sizeof *lc->ev);
    if (!lc->mode || !lc->mode0 || !lc->cross || !lc->lag || !lc->ml || !lc->me || !lc->mp || !lc->mg || !lc->mt || !lc->mn || !lc->ms || !lc->xc || !lc->uc ||
        !lc->wc || !lc->xt || !lc->ut || !lc->wt ||
        !lc->xn || !lc->un || !lc->wn || !lc->xs || !lc->us || !lc->ws || !lc->pt || !lc->pos || !lc->neg || !lc->ev) {
        dp_lcs_locator_free(lc);
        *status = DP_ENOMEM;
        return NULL;
    }
    for (size_t i = 0; i < m; i++)
        lc->mode[i] = -1;
    *status = DP_OK;
    return lc;
}

/* The modes component i's margins admit, [*lo, *hi]: the boundaries it is past, and those it is on. */
static void admitted(const dp_lcs_locator *lc, const double *mg, size_t i, int *lo, int *hi)
{
    int past = 0, on = 0;
    for (size_t b = lc->first[i]; b < lc->first[i + 1]; b++)
        past += mg[b] > 0, on += mg[b] == 0;
    *lo = past, *hi = past + on;
}

/* Components of unknown mode take the one their margins admit, once it is one. */
static void adopt(dp_lcs_locator *lc, const double *mg)
{
    for (size_t i = 0; i < lc->m; i++) {
        int lo, hi;
        admitted(lc, mg, i, &lo, &hi);
        if (lc->mode[i] < 0 && lo == hi)
            lc->mode[i] = lo;
    }
}

void dp_lcs_locator_start(dp_lcs_locator *lc, const dp_lcs_stepper *st)
{
    dp_lcs_margins(st, lc->mg);
    for (size_t i = 0; i < lc->m; i++)
        lc->mode[i] = -1;
    adopt(lc, lc->mg);
}

/* Marks the components whose mode the margins mg do not admit (cross[i] = the direction); their count. */
static size_t changed(dp_lcs_locator *lc, const double *mg)
{
    size_t k = 0;
    for (size_t i = 0; i < lc->m; i++) {
        int lo, hi, md = lc->mode[i];
        admitted(lc, mg, i, &lo, &hi);
        lc->cross[i] = md < 0 || (md >= lo && md <= hi) ? 0 : md < lo ? 1 : -1;
        k += lc->cross[i] != 0;
    }
    return k;
}

/* The boundary component i crosses first in its direction: the one after its mode going up, before it going
 * down. */
static size_t crossing(const dp_lcs_locator *lc, size_t i)
{
    return lc->first[i] + (size_t)lc->mode[i] - (lc->cross[i] < 0);
}

/* Marks, for each component that changed, whether the side it leaves is a multiplier's (its margin there is
 * the θ-step's mean over the step: at the step's θ-point) and so is read from sub-steps of length σ/θ to
 * know it at σ; whether any is. */
static int mark_lags(dp_lcs_locator *lc)
{
    int any = 0;
    for (size_t i = 0; i < lc->m; i++) {
        lc->lag[i] = lc->cross[i] && lc->theta > 0 &&
                     dp_lcs_boundary_lag(lc->probe, crossing(lc, i)) == (lc->cross[i] < 0 ? 1 : -1);
        any |= lc->lag[i];
    }
    return any;
}

/* A sub-step of length s from (x at time t) into xs, us, ws, its margins into mg. DP_OK, or the status of
 * the discretization or of the step. */
static int probe(dp_lcs_locator *lc, double t, const double *x, double s, double *mg, const dp_stop *stop)
{
    dp_lcp_result res;
    int st = dp_lcs_stepper_set_h(lc->probe, s);
    if (st != DP_OK)
        return st;
    if (lc->pf) {
        for (size_t j = 0; j < lc->n; j++)
            lc->pt[j] = lc->sys.p[j] + dp_forcing_eval(&lc->pf[j], t + lc->theta * s);
        dp_lcs_stepper_set_p(lc->probe, lc->pt);
    }
    if (++lc->substeps % STOP_EVERY == 0 && dp_stop_now(stop))
        return DP_ECANCEL;
    memcpy(lc->xs, x, lc->n * sizeof *x);
    st = dp_lcs_step_until(lc->probe, lc->xs, lc->us, lc->ws, &res, stop);
    if (st == DP_OK)
        dp_lcs_margins(lc->probe, mg);
    return st;
}

/* Component i's margin of its crossing boundary, scaled to 1 on either side and signed > 0 on its mode's side:
 * from ml when the side it leaves lags (sub-steps of σ/θ), from ms otherwise (sub-steps of σ). */
static double scaled(const dp_lcs_locator *lc, size_t i, const double *ms, const double *ml)
{
    double r = (lc->lag[i] ? ml : ms)[crossing(lc, i)], v = r > 0 ? r / lc->pos[i] : r < 0 ? r / lc->neg[i] : 0;
    return lc->cross[i] > 0 ? -v : v;
}

/* The smallest scaled margin over the components that changed: > 0 while every one is in its mode. */
static double least(const dp_lcs_locator *lc, const double *ms, const double *ml)
{
    double g = INFINITY;
    for (size_t i = 0; i < lc->m; i++)
        if (lc->cross[i])
            g = fmin(g, scaled(lc, i, ms, ml));
    return g;
}

/* The margins σ into the rest of the step from the current state (time t): a sub-step of σ/θ into ml when a
 * changed component lags, then one of σ into ms (its state in xs, us, ws) when one does not or `state`. */
static int evaluate(dp_lcs_locator *lc, double t, double sigma, int state, const dp_stop *stop)
{
    int lags = 0, plain = state;
    for (size_t i = 0; i < lc->m; i++)
        lags |= lc->cross[i] && lc->lag[i], plain |= lc->cross[i] && !lc->lag[i];
    int s = lags ? probe(lc, t, lc->xc, sigma / lc->theta, lc->ml, stop) : DP_OK;
    return s == DP_OK && plain ? probe(lc, t, lc->xc, sigma, lc->ms, stop) : s;
}

typedef struct search {
    dp_lcs_locator *lc;
    double t, rest;
    const dp_stop *stop;
    int status;
} search;

/* The smallest scaled margin σ into the rest of the step; NaN (which ends the search) when a sub-step fails.
 * A sub-step that fails a few millionths into the rest is one too short for its LCP to be solved to its check
 * (D = 0: its matrix is O(σ)), met when a change follows another at once (a breakdown diode's u crossing its
 * interval in no time): the change is taken to be there, on the new side. */
static double least_at(void *ctx, double sigma)
{
    search *q = ctx;
    int st = evaluate(q->lc, q->t, sigma, 0, q->stop);
    if (st != DP_OK && st != DP_ECANCEL && st != DP_ENOMEM && sigma <= IMMEDIATE * q->rest)
        return -1;
    if (st != DP_OK) {
        q->status = st;
        return NAN;
    }
    return least(q->lc, q->lc->ms, q->lc->ml);
}

/* A state of n states and m components, and its margins, copied. */
static void copy_state(const dp_lcs_locator *lc, double *x, double *u, double *w, double *mg, const double *xf,
                       const double *uf, const double *wf, const double *mf)
{
    memcpy(x, xf, lc->n * sizeof *x);
    memcpy(u, uf, lc->m * sizeof *u);
    memcpy(w, wf, lc->m * sizeof *w);
    memcpy(mg, mf, lc->nb * sizeof *mg);
}

/* Where, within the rest of the step (the trial: xt, mt; me its lagging margins), the first of the marked
 * components leaves its mode: *at, with the state there in xs, us, ws and its margins in ms, ml. A component
 * already on or past its boundary at the current state changes at once; a trial that does not bracket the
 * change dates it at the trial's end. */
static int next_change(dp_lcs_locator *lc, double t, double rest, double tol, const dp_stop *stop, double *at)
{
    int now = 0;
    for (size_t i = 0; i < lc->m; i++) {
        if (!lc->cross[i])
            continue;
        size_t b = crossing(lc, i);
        double r0 = lc->mg[b], r1 = (lc->lag[i] ? lc->me : lc->mt)[b], big = fmax(r0, r1), small = fmin(r0, r1);
        lc->pos[i] = big > 0 ? big : 1, lc->neg[i] = small < 0 ? -small : 1;
        now |= !((lc->cross[i] > 0 ? -r0 : r0) > 0);
    }
    double g1 = least(lc, lc->mt, lc->me);
    if (now || !(rest > 0) || !(g1 < 0)) {
        *at = now || !(rest > 0) ? 0 : rest;
        const double *x = *at > 0 ? lc->xt : lc->xc, *u = *at > 0 ? lc->ut : lc->uc, *w = *at > 0 ? lc->wt : lc->wc;
        const double *mg = *at > 0 ? lc->mt : lc->mg;
        copy_state(lc, lc->xs, lc->us, lc->ws, lc->ms, x, u, w, mg);
        memcpy(lc->ml, *at > 0 ? lc->me : lc->mg, lc->nb * sizeof *lc->ml);
        return DP_OK;
    }
    search q = { lc, t, rest, stop, DP_OK };
    double s = dp_root_bracket(least_at, &q, 0, rest, least(lc, lc->mg, lc->mg), g1, tol, NULL);
    if (q.status != DP_OK)
        return q.status;
    *at = fmin(fmax(s, 0), rest);
    if (!(*at > tol)) {
        *at = 0;
        copy_state(lc, lc->xs, lc->us, lc->ws, lc->ms, lc->xc, lc->uc, lc->wc, lc->mg);
        memcpy(lc->ml, lc->mg, lc->nb * sizeof *lc->ml);
        return DP_OK;
    }
    return evaluate(lc, t, *at, 1, stop);    /* the search's last sub-step need not have been at s */
}

/* Component i's change to mode md at te, u and w its values there: appended, or merged with its change at
 * the same instant (one event from its first mode to its last; none when it is back where it was). */
static int record(dp_lcs_locator *lc, size_t i, int md, double te, double same, double u, double w)
{
    for (size_t k = lc->nev; k-- > 0;) {
        dp_lcs_event *e = &lc->ev[k];
        if (te - e->t > same)
            break;
        if (e->component != i)
            continue;
        if ((size_t)md == e->from) {
            memmove(e, e + 1, (lc->nev - k - 1) * sizeof *e);
            lc->nev--;
        } else {
            e->mode = (size_t)md, e->on = md > (int)e->from, e->u = u, e->w = w;
        }
        return DP_OK;
    }
    if (lc->nev == lc->evcap) {
        dp_lcs_event *ne = realloc(lc->ev, 2 * lc->evcap * sizeof *ne);
        if (ne == NULL)
            return DP_ENOMEM;
        lc->ev = ne, lc->evcap *= 2;
    }
    int from = lc->mode[i];
    lc->ev[lc->nev++] = (dp_lcs_event){ i, (size_t)from, (size_t)md, md > from, te, u, w };
    return DP_OK;
}

/* The marked components take the mode their margins mg admit nearest to theirs, dated te: the changes the
 * locator gave up on (a sub-step failed, or the step was split SPLITS_MAX times). */
static int unlocated(dp_lcs_locator *lc, const double *mg, double te, double same, const double *u, const double *w)
{
    for (size_t i = 0; i < lc->m; i++) {
        if (!lc->cross[i])
            continue;
        int lo, hi;
        admitted(lc, mg, i, &lo, &hi);
        int md = lc->cross[i] > 0 ? lo : hi, s = record(lc, i, md, te, same, u[i], w[i]);
        if (s != DP_OK)
            return s;
        lc->mode[i] = md;
    }
    return DP_OK;
}

/* The components that are on their boundary at the located instant (within TOGETHER of it, and the earliest
 * one in any case) change mode there. */
static int change_modes(dp_lcs_locator *lc, double te, double same)
{
    double g = fmax(least(lc, lc->ms, lc->ml), TOGETHER);
    for (size_t i = 0; i < lc->m; i++)    /* the marks of those that change later go (changed() sets them anew) */
        lc->cross[i] = lc->cross[i] && scaled(lc, i, lc->ms, lc->ml) <= g ? lc->cross[i] : 0;
    for (size_t i = 0; i < lc->m; i++) {
        if (!lc->cross[i])
            continue;
        int s = record(lc, i, lc->mode[i] + lc->cross[i], te, same, lc->us[i], lc->ws[i]);
        if (s != DP_OK)
            return s;
        lc->mode[i] += lc->cross[i];
    }
    return DP_OK;
}

/* How close two instants of a step from t of length h are taken to be one: a few ulps of the time, or
 * SHORTEST of the step when that is more. Changes are located to it. */
static double instant(double t, double h)
{
    return fmax(4 * 2.220446049250313e-16 * (fabs(t) + h), SHORTEST * h);
}

/* The nominal step's end taken, its changes dated there (the locator gave up). */
static int give_up(dp_lcs_locator *lc, double te, double same)
{
    memcpy(lc->mode, lc->mode0, lc->m * sizeof *lc->mode);
    lc->nev = 0;
    copy_state(lc, lc->xt, lc->ut, lc->wt, lc->mt, lc->xn, lc->un, lc->wn, lc->mn);
    changed(lc, lc->mt);
    return unlocated(lc, lc->mt, te, same, lc->ut, lc->wt);
}

/* A multiplier's margin is the nominal step's mean, at its θ-point, so a change in the step's last (1 - θ) h
 * does not show in it. Each component on a side that lags is extrapolated one step on from its last two
 * θ-points; where that reaches its boundary, a sub-step of h/θ (whose θ-point is the step's end) says whether
 * it changes in this step. The components that do are marked (with their margins at the end in me); their
 * count. */
static size_t late_changes(dp_lcs_locator *lc, double t, double h, const double *x, const dp_stop *stop, int *status)
{
    size_t suspects = 0, k = 0;
    *status = DP_OK;
    for (size_t i = 0; i < lc->m; i++) {
        lc->cross[i] = lc->lag[i] = 0;
        int md = lc->mode[i];
        for (int dir = -1; md >= 0 && dir <= 1 && lc->mp_ok && lc->theta > 0; dir += 2) {
            size_t b = lc->first[i] + (size_t)md - (dir < 0);
            if ((dir < 0 && md == 0) || (dir > 0 && b >= lc->first[i + 1]) ||
                dp_lcs_boundary_lag(lc->probe, b) != (dir < 0 ? 1 : -1))
                continue;
            double ahead = 2 * lc->mn[b] - lc->mp[b];
            if (dir < 0 ? !(ahead > 0) : !(ahead < 0))
                lc->cross[i] = dir, suspects++;
        }
    }
    if (suspects == 0)
        return 0;
    memcpy(lc->xc, x, lc->n * sizeof *x);
    if ((*status = probe(lc, t, lc->xc, h / lc->theta, lc->me, stop)) != DP_OK)
        return 0;
    for (size_t i = 0; i < lc->m; i++) {
        if (!lc->cross[i])
            continue;
        double r = lc->me[crossing(lc, i)];
        lc->cross[i] = (lc->cross[i] < 0 ? r < 0 : r > 0) ? lc->cross[i] : 0;
        lc->lag[i] = lc->cross[i] != 0;
        k += lc->cross[i] != 0;
    }
    return k;
}

/* The trial's margins for the components whose side lags: a sub-step of rest/θ from the current state. */
static int trial_lags(dp_lcs_locator *lc, double t, double rest, const dp_stop *stop)
{
    return mark_lags(lc) && rest > 0 ? probe(lc, t, lc->xc, rest / lc->theta, lc->me, stop) : DP_OK;
}

/* The step split at its changes: from the current state (xc at t + done), each change located, the modes
 * changed there and the rest of the step tried again, until a rest keeps every mode. The trial is then the
 * step's end. */
static int split(dp_lcs_locator *lc, double t, double h, int lags_marked, const dp_stop *stop)
{
    double same = instant(t, h), done = 0;
    int s = DP_OK;
    for (int splits = 0; s == DP_OK && (splits == 0 || changed(lc, lc->mt) > 0); splits++) {
        if (splits == SPLITS_MAX)
            return unlocated(lc, lc->mt, t + h, same, lc->ut, lc->wt);
        double at, rest = h - done;
        if (!(splits == 0 && lags_marked))
            s = trial_lags(lc, t + done, rest, stop);
        if (s == DP_OK && (s = next_change(lc, t + done, rest, same, stop, &at)) == DP_OK) {
            copy_state(lc, lc->xc, lc->uc, lc->wc, lc->mg, lc->xs, lc->us, lc->ws, lc->ms);
            done = at < rest ? done + at : h;
            s = change_modes(lc, t + done, same);
        }
        if (s == DP_OK && done < h && (s = probe(lc, t + done, lc->xc, h - done, lc->ms, stop)) == DP_OK)
            copy_state(lc, lc->xt, lc->ut, lc->wt, lc->mt, lc->xs, lc->us, lc->ws, lc->ms);
        else if (s == DP_OK)
            copy_state(lc, lc->xt, lc->ut, lc->wt, lc->mt, lc->xc, lc->uc, lc->wc, lc->mg);
    }
    return s;
}

int dp_lcs_step_located(dp_lcs_locator *lc, dp_lcs_stepper *nominal, double t, double h, double *x, double *u,
                        double *w, dp_lcp_result *res, const dp_stop *stop)
{
    size_t n = lc->n, m = lc->m;
    lc->nev = 0;
    memcpy(lc->xn, x, n * sizeof *x);
    int s = dp_lcs_step_until(nominal, lc->xn, lc->un, lc->wn, res, stop);
    if (s != DP_OK)
        return s;
    dp_lcs_margins(nominal, lc->mn);
    copy_state(lc, lc->xt, lc->ut, lc->wt, lc->mt, lc->xn, lc->un, lc->wn, lc->mn);
    int lags_marked = 0;
    size_t k = changed(lc, lc->mn);
    if (k == 0) {
        k = late_changes(lc, t, h, x, stop, &s);
        lags_marked = 1;
    }
    if (k > 0 && s == DP_OK) {
        memcpy(lc->mode0, lc->mode, m * sizeof *lc->mode);
        memcpy(lc->xc, x, n * sizeof *x);
        memcpy(lc->uc, u, m * sizeof *u);
        memcpy(lc->wc, w, m * sizeof *w);
        s = split(lc, t, h, lags_marked, stop);
    }
    if (s != DP_OK && s != DP_ECANCEL && s != DP_ENOMEM)   /* a sub-step failed: the nominal step, undated */
        s = give_up(lc, t + h, instant(t, h));
    if (s != DP_OK)
        return s;
    lc->mp_ok = lc->nev == 0 && k == 0;
    memcpy(lc->mp, lc->mn, lc->nb * sizeof *lc->mp);
    memcpy(x, lc->xt, n * sizeof *x);
    memcpy(u, lc->ut, m * sizeof *u);
    memcpy(w, lc->wt, m * sizeof *w);
    memcpy(lc->mg, lc->mt, lc->nb * sizeof *lc->mg);
    adopt(lc, lc->mg);
    return DP_OK;
}

const dp_lcs_event *dp_lcs_located_events(const dp_lcs_locator *lc, size_t *n)
{
    *n = lc->nev;
    return lc->ev;
}

unsigned long long dp_lcs_locator_substeps(const dp_lcs_locator *lc)
{
    return lc->substeps;
}
