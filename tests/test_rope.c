/* tests/test_rope.c - ropes in networks with located events (docs/networks.md, docs/contact.md): a rope
 * (Babováková 2012, Fig. 1) is a linear spring k plus the rigid constraint u <= L with restitution 0, so its
 * going taut is a located plastic impact and a taut rope takes its share of another contact's impulse.
 * Against closed forms: a mass thrown out on a rope (the taut instant, the jump, the linear motion after;
 * second order at theta = 1/2 where the backward-Euler graph of events "none" is first order), a mass let go
 * by its load and caught again (second order against a fine reference), two free
 * masses jerked together by their rope, a pair joined by a taut rope whose front mass hits a ledge (the
 * impulse through the rope, momentum and energy of the rigid pair's impact, its accumulating bounces), a
 * tethered block carried by a belt; no creep of hanging masses; and the rules that go with it. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "dashpot/json.h"
#include "dashpot/run.h"
#include "rows.h"

#define G 9.81

/* Runs the document to its end (rows.h); it must finish. */
static void run_doc(const char *json, rows *o)
{
    assert_int_equal(rows_collect(json, 64, o), DP_DONE);
}

/* Row i's t, x and v of node j, Fs of element j, Fn of element j (with contacts: after x, v, Fs, Fd, phase). */
static double T(const rows *o, size_t i) { return o->d[i * o->width]; }
static double X(const rows *o, size_t i, size_t j) { return o->d[i * o->width + 1 + j]; }
static double V(const rows *o, size_t i, size_t j) { return o->d[i * o->width + 1 + o->nx + j]; }
static double FS(const rows *o, size_t i, size_t j) { return o->d[i * o->width + 1 + 2 * o->nx + j]; }
static double FD(const rows *o, size_t i, size_t j) { return o->d[i * o->width + 1 + 2 * o->nx + o->ne + j]; }
static double FN(const rows *o, size_t i, size_t j) { return o->d[i * o->width + 1 + 2 * o->nx + 3 * o->ne + j]; }

/* The impact events of element el, in order, into ev (at most cap); how many. */
static size_t impacts_of(const rows *o, size_t el, dp_event *ev, size_t cap)
{
    size_t n = 0;
    for (size_t i = 0; i < o->events; i++)
        if (o->ev[i].kind == DP_EVENT_IMPACT && o->ev[i].element == el && n < cap)
            ev[n++] = o->ev[i];
    return n;
}


/* ---- a mass thrown out on a rope ---------------------------------------------------------------------- */

/* Mass m on a rope [ground, 0] (k, L) thrown from x = 0 at speed V > L w, w = sqrt(k/m): slack, x = (V/w)
 * sin(w t) until it reaches L at t* = asin(L w / V) / w with speed V cos(w t*); the plastic jerk stops it
 * (impulse m V cos(w t*)); then the spring pulls it back, x = L cos(w (t - t*)), on the linear part until it
 * comes back to L at t* + 2 pi / w (after t_end). */
typedef struct thrown {
    double m, k, L, V, t_end;
} thrown;

static double thrown_taut(const thrown *p)
{
    double w = sqrt(p->k / p->m);
    return asin(p->L * w / p->V) / w;
}

static void thrown_exact(const thrown *p, double t, double *x, double *v)
{
    double w = sqrt(p->k / p->m), ts = thrown_taut(p);
    if (t < ts)
        *x = p->V / w * sin(w * t), *v = p->V * cos(w * t);
    else
        *x = p->L * cos(w * (t - ts)), *v = -p->L * w * sin(w * (t - ts));
}

