/* src/core/studies/sweep_features.c - the features of one run (sweep.h), from its records in one pass.
 *
 * A response curve or a bifurcation diagram needs a few numbers per run, not its samples: the extremes of x
 * and v, the period, the fraction of time stuck, a Poincaré section. They are computed here from the records
 * the run makes at every step (the sweep sets every = 1), so they are located rather than sampled:
 *
 * - x's extremes: the samples' and events' x, and, on every step where v changes sign, the extremum of the
 *   cubic Hermite interpolant of that step (x and v at both ends: the step's own data), at the zero of its
 *   slope, a quadratic. Where a stick event is located the extremum is the event's x itself, exactly.
 * - v's extremes: the samples' v, and where a sample's v is a strict local extremum of three consecutive
 *   samples that all slip (no event among them), the vertex of the parabola through the three, moved by at
 *   most the larger of the two differences to the neighbours (a guard, never active on smooth data).
 * - the Poincaré section at t = after + k T: the Hermite interpolant of the step holding it (x and its slope
 *   for v), the sample itself where a section time is a sample's time.
 * - the period: the smallest p <= 32 such that the points of a sequence repeat after p of them to a
 *   relative 1e-6 of the motion's range, the sequence being the section's points (period p T), the section's
 *   events, or, without a section, the maxima of x (the mean of t[j+p] - t[j]).
 * - stick_fraction: the time between a stick event (or a sample that sticks) and the next slip, over
 *   t_end - after; exact where events are located, to a step otherwise.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/sweep.h"

static const char *const names[DP_FEATURE_COUNT] = { "x_max", "x_min", "v_max", "v_min", "amplitude", "period",
                                                     "stick_fraction" };

const char *dp_feature_name(int f)
{
    return f >= 0 && f < DP_FEATURE_COUNT ? names[f] : NULL;
}

int dp_feature_from_name(const char *name)
{
    for (int f = 0; f < DP_FEATURE_COUNT; f++)
        if (strcmp(names[f], name) == 0)
            return f;
    return -1;
}

void dp_sweep_plan_init(dp_sweep_plan *p)
{
    memset(p, 0, sizeof *p);
    p->features = (1u << DP_FEATURE_COUNT) - 1;
    p->section = DP_SECTION_NONE;
}

/* ---- the step's interpolant ---- */

/* x(s) = (2s^3 - 3s^2 + 1) x0 + (s^3 - 2s^2 + s) h v0 + (-2s^3 + 3s^2) x1 + (s^3 - s^2) h v1, s in [0, 1]. */
void dp_hermite_eval(const dp_traj_point *a, const dp_traj_point *b, double t, double *x, double *v)
{
    double h = b->t - a->t, s = (t - a->t) / h, s2 = s * s, s3 = s2 * s;
    *x = (2 * s3 - 3 * s2 + 1) * a->x + (s3 - 2 * s2 + s) * h * a->v + (-2 * s3 + 3 * s2) * b->x +
         (s3 - s2) * h * b->v;
    *v = ((6 * s2 - 6 * s) * (a->x - b->x)) / h + (3 * s2 - 4 * s + 1) * a->v + (3 * s2 - 2 * s) * b->v;
}

/* The slope is h v(s) with v(s) = A s^2 + B s + C, v(0) = v0, v(1) = v1 of opposite signs: one root in (0, 1),
 * found by the stable form of the quadratic formula; bisection if rounding puts it outside. */
double dp_hermite_turn(const dp_traj_point *a, const dp_traj_point *b)
{
    double h = b->t - a->t, d = (a->x - b->x) / h;
    double A = 6 * d + 3 * (a->v + b->v), B = -6 * d - 4 * a->v - 2 * b->v, C = a->v;
    double s = -1;
    if (fabs(A) <= 1e-14 * (fabs(B) + fabs(C))) {
        s = B != 0 ? -C / B : -1;
    } else {
        double disc = B * B - 4 * A * C;
        if (disc >= 0) {
            double q = -0.5 * (B + copysign(sqrt(disc), B));
            double r1 = q / A, r2 = q != 0 ? C / q : -1;
            s = r1 >= 0 && r1 <= 1 ? r1 : r2;
        }
    }
    if (!(s >= 0 && s <= 1)) { /* rounding: bisect the sign change instead */
        double lo = 0, hi = 1, flo = C;
        for (int i = 0; i < 60; i++) {
            double mid = 0.5 * (lo + hi), fm = (A * mid + B) * mid + C;
            if ((fm > 0) == (flo > 0)) {
                lo = mid;
                flo = fm;
            } else {
                hi = mid;
            }
        }
        s = 0.5 * (lo + hi);
    }
    return a->t + s * h;
}

