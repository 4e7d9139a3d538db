/* tests/test_spec.c - dp_spec_parse (src/json/spec_json.c): valid documents into the expected dp_spec,
 * and a catalogue of invalid ones, each with its status, the exact JSON Pointer and a message fragment.
 *
 * Documents are written with ' for " (replaced before parsing) so the rows stay readable. Every row is its
 * own cmocka test named after the row; on failure the row, the status and every error are printed.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "dashpot/json.h"
#include "dashpot/lcp_json.h"
#include "dashpot/modes_json.h"
#include "dashpot/stability_json.h"

/* ---- helpers ---------------------------------------------------------------------------------------- */

/* A malloc'd copy of doc with every ' turned into ". */
static char *dq(const char *doc)
{
    char *s = strdup(doc);
    assert_non_null(s);
    for (char *p = s; *p; p++)
        if (*p == '\'')
            *p = '"';
    return s;
}

static void print_errors(const dp_errors *e)
{
    for (size_t i = 0; i < e->n; i++)
        print_error("    error %zu: pointer \"%s\" message \"%s\"\n", i, e->item[i].pointer, e->item[i].message);
}

/* Parses doc (with ' for ") into a fresh spec; the caller clears it. */
static int parse_doc(const char *doc, double max_steps, dp_spec *s, dp_errors *e)
{
    char *text = dq(doc);
    dp_spec_init(s);
    dp_errors_init(e);
    int st = dp_spec_parse(text, strlen(text), max_steps, s, e);
    free(text);
    return st;
}

/* Parses a document that must be valid; prints its errors and fails otherwise. */
static void parse_ok(const char *what, const char *doc, dp_spec *s)
{
    dp_errors e;
    int st = parse_doc(doc, 0, s, &e);
    if (st != DP_OK) {
        print_error("%s: expected DP_OK, got %d (%s) for %s\n", what, st, dp_strerror(st), doc);
        print_errors(&e);
    }
    assert_int_equal(st, DP_OK);
    assert_int_equal(e.n, 0);
}

/* An error in e with exactly this pointer whose message contains `part`. */
static int has_error(const dp_errors *e, const char *pointer, const char *part)
{
    for (size_t i = 0; i < e->n; i++)
        if (strcmp(e->item[i].pointer, pointer) == 0 && strstr(e->item[i].message, part) != NULL)
            return 1;
    return 0;
}

/* Checks a double with a description printed on mismatch (values here are exact binary fractions or
 * literals parsed by strtod on both sides, so equality is the right test). */
