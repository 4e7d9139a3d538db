/* tests/test_lcs.c - the θ-step of linear complementarity systems on Cibulka 2014's circuits against
 * closed forms derived from the text: the series RLC with an ideal diode (Example 1.9: a damped oscillation
 * until the current vanishes, then blocked for good), the same with a breakdown diode (an interval law), and
 * the four-diode bridge (Example 1.10, its own matrices: with ideal diodes the load always conducts, so the
 * tank is a parallel RLC). Tolerances: O(h^2) for θ = 1/2 where u = 0 (the diode conducts freely), O(h)
 * after a switch (it lands on a step boundary) and wherever u != 0 (u is taken at the step's end, docs/systems.md
 * §5, a backward Euler treatment of B u). Then what the step refuses and where it says the blame lies (every
 * product it forms from the data checked finite), and a step whose LCP pivots for long (Murty 1978's matrix
 * as D) ended by the stop hook or by Lemke's pivot limit, x unchanged.
 * Then mode changes located inside the step (lcs_events.c): the half-wave rectifier against its piecewise
 * closed form (state error and switch times O(h^2) at θ = 1/2, ratios near 4 as h halves), the breakdown
 * RLC located against plain θ-steps (first order at its switches), no event where nothing switches (the
 * located steps then the plain ones bit for bit), the bridge's four at π, and magnitudes 1e±150, 1e±300.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "dashpot/lcs.h"
#include "dashpot/status.h"

#include "check.h"

/* The series circuit: R = 0.5, L = 1, C = 0.25, no source; x = (charge, current), i(0) = 1, q(0) = 0. */
static const double R = 0.5, L = 1, Cap = 0.25, H = 1e-4;

static double alpha(void) { return R / (2 * L); }
static double omega_d(void) { return sqrt(1 / (L * Cap) - alpha() * alpha()); }
/* q(t) = (i0/wd) e^{-at} sin(wd t), i(t) = e^{-at} (cos wd t - (a/wd) sin wd t) with i0 = 1 */
static double charge(double t) { return exp(-alpha() * t) * sin(omega_d() * t) / omega_d(); }
static double current(double t)
{
    return exp(-alpha() * t) * (cos(omega_d() * t) - alpha() / omega_d() * sin(omega_d() * t));
}
/* the current's first zero: tan(wd t*) = wd / a */
static double t_star(void) { return atan2(omega_d(), alpha()) / omega_d(); }

static dp_lcs_stepper *series(int breakdown, double vb)
{
    static const double A[4] = { 0, 1, -1 / (0.25 * 1), -0.5 / 1 };
    /* ideal (Ex. 1.9): B = b = (0, 1/L), C = (0, 1), u = -v_D, 0 <= u ⊥ i >= 0.
     * breakdown: u = v_D in [-Vb, 0], B = -b, w = -i ∈ -N_K(u) (the seed's i ∈ N_K(u)). */
    static const double Bi[2] = { 0, 1 / 1.0 }, Ci[2] = { 0, 1 }, Bb[2] = { 0, -1 / 1.0 }, Cb[2] = { 0, -1 };
    static const double D[1] = { 0 }, p[2] = { 0, 0 }, q[1] = { 0 };
    dp_lcs_law law = { breakdown ? DP_LCS_INTERVAL : DP_LCS_COMPLEMENTARITY, -vb, 0 };
    dp_lcs sys = { 2, 1, A, breakdown ? Bb : Bi, breakdown ? Cb : Ci, D, p, q, &law };
    int s;
    dp_lcs_stepper *st = dp_lcs_stepper_alloc(&sys, H, 0.5, &s);
    CHECK(st != NULL && s == DP_OK, "stepper: %d", s);
    return st;
}

static void run_to(dp_lcs_stepper *st, double *x, double *u, double *w, double *t, double until)
{
    dp_lcp_result res;
    while (*t < until - H / 2) {
        int s = dp_lcs_step(st, x, u, w, &res);
        CHECK(s == DP_OK, "step at t = %g: %d", *t, s);
        *t += H;
    }
}

