/* tests/test_lcp.c - Lemke's method and the enumeration of complementary bases on the worked
 * examples of Cibulka 2014 with their own numbers (Examples 1.6, 2.4, 2.6, 2.7, 2.11, Lemma 2.5, Theorem 2.3), and
 * Lemke against the enumeration on >= 10^4 random P-matrix and PSD problems and on degenerate integer ones;
 * then the problem's units: the same problems scaled by 1e±10, 1e±60, 1e±200 (and rows by unequal powers of
 * ten) answer with the same count and the same z up to the scale, every listed pair a solution by an
 * independent test in long double; the P-matrix test and its witness at every scale; Murty 1978's matrix,
 * whose 2^m pivots take Lemke's limit (the enumeration answers for m = 12, a 422 at /M above), and whose
 * 500 x 500 case stops on the stop hook's word; hostile magnitudes (1e308, 5e-324) in every entry.
 *
 * The references are independent of Lemke's pivoting: closed forms from the seed's text, and the enumeration
 * (each complementary basis' linear system by LU), whose own answers are checked by their definition (z >= 0,
 * w = Mz + q >= 0, z ⊥ w) and, for P-matrices, by the count: exactly one.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <cjson/cJSON.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_rng.h>

#include "dashpot/lcp.h"
#include "dashpot/lcp_json.h"
#include "dashpot/status.h"

#include "check.h"

typedef struct problem {
    size_t m;
    gsl_matrix *M;
    gsl_vector *q, *z, *w;
    dp_lcp *ws;
} problem;

static problem make(size_t m, const double *M, const double *q)
{
    problem p = { m, gsl_matrix_alloc(m, m), gsl_vector_alloc(m), gsl_vector_alloc(m), gsl_vector_alloc(m),
                  dp_lcp_alloc(m) };
    for (size_t i = 0; i < m; i++) {
        if (q)
            gsl_vector_set(p.q, i, q[i]);
        for (size_t j = 0; j < m; j++)
            if (M)
                gsl_matrix_set(p.M, i, j, M[i * m + j]);
    }
    return p;
}

static void drop(problem *p)
{
    gsl_matrix_free(p->M);
    gsl_vector_free(p->q);
    gsl_vector_free(p->z);
    gsl_vector_free(p->w);
    dp_lcp_free(p->ws);
}

static dp_lcp_result lemke(problem *p)
{
    dp_lcp_result r;
    int s = dp_lcp_lemke(p->ws, p->M, p->q, p->z, p->w, &r);
    CHECK(s == DP_OK, "dp_lcp_lemke returned %d", s);
    return r;
}

/* Is z a solution by the definition, to tol (independent of both solvers)? */
static int solves(const problem *p, const double *z, double tol)
{
    for (size_t i = 0; i < p->m; i++) {
        double w = gsl_vector_get(p->q, i);
        for (size_t j = 0; j < p->m; j++)
            w += gsl_matrix_get(p->M, i, j) * z[j];
        if (z[i] < -tol || w < -tol || fabs(z[i] * w) > tol * (1 + fabs(z[i]) + fabs(w)))
            return 0;
    }
    return 1;
}

static double dist(const double *a, const double *b, size_t m)
{
    double d = 0;
    for (size_t i = 0; i < m; i++)
        d = fmax(d, fabs(a[i] - b[i]));
    return d;
}

