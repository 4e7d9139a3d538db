/* tests/test_network.c - networks of masses (docs/systems.md §1) against independent references:
 * a one-node network is the one-mass model for every law, belt, forcing and theta; a linear two-mass chain
 * follows its modal closed form with second-order error at theta = 1/2; a Coulomb chain's energy loss equals
 * the work of its dampers; sticking blocks do not creep; the records do not depend on the caller's block. */
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

#include "rows.h"
#include "runs/run_table.h"
#include "solvers/run_types.h"
#include "trajectory.h"

/* Runs a network document with blocks of `cap` records; its rows are x, v, Fs, Fd, phase (no contacts). */
static void rows_run(const char *json, size_t cap, rows *r)
{
    rows_collect(json, cap, r);
    assert_int_equal(r->width - 1, 2 * r->nx + 3 * r->ne);
}

static const char *const springs[] = {
    "{\"law\":\"linear\",\"k\":1}", "{\"law\":\"rope\",\"k\":1,\"length\":2}",
    "{\"law\":\"graph\",\"points\":[[-1,-2],[0,0],[1,1],[2,4]]}",
};
static const char *const dampers[] = {
    "{\"law\":\"coulomb\",\"phi0\":0.5}", "{\"law\":\"bingham\",\"tau\":0.4,\"c\":0.3}",
    "{\"law\":\"linear\",\"c\":0.2}", "{\"law\":\"graph\",\"points\":[[-1,-1],[0,-0.5],[0,0.5],[1,1]]}",
    "{\"law\":\"none\"}", "{\"law\":\"coulomb\",\"phi0\":0.3,\"belt_velocity\":0.4}",
    "{\"law\":\"coulomb\",\"phi0\":0.5,\"relaxation\":{\"kind\":\"rational\",\"a\":0.5,\"b\":1}}",
    "{\"law\":\"bingham\",\"tau\":0.4,\"c\":0.3,\"belt_velocity\":0.2,\"relaxation\":{\"kind\":\"linear\",\"L\":0.3}}",
    "{\"law\":\"generalized-coulomb\",\"phi0\":0.2,\"phi1\":0.9,\"belt_velocity\":0.3}",
    "{\"law\":\"generalized-coulomb\",\"phi0\":0.3,\"phi1\":0.6,\"relaxation\":{\"kind\":\"rational\",\"a\":0.2,\"b\":1}}",
};
#define NDAMPERS (sizeof dampers / sizeof *dampers)
static const char *const loads[] = { NULL, "\"kind\":\"harmonic\",\"amplitude\":0.7,\"omega\":1.3,\"phase\":0.2",
                                     "\"kind\":\"constant\",\"value\":0.2" };

/* The one-mass model and a network of two unconnected copies of it step for step: node 0 of the network
 * (stepped by the general network step) is the one-mass trajectory. (A network of just one node and one
 * element [ground, 0] is handed to the one-mass solver itself, network_one_mass.c: checked bit for bit.) */
static void test_one_node_is_the_one_mass_model(void **state)
{
    (void)state;
    char one[1024], net[1024];
    size_t cases = 0;
    for (size_t s = 0; s < 3; s++)
        for (size_t d = 0; d < NDAMPERS; d++)
            for (size_t f = 0; f < 3; f++)
                for (int th = 0; th < 2; th++) {
                    double theta = th ? 1 : 0.5;
                    if (s > 0 && theta < 1)
                        continue;   /* nonlinear springs take theta = 1 in both models */
                    char fo1[160] = "", fo2[160] = "";
                    if (loads[f]) {
                        snprintf(fo1, sizeof fo1, ",\"forcing\":{%s}", loads[f]);
                        snprintf(fo2, sizeof fo2, ",\"forcing\":[{\"node\":0,%s}]", loads[f]);
                    }
                    const char *sv = "\"solver\":{\"kind\":\"stick-slip\",\"dt\":0.01,\"t_end\":8,\"events\":\"none\"";
                    snprintf(one, sizeof one, "{\"model\":{\"mass\":1.3,\"spring\":%s,\"damper\":%s%s},"
                             "\"initial\":{\"x\":1.5,\"v\":0.2},%s,\"theta\":%g},\"output\":{\"every\":7}}",
                             springs[s], dampers[d], fo1, sv, theta);
                    if (loads[f])
                        snprintf(fo2, sizeof fo2, ",\"forcing\":[{\"node\":0,%s},{\"node\":1,%s}]", loads[f], loads[f]);
                    snprintf(net, sizeof net, "{\"model\":{\"masses\":[1.3,1.3],\"elements\":[{\"between\":[\"ground\",0],"
                             "\"spring\":%s,\"damper\":%s},{\"between\":[\"ground\",1],\"spring\":%s,\"damper\":%s}]%s},"
                             "\"initial\":{\"x\":[1.5,1.5],\"v\":[0.2,0.2]},%s,\"theta\":%g},\"output\":{\"every\":7}}",
                             springs[s], dampers[d], springs[s], dampers[d], fo2, sv, theta);
                    traj a;
                    rows b;
                    assert_int_equal(traj_run(one, &a), DP_OK);
                    rows_run(net, 257, &b);
                    assert_int_equal(a.status, DP_DONE);
                    assert_int_equal(b.status, DP_DONE);
                    assert_int_equal(a.n, b.n);
                    for (size_t i = 0; i < a.n; i++) {
                        const double *r = b.d + i * b.width;   /* t, x0 x1, v0 v1, Fs0 Fs1, Fd0 Fd1, phase0 phase1 */
                        assert_true(a.s[i].t == r[0]);
                        assert_true(fabs(a.s[i].x - r[1]) <= 1e-12 * (1 + fabs(a.s[i].x)));
                        assert_true(fabs(a.s[i].v - r[3]) <= 1e-12 * (1 + fabs(a.s[i].v)));
                        assert_true(r[1] == r[2] && r[3] == r[4]);   /* the two copies agree exactly */
                        if (i > 0) {
                            assert_true(fabs(a.s[i].Fs - r[5]) <= 1e-11 * (1 + fabs(a.s[i].Fs)));
                            assert_true(fabs(a.s[i].Fd - r[7]) <= 1e-11 * (1 + fabs(a.s[i].Fd)));
                            assert_int_equal((int)a.s[i].phase, (int)r[9]);
                        }
                    }
                    /* the one-node network: the one-mass solver's own numbers */
                    free(b.d);
                    rows c;
                    char one_node[1024];
                    snprintf(one_node, sizeof one_node, "{\"model\":{\"masses\":[1.3],\"elements\":[{\"between\":"
                             "[\"ground\",0],\"spring\":%s,\"damper\":%s}]%s%s%s},\"initial\":{\"x\":[1.5],\"v\":[0.2]},%s,"
                             "\"theta\":%g},\"output\":{\"every\":7}}", springs[s], dampers[d],
                             loads[f] ? ",\"forcing\":[{\"node\":0," : "", loads[f] ? loads[f] : "", loads[f] ? "}]" : "",
                             sv, theta);
                    rows_run(one_node, 257, &c);
                    assert_int_equal(c.n, a.n);
                    for (size_t i = 0; i < a.n; i++) {
                        const double *r = c.d + i * c.width;
                        assert_true(a.s[i].x == r[1] && a.s[i].v == r[2] && a.s[i].Fs == r[3] && a.s[i].Fd == r[4]);
                    }
                    b = c;
                    traj_free(&a);
                    free(b.d);
                    cases++;
                }
    assert_int_equal(cases, (2 + 2) * NDAMPERS * 3);   /* linear spring: two thetas; the others: theta 1 */
}

