/* tests/test_hostile.c - every numeric member of the one-mass, elastoplastic and right-hand documents at the
 * ends of the doubles (1e308, -1e308, 5e-324, -5e-324, DBL_MAX, 1e155): each document is refused with a
 * located error (a JSON Pointer, finite numbers in its words) or runs to its end or to a stated failure with
 * finite numbers only, never a NaN lookup, a crash or a "diverged" for an overflow of its own scale.
 *
 * An adversarial review found graph lookups with a NaN reading out of bounds (omega = 1.8e308, dt >= 1e155,
 * v = 1e308, a relaxation b = 1e308, a graph point at -5e-324, t_end = 5e-324): under `make test SAN=1` any
 * out-of-bounds read here stops the test.
 */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <cjson/cJSON.h>

#include "dashpot/json.h"
#include "dashpot/run.h"

/* The documents whose members are replaced one at a time (' for "). */
static const struct base { const char *name, *doc; } bases[] = {
    { "lin-harm",
      "{'model':{'mass':1,'spring':{'law':'linear','k':1},'damper':{'law':'linear','c':0.1,'belt_velocity':"
      "0.1},'forcing':{'kind':'harmonic','amplitude':1,'omega':1.8,'phase':0.1}},'initial':{'x':1,'v':0.5},"
      "'solver':{'kind':'stick-slip','dt':0.1,'t_end':1,'theta':0.5,'eps':0.0001},'output':{'every':2}}" },
    { "rope-coul-rat",
      "{'model':{'mass':1,'spring':{'law':'rope','k':1,'length':2},'damper':{'law':'coulomb','phi0':0.3,'re"
      "laxation':{'kind':'rational','a':0.1,'b':1},'belt_velocity':0.2},'forcing':{'kind':'constant','value"
      "':0.5}},'initial':{'x':1,'v':0},'solver':{'dt':0.1,'t_end':1},'output':{'max_samples':5}}" },
    { "graph-graph-table",
      "{'model':{'mass':1,'spring':{'law':'graph','points':[[-1,-1],[0,0],[1,2]]},'damper':{'law':'graph','"
      "points':[[0,-1],[0,1],[1,2]]},'forcing':{'kind':'table','points':[[0,0],[1,1]]}},'initial':{'x':0.5,"
      "'v':0.5},'solver':{'dt':0.1,'t_end':1}}" },
    { "ep-bingham-sum",
      "{'model':{'mass':1,'spring':{'law':'elastoplastic','k':1,'yield':0.5,'offset':0.1},'damper':{'law':'"
      "bingham','tau':0.2,'c':0.1},'forcing':{'kind':'sum','terms':[{'kind':'constant','value':0.1},{'kind'"
      ":'harmonic','amplitude':1,'omega':2}]}},'initial':{'x':0,'v':1},'solver':{'dt':0.1,'t_end':1,'theta'"
      ":0.5}}" },
    { "ep-example",
      "{'model':{'mass':1,'spring':{'law':'elastoplastic','k':1,'yield':0.5},'damper':{'law':'none'}},'init"
      "ial':{'x':0,'v':1},'solver':{'kind':'stick-slip','dt':0.5,'t_end':3,'theta':0.5}}" },
    { "gc-linrel",
      "{'model':{'mass':1,'spring':{'law':'linear','k':1},'damper':{'law':'generalized-coulomb','phi0':0.2,"
      "'phi1':0.3,'relaxation':{'kind':'linear','L':0.5}}},'initial':{'x':1,'v':0},'solver':{'dt':0.1,'t_en"
      "d':1,'theta':1}}" },
    { "coul-power-motion",
      "{'model':{'mass':1,'spring':{'law':'linear','k':1},'damper':{'law':'coulomb','phi0':0.2,'relaxation'"
      ":{'kind':'power','N':2}}},'initial':{'x':0.1,'v':0},'solver':{'dt':0.1,'t_end':1,'theta':1,'branch':"
      "'motion','events':'none'}}" },
    { "thesis",
      "{'model':{'mass':1,'spring':{'law':'linear','k':1},'damper':{'law':'coulomb','phi0':0.3,'relaxation'"
      ":{'kind':'rational','a':0.1,'b':1}},'forcing':{'kind':'constant','value':0.1}},'initial':{'x':1,'v':"
      "0},'solver':{'dt':0.1,'t_end':1,'variant':'thesis','Z':50,'eps':1e-06}}" },
    { "analytic",
      "{'model':{'mass':1,'spring':{'law':'linear','k':1},'damper':{'law':'coulomb','phi0':0.1},'forcing':{"
      "'kind':'constant','value':0.2}},'initial':{'x':1,'v':0.5},'solver':{'kind':'analytic','dt':0.1,'t_en"
      "d':1}}" },
    { "reg-pc",
      "{'model':{'mass':1,'spring':{'law':'linear','k':1},'damper':{'law':'coulomb','phi0':0.1,'belt_veloci"
      "ty':0.1}},'initial':{'x':1,'v':0},'solver':{'kind':'regularized','scheme':'PC','n':100,'dt':0.1,'t_e"
      "nd':1,'rtol':1e-06,'atol':1e-08}}" },
    { "reg-pi",
      "{'model':{'mass':1,'spring':{'law':'graph','points':[[-1,-1],[1,1]]},'damper':{'law':'coulomb','phi0"
      "':0.1}},'initial':{'x':1,'v':0},'solver':{'kind':'regularized','scheme':'PI','k':[10,20],'dt':0.1,'t"
      "_end':1,'stepper':'rk8pd'}}" },
    { "newmark",
      "{'model':{'mass':1,'spring':{'law':'elastoplastic','k':1,'yield':0.5},'damper':{'law':'linear','c':0"
      ".1},'forcing':{'kind':'harmonic','amplitude':1,'omega':1}},'initial':{'x':0,'v':1},'solver':{'kind':"
      "'newmark','dt':0.1,'t_end':1,'beta':0.25,'gamma':0.5}}" },
    { "newmark-lin",
      "{'model':{'mass':1,'spring':{'law':'linear','k':1},'damper':{'law':'none'}},'initial':{'x':1,'v':1},"
      "'solver':{'kind':'newmark','dt':0.1,'t_end':1}}" },
    { "net-smooth",   /* network_smooth.c: a compliant contact and a sloped graph spring, theta-stepped */
      "{'model':{'masses':[1,1.5],'elements':[{'between':['ground',0],'spring':{'law':'graph','points':[[-1,-2"
      "],[0,0],[1,1]]},'damper':{'law':'coulomb','phi0':0.3,'belt_velocity':0.1}},{'between':[0,1],'spring':{"
      "'law':'linear','k':2},'contact':{'distance':-0.5,'compliance':100}}],'forcing':[{'node':1,'kind':'harmo"
      "nic','amplitude':1,'omega':2}]},'initial':{'x':[0.5,0],'v':[0,1]},'solver':{'dt':0.1,'t_end':2,'theta'"
      ":0.5}}" },
    { "net-split",    /* a graph spring with stops and a jump, split on the network (network_run.c) */
      "{'model':{'masses':[1,2],'elements':[{'between':['ground',0],'spring':{'law':'graph','points':[[-0.8,-4"
      "],[-0.8,-1],[0,0],[0,0.5],[0.9,1.4],[0.9,3]]},'damper':{'law':'coulomb','phi0':0.2,'belt_velocity':0."
      "1}},{'between':[0,1],'spring':{'law':'rope','k':1,'length':1.5}}],'forcing':[{'node':1,'kind':'harmo"
      "nic','amplitude':2,'omega':1.5}]},'initial':{'x':[0.2,0.5],'v':[1,0]},'solver':{'dt':0.1,'t_end':2,'"
      "theta':0.5}}" },
    { "net-grounded", /* network_grounded_chain.c: friction and a contact to the ground, "events" "none" */
      "{'model':{'masses':[1,2,1],'elements':[{'between':['ground',0],'spring':{'law':'linear','k':1},'dampe"
      "r':{'law':'coulomb','phi0':0.4,'belt_velocity':0.2}},{'between':[0,1],'spring':{'law':'linear','k':3}},{"
      "'between':[1,2],'spring':{'law':'linear','k':2},'damper':{'law':'linear','c':0.1}},{'between':['ground"
      "',2],'damper':{'law':'coulomb','phi0':0.3}},{'between':['ground',1],'contact':{'distance':-0.5,'restitu"
      "tion':0.5}}],'forcing':[{'node':1,'kind':'constant','value':-2}]},'initial':{'x':[0.5,0,-0.2],'v':[0,0"
      ".5,0]},'solver':{'dt':0.05,'t_end':2,'theta':0.5,'events':'none'},'output':{'every':3}}" },
    { "net-blocks",   /* network_step.c's held solves over blocks: a located chain whose blocks stick */
      "{'model':{'masses':[1,1,1,1],'elements':[{'between':['ground',0],'spring':{'law':'linear','k':1},'dam"
      "per':{'law':'coulomb','phi0':1,'belt_velocity':-0.1}},{'between':['ground',1],'spring':{'law':'linear"
      "','k':1},'damper':{'law':'coulomb','phi0':1.4,'belt_velocity':-0.1}},{'between':['ground',2],'damper':"
      "{'law':'coulomb','phi0':0.6,'belt_velocity':-0.1}},{'between':['ground',3],'damper':{'law':'coulomb',"
      "'phi0':1.2}},{'between':[0,1],'spring':{'law':'linear','k':10}},{'between':[1,2],'spring':{'law':'line"
      "ar','k':10}},{'between':[2,3],'spring':{'law':'linear','k':10}}]},'initial':{'x':[0.5,-0.3,0.1,0.4],"
      "'v':[0,0,0,0]},'solver':{'dt':0.05,'t_end':2,'theta':0.5}}" },
    { "piston",
      "{'model':{'kind':'piston-hinge','m1':1,'m2':1,'J_C':0.1,'r':0.5,'alpha':0.3,'f1':0.2,'f2':0.02,'g':9"
      ".81},'initial':{'x':[0,0.8],'v':[0,0]},'solver':{'kind':'right-hand','t_end':1,'dt':0.25,'rtol':1e-0"
      "8,'atol':1e-10}}" },
    { "rod",
      "{'model':{'kind':'painleve-rod','m':1,'length':1,'mu':0.5,'g':9.81},'initial':{'x':[0,1.2],'v':[0,0]"
      "},'solver':{'kind':'right-hand','t_end':2,'dt':0.1}}" },
};

