/* tests/test_network_step.c - the network's exact theta-step (src/core/network/network_step.c) against brute force:
 * on random small networks of Coulomb elements (between the ground and a mass, between two masses, on
 * belts), every stick/slip pattern is tried as a linear system and the one that satisfies its own sign and
 * interval conditions is the minimizer; the active-set solution must be it, to rounding, with the sticking
 * elements exactly at their belt speed. Then a rope beside a Coulomb damper on a belt from a start past the
 * rope's length (the end of the step's domain is the rope's, not the damper's vertex), against bisection of
 * the scalar inclusion and in the two documents where it was found. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include "dashpot/model.h"
#include "dashpot/graph.h"
#include "dashpot/status.h"
#include "laws/law_table.h"
#include "network/network_step.h"
#include "rows.h"

#define NMAX 4
#define EMAX 5

typedef struct problem {
    size_t n, ne;
    double W[NMAX * NMAX], r[NMAX], h;
    long a[EMAX], b[EMAX];
    double phi[EMAX], vb[EMAX];
} problem;

static uint64_t rng = 88172645463325252ull;
static double urand(void)
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

/* A random SPD W = A A^T + n I / 4, a right side, elements with random ends, thresholds and belts. */
static void random_problem(problem *p)
{
    memset(p, 0, sizeof *p);
    p->n = 1 + (size_t)(urand() * NMAX);
    p->ne = 1 + (size_t)(urand() * EMAX);
    p->h = 0.01 + urand();
    double A[NMAX * NMAX];
    for (size_t i = 0; i < p->n * p->n; i++)
        A[i] = urand() - 0.5;
    for (size_t i = 0; i < p->n; i++)
        for (size_t j = 0; j < p->n; j++) {
            double s = i == j ? 0.25 * (double)p->n : 0;
            for (size_t k = 0; k < p->n; k++)
                s += A[i * p->n + k] * A[j * p->n + k];
            p->W[i * p->n + j] = s;
        }
    for (size_t i = 0; i < p->n; i++)
        p->r[i] = 4 * (urand() - 0.5);
    int ground_zero[NMAX] = { 0 };
    for (size_t e = 0; e < p->ne; e++) {
        long a = (long)(urand() * (double)(p->n + 1)) - 1, b;
        do
            b = (long)(urand() * (double)(p->n + 1)) - 1;
        while (b == a || (a < 0 && b < 0));
        p->a[e] = a, p->b[e] = b;
        p->phi[e] = 0.05 + urand();
        /* a belt at rest only once per node: two stuck ground elements at one speed would make the split of
         * force between them (not the motion) ambiguous, which the brute force cannot settle */
        long node = a < 0 ? b : b < 0 ? a : -1;
        if (node >= 0 && !ground_zero[node] && urand() < 0.4)
            p->vb[e] = 0, ground_zero[node] = 1;
        else
            p->vb[e] = urand() - 0.5;
    }
}

static double zrel(const problem *p, size_t e, const double *v)
{
    return (p->b[e] >= 0 ? v[p->b[e]] : 0) - (p->a[e] >= 0 ? v[p->a[e]] : 0);
}

/* Tries pattern s (per element -1, 0 stick, +1); 1 and the velocity when it is consistent. */
static int try_pattern(const problem *p, const int *s, double *v)
{
    size_t n = p->n, m = 0, idx[EMAX];
    for (size_t e = 0; e < p->ne; e++)
        if (s[e] == 0)
            idx[m++] = e;
    size_t N = n + m;
    gsl_matrix *K = gsl_matrix_calloc(N, N);
    gsl_vector *rhs = gsl_vector_calloc(N), *x = gsl_vector_alloc(N);
    gsl_permutation *perm = gsl_permutation_alloc(N);
    for (size_t i = 0; i < n; i++) {
        for (size_t j = 0; j < n; j++)
            gsl_matrix_set(K, i, j, p->W[i * n + j]);
        gsl_vector_set(rhs, i, p->r[i]);
    }
    for (size_t e = 0; e < p->ne; e++) {
        if (s[e] == 0)
            continue;
        double f = p->h * p->phi[e] * s[e];
        if (p->b[e] >= 0)
            *gsl_vector_ptr(rhs, (size_t)p->b[e]) -= f;
        if (p->a[e] >= 0)
            *gsl_vector_ptr(rhs, (size_t)p->a[e]) += f;
    }
    for (size_t k = 0; k < m; k++) {
        size_t e = idx[k];
        if (p->b[e] >= 0)
            gsl_matrix_set(K, (size_t)p->b[e], n + k, p->h), gsl_matrix_set(K, n + k, (size_t)p->b[e], 1);
        if (p->a[e] >= 0)
            gsl_matrix_set(K, (size_t)p->a[e], n + k, -p->h), gsl_matrix_set(K, n + k, (size_t)p->a[e], -1);
        gsl_vector_set(rhs, n + k, p->vb[e]);
    }
    int sg, ok = 0;
    gsl_linalg_LU_decomp(K, perm, &sg);
    double det = fabs(gsl_linalg_LU_det(K, sg));
    if (det > 1e-12 && gsl_linalg_LU_solve(K, perm, rhs, x) == 0) {
        ok = 1;
        for (size_t i = 0; i < n; i++)
            v[i] = gsl_vector_get(x, i);
        for (size_t e = 0; e < p->ne && ok; e++)
            if (s[e] != 0 && !((zrel(p, e, v) - p->vb[e]) * s[e] > -1e-12))
                ok = 0;
        for (size_t k = 0; k < m && ok; k++)
            if (fabs(gsl_vector_get(x, n + k)) > p->phi[idx[k]] * (1 + 1e-12))
                ok = 0;
    }
    gsl_permutation_free(perm);
    gsl_vector_free(x);
    gsl_vector_free(rhs);
    gsl_matrix_free(K);
    return ok;
}