static void test_rlc_ideal_diode(void **state)
{
    (void)state;
    dp_lcs_stepper *st = series(0, 0);
    double x[2] = { 0, 1 }, u[1], w[1], t = 0;
    run_to(st, x, u, w, &t, 0.5);
    NEAR(x[0], charge(0.5), 1e-8); /* O(h^2): 1e-8 at h = 1e-4 */
    NEAR(x[1], current(0.5), 1e-8);
    NEAR(u[0], 0, 0);              /* conducting: no voltage across the diode */
    double ts = t_star(), qs = charge(ts);
    CHECK(qs > 0.4, "the capacitor is charged when the current stops: q* = %g", qs);
    run_to(st, x, u, w, &t, ts + 0.01);
    double umax = 0;
    for (int k = 0; k < 200; k++) { /* blocked for good: current zero at every step to t = 4 */
        run_to(st, x, u, w, &t, t + 0.0165);
        CHECK(fabs(x[1]) <= 1e-12, "current %g at t = %g", x[1], t);
        NEAR(x[0], qs, 2e-4);      /* O(h) from the step boundary */
        umax = fmax(umax, u[0]);
    }
    NEAR(u[0], qs / Cap, 1e-3);    /* the diode holds the capacitor voltage: -v_D = q* / C */
    dp_lcp_theory th;
    CHECK(dp_lcp_theory_of(dp_lcs_step_matrix(st), &th) == DP_OK, "theory");
    CHECK(th.pd_symmetric && th.p_matrix == 1, "the step matrix h W_22 / L > 0");
    /* M = h C W B = h W_22 / L, W_22 = 1 / det(I - hθA) = 1 / (1 + hθR/L + h^2 θ^2 / (LC)) */
    NEAR(th.mu, H / L / (1 + H * 0.5 * R / L + H * H * 0.25 / (L * Cap)), 1e-15);
    dp_lcs_stepper_free(st);
}

/* Breakdown at Vb: with Vb = 10 > q* / C the diode blocks as the ideal one, holding v_D = -q* / C; with
 * Vb = 0.5 < q* / C = 1.93 the current reverses at t*: i = y', y = q - C Vb, y(t*) = q* - C Vb, i(t*) = 0:
 * y(s) = y* e^{-as} (cos wd s + (a/wd) sin wd s), i(s) = -y* (w0^2/wd) e^{-as} sin wd s, s = t - t*. */
static void test_rlc_breakdown_diode(void **state)
{
    (void)state;
    double ts = t_star(), qs = charge(ts);
    dp_lcs_stepper *st = series(1, 10);
    double x[2] = { 0, 1 }, u[1], w[1], t = 0;
    run_to(st, x, u, w, &t, 3);
    CHECK(fabs(x[1]) <= 1e-12, "blocked: current %g", x[1]);
    NEAR(u[0], -qs / Cap, 1e-3);
    dp_lcs_stepper_free(st);

    double vb = 0.5, ys = qs - Cap * vb, wd = omega_d(), a = alpha(), w02 = 1 / (L * Cap);
    st = series(1, vb);
    x[0] = 0, x[1] = 1, t = 0;
    double s = M_PI / (2 * wd);
    run_to(st, x, u, w, &t, ts + s);
    NEAR(x[1], -ys * w02 / wd * exp(-a * s) * sin(wd * s), 2e-3);
    NEAR(x[0], Cap * vb + ys * exp(-a * s) * (cos(wd * s) + a / wd * sin(wd * s)), 2e-3);
    NEAR(u[0], -vb, 1e-12); /* in breakdown: v_D = -Vb */
    dp_lcs_stepper_free(st);
}

/* Example 1.10 with the seed's A, B, C, D (R = 1, L = 1, C = 0.5): x = (v_C, i_L). With ideal diodes the
 * bridge always conducts, the load current is v_C / R in the tank's frame, so C v_C' = -i_L - v_C / R,
 * L i_L' = v_C: a parallel RLC, v_C(t) = -(i0/(C wd)) e^{-at} sin wd t with a = 1/(2RC), w0^2 = 1/(LC). */
static void test_bridge(void **state)
{
    (void)state;
    const double r = 1, l = 1, c = 0.5;
    double A[4] = { 0, -1 / c, 1 / l, 0 };
    double B[8] = { 0, 0, -1 / c, 1 / c, 0, 0, 0, 0 };
    double C[8] = { 0, 0, 0, 0, -1, 0, 1, 0 };
    double D[16] = { 1 / r, 1 / r, -1, 0, 1 / r, 1 / r, 0, -1, 1, 0, 0, 0, 0, 1, 0, 0 };
    double p[2] = { 0, 0 }, q[4] = { 0, 0, 0, 0 };
    dp_lcs_law law[4] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
    dp_lcs sys = { 2, 4, A, B, C, D, p, q, law };
    int s;
    dp_lcs_stepper *st = dp_lcs_stepper_alloc(&sys, H, 0.5, &s);
    CHECK(st != NULL, "stepper %d", s);
    double x[2] = { 0, 1 }, u[4], w[4], t = 0, a = 1 / (2 * r * c), wd = sqrt(1 / (l * c) - a * a);
    int positive = 0, negative = 0;
    for (int k = 1; k <= 40; k++) {
        run_to(st, x, u, w, &t, 0.1 * k);
        double vc = -(1 / (c * wd)) * exp(-a * t) * sin(wd * t);
        NEAR(x[0], vc, 5e-5); /* first order: u is taken at the step's end (measured 1.6e-5 at h = 1e-4) */
        double iR = u[2] + w[0]; /* i_DF1 + i_DR1: through the load, one way whatever the sign of v_C */
        NEAR(iR, fabs(x[0]) / r, 1e-9);
        positive += x[0] > 1e-3, negative += x[0] < -1e-3;
    }
    CHECK(positive > 3 && negative > 3, "v_C takes both signs (%d, %d): rectified", positive, negative);
    dp_lcs_stepper_free(st);
}

