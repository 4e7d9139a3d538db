/* tests/test_right_hand.c - friction with motion-dependent normal force (src/core/right_hand*.c, Matrosov & Finogenko 1995,
 * docs/systems.md §6) against references built here without the library's equations:
 *  - the equations of motion from T and V by numerical differentiation of the Lagrangian, the normal
 *    reactions from Newton's law with the accelerations of the bodies' centres by finite differences of
 *    their positions: the solver's accelerations satisfy them at random sliding states;
 *  - Painlevé's condition f1 < (1 + sin^2 b)/|sin b cos b| (the paper's §6 remark) and the rod's band
 *    tan(theta) in the roots of t^2 - 3 mu t + 4 = 0, hence mu = 4/3, located by the enumeration to 1e-9;
 *    which paradox (no solution, two) and the two normal forces from the V-shaped scalar equation;
 *  - the exceptional states of §6 (with the corrected N1, N2 of docs/systems.md) outside the set A, the printed
 *    N1 not vanishing there, and the printed sign of (2.3) certifying a state the enumeration refutes;
 *  - a run against an independent fine-step RK4 integration with Newton-solved accelerations, up to the
 *    located velocity zero, whose time it also checks; a paradox stops a run with its record.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "dashpot/right_hand.h"
#include "dashpot/run.h"
#include "dashpot/spec.h"
#include "dashpot/wellposedness.h"

/* ---- the reference mechanics: positions only ---- */

typedef struct pos { double B[2], C[2]; } pos;

/* World positions (x right, y up) of the piston B and the body's centre C (or the rod's end A and centre G). */
static pos where(const dp_right_hand_model *m, const double q[2])
{
    pos p;
    if (m->kind == DP_RIGHT_HAND_ROD) {
        double l = m->length / 2;
        p.B[0] = q[0], p.B[1] = 0;
        p.C[0] = q[0] + l * cos(q[1]), p.C[1] = l * sin(q[1]);
        return p;
    }
    double ex[2] = { cos(m->alpha), sin(m->alpha) }, n[2] = { -sin(m->alpha), cos(m->alpha) };
    for (int i = 0; i < 2; i++) {
        p.B[i] = q[0] * ex[i];
        p.C[i] = p.B[i] + m->r * sin(q[1]) * ex[i] - m->r * cos(q[1]) * n[i];
    }
    return p;
}

/* The velocities of B and C: the positions' derivative along q' (4th-order stencil). */
static void velocities(const dp_right_hand_model *m, const double q[2], const double qd[2], double vB[2], double vC[2])
{
    const double h = 1e-3;
    pos p[4];
    const double k[4] = { 2, 1, -1, -2 };
    for (int i = 0; i < 4; i++) {
        double x[2] = { q[0] + k[i] * h * qd[0], q[1] + k[i] * h * qd[1] };
        p[i] = where(m, x);
    }
    for (int i = 0; i < 2; i++) {
        vB[i] = (-p[0].B[i] + 8 * p[1].B[i] - 8 * p[2].B[i] + p[3].B[i]) / (12 * h);
        vC[i] = (-p[0].C[i] + 8 * p[1].C[i] - 8 * p[2].C[i] + p[3].C[i]) / (12 * h);
    }
}

static double lagrangian(const dp_right_hand_model *m, const double q[2], const double qd[2])
{
    double vB[2], vC[2];
    velocities(m, q, qd, vB, vC);
    pos o = where(m, q);
    if (m->kind == DP_RIGHT_HAND_ROD) {
        double l = m->length / 2, I = m->m * l * l / 3;
        return 0.5 * m->m * (vC[0] * vC[0] + vC[1] * vC[1]) + 0.5 * I * qd[1] * qd[1] - m->m * m->g * o.C[1];
    }
    double T = 0.5 * m->m1 * (vB[0] * vB[0] + vB[1] * vB[1]) + 0.5 * m->m2 * (vC[0] * vC[0] + vC[1] * vC[1]) +
               0.5 * m->J_C * qd[1] * qd[1];
    return T - m->g * (m->m1 * o.B[1] + m->m2 * o.C[1]);
}

/* dL/dqd_i: L is quadratic in qd, so the central difference is exact for any step (1 here). */
static double p_i(const dp_right_hand_model *m, const double q[2], const double qd[2], int i)
{
    double a[2] = { qd[0], qd[1] }, b[2] = { qd[0], qd[1] };
    a[i] += 1, b[i] -= 1;
    return (lagrangian(m, q, a) - lagrangian(m, q, b)) / 2;
}

/* A_ij = d p_i/dqd_j (exact, L quadratic in qd), b_i = dL/dq_i - sum_j dp_i/dq_j qd_j (4th-order in q). */
static void lagrange(const dp_right_hand_model *m, const double q[2], const double qd[2], double A[2][2], double b[2])
{
    const double hq = 1e-3, k[4] = { 2, 1, -1, -2 }, w[4] = { -1, 8, -8, 1 };
    for (int i = 0; i < 2; i++) {
        b[i] = 0;
        for (int j = 0; j < 2; j++) {
            double a[2] = { qd[0], qd[1] }, c[2] = { qd[0], qd[1] };
            a[j] += 1, c[j] -= 1;
            A[i][j] = (p_i(m, q, a, i) - p_i(m, q, c, i)) / 2;
            double dL = 0, dp = 0;
            for (int s = 0; s < 4; s++) {
                double x[2] = { q[0], q[1] };
                x[j] += k[s] * hq;
                if (i == j)
                    dL += w[s] * lagrangian(m, x, qd);
                dp += w[s] * p_i(m, x, qd, i);
            }
            b[i] += (i == j ? dL / (12 * hq) : 0) - dp / (12 * hq) * qd[j];
        }
    }
}

/* Normal reactions by Newton: the centre's acceleration a = d2/dt2 C(q + qd t + qdd t^2/2) at t = 0 by the
 * 4th-order stencil for the second derivative (step 1e-3: truncation ~1e-12, rounding ~1e-10). */
static void reactions(const dp_right_hand_model *m, const double q[2], const double qd[2], const double qdd[2],
                      double N[2])
{
    const double h = 1e-3, k[5] = { 2, 1, 0, -1, -2 }, w[5] = { -1, 16, -30, 16, -1 };
    double aC[2] = { 0, 0 };
    for (int s = 0; s < 5; s++) {
        double t = k[s] * h, x[2] = { q[0] + qd[0] * t + 0.5 * qdd[0] * t * t, q[1] + qd[1] * t + 0.5 * qdd[1] * t * t };
        pos p = where(m, x);
        aC[0] += w[s] * p.C[0] / (12 * h * h), aC[1] += w[s] * p.C[1] / (12 * h * h);
    }
    if (m->kind == DP_RIGHT_HAND_ROD) {
        N[0] = m->m * (aC[1] + m->g), N[1] = 0;
        return;
    }
    double n[2] = { -sin(m->alpha), cos(m->alpha) };
    N[0] = m->m2 * (aC[0] * n[0] + aC[1] * n[1]) + (m->m1 + m->m2) * m->g * cos(m->alpha);
    N[1] = m->m2 * hypot(aC[0], aC[1] + m->g);
}

static double urand(uint64_t *s, double lo, double hi)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * (double)(*s >> 11) / 9007199254740992.0;
}

static dp_right_hand_model piston(double m1, double m2, double JC, double r, double alpha, double f1, double f2)
{
    return (dp_right_hand_model){ .kind = DP_RIGHT_HAND_PISTON_HINGE, .m1 = m1, .m2 = m2, .J_C = JC, .r = r, .alpha = alpha,
                          .f1 = f1, .f2 = f2, .g = 9.81 };
}

static dp_right_hand_model rod(double m, double length, double mu)
{
    return (dp_right_hand_model){ .kind = DP_RIGHT_HAND_ROD, .m = m, .length = length, .mu = mu, .g = 9.81 };
}

/* The solver's accelerations at random sliding states satisfy A qdd = b - sgn(qd) f |N| with A, b from the
 * Lagrangian and N from Newton, to finite-difference accuracy. */