/* The consistent pattern with the least objective (ties only in degenerate cases). */
static int brute_force(const problem *p, double *best)
{
    int s[EMAX], found = 0;
    size_t combos = 1;
    for (size_t e = 0; e < p->ne; e++)
        combos *= 3;
    for (size_t c = 0; c < combos; c++) {
        size_t k = c;
        for (size_t e = 0; e < p->ne; e++, k /= 3)
            s[e] = (int)(k % 3) - 1;
        double v[NMAX];
        if (try_pattern(p, s, v)) {
            memcpy(best, v, sizeof v);
            found = 1;
        }
    }
    return found;
}

static void coulomb_graph(dp_graph *g, double phi)
{
    dp_model m = { .mass = 1, .damper = { .law = DP_DAMPER_COULOMB, .phi0 = phi } };
    assert_int_equal(dp_model_prepare(&m), DP_OK);
    *g = m.damper.graph;
    dp_graph_clear(&m.spring.graph);
}

static void test_coulomb_step_against_brute_force(void **state)
{
    (void)state;
    size_t agree = 0, stuck = 0;
    for (int trial = 0; trial < 12000; trial++) {
        problem p;
        random_problem(&p);
        dp_graph g[EMAX];
        dp_network_step_element el[EMAX];
        for (size_t e = 0; e < p.ne; e++) {
            coulomb_graph(&g[e], p.phi[e]);
            el[e] = (dp_network_step_element){ .a = p.a[e], .b = p.b[e], .A = &g[e], .S = NULL, .vb = p.vb[e] };
        }
        dp_network_step *w = dp_network_step_alloc(p.n, p.n - 1, p.ne, el);
        assert_non_null(w);
        double *W = dp_network_step_W(w), u[EMAX] = { 0 }, guess[NMAX], v[NMAX], ref[NMAX];
        for (size_t i = 0; i < p.n; i++)
            for (size_t d = 0; i + d < p.n; d++)
                W[i * p.n + d] = p.W[(i + d) * p.n + i];
        dp_network_step_W_changed(w);
        for (size_t i = 0; i < p.n; i++)
            guess[i] = urand() < 0.5 ? 0 : urand() - 0.5;
        dp_network_step_forces f[EMAX];
        unsigned long long it = 0;
        assert_int_equal(dp_network_step_solve(w, p.h, p.r, u, guess, v, f, &it), DP_OK);
        assert_true(brute_force(&p, ref));
        for (size_t i = 0; i < p.n; i++)
            assert_true(fabs(v[i] - ref[i]) < 1e-9 * (1 + fabs(ref[i])));
        for (size_t e = 0; e < p.ne; e++) {
            if (f[e].at_rest) {
                stuck++;
                assert_true(fabs(zrel(&p, e, v) - p.vb[e]) <= 1e-15 * (1 + fabs(p.vb[e])) * 4);
                assert_true(fabs(f[e].lambda) <= p.phi[e] * (1 + 1e-12));
            } else {
                assert_true(fabs(f[e].lambda) == p.phi[e]);
            }
        }
        agree++;
        dp_network_step_free(w);
        for (size_t e = 0; e < p.ne; e++)
            dp_graph_clear(&g[e]);
    }
    assert_int_equal(agree, 12000);
    assert_true(stuck > 1000);   /* the sample exercises sticking, not only slip */
}

/* A chain of n blocks as event location steps it (tridiagonal W, Coulomb on every block against the ground
 * and between neighbours) with a random right side; `w` is a fresh workspace with W filled in. */
typedef struct held_case {
    size_t n, ne;
    double W[2 * 12], rhs[12], u[23], h;
    dp_graph g[23];
    dp_network_step_element el[23];
} held_case;

static dp_network_step *held_workspace(const held_case *c)
{
    dp_network_step *w = dp_network_step_alloc(c->n, 1, c->ne, c->el);
    assert_non_null(w);
    memcpy(dp_network_step_W(w), c->W, 2 * c->n * sizeof *c->W);
    dp_network_step_W_changed(w);
    return w;
}

