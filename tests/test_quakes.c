/* tests/test_quakes.c - the slip-event catalogue of network runs (output.quakes, docs/quakes.md): hand-built
 * chains whose episodes are known in closed form (a block sliding to rest under Coulomb friction: distance
 * v0^2 / (2 phi), time v0 / phi, which the theta-rule with located events gives to rounding), blocks slipping
 * together and apart, two quakes merging, an episode open at t_end; on random chains the moments add up to
 * the total slip read off the rows; a Carlson–Langer chain slips at the plate's speed in the long run; the
 * law a Carlson–Langer document builds is the Carlson–Langer friction; bad members are named by pointer. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "dashpot/json.h"
#include "dashpot/run.h"
#include "check.h"
#include "rows.h"

/* A run's records (tests/rows.h): rows flattened (t, then the row), events, quakes. */
typedef rows catalogue;

/* Runs the document to its end in blocks of `cap` records; the spec must parse and the run finish. */
static catalogue *run_doc(const char *json, size_t cap)
{
    catalogue *c = malloc(sizeof *c);
    assert_non_null(c);
    assert_int_equal(rows_collect(json, cap, c), DP_DONE);
    return c;
}

static void catalogue_free(catalogue *c)
{
    free(c->d);
    free(c->quakes);
    free(c);
}

static double total_moment(const catalogue *c)
{
    double m = 0;
    for (size_t i = 0; i < c->nquakes; i++)
        m += c->quakes[i].moment;
    return m;
}

/* A block of mass 1 on Coulomb friction phi (a network: the catalogue steps it on the network solver). */
#define BLOCK(phi) "{\"between\":[\"ground\",%d],\"damper\":{\"law\":\"coulomb\",\"phi0\":" phi "}}"

/* One block sliding from v0 = 1 against phi = 0.5 stops at t = 2 having slid 1: one quake, closed. Cut at
 * t_end = 1 it is open, its moment v0 t - phi t^2 / 2 = 0.75 (the trapezoidal rule is exact on a linear
 * velocity, and the stop is located to rounding). */
static void test_one_block_to_rest_and_open(void **state)
{
    (void)state;
    char json[512];
    for (int open = 0; open < 2; open++) {
        snprintf(json, sizeof json, "{\"model\":{\"masses\":[1],\"elements\":[" BLOCK("0.5") "]},"
                 "\"initial\":{\"v\":[1]},\"solver\":{\"dt\":0.01,\"t_end\":%s},\"output\":{\"quakes\":true}}", 0,
                 open ? "1" : "5");
        catalogue *c = run_doc(json, 64);
        assert_int_equal(c->nquakes, 1);
        const dp_quake *q = &c->quakes[0];
        CHECK(q->open == open, "open %d, expected %d", q->open, open);
        NEAR(q->t, 0, 0);
        assert_int_equal(q->size, 1);
        assert_int_equal(q->hypocentre, 0);
        NEAR(q->duration, open ? 1 : 2, 1e-12);
        NEAR(q->moment, open ? 0.75 : 1, 1e-12);
        /* the rate is read at the steps' ends: the first is 1 - 0.5 dt */
        NEAR(q->peak_rate, 0.995, 1e-12);
        catalogue_free(c);
    }
}

/* Two blocks from v0 = 1 and 2.003, each on phi = 0.5: unconnected, two quakes (moments 1 and 2.003^2,
 * ending at 2 and 4.006: off the step grid, where a stop is located inside a step); joined by a spring and both from 1, they move as one: one quake of size 2, moment 2, hypocentre
 * the lower index (they start together). */