/* With events located, the one-mass model and a network of two unconnected copies of it (the general network
 * step) split their steps at the same instants: the same trajectory and the same events (each copy's),
 * to the root finders' tolerance. */
static void test_one_node_located_events(void **state)
{
    (void)state;
    static const char *const located[] = {
        "{\"law\":\"coulomb\",\"phi0\":0.3}", "{\"law\":\"coulomb\",\"phi0\":0.3,\"belt_velocity\":0.2}",
        "{\"law\":\"bingham\",\"tau\":0.3,\"c\":0.2}",
    };
    char one[768], net[768];
    size_t events = 0;
    for (size_t d = 0; d < 3; d++)
        for (int th = 0; th < 2; th++)
            for (int f = 0; f < 2; f++) {
                const char *load = f ? ",\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":0.9,\"omega\":1.3}" : "";
                const char *nload = f ? ",\"forcing\":[{\"node\":0,\"kind\":\"harmonic\",\"amplitude\":0.9,\"omega\":1.3},"
                                        "{\"node\":1,\"kind\":\"harmonic\",\"amplitude\":0.9,\"omega\":1.3}]" : "";
                snprintf(one, sizeof one, "{\"model\":{\"mass\":1.3,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":%s%s},"
                         "\"initial\":{\"x\":1.5,\"v\":0.2},\"solver\":{\"dt\":0.01,\"t_end\":20,\"theta\":%s},"
                         "\"output\":{\"every\":10}}", located[d], load, th ? "1" : "0.5");
                snprintf(net, sizeof net, "{\"model\":{\"masses\":[1.3,1.3],\"elements\":[{\"between\":[\"ground\",0],"
                         "\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":%s},{\"between\":[\"ground\",1],"
                         "\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":%s}]%s},\"initial\":{\"x\":[1.5,1.5],"
                         "\"v\":[0.2,0.2]},\"solver\":{\"dt\":0.01,\"t_end\":20,\"theta\":%s},\"output\":{\"every\":10}}",
                         located[d], located[d], nload, th ? "1" : "0.5");
                traj a;
                rows b;
                assert_int_equal(traj_run(one, &a), DP_OK);
                rows_run(net, 100, &b);
                assert_int_equal(a.n, b.n);
                for (size_t i = 0; i < a.n; i++) {
                    const double *r = b.d + i * b.width;
                    assert_true(fabs(a.s[i].x - r[1]) < 1e-12 && fabs(a.s[i].v - r[3]) < 1e-12);
                }
                for (size_t i = 0, j = 0; i < a.ne; i++, j++) {
                    /* a touch of the belt speed may show on the network as a stick and a slip 1e-8 apart */
                    while (j < b.events && (b.ev[j].element != 0 || fabs(b.ev[j].t - a.e[i].t) > 1e-6))
                        j++;
                    assert_true(j < b.events);
                    assert_true(fabs(b.ev[j].t - a.e[i].t) < 1e-12 && b.ev[j].kind == a.e[i].kind);
                    events++;
                }
                traj_free(&a);
                free(b.d);
            }
    assert_true(events >= 5);
}

/* Two masses on a belt-driven chain stick and slip; with located events theta = 1/2 keeps second order:
 * errors against a run at dt/64 fall by about 4 per halving (about 2 with events "none"). */
static void stick_slip_chain(double dt, rows *r)
{
    char json[1024];
    snprintf(json, sizeof json, "{\"model\":{\"masses\":[1,1.5],\"elements\":["
             "{\"between\":[\"ground\",0],\"spring\":{\"law\":\"linear\",\"k\":1},"
             "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.4,\"belt_velocity\":0.3}},"
             "{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":2}},"
             "{\"between\":[\"ground\",1],\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5}}],"
             "\"forcing\":[{\"node\":1,\"kind\":\"harmonic\",\"amplitude\":0.8,\"omega\":0.9}]},"
             "\"initial\":{\"x\":[0.5,-0.2]},\"solver\":{\"dt\":%.17g,\"t_end\":10,\"theta\":0.5},"
             "\"output\":{\"every\":%ld}}", dt, lround(0.5 / dt));
    rows_run(json, 64, r);
    assert_int_equal(r->status, DP_DONE);
}

static double stick_slip_chain_error(double dt, const rows *ref)
{
    rows r;
    stick_slip_chain(dt, &r);
    double worst = rows_max_difference(&r, ref, 1, 5);
    free(r.d);
    return worst;
}

static void test_located_chain_is_second_order(void **state)
{
    (void)state;
    rows ref;
    stick_slip_chain(0.01 / 64, &ref);
    assert_true(ref.events >= 4);    /* the chain sticks and slips on the way */
    double e1 = stick_slip_chain_error(0.02, &ref), e2 = stick_slip_chain_error(0.01, &ref),
           e3 = stick_slip_chain_error(0.005, &ref);
    assert_true(e1 / e2 > 3.2 && e1 / e2 < 5);
    assert_true(e2 / e3 > 3.2 && e2 / e3 < 5);
    free(ref.d);
}

/* Parallel stick intervals (two on [ground, 0], one on [0, ground]) under a load of 0.5 all stick; the
 * reported split gives each its share in proportion to its interval's width: 0.1, 0.3 and -0.1. */