static void held_case_make(held_case *c, size_t n)
{
    memset(c, 0, sizeof *c);
    c->n = n, c->ne = 2 * n - 1, c->h = 0.01 + urand();
    for (size_t i = 0; i < n; i++) {
        c->W[2 * i] = 1.5 + urand(), c->W[2 * i + 1] = i + 1 < n ? -0.5 * urand() : 0;
        c->rhs[i] = 2 * (urand() - 0.5);
    }
    for (size_t e = 0; e < c->ne; e++) {
        coulomb_graph(&c->g[e], 0.05 + 0.5 * urand());
        long a = e < n ? -1 : (long)(e - n), b = e < n ? (long)e : (long)(e - n + 1);
        c->el[e] = (dp_network_step_element){ .a = a, .b = b, .A = &c->g[e], .vb = urand() < 0.5 ? 0 : urand() - 0.5 };
    }
}

/* Event location's held solves after pattern restores give, bit for bit, what a fresh workspace gives on the
 * restored pattern: a restore copies back only the elements changed since the save (network_step.c,
 * touch), the fixed forest of the last held solve is reused until an element is fixed, freed or moved, and
 * a held solve of the same length, right side and W is replayed from memory. Between restores the held
 * pattern is changed as event location changes it (fix_end, slip), held solves overwrite the multipliers,
 * W changes, and lengths come back. */
static void test_held_solves_after_restore(void **state)
{
    (void)state;
    size_t compared = 0, switched = 0;
    for (int trial = 0; trial < 600; trial++) {
        held_case c;
        held_case_make(&c, 2 + (size_t)trial % 11);
        dp_network_step *w = held_workspace(&c);
        double guess[12], v[12], v1[12], va[12], vb[12], ma[23], mb[23];
        dp_network_step_forces f[23], fa[23], fb[23];
        for (size_t i = 0; i < c.n; i++)
            guess[i] = urand() < 0.5 ? 0 : urand() - 0.5;
        unsigned long long it = 0;
        assert_int_equal(dp_network_step_solve(w, c.h, c.rhs, c.u, guess, v, f, &it), DP_OK);
        void *buf = malloc(dp_network_step_pattern_bytes(w)), *copy = malloc(dp_network_step_pattern_bytes(w));
        assert_true(buf && copy);
        dp_network_step_pattern_save(w, buf);
        double lengths[3] = { c.h, c.h / 2, c.h / 3 };
        for (int op = 0; op < 16; op++) {
            double r = urand(), hh = urand() < 0.6 ? lengths[op % 3] : c.h * (0.05 + urand());
            size_t k = (size_t)(urand() * (double)c.ne);
            if (r < 0.05) {   /* W changes (the caller says so) */
                c.W[2 * (k % c.n)] += 0.25 * urand();
                memcpy(dp_network_step_W(w), c.W, 2 * c.n * sizeof *c.W);
                dp_network_step_W_changed(w);
            } else if (r < 0.3) {
                if (dp_network_step_fixed(w, k))
                    dp_network_step_slip(w, k, hh, c.u, urand() < 0.5 ? -1 : 1);
                else
                    dp_network_step_fix_end(w, k, v);
                switched++;
            } else if (r < 0.55) {
                (void)dp_network_step_solve_frozen(w, hh, c.rhs, c.u, v1, f, ma);
            } else {
                dp_network_step_pattern_restore(w, buf);
                int sa = dp_network_step_solve_frozen(w, hh, c.rhs, c.u, va, fa, ma);
                dp_network_step *fresh = held_workspace(&c);
                memcpy(copy, buf, dp_network_step_pattern_bytes(w));
                dp_network_step_pattern_restore(fresh, copy);
                int sb = dp_network_step_solve_frozen(fresh, hh, c.rhs, c.u, vb, fb, mb);
                assert_int_equal(sa, sb);
                if (sa != DP_OK) {
                    dp_network_step_free(fresh);
                    continue;
                }
                assert_memory_equal(va, vb, c.n * sizeof *va);
                assert_memory_equal(ma, mb, c.ne * sizeof *ma);
                for (size_t e = 0; e < c.ne; e++) {
                    assert_memory_equal(&fa[e].lambda, &fb[e].lambda, sizeof fa[e].lambda);
                    assert_int_equal(fa[e].at_rest, fb[e].at_rest);
                    assert_int_equal(dp_network_step_violation(w, e, hh, c.u),   /* the multipliers kept */
                                     dp_network_step_violation(fresh, e, hh, c.u));
                }
                dp_network_step_free(fresh);
                compared++;
            }
        }
        free(buf), free(copy);
        dp_network_step_free(w);
        for (size_t e = 0; e < c.ne; e++)
            dp_graph_clear(&c.g[e]);
    }
    assert_true(compared > 2000);   /* the sample compares held solves after many restores */
    assert_true(switched > 1500);   /* and changes the held pattern between them */
}