/* ---- the walk ---- */

static void extreme_x(dp_features *f, double x)
{
    f->xmax = x > f->xmax ? x : f->xmax;
    f->xmin = x < f->xmin ? x : f->xmin;
}

static void extreme_v(dp_features *f, double v)
{
    f->vmax = v > f->vmax ? v : f->vmax;
    f->vmin = v < f->vmin ? v : f->vmin;
}

static void maximum(dp_features *f, double t, double x)
{
    size_t i = f->nmax % DP_FEATURES_MAXIMA;
    f->max_t[i] = t;
    f->max_x[i] = x;
    f->nmax++;
}

static void section_add(dp_features *f, double t, double x, double v)
{
    if (f->nsection < f->plan.section_count)
        f->section[f->nsection++] = (dp_section_point){ t, x, v };
}

/* Section times in (a.t, b.t] (or b.t itself for the first point), interpolated on the step. */
static void section_times(dp_features *f, const dp_traj_point *a, const dp_traj_point *b)
{
    while (f->k_next < f->plan.section_count) {
        double tk = f->plan.after + (double)f->k_next * f->plan.section_period;
        if (tk > b->t)
            return;
        if (tk == b->t) {
            section_add(f, b->t, b->x, b->v);
        } else if (a != NULL && tk > a->t) {
            double x, v;
            dp_hermite_eval(a, b, tk, &x, &v);
            section_add(f, tk, x, v);
        }
        f->k_next++; /* a time before the first point is skipped */
    }
}

/* The step a -> b (b.t > a.t): x's extremum inside it, and the maximum of x it holds. */
static void step_extremum(dp_features *f, const dp_traj_point *a, const dp_traj_point *b)
{
    double after = f->plan.after;
    if ((a->v > 0 && b->v < 0) || (a->v < 0 && b->v > 0)) {
        double ts = dp_hermite_turn(a, b), x, v;
        dp_hermite_eval(a, b, ts, &x, &v);
        if (ts >= after && isfinite(x)) {
            extreme_x(f, x);
            if (a->v > 0)
                maximum(f, ts, x);
        }
    } else if (a->v > 0 && b->v == 0 && b->t >= after) {
        maximum(f, b->t, b->x); /* arrives at a turn exactly: a stick event or a sample at v = 0 */
    }
}

/* The parabola's vertex through (p2, p1, b) where p1's v is a strict local extremum among slipping samples. */
static void v_vertex(dp_features *f, const dp_traj_point *b)
{
    const dp_traj_point *a = &f->p2, *m = &f->p1;
    if (f->npts < 2 || a->event || m->event || b->event || a->phase == DP_PHASE_STICK ||
        m->phase == DP_PHASE_STICK || b->phase == DP_PHASE_STICK || !(a->t < m->t && m->t < b->t))
        return;
    int is_max = m->v > a->v && m->v > b->v, is_min = m->v < a->v && m->v < b->v;
    if (!is_max && !is_min)
        return;
    double d1 = (m->v - a->v) / (m->t - a->t), d2 = (b->v - m->v) / (b->t - m->t), d12 = (d2 - d1) / (b->t - a->t);
    if (d12 == 0)
        return;
    double ts = 0.5 * (a->t + m->t) - d1 / (2 * d12);
    if (!(ts > a->t && ts < b->t) || ts < f->plan.after)
        return;
    double v = a->v + d1 * (ts - a->t) + d12 * (ts - a->t) * (ts - m->t);
    double guard = fmax(fabs(m->v - a->v), fabs(m->v - b->v));
    if (isfinite(v) && fabs(v - m->v) <= guard)
        extreme_v(f, v);
}