static void test_parallel_stick_intervals_share_the_load(void **state)
{
    (void)state;
    const char *json = "{\"model\":{\"masses\":[1],\"elements\":["
        "{\"between\":[\"ground\",0],\"damper\":{\"law\":\"coulomb\",\"phi0\":1}},"
        "{\"between\":[\"ground\",0],\"damper\":{\"law\":\"coulomb\",\"phi0\":3}},"
        "{\"between\":[0,\"ground\"],\"damper\":{\"law\":\"coulomb\",\"phi0\":1}}],"
        "\"forcing\":[{\"node\":0,\"kind\":\"constant\",\"value\":0.5}]},\"solver\":{\"dt\":0.01,\"t_end\":1}}";
    rows r;
    rows_run(json, 64, &r);
    assert_int_equal(r.status, DP_DONE);
    static const double share[3] = { 0.1, 0.3, -0.1 };
    for (size_t i = 0; i < r.n; i++) {
        const double *o = r.d + i * r.width;
        assert_true(o[1] == 0 && o[2] == 0);
        for (int e = 0; e < 3; e++) {
            assert_true(fabs(o[6 + e] - share[e]) < 1e-12);
            assert_true(o[9 + e] == DP_PHASE_STICK);
        }
    }
    free(r.d);
}

/* What the theory guarantees: a network of maximal monotone laws is well posed (existence and uniqueness);
 * a static threshold above the kinetic one breaks monotonicity, and the report says so, naming the element. */
static void test_network_wellposedness(void **state)
{
    (void)state;
    const char *good = "{\"model\":{\"masses\":[1,2],\"elements\":[{\"between\":[\"ground\",0],"
        "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.3}},{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":1}}]}}";
    const char *bad = "{\"model\":{\"masses\":[1,2],\"elements\":[{\"between\":[0,1],\"spring\":{\"law\":\"linear\","
        "\"k\":1}},{\"between\":[\"ground\",1],\"damper\":{\"law\":\"generalized-coulomb\",\"phi0\":0.3,\"phi1\":0.5}}]}}";
    dp_wp_report rep;
    dp_errors errs;
    dp_errors_init(&errs);
    assert_int_equal(dp_wellposedness_parse(good, strlen(good), &rep, &errs), DP_OK);
    assert_string_equal(rep.framework, "network");
    assert_true(rep.existence.guaranteed && rep.uniqueness.guaranteed);
    assert_int_equal(dp_wellposedness_parse(bad, strlen(bad), &rep, &errs), DP_OK);
    assert_false(rep.existence.guaranteed);
    assert_false(rep.uniqueness.guaranteed);
    assert_non_null(rep.counterexample);
    size_t failing = 0;
    for (size_t i = 0; i < rep.nchecks; i++)
        if (!rep.check[i].holds) {
            failing++;
            assert_non_null(strstr(rep.check[i].detail, "element 1"));
        }
    assert_int_equal(failing, 1);
}

/* The regularized scheme (PCn, Yosida dampers) converges to the exact stepping at rate 1/n: each decade of n
 * takes a decade off the error (measured 8.3e-3, 8.4e-4, 8.4e-5 for n = 1e2, 1e3, 1e4). */
static void test_regularized_converges_at_rate_one_over_n(void **state)
{
    (void)state;
    const char *model = "\"model\":{\"masses\":[1,1.5],\"elements\":["
        "{\"between\":[\"ground\",0],\"spring\":{\"law\":\"linear\",\"k\":1},"
        "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.4,\"belt_velocity\":0.3}},"
        "{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":2}},"
        "{\"between\":[\"ground\",1],\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5}}],"
        "\"forcing\":[{\"node\":1,\"kind\":\"harmonic\",\"amplitude\":0.8,\"omega\":0.9}]},"
        "\"initial\":{\"x\":[0.5,-0.2]}";
    char json[1024];
    rows ref;
    snprintf(json, sizeof json, "{%s,\"solver\":{\"dt\":0.0001,\"t_end\":10,\"theta\":0.5},"
             "\"output\":{\"every\":5000}}", model);
    rows_run(json, 64, &ref);
    double err[3];
    for (int k = 0; k < 3; k++) {
        rows r;
        snprintf(json, sizeof json, "{%s,\"solver\":{\"kind\":\"regularized\",\"n\":%g,\"dt\":0.5,\"t_end\":10,"
                 "\"rtol\":1e-10,\"atol\":1e-12}}", model, pow(10, 2 + k));
        rows_run(json, 64, &r);
        assert_int_equal(r.status, DP_DONE);
        assert_int_equal(r.n, ref.n);
        err[k] = 0;
        for (size_t i = 0; i < r.n; i++)
            for (size_t j = 1; j < 5; j++)
                err[k] = fmax(err[k], fabs(r.d[i * r.width + j] - ref.d[i * ref.width + j]));
        for (size_t i = 0; i < r.n; i++)
            for (size_t e = 0; e < r.ne; e++)       /* nothing sticks exactly: no phase */
                assert_true(r.d[i * r.width + 1 + 2 * r.nx + 2 * r.ne + e] == DP_PHASE_NONE);
        free(r.d);
    }
    assert_true(err[0] > 1e-3 && err[0] < 3e-2);
    assert_true(err[0] / err[1] > 8 && err[0] / err[1] < 12.5);
    assert_true(err[1] / err[2] > 8 && err[1] / err[2] < 12.5);
    free(ref.d);
}

/* Two masses, three unit springs (ground-0, 0-1, 1-ground): x(t) = (cos t +/- cos sqrt3 t)/2 from x = (1, 0)
 * (modes (1,1) at omega 1 and (1,-1) at sqrt 3); theta = 1/2 is second order. */
static double chain_error(double dt)
{
    char json[768];
    snprintf(json, sizeof json, "{\"model\":{\"masses\":[1,1],\"elements\":["
             "{\"between\":[\"ground\",0],\"spring\":{\"law\":\"linear\",\"k\":1}},"
             "{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":1}},"
             "{\"between\":[1,\"ground\"],\"spring\":{\"law\":\"linear\",\"k\":1}}]},"
             "\"initial\":{\"x\":[1,0]},\"solver\":{\"dt\":%g,\"t_end\":10,\"theta\":0.5},"
             "\"output\":{\"every\":%d}}", dt, (int)lround(0.5 / dt));
    rows r;
    rows_run(json, 64, &r);
    assert_int_equal(r.status, DP_DONE);
    assert_int_equal(r.n, 21);
    double worst = 0;
    for (size_t i = 0; i < r.n; i++) {
        const double *o = r.d + i * r.width;
        double t = o[0], a = cos(t), b = cos(sqrt(3) * t);
        worst = fmax(worst, fmax(fabs(o[1] - (a + b) / 2), fabs(o[2] - (a - b) / 2)));
        worst = fmax(worst, fabs(o[3] - (-sin(t) - sqrt(3) * sin(sqrt(3) * t)) / 2));
    }
    free(r.d);
    return worst;
}