static void thrown_doc(char *buf, size_t cap, const thrown *p, double dt, double theta, const char *events)
{
    snprintf(buf, cap, "{\"model\":{\"masses\":[%.17g],\"elements\":[{\"between\":[\"ground\",0],\"spring\":"
             "{\"law\":\"rope\",\"k\":%.17g,\"length\":%.17g}}]},\"initial\":{\"x\":[0],\"v\":[%.17g]},"
             "\"solver\":{\"kind\":\"stick-slip\",\"dt\":%.17g,\"t_end\":%.17g,\"theta\":%g,\"events\":\"%s\"},"
             "\"output\":{\"every\":1}}", p->m, p->k, p->L, p->V, dt, p->t_end, theta, events);
}

/* The error at t_end (x and v / w against the closed form); with events located also the taut event's
 * instant and impulse, the jump to rest, and no row past the rope's length. */
static double thrown_error(const thrown *p, double dt, double theta, const char *events, double *t_err)
{
    static char doc[1024];
    rows o;
    thrown_doc(doc, sizeof doc, p, dt, theta, events);
    run_doc(doc, &o);
    double w = sqrt(p->k / p->m), x, v, ts = thrown_taut(p);
    size_t last = o.n - 1;
    assert_true(T(&o, last) == p->t_end);
    thrown_exact(p, p->t_end, &x, &v);
    double err = fabs(X(&o, last, 0) - x) + fabs(V(&o, last, 0) - v) / w;
    if (strcmp(events, "locate") == 0) {
        dp_event ev[4];
        assert_int_equal(impacts_of(&o, 0, ev, 4), 1);
        double vs = p->V * cos(w * ts);
        *t_err = fabs(ev[0].t - ts);
        assert_true(fabs(ev[0].x - p->L) <= 1e-12 * p->L);        /* the elongation there: the rope's length */
        assert_true(fabs(ev[0].v - vs) <= 1e-3 * vs);             /* lengthening at about V cos(w t*) */
        assert_true(ev[0].v_after == 0);                           /* stopped: restitution 0 */
        assert_true(fabs(ev[0].impulse - p->m * ev[0].v) <= 1e-12 * p->m * vs);   /* m times the jump */
        for (size_t i = 0; i < o.n; i++)
            assert_true(X(&o, i, 0) <= p->L * (1 + 1e-14));       /* never past the rope's length */
    }
    free(o.d);
    return err;
}

static void test_thrown_rope_second_order(void **state)
{
    (void)state;
    const thrown p = { .m = 2, .k = 0.5, .L = 1, .V = 1.5, .t_end = 6 };
    double e[4], te[4], r[3];   /* located: error, taut instant's error, ratios */
    for (int j = 0; j < 4; j++)
        e[j] = thrown_error(&p, 0.02 / (1 << j), 0.5, "locate", &te[j]);
    for (int j = 0; j < 3; j++) {
        r[j] = e[j] / e[j + 1];
        printf("theta 1/2 located: dt %g error %.3e, ratio %.3f; taut instant off by %.1e\n", 0.02 / (1 << j), e[j],
               r[j], te[j]);
        assert_true(r[j] > 3.6 && r[j] < 4.4);
    }
    assert_true(e[0] < 1e-4 && te[3] < 1e-6);
    /* the rope's graph by backward Euler (events "none", theta = 1; what a located document ran before):
     * first order, its ratios wandering with where t* falls in its step (1.7 to 3.3), 2.1 on average over
     * five halvings, a thousand times the located error at dt = 0.02 */
    double first = 0, en = 0;
    for (int j = 0; j < 6; j++) {
        double dt = 0.02 / (1 << j);
        en = thrown_error(&p, dt, 1, "none", NULL);
        first = j ? first : en;
        printf("theta 1 events none: dt %g error %.3e, error/dt %.3f\n", dt, en, en / dt);
        assert_true(en / dt > 0.5 && en / dt < 2.5);
    }
    double mean = pow(first / en, 1.0 / 5);
    assert_true(mean > 1.7 && mean < 2.5 && first > 500 * e[0]);
}