static void test_two_blocks_apart_and_together(void **state)
{
    (void)state;
    char json[1024];
    snprintf(json, sizeof json, "{\"model\":{\"masses\":[1,1],\"elements\":[" BLOCK("0.5") "," BLOCK("0.5") "]},"
             "\"initial\":{\"v\":[1,2.003]},\"solver\":{\"dt\":0.01,\"t_end\":6},\"output\":{\"quakes\":true}}", 0, 1);
    catalogue *c = run_doc(json, 64);
    assert_int_equal(c->nquakes, 2);
    for (size_t i = 0; i < 2; i++) {
        const dp_quake *q = &c->quakes[i];   /* handed out as they end: block 0's first */
        assert_int_equal(q->hypocentre, i);
        assert_int_equal(q->size, 1);
        assert_false(q->open);
        NEAR(q->t, 0, 0);
        NEAR(q->duration, i ? 4.006 : 2, 1e-12);
        NEAR(q->moment, i ? 2.003 * 2.003 : 1, 1e-12);
    }
    catalogue_free(c);
    snprintf(json, sizeof json, "{\"model\":{\"masses\":[1,1],\"elements\":[" BLOCK("0.5") "," BLOCK("0.5") ","
             "{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":1}}]},"
             "\"initial\":{\"v\":[1,1]},\"solver\":{\"dt\":0.01,\"t_end\":6},\"output\":{\"quakes\":true}}", 0, 1);
    c = run_doc(json, 64);
    assert_int_equal(c->nquakes, 1);
    assert_int_equal(c->quakes[0].size, 2);
    assert_int_equal(c->quakes[0].hypocentre, 0);
    assert_int_equal(c->quakes[0].first, 0);
    assert_int_equal(c->quakes[0].last, 1);
    NEAR(c->quakes[0].duration, 2, 1e-12);
    NEAR(c->quakes[0].moment, 2, 1e-12);
    catalogue_free(c);
}

/* A chain 0-1-2-3 (unit springs): block 0 slides from v0 = -2 at t = 0 (quake A), blocks 2 and 3 are
 * pulled by -sin t each (a cosine a quarter period late) and start together at asin(0.1) (quake B, two blocks, hypocentre 2); block 1, held
 * by phi = 0.5, starts later and joins both: one quake whose start and hypocentre are A's (the earlier),
 * though B is the larger. Still slipping at t_end: open. */
static void test_merge_keeps_the_earlier_start(void **state)
{
    (void)state;
    char json[2048];
    snprintf(json, sizeof json, "{\"model\":{\"masses\":[1,1,1,1],\"elements\":["
             BLOCK("0.1") "," BLOCK("0.5") "," BLOCK("0.1") "," BLOCK("0.1") ","
             "{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":1}},"
             "{\"between\":[1,2],\"spring\":{\"law\":\"linear\",\"k\":1}},"
             "{\"between\":[2,3],\"spring\":{\"law\":\"linear\",\"k\":1}}],"
             "\"forcing\":[{\"node\":2,\"kind\":\"harmonic\",\"amplitude\":-1,\"omega\":1,\"phase\":%.17g},"
             "{\"node\":3,\"kind\":\"harmonic\",\"amplitude\":-1,\"omega\":1,\"phase\":%.17g}]},"
             "\"initial\":{\"v\":[-2,0,0,0]},\"solver\":{\"dt\":0.001,\"t_end\":0.6},"
             "\"output\":{\"quakes\":true}}", 0, 1, 2, 3, -M_PI / 2, -M_PI / 2);
    catalogue *c = run_doc(json, 64);
    /* the slips as the events say: 2 and 3 at asin(0.1), then 1 */
    double t_slip[4] = { -1, -1, -1, -1 };
    for (size_t i = 0; i < c->events; i++)
        if (c->ev[i].kind == DP_EVENT_SLIP && c->ev[i].element < 4 && t_slip[c->ev[i].element] < 0)
            t_slip[c->ev[i].element] = c->ev[i].t;
    NEAR(t_slip[2], asin(0.1), 1e-9);
    NEAR(t_slip[3], asin(0.1), 1e-9);
    CHECK(t_slip[1] > t_slip[2], "block 1 slips at %g, after blocks 2, 3 at %g", t_slip[1], t_slip[2]);
    assert_int_equal(c->nquakes, 1);
    const dp_quake *q = &c->quakes[0];
    assert_true(q->open);
    NEAR(q->t, 0, 0);
    assert_int_equal(q->hypocentre, 0);
    assert_int_equal(q->size, 4);
    assert_int_equal(q->first, 0);
    assert_int_equal(q->last, 3);
    NEAR(q->duration, 0.6, 1e-12);
    catalogue_free(c);
}

