/* tests/test_network_events.c - located events on networks for the laws whose phase changes are not a
 * linear spring's threshold: static thresholds (generalized Coulomb, phi1 > phi0), relaxation (thesis
 * (3.2)) and elastoplastic (Jenkins) springs' yield and unload (Höschl 1983 §15). Each is checked against
 * an independent reference: a closed form of stick-slip on a belt (Pražák & Rajagopal 2016 §4), the
 * one-mass solver's own event location, or the same network at dt/64; theta = 1/2 stays second order
 * (errors fall by about 4 per halving of dt, less or erratically with events "none"), and a stuck block
 * does not creep. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "dashpot/run.h"
#include "rows.h"
#include "trajectory.h"

#define LINEAR "{\"law\":\"linear\",\"k\":1}"

/* Runs a network document; its rows are t, x, v, Fs, Fd, phase (no contacts). */
static void rows_run(const char *json, rows *r)
{
    rows_collect(json, 128, r);
    assert_int_equal(r->status, DP_DONE);
    assert_int_equal(r->width - 1, 2 * r->nx + 3 * r->ne);
}


/* ---- a block on a belt: the closed form ---------------------------------------------------------- */

/* A block of mass m on a spring k to the ground and generalized Coulomb friction (phi0 < phi1) against a
 * belt at speed V > 0, starting at x = 0 with the belt's speed: it sticks (x = V t) until k x = phi1, slips
 * on the kinetic threshold about x_c = phi0 / k (a half turn of the oscillator of frequency w = sqrt(k/m)
 * from the speed V back to V) and sticks again at x_s = (2 phi0 - phi1) / k: a stick of 2 (phi1 - phi0) /
 * (k V) and a slip of (pi + 2 atan(V / (w A))) / w, A = (phi1 - phi0) / k, for ever. */
typedef struct belt_block {
    double m, k, phi0, phi1, V;
} belt_block;

static double belt_slip_time(const belt_block *b)
{
    double w = sqrt(b->k / b->m), A = (b->phi1 - b->phi0) / b->k;
    return (M_PI + 2 * atan(b->V / (w * A))) / w;
}

static double belt_stick_time(const belt_block *b)
{
    return 2 * (b->phi1 - b->phi0) / (b->k * b->V);
}

/* The block's position at time t; *phase DP_PHASE_STICK or DP_PHASE_SLIP. */
static double belt_x(const belt_block *b, double t, int *phase)
{
    double x1 = b->phi1 / b->k, t0 = x1 / b->V;
    if (t <= t0) {
        *phase = DP_PHASE_STICK;
        return b->V * t;
    }
    double w = sqrt(b->k / b->m), xc = b->phi0 / b->k, A = x1 - xc, xs = xc - A;
    double T = belt_slip_time(b), S = belt_stick_time(b), s = fmod(t - t0, T + S);
    if (s < T) {
        *phase = DP_PHASE_SLIP;
        return xc + A * cos(w * s) + b->V / w * sin(w * s);
    }
    *phase = DP_PHASE_STICK;
    return xs + b->V * (s - T);
}

static const belt_block belt_blocks[2] = { { 1, 1, 0.2, 0.5, 0.3 }, { 1.5, 2, 0.3, 0.9, 0.2 } };

/* Two such blocks (one network, so the general network step, not the one-mass solver), sampled every 0.5. */
static void belt_run(double dt, const char *events, rows *r)
{
    char json[1024];
    const belt_block *a = &belt_blocks[0], *b = &belt_blocks[1];
    snprintf(json, sizeof json, "{\"model\":{\"masses\":[%g,%g],\"elements\":["
             "{\"between\":[\"ground\",0],\"spring\":{\"law\":\"linear\",\"k\":%g},\"damper\":{\"law\":"
             "\"generalized-coulomb\",\"phi0\":%g,\"phi1\":%g,\"belt_velocity\":%g}},"
             "{\"between\":[\"ground\",1],\"spring\":{\"law\":\"linear\",\"k\":%g},\"damper\":{\"law\":"
             "\"generalized-coulomb\",\"phi0\":%g,\"phi1\":%g,\"belt_velocity\":%g}}]},"
             "\"initial\":{\"x\":[0,0],\"v\":[%g,%g]},\"solver\":{\"dt\":%.17g,\"t_end\":12,\"theta\":0.5,"
             "\"events\":\"%s\"},\"output\":{\"every\":%ld}}",
             a->m, b->m, a->k, a->phi0, a->phi1, a->V, b->k, b->phi0, b->phi1, b->V, a->V, b->V, dt, events,
             lround(0.5 / dt));
    if (strcmp(events, "locate") == 0)
        rows_assert_events_mode(json, "locate");
    rows_run(json, r);
}