/* Held solves over blocks of a chain (dp_network_step_blocks, _solve_blocks) give the candidates' margins
 * and the fixed ones' multipliers of the whole held solve bit for bit: random chains of 2..40 nodes with a
 * Coulomb element from the ground to each (so that the stuck ones split the chain), some neighbours
 * uncoupled, random assignments from whole solves and random candidate sets. */
static void test_held_blocks_are_the_whole_solve(void **state)
{
    (void)state;
    enum { N = 40 };
    size_t compared = 0, split = 0;
    for (int trial = 0; trial < 300; trial++) {
        size_t n = 2 + (size_t)(urand() * (N - 1));
        double W[2 * N], rhs[N], u[N] = { 0 }, h = 0.01 + urand(), guess[N], v[N], va[N], ma[N], mb[N];
        unsigned char couple[N], cand[N];
        dp_graph g[N];
        dp_network_step_element el[N];
        dp_network_step_forces f[N];
        for (size_t i = 0; i < n; i++) {
            couple[i] = i + 1 < n && urand() < 0.9;
            W[2 * i] = 1.5 + urand(), W[2 * i + 1] = couple[i] ? -0.5 * urand() - 0.01 : 0;
            rhs[i] = 2 * (urand() - 0.5), guess[i] = urand() < 0.5 ? 0 : urand() - 0.5;
            coulomb_graph(&g[i], 0.05 + 0.5 * urand());
            el[i] = (dp_network_step_element){ .a = urand() < 0.8 ? -1 : (long)i, .b = -1, .A = &g[i],
                                               .vb = urand() < 0.5 ? 0 : urand() - 0.5 };
            if (el[i].a < 0)
                el[i].b = (long)i;
        }
        dp_network_step *w = dp_network_step_alloc(n, 1, n, el);
        assert_non_null(w);
        memcpy(dp_network_step_W(w), W, 2 * n * sizeof *W);
        dp_network_step_W_changed(w);
        unsigned long long it = 0;
        assert_int_equal(dp_network_step_solve(w, h, rhs, u, guess, v, f, &it), DP_OK);
        void *buf = malloc(dp_network_step_pattern_bytes(w));
        assert_non_null(buf);
        dp_network_step_pattern_save(w, buf);
        for (int op = 0; op < 8; op++) {
            double hh = h * (urand() < 0.3 ? 1e-9 : 0.05 + urand());
            dp_network_step_pattern_restore(w, buf);
            if (dp_network_step_solve_frozen(w, hh, rhs, u, va, f, ma) != DP_OK)
                continue;
            double lam[N];
            for (size_t k = 0; k < n; k++)
                lam[k] = dp_network_step_violation(w, k, hh, u);
            for (size_t k = 0; k < n; k++)
                cand[k] = urand() < 0.15;
            dp_network_step_pattern_restore(w, buf);
            size_t blk[6 * N + 2], nb = dp_network_step_blocks(w, cand, couple, blk, 3 * N + 1);
            if (nb == 0)
                continue;
            double Wl[4 * N + 4], rl[N + 1];
            size_t off = 0, covered = 0;
            for (size_t b = 0; b < nb; b++) {   /* rows lo-1 .. hi of W, lo .. hi of the right side */
                size_t lo = blk[2 * b], hi = blk[2 * b + 1];
                for (size_t r = lo; r <= hi + 1; r++)
                    for (size_t d = 0; d < 2; d++)
                        Wl[2 * (off + b) + 2 * (r - lo) + d] = r == 0 ? 0 : W[2 * (r - 1) + d];
                memcpy(rl + off, rhs + lo, (hi - lo + 1) * sizeof *rl);
                off += hi - lo + 1, covered += hi - lo + 1;
            }
            for (size_t k = 0; k < n; k++)
                mb[k] = -12345;
            assert_int_equal(dp_network_step_solve_blocks(w, hh, blk, nb, Wl, rl, u, cand, mb), 1);
            for (size_t k = 0; k < n; k++) {
                if (!cand[k])
                    continue;
                assert_memory_equal(&ma[k], &mb[k], sizeof ma[k]);
                assert_true(lam[k] == dp_network_step_violation(w, k, hh, u));
            }
            compared++, split += covered < n;
        }
        free(buf);
        dp_network_step_free(w);
        for (size_t i = 0; i < n; i++)
            dp_graph_clear(&g[i]);
    }
    assert_true(compared > 1000 && split > 500);   /* many sets, most of them on part of the chain */
}

/* The long factorization asked for polls (network_step.c's polled_cholesky, past 2^22 multiply-adds) gives
 * GSL's answer to rounding: a band W of 600 nodes and half-bandwidth 100 with one Coulomb element, solved
 * without a poll (GSL's factor) and with one that never stops (ours, polled during the factorization);
 * a poll that stops at once ends the solve with DP_ECANCEL. */