static void test_linear_chain_against_its_modes(void **state)
{
    (void)state;
    double e1 = chain_error(0.01), e2 = chain_error(0.005);
    assert_true(e1 < 2e-3);
    assert_true(e1 / e2 > 3.6 && e1 / e2 < 4.4);
}

/* Three blocks with Coulomb friction, coupled by springs, no load: the energy lost equals the work of the
 * friction forces, sum over steps of h Fd_e (z_e + z_e+)/2. At theta = 1/2 the linear part is weighted as
 * the midpoint rule (M (v+ - v) = -h K (x + x+)/2 - h sum b lambda), so the discrete identity is exact. */
static void test_coulomb_chain_energy_balance(void **state)
{
    (void)state;
    const char *json = "{\"model\":{\"masses\":[1,2,1.5],\"elements\":["
        "{\"between\":[\"ground\",0],\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5}},"
        "{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":2}},"
        "{\"between\":[\"ground\",1],\"damper\":{\"law\":\"coulomb\",\"phi0\":0.8}},"
        "{\"between\":[1,2],\"spring\":{\"law\":\"linear\",\"k\":1.5},\"damper\":{\"law\":\"coulomb\",\"phi0\":0.4}},"
        "{\"between\":[2,\"ground\"],\"spring\":{\"law\":\"linear\",\"k\":0.5}}]},"
        "\"initial\":{\"x\":[2,-1,3],\"v\":[0,1,0]},\"solver\":{\"dt\":0.0005,\"t_end\":25,\"theta\":0.5,"
        "\"events\":\"none\"},\"output\":{\"every\":1}}";
    rows r;
    rows_run(json, 509, &r);
    assert_int_equal(r.status, DP_DONE);
    static const long ends[5][2] = { { -1, 0 }, { 0, 1 }, { -1, 1 }, { 1, 2 }, { 2, -1 } };
    static const double k[5] = { 1, 2, 0, 1.5, 0.5 }, m[3] = { 1, 2, 1.5 };
    double work = 0, E[2] = { 0, 0 };
    size_t sticks = 0;
    for (size_t i = 0; i < r.n; i++) {
        const double *o = r.d + i * r.width, *x = o + 1, *v = o + 4, *Fd = o + 12;
        if (i > 0) {
            const double *pv = v - r.width;
            for (int e = 0; e < 5; e++) {
                double z = (ends[e][1] >= 0 ? v[ends[e][1]] : 0) - (ends[e][0] >= 0 ? v[ends[e][0]] : 0);
                double z0 = (ends[e][1] >= 0 ? pv[ends[e][1]] : 0) - (ends[e][0] >= 0 ? pv[ends[e][0]] : 0);
                work += (o[0] - o[-(long)r.width]) * Fd[e] * (z + z0) / 2;
                sticks += o[17 + e] == DP_PHASE_STICK;
            }
        }
        if (i == 0 || i + 1 == r.n) {
            double en = 0;
            for (int j = 0; j < 3; j++)
                en += 0.5 * m[j] * v[j] * v[j];
            for (int e = 0; e < 5; e++) {
                double u = (ends[e][1] >= 0 ? x[ends[e][1]] : 0) - (ends[e][0] >= 0 ? x[ends[e][0]] : 0);
                en += 0.5 * k[e] * u * u;
            }
            E[i == 0 ? 0 : 1] = en;
        }
    }
    assert_true(work > 1);                   /* friction did real work */
    assert_true(sticks > 100);               /* and blocks stuck on the way */
    /* at theta = 1/2 the step is the midpoint rule, whose energy identity is exact: rounding only */
    assert_true(fabs((E[0] - E[1]) - work) < 1e-9 * work);
    free(r.d);
}

/* A block that sticks stays where it is, bit for bit, while its neighbour keeps moving. */
static void test_sticking_block_does_not_creep(void **state)
{
    (void)state;
    const char *json = "{\"model\":{\"masses\":[1,1],\"elements\":["
        "{\"between\":[\"ground\",0],\"damper\":{\"law\":\"coulomb\",\"phi0\":5}},"
        "{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":1}}]},"
        "\"initial\":{\"x\":[0,1],\"v\":[0,0]},\"solver\":{\"dt\":0.001,\"t_end\":20,\"theta\":0.5},"
        "\"output\":{\"every\":10}}";
    rows r;
    rows_run(json, 100, &r);
    assert_int_equal(r.status, DP_DONE);
    for (size_t i = 0; i < r.n; i++) {
        const double *o = r.d + i * r.width;
        assert_true(o[1] == 0 && o[3] == 0);          /* block 0: x and v exactly zero */
        assert_true(fabs(o[2] - cos(o[0])) < 1e-4);   /* block 1: harmonic about the stuck one */
        assert_true(o[9] == DP_PHASE_STICK);
    }
    free(r.d);
}

/* The same records whatever block size the caller uses (events overflowing a block wait in the run). */
static void test_records_do_not_depend_on_the_block(void **state)
{
    (void)state;
    char json[4096];
    int n = snprintf(json, sizeof json, "{\"model\":{\"masses\":[1,1,1,1,1,1],\"elements\":[");
    for (int i = 0; i < 6; i++)
        n += snprintf(json + n, sizeof json - (size_t)n, "%s{\"between\":[\"ground\",%d],\"spring\":{\"law\":\"linear\","
                      "\"k\":1},\"damper\":{\"law\":\"coulomb\",\"phi0\":0.1}}", i ? "," : "", i);
    snprintf(json + n, sizeof json - (size_t)n, "]},\"initial\":{\"x\":[1,1,1,1,1,1]},\"solver\":{\"dt\":0.01,"
             "\"t_end\":30,\"theta\":0.5},\"output\":{\"every\":3}}");
    rows a, b;
    rows_run(json, 1, &a);
    rows_run(json, 1000, &b);
    assert_int_equal(a.n, b.n);
    assert_int_equal(a.events, b.events);
    assert_true(a.events >= 6);   /* the six identical blocks stick in one step: six events at once */
    assert_true(a.ev[a.events - 1].t == a.ev[a.events - 6].t);
    assert_memory_equal(a.d, b.d, a.n * a.width * sizeof *a.d);
    for (size_t i = 0; i < a.events; i++)
        assert_true(a.ev[i].t == b.ev[i].t && a.ev[i].element == b.ev[i].element && a.ev[i].kind == b.ev[i].kind);
    free(a.d);
    free(b.d);
}

