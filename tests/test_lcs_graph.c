/* tests/test_lcs_graph.c - graph laws for LCS components ("any monotone graph dashpot already
 * knows"), -w ∈ G(u), each against something that does not go through the stepper's splitting of G:
 * the graph of the complementarity cone and of an interval give the trajectories of those laws; the Coulomb
 * graph (the damper's builder) in a Jenkins element gives the return mapping's closed form step by step; two
 * coupled 3-vertex graphs are checked at every step against an enumeration of all pairs of pieces (a 2 x 2
 * solve each, written here from the points); a vertical line fixes u; a step with no solution is reported.
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
#include "dashpot/model.h"
#include "dashpot/status.h"

#include "check.h"

static dp_lcs_law graph_law(size_t n, const double *y, const double *f)
{
    dp_lcs_law law = { .kind = DP_LCS_GRAPH };
    CHECK(dp_graph_init_points(&law.graph, n, y, f) == DP_OK, "graph of %zu points", n);
    return law;
}

static dp_lcs_stepper *stepper(const dp_lcs *sys, double h, double theta)
{
    int s;
    dp_lcs_stepper *st = dp_lcs_stepper_alloc(sys, h, theta, &s);
    CHECK(st != NULL && s == DP_OK, "stepper: %d", s);
    return st;
}

/* Two steppers of the same system that differ only in the law, stepped side by side from x0: x, u, w agree
 * at every step to `tol`. Returns the last u of the first (for the caller's own check of the path). */
static double same_trajectory(dp_lcs *a, dp_lcs *b, const double *x0, int steps, double tol)
{
    dp_lcs_stepper *sa = stepper(a, 1e-3, 0.5), *sb = stepper(b, 1e-3, 0.5);
    double xa[2] = { x0[0], x0[1] }, xb[2] = { x0[0], x0[1] }, ua[1], ub[1], wa[1], wb[1];
    dp_lcp_result r;
    for (int k = 0; k < steps; k++) {
        CHECK(dp_lcs_step(sa, xa, ua, wa, &r) == DP_OK && dp_lcs_step(sb, xb, ub, wb, &r) == DP_OK, "step %d", k);
        NEAR(xb[0], xa[0], tol);
        NEAR(xb[1], xa[1], tol);
        NEAR(ub[0], ua[0], tol);
        NEAR(wb[0], wa[0], tol);
    }
    dp_lcs_stepper_free(sa);
    dp_lcs_stepper_free(sb);
    return ua[0];
}

/* Seed 002 Example 1.9 (R = 0.5, L = 1, C = 0.25): the ideal diode 0 <= u ⊥ w >= 0 is -w ∈ N_R+(u), the graph
 * through (0, -1), (0, 0), (1, 0); the breakdown diode u ∈ [-0.5, 0] is N_[-0.5, 0], through (-0.5, -1),
 * (-0.5, 0), (0, 0), (0, 1). */
static void test_graph_equals_complementarity_and_interval(void **state)
{
    (void)state;
    static const double A[4] = { 0, 1, -4, -0.5 }, Bi[2] = { 0, 1 }, Ci[2] = { 0, 1 }, Bb[2] = { 0, -1 },
                        Cb[2] = { 0, -1 }, D[1] = { 0 }, p[2] = { 0, 0 }, q[1] = { 0 }, x0[2] = { 0, 1 };
    dp_lcs_law comp = { .kind = DP_LCS_COMPLEMENTARITY }, iv = { .kind = DP_LCS_INTERVAL, .lo = -0.5, .hi = 0 };
    double cy[3] = { 0, 0, 1 }, cf[3] = { -1, 0, 0 }, iy[4] = { -0.5, -0.5, 0, 0 }, i_f[4] = { -1, 0, 0, 1 };
    dp_lcs_law gc = graph_law(3, cy, cf), gi = graph_law(4, iy, i_f);
    CHECK(dp_lcs_law_rows(&gc) == 1 && dp_lcs_law_rows(&gi) == 2, "the cone is 1 row, the interval 2");
    dp_lcs a = { 2, 1, A, Bi, Ci, D, p, q, &comp }, b = a;
    b.law = &gc;
    /* blocked for good after t* = 0.73: -v_D = q* / C = 1.667 (test_lcs.c has the closed form) */
    NEAR(same_trajectory(&a, &b, x0, 3000, 1e-12), 1.667, 1e-3);
    a = (dp_lcs){ 2, 1, A, Bb, Cb, D, p, q, &iv }, b = a;
    b.law = &gi;
    NEAR(same_trajectory(&a, &b, x0, 2000, 1e-12), -0.5, 1e-12); /* in breakdown: v_D = -V_b */
    dp_graph_clear(&gc.graph);
    dp_graph_clear(&gi.graph);
}