static void point(dp_features *f, dp_traj_point b)
{
    if (b.t >= f->plan.after) {
        if (!f->any) {
            f->any = 1;
            f->t_first = b.t;
            f->xmax = f->xmin = b.x;
            f->vmax = f->vmin = b.v;
        }
        extreme_x(f, b.x);
        extreme_v(f, b.v);
        f->t_last = b.t;
    }
    const dp_traj_point *a = f->npts ? &f->p1 : NULL;
    if (a != NULL && a->t >= f->plan.after && b.t - a->t > f->h)
        f->h = b.t - a->t;
    if (a != NULL && b.t > a->t)
        step_extremum(f, a, &b);
    if (f->plan.section == DP_SECTION_PERIOD && (a == NULL || b.t > a->t))
        section_times(f, a, &b);
    v_vertex(f, &b);
    f->p2 = f->p1;
    f->p1 = b;
    f->npts = f->npts < 2 ? f->npts + 1 : 2;
}

/* The phase since `mark` ends at t (its stick time counted from `after` on); the new one begins. */
static void phase_to(dp_features *f, double t, int phase)
{
    if (f->phase == DP_PHASE_STICK) {
        double lo = f->mark > f->plan.after ? f->mark : f->plan.after;
        if (t > lo)
            f->stick += t - lo;
    }
    f->mark = t;
    f->phase = phase;
}

static void event(dp_features *f, const dp_event *e, int one_mass)
{
    if (!one_mass && e->element != f->plan.element)
        return;
    if (e->kind == DP_EVENT_STICK || e->kind == DP_EVENT_SLIP)
        phase_to(f, e->t, e->kind == DP_EVENT_STICK ? DP_PHASE_STICK : DP_PHASE_SLIP);
    if (f->plan.section == DP_SECTION_EVENT && e->kind == f->plan.section_event && e->t >= f->plan.after)
        section_add(f, e->t, e->x, e->v);
    if (!one_mass)
        return; /* a network's event is an element's: its x, v are no node's */
    point(f, (dp_traj_point){ e->t, e->x, e->v, DP_PHASE_NONE, 1 });
    if (e->kind == DP_EVENT_IMPACT) /* the rate jumps: the steps on either side see their own side */
        point(f, (dp_traj_point){ e->t, e->x, e->v_after, DP_PHASE_NONE, 1 });
}

void dp_features_add(dp_features *f, const dp_record *r)
{
    if (r->type == DP_RECORD_SAMPLE) {
        const dp_sample *s = &r->u.sample;
        phase_to(f, s->t, (int)s->phase);
        point(f, (dp_traj_point){ s->t, s->x, s->v, (int)s->phase, 0 });
    } else if (r->type == DP_RECORD_ROW) {
        const dp_row *w = &r->u.row;
        int phase = f->col_phase >= 0 ? (int)w->val[f->col_phase] : DP_PHASE_NONE;
        phase_to(f, w->t, phase);
        if (f->col_x >= 0 && f->col_v >= 0)
            point(f, (dp_traj_point){ w->t, w->val[f->col_x], w->val[f->col_v], phase, 0 });
    } else if (r->type == DP_RECORD_EVENT) {
        event(f, &r->u.event, f->col_x == -2);
    }
}

/* Where group `name` puts entry `want` (a node or element index) in a row, or -1. */
static long column(const dp_columns *c, const char *name, size_t want)
{
    size_t off = 0;
    for (size_t g = 0; g < c->ngroups; off += c->group[g].n, g++) {
        if (strcmp(c->group[g].name, name) != 0)
            continue;
        for (size_t j = 0; j < c->group[g].n; j++)
            if (c->group[g].index == NULL ? j == want : c->group[g].index[j] == want)
                return (long)(off + j);
    }
    return -1;
}

int dp_features_init(dp_features *f, const dp_sweep_plan *plan, const dp_columns *cols)
{
    memset(f, 0, sizeof *f);
    f->plan = *plan;
    f->phase = DP_PHASE_NONE;
    if (plan->section != DP_SECTION_NONE && plan->section_count > 0) {
        f->section = malloc(plan->section_count * sizeof *f->section);
        if (f->section == NULL)
            return DP_ENOMEM;
    }
    if (cols == NULL) {
        f->col_x = f->col_v = f->col_phase = -2; /* the one-mass model: samples */
    } else {
        f->col_x = column(cols, "x", plan->node);
        f->col_v = column(cols, "v", plan->node);
        f->col_phase = column(cols, "phase", plan->element);
    }
    return DP_OK;
}

void dp_features_clear(dp_features *f)
{
    free(f->section);
    f->section = NULL;
    f->nsection = 0;
}