/* The largest error of the two positions against the closed form over the samples. */
static double belt_error(double dt, const char *events)
{
    rows r;
    belt_run(dt, events, &r);
    double worst = 0;
    assert_int_equal(r.n, 25);
    for (size_t i = 0; i < r.n; i++) {
        const double *o = r.d + i * r.width;
        for (int j = 0; j < 2; j++) {
            int ph;
            worst = fmax(worst, fabs(o[1 + j] - belt_x(&belt_blocks[j], o[0], &ph)));
        }
    }
    free(r.d);
    return worst;
}

static void assert_ratios(const double *e, size_t n, double lo, double hi)
{
    for (size_t i = 0; i + 1 < n; i++) {
        fprintf(stderr, "  error %.3e, ratio %.3f\n", e[i], e[i] / e[i + 1]);
        assert_true(e[i] / e[i + 1] >= lo && e[i] / e[i + 1] <= hi);
    }
}

/* theta = 1/2 through breakaways at phi1 and sticks at the belt speed: second order against the closed
 * form, where events "none" is not. */
static void test_static_threshold_belt_is_second_order(void **state)
{
    (void)state;
    double e[4], f[4];
    for (int i = 0; i < 4; i++) {
        e[i] = belt_error(0.02 / (1 << i), "locate");
        f[i] = belt_error(0.02 / (1 << i), "none");
    }
    assert_ratios(e, 4, 3.5, 4.5);
    assert_true(e[3] < 1e-5);
    fprintf(stderr, " events none:\n");
    for (int i = 0; i + 1 < 4; i++)
        fprintf(stderr, "  error %.3e, ratio %.3f\n", f[i], f[i] / f[i + 1]);
    assert_true(f[0] / f[3] < 0.5 * e[0] / e[3]);   /* three halvings: far less than 64 */
}

/* The events: the closed form's instants (a stick, then a breakaway, in turn) to second order. */
static void test_static_threshold_belt_events(void **state)
{
    (void)state;
    double worst[2] = { 0, 0 };
    for (int h = 0; h < 2; h++) {
        rows r;
        belt_run(0.01 / (1 << h), "locate", &r);
        for (int j = 0; j < 2; j++) {
            const belt_block *b = &belt_blocks[j];
            double t = b->phi1 / (b->k * b->V);   /* the first breakaway */
            size_t seen = 0;
            for (size_t i = 0; i < r.events; i++) {
                if (r.ev[i].element != (size_t)j)
                    continue;
                int kind = seen % 2 == 0 ? DP_EVENT_SLIP : DP_EVENT_STICK;
                assert_int_equal(r.ev[i].kind, kind);
                worst[h] = fmax(worst[h], fabs(r.ev[i].t - t));
                t += kind == DP_EVENT_SLIP ? belt_slip_time(b) : belt_stick_time(b);
                seen++;
            }
            assert_true(seen >= 3);   /* slip, stick, slip at least by t = 12 */
        }
        free(r.d);
    }
    fprintf(stderr, "  event error %.3e, %.3e\n", worst[0], worst[1]);
    assert_true(worst[0] < 1e-4 && worst[1] < 0.4 * worst[0]);
}

/* A block held by its stick interval while a neighbour swings it rests exactly (no creep): x, v and the
 * phase never move, and no event is written for it. With a static threshold the forces go past phi0 (a
 * kinetic threshold alone would let it slip); with relaxation gamma(0) = 0 leaves the interval whole. */