/* Relaxation: a dt that makes W - h theta sum L b b^T indefinite is refused at /solver/dt; a smaller one runs. */
static void test_relaxation_step_bound(void **state)
{
    (void)state;
    char json[512];
    for (int k = 0; k < 2; k++) {
        snprintf(json, sizeof json, "{\"model\":{\"masses\":[0.1,0.1],\"elements\":[{\"between\":[0,1],\"damper\":"
                 "{\"law\":\"coulomb\",\"phi0\":1,\"relaxation\":{\"kind\":\"rational\",\"a\":2,\"b\":1}}}]},"
                 "\"solver\":{\"dt\":%s,\"t_end\":1}}", k ? "0.01" : "0.2");
        dp_spec spec;
        dp_errors errs;
        dp_spec_init(&spec);
        dp_errors_init(&errs);
        int s = dp_spec_parse(json, strlen(json), 0, &spec, &errs);
        assert_int_equal(s, DP_OK);
        dp_run *run = dp_run_alloc(&spec, 0, &errs, &s);
        /* the Delassus bound: W = m = 0.1 per node, b b^T has eigenvalue 2 on (1,-1): 0.1 > h 2 * 2 needs h < 0.025 */
        if (k == 0) {
            assert_null(run);
            assert_int_equal(s, DP_EINVAL);
            assert_string_equal(errs.item[0].pointer, "/solver/dt");
        } else {
            assert_non_null(run);
        }
        dp_run_free(run);
        dp_spec_clear(&spec);
    }
}

/* A ring of 60 blocks (springs around it, friction and a spring to the ground each) written once numbered
 * around the ring (half-bandwidth 59: the run renumbers it, network_order.c) and once with its nodes
 * shuffled: node k of the first is node perm[k] of the second, and every row must say so, written in the
 * user's numbering. Without event location the two runs differ only by the rounding of their orderings. */
static char *ring_doc(const size_t *perm, size_t n)
{
    size_t cap = 400 * n + 4096, len = 0;
    char *d = malloc(cap);
    assert_non_null(d);
    double *x = calloc(n, sizeof *x), *m = calloc(n, sizeof *m);
    assert_non_null(x), assert_non_null(m);
    for (size_t k = 0; k < n; k++)
        m[perm[k]] = 1 + 0.01 * (double)(k % 7);
    len += (size_t)snprintf(d + len, cap - len, "{\"model\":{\"masses\":[");
    for (size_t i = 0; i < n; i++)
        len += (size_t)snprintf(d + len, cap - len, "%s%g", i ? "," : "", m[i]);
    len += (size_t)snprintf(d + len, cap - len, "],\"elements\":[");
    for (size_t k = 0; k < n; k++) {
        len += (size_t)snprintf(d + len, cap - len, "%s{\"between\":[%zu,%zu],\"spring\":{\"law\":\"linear\",\"k\":50}},"
                                "{\"between\":[\"ground\",%zu],\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":"
                                "{\"law\":\"coulomb\",\"phi0\":0.3,\"belt_velocity\":0.1}}", k ? "," : "", perm[k],
                                perm[(k + 1) % n], perm[k]);
        x[perm[k]] = 0.01 * (double)((k * 37) % 11) - 0.05;
    }
    len += (size_t)snprintf(d + len, cap - len, "]},\"initial\":{\"x\":[");
    for (size_t i = 0; i < n; i++)
        len += (size_t)snprintf(d + len, cap - len, "%s%.17g", i ? "," : "", x[i]);
    snprintf(d + len, cap - len, "]},\"solver\":{\"dt\":0.01,\"t_end\":3,\"theta\":0.5,\"events\":\"none\"},"
             "\"output\":{\"every\":10}}");
    free(x), free(m);
    return d;
}

static void test_ring_renumbered(void **state)
{
    (void)state;
    enum { N = 60 };
    size_t ident[N], perm[N];
    for (size_t k = 0; k < N; k++)
        ident[k] = perm[k] = k;
    for (size_t k = N - 1; k > 0; k--) {     /* a fixed shuffle */
        size_t j = (k * 7919 + 13) % (k + 1), t = perm[k];
        perm[k] = perm[j], perm[j] = t;
    }
    char *a_doc = ring_doc(ident, N), *b_doc = ring_doc(perm, N);
    rows a, b;
    rows_run(a_doc, 257, &a);
    rows_run(b_doc, 257, &b);
    assert_int_equal(a.n, b.n);
    double moved = 0;
    for (size_t i = 0; i < a.n; i++)
        for (size_t k = 0; k < N; k++) {
            const double *ra = a.d + i * a.width, *rb = b.d + i * b.width;
            assert_true(fabs(ra[1 + k] - rb[1 + perm[k]]) <= 1e-12);
            assert_true(fabs(ra[1 + N + k] - rb[1 + N + perm[k]]) <= 1e-12);
            moved = fmax(moved, fabs(ra[1 + k] - a.d[1 + k]));
        }
    assert_true(moved > 0.01);   /* the blocks did move: the comparison means something */
    free(a.d), free(b.d), free(a_doc), free(b_doc);
}

/* ---- the stop hook inside a step ------------------------------------------------------------------- */

/* A chain of n blocks on Coulomb friction (phi0 = 1) joined by soft springs, each sliding at its own speed
 * in [0.2, 0.9]: with dt = 1 every block sticks inside the first step, n located events in it, each a
 * root bracketed by held solves over the whole chain. */