/* A mass held taut at x = L by the load 2 cos t > k L (k = m = L = 1) is let go where the load falls to k L
 * (t = pi/3: the multiplier reaching zero, located as a release), swings slack and is caught again at
 * t = 3 pi/2 (a plastic jerk); at theta = 1/2 the state at t = 8 falls by 4.0 per halving of dt against the
 * same run at dt/64. */
static void slack_final(double dt, double *x, double *v, rows *o)
{
    static char doc[1024];
    snprintf(doc, sizeof doc, "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":"
             "{\"law\":\"rope\",\"k\":1,\"length\":1}}],\"forcing\":[{\"node\":0,\"kind\":\"harmonic\","
             "\"amplitude\":2,\"omega\":1,\"phase\":%.17g}]},\"initial\":{\"x\":[1],\"v\":[0]},\"solver\":"
             "{\"kind\":\"stick-slip\",\"dt\":%.17g,\"t_end\":8,\"theta\":0.5},\"output\":{\"every\":100000}}",
             M_PI / 2, dt);
    run_doc(doc, o);
    *x = X(o, o->n - 1, 0), *v = V(o, o->n - 1, 0);
}

static void test_slack_and_taut_again(void **state)
{
    (void)state;
    double xr, vr, x, v, e[4];
    rows o;
    slack_final(0.04 / 64, &xr, &vr, &o);
    assert_int_equal(o.events, 1);                       /* caught again; going slack writes nothing */
    assert_int_equal(o.ev[0].kind, DP_EVENT_IMPACT);
    assert_true(fabs(o.ev[0].t - 3 * M_PI / 2) <= 1e-6);
    free(o.d);
    for (int j = 0; j < 4; j++) {
        slack_final(0.04 / (1 << j), &x, &v, &o);
        free(o.d);
        e[j] = fabs(x - xr) + fabs(v - vr);
    }
    for (int j = 0; j < 3; j++) {
        printf("let go and caught again: dt %g error %.3e, ratio %.3f\n", 0.04 / (1 << j), e[j], e[j] / e[j + 1]);
        assert_true(e[j] / e[j + 1] > 3.6 && e[j] / e[j + 1] < 4.4);
    }
}

/* ---- two free masses jerked together ------------------------------------------------------------------ */

/* Masses m0, m1 on a rope [0, 1] (k = 0, L), both at x = 0, v0 < v1: u' = v1 - v0 until u = L at
 * t* = L / (v1 - v0); the plastic jerk leaves both at the centre of mass's speed (m0 v0 + m1 v1) / (m0 + m1),
 * its impulse the reduced mass times u', the kinetic energy lost 1/2 mu u'^2; then they fly on together with
 * the rope taut at zero tension, momentum kept to rounding. */
static void test_free_pair_jerked(void **state)
{
    (void)state;
    const double m0 = 1, m1 = 3, v0 = -1, v1 = 2, L = 1, du = v1 - v0, vc = (m0 * v0 + m1 * v1) / (m0 + m1);
    const double mu = m0 * m1 / (m0 + m1), ts = L / du;
    static char doc[1024];
    snprintf(doc, sizeof doc, "{\"model\":{\"masses\":[%g,%g],\"elements\":[{\"between\":[0,1],\"spring\":{\"law\":"
             "\"rope\",\"k\":0,\"length\":%g}}]},\"initial\":{\"x\":[0,0],\"v\":[%g,%g]},\"solver\":{\"kind\":"
             "\"stick-slip\",\"dt\":0.01,\"t_end\":2,\"theta\":0.5},\"output\":{\"every\":1}}", m0, m1, L, v0, v1);
    rows o;
    run_doc(doc, &o);
    dp_event ev[4];
    assert_int_equal(impacts_of(&o, 0, ev, 4), 1);
    assert_true(fabs(ev[0].t - ts) <= 1e-12);          /* free flight: theta = 1/2 is exact */
    assert_true(fabs(ev[0].v - du) <= 1e-12 && ev[0].v_after == 0);
    assert_true(fabs(ev[0].impulse - mu * du) <= 1e-12);
    for (size_t i = 0; i < o.n; i++) {
        double p = m0 * V(&o, i, 0) + m1 * V(&o, i, 1);
        assert_true(fabs(p - (m0 * v0 + m1 * v1)) <= 1e-12);    /* no outside force: momentum kept */
        if (T(&o, i) <= ts)
            continue;
        assert_true(fabs(V(&o, i, 0) - vc) <= 1e-12 && fabs(V(&o, i, 1) - vc) <= 1e-12);
        assert_true(fabs(X(&o, i, 1) - X(&o, i, 0) - L) <= 1e-12);   /* taut, not stretched */
        assert_true(fabs(FS(&o, i, 0)) <= 1e-12);                      /* at zero tension */
        double ke = 0.5 * (m0 * V(&o, i, 0) * V(&o, i, 0) + m1 * V(&o, i, 1) * V(&o, i, 1));
        assert_true(fabs(ke - (0.5 * (m0 * v0 * v0 + m1 * v1 * v1) - 0.5 * mu * du * du)) <= 1e-12);
    }
    free(o.d);
}