static void assert_no_creep(const char *damper, double lo)
{
    char json[768];
    snprintf(json, sizeof json, "{\"model\":{\"masses\":[1,1],\"elements\":["
             "{\"between\":[\"ground\",0],\"damper\":%s},"
             "{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":1}}]},"
             "\"initial\":{\"x\":[0.1,0.45],\"v\":[0,0]},\"solver\":{\"dt\":0.01,\"t_end\":20,\"theta\":0.5},"
             "\"output\":{\"every\":1}}", damper);
    rows_assert_events_mode(json, "locate");
    rows r;
    rows_run(json, &r);
    double most = 0;
    for (size_t i = 0; i < r.n; i++) {
        const double *o = r.d + i * r.width;   /* t, x0 x1, v0 v1, Fs0 Fs1, Fd0 Fd1, phase0 phase1 */
        assert_true(o[1] == 0.1 && o[3] == 0);
        assert_int_equal((int)o[9], DP_PHASE_STICK);
        most = fmax(most, fabs(o[7]));
    }
    assert_true(most > lo && most < 0.36);   /* the spring's force reaches 0.35 */
    for (size_t i = 0; i < r.events; i++)
        assert_true(r.ev[i].element != 0);
    free(r.d);
}

static void test_stuck_blocks_do_not_creep(void **state)
{
    (void)state;
    assert_no_creep("{\"law\":\"generalized-coulomb\",\"phi0\":0.2,\"phi1\":0.5}", 0.3);
    assert_no_creep("{\"law\":\"coulomb\",\"phi0\":0.4,\"relaxation\":{\"kind\":\"rational\",\"a\":0.3,\"b\":0.5}}", 0.3);
}

/* The one-mass solver locates its events on its own (stick_slip.c): a network of two unconnected copies of a
 * one-mass document (the general network step) follows it, events and all, to the root finders' tolerance. */
static void assert_network_follows_one_mass(const char *spring, const char *damper, const char *theta, size_t *events)
{
    char one[1024], net[1024];
    for (int f = 0; f < 2; f++) {
        const char *load = f ? ",\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":0.9,\"omega\":1.3}" : "";
        const char *nload = f ? ",\"forcing\":[{\"node\":0,\"kind\":\"harmonic\",\"amplitude\":0.9,\"omega\":1.3},"
                                "{\"node\":1,\"kind\":\"harmonic\",\"amplitude\":0.9,\"omega\":1.3}]" : "";
        snprintf(one, sizeof one, "{\"model\":{\"mass\":1.3,\"spring\":%s,\"damper\":%s%s},"
                 "\"initial\":{\"x\":1.5,\"v\":0.2},\"solver\":{\"dt\":0.01,\"t_end\":20,\"theta\":%s},"
                 "\"output\":{\"every\":10}}", spring, damper, load, theta);
        snprintf(net, sizeof net, "{\"model\":{\"masses\":[1.3,1.3],\"elements\":[{\"between\":[\"ground\",0],"
                 "\"spring\":%s,\"damper\":%s},{\"between\":[\"ground\",1],"
                 "\"spring\":%s,\"damper\":%s}]%s},\"initial\":{\"x\":[1.5,1.5],"
                 "\"v\":[0.2,0.2]},\"solver\":{\"dt\":0.01,\"t_end\":20,\"theta\":%s},\"output\":{\"every\":10}}",
                 spring, damper, spring, damper, nload, theta);
        rows_assert_events_mode(net, "locate");
        traj a;
        rows b;
        assert_int_equal(traj_run(one, &a), DP_OK);
        rows_run(net, &b);
        assert_int_equal(a.n, b.n);
        double worst = 0;
        for (size_t i = 0; i < a.n; i++) {
            const double *r = b.d + i * b.width;
            worst = fmax(worst, fmax(fabs(a.s[i].x - r[1]), fabs(a.s[i].v - r[3])));
            assert_true(r[1] == r[2] && r[3] == r[4]);
        }
        if (worst > 1e-10)
            fprintf(stderr, "%s theta %s load %d: off by %.3e\n", damper, theta, f, worst);
        assert_true(worst < 1e-10);
        for (size_t i = 0, j = 0; i < a.ne; i++, j++) {
            while (j < b.events && (b.ev[j].element != 0 || fabs(b.ev[j].t - a.e[i].t) > 1e-6))
                j++;
            assert_true(j < b.events);
            assert_true(fabs(b.ev[j].t - a.e[i].t) < 1e-10 && b.ev[j].kind == a.e[i].kind);
            (*events)++;
        }
        traj_free(&a);
        free(b.d);
    }
}