/* ---- the moments are the total slip ---------------------------------------------------------------------- */

typedef struct buf {
    char *s;
    size_t len, cap;
} buf;

static void put(buf *b, const char *fmt, ...)
{
    va_list ap;
    for (;;) {
        va_start(ap, fmt);
        int n = vsnprintf(b->s + b->len, b->cap - b->len, fmt, ap);
        va_end(ap);
        if (n >= 0 && (size_t)n < b->cap - b->len) {
            b->len += (size_t)n;
            return;
        }
        b->cap = b->cap ? 2 * b->cap : 4096;
        b->s = realloc(b->s, b->cap);
        assert_non_null(b->s);
    }
}

static uint64_t rng = 88172645463325252ull;

static double uniform(double lo, double hi)
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return lo + (hi - lo) * (double)(rng >> 11) / 9007199254740992.0;
}

/* A random chain of n blocks: springs to the ground and between neighbours, friction to a belt under each
 * block (law 1: generalized Coulomb with rational relaxation, so stepped without location) or, law 0, Coulomb
 * under all but every third block and between those blocks and their neighbours, all on one belt, random masses, stiffnesses, thresholds and belt speeds, a harmonic load. */
static char *random_chain(int n, int law, const char *events)
{
    buf b = { 0 };
    put(&b, "{\"model\":{\"masses\":[");
    for (int i = 0; i < n; i++)
        put(&b, "%s%.6f", i ? "," : "", uniform(0.5, 2));
    put(&b, "],\"elements\":[");
    double vb = uniform(-0.1, 0.1);   /* one belt: blocks that stick to it keep their distances */
    for (int i = 0; i < n; i++) {
        double phi = uniform(0.5, 1.5);
        put(&b, "%s{\"between\":[\"ground\",%d],\"spring\":{\"law\":\"linear\",\"k\":%.6f}", i ? "," : "", i,
            uniform(0.5, 2));
        if (law == 0 && i % 3 == 2) {   /* held by its friction to block i - 1 alone (below) */
            put(&b, "}");
            continue;
        }
        put(&b, ",");
        if (law == 0)
            put(&b, "\"damper\":{\"law\":\"coulomb\",\"phi0\":%.6f,\"belt_velocity\":%.6f}}", phi, vb);
        else
            put(&b, "\"damper\":{\"law\":\"generalized-coulomb\",\"phi0\":%.6f,\"phi1\":%.6f,\"belt_velocity\":%.6f,"
                "\"relaxation\":{\"kind\":\"rational\",\"a\":%.6f,\"b\":%.6f}}}", phi, 1.2 * phi, vb, 0.5 * phi, 1.0);
    }
    for (int i = 0; i + 1 < n; i++) {
        put(&b, ",{\"between\":[%d,%d],\"spring\":{\"law\":\"linear\",\"k\":%.6f}", i, i + 1, uniform(1, 4));
        if (law == 0 && i % 3 == 1)   /* friction between neighbours, sharing a node with block i's: no loop of friction
                           * elements (whose closing element networks.md reports slipping though nothing moves) */
            put(&b, ",\"damper\":{\"law\":\"coulomb\",\"phi0\":%.6f}", uniform(0.1, 0.5));
        put(&b, "}");
    }
    put(&b, "],\"forcing\":[{\"node\":0,\"kind\":\"harmonic\",\"amplitude\":1.5,\"omega\":0.5,\"phase\":0}]},"
        "\"initial\":{\"v\":[");
    for (int i = 0; i < n; i++)
        put(&b, "%s%.6f", i ? "," : "", uniform(-0.3, 0.3));
    put(&b, "]},\"solver\":{\"dt\":0.01,\"t_end\":30,\"events\":\"%s\"},"
        "\"output\":{\"quakes\":true,\"every\":1}}", events);
    return b.s;
}

/* Two quakes equal member by member, to the bit (the struct's padding aside). */
static int same_quake(const dp_quake *a, const dp_quake *b)
{
    return a->t == b->t && a->duration == b->duration && a->moment == b->moment && a->peak_rate == b->peak_rate &&
           a->size == b->size && a->hypocentre == b->hypocentre && a->first == b->first && a->last == b->last &&
           a->open == b->open;
}