static char *all_stick_chain(size_t n, double dt)
{
    size_t cap = 256 * n + 512, len = 0;
    char *d = malloc(cap);
    assert_non_null(d);
    len += (size_t)snprintf(d + len, cap - len, "{\"model\":{\"masses\":[");
    for (size_t i = 0; i < n; i++)
        len += (size_t)snprintf(d + len, cap - len, "%s1", i ? "," : "");
    len += (size_t)snprintf(d + len, cap - len, "],\"elements\":[");
    for (size_t i = 0; i < n; i++)
        len += (size_t)snprintf(d + len, cap - len, "%s{\"between\":[\"ground\",%zu],\"damper\":{\"law\":\"coulomb\","
                                "\"phi0\":1}}", i ? "," : "", i);
    for (size_t i = 0; i + 1 < n; i++)
        len += (size_t)snprintf(d + len, cap - len, ",{\"between\":[%zu,%zu],\"spring\":{\"law\":\"linear\","
                                "\"k\":0.01}}", i, i + 1);
    len += (size_t)snprintf(d + len, cap - len, "]},\"initial\":{\"v\":[");
    for (size_t i = 0; i < n; i++)
        len += (size_t)snprintf(d + len, cap - len, "%s%.6g", i ? "," : "", 0.2 + 0.7 * (double)((i * 37) % 101) / 101);
    snprintf(d + len, cap - len, "]},\"solver\":{\"dt\":%g,\"t_end\":2,\"theta\":0.5},\"output\":{\"every\":1}}", dt);
    return d;
}

typedef struct hook { unsigned polls, stop_at; int answer; } hook;

/* Says stop at its stop_at-th poll; before that `answer` (0: go on, -1: yield). */
static int counting_hook(void *ctx)
{
    hook *h = ctx;
    return ++h->polls >= h->stop_at ? 1 : h->answer;
}

static dp_run *run_of(const char *json)
{
    dp_spec spec;
    dp_errors errs;
    int s;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    assert_int_equal(dp_spec_parse(json, strlen(json), 0, &spec, &errs), DP_OK);
    dp_run *run = dp_run_alloc(&spec, 0, &errs, &s);
    dp_spec_clear(&spec);
    assert_non_null(run);
    return run;
}

/* 4000 blocks that all stick in the first step of dt = 1 (about 10^5 held solves of the whole chain in that
 * one step): a hook that says stop at its 5th poll ends the run inside the step, in the first dp_run_next,
 * with DP_ECANCEL and a message, after a handful of solves; it was polled exactly 5 times, and the run is
 * finished (later calls say DP_ECANCEL again and ask the hook no more). The solves are counted by the
 * summary's iterations: a solve of 4000 nodes and 7999 elements is past DP_RUN_POLL_WORK units, so each
 * is followed by a poll. */
static void test_stop_inside_a_step(void **state)
{
    (void)state;
    char *doc = all_stick_chain(4000, 1);
    dp_run *run = run_of(doc);
    hook h = { 0, 5, 0 };
    dp_run_set_stop(run, counting_hook, &h);
    dp_record buf[64];
    size_t n;
    int s;
    do
        s = dp_run_next(run, buf, 64, &n);
    while (s == DP_MORE && h.polls < 5);
    assert_int_equal(s, DP_ECANCEL);
    assert_int_equal(h.polls, 5);
    const dp_summary *sum = dp_run_summary(run);
    assert_true(sum->steps == 0);                 /* inside the first step */
    assert_true(sum->iterations <= 2 * 5 + 64);   /* a few solves (bracketing counts its evaluations too) */
    assert_non_null(strstr(dp_run_error(run), "stopped"));
    assert_int_equal(dp_run_next(run, buf, 64, &n), DP_ECANCEL);
    assert_int_equal(h.polls, 5);
    dp_run_free(run);
    free(doc);
}

/* A yield asked for inside a step is honoured between steps, and changes nothing: a hook that yields at
 * every poll gives the records of the run without one, bit for bit (40 blocks, located events). */
static void test_yield_inside_a_step(void **state)
{
    (void)state;
    char *doc = all_stick_chain(40, 0.05);
    rows plain;
    rows_run(doc, 64, &plain);
    dp_run *run = run_of(doc);
    hook h = { 0, (unsigned)-1, -1 };
    dp_run_set_stop(run, counting_hook, &h);
    dp_record buf[64];
    size_t n, at = 0, events = 0;
    int s;
    do {
        s = dp_run_next(run, buf, 64, &n);
        for (size_t i = 0; i < n; i++) {
            if (buf[i].type == DP_RECORD_EVENT) {
                assert_true(events < plain.events && buf[i].u.event.t == plain.ev[events].t);
                events++;
                continue;
            }
            assert_true(at < plain.n);
            assert_memory_equal(buf[i].u.row.val, plain.d + at * plain.width + 1, (plain.width - 1) * sizeof(double));
            at++;
        }
    } while (s == DP_MORE);
    assert_int_equal(s, DP_DONE);
    assert_int_equal(at, plain.n);
    assert_int_equal(events, plain.events);
    assert_true(plain.events >= 40 && h.polls >= 20);   /* every block stuck; the hook was asked throughout */
    dp_run_free(run);
    free(plain.d), free(doc);
}

/* ---- the working-memory limit and hostile magnitudes ---------------------------------------------------- */

/* A sparse random graph of 20 000 nodes (14 000 springs between random nodes, friction on every 50th): its
 * half-bandwidth after reverse Cuthill-McKee is about a thousand, so its band matrices would take about a
 * gigabyte (it once did). It is refused by dp_run_alloc with DP_ELIMIT at /model/elements, the estimate and
 * the limit in the message. A Burridge-Knopoff chain of 20 000 blocks (half-bandwidth 1) is accepted. */
static char *random_graph(size_t n, size_t m, int chain)
{
    size_t cap = 160 * (n + m) + 256, len = 0;
    char *d = malloc(cap);
    assert_non_null(d);
    uint64_t x = 88172645463325252ull;
    len += (size_t)snprintf(d + len, cap - len, "{\"model\":{\"masses\":[");
    for (size_t i = 0; i < n; i++)
        len += (size_t)snprintf(d + len, cap - len, "%s1", i ? "," : "");
    len += (size_t)snprintf(d + len, cap - len, "],\"elements\":[");
    for (size_t k = 0; k < m; k++) {
        size_t a, b;
        if (chain) {
            a = k, b = k + 1;
        } else {
            x ^= x << 13, x ^= x >> 7, x ^= x << 17;
            a = (size_t)(x % n), b = (size_t)((x >> 32) % n);
            if (a == b)
                b = (a + 1) % n;
        }
        len += (size_t)snprintf(d + len, cap - len, "{\"between\":[%zu,%zu],\"spring\":{\"law\":\"linear\",\"k\":1}},",
                                a, b);
    }
    for (size_t i = 0; i < n; i += chain ? 1 : 50)
        len += (size_t)snprintf(d + len, cap - len, "%s{\"between\":[\"ground\",%zu],\"damper\":{\"law\":\"coulomb\","
                                "\"phi0\":0.1}}", i ? "," : "", i);
    snprintf(d + len, cap - len, "]},\"solver\":{\"dt\":0.1,\"t_end\":0.2}}");
    return d;
}