static void test_static_threshold_follows_one_mass(void **state)
{
    (void)state;
    static const char *const located[] = {
        "{\"law\":\"generalized-coulomb\",\"phi0\":0.2,\"phi1\":0.5}",
        "{\"law\":\"generalized-coulomb\",\"phi0\":0.2,\"phi1\":0.9,\"belt_velocity\":0.3}",
    };
    size_t events = 0;
    for (size_t d = 0; d < 2; d++)
        for (int th = 0; th < 2; th++)
            assert_network_follows_one_mass(LINEAR, located[d], th ? "1" : "0.5", &events);
    assert_true(events >= 10);
}

/* ---- a chain against itself at dt/64 ------------------------------------------------------------- */

/* Two blocks on a belt-driven chain (dampers d0 on [ground, 0], d1 on [ground, 1], a spring between them,
 * a harmonic load on node 1) to t = 10, sampled every 0.5. */
static void chain_run(const char *d0, const char *d1, double dt, const char *events, rows *r)
{
    char json[1536];
    snprintf(json, sizeof json, "{\"model\":{\"masses\":[1,1.5],\"elements\":["
             "{\"between\":[\"ground\",0],\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":%s},"
             "{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":2}},"
             "{\"between\":[\"ground\",1],\"damper\":%s}],"
             "\"forcing\":[{\"node\":1,\"kind\":\"harmonic\",\"amplitude\":0.8,\"omega\":0.9}]},"
             "\"initial\":{\"x\":[0.5,-0.2]},\"solver\":{\"dt\":%.17g,\"t_end\":10,\"theta\":0.5,"
             "\"events\":\"%s\"},\"output\":{\"every\":%ld}}", d0, d1, dt, events, lround(0.5 / dt));
    if (strcmp(events, "locate") == 0)
        rows_assert_events_mode(json, "locate");
    rows_run(json, r);
}

/* The largest error of x and v over the samples against `ref`. */
static double chain_error(const char *d0, const char *d1, double dt, const char *events, const rows *ref)
{
    rows r;
    chain_run(d0, d1, dt, events, &r);
    double worst = rows_max_difference(&r, ref, 1, 5);
    free(r.d);
    return worst;
}

/* theta = 1/2 through the chain's events: errors against dt/64 fall by 3.5..4.5 per halving of dt from
 * 0.02 to 0.0025 with events located; events "none" falls by less over the same three halvings. */
static void assert_chain_second_order(const char *d0, const char *d1, size_t min_events)
{
    rows ref;
    chain_run(d0, d1, 0.0025 / 64, "locate", &ref);
    assert_true(ref.events >= min_events);
    double e[4], f[4];
    for (int i = 0; i < 4; i++) {
        e[i] = chain_error(d0, d1, 0.02 / (1 << i), "locate", &ref);
        f[i] = chain_error(d0, d1, 0.02 / (1 << i), "none", &ref);
    }
    assert_ratios(e, 4, 3.5, 4.5);
    fprintf(stderr, " events none:\n");
    for (int i = 0; i + 1 < 4; i++)
        fprintf(stderr, "  error %.3e, ratio %.3f\n", f[i], f[i] / f[i + 1]);
    assert_true(f[0] / f[3] < 0.5 * e[0] / e[3]);
    free(ref.d);
}

static void test_relaxation_chain_is_second_order(void **state)
{
    (void)state;
    assert_chain_second_order(
        "{\"law\":\"coulomb\",\"phi0\":0.4,\"belt_velocity\":0.3,\"relaxation\":{\"kind\":\"rational\",\"a\":0.2,\"b\":0.5}}",
        "{\"law\":\"bingham\",\"tau\":0.5,\"c\":0.1,\"relaxation\":{\"kind\":\"linear\",\"L\":0.2}}", 4);
}

static void test_static_threshold_chain_is_second_order(void **state)
{
    (void)state;
    assert_chain_second_order(
        "{\"law\":\"generalized-coulomb\",\"phi0\":0.3,\"phi1\":0.6,\"belt_velocity\":0.3}",
        "{\"law\":\"generalized-coulomb\",\"phi0\":0.3,\"phi1\":0.5,\"relaxation\":{\"kind\":\"rational\",\"a\":0.1,\"b\":0.5}}", 4);
}