/* The total slip off the rows: over every step and every element that slipped at its start or end,
 * |du - v_b dt|, du from the rows' positions. Belt speeds are read back from the document's order. */
static double slip_from_rows(const catalogue *c, const double *belt, const long *ea, const long *eb)
{
    size_t nn = c->nx, ne = c->ne;
    double total = 0;
    for (size_t k = 1; k < c->n; k++) {
        const double *r0 = c->d + (k - 1) * c->width, *r1 = c->d + k * c->width;
        const double *x0 = r0 + 1, *x1 = r1 + 1, *ph0 = r0 + 1 + 2 * nn + 2 * ne, *ph1 = r1 + 1 + 2 * nn + 2 * ne;
        for (size_t e = 0; e < ne; e++) {
            if (ph0[e] != DP_PHASE_SLIP && ph1[e] != DP_PHASE_SLIP)
                continue;
            double u0 = (eb[e] >= 0 ? x0[eb[e]] : 0) - (ea[e] >= 0 ? x0[ea[e]] : 0);
            double u1 = (eb[e] >= 0 ? x1[eb[e]] : 0) - (ea[e] >= 0 ? x1[ea[e]] : 0);
            total += fabs((u1 - u0) - belt[e] * (r1[0] - r0[0]));
        }
    }
    return total;
}

/* Every slip belongs to exactly one quake: on random chains (Coulomb stepped without location, and
 * velocity-weakening friction with a static threshold) the moments add up to the rows' total slip to 1e-9;
 * with located events they are at least the rows' (which see one net displacement per step) and close; the
 * catalogue does not depend on the sample decimation or the caller's block. */
static void test_moments_are_the_total_slip(void **state)
{
    (void)state;
    for (int trial = 0; trial < 6; trial++) {
        int n = 6 + 4 * (trial % 4), law = trial % 2;
        char *doc = random_chain(n, law, trial >= 4 ? "locate" : "none");
        dp_spec spec;
        dp_errors errs;
        dp_spec_init(&spec);
        dp_errors_init(&errs);
        assert_int_equal(dp_spec_parse(doc, strlen(doc), 0, &spec, &errs), DP_OK);
        size_t ne = spec.net->nel;
        double *belt = calloc(ne, sizeof *belt);
        long *ea = calloc(ne, sizeof *ea), *eb = calloc(ne, sizeof *eb);
        for (size_t e = 0; e < ne; e++) {
            belt[e] = spec.net->el[e].has_damper ? spec.net->el[e].damper.belt_velocity : 0;
            ea[e] = spec.net->el[e].a, eb[e] = spec.net->el[e].b;
        }
        dp_spec_clear(&spec);
        catalogue *c = run_doc(doc, 1000);
        double slip = slip_from_rows(c, belt, ea, eb), moments = total_moment(c);
        CHECK(c->nquakes > 3 && slip > 1, "trial %d: %zu quakes, slip %g: too little happened to test", trial,
              c->nquakes, slip);
        if (trial < 4)
            CHECK(fabs(moments - slip) <= 1e-9 * slip, "trial %d: moments %.17g, slip from the rows %.17g", trial,
                  moments, slip);
        else   /* located: a step split where an element reverses counts both parts, the rows only the net */
            CHECK(moments >= slip * (1 - 1e-12) && moments <= slip * (1 + 1e-5),
                  "trial %d (located): moments %.17g, slip from the rows %.17g", trial, moments, slip);
        size_t sizes = 0;
        for (size_t i = 0; i < c->nquakes; i++) {
            sizes += c->quakes[i].size;
            CHECK(c->quakes[i].first <= c->quakes[i].hypocentre && c->quakes[i].hypocentre <= c->quakes[i].last, "hypocentre in range");
            CHECK(i == 0 || c->quakes[i].open || !c->quakes[i - 1].open, "open quakes come last");
        }
        assert_true(sizes >= c->nquakes);
        /* decimated, without samples, in blocks of 3: the same quakes, bit for bit */
        char *every = strstr(doc, "\"every\":1}");
        assert_non_null(every);
        size_t len = strlen(doc);
        char *doc7 = malloc(len + 32);
        memcpy(doc7, doc, (size_t)(every - doc));
        strcpy(doc7 + (every - doc), "\"every\":7,\"samples\":false}}");
        catalogue *d = run_doc(doc7, 3);
        assert_int_equal(d->nquakes, c->nquakes);
        for (size_t i = 0; i < c->nquakes; i++)
            CHECK(same_quake(&d->quakes[i], &c->quakes[i]), "trial %d: quake %zu differs decimated", trial, i);
        catalogue_free(d), catalogue_free(c);
        free(doc7), free(doc), free(belt), free(ea), free(eb);
    }
}