static void test_equations_from_lagrangian(void **state)
{
    (void)state;
    uint64_t seed = 21;
    int checked = 0;
    for (int it = 0; it < 400; it++) {
        int isrod = it % 2;
        dp_right_hand_model m = isrod ? rod(urand(&seed, 0.5, 3), urand(&seed, 0.5, 2), urand(&seed, 0, 1.2))
                              : piston(urand(&seed, 0.5, 3), urand(&seed, 0.5, 3), urand(&seed, 0, 0.5),
                                       urand(&seed, 0.2, 1.5), urand(&seed, 0, M_PI / 2), urand(&seed, 0, 0.6),
                                       urand(&seed, 0, 0.1));
        double q[2] = { urand(&seed, -1, 1), isrod ? urand(&seed, 0.2, 1.4) : urand(&seed, -M_PI, M_PI) };
        double qd[2] = { urand(&seed, 0.1, 2) * (urand(&seed, 0, 1) < 0.5 ? -1 : 1), urand(&seed, -2, 2) };
        dp_right_hand_result res;
        dp_right_hand_solve(&m, q, qd, NULL, &res);
        if (res.n != 1 || res.continuum || res.sol[0].liftoff)
            continue;
        const dp_right_hand_sol *s = &res.sol[0];
        double A[2][2], b[2], N[2];
        lagrange(&m, q, qd, A, b);
        reactions(&m, q, qd, s->qdd, N);
        double f[2] = { isrod ? m.mu : m.f1, isrod ? 0 : m.f2 };
        for (int i = 0; i < 2; i++) {
            double Q = -(qd[i] > 0 ? 1 : qd[i] < 0 ? -1 : 0) * f[i] * fabs(N[i]);
            double lhs = A[i][0] * s->qdd[0] + A[i][1] * s->qdd[1], rhs = b[i] + Q;
            double scale = 1 + fabs(lhs) + fabs(b[i]) + fabs(Q);
            if (fabs(lhs - rhs) > 1e-7 * scale)
                fail_msg("%s state %d coordinate %d: A qdd = %.12g, b + Q = %.12g", isrod ? "rod" : "piston", it,
                         i, lhs, rhs);
            double Nl = isrod && i == 1 ? 0 : fabs(s->N[i]);
            if (fabs(Nl - fabs(N[i])) > 1e-7 * (1 + fabs(N[i])))
                fail_msg("state %d: |N%d| = %.12g, Newton gives %.12g", it, i, Nl, fabs(N[i]));
        }
        checked++;
    }
    if (checked < 300)
        fail_msg("only %d of 400 random states had one solution", checked);
}

static int unique_at(const dp_right_hand_model *m, const double q[2], const double qd[2])
{
    dp_right_hand_result res;
    dp_right_hand_solve(m, q, qd, NULL, &res);
    return res.n == 1 && !res.continuum;
}

/* The edge between a unique angle `ok` and a paradoxical one `bad`, by bisection on the enumeration. */
static double edge(const dp_right_hand_model *m, double ok, double bad, double x, double xd, double ad)
{
    while (fabs(bad - ok) > 1e-12) {
        double mid = 0.5 * (ok + bad);
        double q[2] = { x, mid }, qd[2] = { xd, ad };
        if (unique_at(m, q, qd))
            ok = mid;
        else
            bad = mid;
    }
    return 0.5 * (ok + bad);
}

/* Painlevé's example (alpha = 0, f2 = 0, m1 = m2 = 1, J_C = 0): sliding x' > 0, beta' = 0, the acceleration
 * problem is unique exactly where f1 sin cos < 1 + sin^2, i.e. outside tan(beta) in roots of 2t^2 - f1 t + 1. */
static void test_painleve_condition(void **state)
{
    (void)state;
    const double f1s[] = { 2.9, 3.5, 5, 8, 20 };
    for (size_t i = 0; i < sizeof f1s / sizeof *f1s; i++) {
        double f1 = f1s[i], d = sqrt(f1 * f1 - 8);
        dp_right_hand_model m = piston(1, 1, 0, 0.8, 0, f1, 0);
        double lo = atan((f1 - d) / 4), hi = atan((f1 + d) / 4), mid = atan(f1 / 4);
        double a = edge(&m, 1e-3, mid, 0, 1, 0), b = edge(&m, M_PI / 2 - 1e-3, mid, 0, 1, 0);
        if (fabs(a - lo) > 1e-9 || fabs(b - hi) > 1e-9)
            fail_msg("f1 = %g: edges %.15g, %.15g; expected %.15g, %.15g", f1, a, b, lo, hi);
        /* beta' = 0: h(0) > 0 in the band, no solution (inconsistency) */
        dp_right_hand_result res;
        double q[2] = { 0, mid }, qd[2] = { 1, 0 };
        dp_right_hand_solve(&m, q, qd, NULL, &res);
        assert_int_equal(res.n, 0);
    }
    /* below 2 sqrt(2) no angle is paradoxical */
    dp_right_hand_model m = piston(1, 1, 0, 0.8, 0, 2 * sqrt(2) - 1e-6, 0);
    for (int k = 1; k < 2000; k++) {
        double q[2] = { 0, k * (M_PI / 2) / 2000 }, qd[2] = { 1, 0 };
        if (!unique_at(&m, q, qd))
            fail_msg("f1 < 2 sqrt 2 but beta = %g is paradoxical", q[1]);
    }
}

/* Indeterminacy in Painlevé's example: beta in the third quadrant spinning fast makes K < 0 and the V-shaped
 * h(N) = (1 + s^2)(K - N)/(s c) - P + f|N| negative at 0: two roots, one N of each sign, computed here. */
static void test_painleve_indeterminacy(void **state)
{
    (void)state;
    double f = 5, r = 0.8, g = 9.81, beta = M_PI + atan(f / 4), bd = 10;
    dp_right_hand_model m = piston(1, 1, 0, r, 0, f, 0);
    double s = sin(beta), c = cos(beta), sc = s * c;
    double K = g * (1 + c * c) + r * bd * bd * c, P = r * bd * bd * s + g * sc;
    double rhs = P - (1 + s * s) * K / sc;
    double Np = rhs / (f - (1 + s * s) / sc), Nm = rhs / (-(1 + s * s) / sc - f);
    assert_true(Np > 0 && Nm < 0);
    dp_right_hand_result res;
    double q[2] = { 0, beta }, qd[2] = { 1, bd };
    dp_right_hand_solve(&m, q, qd, NULL, &res);
    assert_int_equal(res.n, 2);
    double a = fmax(res.sol[0].N[0], res.sol[1].N[0]), b = fmin(res.sol[0].N[0], res.sol[1].N[0]);
    if (fabs(a - Np) > 1e-9 * fabs(Np) || fabs(b - Nm) > 1e-9 * fabs(Nm))
        fail_msg("N = %.15g, %.15g; expected %.15g, %.15g", a, b, Np, Nm);
}

/* The rod sliding with x_A' < 0, theta' = 0: N (1 + 3cos^2 - 3 mu sin cos) = m g, paradoxical for tan(theta)
 * between the roots of t^2 - 3 mu t + 4 = 0 (none for mu < 4/3); mu = 4/3 itself located at tan = 2. */
