/* tests/test_lcs.c - the θ-step of linear complementarity systems on Cibulka 2014's circuits against
 * closed forms derived from the text: the series RLC with an ideal diode (Example 1.9: a damped oscillation
 * until the current vanishes, then blocked for good), the same with a breakdown diode (an interval law), and
 * the four-diode bridge (Example 1.10, its own matrices: with ideal diodes the load always conducts, so the
 * tank is a parallel RLC). Tolerances: O(h^2) for θ = 1/2 where u = 0 (the diode conducts freely), O(h)
 * after a switch (it lands on a step boundary) and wherever u != 0 (u is taken at the step's end, docs/systems.md
 * §5, a backward Euler treatment of B u). Then what the step refuses and where it says the blame lies (every
 * product it forms from the data checked finite), and a step whose LCP pivots for long (Murty 1978's matrix
 * as D) ended by the stop hook or by Lemke's pivot limit, x unchanged.
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

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rlc_ideal_diode), cmocka_unit_test(test_rlc_breakdown_diode),
        cmocka_unit_test(test_bridge),          cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_located_refusals), cmocka_unit_test(test_long_step_stopped),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