static void test_bad_input(void **state)
{
    (void)state;
    double A[1] = { 0 }, B[1] = { 1 }, C[1] = { 1 }, D[1] = { 0 }, p[1] = { 0 }, q[1] = { 0 };
    dp_lcs_law law = { DP_LCS_INTERVAL, 1, -1 };
    dp_lcs sys = { 1, 1, A, B, C, D, p, q, &law };
    int s;
    CHECK(dp_lcs_stepper_alloc(&sys, 0.1, 0.5, &s) == NULL && s == DP_EINVAL, "interval with lo > hi");
    law.hi = 2;
    CHECK(dp_lcs_stepper_alloc(&sys, -0.1, 0.5, &s) == NULL && s == DP_EINVAL, "negative step");
    A[0] = 10; /* I - h θ A = 1 - 0.2 * 0.5 * 10 = 0 */
    CHECK(dp_lcs_stepper_alloc(&sys, 0.2, 0.5, &s) == NULL && s == DP_EINVAL, "singular I - hθA");
    /* No solution: D = -1, q = -1, x = 0 give w = -1 - u (1 + h C W B = 1 + 0.1 u... the step's matrix is
     * D + h C B = -1 + 0.1) so w = -1 - 0.9 u < 0 for every u >= 0: reported, x unchanged. */
    A[0] = 0, D[0] = -1, q[0] = -1, law.kind = DP_LCS_COMPLEMENTARITY;
    dp_lcs_stepper *st = dp_lcs_stepper_alloc(&sys, 0.1, 0.5, &s);
    CHECK(st != NULL, "stepper");
    double x[1] = { 0 }, u[1], w[1];
    dp_lcp_result res;
    CHECK(dp_lcs_step(st, x, u, w, &res) == DP_ESOLVE && x[0] == 0, "no solution: DP_ESOLVE, x unchanged");
    dp_lcs_stepper_free(st);
}

/* Each product the step forms from the data, made to overflow in turn: refused, and blamed on its member. */
static void test_located_refusals(void **state)
{
    (void)state;
    struct { double A, B, C, D, p, h; const char *where; } cases[] = {
        { 1e308, 1, 1, 0, 0, 10, "/model/lcs/A" },   /* h θ A */
        { 0, 1e308, 1, 0, 0, 10, "/model/lcs/B" },   /* h W B */
        { 0, 1e300, 1e308, 0, 0, 1, "/model/lcs/C" }, /* C h W B */
        { 0, 1, 1e308, 1e308, 0, 1, "/model/lcs/D" }, /* D + h C W B */
        { 0, 1, 1, 0, 1e308, 10, "/model/lcs/p" },   /* h W p */
        { 2, 1, 1, 0, 0, 1, "/solver/dt" },          /* I - h θ A = 0 */
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        double A[1] = { cases[k].A }, B[1] = { cases[k].B }, C[1] = { cases[k].C }, D[1] = { cases[k].D };
        double p[1] = { cases[k].p }, q[1] = { 0 };
        dp_lcs_law law = { DP_LCS_COMPLEMENTARITY, 0, 0 };
        dp_lcs sys = { 1, 1, A, B, C, D, p, q, &law };
        int s;
        const char *where, *why;
        dp_lcs_stepper *st = dp_lcs_stepper_alloc_why(&sys, cases[k].h, 0.5, &s, &where, &why);
        CHECK(st == NULL && s == DP_EINVAL && strcmp(where, cases[k].where) == 0, "case %zu: %s, got %s (%s)", k,
              cases[k].where, where, why);
        if (strcmp(where, "/model/lcs/C") == 0 || strcmp(where, "/model/lcs/D") == 0)
            continue; /* the others scale with h: */
        st = dp_lcs_stepper_alloc(&sys, cases[k].h / 1e10, 0.5, &s);
        CHECK(st != NULL, "case %zu with a step 1e10 times shorter: accepted", k);
        dp_lcs_stepper_free(st);
    }
}

/* D = Murty 1978's matrix (unit diagonal, 3/2 below: Lemke needs 2^m pivots), q = -e, B = C = 0: the step's
 * LCP is D's alone. */
static dp_lcs_stepper *murty_system(size_t m, double *store)
{
    double *A = store, *B = A + 1, *C = B + m, *D = C + m, *p = D + m * m, *q = p + 1;
    dp_lcs_law *law = (dp_lcs_law *)(q + m);
    A[0] = 0, p[0] = 0;
    for (size_t i = 0; i < m; i++) {
        B[i] = C[i] = 0, q[i] = -1;
        law[i] = (dp_lcs_law){ DP_LCS_COMPLEMENTARITY, 0, 0 };
        for (size_t j = 0; j < m; j++)
            D[i * m + j] = i == j ? 1 : j < i ? 1.5 : 0;
    }
    dp_lcs sys = { 1, m, A, B, C, D, p, q, law };
    int s;
    dp_lcs_stepper *st = dp_lcs_stepper_alloc(&sys, 0.1, 0.5, &s);
    CHECK(st != NULL, "stepper %d", s);
    return st;
}