static void test_rod_threshold(void **state)
{
    (void)state;
    const double mus[] = { 1.34, 1.5, 2, 3, 6 };
    for (size_t i = 0; i < sizeof mus / sizeof *mus; i++) {
        double mu = mus[i], d = sqrt(9 * mu * mu - 16);
        dp_right_hand_model m = rod(1.3, 1.7, mu);
        double lo = atan((3 * mu - d) / 2), hi = atan((3 * mu + d) / 2), mid = atan(3 * mu / 2);
        double a = edge(&m, 1e-3, mid, 0, -1, 0), b = edge(&m, M_PI / 2 - 1e-3, mid, 0, -1, 0);
        if (fabs(a - lo) > 1e-9 || fabs(b - hi) > 1e-9)
            fail_msg("mu = %g: edges %.15g, %.15g; expected %.15g, %.15g", mu, a, b, lo, hi);
        dp_right_hand_result res;
        double q[2] = { 0, mid }, qd[2] = { -1, 0 };
        dp_right_hand_solve(&m, q, qd, NULL, &res);
        assert_int_equal(res.n, 0);          /* g - l sin theta'^2 > 0: inconsistency */
        qd[1] = 6;                           /* g - l sin theta'^2 < 0: indeterminacy */
        dp_right_hand_solve(&m, q, qd, NULL, &res);
        assert_int_equal(res.n, 2);
        qd[0] = 1;                           /* sliding the other way is never paradoxical */
        assert_true(unique_at(&m, q, qd));
    }
    double ok = 1, bad = 2, t2[2] = { 0, atan(2) }, v[2] = { -1, 0 };
    while (bad - ok > 1e-12) {
        double mid = 0.5 * (ok + bad);
        dp_right_hand_model m = rod(1, 1, mid);
        if (unique_at(&m, t2, v))
            ok = mid;
        else
            bad = mid;
    }
    if (fabs(ok - 4.0 / 3.0) > 1e-9)
        fail_msg("mu threshold %.15g, expected 4/3", ok);
    dp_right_hand_model m = rod(1, 1, 4.0 / 3.0 - 1e-6);
    for (int k = 1; k < 4000; k++) {
        double q[2] = { 0, k * (M_PI / 2) / 4000 };
        if (!unique_at(&m, q, v))
            fail_msg("mu < 4/3 but theta = %g is paradoxical", q[1]);
    }
}

static const dp_right_hand_sol *stuck_solution(const dp_right_hand_result *res, int k)
{
    for (int i = 0; i < res->n && i < DP_RIGHT_HAND_MAX_SOL; i++)
        if (res->sol[i].mode[k] == DP_RIGHT_HAND_STICK)
            return &res->sol[i];
    return NULL;
}

/* Seed 004 §6, cases 2 and 3 and the closing remark, with N1 = m2 r (b'' sin b + b'^2 cos b) + m g cos a. */
static void test_exceptional_states(void **state)
{
    (void)state;
    dp_right_hand_conditions c;
    dp_right_hand_result res;
    /* case 2: alpha = pi/2, beta' = 0: free fall x'' = -g with the hinge on its cone at N2 = 0 */
    dp_right_hand_model m = piston(1, 1, 0.1, 0.5, M_PI / 2, 0.3, 0.05);
    double q[2] = { 0, 0.6 }, qd[2] = { 0.7, 0 };
    dp_right_hand_solve(&m, q, qd, NULL, &res);
    const dp_right_hand_sol *s = stuck_solution(&res, 1);
    assert_non_null(s);
    assert_true(fabs(s->qdd[0] + 9.81) < 1e-12 && fabs(s->qdd[1]) < 1e-12 && fabs(s->N[1]) < 1e-12);
    dp_right_hand_conditions_at(&m, q, qd, s, &c);
    assert_int_equal(c.in_A, 0);
    qd[1] = 0.4;
    dp_right_hand_solve(&m, q, qd, NULL, &res);
    assert_int_equal(res.n, 1);
    dp_right_hand_conditions_at(&m, q, qd, &res.sol[0], &c);
    assert_int_equal(c.in_A, 1);

    /* case 3: f2 = 0, x' = 0, beta = pi - alpha, beta'^2 = xi = m g/(m2 r): N1 = 0 and Q1 = 0 */
    double alpha = 0.4, xi = 3 * 9.81 / (2 * 0.5);
    m = piston(1, 2, 0.1, 0.5, alpha, 0.3, 0);
    double q3[2] = { 0, M_PI - alpha }, qd3[2] = { 0, sqrt(xi) };
    dp_right_hand_solve(&m, q3, qd3, NULL, &res);
    s = stuck_solution(&res, 0);
    assert_non_null(s);
    if (fabs(s->N[0]) > 1e-12 * 3 * 9.81 || fabs(s->Q[0]) > 1e-12 * 3 * 9.81)
        fail_msg("case 3: N1 = %g, Q1 = %g, expected 0", s->N[0], s->Q[0]);
    dp_right_hand_conditions_at(&m, q3, qd3, s, &c);
    assert_int_equal(c.in_A, 0);
    /* the printed N1 (beta' where beta'^2 belongs) does not vanish there: the paper's own case 3 needs the
     * correction */
    double printed = m.m2 * m.r * (s->qdd[1] * sin(q3[1]) + qd3[1] * cos(q3[1])) + 3 * m.g * cos(alpha);
    assert_true(fabs(printed) > 1);
    qd3[1] *= 1.01;
    dp_right_hand_solve(&m, q3, qd3, NULL, &res);
    assert_true(res.n >= 1);
    dp_right_hand_conditions_at(&m, q3, qd3, &res.sol[0], &c);
    assert_int_equal(c.in_A, 1);

    /* the closing remark: Painleve's example, beta = pi, beta' = +-sqrt(2 g/r) */
    m = piston(1, 1, 0, 0.7, 0, 0.5, 0);
    for (int sg = -1; sg <= 1; sg += 2) {
        double qp[2] = { 0, M_PI }, qdp[2] = { 0, sg * sqrt(2 * 9.81 / 0.7) };
        dp_right_hand_solve(&m, qp, qdp, NULL, &res);
        s = stuck_solution(&res, 0);
        assert_non_null(s);
        dp_right_hand_conditions_at(&m, qp, qdp, s, &c);
        assert_int_equal(c.in_A, 0);
    }
}

/* (2.3) as printed, |a12 - f Delta d|N1|/db''| a21/a22, against the corrected sign: at beta = atan(1/sqrt 2),
 * f1 = 4 (Painleve's example, x' > 0) the printed form holds (margin > 0) while the enumeration finds no
 * acceleration; the corrected margin is negative, and equals 2 - (cos^2 + f sin cos). */
static void test_condition_23_sign(void **state)
{
    (void)state;
    double r = 0.8, f = 4, beta = atan(1 / sqrt(2)), s = sin(beta), c = cos(beta);
    dp_right_hand_model m = piston(1, 1, 0, r, 0, f, 0);
    double q[2] = { 0, beta }, qd[2] = { 1, 0 };
    assert_false(unique_at(&m, q, qd));
    dp_right_hand_sol sol = { .qdd = { 0, 0 }, .mode = { DP_RIGHT_HAND_SLIP_POS, DP_RIGHT_HAND_FREE } };
    dp_right_hand_conditions k;
    dp_right_hand_conditions_at(&m, q, qd, &sol, &k);
    double a12 = r * c, a22 = r * r, dN = r * s; /* N1 > 0 at qdd = 0 */
    double printed = 2 - fabs((a12 - f * dN) * a12 / a22);
    assert_true(printed > 0);
    if (fabs(k.c23 - (2 - (c * c + f * s * c))) > 1e-12)
        fail_msg("(2.3) margin %.15g, expected %.15g", k.c23, 2 - (c * c + f * s * c));
    assert_true(k.c23 < 0);
}

/* ---- an independent integration: RK4, accelerations by Newton on the Lagrangian's equations ---- */

/* The smooth phase's accelerations: friction -sg_i f_i |N_i| with the phase's signs sg held. */
static void accel_ref(const dp_right_hand_model *m, const double q[2], const double qd[2], const double sg[2],
                      double qdd[2])
{
    double A[2][2], b[2], f[2] = { m->f1, m->f2 };
    lagrange(m, q, qd, A, b);
    double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
    qdd[0] = (A[1][1] * b[0] - A[0][1] * b[1]) / det, qdd[1] = (A[0][0] * b[1] - A[1][0] * b[0]) / det;
    for (int it = 0; it < 60; it++) { /* fixed point qdd = A^-1 (b + Q(qdd)): a contraction for these data */
        double N[2], r[2];
        reactions(m, q, qd, qdd, N);
        for (int i = 0; i < 2; i++)
            r[i] = b[i] - sg[i] * f[i] * fabs(N[i]);
        qdd[0] = (A[1][1] * r[0] - A[0][1] * r[1]) / det, qdd[1] = (A[0][0] * r[1] - A[1][0] * r[0]) / det;
    }
}