/* The dampers without a relaxation (the steps that write no row skip their forces), then the others. */
static const size_t plain_dampers[] = { 0, 1, 2, 3, 4, 5, 8 }, relaxed_dampers[] = { 6, 7, 9 };

/* A chain of 6 blocks, each on a ground spring and a damper of the list `ds` (from d0 on), neighbours on
 * springs of stiffness kc with dampers of the same list, a harmonic and a constant load; every `every`-th step
 * written. */
static void decimated_doc(char *d, size_t cap, const size_t *ds, size_t nds, size_t d0, const char *kc,
                          const char *events, int every)
{
    size_t len = (size_t)snprintf(d, cap, "{\"model\":{\"masses\":[1,2,1,1.5,1,1],\"elements\":[");
    for (size_t i = 0; i < 6; i++) {
        len += (size_t)snprintf(d + len, cap - len, "{\"between\":[\"ground\",%zu],\"spring\":{\"law\":\"linear\","
                                "\"k\":%g},\"damper\":%s},", i, 1 + 0.3 * (double)i, dampers[ds[(d0 + i) % nds]]);
        if (i + 1 < 6)
            len += (size_t)snprintf(d + len, cap - len, "{\"between\":[%zu,%zu],\"spring\":{\"law\":\"linear\","
                                    "\"k\":%s},\"damper\":%s},", i, i + 1, kc, dampers[ds[(d0 + 2 * i + 1) % nds]]);
    }
    len--;   /* the last comma */
    snprintf(d + len, cap - len, "],\"forcing\":[{\"node\":0,%s},{\"node\":4,%s}]},\"initial\":{\"x\":[1,-0.5,0.3,"
             "0.8,-1,0.2],\"v\":[0,0.4,0,-0.3,0,0]},\"solver\":{\"kind\":\"stick-slip\",\"dt\":0.01,\"t_end\":3,"
             "\"theta\":0.5,\"events\":\"%s\"},\"output\":{\"every\":%d}}", loads[1], loads[2], events, every);
}

/* A step that writes no row forms no forces (network_run_element_phases: its phases, and a bound that shows
 * the forces finite): the rows written every 5th step are those rows of the run that writes every step, bit
 * for bit, for plain laws, for laws whose forces are formed every step, and where the bound fails (k 1e200). */
static void test_decimated_rows_are_the_full_rows(void **state)
{
    (void)state;
    static char doc[8192];
    const char *kcs[] = { "2", "1e200" };
    int ran = 0;
    for (size_t d0 = 0; d0 < 10; d0++)
        for (size_t c = 0; c < 2; c++)
            for (int loc = 0; loc < 2; loc++) {
                rows all = { 0 }, some = { 0 };
                const size_t *ds = d0 < 7 ? plain_dampers : relaxed_dampers, nds = d0 < 7 ? 7 : 3;
                decimated_doc(doc, sizeof doc, ds, nds, d0, kcs[c], loc ? "locate" : "none", 1);
                rows_run(doc, 64, &all);
                decimated_doc(doc, sizeof doc, ds, nds, d0, kcs[c], loc ? "locate" : "none", 5);
                rows_run(doc, 64, &some);
                assert_int_equal(all.status, some.status);
                ran += all.status == DP_DONE && c == 1;
                /* t = 0, every 5th step and the last; a run that fails writes its rows up to the failure */
                assert_true(some.n >= (all.n - 1) / 5 + (all.status == DP_DONE));
                for (size_t j = 0, i = 0; j < some.n; j++) {
                    while (i < all.n && all.d[i * all.width] != some.d[j * some.width])
                        i++;
                    assert_true(i < all.n && (i % 5 == 0 || i == all.n - 1));
                    assert_memory_equal(some.d + j * some.width, all.d + i * all.width, some.width * sizeof(double));
                    /* and the forces are the row's own: a ground spring's k x (element 2b of block b) */
                    const double *row = some.d + j * some.width + 1, *Fs = row + 2 * some.nx;
                    for (size_t b = 0; b < 6; b++)
                        assert_true(fabs(Fs[2 * b] - (1 + 0.3 * (double)b) * row[b]) <= 1e-12 * (1 + fabs(row[b])));
                }
                free(all.d), free(some.d), free(all.quakes), free(some.quakes);
            }
    assert_true(ran >= 10);   /* most runs past the bound end well */
}

static void test_working_memory_limit(void **state)
{
    (void)state;
    for (int chain = 0; chain < 2; chain++) {
        char *doc = random_graph(20000, chain ? 19999 : 14000, chain);
        dp_spec spec;
        dp_errors errs;
        int s;
        dp_spec_init(&spec);
        dp_errors_init(&errs);
        assert_int_equal(dp_spec_parse(doc, strlen(doc), 0, &spec, &errs), DP_OK);
        dp_run *run = dp_run_alloc(&spec, 0, &errs, &s);
        if (chain) {
            if (run == NULL)
                fprintf(stderr, "%s: %s\n", errs.item[0].pointer, errs.item[0].message);
            assert_non_null(run);
        } else {
            assert_null(run);
            assert_int_equal(s, DP_ELIMIT);
            assert_int_equal(errs.n, 1);
            assert_string_equal(errs.item[0].pointer, "/model/elements");
            assert_non_null(strstr(errs.item[0].message, "over the limit of 128 MiB"));
            unsigned mib = 0;   /* the estimate: six bands of 20 000 x (p + 1) doubles, p in the hundreds */
            assert_int_equal(sscanf(strstr(errs.item[0].message, "about ") + 6, "%u", &mib), 1);
            assert_true(mib > 128 && mib < 4096);
        }
        dp_run_free(run);
        dp_spec_clear(&spec);
        free(doc);
    }
}

/* Hostile magnitudes: a stiffness of 1e308 or an initial state of 1e300 and more is refused at its member
 * before any step (W's entries and the state are checked where formed), never streamed into NaN or into
 * "the solution diverged"; a mass of 5e-324 is refused by the parser's range or runs finite. */