static int stop_second(void *ctx)
{
    return ++*(int *)ctx >= 2;
}

static void test_long_step_stopped(void **state)
{
    (void)state;
    size_t m = 200;
    double *store = malloc((2 + 3 * m + m * m) * sizeof(double) + m * sizeof(dp_lcs_law));
    dp_lcs_stepper *st = murty_system(m, store);
    double x[1] = { 7 }, u[200], w[200];
    dp_lcp_result res;
    int asked = 0;
    dp_stop stop = { stop_second, &asked };
    CHECK(dp_lcs_step_until(st, x, u, w, &res, &stop) == DP_ECANCEL && asked == 2 && x[0] == 7,
          "m = 200: DP_ECANCEL at the second question (%d), x unchanged (%g)", asked, x[0]);
    dp_lcs_stepper_free(st);
    st = murty_system(13, store);
    CHECK(dp_lcs_step(st, x, u, w, &res) == DP_ELIMIT && res.pivots == dp_lcp_pivot_limit(13) && x[0] == 7,
          "m = 13: Lemke's limit, %zu pivots, x unchanged", res.pivots);
    dp_lcs_stepper_free(st);
    st = murty_system(10, store);
    CHECK(dp_lcs_step(st, x, u, w, &res) == DP_OK && res.pivots == 1024 && u[0] == 1 && u[1] == 0,
          "m = 10: solved in 2^10 pivots, u = e_1");
    dp_lcs_stepper_free(st);
    free(store);
}

/* ---- mode changes located inside the step ------------------------------------------------------------
 * The half-wave rectifier: a source e(t) = V sin(wt), an ideal diode, L and R in series into a capacitor C
 * with a load R_L across it; x = (v, i) (the capacitor's voltage, the diode's current), u = -v_D ⊥ w = i:
 *     C v' = i - v / R_L,   L i' = e - R i - v + u,   0 <= u ⊥ i >= 0.
 * Each mode is a linear ODE with a closed form: conducting (u = 0) x' = A x + b e(t), solved by the matrix
 * exponential of A and the sinusoid's particular solution; blocking (i = 0) v = v0 e^{-(t - t0)/(R_L C)},
 * u = v - e >= 0. The diode blocks when i reaches 0 and unblocks when e rises to v: roots of these closed
 * forms, bracketed on a fine grid and bisected to rounding, give the reference switch times. */
#include <complex.h>

typedef struct rectifier { double R, L, C, RL, V, w; } rectifier;

static const rectifier RECT = { 0.2, 0.1, 1, 2, 1, 2 };

#define SEG_MAX 64

/* The reference: its pieces (start, state there, conducting or not), from t = 0 to past t_end. */
typedef struct reference {
    rectifier c;
    size_t n;
    double t0[SEG_MAX], x0[SEG_MAX][2];
    int on[SEG_MAX];
} reference;

static void rect_matrix(const rectifier *c, double A[4])
{
    A[0] = -1 / (c->RL * c->C), A[1] = 1 / c->C, A[2] = -1 / c->L, A[3] = -c->R / c->L;
}

/* The particular solution of x' = A x + (0, V sin(wt) / L): Im(X e^{iwt}), (iw I - A) X = (0, V / L). */
static void particular(const rectifier *c, double t, double xp[2])
{
    double A[4];
    rect_matrix(c, A);
    double complex a = I * c->w - A[0], b = -A[1], cc = -A[2], d = I * c->w - A[3], det = a * d - b * cc;
    double complex f = c->V / c->L, X0 = -b * f / det, X1 = a * f / det, e = cexp(I * c->w * t);
    xp[0] = cimag(X0 * e), xp[1] = cimag(X1 * e);
}

/* e^{A s} y for the 2 x 2 A: (e^{l1 s}(A - l2 I) - e^{l2 s}(A - l1 I)) / (l1 - l2), l1 != l2 its eigenvalues. */
static void propagate(const double A[4], double s, const double y[2], double out[2])
{
    double tr = A[0] + A[3], det = A[0] * A[3] - A[1] * A[2];
    double complex disc = csqrt(tr * tr / 4 - det), l1 = tr / 2 + disc, l2 = tr / 2 - disc;
    double complex e1 = cexp(l1 * s), e2 = cexp(l2 * s), k = 1 / (l1 - l2);
    for (int r = 0; r < 2; r++) {
        double complex acc = 0;
        for (int j = 0; j < 2; j++) {
            double a = A[2 * r + j], id = r == j;
            acc += k * (e1 * (a - l2 * id) - e2 * (a - l1 * id)) * y[j];
        }
        out[r] = creal(acc);
    }
}