static int polls;
static int never(void *ctx, unsigned long long units) { (void)ctx, (void)units; polls++; return 0; }
static int at_once(void *ctx, unsigned long long units) { (void)ctx, (void)units; return 1; }

static void test_polled_factorization(void **state)
{
    (void)state;
    enum { N = 600, P = 100 };
    dp_damper d = { .law = DP_DAMPER_COULOMB, .phi0 = 0.5 };
    assert_int_equal(dp_damper_prepare(&d), DP_OK);
    dp_network_step_element el[1] = { { .a = -1, .b = 7, .A = &d.graph } };
    double rhs[N], u[1] = { 0 }, guess[N] = { 0 }, v[3][N];
    for (size_t i = 0; i < N; i++)
        rhs[i] = sin(0.37 * (double)i);
    dp_network_step_forces f[1];
    for (int k = 0; k < 3; k++) {
        dp_network_step *w = dp_network_step_alloc(N, P, 1, el);
        assert_non_null(w);
        double *W = dp_network_step_W(w);
        for (size_t i = 0; i < N; i++) {
            W[i * (P + 1)] = 2.0 * P + 1;
            for (size_t q = 1; q <= P; q++)
                W[i * (P + 1) + q] = i + q < N ? -1.0 / (double)(q + 1) : 0;
        }
        dp_network_step_W_changed(w);
        if (k)
            dp_network_step_set_poll(w, k == 1 ? never : at_once, NULL);
        unsigned long long it = 0;
        int s = dp_network_step_solve(w, 0.1, rhs, u, guess, v[k], f, &it);
        assert_int_equal(s, k == 2 ? DP_ECANCEL : DP_OK);
        dp_network_step_free(w);
    }
    assert_true(polls > 1);   /* asked during the factorization, not only after the solve */
    double worst = 0;
    for (size_t i = 0; i < N; i++)
        worst = fmax(worst, fabs(v[1][i] - v[0][i]) / (1e-300 + fabs(v[0][i]) + 1e-3));
    assert_true(worst <= 1e-12);
    dp_graph_clear(&d.graph);
}

/* ---- a rope beside a Coulomb damper on a belt, started past the rope's length ------------------------- */

/* One mass W on an element [ground, 0] with a rope S (k, L; Babováková 2012, Fig. 1) at elongation u and a
 * Coulomb damper A (phi) on a belt vb, and optionally a stop in A (a vertical end at z - vb = ystop): the
 * step's inclusion r - W v in h (A(v - vb) + S(u + h v)). */
typedef struct rope_belt {
    double W, r, h, u, k, L, phi, vb, ystop;
    int stop;
} rope_belt;

/* The graphs: A is Coulomb, or Coulomb with its right ray turned up at ystop > 0 (a stop). */
static void rope_belt_graphs(const rope_belt *c, dp_graph *A, dp_graph *S)
{
    assert_int_equal(dp_rope_graph(S, c->k, c->L), DP_OK);
    if (!c->stop) {
        coulomb_graph(A, c->phi);
        return;
    }
    double y[3] = { 0, 0, c->ystop }, f[3] = { -c->phi, c->phi, c->phi };
    double flat[2] = { 1, 0 }, up[2] = { 0, 1 };
    assert_int_equal(dp_graph_init(A, 3, y, f, flat, up), DP_OK);
}

/* The force interval of W v - r + h Sigma(v), empty (both ends infinite) outside the domain. */
static void rope_belt_residual(const rope_belt *c, const dp_graph *A, const dp_graph *S, double v, double *lo,
                               double *hi)
{
    double al, ah, sl, sh;
    dp_graph_force(A, v - c->vb, &al, &ah);
    dp_graph_force(S, c->u + c->h * v, &sl, &sh);
    *lo = c->W * v - c->r + c->h * (al + sl);
    *hi = c->W * v - c->r + c->h * (ah + sh);
}

/* The minimizer by bisection on the monotone residual: v* where its interval holds 0. */
static double rope_belt_reference(const rope_belt *c, const dp_graph *A, const dp_graph *S)
{
    double a = -1e3, b = 1e3, lo, hi;
    for (int it = 0; it < 400 && a < b; it++) {
        double m = 0.5 * (a + b);
        if (m == a || m == b)
            break;
        rope_belt_residual(c, A, S, m, &lo, &hi);
        if (hi < 0)
            a = m;
        else if (lo > 0)
            b = m;
        else
            return m;
    }
    rope_belt_residual(c, A, S, b, &lo, &hi);
    return lo <= 0 ? b : a;
}

/* Solves the step from the guess (its graphs in A, S for the caller to clear): v, the forces, the iterations. */
static void rope_belt_solve(const rope_belt *c, double guess, dp_graph *A, dp_graph *S, double *v,
                            dp_network_step_forces *f, unsigned long long *it)
{
    rope_belt_graphs(c, A, S);
    dp_network_step_element el[1] = { { .a = -1, .b = 0, .A = A, .S = S, .vb = c->vb } };
    dp_network_step *w = dp_network_step_alloc(1, 0, 1, el);
    assert_non_null(w);
    dp_network_step_W(w)[0] = c->W;
    dp_network_step_W_changed(w);
    double u[1] = { c->u }, r[1] = { c->r }, g[1] = { guess };
    *it = 0;
    assert_int_equal(dp_network_step_solve(w, c->h, r, u, g, v, f, it), DP_OK);
    dp_network_step_free(w);
}