/* One RK4 step within the phase of the signs of y's velocities at its start. */
static void rk4(const dp_right_hand_model *m, double y[4], double h)
{
    double k[4][4], t[4], sg[2] = { y[2] > 0 ? 1 : -1, y[3] > 0 ? 1 : -1 };
    for (int s = 0; s < 4; s++) {
        for (int i = 0; i < 4; i++)
            t[i] = y[i] + (s == 0 ? 0 : s == 3 ? h : h / 2) * (s ? k[s - 1][i] : 0);
        k[s][0] = t[2], k[s][1] = t[3];
        accel_ref(m, t, t + 2, sg, &k[s][2]);
    }
    for (int i = 0; i < 4; i++)
        y[i] += h / 6 * (k[0][i] + 2 * k[1][i] + 2 * k[2][i] + k[3][i]);
}

/* A run of model m from (x0, v0) (the rod's third entries, its end's height and rate, 0: on the floor). */
static dp_run *start3(const dp_right_hand_model *m, const double x0[3], const double v0[3], double t_end, double dt)
{
    dp_spec spec;
    dp_spec_init(&spec);
    spec.rh = malloc(sizeof *spec.rh);
    spec.x0v = calloc(3, sizeof(double));
    spec.v0v = calloc(3, sizeof(double));
    assert_non_null(spec.rh);
    *spec.rh = *m;
    memcpy(spec.x0v, x0, 3 * sizeof(double));
    memcpy(spec.v0v, v0, 3 * sizeof(double));
    spec.solver.kind = DP_SOLVER_RIGHT_HAND;
    spec.solver.t_end = t_end, spec.solver.dt = dt, spec.solver.rtol = 1e-11, spec.solver.atol = 1e-13;
    dp_errors errs;
    dp_errors_init(&errs);
    int st;
    dp_run *r = dp_run_alloc(&spec, 0, &errs, &st);
    dp_spec_clear(&spec);
    if (r == NULL)
        fail_msg("run refused: %s %s", errs.n ? errs.item[0].pointer : "", errs.n ? errs.item[0].message : "");
    return r;
}

static dp_run *start(const dp_right_hand_model *m, const double x0[2], const double v0[2], double t_end, double dt)
{
    double x[3] = { x0[0], x0[1], 0 }, v[3] = { v0[0], v0[1], 0 };
    return start3(m, x, v, t_end, dt);
}

/* The reference from (t, y) to t1: RK4 steps of h in the phase of the velocities' signs; a step in which
 * a velocity changes sign is cut at the zero (bisection on one RK4 step's length), the velocity set to 0
 * and the next phase sliding the other way (this test's data reverse, they do not stick). */
static void ref_advance(const dp_right_hand_model *m, double y[4], double *t, double t1, double *tcross)
{
    const double h = 1e-3;
    while (*t < t1 - 1e-13) {
        double hs = fmin(h, t1 - *t), w[4];
        memcpy(w, y, sizeof w);
        rk4(m, w, hs);
        int k = (w[2] > 0) != (y[2] > 0) && y[2] != 0 ? 2 : (w[3] > 0) != (y[3] > 0) && y[3] != 0 ? 3 : 0;
        if (k == 0) {
            memcpy(y, w, sizeof w);
            *t += hs;
            continue;
        }
        double lo = 0, hi = hs;
        for (int it = 0; it < 60; it++) {
            double mid = 0.5 * (lo + hi);
            memcpy(w, y, sizeof w);
            rk4(m, w, mid);
            if ((w[k] > 0) == (y[k] > 0))
                lo = mid;
            else
                hi = mid;
        }
        rk4(m, y, hi);
        y[k] = 0; /* the next phase's sign: rk4 reads 0 as sliding negative, the reversal these data make */
        *t += hi;
        if (*tcross < 0)
            *tcross = *t;
    }
}

/* Both coordinates sliding; beta' reaches zero and reverses: the run's samples against the RK4 reference at
 * h = 1e-3 (error ~1e-10 per phase) on both smooth phases, and the located time of the zero against the
 * reference's. */
static void test_trajectory_against_rk4(void **state)
{
    (void)state;
    dp_right_hand_model m = piston(1.5, 1, 0.05, 0.6, 0.3, 0.25, 0.03);
    double x0[2] = { 0, 0.4 }, v0[2] = { 2, 1.5 };
    dp_run *r = start(&m, x0, v0, 0.5, 0.05);
    dp_record buf[64];
    size_t n;
    int st, rows = 0, after = 0;
    double tev = -1, y[4] = { x0[0], x0[1], v0[0], v0[1] }, t = 0, tref = -1;
    do {
        st = dp_run_next(r, buf, 64, &n);
        for (size_t i = 0; i < n; i++) {
            if (buf[i].type == DP_RECORD_EVENT && tev < 0 && buf[i].u.event.element == 1)
                tev = buf[i].u.event.t;
            if (buf[i].type != DP_RECORD_ROW)
                continue;
            const double *v = buf[i].u.row.val;
            ref_advance(&m, y, &t, buf[i].u.row.t, &tref);
            for (int k = 0; k < 4; k++)
                if (fabs(v[k] - y[k]) > 1e-8)
                    fail_msg("t = %g: component %d %.15g, reference %.15g", t, k, v[k], y[k]);
            assert_true(v[8] == DP_PHASE_SLIP && v[9] == DP_PHASE_SLIP);
            rows++;
            after += tref > 0;
        }
    } while (st == DP_MORE);
    assert_int_equal(st, DP_DONE);
    dp_run_free(r);
    assert_true(rows == 11 && after >= 4);
    if (!(tev > 0) || fabs(tev - tref) > 1e-9)
        fail_msg("beta' = 0 located at %.15g, reference %.15g", tev, tref);
}

/* A paradox at t = 0 stops the run in its first block with the record: which paradox, time, state. */
static void test_paradox_stops_run(void **state)
{
    (void)state;
    dp_right_hand_model m = piston(1, 1, 0, 0.8, 0, 5, 0);
    double x0[2] = { 0, atan(5.0 / 4) }, v0[2] = { 1, 0 };
    dp_run *r = start(&m, x0, v0, 1, 0.1);
    dp_record buf[8];
    size_t n;
    int st = dp_run_next(r, buf, 8, &n);
    assert_int_equal(st, DP_ESOLVE);
    assert_int_equal(n, 0);
    const char *why = dp_run_error(r);
    if (strstr(why, "inconsistency") == NULL || strstr(why, "t=0,") == NULL || strstr(why, "qd=[1,0]") == NULL)
        fail_msg("record: %s", why);
    dp_run_free(r);
    double y0[2] = { 0, M_PI + atan(5.0 / 4) }, w0[2] = { 1, 10 };
    r = start(&m, y0, w0, 1, 0.1);
    assert_int_equal(dp_run_next(r, buf, 8, &n), DP_ESOLVE);
    if (strstr(dp_run_error(r), "indeterminacy") == NULL || strstr(dp_run_error(r), "qdd=[") == NULL)
        fail_msg("record: %s", dp_run_error(r));
    dp_run_free(r);
}

/* x held (x'' = 0), beta sliding with sign sg: beta'' by fixed point on the Lagrangian's second row, the
 * force that holds x, Q1 = a_12 beta'' - b_1, and the cone's margin f1 |N1| - |Q1|. */
static double held(const dp_right_hand_model *m, const double y[4], double sg, double *bdd)
{
    double A[2][2], b[2], N[2], qdd[2] = { 0, 0 };
    lagrange(m, y, y + 2, A, b);
    for (int it = 0; it < 60; it++) {
        reactions(m, y, y + 2, qdd, N);
        qdd[1] = (b[1] - sg * m->f2 * fabs(N[1])) / A[1][1];
    }
    reactions(m, y, y + 2, qdd, N);
    *bdd = qdd[1];
    return m->f1 * fabs(N[0]) - fabs(A[0][1] * qdd[1] - b[0]);
}