/* The Jenkins element as an LCS: x = (s, e), s' = u (the slider), e' = v(t) = cos t (driven), force
 * -w = k (e - s) ∈ φ Sgn(u) (the Coulomb graph of the one-mass damper's builder). With A = 0 the θ-step is
 * e+ = e + h v(t + θh), s+ = s + h u+: the return mapping, F* = k (e+ - s), F = clamp(F*, -φ, φ). */
static void test_coulomb_graph_is_the_return_mapping(void **state)
{
    (void)state;
    const double k = 2, phi = 0.5, h = 0.01;
    dp_damper d = { .law = DP_DAMPER_COULOMB, .phi0 = phi };
    CHECK(dp_damper_prepare(&d) == DP_OK, "coulomb graph");
    dp_lcs_law law = { .kind = DP_LCS_COULOMB, .phi0 = phi, .graph = d.graph };
    double A[4] = { 0 }, B[2] = { 1, 0 }, C[2] = { k, -k }, D[1] = { 0 }, p[2] = { 0, 0 }, q[1] = { 0 };
    dp_lcs sys = { 2, 1, A, B, C, D, p, q, &law };
    dp_lcs_stepper *st = stepper(&sys, h, 0.5);
    double x[2] = { 0, 0 }, u[1], w[1], s = 0, e = 0;
    int slid = 0, stuck = 0;
    for (int n = 0; n < 1000; n++) {
        p[1] = cos((n + 0.5) * h);
        dp_lcs_stepper_set_p(st, p);
        dp_lcp_result r;
        CHECK(dp_lcs_step(st, x, u, w, &r) == DP_OK, "step %d", n);
        e += h * p[1];
        double F = fmax(-phi, fmin(phi, k * (e - s)));
        double us = (e - F / k - s) / h;
        s = e - F / k;
        NEAR(x[0], s, 1e-12);
        NEAR(x[1], e, 1e-12);
        NEAR(-w[0], F, 1e-12);
        NEAR(u[0], us, 1e-9);
        slid += fabs(F) == phi, stuck += fabs(F) < phi - 1e-9 && u[0] == 0;
    }
    CHECK(slid > 100 && stuck > 100, "both the stick interval and the slip rays are used (%d, %d)", slid, stuck);
    dp_lcs_stepper_free(st);
    dp_graph_clear(&law.graph);
}

/* ---- two coupled 3-vertex graphs against an enumeration of their pieces --------------------------------- */

/* A closed piece of a graph through points: P + t d, t in [0, tmax] (INFINITY for the end rays, which
 * continue the first and last segments: the left one backwards). */
typedef struct { double py, pf, dy, df, tmax; } closed_piece;

static size_t pieces_of(size_t n, const double *y, const double *f, closed_piece *out)
{
    size_t k = 0;
    out[k++] = (closed_piece){ y[0], f[0], y[0] - y[1], f[0] - f[1], INFINITY };
    for (size_t i = 0; i + 1 < n; i++)
        out[k++] = (closed_piece){ y[i], f[i], y[i + 1] - y[i], f[i + 1] - f[i], 1 };
    out[k++] = (closed_piece){ y[n - 1], f[n - 1], y[n - 1] - y[n - 2], f[n - 1] - f[n - 2], INFINITY };
    return k;
}

/* Every u with -(M u + r) ∈ G0(u0) x G1(u1): for each pair of pieces, F_i + (M u)_i + r_i = 0 is 2 x 2 in
 * (t0, t1); kept when both t lie on their pieces, distinct ones only. Returns the number found. */