static const double hostile[] = { 1e308, -1e308, 5e-324, -5e-324, DBL_MAX, 1e155 };

/* Whether text holds a word that is a non-finite number as printf writes one. */
static int says_nonfinite(const char *text)
{
    static const char *const words[] = { "nan", "inf", NULL };
    for (const char *const *w = words; *w; w++)
        for (const char *p = strstr(text, *w); p; p = strstr(p + 1, *w)) {
            int before = p > text && (p[-1] >= 'a' && p[-1] <= 'z');
            char after = p[strlen(*w)];
            if (!before && !(after >= 'a' && after <= 'z'))
                return 1;
        }
    return 0;
}

static int record_finite(const dp_record *rec, const dp_columns *cols)
{
    if (rec->type == DP_RECORD_SAMPLE) {
        const dp_sample *s = &rec->u.sample;
        return isfinite(s->t) && isfinite(s->x) && isfinite(s->v) && isfinite(s->Fs) && isfinite(s->Fd)
               && isfinite(s->Fc) && isfinite(s->p);
    }
    if (rec->type == DP_RECORD_EVENT)
        return isfinite(rec->u.event.t) && isfinite(rec->u.event.x) && isfinite(rec->u.event.v);
    for (size_t i = 0; cols && i < cols->width; i++)
        if (!isfinite(rec->u.row.val[i]))
            return 0;
    return isfinite(rec->u.row.t);
}