/* ---- an impulse through a taut rope --------------------------------------------------------------------- */

/* Node 0 at height 1 with node 1 hanging from it on a taut rope [1, 0] (L = 1, k = 0), both falling at V; a
 * ledge ["ground", 0] at 0.5 catches node 0 alone (node 1 passes it). At the impact (t = 0.5 - (1 - x0))
 * Newton's law on the ledge (restitution e) and the plastic rope make the pair one rigid body: both leave at
 * e V, the ledge's impulse (m0 + m1)(1 + e) V, the rope's m1 (1 + e) V, the kinetic energy times e^2. Before
 * ropes were contacts the rope took no impulse in the impact problem (and a rope network was not located). */
static void pair_doc(char *buf, size_t cap, double e, double g, double dt, double t_end, double theta)
{
    snprintf(buf, cap, "{\"model\":{\"masses\":[1,2],\"elements\":[{\"between\":[1,0],\"spring\":{\"law\":"
             "\"rope\",\"k\":0,\"length\":1}},{\"between\":[\"ground\",0],\"contact\":{\"distance\":0.5,"
             "\"restitution\":%.17g}}],\"forcing\":[{\"node\":0,\"kind\":\"constant\",\"value\":%.17g},{\"node\":1,"
             "\"kind\":\"constant\",\"value\":%.17g}]},\"initial\":{\"x\":[1,0],\"v\":[-1,-1]},\"solver\":{\"kind\":"
             "\"stick-slip\",\"dt\":%g,\"t_end\":%g,\"theta\":%g},\"output\":{\"every\":1}}",
             e, -g, -2 * g, dt, t_end, theta);
}

static void pair_impact(double e, double theta)
{
    static char doc[1024];
    const double m0 = 1, m1 = 2, speed = 1;
    pair_doc(doc, sizeof doc, e, 0, 0.01, 0.8, theta);
    rows o;
    run_doc(doc, &o);
    dp_event rope[4], ledge[4];
    assert_int_equal(impacts_of(&o, 1, ledge, 4), 1);
    assert_int_equal(impacts_of(&o, 0, rope, 4), 1);          /* the rope took its share */
    char mode[DP_POINTER_MAX];
    rows_verdict(doc, mode, sizeof mode);
    assert_string_equal(mode, "locate");
    assert_true(fabs(ledge[0].t - 0.5) <= 1e-12 && rope[0].t == ledge[0].t);
    assert_true(fabs(ledge[0].impulse - (m0 + m1) * (1 + e) * speed) <= 1e-12);
    assert_true(fabs(rope[0].impulse - m1 * (1 + e) * speed) <= 1e-12);
    assert_true(fabs(rope[0].x - 1) <= 1e-12 && rope[0].v == 0 && rope[0].v_after == 0);   /* taut, held */
    for (size_t i = 0; i < o.n; i++) {
        if (T(&o, i) <= 0.5)
            continue;
        assert_true(fabs(V(&o, i, 0) - e * speed) <= 1e-12 && fabs(V(&o, i, 1) - e * speed) <= 1e-12);
        double p = m0 * V(&o, i, 0) + m1 * V(&o, i, 1), ke = 0.5 * (m0 + m1) * e * e * speed * speed;
        assert_true(fabs(p - (-(m0 + m1) * speed + ledge[0].impulse)) <= 1e-12);   /* the ledge's impulse */
        assert_true(fabs(0.5 * (m0 * V(&o, i, 0) * V(&o, i, 0) + m1 * V(&o, i, 1) * V(&o, i, 1)) - ke) <= 1e-12);
    }
    free(o.d);
}