/* The state at t of the piece that starts at t0 in x0. */
static void piece_at(const rectifier *c, int on, double t0, const double x0[2], double t, double x[2])
{
    if (!on) {
        x[0] = x0[0] * exp(-(t - t0) / (c->RL * c->C)), x[1] = 0;
        return;
    }
    double A[4], p0[2], p1[2], y[2];
    rect_matrix(c, A);
    particular(c, t0, p0);
    particular(c, t, p1);
    y[0] = x0[0] - p0[0], y[1] = x0[1] - p0[1];
    propagate(A, t - t0, y, x);
    x[0] += p1[0], x[1] += p1[1];
}

/* The switch function of a piece: the current while conducting, v - e while blocking (both > 0 inside). */
static double switch_fn(const rectifier *c, int on, double t0, const double x0[2], double t)
{
    double x[2];
    piece_at(c, on, t0, x0, t, x);
    return on ? x[1] : x[0] - c->V * sin(c->w * t);
}

static void reference_build(reference *ref, const rectifier *c, double t_end)
{
    *ref = (reference){ .c = *c, .n = 1, .on = { 1 } };   /* from rest at e = 0 rising: it conducts at once */
    for (double t = 0, dt = 1e-4; ref->n < SEG_MAX;) {
        size_t k = ref->n - 1;
        int on = ref->on[k];
        double a = t + dt;
        while (a < t_end + 1 && switch_fn(c, on, ref->t0[k], ref->x0[k], a) > 0)
            a += dt;
        if (a >= t_end + 1)
            return;
        double lo = a - dt, hi = a;
        while (hi - lo > 4e-16 * hi) {
            double mid = (lo + hi) / 2;
            *(switch_fn(c, on, ref->t0[k], ref->x0[k], mid) > 0 ? &lo : &hi) = mid;
        }
        t = (lo + hi) / 2;
        piece_at(c, on, ref->t0[k], ref->x0[k], t, ref->x0[k + 1]);
        if (on)
            ref->x0[k + 1][1] = 0;
        ref->t0[k + 1] = t, ref->on[k + 1] = !on, ref->n++;
    }
}

static void reference_at(const reference *ref, double t, double x[2])
{
    size_t k = ref->n - 1;
    while (k > 0 && ref->t0[k] > t)
        k--;
    piece_at(&ref->c, ref->on[k], ref->t0[k], ref->x0[k], t, x);
}

typedef struct rect_run {
    double err;                /* the largest |x - x_ref| over the sample times */
    double t_ev[SEG_MAX];      /* the located switch times */
    int on_ev[SEG_MAX];
    size_t nev;
} rect_run;

/* The rectifier from rest to t_end by steps h at θ = 1/2, the error taken every `sample` time units; with
 * `locate` its switches located (their times recorded), else plain θ-steps. The state is scaled by `scale`
 * (V and x0 times it: the system is linear, so the run should be too). */
static rect_run rectifier_run(const rectifier *c, double h, double t_end, double sample, int locate, double scale,
                              const reference *ref)
{
    double A[4], B[2] = { 0, 1 / c->L }, C[2] = { 0, 1 }, D[1] = { 0 }, p[2] = { 0, 0 }, q[1] = { 0 };
    rect_matrix(c, A);
    dp_forcing pf[2] = { { .kind = DP_FORCING_NONE },
                         { .kind = DP_FORCING_HARMONIC, .amplitude = scale * c->V / c->L, .omega = c->w,
                           .phase = -M_PI / 2 } };
    dp_lcs_law law = { DP_LCS_COMPLEMENTARITY, 0, 0 };
    dp_lcs sys = { 2, 1, A, B, C, D, p, q, &law };
    int s;
    dp_lcs_stepper *st = dp_lcs_stepper_alloc(&sys, h, 0.5, &s), *alg = dp_lcs_stepper_alloc(&sys, 0, 1, &s);
    dp_lcs_locator *lc = dp_lcs_locator_alloc(&sys, pf, h, 0.5, &s);
    CHECK(st && alg && lc, "steppers and locator: %d", s);
    double x[2] = { 0, 0 }, u[1], w[1], xr[2], pt[2];
    dp_lcp_result res;
    CHECK(dp_lcs_step(alg, x, u, w, &res) == DP_OK, "the algebraic part at t = 0");
    dp_lcs_locator_start(lc, alg);
    rect_run out = { 0 };
    long steps = lround(t_end / h), every = lround(sample / h);
    for (long k = 0; k < steps; k++) {
        double t = (double)k * h;
        pt[0] = 0, pt[1] = dp_forcing_eval(&pf[1], t + 0.5 * h);
        dp_lcs_stepper_set_p(st, pt);
        s = locate ? dp_lcs_step_located(lc, st, t, h, x, u, w, &res, NULL) : dp_lcs_step(st, x, u, w, &res);
        CHECK(s == DP_OK, "step from t = %g: %d", t, s);
        size_t ne;
        const dp_lcs_event *ev = dp_lcs_located_events(lc, &ne);
        for (size_t j = 0; locate && j < ne && out.nev < SEG_MAX; j++)
            out.t_ev[out.nev] = ev[j].t, out.on_ev[out.nev++] = ev[j].on;
        if ((k + 1) % every == 0 && ref) {
            reference_at(ref, (double)(k + 1) * h, xr);
            out.err = fmax(out.err, fmax(fabs(x[0] / scale - xr[0]), fabs(x[1] / scale - xr[1])));
        }
    }
    dp_lcs_locator_free(lc);
    dp_lcs_stepper_free(alg);
    dp_lcs_stepper_free(st);
    return out;
}