/* ---- Carlson–Langer ------------------------------------------------------------------------------------ */

/* The Carlson–Langer chain (docs/quakes.md) in the plate's frame: unit masses, unit springs to the plate,
 * l^2 between neighbours, friction phi(v) = (1 - sigma) / (1 + 2 alpha |v| / (1 - sigma)) against the ground,
 * which moves at -nu in this frame; initial offsets in [-1, 0). */
static char *carlson_langer(int n, double l, double sigma, double alpha, double nu, double dt, double t_end)
{
    buf b = { 0 };
    put(&b, "{\"model\":{\"masses\":[");
    for (int i = 0; i < n; i++)
        put(&b, "%s1", i ? "," : "");
    put(&b, "],\"elements\":[");
    for (int i = 0; i < n; i++)
        put(&b, "%s{\"between\":[\"ground\",%d],\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":"
            "\"generalized-coulomb\",\"phi0\":%.17g,\"phi1\":1,\"belt_velocity\":%.17g,\"relaxation\":{\"kind\":"
            "\"rational\",\"a\":%.17g,\"b\":%.17g}}}", i ? "," : "", i, 1 - sigma, -nu, 1 - sigma,
            (1 - sigma) / (2 * alpha));
    for (int i = 0; i + 1 < n; i++)
        put(&b, ",{\"between\":[%d,%d],\"spring\":{\"law\":\"linear\",\"k\":%.17g}}", i, i + 1, l * l);
    put(&b, "]},\"initial\":{\"x\":[");
    for (int i = 0; i < n; i++)
        put(&b, "%s%.6f", i ? "," : "", -uniform(0, 1));
    put(&b, "]},\"solver\":{\"dt\":%g,\"t_end\":%g},\"output\":{\"quakes\":true,\"samples\":false}}", dt, t_end);
    return b.s;
}

/* The law the document builds: the graph's force at v (phi0 sgn v) less the relaxation gamma(v) equals
 * phi(v) at every speed, the stick interval at rest is [-1, 1], and the kinetic limit at 0+ is 1 - sigma. */
static void test_carlson_langer_law(void **state)
{
    (void)state;
    const double sigma = 0.01, alpha = 2.5;
    char *doc = carlson_langer(2, 3, sigma, alpha, 0.01, 0.01, 1);
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    assert_int_equal(dp_spec_parse(doc, strlen(doc), 0, &spec, &errs), DP_OK);
    const dp_damper *d = &spec.net->el[0].damper;
    NEAR(dp_damper_static(d), 1, 0);
    NEAR(dp_damper_kinetic(d), 1 - sigma, 0);
    const double v[] = { 1e-9, 1e-4, 0.01, 0.1, 0.37, 1, 3, 10, 1e3 };
    for (size_t k = 0; k < sizeof v / sizeof *v; k++)
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            double z = sgn * v[k], lo, hi;
            dp_graph_force(&d->graph, z, &lo, &hi);
            CHECK(lo == hi, "a single force while slipping at %g", z);
            double F = lo - dp_relaxation_eval(&d->relaxation, z);
            double phi = sgn * (1 - sigma) / (1 + 2 * alpha * v[k] / (1 - sigma));
            CHECK(fabs(F - phi) <= 1e-15 * (1 + fabs(phi)), "v = %g: the law gives %.17g, Carlson–Langer %.17g", z,
                  F, phi);
        }
    double lo, hi;
    dp_graph_force(&d->graph, 0, &lo, &hi);   /* the kinetic graph's interval; the static one is [-phi1, phi1] */
    NEAR(hi, 1 - sigma, 0);
    dp_spec_clear(&spec);
    free(doc);
}