static void test_impulse_through_rope_e05(void **state) { (void)state; pair_impact(0.5, 1); pair_impact(0.5, 0.5); }
static void test_impulse_through_rope_e1(void **state) { (void)state; pair_impact(1, 1); pair_impact(1, 0.5); }

/* The same pair under gravity bounces on the ledge as one rigid body of mass m0 + m1: impacts at
 * t1 (1 = 0.5 + V t1 + g t1^2 / 2) with speed v1 = V + g t1, accumulating at t_inf = t1 + 2 e v1 / (g (1 - e));
 * at every one the rope takes m1 / (m0 + m1) of the ledge's impulse, and after t_inf the pair rests on the
 * ledge with the rope's tension m1 g and the ledge's force (m0 + m1) g. */
static void test_pair_bounces_to_rest(void **state)
{
    (void)state;
    static char doc[1024];
    const double m0 = 1, m1 = 2, speed = 1, e = 0.5;
    double t1 = (-speed + sqrt(speed * speed + 2 * G * 0.5)) / G, v1 = speed + G * t1;
    double t_inf = t1 + 2 * e * v1 / (G * (1 - e));
    pair_doc(doc, sizeof doc, e, G, 1e-3, 2, 0.5);
    rows o;
    run_doc(doc, &o);
    static dp_event rope[512], ledge[512];
    size_t nr = impacts_of(&o, 0, rope, 512), nl = impacts_of(&o, 1, ledge, 512);
    assert_true(nl > 10 && nr == nl);
    assert_true(fabs(ledge[0].t - t1) <= 1e-12 && fabs(ledge[0].v + v1) <= 1e-12);
    for (size_t k = 0; k < nl; k++) {
        assert_true(rope[k].t == ledge[k].t);
        assert_true(fabs(rope[k].impulse - m1 / (m0 + m1) * ledge[k].impulse) <= 1e-9 * ledge[0].impulse);
    }
    assert_true(fabs(ledge[nl - 1].t - t_inf) <= 1e-9);
    size_t last = o.n - 1;
    assert_true(fabs(X(&o, last, 0) - 0.5) <= 1e-12 && V(&o, last, 0) == 0 && V(&o, last, 1) == 0);
    assert_true(fabs(X(&o, last, 0) - X(&o, last, 1) - 1) <= 1e-12);
    assert_true(fabs(FS(&o, last, 0) - m1 * G) <= 1e-12 * m1 * G);
    assert_true(fabs(FN(&o, last, 1) + (m0 + m1) * G) <= 1e-12 * (m0 + m1) * G);
    assert_true(FN(&o, last, 0) == 0);          /* a rope has no contact force: its tension is Fs */
    free(o.d);
}

/* ---- resting taut ---------------------------------------------------------------------------------------- */

/* A mass held out by a constant load F > k L on a taut rope rests at x = L exactly, its tension F (k L of it
 * the spring's, the rest the constraint's multiplier); a chain of two ropes hanging under gravity rests with
 * the tensions of statics. At theta = 1/2 and 1. */