static void test_rectifier_convergence(void **state)
{
    (void)state;
    const double t_end = 6, h0 = 0.01;
    static reference ref;
    reference_build(&ref, &RECT, t_end);
    size_t nswitch = 0;
    while (nswitch + 1 < ref.n && ref.t0[nswitch + 1] <= t_end)
        nswitch++;
    rect_run loc[4];
    double tev[4];
    for (int k = 0; k < 4; k++) {
        double h = h0 / (1 << k);
        loc[k] = rectifier_run(&RECT, h, t_end, 0.05, 1, 1, &ref);
        CHECK(loc[k].nev == nswitch, "h = %g: %zu events, the reference switches %zu times", h, loc[k].nev, nswitch);
        tev[k] = 0;
        for (size_t j = 0; j < nswitch; j++) {   /* blocks (on: u = -v_D > 0), conducts (off), in turn */
            CHECK(loc[k].on_ev[j] == !ref.on[j + 1], "event %zu: %s", j, loc[k].on_ev[j] ? "on" : "off");
            tev[k] = fmax(tev[k], fabs(loc[k].t_ev[j] - ref.t0[j + 1]));
        }
    }
    for (int k = 0; k < 3; k++) {
        double r = loc[k].err / loc[k + 1].err, rt = tev[k] / tev[k + 1];
        CHECK(r >= 3.5 && r <= 4.5, "state error ratio %.3f at h = %g (errors %.3e, %.3e)", r, h0 / (1 << k), loc[k].err,
              loc[k + 1].err);
        CHECK(rt >= 3.5 && rt <= 4.5, "switch time error ratio %.3f at h = %g (%.3e, %.3e)", rt, h0 / (1 << k), tev[k],
              tev[k + 1]);
    }
    CHECK(tev[3] < 1e-6, "the switch times to %.3e at h = %g: O(h^2)", tev[3], h0 / 8);
}

/* The breakdown diode's RLC (Vb = 0.5, as test_rlc_breakdown_diode): forward until t* (u = 0), then at once
 * in breakdown (u = -Vb: u jumps across its interval while the current passes through 0 with a slope, so the
 * current's derivative jumps by Vb/L) for half a damped period, to t2 = t* + π/wd, where the current is 0
 * again and the capacitor, swung past 0 (q2 < 0), drives it forward: u jumps back to 0, for the next half
 * period (to t2 + π/wd = 3.9): q = q2 e^{-as}(cos wd s + (a/wd) sin wd s), i = -q2 (w0^2/wd) e^{-as} sin wd s.
 * Without location the steps that hold t* and t2 take the new u over all of them: an O(h) error in the
 * current, first order; located, second order. */
static void breakdown_reference(double t, double x[2])
{
    double vb = 0.5, ts = t_star(), qs = charge(ts), ys = qs - Cap * vb, wd = omega_d(), a = alpha();
    double w02 = 1 / (L * Cap), half = M_PI / wd, s = t - ts;
    if (t <= ts) {
        x[0] = charge(t), x[1] = current(t);
    } else if (s <= half) {
        x[0] = Cap * vb + ys * exp(-a * s) * (cos(wd * s) + a / wd * sin(wd * s));
        x[1] = -ys * w02 / wd * exp(-a * s) * sin(wd * s);
    } else {
        double q2 = Cap * vb - ys * exp(-a * half);
        s -= half;
        x[0] = q2 * exp(-a * s) * (cos(wd * s) + a / wd * sin(wd * s));
        x[1] = -q2 * w02 / wd * exp(-a * s) * sin(wd * s);
    }
}

typedef struct run_result { double err; size_t nev; double t_ev[8]; size_t mode[8]; } run_result;