/* Solves the step from the guess; checks v against the reference and the balance W v - r + h lambda = 0. */
static void rope_belt_check(const rope_belt *c, double guess, double tol)
{
    dp_graph A, S;
    double v[1];
    dp_network_step_forces f[1];
    unsigned long long it;
    rope_belt_solve(c, guess, &A, &S, v, f, &it);
    double ref = rope_belt_reference(c, &A, &S);
    assert_true(fabs(v[0] - ref) <= tol * (1 + fabs(ref)));
    assert_true(fabs(c->W * v[0] - c->r + c->h * f[0].lambda) <= 1e-12 * (1 + fabs(c->r) + c->h * fabs(f[0].lambda)));
    assert_true(c->u + c->h * v[0] <= c->L * (1 + 1e-15));   /* the rope no longer than its length */
    dp_graph_clear(&A), dp_graph_clear(&S);
}

/* The steps on which the primal method cycled, reduced to the element and its node: the rope exactly taut
 * (u = L, so the domain ends at z = 0) and the guess beyond that end. The start was fixed at the damper's
 * vertex z = vb > 0, outside the rope's domain: released down onto a piece reaching back to z = 0, walked up
 * and fixed there again at once. Fixed at the rope's end, the rope stays taut and carries the load:
 * v = 0, lambda = r/h, the damper slipping backwards (-phi). */
static void test_taut_rope_on_belt_reproducers(void **state)
{
    (void)state;
    const rope_belt cases[2] = {
        { .W = 1, .r = 0.70177073049416816, .h = 0.003, .u = 2, .k = 1, .L = 2, .phi = 0.1, .vb = 0.1 },
        { .W = 1, .r = 0.94824024679648944, .h = 0.01, .u = 0.8, .k = 1, .L = 0.8, .phi = 0.3, .vb = 0.1 },
    };
    const double guess[2] = { 0.6985587609826075, 0.94370666557327398 };
    for (int k = 0; k < 2; k++) {
        const rope_belt *c = &cases[k];
        dp_graph A, S;
        double v[1];
        dp_network_step_forces f[1];
        unsigned long long it;
        rope_belt_solve(c, guess[k], &A, &S, v, f, &it);
        assert_true(v[0] == 0);
        assert_true(fabs(f[0].lambda - c->r / c->h) <= 1e-12 * c->r / c->h);
        assert_true(f[0].a == -c->phi);
        assert_true(fabs(f[0].s - (c->r / c->h + c->phi)) <= 1e-12 * c->r / c->h);
        assert_true(it <= 4);
        dp_graph_clear(&A), dp_graph_clear(&S);
        rope_belt_check(c, guess[k], 1e-12);
    }
}

/* Random such steps against bisection: the rope slack or nearly taut, the guess often past its end, the
 * load pulling or pushing, the belt either way; with a stop in the damper as well, either end the tighter. */
static void test_rope_on_belt_against_bisection(void **state)
{
    (void)state;
    size_t past = 0;
    for (int trial = 0; trial < 4000; trial++) {
        rope_belt c = { .W = 0.2 + 2 * urand(), .h = 0.001 + 0.05 * urand(), .k = 0.1 + 3 * urand(),
                        .L = 0.2 + 2 * urand(), .phi = 0.02 + urand(), .vb = urand() - 0.5 };
        c.r = 4 * (urand() - 0.5);
        c.u = c.L - (urand() < 0.5 ? 0 : 0.05 * urand());
        c.stop = urand() < 0.3;
        c.ystop = 0.01 + 0.5 * urand();
        double guess = 3 * (urand() - 0.5);
        past += c.u + c.h * guess > c.L;
        rope_belt_check(&c, guess, 1e-9);
    }
    assert_true(past > 1000);   /* the sample starts past the rope's end often */
}