static void test_hanging_rests(void **state)
{
    (void)state;
    static char doc[1024];
    for (int th = 0; th < 2; th++) {
        snprintf(doc, sizeof doc, "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":"
                 "{\"law\":\"rope\",\"k\":1,\"length\":1}}],\"forcing\":[{\"node\":0,\"kind\":\"constant\","
                 "\"value\":3}]},\"initial\":{\"x\":[1],\"v\":[0]},\"solver\":{\"kind\":\"stick-slip\",\"dt\":0.01,"
                 "\"t_end\":5,\"theta\":%s},\"output\":{\"every\":1}}", th ? "1" : "0.5");
        rows o;
        run_doc(doc, &o);
        assert_int_equal(o.n, 501);
        for (size_t i = 0; i < o.n; i++) {
            assert_true(X(&o, i, 0) == 1 && V(&o, i, 0) == 0);
            assert_true(fabs(FS(&o, i, 0) - 3) <= 1e-15 * 3 * 2);
        }
        assert_int_equal(o.events, 0);
        free(o.d);
        snprintf(doc, sizeof doc, "{\"model\":{\"masses\":[1,2],\"elements\":[{\"between\":[0,\"ground\"],"
                 "\"spring\":{\"law\":\"rope\",\"k\":1,\"length\":1}},{\"between\":[1,0],\"spring\":{\"law\":\"rope\","
                 "\"k\":3,\"length\":2}}],\"forcing\":[{\"node\":0,\"kind\":\"constant\",\"value\":%.17g},{\"node\":1,"
                 "\"kind\":\"constant\",\"value\":%.17g}]},\"initial\":{\"x\":[-1,-3],\"v\":[0,0]},"
                 "\"solver\":{\"kind\":\"stick-slip\",\"dt\":0.01,\"t_end\":5,\"theta\":%s},\"output\":{\"every\":1}}",
                 -G, -2 * G,
                 th ? "1" : "0.5");
        run_doc(doc, &o);
        for (size_t i = 0; i < o.n; i++) {
            assert_true(X(&o, i, 0) == -1 && X(&o, i, 1) == -3 && V(&o, i, 0) == 0 && V(&o, i, 1) == 0);
            assert_true(fabs(FS(&o, i, 0) - 3 * G) <= 1e-14 * 3 * G && fabs(FS(&o, i, 1) - 2 * G) <= 1e-14 * 2 * G);
        }
        free(o.d);
    }
}

/* A block on Coulomb friction against a belt at speed vb, tethered by a rope [ground, 0] (k L < phi0): it
 * sticks to the belt (x = vb t) until the rope goes taut at t = L / vb, where the plastic jerk stops it (a
 * bounded friction force carries no impulse: the block leaves the belt's speed and slips, an event at the
 * same instant); then it rests at x = L held by the tension phi0 against the slipping friction. */
static void test_tethered_block_on_belt(void **state)
{
    (void)state;
    const double vb = 0.5, L = 1, phi0 = 0.5, k = 0.2;
    static char doc[1024];
    snprintf(doc, sizeof doc, "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":"
             "{\"law\":\"rope\",\"k\":%g,\"length\":%g},\"damper\":{\"law\":\"coulomb\",\"phi0\":%g,"
             "\"belt_velocity\":%g}}]},\"initial\":{\"x\":[0],\"v\":[%g]},\"solver\":{\"kind\":\"stick-slip\","
             "\"dt\":0.01,\"t_end\":4,\"theta\":0.5},\"output\":{\"every\":1}}", k, L, phi0, vb, vb);
    rows o;
    run_doc(doc, &o);
    assert_int_equal(o.events, 2);
    assert_int_equal(o.ev[0].kind, DP_EVENT_IMPACT);
    assert_int_equal(o.ev[1].kind, DP_EVENT_SLIP);
    assert_true(fabs(o.ev[0].t - L / vb) <= 1e-12 && o.ev[1].t == o.ev[0].t);
    assert_true(fabs(o.ev[0].v - vb) <= 1e-12 && o.ev[0].v_after == 0 && fabs(o.ev[0].impulse - vb) <= 1e-12);
    for (size_t i = 0; i < o.n; i++) {
        if (T(&o, i) < L / vb) {
            assert_true(fabs(X(&o, i, 0) - vb * T(&o, i)) <= 1e-12 && V(&o, i, 0) == vb);
            assert_true(fabs(FS(&o, i, 0) - k * X(&o, i, 0)) <= 1e-15);   /* slack: the spring alone */
        } else if (T(&o, i) > L / vb) {
            assert_true(fabs(X(&o, i, 0) - L) <= 1e-14 && V(&o, i, 0) == 0);
            assert_true(fabs(FS(&o, i, 0) - phi0) <= 1e-15 && FD(&o, i, 0) == -phi0);
        }
    }
    free(o.d);
}