/* Runs one document; returns 1 when its answer is one of the allowed ones, printing it otherwise. */
static int answer_ok(const char *what, const char *text)
{
    dp_spec spec;
    dp_errors e;
    dp_spec_init(&spec);
    dp_errors_init(&e);
    int st = dp_spec_parse(text, strlen(text), 1e5, &spec, &e), ok = 1;
    if (st != DP_OK) {
        for (size_t i = 0; i < e.n; i++)
            if (e.item[i].pointer[0] != '/' || says_nonfinite(e.item[i].message)) {
                print_error("%s: refused at \"%s\": %s\n", what, e.item[i].pointer, e.item[i].message);
                ok = 0;
            }
        ok = ok && e.n > 0;
        dp_spec_clear(&spec);
        return ok;
    }
    dp_buf meta = { 0 }; /* the meta line, with its well-posedness report, says no nan or inf either */
    if (dp_spec_meta_json(&spec, &meta) != DP_OK || says_nonfinite(meta.data)) {
        print_error("%s: meta line %s\n", what, meta.data ? meta.data : "(not written)");
        ok = 0;
    }
    dp_buf_free(&meta);
    dp_run *run = dp_run_alloc(&spec, 1e5, &e, &st);
    dp_spec_clear(&spec);
    if (run == NULL) {
        ok = e.n > 0 && e.item[0].pointer[0] == '/' && !says_nonfinite(e.item[0].message);
        if (!ok)
            print_error("%s: not allocated (%d) at \"%s\": %s\n", what, st, e.n ? e.item[0].pointer : "",
                        e.n ? e.item[0].message : "");
        return ok;
    }
    dp_record buf[256];
    size_t n;
    while ((st = dp_run_next(run, buf, 256, &n)) == DP_MORE || st == DP_DONE) {
        for (size_t i = 0; i < n; i++)
            if (!record_finite(&buf[i], dp_run_columns(run))) {
                print_error("%s: a record with a non-finite number\n", what);
                ok = 0;
            }
        if (st == DP_DONE)
            break;
    }
    const char *why = dp_run_error(run);
    if (st != DP_DONE && (says_nonfinite(why) || strstr(why, "diverged") != NULL)) {
        print_error("%s: failed (%d): %s\n", what, st, why);
        ok = 0;
    }
    dp_run_free(run);
    return ok;
}