static void rk4_held(const dp_right_hand_model *m, double y[4], double h, double sg)
{
    double k[4][2], t[4];
    for (int s = 0; s < 4; s++) {
        memcpy(t, y, sizeof t);
        double c = s == 0 ? 0 : s == 3 ? h : h / 2;
        if (s) {
            t[1] += c * k[s - 1][0];
            t[3] += c * k[s - 1][1];
        }
        k[s][0] = t[3];
        held(m, t, sg, &k[s][1]);
    }
    y[1] += h / 6 * (k[0][0] + 2 * k[1][0] + 2 * k[2][0] + k[3][0]);
    y[3] += h / 6 * (k[0][1] + 2 * k[1][1] + 2 * k[2][1] + k[3][1]);
}

/* The piston held by friction while the body swings down from rest (beta sliding backwards, beta' < 0):
 * the run's samples in the stick phase against RK4 of the held system, and the located time where the
 * force that holds x leaves the cone f1 |N1| against the reference's (bisection on one RK4 step). */
static void test_stick_until_cone(void **state)
{
    (void)state;
    dp_right_hand_model m = piston(1, 1, 0.1, 0.5, 0.3, 0.2, 0.02);
    double x0[2] = { 0, 0.8 }, v0[2] = { 0, 0 }, h = 1e-3, bdd;
    dp_run *r = start(&m, x0, v0, 0.45, 0.05);
    dp_record buf[64];
    size_t n;
    int st, rows = 0;
    double tev = -1, y[4] = { 0, 0.8, 0, 0 }, t = 0;
    do {
        st = dp_run_next(r, buf, 64, &n);
        for (size_t i = 0; i < n; i++) {
            if (buf[i].type == DP_RECORD_EVENT && tev < 0 && buf[i].u.event.element == 0) {
                assert_int_equal(buf[i].u.event.kind, DP_EVENT_SLIP);
                tev = buf[i].u.event.t;
            }
            if (buf[i].type != DP_RECORD_ROW || tev >= 0)
                continue;
            const double *v = buf[i].u.row.val;
            while (t < buf[i].u.row.t - 1e-12)
                rk4_held(&m, y, fmin(h, buf[i].u.row.t - t), -1), t += fmin(h, buf[i].u.row.t - t);
            for (int k = 0; k < 4; k++)
                if (fabs(v[k] - y[k]) > 1e-8)
                    fail_msg("t = %g: component %d %.15g, reference %.15g", t, k, v[k], y[k]);
            assert_true(v[8] == DP_PHASE_STICK && v[4] == 0);
            rows++;
        }
    } while (st == DP_MORE);
    assert_int_equal(st, DP_DONE);
    dp_run_free(r);
    assert_true(rows >= 5);
    double z[4] = { 0, 0.8, 0, 0 }, prev[4], tz = 0;
    while (held(&m, z, -1, &bdd) >= 0) {
        memcpy(prev, z, sizeof z);
        rk4_held(&m, z, h, -1);
        tz += h;
    }
    double lo = 0, hi = h;
    for (int it = 0; it < 60; it++) {
        double mid = 0.5 * (lo + hi), w[4];
        memcpy(w, prev, sizeof w);
        rk4_held(&m, w, mid, -1);
        if (held(&m, w, -1, &bdd) >= 0)
            lo = mid;
        else
            hi = mid;
    }
    double tref = tz - h + hi;
    if (!(tev > 0) || fabs(tev - tref) > 1e-9)
        fail_msg("the cone left at %.15g, reference %.15g", tev, tref);
}

/* Where (2.3) holds, the paper's map of §2, F_s(q'') = (b_s - sum_{i != s} a_si q''_i - f_s sgn(q_s') |N_s(q'')|)
 * / a_ss, contracts: iterated from 0 it reaches the enumeration's one solution. Random piston states with both
 * coordinates sliding and f2 > 0 (k* = 2, no frictionless coordinate), A, b and N from the test's own
 * mechanics; the states where (2.3) fails are skipped, and enough must remain. */
static void test_contraction_where_23_holds(void **state)
{
    (void)state;
    uint64_t seed = 4;
    int checked = 0;
    for (int it = 0; it < 300; it++) {
        dp_right_hand_model m = piston(urand(&seed, 1, 3), urand(&seed, 0.2, 1), urand(&seed, 0.5, 2), urand(&seed, 0.2, 0.6),
                               urand(&seed, 0, M_PI / 2), urand(&seed, 0, 0.4), urand(&seed, 0.01, 0.1));
        double q[2] = { 0, urand(&seed, -M_PI, M_PI) };
        double qd[2] = { urand(&seed, 0.1, 2) * (it % 2 ? 1 : -1), urand(&seed, 0.1, 2) * (it % 3 ? 1 : -1) };
        dp_right_hand_result res;
        dp_right_hand_solve(&m, q, qd, NULL, &res);
        assert_int_equal(res.n, 1);
        dp_right_hand_conditions c;
        dp_right_hand_conditions_at(&m, q, qd, &res.sol[0], &c);
        if (!(c.c23 > 0.05))
            continue;
        double A[2][2], b[2], x[2] = { 0, 0 }, f[2] = { m.f1, m.f2 };
        lagrange(&m, q, qd, A, b);
        for (int k = 0; k < 200; k++) {
            double N[2], y[2];
            reactions(&m, q, qd, x, N);
            for (int s = 0; s < 2; s++)
                y[s] = (b[s] - A[s][1 - s] * x[1 - s] - (qd[s] > 0 ? 1 : -1) * f[s] * fabs(N[s])) / A[s][s];
            x[0] = y[0], x[1] = y[1];
        }
        for (int s = 0; s < 2; s++)
            if (fabs(x[s] - res.sol[0].qdd[s]) > 1e-7 * (1 + fabs(x[s])))
                fail_msg("state %d: the contraction gives qdd%d = %.12g, the enumeration %.12g", it, s, x[s],
                         res.sol[0].qdd[s]);
        checked++;
    }
    if (checked < 50)
        fail_msg("only %d states with (2.3)", checked);
}

/* The theorems for the rod: mu = 1 < 4/3 is (2.3) everywhere (Theorems 4.1, 4.2); sliding x_A' < 0 at
 * theta = 1.1 the margin is m - (3m/4)(sin^2 + mu sin cos) > 0 (Theorems 3.1, 5.1); mu = 1.5 at tan = 2 is
 * Painlevé's inconsistency and no theorem applies. */
static void test_rod_theorems(void **state)
{
    (void)state;
    dp_right_hand_model m = rod(2, 1, 1);
    double q[2] = { 0, 1.1 }, qd[2] = { -0.5, 0 }, s = sin(1.1), c = cos(1.1);
    dp_wp_report rep;
    dp_right_hand_wellposedness(&m, q, qd, &rep);
    assert_true(rep.existence.guaranteed && rep.uniqueness.guaranteed);
    assert_string_equal(rep.existence.theorem, "Matrosov-Finogenko Theorems 4.1, 4.2");
    assert_string_equal(rep.uniqueness.theorem, "Matrosov-Finogenko Theorem 5.1");
    dp_right_hand_result res;
    dp_right_hand_solve(&m, q, qd, NULL, &res);
    assert_int_equal(res.n, 1);
    dp_right_hand_conditions k;
    dp_right_hand_conditions_at(&m, q, qd, &res.sol[0], &k);
    double expect = 2 - 0.75 * 2 * (s * s + s * c);
    if (fabs(k.c23 - expect) > 1e-12)
        fail_msg("(2.3) margin %.15g, expected %.15g", k.c23, expect);
    m.mu = 1.5;
    double q2[2] = { 0, atan(2) };
    dp_right_hand_wellposedness(&m, q2, qd, &rep);
    assert_false(rep.existence.guaranteed);
    assert_null(rep.existence.theorem);
    assert_false(rep.check[0].holds);
}