static int enumerate(const closed_piece *g0, size_t n0, const closed_piece *g1, size_t n1, const double M[4],
                     const double r[2], double *u)
{
    int found = 0;
    for (size_t a = 0; a < n0; a++)
        for (size_t b = 0; b < n1; b++) {
            const closed_piece *P[2] = { &g0[a], &g1[b] };
            double K[4], rhs[2];
            for (int i = 0; i < 2; i++) {
                rhs[i] = -(P[i]->pf + r[i] + M[2 * i] * P[0]->py + M[2 * i + 1] * P[1]->py);
                for (int j = 0; j < 2; j++)
                    K[2 * i + j] = M[2 * i + j] * P[j]->dy + (i == j ? P[i]->df : 0);
            }
            double det = K[0] * K[3] - K[1] * K[2];
            if (fabs(det) < 1e-14)
                continue;
            double t[2] = { (rhs[0] * K[3] - K[1] * rhs[1]) / det, (K[0] * rhs[1] - K[2] * rhs[0]) / det };
            if (t[0] < -1e-12 || t[0] > P[0]->tmax + 1e-12 || t[1] < -1e-12 || t[1] > P[1]->tmax + 1e-12)
                continue;
            double v0 = P[0]->py + t[0] * P[0]->dy, v1 = P[1]->py + t[1] * P[1]->dy;
            int dup = 0;
            for (int s = 0; s < found; s++)
                dup |= fabs(u[2 * s] - v0) < 1e-9 && fabs(u[2 * s + 1] - v1) < 1e-9;
            if (!dup && found < 4)
                u[2 * found] = v0, u[2 * found + 1] = v1, found++;
        }
    return found;
}

/* x' = A x + u + p(t), w = x + D u + q, -w_i ∈ G_i(u_i), each graph with three vertices where it turns (the
 * end points only set the rays): G0 through (-2, -1.5), (-1, -1), (0, 0), (1, 0.25), (2, 1.25), single-valued
 * with slopes 0.5, 1, 0.25, 1 (a concave kink at 0 between convex ones); G1 through (0, -1), (0, 0.2),
 * (1, 0.7), (1, 1.5), (2, 1.5): u1 >= 0, a jump to 0.2 at 0, slope 0.5, a jump from 0.7 to 1.5 at 1, then
 * flat. The reference θ-step is written out here: W = (I - hθA)^-1 by its 2 x 2 formula. */
static void test_three_vertex_graphs_against_enumeration(void **state)
{
    (void)state;
    const double h = 0.01, th = 0.5;
    double y0[5] = { -2, -1, 0, 1, 2 }, f0[5] = { -1.5, -1, 0, 0.25, 1.25 };
    double y1[5] = { 0, 0, 1, 1, 2 }, f1[5] = { -1, 0.2, 0.7, 1.5, 1.5 };
    dp_lcs_law law[2] = { graph_law(5, y0, f0), graph_law(5, y1, f1) };
    CHECK(dp_lcs_law_rows(&law[0]) == 6 && dp_lcs_law_rows(&law[1]) == 3, "rows: 1 + 2 + 2 + 1 and 0 + 2 + 0 + 1");
    double A[4] = { 0, 1, -1, -0.1 }, I[4] = { 1, 0, 0, 1 }, D[4] = { 0.5, 0, 0, 0.5 }, p[2] = { 0, 0 },
           q[2] = { 0.1, -0.2 };
    dp_lcs sys = { 2, 2, A, I, I, D, p, q, law };
    dp_lcs_stepper *st = stepper(&sys, h, th);
    closed_piece g0[6], g1[6];
    size_t n0 = pieces_of(5, y0, f0, g0), n1 = pieces_of(5, y1, f1, g1);
    double L[4] = { 1 - h * th * A[0], -h * th * A[1], -h * th * A[2], 1 - h * th * A[3] };
    double det = L[0] * L[3] - L[1] * L[2], W[4] = { L[3] / det, -L[1] / det, -L[2] / det, L[0] / det };
    double M[4] = { D[0] + h * W[0], h * W[1], h * W[2], D[3] + h * W[3] };
    double x[2] = { 1, 0 }, xr[2] = { 1, 0 }, u[2], w[2];
    int seen[8] = { 0 };
    for (int n = 0; n < 3000; n++) {
        p[1] = 3 * cos((n + th) * h * 0.7);
        dp_lcs_stepper_set_p(st, p);
        dp_lcp_result res;
        CHECK(dp_lcs_step(st, x, u, w, &res) == DP_OK, "step %d", n);
        double v[2] = { xr[0] + h * (1 - th) * (A[0] * xr[0] + A[1] * xr[1]) + h * p[0],
                        xr[1] + h * (1 - th) * (A[2] * xr[0] + A[3] * xr[1]) + h * p[1] };
        double xh[2] = { W[0] * v[0] + W[1] * v[1], W[2] * v[0] + W[3] * v[1] };
        double r[2] = { xh[0] + q[0], xh[1] + q[1] }, ur[8];
        int count = enumerate(g0, n0, g1, n1, M, r, ur);
        CHECK(count == 1, "step %d: %d solutions (M is positive definite: exactly one)", n, count);
        xr[0] = xh[0] + h * (W[0] * ur[0] + W[1] * ur[1]);
        xr[1] = xh[1] + h * (W[2] * ur[0] + W[3] * ur[1]);
        NEAR(u[0], ur[0], 1e-9);
        NEAR(u[1], ur[1], 1e-9);
        NEAR(x[0], xr[0], 1e-9);
        NEAR(x[1], xr[1], 1e-9);
        NEAR(w[1], xr[1] + D[3] * ur[1] + q[1], 1e-9);
        seen[0] += ur[0] < -1, seen[1] += ur[0] > -1 && ur[0] < 0, seen[2] += ur[0] > 0 && ur[0] < 1;
        seen[3] += ur[0] > 1, seen[4] += ur[1] == 0 && -w[1] < 0.2 - 1e-6; /* inside the jump at 0 */
        seen[5] += ur[1] > 0 && ur[1] < 1, seen[6] += fabs(ur[1] - 1) < 1e-12 && -w[1] > 0.7 + 1e-6 &&
                                                      -w[1] < 1.5 - 1e-6, seen[7] += ur[1] > 1;
    }
    for (int i = 0; i < 8; i++)
        CHECK(seen[i] > 50, "piece class %d visited %d times", i, seen[i]);
    dp_lcs_stepper_free(st);
    dp_graph_clear(&law[0].graph);
    dp_graph_clear(&law[1].graph);
}