/* Each numeric leaf of `node` (pointer `at`) at each hostile value, the rest of the document unchanged. */
static void each_leaf(cJSON *root, cJSON *node, char *at, size_t len, int *bad, int *cases)
{
    if (cJSON_IsNumber(node)) {
        double keep = node->valuedouble;
        for (size_t i = 0; i < sizeof hostile / sizeof *hostile; i++) {
            cJSON_SetNumberValue(node, hostile[i]);
            char *text = cJSON_PrintUnformatted(root), what[256];
            assert_non_null(text);
            snprintf(what, sizeof what, "%s = %g in %s", at, hostile[i], text);
            *bad += !answer_ok(what, text);
            (*cases)++;
            cJSON_free(text);
        }
        cJSON_SetNumberValue(node, keep);
        return;
    }
    size_t i = 0;
    for (cJSON *c = node->child; c; c = c->next, i++) {
        int n = c->string ? snprintf(at + len, 160 - len, "/%s", c->string)
                          : snprintf(at + len, 160 - len, "/%zu", i);
        each_leaf(root, c, at, len + (size_t)n, bad, cases);
        at[len] = 0;
    }
}

static void test_every_member_at_the_ends(void **state)
{
    const struct base *b = *state;
    char *text = strdup(b->doc), at[160] = "";
    assert_non_null(text);
    for (char *p = text; *p; p++)
        *p = *p == '\'' ? '"' : *p;
    cJSON *root = cJSON_Parse(text);
    assert_non_null(root);
    assert_true(answer_ok(b->name, text)); /* the document itself runs */
    int bad = 0, cases = 0;
    each_leaf(root, root, at, 0, &bad, &cases);
    cJSON_Delete(root);
    free(text);
    assert_true(cases >= 6);
    assert_int_equal(bad, 0);
}

/* The review's own inputs, each named: refused at the member or run with finite numbers. */
static void test_review_inputs(void **state)
{
    (void)state;
    static const char *const docs[] = {
        "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"none\"},"
        "\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":1,\"omega\":1.79e308}},\"solver\":{\"t_end\":1}}",
        "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":\"none\"}},"
        "\"initial\":{\"v\":1},\"solver\":{\"dt\":1e155,\"t_end\":1e156}}",
        "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"graph\",\"points\":[[-5e-324,-1],[1,1]]},"
        "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.1}},\"initial\":{\"x\":0.5},\"solver\":{\"t_end\":1}}",
        "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"elastoplastic\",\"k\":1,\"yield\":0.5},"
        "\"damper\":{\"law\":\"none\"}},\"initial\":{\"v\":1},\"solver\":{\"dt\":0.5,\"t_end\":5e-324}}",
    };
    for (size_t i = 0; i < sizeof docs / sizeof *docs; i++)
        assert_true(answer_ok(docs[i], docs[i]));
}