/* A second acceleration appearing mid-run (its branch's coefficient crossing zero, the candidate arriving from
 * infinity): the run stops there with the indeterminacy and both candidates, in few steps rather than
 * crawling toward the boundary with vanishing steps. */
static void test_indeterminacy_mid_run(void **state)
{
    (void)state;
    dp_right_hand_model m = piston(2.2125135032518366, 3.6782720695148559, 0.6876667405886886, 0.41610333722368964,
                           0.73521748059865155, 5.2067753128738961, 0.25320956192594468);
    double x0[2] = { 0, -1.2396900130422936 }, v0[2] = { -0.68885202598238937, -4.7616041916243752 };
    dp_run *r = start(&m, x0, v0, 1, 0.05);
    dp_record buf[64];
    size_t n;
    int st;
    double tl = -1;
    do {
        st = dp_run_next(r, buf, 64, &n); /* the records of the block that fails come with its status */
        for (size_t i = 0; i < n; i++)
            if (buf[i].type == DP_RECORD_ROW)
                tl = buf[i].u.row.t;
    } while (st == DP_MORE);
    assert_int_equal(st, DP_ESOLVE);
    char why[256];
    snprintf(why, sizeof why, "%s", dp_run_error(r));
    double t, q[2], qd[2];
    if (strstr(why, "Painleve indeterminacy (2 accelerations)") == NULL ||
        sscanf(strstr(why, "t="), "t=%lf, q=[%lf,%lf], qd=[%lf,%lf]", &t, &q[0], &q[1], &qd[0], &qd[1]) != 5)
        fail_msg("record: %s", why);
    assert_true(dp_run_summary(r)->steps < 1000);
    dp_run_free(r);
    if (!(t > tl && t < tl + 0.05))
        fail_msg("stop at %.12g, last row at %.12g: %s", t, tl, why);
    /* the record's state (9 digits) lies within 1e-6 s of motion of the boundary: one solution just before it,
     * two just after, the new one from far away */
    dp_right_hand_result res;
    double qa[2] = { q[0] + 1e-6 * qd[0], q[1] + 1e-6 * qd[1] }, qe[2] = { q[0] - 1e-6 * qd[0], q[1] - 1e-6 * qd[1] };
    dp_right_hand_solve(&m, qa, qd, NULL, &res);
    assert_int_equal(res.n, 2);
    double big = fmax(fabs(res.sol[0].qdd[0]), fabs(res.sol[1].qdd[0]));
    double small = fmin(fabs(res.sol[0].qdd[0]), fabs(res.sol[1].qdd[0]));
    if (!(big > 1e4 && small < 100))
        fail_msg("candidates %g and %g", small, big);
    dp_right_hand_solve(&m, qe, qd, NULL, &res);
    assert_int_equal(res.n, 1);
}

/* Random models and states (both models, every coordinate moving or at rest, alpha at its ends too, f1 up to
 * 6): every run ends - done, or stopped with a record naming a paradox, the rod leaving or reaching the floor -
 * within 2*10^4 integrator steps, every row finite; the stalls a first sweep of this kind found (steps
 * collapsing before a boundary, located events that make no progress) would exceed that. */
static void test_random_runs_end(void **state)
{
    (void)state;
    uint64_t seed = 2026;
    int stopped = 0, done = 0;
    for (int it = 0; it < 400; it++) {
        int isrod = it % 3 == 0;
        dp_right_hand_model m = isrod ? rod(urand(&seed, 0.1, 5), urand(&seed, 0.1, 3), urand(&seed, 0, 3))
                              : piston(urand(&seed, 0.1, 5), urand(&seed, 0.1, 5), it % 4 ? urand(&seed, 0, 2) : 0,
                                       urand(&seed, 0.05, 2), it % 5 ? urand(&seed, 0, M_PI / 2) : (it % 2) * M_PI / 2,
                                       urand(&seed, 0, it % 4 ? 1 : 6), it % 3 ? urand(&seed, 0, 0.5) : 0);
        double x0[2] = { 0, isrod ? urand(&seed, 0.05, 3.1) : urand(&seed, -M_PI, M_PI) };
        double v0[2] = { it % 3 ? urand(&seed, -3, 3) : 0, it % 2 ? urand(&seed, -5, 5) : 0 };
        dp_spec spec;
        dp_spec_init(&spec);
        spec.rh = malloc(sizeof *spec.rh), spec.x0v = calloc(3, sizeof(double)), spec.v0v = calloc(3, sizeof(double));
        *spec.rh = m;
        memcpy(spec.x0v, x0, sizeof x0), memcpy(spec.v0v, v0, sizeof v0);
        spec.solver.kind = DP_SOLVER_RIGHT_HAND, spec.solver.t_end = 3, spec.solver.dt = 0.1;
        spec.solver.rtol = 1e-10, spec.solver.atol = 1e-12;
        dp_errors errs;
        dp_errors_init(&errs);
        int st;
        dp_run *r = dp_run_alloc(&spec, 2e4, &errs, &st);
        dp_spec_clear(&spec);
        assert_non_null(r);
        dp_record buf[64];
        size_t n;
        do {
            st = dp_run_next(r, buf, 64, &n);
            for (size_t i = 0; i < n; i++)
                for (size_t j = 0; buf[i].type == DP_RECORD_ROW && j < dp_run_columns(r)->width; j++)
                    if (!isfinite(buf[i].u.row.val[j]))
                        fail_msg("run %d: a row holds %g", it, buf[i].u.row.val[j]);
        } while (st == DP_MORE);
        const char *why = dp_run_error(r);
        if (st == DP_DONE)
            done++;
        else if (st == DP_ESOLVE && (strstr(why, "Painleve ") || strstr(why, "the rod ")))
            stopped++;
        else
            fail_msg("run %d ended with %d: %s (m %.17g %.17g %.17g x0 %.17g v0 %.17g %.17g)", it, st, why, m.m, m.length,
                     m.mu, x0[1], v0[0], v0[1]);
        dp_run_free(r);
    }
    assert_true(done > 150 && stopped > 50);
}

/* ---- the rod off the floor: flight, landing, impact ---- */

/* The test's own kinetic energy of the rod from A's velocity (xd, yd) and theta' (G = A + l (cos, sin)). */
static double rod_T(const dp_right_hand_model *m, double th, double xd, double yd, double thd)
{
    double l = m->length / 2, vx = xd - l * sin(th) * thd, vy = yd + l * cos(th) * thd;
    return 0.5 * m->m * (vx * vx + vy * vy) + 0.5 * m->m * l * l / 3 * thd * thd;
}

/* The rod's energy T + V from a row (q, qd, ..., gap = [y_A, y_A']). */
static double row_energy(const dp_right_hand_model *m, const double *v)
{
    double l = m->length / 2;
    return rod_T(m, v[1], v[2], v[12], v[3]) + m->m * m->g * (v[11] + l * sin(v[1]));
}

/* Records of a whole run (rows and events copied out), its status. */
typedef struct recs {
    int n, st;
    dp_record rec[4096];
    double val[4096][16];
} recs;

static void collect(dp_run *r, recs *out)
{
    dp_record buf[64];
    size_t n;
    out->n = 0;
    do {
        out->st = dp_run_next(r, buf, 64, &n);
        for (size_t i = 0; i < n && out->n < 4096; i++) {
            out->rec[out->n] = buf[i];
            if (buf[i].type == DP_RECORD_ROW)
                memcpy(out->val[out->n], buf[i].u.row.val, dp_run_columns(r)->width * sizeof(double));
            out->n++;
        }
    } while (out->st == DP_MORE);
}

/* A rod thrown up from above the floor: before it lands every row is the closed form (G's parabola, theta
 * uniform); the landing is the first zero of A's height, found here by a scan and bisection, to 1e-10, the
 * impact's velocity before is the height's rate there, and with e = 0.5 it bounces (a lift-off follows). */