static run_result breakdown_run(double h, int locate)
{
    static const double A[4] = { 0, 1, -4, -0.5 }, B[2] = { 0, -1 }, C[2] = { 0, -1 }, D[1] = { 0 };
    static const double p[2] = { 0, 0 }, q[1] = { 0 };
    dp_lcs_law law = { DP_LCS_INTERVAL, -0.5, 0 };
    dp_lcs sys = { 2, 1, A, B, C, D, p, q, &law };
    int s;
    dp_lcs_stepper *st = dp_lcs_stepper_alloc(&sys, h, 0.5, &s), *alg = dp_lcs_stepper_alloc(&sys, 0, 1, &s);
    dp_lcs_locator *lc = dp_lcs_locator_alloc(&sys, NULL, h, 0.5, &s);
    CHECK(st && alg && lc, "steppers and locator: %d", s);
    double x[2] = { 0, 1 }, u[1], w[1], xr[2];
    dp_lcp_result res;
    CHECK(dp_lcs_step(alg, x, u, w, &res) == DP_OK, "the algebraic part at t = 0");
    dp_lcs_locator_start(lc, alg);
    run_result out = { 0 };
    long steps = lround(3.5 / h), every = lround(0.05 / h);
    for (long k = 0; k < steps; k++) {
        s = locate ? dp_lcs_step_located(lc, st, (double)k * h, h, x, u, w, &res, NULL) : dp_lcs_step(st, x, u, w, &res);
        CHECK(s == DP_OK, "step %ld: %d", k, s);
        size_t ne;
        const dp_lcs_event *ev = dp_lcs_located_events(lc, &ne);
        for (size_t j = 0; locate && j < ne && out.nev < 8; j++)
            out.t_ev[out.nev] = ev[j].t, out.mode[out.nev++] = ev[j].mode;
        if ((k + 1) % every == 0) {
            breakdown_reference((double)(k + 1) * h, xr);
            out.err = fmax(out.err, fmax(fabs(x[0] - xr[0]), fabs(x[1] - xr[1])));
        }
    }
    dp_lcs_locator_free(lc);
    dp_lcs_stepper_free(alg);
    dp_lcs_stepper_free(st);
    return out;
}

static void test_breakdown_contrast(void **state)
{
    (void)state;
    run_result loc[4], plain[4];
    double ts = t_star(), t2 = ts + M_PI / omega_d();
    for (int k = 0; k < 4; k++) {
        double h = 0.01 / (1 << k);
        loc[k] = breakdown_run(h, 1);
        plain[k] = breakdown_run(h, 0);
        CHECK(loc[k].nev == 2 && loc[k].mode[0] == 0 && loc[k].mode[1] == 2, "h = %g: forward -> breakdown (one "
              "event through the interval) -> forward; %zu events", h, loc[k].nev);
        CHECK(fabs(loc[k].t_ev[0] - ts) < h * h && fabs(loc[k].t_ev[1] - t2) < h * h,
              "h = %g: the switches at %.12f, %.12f, the reference's %.12f, %.12f: O(h^2)", h, loc[k].t_ev[0],
              loc[k].t_ev[1], ts, t2);
    }
    for (int k = 0; k < 3; k++) {
        double r = loc[k].err / loc[k + 1].err;
        CHECK(r >= 3.5 && r <= 4.5, "located: ratio %.3f at h = %g", r, 0.01 / (1 << k));
    }
    /* Plain steps: first order (their ratios wander with where the switch falls in its step: 1.2 .. 3.6 here),
     * so over three halvings the error falls by far less than 4^3 = 64, and stays far above the located one. */
    double fall = plain[0].err / plain[3].err;
    CHECK(fall < 16, "plain steps: the error falls by %.3g over three halvings: not second order", fall);
    CHECK(plain[3].err > 50 * loc[3].err, "plain %.3e against located %.3e at h = %g", plain[3].err, loc[3].err,
          0.01 / 8);
}

/* No switch, no event: an overdamped series RLC (R = 3, L = C = 1) charged by a constant source from
 * i(0) = 0.5 keeps i > 0 (q' = 0.36 e^{-0.38t} + 0.14 e^{-2.62t}), so the located steps are the plain ones,
 * bit for bit, and none is split. The bridge's diodes switch in pairs when v_C = -2 e^{-t} sin t changes sign
 * at t = π: four events at one instant, O(h^2) from π, none at t = 0 where every pair is 0 = 0. */