/* In the long run the blocks slip, on average, at the plate's speed: sum of moments / (N T) -> nu. The net
 * slip is nu T per block up to the bounded offsets; the moments count backward slips too (the friction here
 * is symmetric: docs/quakes.md), which at l = 1, alpha = 1 stay small: within 5 %. */
static void test_long_run_slip_rate(void **state)
{
    (void)state;
    const int n = 16;
    const double nu = 0.01, T = 3000;
    char *doc = carlson_langer(n, 1, 0.01, 1, nu, 0.05, T);
    catalogue *c = run_doc(doc, 4096);
    double rate = total_moment(c) / (n * T);
    CHECK(c->nquakes > 100, "%zu quakes", c->nquakes);
    CHECK(fabs(rate - nu) <= 0.05 * nu, "slip rate %.6g, plate speed %g", rate, nu);
    size_t big = 0;
    for (size_t i = 0; i < c->nquakes; i++)
        big += c->quakes[i].size == (size_t)n;
    CHECK(big > 0 && big < c->nquakes, "%zu of %zu quakes span the chain: sizes vary", big, c->nquakes);
    catalogue_free(c);
    free(doc);
}

/* ---- bad members ------------------------------------------------------------------------------------- */

static void expect_error(const char *json, const char *pointer)
{
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(json, strlen(json), 0, &spec, &errs);
    CHECK(s == DP_EINVAL && errs.n >= 1, "%s: status %d, %zu errors", json, s, errs.n);
    CHECK(strcmp(errs.item[0].pointer, pointer) == 0, "%s: error at %s (%s), expected %s", json, errs.item[0].pointer,
          errs.item[0].message, pointer);
    dp_spec_clear(&spec);
}

static void test_bad_quakes_members(void **state)
{
    (void)state;
    static const char net[] = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],"
                              "\"damper\":{\"law\":\"coulomb\",\"phi0\":1}}]},";
    char json[1024];
    snprintf(json, sizeof json, "%s\"output\":{\"quakes\":\"yes\"}}", net);
    expect_error(json, "/output/quakes");
    snprintf(json, sizeof json, "%s\"output\":{\"quakes\":1}}", net);
    expect_error(json, "/output/quakes");
    expect_error("{\"model\":{\"masses\":[1,1],\"elements\":[{\"between\":[0,1],\"spring\":{\"law\":\"linear\","
                 "\"k\":1},\"damper\":{\"law\":\"linear\",\"c\":1}}]},\"output\":{\"quakes\":true}}",
                 "/output/quakes");
    expect_error("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\","
                 "\"phi0\":1}},\"output\":{\"quakes\":true}}", "/output/quakes");
    expect_error("{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\","
                 "\"phi0\":1},\"contact\":{\"distance\":1}},\"output\":{\"quakes\":true}}", "/output/quakes");
    snprintf(json, sizeof json, "%s\"solver\":{\"kind\":\"regularized\",\"n\":100,\"t_end\":1},"
             "\"output\":{\"quakes\":true}}", net);
    expect_error(json, "/output/quakes");
    /* quakes false is fine anywhere */
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    const char *ok = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"none\"}},"
                     "\"output\":{\"quakes\":false}}";
    assert_int_equal(dp_spec_parse(ok, strlen(ok), 0, &spec, &errs), DP_OK);
    dp_spec_clear(&spec);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_block_to_rest_and_open),
        cmocka_unit_test(test_two_blocks_apart_and_together),
        cmocka_unit_test(test_merge_keeps_the_earlier_start),
        cmocka_unit_test(test_moments_are_the_total_slip),
        cmocka_unit_test(test_carlson_langer_law),
        cmocka_unit_test(test_long_run_slip_rate),
        cmocka_unit_test(test_bad_quakes_members),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