static void test_flight_closed_form(void **state)
{
    (void)state;
    dp_right_hand_model m = rod(1, 1, 0.4);
    m.e = 0.5;
    double x0[3] = { 0.1, 1.0, 0.2 }, v0[3] = { 0.3, 2.0, 3.0 }, l = 0.5, g = m.g;
    double xG = x0[0] + l * cos(x0[1]), yG = x0[2] + l * sin(x0[1]);
    double vx = v0[0] - l * sin(x0[1]) * v0[1], vy = v0[2] + l * cos(x0[1]) * v0[1], w = v0[1];
#define HA(t) (yG + vy * (t) - 0.5 * g * (t) * (t) - l * sin(x0[1] + w * (t)))
    double lo = 0, hi = 0;
    for (double t = 1e-4; hi == 0; t += 1e-4) {
        assert_true(yG + vy * t - 0.5 * g * t * t + l * sin(x0[1] + w * t) > 0); /* B stays up */
        if (HA(t) < 0)
            lo = t - 1e-4, hi = t;
    }
    for (int i = 0; i < 200; i++) {
        double mid = 0.5 * (lo + hi);
        if (HA(mid) > 0)
            lo = mid;
        else
            hi = mid;
    }
    double tland = lo, rate = vy - g * tland - l * w * cos(x0[1] + w * tland);
    recs *R = malloc(sizeof *R);
    dp_run *r = start3(&m, x0, v0, 1.2, 0.01);
    collect(r, R);
    dp_run_free(r);
    int rows = 0, impact = -1;
    for (int i = 0; i < R->n; i++) {
        const dp_record *c = &R->rec[i];
        if (c->type == DP_RECORD_EVENT && c->u.event.kind == DP_EVENT_IMPACT && impact < 0) {
            impact = i;
            if (fabs(c->u.event.t - tland) > 1e-10 || fabs(c->u.event.v - rate) > 1e-9)
                fail_msg("landing at %.15g with rate %.15g, the closed form %.15g, %.15g", c->u.event.t, c->u.event.v,
                         tland, rate);
            assert_true(i + 1 < R->n && R->rec[i + 1].type == DP_RECORD_EVENT && R->rec[i + 1].u.event.kind == DP_EVENT_LIFTOFF);
            assert_true(c->u.event.v_after > 0 && c->u.event.impulse > 0);
        }
        if (c->type != DP_RECORD_ROW || impact >= 0)
            continue;
        double t = c->u.row.t, th = x0[1] + w * t, *v = R->val[i];
        double ref[6] = { xG + vx * t - l * cos(th), th, vx + l * sin(th) * w, w, HA(t), vy - g * t - l * cos(th) * w };
        double got[6] = { v[0], v[1], v[2], v[3], v[11], v[12] };
        for (int k = 0; k < 6; k++)
            if (fabs(got[k] - ref[k]) > 1e-12 * (1 + fabs(ref[k])))
                fail_msg("t = %g: entry %d %.17g, closed form %.17g", t, k, got[k], ref[k]);
        assert_true(v[6] == 0 && v[7] == DP_PHASE_NONE);
        rows++;
    }
#undef HA
    assert_true(impact > 0 && rows == (int)floor(tland / 0.01) + 1);
    free(R);
}

/* A frictionless impact: Newton's law at A with the effective mass m/(1 + 3 cos^2) (the normal's inverse
 * Delassus entry): e = 1 keeps T to rounding, e < 1 loses (1 - e^2) m_eff vn^2 / 2 with the impulse
 * (1 + e) m_eff |vn|; random states. */
static void test_impact_frictionless(void **state)
{
    (void)state;
    uint64_t seed = 11;
    for (int it = 0; it < 500; it++) {
        dp_right_hand_model m = rod(urand(&seed, 0.1, 5), urand(&seed, 0.1, 3), 0);
        double th = urand(&seed, 0.02, M_PI - 0.02), xd = urand(&seed, -3, 3), yd = -urand(&seed, 0.01, 5);
        double thd = urand(&seed, -5, 5), e = it % 2 ? 1 : urand(&seed, 0, 1), c = cos(th);
        double meff = m.m / (1 + 3 * c * c), T0 = rod_T(&m, th, xd, yd, thd);
        dp_right_hand_impact im;
        assert_true(dp_right_hand_rod_impact(&m, th, xd, yd, thd, e, &im));
        double T1 = rod_T(&m, th, im.vt, im.vn, im.thetad), loss = 0.5 * (1 - e * e) * meff * yd * yd;
        if (fabs((T0 - T1) - loss) > 1e-13 * T0 || fabs(im.vn + e * yd) > 1e-12 * fabs(yd) ||
            fabs(im.Pn - (1 + e) * meff * fabs(yd)) > 1e-12 * im.Pn || im.Pt != 0)
            fail_msg("state %d (e = %g): T %.17g -> %.17g (loss %.17g, closed form %.17g), vn %.17g, Pn %.17g", it, e,
                     T0, T1, T0 - T1, loss, im.vn, im.Pn);
    }
}

/* With friction (mu up to 4, past Painlevé's 4/3) the impact never gains energy: T after <= T before, the
 * friction impulse within its cone, the velocities after those of the impulse through the rod's own
 * mechanics (G's momentum and the angular momentum about G), the energy change the works' sum, the
 * restitution's work -e^2 that of compression unless the end stays down; sticking and slip that reverses
 * both occur. */
static void test_impact_dissipates(void **state)
{
    (void)state;
    uint64_t seed = 12;
    int sticks = 0, reverses = 0;
    for (int it = 0; it < 3000; it++) {
        dp_right_hand_model m = rod(urand(&seed, 0.1, 5), urand(&seed, 0.1, 3), urand(&seed, 0, 4));
        double th = urand(&seed, 0.02, M_PI - 0.02), xd = it % 7 ? urand(&seed, -3, 3) : 0, yd = -urand(&seed, 0.01, 5);
        double thd = urand(&seed, -5, 5), e = it % 5 ? urand(&seed, 0, 1) : 1, l = m.length / 2;
        double T0 = rod_T(&m, th, xd, yd, thd);
        dp_right_hand_impact im;
        assert_true(dp_right_hand_rod_impact(&m, th, xd, yd, thd, e, &im));
        double T1 = rod_T(&m, th, im.vt, im.vn, im.thetad);
        /* G's velocity jumps by P/m, theta' by (r_A x P)/I with r_A = -l (cos, sin) */
        double dw = (l * sin(th) * im.Pt - l * cos(th) * im.Pn) / (m.m * l * l / 3);
        double vt = xd + im.Pt / m.m + dw * l * sin(th), vn = yd + im.Pn / m.m - dw * l * cos(th);
        double sc = fabs(xd) + fabs(yd) + l * fabs(thd) + 1e-300;
        if (!(T1 <= T0 * (1 + 1e-13)) || im.vn < 0 || fabs(im.Pt) > m.mu * im.Pn * (1 + 1e-12) + 1e-15 * im.Pn ||
            fabs(im.thetad - thd - dw) > 1e-12 * (fabs(thd) + fabs(dw)) || fabs(vt - im.vt) > 1e-11 * sc ||
            fabs(vn - im.vn) > 1e-11 * sc || fabs((T1 - T0) - (im.work_c + im.work_r + im.work_t)) > 1e-11 * T0)
            fail_msg("state %d (mu %g, e %g, th %g): T %.17g -> %.17g, works %g %g %g, P (%g, %g), v (%g, %g) vs (%g, %g)",
                     it, m.mu, e, th, T0, T1, im.work_c, im.work_r, im.work_t, im.Pt, im.Pn, im.vt, im.vn, vt, vn);
        if (im.vn > 0 && fabs(im.work_r + e * e * im.work_c) > 1e-11 * T0)
            fail_msg("state %d: restitution's work %.17g, -e^2 W_c %.17g", it, im.work_r, -e * e * im.work_c);
        sticks += im.stick && xd != 0;
        reverses += xd * im.vt < 0;
    }
    assert_true(sticks > 100 && reverses > 20);
}