#define CHECK_NUM(what, got, want)                                                                        \
    do {                                                                                                  \
        if ((double)(got) != (double)(want))                                                              \
            print_error("%s: %s = %.17g, expected %.17g\n", what, #got, (double)(got), (double)(want));  \
        assert_true((double)(got) == (double)(want));                                                     \
    } while (0)

/* Compares the initial state, solver and output parts of s with those of want. */
static void check_run_fields(const char *w, const dp_spec *s, const dp_spec *want)
{
    CHECK_NUM(w, s->x0, want->x0);
    CHECK_NUM(w, s->v0, want->v0);
    assert_int_equal(s->solver.kind, want->solver.kind);
    CHECK_NUM(w, s->solver.dt, want->solver.dt);
    CHECK_NUM(w, s->solver.t_end, want->solver.t_end);
    CHECK_NUM(w, s->solver.theta, want->solver.theta);
    assert_int_equal(s->solver.variant, want->solver.variant);
    assert_int_equal(s->solver.Z, want->solver.Z);
    CHECK_NUM(w, s->solver.eps, want->solver.eps);
    assert_int_equal(s->solver.events, want->solver.events);
    assert_int_equal(s->output.every, want->output.every);
    assert_int_equal(s->output.samples, want->output.samples);
    assert_int_equal(s->output.events, want->output.events);
}

#define SPRING_OK "'spring':{'law':'linear','k':1}"
#define DAMPER_OK "'damper':{'law':'none'}"
/* A valid model with x appended inside "model". */
#define MODEL_WITH(x) "{'model':{'mass':1," SPRING_OK "," DAMPER_OK x "}}"
#define SPRING(x) "{'model':{'mass':1,'spring':" x "," DAMPER_OK "}}"
#define DAMPER(x) "{'model':{'mass':1," SPRING_OK ",'damper':" x "}}"
#define FORCING(x) MODEL_WITH(",'forcing':" x)
/* A valid document with x appended at the top level. */
#define TOP(x) "{'model':{'mass':1," SPRING_OK "," DAMPER_OK "}" x "}"

/* ---- valid documents -------------------------------------------------------------------------------- */

/* The model of docs/architecture.md, and every default of spec.h / the schema. */
static void test_architecture_example(void **state)
{
    (void)state;
    dp_spec s;
    parse_ok("architecture example",
             "{'model': {'mass': 1,"
             " 'spring':  {'law': 'linear', 'k': 1},"
             " 'damper':  {'law': 'coulomb', 'phi0': 1,"
             "             'relaxation': {'kind': 'rational', 'a': 0.5, 'b': 1}},"
             " 'forcing': {'kind': 'harmonic', 'amplitude': 0.5, 'omega': 1.3, 'phase': 0}}}", &s);
    const char *w = "architecture example";
    CHECK_NUM(w, s.model.mass, 1);
    assert_int_equal(s.model.spring.law, DP_SPRING_LINEAR);
    CHECK_NUM(w, s.model.spring.k, 1);
    assert_int_equal(s.model.damper.law, DP_DAMPER_COULOMB);
    CHECK_NUM(w, s.model.damper.phi0, 1);
    CHECK_NUM(w, s.model.damper.belt_velocity, 0);
    assert_int_equal(s.model.damper.relaxation.kind, DP_RELAX_RATIONAL);
    CHECK_NUM(w, s.model.damper.relaxation.a, 0.5);
    CHECK_NUM(w, s.model.damper.relaxation.b, 1);
    assert_int_equal(s.model.forcing.kind, DP_FORCING_HARMONIC);
    CHECK_NUM(w, s.model.forcing.amplitude, 0.5);
    CHECK_NUM(w, s.model.forcing.omega, 1.3);
    CHECK_NUM(w, s.model.forcing.phase, 0);
    /* dp_model_prepare has run: both graphs exist. */
    assert_true(s.model.spring.graph.n >= 1);
    assert_true(s.model.damper.graph.n >= 1);
    /* Defaults (spec.h, the schema): theta chosen (1/2: a linear spring, the exact variant); every chosen,
     * 1: 10^4 steps are within the sample budget of 10 001. */
    check_run_fields(w, &s, &(dp_spec){ .x0 = 0, .v0 = 0,
        .solver = { DP_SOLVER_STICK_SLIP, 1e-3, 10, 0.5, DP_VARIANT_EXACT, 100, 1e-4, DP_EVENTS_LOCATE },
        .output = { 1, 1, 1 } });
    assert_int_equal(s.chosen, DP_CHOSEN_THETA | DP_CHOSEN_EVERY);
    dp_spec_clear(&s);
}

static void test_spring_laws(void **state)
{
    (void)state;
    dp_spec s;
    parse_ok("rope spring", SPRING("{'law':'rope','k':2,'length':0.5}"), &s);
    assert_int_equal(s.model.spring.law, DP_SPRING_ROPE);
    CHECK_NUM("rope", s.model.spring.k, 2);
    CHECK_NUM("rope", s.model.spring.length, 0.5);
    dp_spec_clear(&s);

    parse_ok("graph spring", SPRING("{'law':'graph','points':[[-1,-2],[0,0],[1,2]]}"), &s);
    assert_int_equal(s.model.spring.law, DP_SPRING_GRAPH);
    assert_int_equal(s.model.spring.graph.n, 3);
    CHECK_NUM("graph spring", s.model.spring.graph.y[0], -1);
    CHECK_NUM("graph spring", s.model.spring.graph.f[0], -2);
    CHECK_NUM("graph spring", s.model.spring.graph.y[2], 1);
    CHECK_NUM("graph spring", s.model.spring.graph.f[2], 2);
    dp_spec_clear(&s);
}

static void test_damper_laws(void **state)
{
    (void)state;
    dp_spec s;
    parse_ok("none damper", DAMPER("{'law':'none','belt_velocity':0.25}"), &s);
    assert_int_equal(s.model.damper.law, DP_DAMPER_NONE);
    CHECK_NUM("none damper", s.model.damper.belt_velocity, 0.25);
    assert_int_equal(s.model.damper.relaxation.kind, DP_RELAX_NONE);
    dp_spec_clear(&s);

    parse_ok("linear damper", DAMPER("{'law':'linear','c':0.3}"), &s);
    assert_int_equal(s.model.damper.law, DP_DAMPER_LINEAR);
    CHECK_NUM("linear damper", s.model.damper.c, 0.3);
    dp_spec_clear(&s);

    parse_ok("bingham damper", DAMPER("{'law':'bingham','tau':0.2,'c':0.1}"), &s);
    assert_int_equal(s.model.damper.law, DP_DAMPER_BINGHAM);
    CHECK_NUM("bingham damper", s.model.damper.tau, 0.2);
    CHECK_NUM("bingham damper", s.model.damper.c, 0.1);
    dp_spec_clear(&s);

    parse_ok("generalized-coulomb damper", DAMPER("{'law':'generalized-coulomb','phi0':1,'phi1':1.5}"), &s);
    assert_int_equal(s.model.damper.law, DP_DAMPER_GENERALIZED_COULOMB);
    CHECK_NUM("generalized-coulomb", s.model.damper.phi0, 1);
    CHECK_NUM("generalized-coulomb", s.model.damper.phi1, 1.5);
    dp_spec_clear(&s);

    /* Coulomb drawn by hand: the vertical piece at v = 0 is the stick interval [-1, 1]. */
    parse_ok("graph damper", DAMPER("{'law':'graph','points':[[-1,-1],[0,-1],[0,1],[1,1]]}"), &s);
    assert_int_equal(s.model.damper.law, DP_DAMPER_GRAPH);
    assert_int_equal(s.model.damper.graph.n, 4);
    CHECK_NUM("graph damper", s.model.damper.graph.f[1], -1);
    CHECK_NUM("graph damper", s.model.damper.graph.f[2], 1);
    dp_spec_clear(&s);
}

static void test_relaxation_kinds(void **state)
{
    (void)state;
    dp_spec s;
    parse_ok("linear relaxation",
             DAMPER("{'law':'coulomb','phi0':1,'relaxation':{'kind':'linear','L':0.1}}"), &s);
    assert_int_equal(s.model.damper.relaxation.kind, DP_RELAX_LINEAR);
    CHECK_NUM("linear relaxation", s.model.damper.relaxation.L, 0.1);
    dp_spec_clear(&s);

    parse_ok("power relaxation", DAMPER("{'law':'coulomb','phi0':1,'relaxation':{'kind':'power','N':2}}"), &s);
    assert_int_equal(s.model.damper.relaxation.kind, DP_RELAX_POWER);
    CHECK_NUM("power relaxation", s.model.damper.relaxation.N, 2);
    dp_spec_clear(&s);
}

static void test_forcing_kinds(void **state)
{
    (void)state;
    dp_spec s;
    parse_ok("constant forcing", FORCING("{'kind':'constant','value':-2.5}"), &s);
    assert_int_equal(s.model.forcing.kind, DP_FORCING_CONSTANT);
    CHECK_NUM("constant forcing", s.model.forcing.value, -2.5);
    dp_spec_clear(&s);

    parse_ok("table forcing", FORCING("{'kind':'table','points':[[0,1],[0.5,-1],[2,3]]}"), &s);
    assert_int_equal(s.model.forcing.kind, DP_FORCING_TABLE);
    assert_int_equal(s.model.forcing.n, 3);
    CHECK_NUM("table forcing", s.model.forcing.t[1], 0.5);
    CHECK_NUM("table forcing", s.model.forcing.F[1], -1);
    CHECK_NUM("table forcing", s.model.forcing.t[2], 2);
    dp_spec_clear(&s);

    parse_ok("one-point table", FORCING("{'kind':'table','points':[[1,4]]}"), &s);
    assert_int_equal(s.model.forcing.n, 1);
    dp_spec_clear(&s);

    parse_ok("sum forcing",
             FORCING("{'kind':'sum','terms':[{'kind':'constant','value':1},"
                     "{'kind':'harmonic','amplitude':2,'omega':3}]}"), &s);
    const dp_forcing *f = &s.model.forcing;
    assert_int_equal(f->kind, DP_FORCING_SUM);
    assert_int_equal(f->nterms, 2);
    assert_int_equal(f->terms[0].kind, DP_FORCING_CONSTANT);
    CHECK_NUM("sum term 0", f->terms[0].value, 1);
    assert_int_equal(f->terms[1].kind, DP_FORCING_HARMONIC);
    CHECK_NUM("sum term 1", f->terms[1].amplitude, 2);
    CHECK_NUM("sum term 1", f->terms[1].omega, 3);
    CHECK_NUM("sum term 1 default phase", f->terms[1].phase, 0);
    dp_spec_clear(&s);
}

/* A forcing nesting `sums` sums around a constant: DP_FORCING_MAX_DEPTH levels in all are allowed. */
static char *nested_sums(int sums)
{
    size_t cap = 256 + (size_t)sums * 64;
    char *s = malloc(cap);
    assert_non_null(s);
    size_t n = (size_t)snprintf(s, cap, "%s", "{'model':{'mass':1," SPRING_OK "," DAMPER_OK ",'forcing':");
    for (int i = 0; i < sums; i++)
        n += (size_t)snprintf(s + n, cap - n, "{'kind':'sum','terms':[");
    n += (size_t)snprintf(s + n, cap - n, "{'kind':'constant','value':1}");
    for (int i = 0; i < sums; i++)
        n += (size_t)snprintf(s + n, cap - n, "]}");
    snprintf(s + n, cap - n, "}}");
    return s;
}

static void test_forcing_depth_limit_ok(void **state)
{
    (void)state;
    dp_spec s;
    char *doc = nested_sums(DP_FORCING_MAX_DEPTH - 1);
    parse_ok("sums nested to the depth limit", doc, &s);
    free(doc);
    const dp_forcing *f = &s.model.forcing;
    for (int i = 0; i < DP_FORCING_MAX_DEPTH - 1; i++) {
        assert_int_equal(f->kind, DP_FORCING_SUM);
        f = &f->terms[0];
    }
    assert_int_equal(f->kind, DP_FORCING_CONSTANT);
    dp_spec_clear(&s);
}

/* The regularized solver's fields (spec.h): scheme, the n / k list, tolerances, stepper. */
static void test_regularized_fields(void **state)
{
    (void)state;
    dp_spec s;
    parse_ok("regularized PI fields",
             TOP(",'solver':{'kind':'regularized','scheme':'PI','k':[10,100,1e4],'t_end':3,'dt':0.1,"
                 "'rtol':1e-6,'atol':0,'stepper':'bsimp'}"), &s);
    assert_int_equal(s.solver.kind, DP_SOLVER_REGULARIZED);
    assert_int_equal(s.solver.scheme, DP_SCHEME_PI);
    assert_int_equal(s.solver.n_count, 3);
    CHECK_NUM("k[2]", s.solver.n_list[2], 1e4);
    CHECK_NUM("rtol", s.solver.rtol, 1e-6);
    CHECK_NUM("atol", s.solver.atol, 0);
    CHECK_NUM("dt", s.solver.dt, 0.1);
    assert_int_equal(s.solver.stepper, DP_STEPPER_BSIMP);
    dp_spec_clear(&s);
    parse_ok("regularized defaults", TOP(",'solver':{'kind':'regularized','n':50}"), &s);
    assert_int_equal(s.solver.scheme, DP_SCHEME_PC);
    assert_int_equal(s.solver.stepper, DP_STEPPER_MSBDF);
    assert_int_equal(s.solver.n_count, 1);
    CHECK_NUM("n", s.solver.n_list[0], 50);
    dp_spec_clear(&s);
}

static void test_solver_initial_output(void **state)
{
    (void)state;
    dp_spec s;
    parse_ok("every stick-slip field",
             TOP(",'initial':{'x':0.125,'v':-0.5},"
                 "'solver':{'kind':'stick-slip','dt':0.01,'t_end':2,'theta':0.5,'variant':'exact','Z':5,"
                 "'eps':1e-6,'events':'none'},"
                 "'output':{'every':10,'samples':false,'events':false}"), &s);
    check_run_fields("stick-slip fields", &s, &(dp_spec){ .x0 = 0.125, .v0 = -0.5,
        .solver = { DP_SOLVER_STICK_SLIP, 0.01, 2, 0.5, DP_VARIANT_EXACT, 5, 1e-6, DP_EVENTS_NONE },
        .output = { 10, 0, 0 } });
    dp_spec_clear(&s);

    parse_ok("thesis variant",
             "{'model':{'mass':1," SPRING_OK ",'damper':{'law':'coulomb','phi0':1}},"
             "'solver':{'variant':'thesis'}}", &s);
    assert_int_equal(s.solver.variant, DP_VARIANT_THESIS);
    dp_spec_clear(&s);

    parse_ok("analytic solver", TOP(",'solver':{'kind':'analytic','t_end':5,'dt':0.125}"), &s);
    assert_int_equal(s.solver.kind, DP_SOLVER_ANALYTIC);
    CHECK_NUM("analytic", s.solver.t_end, 5);
    CHECK_NUM("analytic", s.solver.dt, 0.125);
    dp_spec_clear(&s);
}

/* The length is authoritative: bytes after it are never read, a NUL inside it is malformed. */
static void test_length_not_nul(void **state)
{
    (void)state;
    char *doc = dq(TOP("") "  garbage that is past the length");
    size_t len = strlen(doc) - strlen("garbage that is past the length");
    dp_spec s;
    dp_errors e;
    dp_spec_init(&s);
    dp_errors_init(&e);
    int st = dp_spec_parse(doc, len, 0, &s, &e);
    if (st != DP_OK)
        print_errors(&e);
    assert_int_equal(st, DP_OK);
    dp_spec_clear(&s);

    doc[len - 1] = '\0';           /* a NUL in the trailing whitespace */
    dp_spec_init(&s);
    dp_errors_init(&e);
    st = dp_spec_parse(doc, len, 0, &s, &e);
    assert_int_equal(st, DP_ESYNTAX);
    assert_int_equal(e.n, 1);
    assert_string_equal(e.item[0].pointer, "");
    dp_spec_clear(&s);
    free(doc);
}

/* Exactly DP_JSON_MAX_DEPTH levels reach cJSON (and fail as a non-object root); one more is rejected. */
static void test_depth_boundary(void **state)
{
    (void)state;
    for (int extra = 0; extra <= 1; extra++) {
        int depth = DP_JSON_MAX_DEPTH + extra;
        char *doc = malloc(2 * (size_t)depth + 1);
        assert_non_null(doc);
        memset(doc, '[', (size_t)depth);
        memset(doc + depth, ']', (size_t)depth);
        doc[2 * depth] = '\0';
        dp_spec s;
        dp_errors e;
        dp_spec_init(&s);
        dp_errors_init(&e);
        int st = dp_spec_parse(doc, strlen(doc), 0, &s, &e);
        print_message("depth %d: status %d, message \"%s\"\n", depth, st, e.n ? e.item[0].message : "");
        assert_int_equal(st, extra ? DP_ESYNTAX : DP_EINVAL);
        assert_int_equal(e.n, 1);
        assert_string_equal(e.item[0].pointer, "");
        assert_non_null(strstr(e.item[0].message, extra ? "nested deeper than 64" : "must be an object"));
        dp_spec_clear(&s);
        free(doc);
    }
}

/* A malformed document is one error at "", its place as byte, line and column (columns count characters),
 * and what is wrong there (src/json/body.c). Raw text: no ' for " here, single quotes are one of the cases. */
/* A body is not NUL-terminated: a document cut inside a literal ("fal", "tru", "nul") is described from its
 * own bytes only (found by tests/fuzz/fuzz_spec.c: the reader compared 5 bytes of a 3-byte body; the
 * sanitizer build reads past an exact-size allocation here). */
static void test_cut_literal_reads_no_further(void **state)
{
    (void)state;
    static const char *const cut[] = { "fal", "tru", "nul", "f", "[tr", "{\"a\":nu" };
    for (size_t i = 0; i < sizeof cut / sizeof *cut; i++) {
        size_t n = strlen(cut[i]);
        char *exact = malloc(n);
        assert_non_null(exact);
        memcpy(exact, cut[i], n);
        dp_spec s;
        dp_errors e;
        dp_spec_init(&s);
        dp_errors_init(&e);
        int st = dp_spec_parse(exact, n, 0, &s, &e);
        free(exact);
        dp_spec_clear(&s);
        assert_int_equal(st, DP_ESYNTAX);
        assert_int_equal(e.n, 1);
        assert_string_equal(e.item[0].pointer, "");
    }
}

static void test_malformed_where_and_why(void **state)
{
    (void)state;
    static const struct { const char *doc; size_t len; const char *message; } cases[] = {
        { "{\"model\": {\"mass\": NaN}}", 0,
          "malformed JSON near byte 19 (line 1, column 20): JSON has no NaN or Infinity; send a number or null" },
        { "{\n  \"model\": {\n    \"mass\": -Infinity\n  }\n}", 0,
          "malformed JSON near byte 27 (line 3, column 13): JSON has no NaN or Infinity; send a number or null" },
        { "{'model': {}}", 0,
          "malformed JSON near byte 1 (line 1, column 2): JSON keys take double quotes, not single quotes" },
        { "{\"model\": {\"spring\": {\"law\": 'linear'}}}", 0,
          "malformed JSON near byte 29 (line 1, column 30): JSON strings take double quotes, not single quotes" },
        { "{\"model\": {\"mass\": 1,}}", 0,
          "malformed JSON near byte 20 (line 1, column 21): a trailing comma before }; remove it" },
        { "{\"solver\": {\"n\": [1, 2,]}}", 0,
          "malformed JSON near byte 22 (line 1, column 23): a trailing comma before ]; remove it" },
        { "{\"model\": {\"mass\": 1 /* kg */}}", 0,
          "malformed JSON near byte 21 (line 1, column 22): JSON has no comments" },
        { "{\n  // the oscillator\n  \"model\": {}\n}", 0,
          "malformed JSON near byte 4 (line 2, column 3): JSON has no comments" },
        { "{model: {}}", 0,
          "malformed JSON near byte 1 (line 1, column 2): the key model must be in double quotes: \"model\"" },
        { "{\"model\": {\"mass\": 1", 0,
          "malformed JSON near byte 20 (line 1, column 21): the document ends early: the { at line 1, column 11 "
          "is never closed" },
        { "{\"model\": {\"damper\": {\"law\": \"coul", 0,
          "malformed JSON near byte 34 (line 1, column 35): the document ends inside the string opened at line 1, "
          "column 30" },
        { "{\"model\": {} \"solver\": {}}", 0,
          "malformed JSON near byte 13 (line 1, column 14): a comma is missing between two members" },
        { "{\"model\": {\"mass\": True}}", 0,
          "malformed JSON near byte 19 (line 1, column 20): unknown word \"True\"; JSON's literals are true, false "
          "and null" },
        { "{\"model\": {\"mass\": 1]}", 0,
          "malformed JSON near byte 20 (line 1, column 21): this ] does not close the { at line 1, column 11" },
        { "{\"model\": {\"nom\": \"\xc3\xa9t\xc3\xa9\", \"mass\": .5}}", 0,      /* é is one column, two bytes */
          "malformed JSON near byte 35 (line 1, column 34): a JSON number needs a digit before its point (0.5, not .5)" },
        { "{\"model\": {\"law\": \"\\x\"}}", 0,
          "malformed JSON near byte 19 (line 1, column 20): invalid escape \\ followed by 'x'; JSON's are \\\" \\\\ "
          "\\/ \\b \\f \\n \\r \\t \\uXXXX" },
        { "{\"model\": {\"mass\": 1.5.5}}", 0,
          "malformed JSON near byte 19 (line 1, column 20): \"1.5.5\" is not a number" },
        { "{\"model\": {\"mass\": 1, \"k\": 12345678901234567890123456789012345678901234567890123456789012345678901234567890e}}", 0,
          "malformed JSON near byte 27 (line 1, column 28): \"1234567890123456789012345678901234567890...\" is not a number" },
        { "{\"model\":\0{}}", 13,
          "malformed JSON near byte 9 (line 1, column 10): a NUL byte outside any string" },
        { "\n\n {} []", 0,
          "malformed JSON near byte 6 (line 3, column 5): data after the document (send one JSON object)" },
        { " \n", 0, "malformed JSON near byte 2 (line 2, column 1): empty document: send one JSON object" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        size_t len = cases[i].len ? cases[i].len : strlen(cases[i].doc);
        dp_spec s;
        dp_errors e;
        dp_spec_init(&s);
        dp_errors_init(&e);
        int st = dp_spec_parse(cases[i].doc, len, 0, &s, &e);
        if (st != DP_ESYNTAX || e.n != 1 || strcmp(e.item[0].message, cases[i].message) != 0) {
            print_error("case %zu: status %d for %s\n   expected: %s\n", i, st, cases[i].doc, cases[i].message);
            print_errors(&e);
        }
        assert_int_equal(st, DP_ESYNTAX);
        assert_int_equal(e.n, 1);
        assert_string_equal(e.item[0].pointer, "");
        assert_string_equal(e.item[0].message, cases[i].message);
        dp_spec_clear(&s);
    }
}

/* ---- one reader for every route ---------------------------------------------------------------------- */

/* Every entry point that reads a body, the CLI's and the daemon's alike. */
static int route(int k, const char *text, size_t len, dp_errors *e)
{
    dp_buf out = { 0 };
    dp_spec s;
    dp_wp_report rep;
    dp_model m = { 0 };
    int st;
    dp_errors_init(e);
    switch (k) {
    case 0: dp_spec_init(&s); st = dp_spec_parse(text, len, 0, &s, e); dp_spec_clear(&s); break;
    case 1: st = dp_stability_respond(text, len, DP_STABILITY_JSON, &out, e); break;
    case 2: st = dp_lcp_respond(text, len, &out, e); break;
    case 3: st = dp_modes_respond(text, len, &out, e); break;
    case 4: st = dp_response_respond(text, len, DP_FORMAT_JSON, &out, e); break;
    case 5: st = dp_wellposedness_parse(text, len, &rep, e); break;
    default: st = dp_model_parse_lenient(text, len, &m, e); dp_model_clear(&m); break;
    }
    dp_buf_free(&out);
    return st;
}

#define ROUTES 7
static const char *const route_name[ROUTES] = { "simulate", "stability", "lcp", "modes", "response",
                                                "wellposedness", "lenient model" };

/* The same fault in a body gets the same status, pointer and words on every route: malformed JSON (one
 * error), a non-object document, too deep a nesting, a NUL in a key, a repeated key at any depth. */
static void test_same_words_on_every_route(void **state)
{
    (void)state;
    static const struct { const char *doc; size_t len; int status; const char *pointer, *message; } cases[] = {
        { "{\"model\": {\"mass\": NaN}}", 0, DP_ESYNTAX, "",
          "malformed JSON near byte 19 (line 1, column 20): JSON has no NaN or Infinity; send a number or null" },
        { "{\"M\": [[1]],\n \"q\": [1],}", 0, DP_ESYNTAX, "",
          "malformed JSON near byte 22 (line 2, column 10): a trailing comma before }; remove it" },
        { "{'mass': 1}", 0, DP_ESYNTAX, "",
          "malformed JSON near byte 1 (line 1, column 2): JSON keys take double quotes, not single quotes" },
        { "{\"model\": {}", 0, DP_ESYNTAX, "",
          "malformed JSON near byte 12 (line 1, column 13): the document ends early: the { at line 1, column 1 "
          "is never closed" },
        { "", 0, DP_ESYNTAX, "", "malformed JSON near byte 0 (line 1, column 1): empty document: send one JSON object" },
        { "[{\"model\": {}}]", 0, DP_EINVAL, "", "must be an object, got an array" },
        { "{\"x\": {\"y\": [{\"z\": 1, \"z\": 2}]}}", 0, DP_EINVAL, "/x/y/0/z", "duplicate key \"z\"" },
        { "{\"a/b\": 1, \"a/b\": 2}", 0, DP_EINVAL, "/a~1b", "duplicate key \"a/b\"" },
        { "{\"k\\u0000ey\": 1}", 0, DP_EINVAL, "",
          "a key of this object contains a NUL character (\\u0000), which no field may hold" },
        { "{\"x\": [\"a\\u0000\"]}", 0, DP_EINVAL, "/x/0",
          "this string contains a NUL character (\\u0000), which no field may hold" },
    };
    char deep[2 * (DP_JSON_MAX_DEPTH + 1) + 3];
    memset(deep, '[', DP_JSON_MAX_DEPTH + 1);
    memset(deep + DP_JSON_MAX_DEPTH + 1, ']', DP_JSON_MAX_DEPTH + 1);
    deep[2 * (DP_JSON_MAX_DEPTH + 1)] = '\0';
    for (size_t i = 0; i <= sizeof cases / sizeof cases[0]; i++) {
        int last = i == sizeof cases / sizeof cases[0];
        const char *doc = last ? deep : cases[i].doc;
        const char *pointer = last ? "" : cases[i].pointer;
        const char *message = last ? "malformed JSON near byte 64 (line 1, column 65): nested deeper than 64 levels"
                                   : cases[i].message;
        int status = last ? DP_ESYNTAX : cases[i].status;
        for (int k = 0; k < ROUTES; k++) {
            dp_errors e;
            int st = route(k, doc, strlen(doc), &e);
            if (st != status || !has_error(&e, pointer, message)) {
                print_error("%s, %s: status %d, expected %d with \"%s\" at \"%s\"\n", route_name[k], doc, st,
                            status, message, pointer);
                print_errors(&e);
            }
            assert_int_equal(st, status);
            assert_true(has_error(&e, pointer, message));
            if (status == DP_ESYNTAX || !strcmp(message, "must be an object, got an array"))
                assert_int_equal(e.n, 1);
        }
    }
}

/* Several independent mistakes are all reported, each at its own place. */
static void test_multiple_errors(void **state)
{
    (void)state;
    static const char *const want[][2] = {
        { "/model/mass", "must be a finite number > 0, got -1" },
        { "/model/damper/law", "unknown law \"colomb\"" },
        { "/model/forcing/points/1", "t must be strictly increasing" },
        { "/solver/dt", "must be a finite number > 0, got 0" },
        { "/solver/Z", "must be an integer in [1, 1000000], got 2.5" },
        { "/output/every", "must be an integer >= 1" },
        { "/bogus", "unknown key \"bogus\"" },
    };
    dp_spec s;
    dp_errors e;
    int st = parse_doc("{'model':{'mass':-1," SPRING_OK ",'damper':{'law':'colomb'},"
                       "'forcing':{'kind':'table','points':[[1,0],[0,1]]}},"
                       "'solver':{'dt':0,'Z':2.5},'output':{'every':0},'bogus':true}", 0, &s, &e);
    print_errors(&e);
    assert_int_equal(st, DP_EINVAL);
    assert_true(e.n >= 3);
    assert_int_equal(e.n, sizeof want / sizeof want[0]);
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
        if (!has_error(&e, want[i][0], want[i][1]))
            print_error("multiple errors: no error at %s containing \"%s\"\n", want[i][0], want[i][1]);
        assert_true(has_error(&e, want[i][0], want[i][1]));
    }
    dp_spec_clear(&s);
}

/* ---- the catalogue of invalid documents ------------------------------------------------------------- */

typedef struct row {
    const char *name;
    const char *doc;          /* ' for "; NULL: made by `make` */
    char *(*make)(void);
    int status;
    const char *pointer;      /* exact */
    const char *part;         /* a substring of that error's message */
    double max_steps;         /* 0: the default ceiling */
} row;

static char *deep_arrays(void)
{
    char *s = malloc(201);
    assert_non_null(s);
    memset(s, '[', 100);
    memset(s + 100, ']', 100);
    s[200] = '\0';
    return s;
}

static char *deep_in_model(void)
{
    /* Depth counted across the whole document: 2 objects + 63 arrays. */
    char *s = malloc(512);
    assert_non_null(s);
    size_t n = (size_t)snprintf(s, 512, "{'model':{'mass':");
    memset(s + n, '[', 63);
    memset(s + n + 63, ']', 63);
    snprintf(s + n + 126, 512 - n - 126, "}}");
    return s;
}

static char *too_many_points(void)
{
    size_t cap = 128 + (size_t)(DP_GRAPH_MAX_POINTS + 1) * 24;
    char *s = malloc(cap);
    assert_non_null(s);
    size_t n = (size_t)snprintf(s, cap, "%s", "{'model':{'mass':1," DAMPER_OK ",'spring':{'law':'graph','points':[");
    for (int i = 0; i <= DP_GRAPH_MAX_POINTS; i++)
        n += (size_t)snprintf(s + n, cap - n, "%s[%d,%d]", i ? "," : "", i, i);
    snprintf(s + n, cap - n, "]}}}");
    return s;
}

static char *sums_too_deep(void)
{
    return nested_sums(DP_FORCING_MAX_DEPTH);
}

#define DAMPER_LAWS "none, linear, coulomb, bingham, generalized-coulomb, graph"
#define GSPRING(pts) SPRING("{'law':'graph','points':" pts "}")

static const row rows[] = {
    /* syntax */
    { "malformed JSON", "{'model': }", NULL, DP_ESYNTAX, "", "malformed JSON near byte 10", 0 },
    { "truncated document", "{'model': {'mass': 1", NULL, DP_ESYNTAX, "", "malformed JSON near byte", 0 },
    { "trailing garbage", TOP("") " x", NULL, DP_ESYNTAX, "", "data after the document", 0 },
    { "two documents", "{} {}", NULL, DP_ESYNTAX, "", "malformed JSON near byte 3", 0 },
    { "empty document", "", NULL, DP_ESYNTAX, "", "empty document", 0 },
    { "only whitespace", "  \n ", NULL, DP_ESYNTAX, "", "malformed JSON", 0 },
    { "bare word", "nul", NULL, DP_ESYNTAX, "", "malformed JSON", 0 },
    { "100 nested arrays", NULL, deep_arrays, DP_ESYNTAX, "", "nested deeper than 64 levels", 0 },
    { "65 levels below the root", NULL, deep_in_model, DP_ESYNTAX, "", "nested deeper than 64", 0 },
    { "brackets inside strings do not nest", "{'model':'[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[["
      "[[[[[[[[[[[[[[[[[[[['}", NULL, DP_EINVAL, "/model", "must be an object, got a string", 0 },
    /* root and model */
    { "root is an array", "[1, 2]", NULL, DP_EINVAL, "", "must be an object, got an array", 0 },
    { "root is a number", "42", NULL, DP_EINVAL, "", "must be an object, got a number", 0 },
    { "missing model", "{}", NULL, DP_EINVAL, "/model", "missing required key \"model\"", 0 },
    { "model is null", "{'model':null}", NULL, DP_EINVAL, "/model", "must be an object, got null", 0 },
    { "missing mass", "{'model':{" SPRING_OK "," DAMPER_OK "}}", NULL, DP_EINVAL, "/model/mass",
      "missing required key \"mass\" (a finite number > 0)", 0 },
    { "missing spring", "{'model':{'mass':1," DAMPER_OK "}}", NULL, DP_EINVAL, "/model/spring",
      "missing required key \"spring\"", 0 },
    { "missing damper", "{'model':{'mass':1," SPRING_OK "}}", NULL, DP_EINVAL, "/model/damper",
      "missing required key \"damper\"", 0 },
    { "mass 0", "{'model':{'mass':0," SPRING_OK "," DAMPER_OK "}}", NULL, DP_EINVAL, "/model/mass",
      "must be a finite number > 0, got 0", 0 },
    { "mass negative", "{'model':{'mass':-1," SPRING_OK "," DAMPER_OK "}}", NULL, DP_EINVAL, "/model/mass",
      "must be a finite number > 0, got -1", 0 },
    { "mass a string", "{'model':{'mass':'1'," SPRING_OK "," DAMPER_OK "}}", NULL, DP_EINVAL, "/model/mass",
      "must be a finite number > 0, got a string", 0 },
    { "mass overflows", "{'model':{'mass':1e999," SPRING_OK "," DAMPER_OK "}}", NULL, DP_EINVAL, "/model/mass",
      "must be a finite number > 0, got a literal too large for a double", 0 },
    { "mass shown with round-trip digits", "{'model':{'mass':-0.1," SPRING_OK "," DAMPER_OK "}}", NULL,
      DP_EINVAL, "/model/mass", "got -0.1", 0 },
    /* springs */
    { "negative k", SPRING("{'law':'linear','k':-2}"), NULL, DP_EINVAL, "/model/spring/k",
      "must be a finite number >= 0, got -2", 0 },
    { "missing k", SPRING("{'law':'linear'}"), NULL, DP_EINVAL, "/model/spring/k", "missing required key \"k\"", 0 },
    { "rope without length", SPRING("{'law':'rope','k':1}"), NULL, DP_EINVAL, "/model/spring/length",
      "missing required key", 0 },
    { "missing law", SPRING("{'k':1}"), NULL, DP_EINVAL, "/model/spring/law",
      "missing required key \"law\" (one of: linear, rope, graph, elastoplastic)", 0 },
    { "law not a string", SPRING("{'law':1,'k':1}"), NULL, DP_EINVAL, "/model/spring/law",
      "must be a string, one of: linear, rope, graph, elastoplastic; got a number", 0 },
    { "unknown spring law", SPRING("{'law':'cubic','k':1}"), NULL, DP_EINVAL, "/model/spring/law",
      "unknown law \"cubic\"; expected one of: linear, rope, graph, elastoplastic", 0 },
    /* dampers */
    { "negative phi0", DAMPER("{'law':'coulomb','phi0':-1}"), NULL, DP_EINVAL, "/model/damper/phi0",
      "must be a finite number >= 0, got -1", 0 },
    { "negative tau", DAMPER("{'law':'bingham','tau':-1,'c':1}"), NULL, DP_EINVAL, "/model/damper/tau",
      ">= 0, got -1", 0 },
    { "negative bingham c", DAMPER("{'law':'bingham','tau':1,'c':-3}"), NULL, DP_EINVAL, "/model/damper/c",
      ">= 0, got -3", 0 },
    { "negative linear c", DAMPER("{'law':'linear','c':-0.5}"), NULL, DP_EINVAL, "/model/damper/c",
      ">= 0, got -0.5", 0 },
    { "phi1 < phi0", DAMPER("{'law':'generalized-coulomb','phi0':2,'phi1':1}"), NULL, DP_EINVAL,
      "/model/damper/phi1", "must be >= phi0 (2), got 1", 0 },
    { "unknown damper law", DAMPER("{'law':'colomb','phi0':1}"), NULL, DP_EINVAL, "/model/damper/law",
      "unknown law \"colomb\"; expected one of: " DAMPER_LAWS, 0 },
    { "belt_velocity a bool", DAMPER("{'law':'none','belt_velocity':true}"), NULL, DP_EINVAL,
      "/model/damper/belt_velocity", "must be a finite number, got a boolean", 0 },
    /* unknown and duplicate keys */
    { "unknown key at the root", TOP(",'modle':{}"), NULL, DP_EINVAL, "/modle",
      "unknown key \"modle\"; expected one of: model, initial, solver, output", 0 },
    { "unknown key in model", MODEL_WITH(",'masss':2"), NULL, DP_EINVAL, "/model/masss",
      "unknown key \"masss\"; expected one of: mass, spring, damper, forcing", 0 },
    { "key of another law", DAMPER("{'law':'coulomb','phi0':1,'c':2}"), NULL, DP_EINVAL, "/model/damper/c",
      "unknown key \"c\" for law \"coulomb\"; expected one of: law, phi0, relaxation, belt_velocity", 0 },
    { "theta with the analytic solver", TOP(",'solver':{'kind':'analytic','theta':1}"), NULL, DP_EINVAL,
      "/solver/theta", "for kind \"analytic\"; expected one of: kind, t_end, dt", 0 },
    { "unknown key in output", TOP(",'output':{'every':1,'format':'csv'}"), NULL, DP_EINVAL, "/output/format",
      "expected one of: every, max_samples, samples, events", 0 },
    { "unknown key in initial", TOP(",'initial':{'x0':1}"), NULL, DP_EINVAL, "/initial/x0",
      "expected one of: x, v", 0 },
    { "pointer escaping of a key", MODEL_WITH(",'a/b~c':1"), NULL, DP_EINVAL, "/model/a~1b~0c",
      "unknown key \"a/b~c\"", 0 },
    { "duplicate key", "{'model':{'mass':1,'mass':2," SPRING_OK "," DAMPER_OK "}}", NULL, DP_EINVAL,
      "/model/mass", "duplicate key \"mass\"", 0 },
    { "duplicate root key", TOP(",'output':{},'output':{}"), NULL, DP_EINVAL, "/output", "duplicate key", 0 },
    /* point lists */
    { "points not an array", GSPRING("5"), NULL, DP_EINVAL, "/model/spring/points",
      "must be an array of 2..10000 [x, F] pairs, got a number", 0 },
    { "missing points", SPRING("{'law':'graph'}"), NULL, DP_EINVAL, "/model/spring/points",
      "missing required key \"points\"", 0 },
    { "point not an array", GSPRING("[[0,0],{'x':1}]"), NULL, DP_EINVAL, "/model/spring/points/1",
      "must be a pair [x, F] of numbers, got an object", 0 },
    { "point with 3 numbers", GSPRING("[[0,0],[1,2,3]]"), NULL, DP_EINVAL, "/model/spring/points/1",
      "must have exactly 2 elements [x, F], got 3", 0 },
    { "point with 1 number", GSPRING("[[0,0],[1]]"), NULL, DP_EINVAL, "/model/spring/points/1",
      "got 1", 0 },
    { "point with a string", GSPRING("[[0,0],[1,'a']]"), NULL, DP_EINVAL, "/model/spring/points/1/1",
      "must be a finite number, got a string", 0 },
    { "point overflows", GSPRING("[[0,0],[1e400,1]]"), NULL, DP_EINVAL, "/model/spring/points/1/0",
      "too large for a double", 0 },
    { "unsorted x", GSPRING("[[0,0],[1,1],[0.5,2]]"), NULL, DP_EINVAL, "/model/spring/points/2",
      "x must be non-decreasing: 0.5 after 1", 0 },
    { "decreasing F", GSPRING("[[0,0],[1,1],[2,0.5]]"), NULL, DP_EINVAL, "/model/spring/points/2",
      "F must be non-decreasing: 0.5 after 1", 0 },
    { "repeated point", GSPRING("[[0,0],[0,0],[1,1]]"), NULL, DP_EINVAL, "/model/spring/points/1",
      "repeats the previous point (0, 0)", 0 },
    { "one graph point", GSPRING("[[0,0]]"), NULL, DP_EINVAL, "/model/spring/points", "got 1", 0 },
    { "10001 graph points", NULL, too_many_points, DP_EINVAL, "/model/spring/points", "got 10001", 0 },
    { "unsorted damper v", DAMPER("{'law':'graph','points':[[0,0],[-1,1]]}"), NULL, DP_EINVAL,
      "/model/damper/points/1", "v must be non-decreasing: -1 after 0", 0 },
    /* relaxation */
    { "relaxation b = 0", DAMPER("{'law':'coulomb','phi0':1,'relaxation':{'kind':'rational','a':1,'b':0}}"),
      NULL, DP_EINVAL, "/model/damper/relaxation/b", "must be a finite number > 0, got 0", 0 },
    { "power N = 1", DAMPER("{'law':'coulomb','phi0':1,'relaxation':{'kind':'power','N':1}}"), NULL, DP_EINVAL,
      "/model/damper/relaxation/N", "must be a finite number > 1, got 1", 0 },
    { "power N < 1", DAMPER("{'law':'coulomb','phi0':1,'relaxation':{'kind':'power','N':0.5}}"), NULL,
      DP_EINVAL, "/model/damper/relaxation/N", "> 1, got 0.5", 0 },
    { "unknown relaxation kind", DAMPER("{'law':'coulomb','phi0':1,'relaxation':{'kind':'cubic'}}"), NULL,
      DP_EINVAL, "/model/damper/relaxation/kind",
      "unknown kind \"cubic\"; expected one of: rational, linear, power", 0 },
    { "relaxation not an object", DAMPER("{'law':'coulomb','phi0':1,'relaxation':'rational'}"), NULL,
      DP_EINVAL, "/model/damper/relaxation", "must be an object, got a string", 0 },
    /* forcing */
    { "table t unsorted", FORCING("{'kind':'table','points':[[0,0],[2,1],[1,2]]}"), NULL, DP_EINVAL,
      "/model/forcing/points/2", "t must be strictly increasing: 1 after 2", 0 },
    { "table t repeated", FORCING("{'kind':'table','points':[[0,0],[0,1]]}"), NULL, DP_EINVAL,
      "/model/forcing/points/1", "t must be strictly increasing: 0 after 0", 0 },
    { "empty table", FORCING("{'kind':'table','points':[]}"), NULL, DP_EINVAL, "/model/forcing/points",
      "must be an array of 1..10000 [t, F] pairs, got 0", 0 },
    { "empty sum", FORCING("{'kind':'sum','terms':[]}"), NULL, DP_EINVAL, "/model/forcing/terms",
      "must be an array of 1..64 forcings, got 0", 0 },
    { "sum too deep", NULL, sums_too_deep, DP_EINVAL,
      "/model/forcing/terms/0/terms/0/terms/0/terms/0/terms/0/terms/0/terms/0/terms",
      "sums nest at most 8 deep", 0 },
    { "bad term in a sum", FORCING("{'kind':'sum','terms':[{'kind':'constant','value':1},{'kind':'step'}]}"),
      NULL, DP_EINVAL, "/model/forcing/terms/1/kind", "expected one of: constant, harmonic, table, sum", 0 },
    { "harmonic without omega", FORCING("{'kind':'harmonic','amplitude':1}"), NULL, DP_EINVAL,
      "/model/forcing/omega", "missing required key \"omega\"", 0 },
    { "forcing without kind", FORCING("{'value':1}"), NULL, DP_EINVAL, "/model/forcing/kind",
      "missing required key \"kind\"", 0 },
    /* initial */
    { "initial x a string", TOP(",'initial':{'x':'0'}"), NULL, DP_EINVAL, "/initial/x",
      "must be a finite number, got a string", 0 },
    { "initial an array", TOP(",'initial':[0,0]"), NULL, DP_EINVAL, "/initial", "must be an object", 0 },
    /* solver */
    { "dt = 0", TOP(",'solver':{'dt':0}"), NULL, DP_EINVAL, "/solver/dt", "must be a finite number > 0, got 0", 0 },
    { "dt < 0", TOP(",'solver':{'dt':-1e-3}"), NULL, DP_EINVAL, "/solver/dt", "> 0, got -0.001", 0 },
    { "t_end = 0", TOP(",'solver':{'t_end':0}"), NULL, DP_EINVAL, "/solver/t_end", "> 0, got 0", 0 },
    { "t_end < 0 (analytic)", TOP(",'solver':{'kind':'analytic','t_end':-1}"), NULL, DP_EINVAL,
      "/solver/t_end", "> 0, got -1", 0 },
    { "theta 0.3", TOP(",'solver':{'theta':0.3}"), NULL, DP_EINVAL, "/solver/theta",
      "must be a finite number in [0.5, 1], got 0.3", 0 },
    { "theta 1.5", TOP(",'solver':{'theta':1.5}"), NULL, DP_EINVAL, "/solver/theta", "in [0.5, 1], got 1.5", 0 },
    { "unknown variant", TOP(",'solver':{'variant':'fast'}"), NULL, DP_EINVAL, "/solver/variant",
      "unknown variant \"fast\"; expected one of: exact, thesis", 0 },
    { "unknown solver kind", TOP(",'solver':{'kind':'rk4'}"), NULL, DP_EINVAL, "/solver/kind",
      "unknown kind \"rk4\"; expected one of: stick-slip, analytic", 0 },
    { "unknown events mode", TOP(",'solver':{'events':'all'}"), NULL, DP_EINVAL, "/solver/events",
      "expected one of: locate, none", 0 },
    { "Z = 0", TOP(",'solver':{'Z':0}"), NULL, DP_EINVAL, "/solver/Z", "must be an integer in [1, 1000000], got 0", 0 },
    { "Z = 2.5", TOP(",'solver':{'Z':2.5}"), NULL, DP_EINVAL, "/solver/Z", "integer in [1, 1000000], got 2.5", 0 },
    { "Z too large", TOP(",'solver':{'Z':1e7}"), NULL, DP_EINVAL, "/solver/Z", "got 10000000", 0 },
    { "eps = 0", TOP(",'solver':{'eps':0}"), NULL, DP_EINVAL, "/solver/eps", "> 0, got 0", 0 },
    /* the regularized solver */
    { "n = 0", TOP(",'solver':{'kind':'regularized','n':0}"), NULL, DP_EINVAL, "/solver/n",
      "must be a finite number > 0, got 0", 0 },
    { "n a string", TOP(",'solver':{'kind':'regularized','n':'100'}"), NULL, DP_EINVAL, "/solver/n",
      "must be a finite number > 0 or an array of 1..16 of them, got a string", 0 },
    { "n an empty array", TOP(",'solver':{'kind':'regularized','n':[]}"), NULL, DP_EINVAL, "/solver/n",
      "got 0 elements", 0 },
    { "n with 17 values", TOP(",'solver':{'kind':'regularized','n':[1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17]}"),
      NULL, DP_EINVAL, "/solver/n", "array of 1..16 of them, got 17 elements", 0 },
    { "n decreasing", TOP(",'solver':{'kind':'regularized','n':[10,100,100]}"), NULL, DP_EINVAL, "/solver/n/2",
      "must be strictly increasing: 100 after 100", 0 },
    { "n element negative", TOP(",'solver':{'kind':'regularized','n':[10,-1]}"), NULL, DP_EINVAL, "/solver/n/1",
      "must be a finite number > 0, got -1", 0 },
    { "k with scheme PC", TOP(",'solver':{'kind':'regularized','k':100}"), NULL, DP_EINVAL, "/solver/k",
      "\"k\" belongs to scheme PI; scheme PC takes \"n\"", 0 },
    { "n with scheme PI", TOP(",'solver':{'kind':'regularized','scheme':'PI','n':100}"), NULL, DP_EINVAL,
      "/solver/n", "\"n\" belongs to scheme PC; scheme PI takes \"k\"", 0 },
    { "unknown scheme", TOP(",'solver':{'kind':'regularized','scheme':'PCn'}"), NULL, DP_EINVAL,
      "/solver/scheme", "unknown scheme \"PCn\"; expected one of: PC, PI", 0 },
    { "unknown stepper", TOP(",'solver':{'kind':'regularized','stepper':'rk4'}"), NULL, DP_EINVAL,
      "/solver/stepper", "expected one of: msbdf, rk4imp, bsimp, rkf45, rkck, rk8pd", 0 },
    { "rtol < 0", TOP(",'solver':{'kind':'regularized','rtol':-1e-8}"), NULL, DP_EINVAL, "/solver/rtol",
      "must be a finite number >= 0, got -1e-08", 0 },
    { "rtol and atol 0", TOP(",'solver':{'kind':'regularized','rtol':0,'atol':0}"), NULL, DP_EINVAL,
      "/solver/rtol", "not both 0", 0 },
    { "theta with regularized", TOP(",'solver':{'kind':'regularized','theta':0.5}"), NULL, DP_EINVAL,
      "/solver/theta", "unknown key \"theta\" for kind \"regularized\"", 0 },
    { "regularized generalized coulomb", "{'model':{'mass':1," SPRING_OK ",'damper':{'law':'generalized-coulomb',"
      "'phi0':1,'phi1':2}},'solver':{'kind':'regularized'}}", NULL, DP_EINVAL, "/model/damper/law",
      "generalized-coulomb (phi1 > phi0) is not monotone", 0 },
    { "regularized power relaxation", "{'model':{'mass':1," SPRING_OK ",'damper':{'law':'coulomb','phi0':1,"
      "'relaxation':{'kind':'power','N':2}}},'solver':{'kind':'regularized'}}", NULL, DP_EINVAL,
      "/model/damper/relaxation", "not Lipschitz at 0", 0 },
    { "PI with relaxation", "{'model':{'mass':1," SPRING_OK ",'damper':{'law':'coulomb','phi0':1,"
      "'relaxation':{'kind':'linear','L':0.1}}},'solver':{'kind':'regularized','scheme':'PI'}}", NULL,
      DP_EINVAL, "/model/damper/relaxation", "has no relaxation; use scheme PC", 0 },
    /* output */
    { "every = 0", TOP(",'output':{'every':0}"), NULL, DP_EINVAL, "/output/every", "must be an integer >= 1", 0 },
    { "every = 1.5", TOP(",'output':{'every':1.5}"), NULL, DP_EINVAL, "/output/every", "got 1.5", 0 },
    { "samples not a bool", TOP(",'output':{'samples':'yes'}"), NULL, DP_EINVAL, "/output/samples",
      "must be true or false, got a string", 0 },
    { "events a number", TOP(",'output':{'events':1}"), NULL, DP_EINVAL, "/output/events",
      "must be true or false, got a number", 0 },
    /* the core's cross-field rules (src/core/rules/spec.c dp_spec_check) */
    { "steps over the hard ceiling", TOP(",'solver':{'t_end':1e6,'dt':1e-6}"), NULL, DP_ELIMIT, "/solver/dt",
      "exceeds the limit", 1e9 },
    { "steps over a front end's limit", TOP(",'solver':{'t_end':10,'dt':1e-3}"), NULL, DP_ELIMIT, "/solver/dt",
      "exceeds the limit of 1000 steps", 1000 },
    { "x0 beyond the rope", "{'model':{'mass':1,'spring':{'law':'rope','k':1,'length':0.5}," DAMPER_OK "},"
      "'initial':{'x':1}}", NULL, DP_EINVAL, "/initial/x", "inextensible", 0 },
    { "analytic with a graph damper", "{'model':{'mass':1," SPRING_OK ",'damper':{'law':'graph','points':"
      "[[0,0],[1,1]]}},'solver':{'kind':'analytic'}}", NULL, DP_EINVAL, "/model/damper/law",
      "the analytic solver needs a coulomb", 0 },
    /* k = 5.6e53: half-period 4.2e-27, 4.8e27 turning points by t = 20, and below the rounding of t the clock
     * stopped: the run never ended (tests/fuzz/fuzz_spec.c). Far from rest with phi0 tiny, also by rest. */
    { "analytic with more turning points than steps", "{'model':{'mass':1,'spring':{'law':'linear','k':5.6e53},"
      "'damper':{'law':'coulomb','phi0':0.4}},'initial':{'x':-2},'solver':{'kind':'analytic','dt':0.01,"
      "'t_end':20}}", NULL, DP_ELIMIT, "/model/spring/k", "turning points by t_end", 0 },
    { "analytic turning points over a front end's limit", "{'model':{'mass':1,'spring':{'law':'linear','k':1e6},"
      "'damper':{'law':'coulomb','phi0':1e-9}},'initial':{'x':1},'solver':{'kind':'analytic','dt':1,"
      "'t_end':1000}}", NULL, DP_ELIMIT, "/model/spring/k", "over the limit of 1000 per run", 1000 },
};

/* The row at *state: parse, then the status, an error at the exact pointer with the message part. */
static void run_row(void **state)
{
    const row *r = *state;
    char *made = r->make ? r->make() : NULL;
    dp_spec s;
    dp_errors e;
    int st = parse_doc(made ? made : r->doc, r->max_steps, &s, &e);
    int found = has_error(&e, r->pointer, r->part);
    if (st != r->status || !found) {
        print_error("row \"%s\": expected status %d with an error at \"%s\" containing \"%s\"; got status %d (%s)\n",
                    r->name, r->status, r->pointer, r->part, st, dp_strerror(st));
        print_errors(&e);
    }
    if (st == DP_ESYNTAX)
        assert_int_equal(e.n, 1);          /* malformed: exactly one error, about the document */
    assert_int_equal(st, r->status);
    assert_true(found);
    dp_spec_clear(&s);
    free(made);
}

int main(void)
{
    static const struct CMUnitTest fixed[] = {
        cmocka_unit_test(test_architecture_example),
        cmocka_unit_test(test_spring_laws),
        cmocka_unit_test(test_damper_laws),
        cmocka_unit_test(test_relaxation_kinds),
        cmocka_unit_test(test_forcing_kinds),
        cmocka_unit_test(test_forcing_depth_limit_ok),
        cmocka_unit_test(test_solver_initial_output),
        cmocka_unit_test(test_regularized_fields),
        cmocka_unit_test(test_length_not_nul),
        cmocka_unit_test(test_depth_boundary),
        cmocka_unit_test(test_malformed_where_and_why),
        cmocka_unit_test(test_cut_literal_reads_no_further),
        cmocka_unit_test(test_same_words_on_every_route),
        cmocka_unit_test(test_multiple_errors),
    };
    size_t nf = sizeof fixed / sizeof fixed[0], nr = sizeof rows / sizeof rows[0];
    struct CMUnitTest *tests = calloc(nf + nr, sizeof *tests);
    if (tests == NULL)
        return 1;
    memcpy(tests, fixed, sizeof fixed);
    for (size_t i = 0; i < nr; i++)
        tests[nf + i] = (struct CMUnitTest){ rows[i].name, run_row, NULL, NULL, (void *)&rows[i] };
    int failed = _cmocka_run_group_tests("spec", tests, nf + nr, NULL, NULL);
    free(tests);
    return failed;
}