/* Relaxation (thesis (3.2)): the held step iterates on gamma as the whole step does; the one-mass solver's
 * located events are followed, events and all. */
static void test_relaxation_follows_one_mass(void **state)
{
    (void)state;
    static const char *const located[] = {
        "{\"law\":\"coulomb\",\"phi0\":0.5,\"relaxation\":{\"kind\":\"rational\",\"a\":0.5,\"b\":1}}",
        "{\"law\":\"bingham\",\"tau\":0.4,\"c\":0.3,\"belt_velocity\":0.2,\"relaxation\":{\"kind\":\"linear\",\"L\":0.3}}",
        "{\"law\":\"generalized-coulomb\",\"phi0\":0.3,\"phi1\":0.6,\"relaxation\":{\"kind\":\"rational\",\"a\":0.2,\"b\":1}}",
    };
    size_t events = 0;
    for (size_t d = 0; d < 3; d++)
        for (int th = 0; th < 2; th++)
            assert_network_follows_one_mass(LINEAR, located[d], th ? "1" : "0.5", &events);
    assert_true(events >= 15);
}

/* ---- elastoplastic (Jenkins) springs: yield and unload located ---------------------------------------- */

/* Runs a network document with elastoplastic springs: rows t, x, v, Fs, Fd, phase, then p of each of the
 * `nep` elastoplastic elements. */
static void rows_run_ep(const char *json, size_t nep, rows *r)
{
    rows_collect(json, 128, r);
    assert_int_equal(r->status, DP_DONE);
    assert_int_equal(r->width - 1, 2 * r->nx + 3 * r->ne + nep);
}

/* One mass on a Jenkins spring beside a damper under a harmonic load, as a one-node network (networks with
 * an elastoplastic spring step on the network solver, not the one-mass one): the one-mass solver's located
 * answer (event_location.c) is followed, samples, offsets and events, to the root finders' tolerance;
 * from an elongation past yield both write a yield at t = 0. */
static void assert_jenkins_follows_one_mass(const char *damper, const char *theta, double x0, size_t *kinds)
{
    char one[1024], net[1024];
    snprintf(one, sizeof one, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1},"
             "\"damper\":%s,\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":1.6,\"omega\":0.3}},"
             "\"initial\":{\"x\":%g,\"v\":0},\"solver\":{\"dt\":0.01,\"t_end\":30,\"theta\":%s},"
             "\"output\":{\"every\":10}}", damper, x0, theta);
    snprintf(net, sizeof net, "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],"
             "\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":1},\"damper\":%s}],\"forcing\":[{\"node\":0,"
             "\"kind\":\"harmonic\",\"amplitude\":1.6,\"omega\":0.3}]},\"initial\":{\"x\":[%g],\"v\":[0]},"
             "\"solver\":{\"dt\":0.01,\"t_end\":30,\"theta\":%s},\"output\":{\"every\":10}}", damper, x0, theta);
    rows_assert_events_mode(one, "locate");
    rows_assert_events_mode(net, "locate");
    traj a;
    rows b;
    assert_int_equal(traj_run(one, &a), DP_OK);
    rows_run_ep(net, 1, &b);
    assert_int_equal(a.n, b.n);
    double worst = 0;
    for (size_t i = 0; i < a.n; i++) {   /* t, x, v, Fs, Fd, phase, p */
        const double *r = b.d + i * b.width;
        worst = fmax(worst, fmax(fmax(fabs(a.s[i].x - r[1]), fabs(a.s[i].v - r[2])), fabs(a.s[i].p - r[6])));
    }
    if (worst > 1e-10)
        fprintf(stderr, "%s theta %s x0 %g: off by %.3e\n", damper, theta, x0, worst);
    assert_true(worst < 1e-10);
    assert_int_equal(a.ne, b.events);
    for (size_t i = 0; i < a.ne; i++) {
        assert_int_equal(b.ev[i].kind, a.e[i].kind);
        assert_true(fabs(b.ev[i].t - a.e[i].t) < 1e-10);
        kinds[a.e[i].kind]++;
    }
    traj_free(&a);
    free(b.d);
}