/* The two documents the cycle was found in (events "none", theta = 1) run to their end. */
static void test_rope_on_belt_documents(void **state)
{
    (void)state;
    static const char *docs[2] = {
        "{\"model\": {\"masses\": [1, 1, 0.5], \"elements\": ["
        "{\"between\": [\"ground\", 0], \"damper\": {\"law\": \"linear\", \"c\": 0.05}},"
        "{\"between\": [\"ground\", 1], \"spring\": {\"law\": \"rope\", \"k\": 1, \"length\": 2},"
        " \"damper\": {\"law\": \"coulomb\", \"phi0\": 0.1, \"belt_velocity\": 0.1}},"
        "{\"between\": [\"ground\", 2],"
        " \"spring\": {\"law\": \"graph\", \"points\": [[1.069, -1.772], [1.331, 0.966]]},"
        " \"damper\": {\"law\": \"linear\", \"c\": 0.3}}],"
        " \"forcing\": [{\"node\": 1, \"kind\": \"harmonic\", \"amplitude\": 2, \"omega\": 0.7}]},"
        " \"initial\": {\"x\": [-0.054, 0.156, 0.201], \"v\": [-0.728, 0.502, 0.151]},"
        " \"solver\": {\"dt\": 0.003, \"t_end\": 5, \"theta\": 1, \"events\": \"none\"}, \"output\": {\"every\": 50}}",
        "{\"model\": {\"masses\": [1, 2, 1], \"elements\": ["
        "{\"between\": [\"ground\", 0], \"spring\": {\"law\": \"rope\", \"k\": 1, \"length\": 0.8},"
        " \"damper\": {\"law\": \"coulomb\", \"phi0\": 0.3, \"belt_velocity\": 0.1}},"
        "{\"between\": [\"ground\", 1], \"spring\": {\"law\": \"graph\", \"points\": [[-1.05, -0.505], [-0.923, 1.619],"
        " [0.589, 1.829], [1.447, 3.784]]}, \"damper\": {\"law\": \"coulomb\", \"phi0\": 0.1, \"belt_velocity\": 0}},"
        "{\"between\": [\"ground\", 2], \"spring\": {\"law\": \"graph\", \"points\": [[0.21, 0.406], [0.599, 2.139],"
        " [1.251, 3.681]]}, \"damper\": {\"law\": \"coulomb\", \"phi0\": 0.8, \"belt_velocity\": -0.2}},"
        "{\"between\": [0, 1], \"contact\": {\"distance\": -1.433, \"restitution\": 1}},"
        "{\"between\": [1, 0], \"contact\": {\"distance\": -0.606, \"compliance\": 100000.0}},"
        "{\"between\": [1, \"ground\"], \"contact\": {\"distance\": -0.367, \"compliance\": 10}}],"
        " \"forcing\": [{\"node\": 0, \"kind\": \"harmonic\", \"amplitude\": 5, \"omega\": 2}]},"
        " \"initial\": {\"x\": [-0.203, -0.035, 0.2], \"v\": [-0.043, 0.152, 0.769]},"
        " \"solver\": {\"dt\": 0.01, \"t_end\": 5, \"theta\": 1, \"events\": \"none\"}, \"output\": {\"every\": 50}}",
    };
    for (int k = 0; k < 2; k++) {
        rows o;
        assert_int_equal(rows_collect(docs[k], 64, &o), DP_DONE);
        assert_true(o.n > 10 && fabs(o.d[(o.n - 1) * o.width] - 5) < 1e-9);   /* it reached t_end */
        for (size_t i = 0; i < o.n * o.width; i++)
            assert_false(isnan(o.d[i]));
        free(o.d), free(o.quakes);
    }
}

/* Kept factors: a workspace that lives through many solves keeps its contracted factors for the structures
 * it met (the current one and spares of W itself), compares W by its bytes after W_changed and keeps the
 * fixed forest's index while the fixed elements stay; each solve must still give the bits of a fresh
 * workspace, while W is rewritten with the same numbers, changed and changed back, and belts change speed
 * (a stuck element's vertex moves). A chain of 6 blocks, on each a Coulomb element on a belt, Coulomb
 * between neighbours, and graphs whose rays have a slope (their free pieces add to W, so H is formed) on
 * none, one or every other block, or Moreau-Jean's contacts on every other block, pushed onto them and
 * re-armed at -e times their last rate each step (a resting contact's vertex moves every step); warm
 * starts from the last velocity as a run makes them, and random ones. The poll's units show that factors
 * were reused. */
static unsigned long long kept_units;
static int count_units(void *ctx, unsigned long long units) { (void)ctx, kept_units += units; return 0; }

static void kept_W(double *W, size_t n, double scale)
{
    for (size_t i = 0; i < n; i++)
        W[2 * i] = scale * (3 + (double)i / 7), W[2 * i + 1] = i + 1 < n ? -scale : 0;
}

enum { KN = 6, KNE = 2 * KN - 1 };