/* A rod dropped on a frictionless floor (e = 0.6) bounces, the bounces accumulate and it slides until it lies
 * flat: between two rows its energy T + V changes by the sum of the impacts' T changes in between, each
 * (Pn/2)(du + du_after) from its event (no friction impulse), to 1e-9; the rows in flight or sliding keep it. */
static void test_dropped_rod_frictionless(void **state)
{
    (void)state;
    dp_right_hand_model m = rod(2, 1, 0);
    m.e = 0.6;
    double x0[3] = { 0, 1.0, 0.3 }, v0[3] = { 0, 1.5, 0 };
    recs *R = malloc(sizeof *R);
    dp_run *r = start3(&m, x0, v0, 1.5, 0.01);
    collect(r, R);
    if (R->st != DP_ESOLVE || strstr(dp_run_error(r), "lies flat") == NULL)
        fail_msg("ended with %d: %s", R->st, dp_run_error(r));
    dp_run_free(r);
    double E = NAN, lost = 0, total = 0, E0 = NAN;
    int impacts = 0, sliding = 0;
    for (int i = 0; i < R->n; i++) {
        const dp_record *c = &R->rec[i];
        if (c->type == DP_RECORD_EVENT && c->u.event.kind == DP_EVENT_IMPACT) {
            lost += 0.5 * c->u.event.impulse * (c->u.event.v + c->u.event.v_after);
            impacts++;
        }
        if (c->type != DP_RECORD_ROW)
            continue;
        double e1 = row_energy(&m, R->val[i]);
        if (isnan(E0))
            E0 = e1;
        else if (fabs(e1 - E - lost) > 1e-9 * E0)
            fail_msg("t = %g: energy %.15g, before %.15g and the impacts' %.15g", c->u.row.t, e1, E, lost);
        total += lost, lost = 0, E = e1;
        sliding += R->val[i][11] == 0 && R->val[i][6] > 0;
    }
    assert_true(impacts >= 5 && sliding >= 3 && total < -0.1 * E0);
    free(R);
}

/* The same rod on a rough floor (mu = 0.3, e = 0.5): it bounces, comes down to stick or slide (an event right
 * after its last impact), the energy never grows from row to row, and is kept between rows in flight with no
 * event between them. */
static void test_dropped_rod_rough(void **state)
{
    (void)state;
    dp_right_hand_model m = rod(1, 1, 0.3);
    m.e = 0.5;
    double x0[3] = { 0, 1.2, 0.5 }, v0[3] = { 0.5, 1, 0 };
    recs *R = malloc(sizeof *R);
    dp_run *r = start3(&m, x0, v0, 1.4, 0.01);
    collect(r, R);
    assert_int_equal(R->st, DP_DONE);
    dp_run_free(r);
    double E = INFINITY, E0 = NAN;
    int impacts = 0, last = -1, events_since = 0, flying = 0, kept = 0;
    for (int i = 0; i < R->n; i++) {
        const dp_record *c = &R->rec[i];
        if (c->type == DP_RECORD_EVENT) {
            events_since++;
            if (c->u.event.kind == DP_EVENT_IMPACT)
                impacts++, last = i;
            continue;
        }
        double e1 = row_energy(&m, R->val[i]);
        if (isnan(E0))
            E0 = e1;
        if (e1 > E + 1e-10 * E0)
            fail_msg("t = %g: the energy grows from %.15g to %.15g", c->u.row.t, E, e1);
        int fl = R->val[i][7] == DP_PHASE_NONE;
        if (fl && flying && events_since == 0) {
            if (fabs(e1 - E) > 1e-10 * E0)
                fail_msg("t = %g: in flight the energy moves from %.15g to %.15g", c->u.row.t, E, e1);
            kept++;
        }
        E = e1, flying = fl, events_since = 0;
    }
    if (!(impacts >= 5 && kept >= 20 && last > 0 && E < 0.6 * E0))
        fail_msg("%d impacts, %d kept, last %d, E %g of %g", impacts, kept, last, E, E0);
    const dp_event *after = &R->rec[last + 1].u.event;
    assert_true(R->rec[last + 1].type == DP_RECORD_EVENT && (after->kind == DP_EVENT_STICK || after->kind == DP_EVENT_SLIP));
    free(R);
}

/* Hostile magnitudes (masses, lengths, g, heights and rates from 1e-300 to 1e300, restitution and mu over
 * their ranges): each rod is refused by the rules or its run ends - done, a record, or the step limit - with
 * every row finite. */
static void test_rod_hostile(void **state)
{
    (void)state;
    uint64_t seed = 13;
    int ran = 0;
    for (int it = 0; it < 300; it++) {
        double dec[6];
        for (int k = 0; k < 6; k++)
            dec[k] = pow(10, urand(&seed, -300, 300) * (it % 3 == 0 ? 1 : 0.05));
        dp_right_hand_model m = rod(dec[0], dec[1], urand(&seed, 0, 5));
        m.e = urand(&seed, 0, 1), m.g = it % 2 ? dec[2] : 9.81;
        double x0[3] = { 0, urand(&seed, 1e-9, M_PI - 1e-9), it % 4 ? dec[3] : 0 };
        double v0[3] = { urand(&seed, -1, 1) * dec[4], urand(&seed, -1, 1) * dec[5], urand(&seed, -1, 1) * dec[3] };
        dp_spec spec;
        dp_spec_init(&spec);
        spec.rh = malloc(sizeof *spec.rh), spec.x0v = malloc(3 * sizeof(double)), spec.v0v = malloc(3 * sizeof(double));
        *spec.rh = m;
        memcpy(spec.x0v, x0, sizeof x0), memcpy(spec.v0v, v0, sizeof v0);
        spec.solver.kind = DP_SOLVER_RIGHT_HAND, spec.solver.t_end = 1, spec.solver.dt = 0.1;
        spec.solver.rtol = 1e-10, spec.solver.atol = 1e-12;
        dp_errors errs;
        dp_errors_init(&errs);
        int st;
        dp_run *r = dp_run_alloc(&spec, 2e4, &errs, &st);
        dp_spec_clear(&spec);
        if (r == NULL) {
            assert_true(errs.n > 0);
            continue;
        }
        ran++;
        dp_record buf[64];
        size_t n;
        do {
            st = dp_run_next(r, buf, 64, &n);
            for (size_t i = 0; i < n; i++)
                for (size_t j = 0; buf[i].type == DP_RECORD_ROW && j < dp_run_columns(r)->width; j++)
                    if (!isfinite(buf[i].u.row.val[j]))
                        fail_msg("run %d: a row holds %g", it, buf[i].u.row.val[j]);
        } while (st == DP_MORE);
        if (st != DP_DONE && st != DP_ESOLVE && st != DP_ELIMIT)
            fail_msg("run %d ended with %d: %s", it, st, dp_run_error(r));
        dp_run_free(r);
    }
    assert_true(ran > 50);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_equations_from_lagrangian),
        cmocka_unit_test(test_painleve_condition),
        cmocka_unit_test(test_painleve_indeterminacy),
        cmocka_unit_test(test_rod_threshold),
        cmocka_unit_test(test_exceptional_states),
        cmocka_unit_test(test_condition_23_sign),
        cmocka_unit_test(test_trajectory_against_rk4),
        cmocka_unit_test(test_paradox_stops_run),
        cmocka_unit_test(test_rod_theorems),
        cmocka_unit_test(test_stick_until_cone),
        cmocka_unit_test(test_contraction_where_23_holds),
        cmocka_unit_test(test_indeterminacy_mid_run),
        cmocka_unit_test(test_random_runs_end),
        cmocka_unit_test(test_flight_closed_form),
        cmocka_unit_test(test_impact_frictionless),
        cmocka_unit_test(test_impact_dissipates),
        cmocka_unit_test(test_dropped_rod_frictionless),
        cmocka_unit_test(test_dropped_rod_rough),
        cmocka_unit_test(test_rod_hostile),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