static void test_jenkins_follows_one_mass(void **state)
{
    (void)state;
    static const char *const dampers[] = {
        "{\"law\":\"none\"}", "{\"law\":\"linear\",\"c\":0.2}", "{\"law\":\"coulomb\",\"phi0\":0.5}",
    };
    size_t kinds[DP_EVENT_UNLOAD + 1] = { 0 };
    for (size_t d = 0; d < 3; d++)
        for (int th = 0; th < 2; th++)
            for (int past = 0; past < 2; past++)   /* from rest, or from past yield: a yield at t = 0 */
                assert_jenkins_follows_one_mass(dampers[d], th ? "1" : "0.5", past ? 1.5 : 0, kinds);
    /* the Coulomb damper sticks and slips between the slider's yields and unloads (and with it at once) */
    for (int k = DP_EVENT_STICK; k <= DP_EVENT_UNLOAD; k++) {
        fprintf(stderr, "  events of kind %d: %zu\n", k, kinds[k]);
        assert_true(kinds[k] >= 4);
    }
}

/* A three-block chain with two Jenkins elements (one between blocks 0 and 1, one holding block 2 to the
 * ground), a Coulomb damper on block 0 and a harmonic load on block 2, to t = 10 sampled every 0.5. */
static void jenkins_chain_run(double dt, const char *events, rows *r)
{
    char json[1536];
    snprintf(json, sizeof json, "{\"model\":{\"masses\":[1,1.5,0.8],\"elements\":["
             "{\"between\":[\"ground\",0],\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"coulomb\","
             "\"phi0\":0.3}},"
             "{\"between\":[0,1],\"spring\":{\"law\":\"elastoplastic\",\"k\":2,\"yield\":0.4}},"
             "{\"between\":[1,2],\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"linear\",\"c\":0.1}},"
             "{\"between\":[\"ground\",2],\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":0.3}}],"
             "\"forcing\":[{\"node\":2,\"kind\":\"harmonic\",\"amplitude\":1.2,\"omega\":0.9}]},"
             "\"initial\":{\"x\":[0.2,0,-0.1]},\"solver\":{\"dt\":%.17g,\"t_end\":10,\"theta\":0.5,"
             "\"events\":\"%s\"},\"output\":{\"every\":%ld}}", dt, events, lround(0.5 / dt));
    rows_assert_events_mode(json, events);
    rows_run_ep(json, 2, r);
}

/* The largest error of x, v and the offsets p over the samples against `ref`. */
static double jenkins_chain_error(double dt, const char *events, const rows *ref)
{
    rows r;
    jenkins_chain_run(dt, events, &r);
    assert_int_equal(r.n, ref->n);
    double worst = 0;
    for (size_t i = 0; i < r.n; i++) {
        const double *o = r.d + i * r.width, *q = ref->d + i * ref->width;
        for (size_t j = 1; j <= 6; j++)                 /* x, v */
            worst = fmax(worst, fabs(o[j] - q[j]));
        for (size_t j = r.width - 2; j < r.width; j++)  /* p */
            worst = fmax(worst, fabs(o[j] - q[j]));
    }
    free(r.d);
    return worst;
}

/* theta = 1/2 through yields and unloads of two sliders and a damper's stick and slip: errors against
 * dt/64 fall by 3.5..4.5 per halving of dt from 0.02 to 0.0025; events "none" falls by less. */