static void test_hostile_magnitudes(void **state)
{
    (void)state;
    static const struct { const char *k, *x, *pointer; } cases[] = {
        { "1e308", "1", "/model/elements/0/spring" },
        { "1", "1e300", "/initial/x/0" },
        { "1", "-1e308", "/initial/x/0" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char doc[512];
        snprintf(doc, sizeof doc, "{\"model\":{\"masses\":[1,1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":"
                 "{\"law\":\"linear\",\"k\":%s},\"damper\":{\"law\":\"coulomb\",\"phi0\":0.2}},{\"between\":[0,1],"
                 "\"spring\":{\"law\":\"linear\",\"k\":1}}],\"forcing\":[]},\"initial\":{\"x\":[%s,0]},\"solver\":"
                 "{\"dt\":0.01,\"t_end\":1}}", cases[i].k, cases[i].x);
        dp_spec spec;
        dp_errors errs;
        int s;
        dp_spec_init(&spec);
        dp_errors_init(&errs);
        s = dp_spec_parse(doc, strlen(doc), 0, &spec, &errs);
        dp_run *run = s == DP_OK ? dp_run_alloc(&spec, 0, &errs, &s) : NULL;
        assert_null(run);
        assert_int_equal(s, DP_EINVAL);
        assert_true(errs.n >= 1);
        assert_string_equal(errs.item[0].pointer, cases[i].pointer);
        dp_spec_clear(&spec);
    }
}

/* Which friction chains the lean grounded chain steps (runs/run_table.c, dp_network_is_grounded_chain): Coulomb
 * dampers from the ground to distinct nodes on any belt, with springs and linear dampers, and "events":
 * "none"; not located events, generalized Coulomb's static threshold, relaxation, Bingham, friction between
 * two nodes, two set-valued laws on one node, a chain without any. */
static void test_grounded_chain_chosen(void **state)
{
    (void)state;
    static const struct { const char *e0, *e2, *events; int lean; } cases[] = {
        { "[\"ground\",0],\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5,\"belt_velocity\":0.5}", "[2,\"ground\"],"
          "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.3}", "none", 1 },
        { "[\"ground\",0],\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5}", "[\"ground\",2],\"contact\":{\"distance\":-1,"
          "\"restitution\":0.5}", "none", 1 },
        { "[\"ground\",0],\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5}", "[\"ground\",1],\"damper\":{\"law\":"
          "\"linear\",\"c\":0.2,\"belt_velocity\":0.1}", "none", 1 },
        { "[\"ground\",0],\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5}", "[\"ground\",2],\"damper\":{\"law\":"
          "\"coulomb\",\"phi0\":0.3}", "locate", 0 },
        { "[\"ground\",0],\"damper\":{\"law\":\"generalized-coulomb\",\"phi0\":0.5,\"phi1\":0.7}", "[\"ground\",2],"
          "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.3}", "none", 0 },
        { "[\"ground\",0],\"damper\":{\"law\":\"bingham\",\"tau\":0.5,\"c\":1}", "[\"ground\",2],\"damper\":{\"law\":"
          "\"coulomb\",\"phi0\":0.3}", "none", 0 },
        { "[0,1],\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5}", "[\"ground\",2],\"damper\":{\"law\":\"coulomb\","
          "\"phi0\":0.3}", "none", 0 },
        { "[\"ground\",0],\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5}", "[0,\"ground\"],\"damper\":{\"law\":"
          "\"coulomb\",\"phi0\":0.3}", "none", 0 },
        { "[\"ground\",0],\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5},\"contact\":{\"distance\":-1}", "[\"ground\",2],"
          "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.3}", "none", 0 },
        { "[\"ground\",0],\"damper\":{\"law\":\"coulomb\",\"phi0\":0}", "[\"ground\",2],\"damper\":{\"law\":\"linear\","
          "\"c\":1}", "none", 0 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char doc[1024];
        snprintf(doc, sizeof doc, "{\"model\":{\"masses\":[1,1,1],\"elements\":[{\"between\":%s},{\"between\":[0,1],"
                 "\"spring\":{\"law\":\"linear\",\"k\":1}},{\"between\":[1,2],\"spring\":{\"law\":\"linear\",\"k\":1}},"
                 "{\"between\":%s}]},\"initial\":{\"x\":[1,0,0]},\"solver\":{\"kind\":\"stick-slip\",\"dt\":0.01,"
                 "\"t_end\":1,\"events\":\"%s\"}}", cases[i].e0, cases[i].e2, cases[i].events);
        dp_spec spec;
        dp_errors errs;
        dp_spec_init(&spec);
        dp_errors_init(&errs);
        int s = dp_spec_parse(doc, strlen(doc), 0, &spec, &errs);
        if (s != DP_OK)
            fprintf(stderr, "%s\n%s: %s\n", doc, errs.n ? errs.item[0].pointer : "", errs.n ? errs.item[0].message : "");
        assert_int_equal(s, DP_OK);
        const dp_run_type *t = dp_run_type_of(&spec);
        if ((t == &dp_run_network_grounded_chain) != cases[i].lean)
            fprintf(stderr, "case %zu: %s\n", i, doc);
        assert_int_equal(t == &dp_run_network_grounded_chain, cases[i].lean);
        dp_spec_clear(&spec);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_node_is_the_one_mass_model),
        cmocka_unit_test(test_linear_chain_against_its_modes),
        cmocka_unit_test(test_one_node_located_events),
        cmocka_unit_test(test_located_chain_is_second_order),
        cmocka_unit_test(test_coulomb_chain_energy_balance),
        cmocka_unit_test(test_sticking_block_does_not_creep),
        cmocka_unit_test(test_records_do_not_depend_on_the_block),
        cmocka_unit_test(test_relaxation_step_bound),
        cmocka_unit_test(test_network_wellposedness),
        cmocka_unit_test(test_parallel_stick_intervals_share_the_load),
        cmocka_unit_test(test_regularized_converges_at_rate_one_over_n),
        cmocka_unit_test(test_ring_renumbered),
        cmocka_unit_test(test_stop_inside_a_step),
        cmocka_unit_test(test_yield_inside_a_step),
        cmocka_unit_test(test_working_memory_limit),
        cmocka_unit_test(test_hostile_magnitudes),
        cmocka_unit_test(test_decimated_rows_are_the_full_rows),
        cmocka_unit_test(test_grounded_chain_chosen),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