/* One solve by w and by a fresh workspace on the same inputs: the same bits. */
static void kept_solve_once(dp_network_step *w, const dp_network_step_element *el, double scale, const double *rhs,
                            double *v, unsigned long long *kept, unsigned long long *fresh_units)
{
    double u[KNE] = { 0 }, v1[KN], v2[KN];
    unsigned long long it = 0;
    dp_network_step_forces f1[KNE], f2[KNE];
    kept_units = 0;
    assert_int_equal(dp_network_step_solve(w, 0.01, rhs, u, v, v1, f1, &it), DP_OK);
    *kept += kept_units;
    dp_network_step *fresh = dp_network_step_alloc(KN, 1, KNE, el);
    assert_non_null(fresh);
    dp_network_step_set_poll(fresh, count_units, NULL);
    kept_W(dp_network_step_W(fresh), KN, scale);
    dp_network_step_W_changed(fresh);
    kept_units = 0;
    assert_int_equal(dp_network_step_solve(fresh, 0.01, rhs, u, v, v2, f2, &it), DP_OK);
    *fresh_units += kept_units;
    dp_network_step_free(fresh);
    assert_memory_equal(v1, v2, sizeof v1);
    for (size_t e = 0; e < KNE; e++) {   /* field by field: the struct's padding is not an answer */
        assert_memory_equal(&f1[e].z, &f2[e].z, sizeof f1[e].z);
        assert_memory_equal(&f1[e].lambda, &f2[e].lambda, sizeof f1[e].lambda);
        assert_memory_equal(&f1[e].a, &f2[e].a, sizeof f1[e].a);
        assert_memory_equal(&f1[e].s, &f2[e].s, sizeof f1[e].s);
        assert_int_equal(f1[e].at_rest, f2[e].at_rest);
    }
    memcpy(v, v1, sizeof v1);
}

static void test_kept_factors_bit_for_bit(void **state)
{
    (void)state;
    for (int sloped = 0; sloped < 4; sloped++) {   /* rays with a slope on no block, on block 0, on odd blocks;
                                                      contacts on odd blocks */
        dp_graph g[KNE];
        dp_network_step_element el[KNE];
        for (size_t e = 0; e < KNE; e++) {
            double y[2] = { 0, 0 }, f[2] = { -0.3 - 0.1 * (double)(e % 3), 0.3 + 0.1 * (double)(e % 3) };
            int slope = e < KN && (sloped == 1 ? e == 0 : sloped == 2 && e % 2);
            double ray[2] = { 1, slope ? 0.5 : 0 }, down[2] = { 0, 1 }, zero = 0;
            if (sloped == 3 && e < KN && e % 2)   /* the rigid cone of a contact */
                assert_int_equal(dp_graph_init(&g[e], 1, &zero, &zero, down, ray), DP_OK);
            else
                assert_int_equal(dp_graph_init(&g[e], 2, y, f, ray, ray), DP_OK);
            el[e] = e < KN ? (dp_network_step_element){ .a = -1, .b = (long)e, .A = &g[e], .vb = 0.05 * (double)(e % 2) }
                           : (dp_network_step_element){ .a = (long)(e - KN), .b = (long)(e - KN + 1), .A = &g[e] };
        }
        dp_network_step *w = dp_network_step_alloc(KN, 1, KNE, el);
        assert_non_null(w);
        dp_network_step_set_poll(w, count_units, NULL);
        double v[KN] = { 0 }, rhs[KN], scale = 1;
        unsigned long long kept = 0, fresh_units = 0;
        kept_W(dp_network_step_W(w), KN, scale);
        dp_network_step_W_changed(w);
        for (int step = 0; step < 600; step++) {
            if (step % 7 == 3 || step % 50 == 10 || step % 50 == 24) {   /* the same numbers, another W and back */
                scale = step % 50 == 10 ? 1.5 : step % 50 == 24 ? 1 : scale;
                kept_W(dp_network_step_W(w), KN, scale);
                dp_network_step_W_changed(w);
            }
            if (step % 60 == 30 && sloped < 3)   /* the odd blocks' belts change speed: stuck vertices move */
                for (size_t e = 1; e < KN; e += 2)
                    el[e].vb = 0.05 * cos(0.1 * step);
            for (size_t e = 1; sloped == 3 && e < KN; e += 2)   /* re-armed at -e u' (e = 1/2) */
                el[e].vb = fabs(v[e]) < 1e-300 ? 0 : -0.5 * v[e];
            for (size_t i = 0; i < KN; i++)
                rhs[i] = 0.8 * (urand() - 0.5) + 0.3 * sin(0.05 * step + (double)i) - (sloped == 3 ? 0.5 : 0);
            if (step % 11 == 0)
                for (size_t i = 0; i < KN; i++)
                    v[i] = urand() - 0.5;
            kept_solve_once(w, el, scale, rhs, v, &kept, &fresh_units);
        }
        assert_true(kept < fresh_units);   /* a fresh workspace factors every solve, the kept one reuses */
        dp_network_step_free(w);
        for (size_t e = 0; e < KNE; e++)
            dp_graph_clear(&g[e]);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_coulomb_step_against_brute_force),
        cmocka_unit_test(test_polled_factorization),
        cmocka_unit_test(test_kept_factors_bit_for_bit),
        cmocka_unit_test(test_held_solves_after_restore),
        cmocka_unit_test(test_held_blocks_are_the_whole_solve),
        cmocka_unit_test(test_taut_rope_on_belt_reproducers),
        cmocka_unit_test(test_rope_on_belt_against_bisection),
        cmocka_unit_test(test_rope_on_belt_documents),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