static void test_no_spurious_events(void **state)
{
    (void)state;
    double A[4] = { 0, 1, -1, -3 }, B[2] = { 0, 1 }, C[2] = { 0, 1 }, D[1] = { 0 }, p[2] = { 0, 1 }, q[1] = { 0 };
    dp_lcs_law law = { DP_LCS_COMPLEMENTARITY, 0, 0 };
    dp_lcs sys = { 2, 1, A, B, C, D, p, q, &law };
    int s;
    dp_lcs_stepper *st = dp_lcs_stepper_alloc(&sys, 0.01, 0.5, &s), *alg = dp_lcs_stepper_alloc(&sys, 0, 1, &s);
    dp_lcs_stepper *plain = dp_lcs_stepper_alloc(&sys, 0.01, 0.5, &s);
    dp_lcs_locator *lc = dp_lcs_locator_alloc(&sys, NULL, 0.01, 0.5, &s);
    double x[2] = { 0, 0.5 }, y[2] = { 0, 0.5 }, u[1], w[1], v[1], z[1];
    dp_lcp_result res;
    CHECK(dp_lcs_step(alg, x, u, w, &res) == DP_OK, "algebraic part");
    dp_lcs_locator_start(lc, alg);
    size_t events = 0, ne;
    for (int k = 0; k < 2000; k++) {
        CHECK(dp_lcs_step_located(lc, st, k * 0.01, 0.01, x, u, w, &res, NULL) == DP_OK, "step %d", k);
        CHECK(dp_lcs_step(plain, y, v, z, &res) == DP_OK, "plain step %d", k);
        dp_lcs_located_events(lc, &ne);
        events += ne;
        CHECK(x[0] == y[0] && x[1] == y[1] && u[0] == v[0], "step %d: located (%.17g, %.17g), plain (%.17g, %.17g)",
              k, x[0], x[1], y[0], y[1]);
    }
    CHECK(events == 0 && dp_lcs_locator_substeps(lc) == 0 && x[1] > 0, "%zu events, %llu sub-steps, i = %g", events,
          dp_lcs_locator_substeps(lc), x[1]);
    dp_lcs_locator_free(lc);
    dp_lcs_stepper_free(plain);
    dp_lcs_stepper_free(alg);
    dp_lcs_stepper_free(st);

    const double c = 0.5, h = 1e-3;
    double Ab[4] = { 0, -1 / c, 1, 0 }, Bb[8] = { 0, 0, -1 / c, 1 / c, 0, 0, 0, 0 };
    double Cb[8] = { 0, 0, 0, 0, -1, 0, 1, 0 }, Db[16] = { 1, 1, -1, 0, 1, 1, 0, -1, 1, 0, 0, 0, 0, 1, 0, 0 };
    double pb[2] = { 0, 0 }, qb[4] = { 0, 0, 0, 0 }, xb[2] = { 0, 1 }, ub[4], wb[4];
    dp_lcs_law lb[4] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
    dp_lcs bridge = { 2, 4, Ab, Bb, Cb, Db, pb, qb, lb };
    st = dp_lcs_stepper_alloc(&bridge, h, 0.5, &s), alg = dp_lcs_stepper_alloc(&bridge, 0, 1, &s);
    lc = dp_lcs_locator_alloc(&bridge, NULL, h, 0.5, &s);
    CHECK(dp_lcs_step(alg, xb, ub, wb, &res) == DP_OK, "bridge: algebraic part");
    dp_lcs_locator_start(lc, alg);
    size_t seen = 0;
    for (int k = 0; k < 4000; k++) {
        CHECK(dp_lcs_step_located(lc, st, k * h, h, xb, ub, wb, &res, NULL) == DP_OK, "bridge step %d", k);
        const dp_lcs_event *ev = dp_lcs_located_events(lc, &ne);
        for (size_t j = 0; j < ne; j++, seen++)
            CHECK(fabs(ev[j].t - M_PI) < h * h && ev[j].component == j && ev[j].on == (j % 2 == 0),
                  "bridge event %zu: component %zu %s at %.15f", seen, ev[j].component, ev[j].on ? "on" : "off", ev[j].t);
    }
    CHECK(seen == 4, "bridge: %zu events, expected 4 at t = π", seen);
    dp_lcs_locator_free(lc);
    dp_lcs_stepper_free(alg);
    dp_lcs_stepper_free(st);
}

/* The rectifier scaled by 1e±150 (its source and so its whole solution: the system is linear) switches at the
 * same instants as at scale 1, to 1e-9 of a step: every decision is taken on signs and scaled margins. At
 * 1e±300 the sub-steps' LCPs leave the normal doubles and may fail their check: a change is then dated at the
 * end of its step (the locator gives up, never the run), so within a step. */
static void test_hostile_magnitudes(void **state)
{
    (void)state;
    const double h = 0.01;
    rect_run one = rectifier_run(&RECT, h, 6, 0.05, 1, 1, NULL);
    double scales[] = { 1e150, 1e-150, 1e300, 1e-300 };
    for (size_t k = 0; k < sizeof scales / sizeof *scales; k++) {
        rect_run big = rectifier_run(&RECT, h, 6, 0.05, 1, scales[k], NULL);
        double tol = k < 2 ? 1e-9 * h : h;
        CHECK(big.nev == one.nev, "scale %g: %zu events, %zu at scale 1", scales[k], big.nev, one.nev);
        for (size_t j = 0; j < one.nev; j++)
            CHECK(fabs(big.t_ev[j] - one.t_ev[j]) <= tol && big.on_ev[j] == one.on_ev[j],
                  "scale %g: event %zu at %.15f, at scale 1 %.15f", scales[k], j, big.t_ev[j], one.t_ev[j]);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rlc_ideal_diode), cmocka_unit_test(test_rlc_breakdown_diode),
        cmocka_unit_test(test_bridge),          cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_located_refusals), cmocka_unit_test(test_long_step_stopped),
        cmocka_unit_test(test_rectifier_convergence), cmocka_unit_test(test_breakdown_contrast),
        cmocka_unit_test(test_no_spurious_events),  cmocka_unit_test(test_hostile_magnitudes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