/* A vertical line fixes u (no LCP row): x' = -x + u with u = 0.3, the θ = 1/2 step in closed form. A graph
 * with no solution at a step (-w = 0.9 u + 1 against u >= 0, G(u) = 0.5 u) is DP_ESOLVE, x unchanged. */
static void test_fixed_u_and_no_solution(void **state)
{
    (void)state;
    double vy[2] = { 0.3, 0.3 }, vf[2] = { -1, 1 };
    dp_lcs_law law = graph_law(2, vy, vf);
    CHECK(dp_lcs_law_rows(&law) == 0, "a vertical line adds no row");
    double A[1] = { -1 }, B[1] = { 1 }, C[1] = { 1 }, D[1] = { 0 }, p[1] = { 0 }, q[1] = { 0 };
    dp_lcs sys = { 1, 1, A, B, C, D, p, q, &law };
    dp_lcs_stepper *st = stepper(&sys, 0.1, 0.5);
    double x[1] = { 1 }, xr = 1, u[1], w[1];
    dp_lcp_result res;
    for (int n = 0; n < 20; n++) {
        CHECK(dp_lcs_step(st, x, u, w, &res) == DP_OK, "step %d", n);
        xr = ((1 - 0.05) * xr + 0.1 * 0.3) / (1 + 0.05);
        NEAR(u[0], 0.3, 0);
        NEAR(x[0], xr, 1e-14);
        NEAR(w[0], xr, 1e-14);
    }
    dp_lcs_stepper_free(st);
    dp_graph_clear(&law.graph);

    double ry[3] = { 0, 0, 1 }, rf[3] = { -1, 0, 0.5 };
    law = graph_law(3, ry, rf);
    A[0] = 0, D[0] = -1, q[0] = -1; /* the step's matrix D + h C B = -0.9; -w = 0.9 u + 1 */
    st = stepper(&sys, 0.1, 0.5);
    x[0] = 0;
    CHECK(dp_lcs_step(st, x, u, w, &res) == DP_ESOLVE && x[0] == 0, "no solution: DP_ESOLVE, x unchanged");
    dp_lcs_stepper_free(st);
    dp_graph_clear(&law.graph);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_graph_equals_complementarity_and_interval),
        cmocka_unit_test(test_coulomb_graph_is_the_return_mapping),
        cmocka_unit_test(test_three_vertex_graphs_against_enumeration),
        cmocka_unit_test(test_fixed_u_and_no_solution),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