/* ---- the rules ---------------------------------------------------------------------------------------------- */

/* theta < 1 for a rope with events located; without, it is its graph by backward Euler and needs theta = 1;
 * beside a graph spring (not located) a rope is stepped as before, with events "step", bit for bit as with
 * events "none" (a one-node network with a rope and events "none" stays on the one-mass solver, bit for bit:
 * tests/test_network.c). */
static void test_rules_and_modes(void **state)
{
    (void)state;
    static char doc[1024];
    char got[DP_POINTER_MAX];
    const char *fmt = "{\"model\":{\"masses\":[1],\"elements\":[{\"between\":[\"ground\",0],\"spring\":{\"law\":"
                      "\"rope\",\"k\":1,\"length\":1}}%s]},\"initial\":{\"x\":[0],\"v\":[2]},\"solver\":{\"dt\":0.01,"
                      "\"t_end\":3,\"theta\":%s,\"events\":\"%s\"}}";
    const char *graph = ",{\"between\":[\"ground\",0],\"spring\":{\"law\":\"graph\",\"points\":[[-1,-1],[0,0],[0,0.5],[1,2]]}}";
    snprintf(doc, sizeof doc, fmt, "", "0.5", "locate");
    rows_verdict(doc, got, sizeof got);
    assert_string_equal(got, "locate");
    snprintf(doc, sizeof doc, fmt, "", "1", "locate");
    rows_verdict(doc, got, sizeof got);
    assert_string_equal(got, "locate");
    snprintf(doc, sizeof doc, fmt, "", "0.5", "none");
    rows_verdict(doc, got, sizeof got);
    assert_string_equal(got, "/model/elements/0/spring");
    snprintf(doc, sizeof doc, fmt, "", "1", "none");
    rows_verdict(doc, got, sizeof got);
    assert_string_equal(got, "none");
    /* beside a graph spring with a jump (located too, network_smooth.c's split): any theta with events
     * located, theta = 1 without, the graph's rule named */
    snprintf(doc, sizeof doc, fmt, graph, "0.5", "locate");
    rows_verdict(doc, got, sizeof got);
    assert_string_equal(got, "locate");
    snprintf(doc, sizeof doc, fmt, graph, "0.5", "none");
    rows_verdict(doc, got, sizeof got);
    assert_string_equal(got, "/model/elements/0/spring");
    snprintf(doc, sizeof doc, fmt, graph, "1", "none");
    rows_verdict(doc, got, sizeof got);
    assert_string_equal(got, "none");
    rows a;
    run_doc(doc, &a);
    free(a.d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_thrown_rope_second_order),
        cmocka_unit_test(test_slack_and_taut_again),
        cmocka_unit_test(test_free_pair_jerked),
        cmocka_unit_test(test_impulse_through_rope_e05),
        cmocka_unit_test(test_impulse_through_rope_e1),
        cmocka_unit_test(test_pair_bounces_to_rest),
        cmocka_unit_test(test_hanging_rests),
        cmocka_unit_test(test_tethered_block_on_belt),
        cmocka_unit_test(test_rules_and_modes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