/* The kind of answer: an overflow of the document's own scale is a 422 at its member where the start of the
 * run shows it, and "overflow", not "diverged", where only the run does; an ordinary divergence stays one. */
static void test_overflow_named(void **state)
{
    (void)state;
    dp_spec spec;
    dp_errors e;
    const char *wide = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":"
                       "\"none\"},\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":1,\"omega\":1e308}},"
                       "\"solver\":{\"t_end\":10}}";
    dp_spec_init(&spec);
    dp_errors_init(&e);
    assert_int_equal(dp_spec_parse(wide, strlen(wide), 0, &spec, &e), DP_EINVAL);
    assert_string_equal(e.item[0].pointer, "/model/forcing/omega");
    assert_non_null(strstr(e.item[0].message, "omega t_end + phase"));
    dp_spec_clear(&spec);
    const char *grows = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":"
                        "\"linear\",\"c\":0,\"relaxation\":{\"kind\":\"linear\",\"L\":50}}},\"initial\":{\"x\":1},"
                        "\"solver\":{\"dt\":0.01,\"t_end\":100,\"theta\":1}}";
    const char *huge = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":{\"law\":"
                       "\"none\"},\"forcing\":{\"kind\":\"constant\",\"value\":1e308}},\"solver\":{\"dt\":0.1,"
                       "\"t_end\":10,\"theta\":1}}";
    const char *want[] = { "the solution diverged at t = 10.24", "the step's quantities overflow at t = " };
    const char *docs[] = { grows, huge };
    for (int i = 0; i < 2; i++) {
        dp_spec_init(&spec);
        dp_errors_init(&e);
        assert_int_equal(dp_spec_parse(docs[i], strlen(docs[i]), 0, &spec, &e), DP_OK);
        int st;
        dp_run *run = dp_run_alloc(&spec, 0, &e, &st);
        dp_spec_clear(&spec);
        assert_non_null(run);
        dp_record buf[512];
        size_t n;
        while ((st = dp_run_next(run, buf, 512, &n)) == DP_MORE)
            ;
        assert_int_equal(st, i == 0 ? DP_ENONFINITE : DP_ESOLVE);
        assert_non_null(strstr(dp_run_error(run), want[i]));
        dp_run_free(run);
    }
}

/* A rule about a member the document leaves to its default points to the nearest member it has. */
static void test_pointer_to_present_member(void **state)
{
    (void)state;
    const char *doc = "{\"model\":{\"kind\":\"painleve-rod\",\"m\":1,\"length\":1,\"mu\":0.5},"
                      "\"initial\":{\"v\":[0,0]},\"solver\":{\"t_end\":1,\"dt\":0.1}}";
    dp_spec spec;
    dp_errors e;
    dp_spec_init(&spec);
    dp_errors_init(&e);
    assert_int_equal(dp_spec_parse(doc, strlen(doc), 0, &spec, &e), DP_EINVAL);
    dp_spec_clear(&spec);
    assert_int_equal(e.n, 1);
    assert_string_equal(e.item[0].pointer, "/initial");
    assert_non_null(strstr(e.item[0].message, "/initial/x/1 is absent"));
}

int main(void)
{
    struct CMUnitTest tests[sizeof bases / sizeof *bases + 3];
    size_t n = 0;
    for (size_t i = 0; i < sizeof bases / sizeof *bases; i++)
        tests[n++] = (struct CMUnitTest){ bases[i].name, test_every_member_at_the_ends, NULL, NULL,
                                          (void *)&bases[i] };
    tests[n++] = (struct CMUnitTest)cmocka_unit_test(test_review_inputs);
    tests[n++] = (struct CMUnitTest)cmocka_unit_test(test_overflow_named);
    tests[n++] = (struct CMUnitTest)cmocka_unit_test(test_pointer_to_present_member);
    return _cmocka_run_group_tests("hostile", tests, n, NULL, NULL);
}