static void test_jenkins_chain_is_second_order(void **state)
{
    (void)state;
    rows ref;
    jenkins_chain_run(0.0025 / 64, "locate", &ref);
    size_t yields = 0, unloads = 0;
    for (size_t i = 0; i < ref.events; i++) {
        yields += ref.ev[i].kind == DP_EVENT_YIELD;
        unloads += ref.ev[i].kind == DP_EVENT_UNLOAD;
    }
    fprintf(stderr, "  reference: %zu events, %zu yields, %zu unloads\n", ref.events, yields, unloads);
    assert_true(yields >= 4 && unloads >= 4);
    double e[4], f[4];
    for (int i = 0; i < 4; i++) {
        e[i] = jenkins_chain_error(0.02 / (1 << i), "locate", &ref);
        f[i] = jenkins_chain_error(0.02 / (1 << i), "none", &ref);
    }
    assert_ratios(e, 4, 3.5, 4.5);
    /* unlocated, a kink inside a step costs an error of its own whose size depends on where it falls:
     * the ratios wander (measured 4.2, 3.6, 4.8) where the located ones stay within 0.1 of 4 */
    double dev_located = 0, dev_none = 0;
    fprintf(stderr, " events none:\n");
    for (int i = 0; i + 1 < 4; i++) {
        fprintf(stderr, "  error %.3e, ratio %.3f\n", f[i], f[i] / f[i + 1]);
        dev_located = fmax(dev_located, fabs(e[i] / e[i + 1] - 4));
        dev_none = fmax(dev_none, fabs(f[i] / f[i + 1] - 4));
    }
    assert_true(dev_located < 0.1 && dev_none > 0.5);
    free(ref.d);
}

/* No creep: a block held by its Coulomb damper beside a swinging neighbour, its Jenkins spring to the ground
 * loaded inside its yield force, rests exactly (x, v, p never move, no event of its own); a block resting on
 * the yield surface under a constant load equal to the yield force rests exactly too, without a yield. */
static void test_jenkins_does_not_creep(void **state)
{
    (void)state;
    const char *held = "{\"model\":{\"masses\":[1,1],\"elements\":["
        "{\"between\":[\"ground\",0],\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":0.3},"
        "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.5}},{\"between\":[0,1],\"spring\":{\"law\":\"linear\",\"k\":1}}]},"
        "\"initial\":{\"x\":[0.1,0.45],\"v\":[0,0]},\"solver\":{\"dt\":0.01,\"t_end\":20,\"theta\":0.5},"
        "\"output\":{\"every\":1}}";
    rows_assert_events_mode(held, "locate");
    rows r;
    rows_run_ep(held, 1, &r);
    double most = 0;
    for (size_t i = 0; i < r.n; i++) {
        const double *o = r.d + i * r.width;   /* t, x0 x1, v0 v1, Fs0 Fs1, Fd0 Fd1, phase0 phase1, p0 */
        assert_true(o[1] == 0.1 && o[3] == 0 && o[11] == 0);
        assert_true(o[5] == 0.1);                  /* elastic: k x */
        assert_int_equal((int)o[9], DP_PHASE_STICK);
        most = fmax(most, fabs(o[7]));
    }
    assert_true(most > 0.3 && most < 0.5);      /* the damper holds past the spring's yield force */
    for (size_t i = 0; i < r.events; i++)
        assert_true(r.ev[i].element != 0);
    free(r.d);
    const char *yielded = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],"
        "\"spring\":{\"law\":\"elastoplastic\",\"k\":2,\"yield\":0.5}}],\"forcing\":[{\"node\":0,\"kind\":\"constant\","
        "\"value\":0.5}]},\"initial\":{\"x\":[0.25],\"v\":[0]},\"solver\":{\"dt\":0.01,\"t_end\":20,\"theta\":0.5},"
        "\"output\":{\"every\":7}}";
    rows_assert_events_mode(yielded, "locate");
    rows_run_ep(yielded, 1, &r);
    for (size_t i = 0; i < r.n; i++) {
        const double *o = r.d + i * r.width;   /* t, x, v, Fs, Fd, phase, p */
        assert_true(o[1] == 0.25 && o[2] == 0 && o[3] == 0.5 && o[6] == 0);
    }
    assert_int_equal(r.events, 0);
    free(r.d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_static_threshold_belt_is_second_order),
        cmocka_unit_test(test_static_threshold_belt_events),
        cmocka_unit_test(test_static_threshold_follows_one_mass),
        cmocka_unit_test(test_stuck_blocks_do_not_creep),
        cmocka_unit_test(test_relaxation_follows_one_mass),
        cmocka_unit_test(test_relaxation_chain_is_second_order),
        cmocka_unit_test(test_static_threshold_chain_is_second_order),
        cmocka_unit_test(test_jenkins_follows_one_mass),
        cmocka_unit_test(test_jenkins_chain_is_second_order),
        cmocka_unit_test(test_jenkins_does_not_creep),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