/* Example 1.6: 0 <= u ⊥ v + u >= 0 has u = v^- = max(-v, 0), v + u = v^+ (M = I, q = v), zeros included. */
static void test_example_1_6(void **state)
{
    (void)state;
    double I[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    double vs[][3] = { { -1, 2, -3 }, { 0, -0.5, 0 }, { 4, 5, 6 }, { -2, -2, -2 }, { 0, 0, 0 } };
    for (size_t k = 0; k < sizeof vs / sizeof vs[0]; k++) {
        problem p = make(3, I, vs[k]);
        dp_lcp_result r = lemke(&p);
        CHECK(r.outcome == DP_LCP_SOLVED, "v #%zu solved", k);
        for (size_t i = 0; i < 3; i++) {
            NEAR(gsl_vector_get(p.z, i), fmax(-vs[k][i], 0), 0);
            NEAR(gsl_vector_get(p.w, i), fmax(vs[k][i], 0), 0);
        }
        dp_lcp_solutions s;
        CHECK(dp_lcp_enumerate(p.M, p.q, &s) == DP_OK, "enumerate");
        CHECK(s.n == 1 && s.singular == 0, "one solution, got %zu (%zu singular)", s.n, s.singular);
        dp_lcp_solutions_clear(&s);
        drop(&p);
    }
}

/* Example 2.4: p ∈ a u + N_R+(u), i.e. M = [a], q = [-p] (w = a u - p). a > 0: u = max(p, 0)/a, µ = a, the
 * solution Lipschitz in p with constant L/µ = 1/a. a = 0: p > 0 none, p < 0 u = 0, p = 0 every u >= 0 (a
 * continuum: one singular basis). a < 0: p > 0 none, p < 0 two, u = 0 and u = p/a (Figure 7). */
static void test_example_2_4(void **state)
{
    (void)state;
    struct { double a, p; size_t n; double u0, u1; int ray; } cases[] = {
        { 2, 3, 1, 1.5, 0, 0 },  { 2, -3, 1, 0, 0, 0 },    { 0.5, 1, 1, 2, 0, 0 },
        { 0, 1, 0, 0, 0, 1 },    { 0, -1, 1, 0, 0, 0 },    { 0, 0, 1, 0, 0, 0 },
        { -2, 1, 0, 0, 0, 1 },   { -2, -3, 2, 0, 1.5, 0 },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double M[1] = { cases[k].a }, q[1] = { -cases[k].p };
        problem p = make(1, M, q);
        dp_lcp_solutions s;
        CHECK(dp_lcp_enumerate(p.M, p.q, &s) == DP_OK, "enumerate");
        CHECK(s.n == cases[k].n, "a = %g, p = %g: %zu solutions, expected %zu", cases[k].a, cases[k].p, s.n,
              cases[k].n);
        if (s.n >= 1)
            NEAR(s.z[0], cases[k].u0, 1e-15);
        if (s.n == 2)
            NEAR(s.z[1], cases[k].u1, 1e-15);
        CHECK(s.singular == (cases[k].a == 0 ? 1u : 0u), "singular bases %zu", s.singular);
        dp_lcp_result r = lemke(&p);
        CHECK((r.outcome == DP_LCP_RAY) == cases[k].ray, "a = %g, p = %g: Lemke outcome %d", cases[k].a,
              cases[k].p, (int)r.outcome);
        if (!cases[k].ray)
            CHECK(solves(&p, p.z->data, 1e-15), "Lemke's answer solves a = %g, p = %g", cases[k].a, cases[k].p);
        dp_lcp_theory t;
        CHECK(dp_lcp_theory_of(p.M, &t) == DP_OK, "theory");
        CHECK(t.p_matrix == (cases[k].a > 0), "P-matrix iff a > 0");
        NEAR(t.mu, cases[k].a, 0);
        if (cases[k].a > 0)
            NEAR(t.lipschitz, 1 / cases[k].a, 1e-15);
        dp_lcp_solutions_clear(&s);
        drop(&p);
    }
}

/* Example 2.6 with Lemma 2.5 and Theorem 2.3: A with <Ah, h> > 0 (here not symmetric: A = [[2, 3], [-3, 1]],
 * symmetric part diag(2, 1), µ = 1) has one solution for every p, and |u1 - u2| <= |p1 - p2| / µ. */
static void test_example_2_6(void **state)
{
    (void)state;
    double A[4] = { 2, 3, -3, 1 };
    problem p = make(2, A, NULL);
    dp_lcp_theory t;
    CHECK(dp_lcp_theory_of(p.M, &t) == DP_OK, "theory");
    NEAR(t.mu, 1.0, 1e-15);
    CHECK(t.pd_symmetric && t.p_matrix == 1, "pd symmetric part, P-matrix");
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double prev_z[2] = { 0 }, prev_p[2] = { 0 };
    for (int k = 0; k < 200; k++) {
        double pv[2] = { 4 * gsl_rng_uniform(rng) - 2, 4 * gsl_rng_uniform(rng) - 2 };
        gsl_vector_set(p.q, 0, -pv[0]);
        gsl_vector_set(p.q, 1, -pv[1]);
        dp_lcp_result r = lemke(&p);
        CHECK(r.outcome == DP_LCP_SOLVED, "solved");
        dp_lcp_solutions s;
        CHECK(dp_lcp_enumerate(p.M, p.q, &s) == DP_OK && s.n == 1, "exactly one solution");
        CHECK(dist(s.z, p.z->data, 2) <= 1e-14, "Lemke = enumeration");
        if (k > 0) {
            double du = hypot(p.z->data[0] - prev_z[0], p.z->data[1] - prev_z[1]);
            double dpv = hypot(pv[0] - prev_p[0], pv[1] - prev_p[1]);
            CHECK(du <= dpv / t.mu + 1e-14, "Lipschitz: |du| = %g > |dp|/µ = %g", du, dpv / t.mu);
        }
        memcpy(prev_z, p.z->data, sizeof prev_z);
        memcpy(prev_p, pv, sizeof prev_p);
        dp_lcp_solutions_clear(&s);
    }
    gsl_rng_free(rng);
    drop(&p);
}

/* Example 2.7, normal compliance: 0 <= y - r + λ/k ⊥ λ >= 0 gives λ = k max(r - y, 0), µ = 1/k. */
static void test_example_2_7(void **state)
{
    (void)state;
    double k = 1e4, r = 0.1, ys[] = { 0.2, 0.1, 0.0999, 0.05 };
    for (size_t i = 0; i < 4; i++) {
        double M[1] = { 1 / k }, q[1] = { ys[i] - r };
        problem p = make(1, M, q);
        lemke(&p);
        NEAR(gsl_vector_get(p.z, 0), k * fmax(r - ys[i], 0), 1e-12 * k);
        drop(&p);
    }
}

/* Example 2.11: A PSD, S(p) = Ap + N_K(p) monotone; for the LCP the solution set is convex (Proposition 2.2
 * (ii)): with A = [[1, 1], [1, 1]] (singular, PSD) and q = (-1, -1) every z >= 0 with z1 + z2 = 1 solves.
 * The enumeration finds the two vertices (1, 0), (0, 1), reports the singular basis, and Lemke lands on one
 * of them. With q = (1, -1): w1 = w2 + 2 > 0 forces z1 = 0, then w2 = z2 - 1 = 0 (z2 > 0), so z = (0, 1) is
 * the only solution. µ = 0: PSD, not positive definite. */
static void test_example_2_11(void **state)
{
    (void)state;
    double A[4] = { 1, 1, 1, 1 }, q[2] = { -1, -1 };
    problem p = make(2, A, q);
    dp_lcp_solutions s;
    CHECK(dp_lcp_enumerate(p.M, p.q, &s) == DP_OK, "enumerate");
    CHECK(s.n == 2 && s.singular == 1, "two vertices and one singular basis, got %zu, %zu", s.n, s.singular);
    dp_lcp_result r = lemke(&p);
    CHECK(r.outcome == DP_LCP_SOLVED, "solved");
    NEAR(p.z->data[0] + p.z->data[1], 1.0, 1e-15);
    CHECK(solves(&p, p.z->data, 1e-15), "Lemke's answer solves it");
    dp_lcp_theory t;
    CHECK(dp_lcp_theory_of(p.M, &t) == DP_OK, "theory");
    CHECK(t.psd && !t.pd_symmetric && t.p_matrix == 0, "PSD, not PD, not P");
    NEAR(t.mu, 0, 1e-15);
    dp_lcp_solutions_clear(&s);
    gsl_vector_set(p.q, 0, 1);
    CHECK(dp_lcp_enumerate(p.M, p.q, &s) == DP_OK && s.n == 1, "one solution for q = (1, -1)");
    NEAR(s.z[0], 0, 0);
    NEAR(s.z[1], 1, 1e-15);
    lemke(&p);
    NEAR(p.z->data[1], 1, 1e-15);
    dp_lcp_solutions_clear(&s);
    drop(&p);
}

/* Not a P-matrix: the test's witness is the failing principal minor (here the determinant). */
static void test_p_matrix_witness(void **state)
{
    (void)state;
    double M[4] = { 1, 2, 3, 1 }; /* minors 1, 1, det = 1 - 6 = -5 */
    problem p = make(2, M, NULL);
    dp_lcp_theory t;
    CHECK(dp_lcp_theory_of(p.M, &t) == DP_OK, "theory");
    CHECK(t.p_matrix == 0 && t.minor_set == 3u, "not P, witness {1,2}, got %u", t.minor_set);
    NEAR(t.minor, -5, 1e-14);
    NEAR(t.mu, 1 - 2.5, 1e-14); /* symmetric part [[1, 2.5], [2.5, 1]]: eigenvalues 3.5, -1.5 */
    drop(&p);
}

/* Random problems of size 1..8; kind 0: P by the principal-minor test, 1: positive definite symmetric part
 * plus a skew part, 2: PSD of rank < m (B Bᵀ + skew), 3: degenerate integer data (entries in -2..2, q with
 * zeros, so ratio ties are exact). */
static void random_problem(gsl_rng *rng, int kind, problem *p)
{
    size_t m = p->m;
    for (;;) {
        if (kind == 1 || kind == 2) {
            size_t rank = kind == 1 ? m + 1 : (m > 1 ? m - 1 : 1);
            gsl_matrix_set_zero(p->M);
            for (size_t c = 0; c < rank; c++) {
                double b[DP_LCP_MAX];
                for (size_t i = 0; i < m; i++)
                    b[i] = 2 * gsl_rng_uniform(rng) - 1;
                for (size_t i = 0; i < m; i++)
                    for (size_t j = 0; j < m; j++)
                        p->M->data[i * m + j] += b[i] * b[j];
            }
            for (size_t i = 0; i < m; i++)
                for (size_t j = 0; j < i; j++) {
                    double s = 2 * gsl_rng_uniform(rng) - 1;
                    p->M->data[i * m + j] += s;
                    p->M->data[j * m + i] -= s;
                }
        } else {
            for (size_t i = 0; i < m * m; i++)
                p->M->data[i] = kind == 3 ? (double)((int)gsl_rng_uniform_int(rng, 5) - 2)
                                          : 4 * gsl_rng_uniform(rng) - 2 + (i % (m + 1) == 0 ? 2.5 : 0);
        }
        for (size_t i = 0; i < m; i++)
            p->q->data[i] = kind == 3 ? (double)((int)gsl_rng_uniform_int(rng, 5) - 2) * (gsl_rng_uniform(rng) < 0.5)
                                      : 4 * gsl_rng_uniform(rng) - 2;
        if (kind != 0)
            return;
        dp_lcp_theory t;
        CHECK(dp_lcp_theory_of(p->M, &t) == DP_OK, "theory");
        if (t.p_matrix == 1)
            return;
    }
}

static void test_random_against_enumeration(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    size_t total = 0, solved = 0, rays = 0, degenerate_solved = 0;
    for (int kind = 0; kind < 4; kind++) {
        for (int n = 0; n < 2600; n++) {
            size_t m = 1 + (size_t)n % 8;
            problem p = make(m, NULL, NULL);
            random_problem(rng, kind, &p);
            dp_lcp_solutions s;
            CHECK(dp_lcp_enumerate(p.M, p.q, &s) == DP_OK, "enumerate");
            for (size_t k = 0; k < s.n; k++)
                CHECK(solves(&p, s.z + k * m, 1e-9), "enumerated solution %zu solves", k);
            dp_lcp_result r = lemke(&p);
            total++;
            if (r.outcome == DP_LCP_SOLVED) {
                solved++;
                CHECK(solves(&p, p.z->data, 1e-11), "kind %d m %zu #%d: Lemke's answer solves (residual %g)", kind,
                      m, n, r.residual);
                CHECK(r.residual <= 1e-12, "kind %d: relative residual %g", kind, r.residual);
                size_t k = 0;
                while (k < s.n && dist(s.z + k * m, p.z->data, m) > 1e-9 * (1 + fabs(s.z[k * m])))
                    k++;
                CHECK(k < s.n, "kind %d m %zu #%d: Lemke's solution is one of the %zu enumerated",
                      kind, m, n, s.n);
                degenerate_solved += kind == 3;
            } else {
                rays++;
                /* A ray proves infeasibility for P-matrices (never happens) and for PSD M (Cottle-Pang-Stone
                 * Thm 4.4.13: copositive-plus); for general M it proves nothing. */
                if (kind <= 2)
                    CHECK(s.n == 0, "kind %d m %zu #%d: Lemke's ray but %zu solutions", kind, m, n, s.n);
            }
            if (kind <= 1)
                CHECK(s.n == 1 && r.outcome == DP_LCP_SOLVED, "P-matrix: exactly one solution, got %zu", s.n);
            dp_lcp_solutions_clear(&s);
            drop(&p);
        }
    }
    printf("random: %zu problems, %zu solved by Lemke (%zu degenerate integer ones), %zu rays\n", total, solved,
           degenerate_solved, rays);
    CHECK(total >= 10000 && degenerate_solved > 500, "enough problems");
    gsl_rng_free(rng);
}

/* Larger P problems (m = 30, 100) against the definition, since enumeration is out of reach. */
static void test_large(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    size_t sizes[] = { 30, 100 };
    for (size_t k = 0; k < 2; k++) {
        for (int n = 0; n < 20; n++) {
            problem p = make(sizes[k], NULL, NULL);
            random_problem(rng, 1, &p);
            dp_lcp_result r = lemke(&p);
            CHECK(r.outcome == DP_LCP_SOLVED && solves(&p, p.z->data, 1e-10), "m = %zu solved", sizes[k]);
            CHECK(r.residual <= 1e-11, "residual %g", r.residual);
            drop(&p);
        }
    }
    gsl_rng_free(rng);
}

static void test_bad_input(void **state)
{
    (void)state;
    problem p = make(2, (double[]){ 1, 0, 0, 1 }, (double[]){ -1, NAN });
    dp_lcp_result r;
    CHECK(dp_lcp_lemke(p.ws, p.M, p.q, p.z, p.w, &r) == DP_EINVAL, "NaN in q");
    gsl_vector *q3 = gsl_vector_calloc(3);
    CHECK(dp_lcp_lemke(p.ws, p.M, q3, p.z, p.w, &r) == DP_EINVAL, "size mismatch");
    dp_lcp_solutions s;
    CHECK(dp_lcp_enumerate(p.M, q3, &s) == DP_EINVAL, "size mismatch in enumeration");
    dp_lcp_solutions_clear(&s);
    CHECK(dp_lcp_alloc(0) == NULL && dp_lcp_alloc(DP_LCP_MAX + 1) == NULL, "sizes out of range");
    gsl_vector_free(q3);
    drop(&p);
}

/* Badly scaled problems (entries 10^-9 .. 1, where a tiny pivot amplifies the tableau's rounding): the
 * residual, measured here by the definition relative to |q| + |M| |z|, must still be at rounding level.
 * Measured: with the refinement step worst 2e-16; with the tableau's values alone 12 of ~13800 solved
 * problems are above 1e-12 (worst 1.4e-10), and with an LU solve of the final basis instead (the solver
 * before) 1 is (worst 2.8e-11): both fail. */
static void test_badly_scaled(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    size_t solved = 0, above = 0;
    double worst = 0;
    for (int t = 0; t < 20000; t++) {
        size_t m = 2 + (size_t)t % 5;
        problem p = make(m, NULL, NULL);
        for (size_t i = 0; i < m; i++) {
            for (size_t j = 0; j < m; j++)
                gsl_matrix_set(p.M, i, j, (2 * gsl_rng_uniform(rng) - 1) * pow(10, -9 * gsl_rng_uniform(rng)));
            gsl_matrix_set(p.M, i, i, fabs(gsl_matrix_get(p.M, i, i)));
            gsl_vector_set(p.q, i, 2 * gsl_rng_uniform(rng) - 1);
        }
        dp_lcp_result r = lemke(&p);
        if (r.outcome == DP_LCP_SOLVED) {
            double zmax = 0, mmax = 0, qmax = 0, e = 0;
            for (size_t i = 0; i < m; i++) {
                zmax = fmax(zmax, fabs(p.z->data[i]));
                qmax = fmax(qmax, fabs(p.q->data[i]));
                for (size_t j = 0; j < m; j++)
                    mmax = fmax(mmax, fabs(gsl_matrix_get(p.M, i, j)));
            }
            for (size_t i = 0; i < m; i++) {
                double w = gsl_vector_get(p.q, i), z = p.z->data[i];
                for (size_t j = 0; j < m; j++)
                    w += gsl_matrix_get(p.M, i, j) * p.z->data[j];
                e = fmax(e, fmax(fmax(-z, -w), fabs(fmin(z, w))));
            }
            e /= qmax + mmax * zmax;
            solved++;
            above += e > 1e-12;
            worst = fmax(worst, e);
        }
        drop(&p);
    }
    printf("badly scaled: %zu solved, %zu above 1e-12 relative, worst %.3g\n", solved, above, worst);
    CHECK(solved > 10000, "solved %zu", solved);
    CHECK(above == 0 && worst <= 1e-14, "%zu above 1e-12, worst %g", above, worst);
    gsl_rng_free(rng);
}

/* Hilbert matrices (positive definite, condition 1e10 .. 1e16) with q = -M z*, z* > 0: the answer is z*,
 * every z basic. From m = 10 the refined answer fails its check and the unrefined one is compared with it;
 * either way the residual (by the definition, relative) is at rounding level, whereas z itself is only as
 * good as the conditioning allows (the backward error is what a pivoting method controls). */
static void test_ill_conditioned(void **state)
{
    (void)state;
    for (size_t m = 6; m <= 12; m++) {
        problem p = make(m, NULL, NULL);
        double zs[12], qmax = 0, zmax = 0, e = 0;
        for (size_t j = 0; j < m; j++)
            zs[j] = 1.0 + 0.1 * (double)j;
        for (size_t i = 0; i < m; i++) {
            double q = 0;
            for (size_t j = 0; j < m; j++) {
                gsl_matrix_set(p.M, i, j, 1.0 / (double)(i + j + 1));
                q -= zs[j] / (double)(i + j + 1);
            }
            gsl_vector_set(p.q, i, q);
            qmax = fmax(qmax, fabs(q));
        }
        dp_lcp_result r = lemke(&p);
        CHECK(r.outcome == DP_LCP_SOLVED, "Hilbert m = %zu solved", m);
        for (size_t i = 0; i < m; i++)
            zmax = fmax(zmax, p.z->data[i]);
        for (size_t i = 0; i < m; i++) {
            double w = gsl_vector_get(p.q, i), z = p.z->data[i];
            for (size_t j = 0; j < m; j++)
                w += gsl_matrix_get(p.M, i, j) * p.z->data[j];
            e = fmax(e, fmax(fmax(-z, -w), fabs(fmin(z, w))));
        }
        CHECK(e <= 1e-12 * (qmax + zmax), "Hilbert m = %zu: residual %g", m, e);
        CHECK(r.residual <= 1e-12, "reported residual %g (relative to each row's terms)", r.residual);
        if (m <= 8)
            CHECK(dist(p.z->data, zs, m) <= 1e-5, "Hilbert m = %zu: z = z*", m);
        drop(&p);
    }
}

/* ---- the problem's units ---------------------------------------------------------------------------- */

/* Is z a solution, by a test of its own in long double: each row's violation below 1e-8 of its terms at z or
 * 1e-12 of its normwise size (|q_i| + max_j |M_ij| max |z|)? */
static int solves_rel(const gsl_matrix *M, const gsl_vector *q, const double *z)
{
    size_t m = q->size;
    long double zbig = 0;
    for (size_t j = 0; j < m; j++) {
        if (z[j] < 0)
            return 0;
        zbig = fmaxl(zbig, z[j]);
    }
    for (size_t i = 0; i < m; i++) {
        long double w = gsl_vector_get(q, i), terms = fabsl(w), row = 0;
        for (size_t j = 0; j < m; j++) {
            long double t = (long double)gsl_matrix_get(M, i, j) * z[j];
            w += t, terms += fabsl(t), row = fmaxl(row, fabsl((long double)gsl_matrix_get(M, i, j)));
        }
        long double tol = 1e-8L * terms + 1e-12L * (fabsl((long double)gsl_vector_get(q, i)) + row * zbig);
        if (w < -tol || (z[i] > 0 && fabsl(w) > tol && (long double)z[i] * row > 1e-8L * (terms + 1e-300L)))
            return 0;
    }
    return 1;
}

/* The route's answer to (M, q) as a cJSON tree (NULL when it refused), and its status. */
static cJSON *respond(const gsl_matrix *M, const gsl_vector *q, const dp_stop *stop, int *status, dp_errors *e)
{
    size_t m = q->size;
    char *doc = malloc(64 * (m * m + m) + 64), *at = doc;
    at += sprintf(at, "{\"M\":[");
    for (size_t i = 0; i < m; i++) {
        at += sprintf(at, "%s[", i ? "," : "");
        for (size_t j = 0; j < m; j++)
            at += sprintf(at, "%s%.17g", j ? "," : "", gsl_matrix_get(M, i, j));
        at += sprintf(at, "]");
    }
    at += sprintf(at, "],\"q\":[");
    for (size_t i = 0; i < m; i++)
        at += sprintf(at, "%s%.17g", i ? "," : "", gsl_vector_get(q, i));
    at += sprintf(at, "]}");
    dp_buf out = { 0 };
    dp_errors_init(e);
    *status = dp_lcp_respond_until(doc, strlen(doc), stop, &out, e);
    free(doc);
    cJSON *d = NULL;
    if (*status == DP_OK) {
        CHECK(strstr(out.data, "nan") == NULL && strstr(out.data, "inf") == NULL, "no NaN or inf: %s", out.data);
        d = cJSON_ParseWithLength(out.data, out.len);
        CHECK(d != NULL, "the answer parses: %s", out.data);
    }
    dp_buf_free(&out);
    return d;
}

/* An answer agrees with itself: count = the solutions listed, each a solution by solves_rel, Lemke's solved z
 * among them, and the verdict says one solution exactly when one is listed. The count. */
static size_t consistent_answer(const cJSON *d, const gsl_matrix *M, const gsl_vector *q)
{
    size_t m = q->size;
    const cJSON *sol = cJSON_GetObjectItem(d, "solutions"), *lemke = cJSON_GetObjectItem(d, "lemke");
    size_t n = (size_t)cJSON_GetArraySize(sol);
    CHECK((size_t)cJSON_GetObjectItem(d, "count")->valuedouble == n, "count = the solutions listed");
    double z[DP_LCP_ENUM_MAX];
    for (const cJSON *s = sol->child; s; s = s->next) {
        size_t j = 0;
        for (const cJSON *x = cJSON_GetObjectItem(s, "z")->child; x; x = x->next)
            z[j++] = x->valuedouble;
        if (!(j == m && solves_rel(M, q, z))) {
            char *t = cJSON_PrintUnformatted(d);
            for (size_t i = 0; i < m; i++) {
                for (size_t k = 0; k < m; k++)
                    print_error("%.17g ", gsl_matrix_get(M, i, k));
                print_error("| %.17g\n", gsl_vector_get(q, i));
            }
            print_error("%s\n", t);
            free(t);
        }
        CHECK(j == m && solves_rel(M, q, z), "every listed z is a solution");
    }
    const char *v = cJSON_GetObjectItem(d, "verdict")->valuestring;
    CHECK((strncmp(v, "exactly one", 11) == 0) == (n == 1 && cJSON_IsTrue(cJSON_GetObjectItem(
              cJSON_GetObjectItem(d, "theory"), "p_matrix"))) || (n != 1 && strncmp(v, "exactly one", 11) != 0),
          "the verdict \"%s\" agrees with %zu listed", v, n);
    if (n == 1)
        CHECK(strncmp(v, "no solution", 11) != 0 && strncmp(v, "0 ", 2) != 0, "verdict \"%s\" with one listed", v);
    if (strcmp(cJSON_GetObjectItem(lemke, "outcome")->valuestring, "solved") == 0) {
        size_t j = 0;
        for (const cJSON *x = cJSON_GetObjectItem(lemke, "z")->child; x; x = x->next)
            z[j++] = x->valuedouble;
        CHECK(solves_rel(M, q, z), "Lemke's solved z is a solution");
    }
    return n;
}

/* The listed z of an answer, k-th, into z. */
static void listed_z(const cJSON *d, size_t k, double *z)
{
    const cJSON *s = cJSON_GetArrayItem(cJSON_GetObjectItem(d, "solutions"), (int)k);
    size_t j = 0;
    for (const cJSON *x = cJSON_GetObjectItem(s, "z")->child; x; x = x->next)
        z[j++] = x->valuedouble;
}

/* Is z (scaled by 1/zs) among the listed solutions of d, to 1e-8 of the largest entry? */
static int among(const cJSON *d, const double *z, double zs, size_t m)
{
    double y[DP_LCP_ENUM_MAX];
    size_t n = (size_t)cJSON_GetArraySize(cJSON_GetObjectItem(d, "solutions"));
    for (size_t k = 0; k < n; k++) {
        listed_z(d, k, y);
        double diff = 0, big = 0;
        for (size_t j = 0; j < m; j++) {
            diff = fmax(diff, fabs(y[j] * zs - z[j]));
            big = fmax(big, fabs(z[j]));
        }
        if (diff <= 1e-8 * big || (big == 0 && diff == 0))
            return 1;
    }
    return 0;
}

/* (cM, cq): the same z; (M, cq): z times c; rows times unequal powers of ten: the same z. */
static void test_scalings(void **state)
{
    (void)state;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    const double scales[] = { 1e10, 1e-10, 1e60, 1e-60, 1e200, 1e-200 };
    size_t cases = 0, several = 0;
    for (int n = 0; n < 400; n++) {
        int kind = n % 4;
        size_t m = 1 + (size_t)n % 6;
        problem p = make(m, NULL, NULL);
        random_problem(rng, kind, &p);
        int st;
        dp_errors e;
        cJSON *d0 = respond(p.M, p.q, NULL, &st, &e);
        CHECK(st == DP_OK, "the unscaled problem answers");
        size_t n0 = consistent_answer(d0, p.M, p.q);
        several += n0 > 1;
        for (size_t k = 0; k < sizeof scales / sizeof *scales; k++) {
            for (int how = 0; how < 3; how++) {
                problem s = make(m, NULL, NULL);
                double c = scales[k], zs = how == 1 ? c : 1.0;
                for (size_t i = 0; i < m; i++) {
                    double row = how == 2 ? pow(10, (double)(int)gsl_rng_uniform_int(rng, 401) - 200) : c;
                    gsl_vector_set(s.q, i, gsl_vector_get(p.q, i) * row);
                    for (size_t j = 0; j < m; j++)
                        gsl_matrix_set(s.M, i, j, gsl_matrix_get(p.M, i, j) * (how == 1 ? 1.0 : row));
                }
                cJSON *d = respond(s.M, s.q, NULL, &st, &e);
                CHECK(st == DP_OK, "kind %d m %zu scaled by %g (%d) answers", kind, m, c, how);
                size_t nk = consistent_answer(d, s.M, s.q);
                CHECK(nk == n0, "kind %d m %zu #%d scaled by %g (%d): %zu solutions, unscaled %zu", kind, m, n, c,
                      how, nk, n0);
                double z[DP_LCP_ENUM_MAX];
                for (size_t t = 0; t < nk; t++) {
                    listed_z(d, t, z);
                    CHECK(among(d0, z, zs, m), "kind %d m %zu scaled by %g (%d): solution %zu is the unscaled one",
                          kind, m, c, how, t);
                }
                cJSON_Delete(d);
                drop(&s);
                cases++;
            }
        }
        cJSON_Delete(d0);
        drop(&p);
    }
    printf("scalings: %zu scaled problems, %zu originals with several solutions\n", cases, several);
    CHECK(several > 10, "some problems with several solutions among them (%zu)", several);
    gsl_rng_free(rng);
}

/* The reviewed cases: a non-solution listed beside the solution (the acceptance tolerance was absolute), the
 * counts 4 and 6 of an SPD problem scaled by 1e10 and 1e-10, 1e200 I "solved" with w = -1, a positive minor
 * as the witness at 1e±60, z = null for a tiny M and a huge q. */
static void test_reviewed_scales(void **state)
{
    (void)state;
    int st;
    dp_errors e;
    problem a = make(2, (double[]){ 1.42, 0, 2.84, 2 }, (double[]){ 8.9e9, -1.9e8 });
    cJSON *d = respond(a.M, a.q, NULL, &st, &e);
    CHECK(st == DP_OK && consistent_answer(d, a.M, a.q) == 1, "one solution listed");
    double z[2];
    listed_z(d, 0, z);
    CHECK(z[0] == 0 && fabs(z[1] - 9.5e7) <= 1e-8 * 9.5e7, "z = (0, 9.5e7), got (%g, %g)", z[0], z[1]);
    cJSON_Delete(d);
    drop(&a);
    const double scales[] = { 1, 1e10, 1e-10, 1e60, 1e-60, 1e200, 1e-200 };
    for (size_t k = 0; k < sizeof scales / sizeof *scales; k++) {
        double c = scales[k];
        problem p = make(2, (double[]){ 2 * c, c, c, 2 * c }, (double[]){ -c, -c });
        d = respond(p.M, p.q, NULL, &st, &e);
        CHECK(st == DP_OK && consistent_answer(d, p.M, p.q) == 1, "SPD times %g: one solution", c);
        listed_z(d, 0, z);
        NEAR(z[0], 1.0 / 3, 1e-15);
        NEAR(z[1], 1.0 / 3, 1e-15);
        cJSON_Delete(d);
        dp_lcp_theory t;
        CHECK(dp_lcp_theory_of(p.M, &t) == DP_OK && t.p_matrix == 1 && t.pd_symmetric, "times %g: P, PD", c);
        NEAR(t.mu / c, 1, 1e-14);
        drop(&p);
        problem n = make(2, (double[]){ c, 2 * c, 3 * c, 4 * c }, NULL); /* minors c, 4c, -2 c^2 */
        CHECK(dp_lcp_theory_of(n.M, &t) == DP_OK && t.p_matrix == 0 && t.minor_set == 3u, "times %g: not P", c);
        if (c * c < 1e300 && c * c > 1e-300)
            CHECK(t.minor < 0 && fabs(t.minor / (c * c) + 2) <= 1e-14, "times %g: the witness -2 c^2 = %g", c, t.minor);
        else if (c > 1) /* beyond the doubles: NaN (null on the wire), the rows still name it */
            CHECK(isnan(t.minor), "times %g: the witness -2 c^2 is beyond the doubles: NaN, got %g", c, t.minor);
        else /* below them: -0, a negative number that underflowed */
            CHECK(t.minor == 0 && signbit(t.minor), "times %g: the witness -2 c^2 underflows to -0, got %g", c, t.minor);
        drop(&n);
    }
    problem big = make(2, (double[]){ 1e200, 0, 0, 1e200 }, (double[]){ -1, -1 });
    dp_lcp_result r;
    CHECK(dp_lcp_lemke(big.ws, big.M, big.q, big.z, big.w, &r) == DP_OK && r.outcome == DP_LCP_SOLVED, "1e200 I");
    CHECK(big.z->data[0] == 1e-200 && big.z->data[1] == 1e-200 && big.w->data[0] == 0 && big.w->data[1] == 0,
          "z = 1e-200, w = 0, got z (%g, %g), w (%g, %g)", big.z->data[0], big.z->data[1], big.w->data[0],
          big.w->data[1]);
    drop(&big);
    problem huge = make(2, (double[]){ 1e-200, 0, 0, 1e-200 }, (double[]){ -1e200, -1 });
    CHECK(dp_lcp_lemke(huge.ws, huge.M, huge.q, huge.z, huge.w, &r) == DP_ENONFINITE, "z = 1e400: DP_ENONFINITE");
    d = respond(huge.M, huge.q, NULL, &st, &e);
    CHECK(d == NULL && st == DP_EINVAL && e.n == 1 && strcmp(e.item[0].pointer, "/q") == 0,
          "a 422 at /q, got %d at %s", st, e.n ? e.item[0].pointer : "-");
    drop(&huge);
}

/* Murty 1978's matrix: 1 on the diagonal, 3/2 below it (his 2 would be halved by the equilibration of the
 * rows, and the scaled problem takes 2 pivots; 3/2 is left as it is and keeps his 2^m), q = -e. A P-matrix
 * (triangular, unit diagonal): exactly one solution, z = e_1. */
static problem murty(size_t m)
{
    problem p = make(m, NULL, NULL);
    for (size_t i = 0; i < m; i++) {
        gsl_vector_set(p.q, i, -1);
        for (size_t j = 0; j < m; j++)
            gsl_matrix_set(p.M, i, j, i == j ? 1 : j < i ? 1.5 : 0);
    }
    return p;
}

static void test_murty(void **state)
{
    (void)state;
    problem p = murty(10);
    dp_lcp_result r;
    CHECK(dp_lcp_lemke(p.ws, p.M, p.q, p.z, p.w, &r) == DP_OK && r.pivots == 1024, "m = 10: 2^10 pivots, %zu",
          r.pivots);
    drop(&p);
    p = murty(12);
    CHECK(dp_lcp_lemke(p.ws, p.M, p.q, p.z, p.w, &r) == DP_ELIMIT && r.pivots == dp_lcp_pivot_limit(12),
          "m = 12: the limit, %zu pivots", r.pivots);
    int st;
    dp_errors e;
    cJSON *d = respond(p.M, p.q, NULL, &st, &e);
    CHECK(st == DP_OK && consistent_answer(d, p.M, p.q) == 1, "m = 12 answered by the enumeration: one solution");
    const cJSON *l = cJSON_GetObjectItem(d, "lemke");
    CHECK(strcmp(cJSON_GetObjectItem(l, "outcome")->valuestring, "pivot-limit") == 0 &&
          cJSON_IsNull(cJSON_GetObjectItem(l, "z")), "Lemke's outcome pivot-limit, no z");
    double z[12];
    listed_z(d, 0, z);
    for (size_t j = 0; j < 12; j++)
        NEAR(z[j], j == 0, 0);
    CHECK(strncmp(cJSON_GetObjectItem(d, "verdict")->valuestring, "exactly one solution: ", 22) == 0,
          "verdict %s", cJSON_GetObjectItem(d, "verdict")->valuestring);
    cJSON_Delete(d);
    drop(&p);
    p = murty(13);
    d = respond(p.M, p.q, NULL, &st, &e);
    CHECK(d == NULL && st == DP_ELIMIT && e.n == 1 && strcmp(e.item[0].pointer, "/M") == 0 &&
          strstr(e.item[0].message, "3600 pivots") != NULL, "m = 13: over-limit at /M naming the pivots: %s",
          e.n ? e.item[0].message : "-");
    drop(&p);
}

/* A stop hook that says stop at its n-th question. */
typedef struct countdown {
    int asked, stop_at;
} countdown;

static int count_down(void *ctx)
{
    countdown *c = ctx;
    return ++c->asked >= c->stop_at;
}

static void test_murty_stopped(void **state)
{
    (void)state;
    problem p = murty(DP_LCP_MAX);
    countdown c = { 0, 5 };
    dp_stop stop = { count_down, &c };
    dp_lcp_result r;
    CHECK(dp_lcp_lemke_until(p.ws, p.M, p.q, p.z, p.w, &r, &stop) == DP_ECANCEL && c.asked == 5,
          "m = 500: DP_ECANCEL at the 5th question (asked %d, %zu pivots)", c.asked, r.pivots);
    CHECK(r.pivots < 100, "within a few pivots of it: %zu", r.pivots);
    c = (countdown){ 0, 3 };
    int st;
    dp_errors e;
    CHECK(respond(p.M, p.q, &stop, &st, &e) == NULL && st == DP_ECANCEL && c.asked == 3, "the route: DP_ECANCEL");
    drop(&p);
    p = murty(12); /* the enumeration polls too: Lemke takes its limit unasked-to-stop, then the bases */
    c = (countdown){ 0, 1000000 };
    CHECK(dp_lcp_lemke_until(p.ws, p.M, p.q, p.z, p.w, &r, &stop) == DP_ELIMIT, "limit");
    int lemke_polls = c.asked;
    c = (countdown){ 0, lemke_polls + 2 };
    CHECK(respond(p.M, p.q, &stop, &st, &e) == NULL && st == DP_ECANCEL, "the enumeration stops too");
    dp_lcp_solutions s;
    c = (countdown){ 0, 1 };
    CHECK(dp_lcp_enumerate_until(p.M, p.q, &s, &stop) == DP_ECANCEL && s.n <= 1, "the enumeration alone");
    dp_lcp_solutions_clear(&s);
    drop(&p);
}

/* Every entry of M and q drawn from the extremes of the doubles, 1..4 rows: an answer (every listed pair a
 * solution, no NaN or inf) or a 422 at /q or /M, never a crash (the SAN=1 build runs this too). */
static void test_hostile_magnitudes(void **state)
{
    (void)state;
    const double v[] = { 1e308, -1e308, 5e-324, -5e-324, 0, 1, -1, 1.7976931348623157e308, -2.2250738585072014e-308 };
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    size_t answered = 0, refused = 0;
    for (int n = 0; n < 3000; n++) {
        size_t m = 1 + (size_t)n % 4;
        problem p = make(m, NULL, NULL);
        for (size_t i = 0; i < m; i++) {
            gsl_vector_set(p.q, i, v[gsl_rng_uniform_int(rng, 9)]);
            for (size_t j = 0; j < m; j++)
                gsl_matrix_set(p.M, i, j, v[gsl_rng_uniform_int(rng, 9)]);
        }
        int st;
        dp_errors e;
        cJSON *d = respond(p.M, p.q, NULL, &st, &e);
        if (d) {
            consistent_answer(d, p.M, p.q);
            answered++;
        } else {
            CHECK(st == DP_EINVAL && e.n >= 1 && (strcmp(e.item[0].pointer, "/q") == 0 ||
                                                 strcmp(e.item[0].pointer, "/M") == 0),
                  "refused with %d at %s", st, e.n ? e.item[0].pointer : "-");
            refused++;
        }
        cJSON_Delete(d);
        drop(&p);
    }
    printf("hostile magnitudes: %zu answered, %zu refused at a pointer\n", answered, refused);
    CHECK(answered > 1000 && refused > 100, "both answered (%zu) and refused (%zu) ones", answered, refused);
    gsl_rng_free(rng);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_example_1_6),       cmocka_unit_test(test_example_2_4),
        cmocka_unit_test(test_example_2_6),       cmocka_unit_test(test_example_2_7),
        cmocka_unit_test(test_example_2_11),      cmocka_unit_test(test_p_matrix_witness),
        cmocka_unit_test(test_random_against_enumeration), cmocka_unit_test(test_large),
        cmocka_unit_test(test_bad_input),         cmocka_unit_test(test_badly_scaled),
        cmocka_unit_test(test_ill_conditioned),   cmocka_unit_test(test_scalings),
        cmocka_unit_test(test_reviewed_scales),   cmocka_unit_test(test_murty),
        cmocka_unit_test(test_murty_stopped),     cmocka_unit_test(test_hostile_magnitudes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
