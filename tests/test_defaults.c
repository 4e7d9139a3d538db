/* tests/test_defaults.c - what dashpot chooses for a document that leaves a member out, and what it warns
 * about (include/dashpot/spec.h dp_spec_choose, include/dashpot/warnings.h):
 *   - theta: 1/2 (second order) where the model's rules allow it, else 1; an explicit theta is kept;
 *   - output.every: a budget of DP_SPEC_SAMPLE_BUDGET samples when neither every nor max_samples is given;
 *   - the coarse-step warning: dt > T_min / 10, T_min = 2 pi / omega_max, omega_max bounded from above by
 *     Gershgorin's theorem; checked against the exact omega_max of systems whose spectrum is known.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "check.h"
#include "dashpot/json.h"
#include "dashpot/run.h"
#include "dashpot/warnings.h"

/* Parses a valid document (' for ") into s; the caller clears it. */
static void parse(const char *doc, dp_spec *s)
{
    char *text = strdup(doc);
    assert_non_null(text);
    for (char *p = text; *p; p++)
        if (*p == '\'')
            *p = '"';
    dp_errors e;
    dp_errors_init(&e);
    dp_spec_init(s);
    int st = dp_spec_parse(text, strlen(text), 0, s, &e);
    for (size_t i = 0; i < e.n; i++)
        print_error("  %s: %s\n", e.item[i].pointer, e.item[i].message);
    free(text);
    assert_int_equal(st, DP_OK);
}

/* The warnings of a document. */
static void warnings_of(const char *doc, dp_warnings *w)
{
    dp_spec s;
    parse(doc, &s);
    dp_spec_warnings(&s, w);
    dp_spec_clear(&s);
}

/* omega_max from the warning's text ("omega_max <= X"), to compare the bound with the exact value. */
static double omega_bound(const dp_warning *w)
{
    const char *p = strstr(w->detail, "omega_max <= ");
    assert_non_null(p);
    return strtod(p + strlen("omega_max <= "), NULL);
}

#define ONE_MASS(m, k, dt, kind)                                                                             \
    "{'model': {'mass': " #m ", 'spring': {'law': 'linear', 'k': " #k "}, 'damper': {'law': 'coulomb', "      \
    "'phi0': 0.1}}, 'initial': {'x': 1}, 'solver': {'kind': '" kind "', 'dt': " #dt ", 't_end': 1}}"

/* The user's report: m = 0.001, k = 1e6, dt = 1e-3 spans 5.03 periods of 2 pi sqrt(m/k) = 1.987e-4. */
static void test_coarse_one_mass(void **state)
{
    (void)state;
    dp_warnings w;
    warnings_of(ONE_MASS(0.001, 1e6, 1e-3, "stick-slip"), &w);
    assert_int_equal(w.n, 1);
    assert_string_equal(w.item[0].code, "coarse-step");
    assert_string_equal(w.item[0].pointer, "/solver/dt");
    CHECK(strstr(w.item[0].detail, "is 5.03 of the shortest natural period") != NULL, "%s", w.item[0].detail);
    NEAR(omega_bound(&w.item[0]), sqrt(1e9), 1e-6 * sqrt(1e9));   /* one mass: the bound is exact */
    warnings_of("{'model': {'mass': 0.001, 'spring': {'law': 'linear', 'k': 1e6}, 'damper': {'law': 'linear',"
                " 'c': 0.1}}, 'initial': {'x': 1}, 'solver': {'kind': 'newmark', 'dt': 1e-3, 't_end': 1}}",
                &w);                                              /* Newmark steps at a fixed dt too */
    assert_int_equal(w.n, 1);
}

/* m = k = 1: T = 2 pi; dt = T/10 is the last step that is not warned about. */
static void test_coarse_threshold(void **state)
{
    (void)state;
    dp_warnings w;
    warnings_of(ONE_MASS(1, 1, 0.6283185307179586, "stick-slip"), &w);
    assert_int_equal(w.n, 0);
    warnings_of(ONE_MASS(1, 1, 0.6284, "stick-slip"), &w);
    assert_int_equal(w.n, 1);
    warnings_of(ONE_MASS(1, 1, 1e-3, "stick-slip"), &w);
    assert_int_equal(w.n, 0);
}

/* The solvers that choose their own steps, and laws without a stiffness, are not judged. */
static void test_coarse_not_judged(void **state)
{
    (void)state;
    dp_warnings w;
    warnings_of(ONE_MASS(0.001, 1e6, 1e-3, "regularized"), &w);
    assert_int_equal(w.n, 0);
    warnings_of("{'model': {'mass': 0.001, 'spring': {'law': 'graph', 'points': [[-1, -1e6], [1, 1e6]]}, "
                "'damper': {'law': 'none'}}, "
                "'solver': {'dt': 1e-3, 't_end': 1}}", &w);
    assert_int_equal(w.n, 0);
}

/* A fixed-free chain of 3 unit masses and unit springs: omega_j = 2 sin((2j - 1) pi / 14), the largest
 * 2 sin(5 pi / 14) = 1.8019; Gershgorin bounds omega_max^2 by the largest row sum, 4. So the bound is above
 * the truth and within sqrt(2) of it, and dt = 0.33 (above pi/10 = 0.314, below the true T/10 = 0.349) is
 * warned about: the estimate errs towards warning. */
static void test_coarse_chain(void **state)
{
    (void)state;
    const char *chain =
        "{'model': {'masses': [1, 1, 1], 'elements': ["
        "{'between': ['ground', 0], 'spring': {'law': 'linear', 'k': 1}},"
        "{'between': [0, 1], 'spring': {'law': 'linear', 'k': 1}},"
        "{'between': [1, 2], 'spring': {'law': 'linear', 'k': 1}}]},"
        "'initial': {'x': [0, 0, 1], 'v': [0, 0, 0]}, 'solver': {'dt': %s, 't_end': 1}}";
    char doc[1024];
    dp_warnings w;
    double exact = 2 * sin(5 * M_PI / 14);
    snprintf(doc, sizeof doc, chain, "0.33");
    warnings_of(doc, &w);
    assert_int_equal(w.n, 1);
    double bound = omega_bound(&w.item[0]);
    CHECK(bound >= exact && bound <= sqrt(2) * exact, "bound %g, exact %g", bound, exact);
    NEAR(bound, 2, 1e-5);
    snprintf(doc, sizeof doc, chain, "0.3");
    warnings_of(doc, &w);
    assert_int_equal(w.n, 0);
}

/* A mass matrix: M = [[2, .5], [.5, 2]], K = [[3, -1], [-1, 3]] share the eigenvectors (1, 1), (1, -1):
 * omega^2 = 2/2.5 = 0.8 and 4/1.5 = 2.667 exactly. Gershgorin: (3 + 1) / (2 - 0.5) = 2.667, here exact. */
static void test_coarse_mass_matrix(void **state)
{
    (void)state;
    dp_warnings w;
    warnings_of("{'model': {'mass_matrix': [[2, 0.5], [0.5, 2]], 'stiffness_matrix': [[3, -1], [-1, 3]]},"
                "'initial': {'x': [1, 0], 'v': [0, 0]}, 'solver': {'dt': 0.5, 't_end': 1}}", &w);
    assert_int_equal(w.n, 1);
    NEAR(omega_bound(&w.item[0]), sqrt(4 / 1.5), 1e-5);
}

/* theta left out: 1/2 where the rules allow theta < 1, else 1; the meta line says it was chosen. */
static void test_default_theta(void **state)
{
    (void)state;
    static const struct { const char *doc; double theta; } rows[] = {
        { "{'model': {'mass': 1, 'spring': {'law': 'linear', 'k': 1}, 'damper': {'law': 'coulomb', 'phi0': 1}}}", 0.5 },
        { "{'model': {'mass': 1, 'spring': {'law': 'elastoplastic', 'k': 1, 'yield': 1}, 'damper': {'law': 'none'}}}", 0.5 },
        { "{'model': {'mass': 1, 'spring': {'law': 'rope', 'k': 1, 'length': 2}, 'damper': {'law': 'none'}}}", 1 },
        { "{'model': {'mass': 1, 'spring': {'law': 'graph', 'points': [[-1, -1], [1, 1]]}, 'damper': {'law': 'none'}}}", 1 },
        { "{'model': {'mass': 1, 'spring': {'law': 'linear', 'k': 1}, 'damper': {'law': 'coulomb', 'phi0': 1}},"
          " 'solver': {'variant': 'thesis'}}", 1 },
        { "{'model': {'mass': 1, 'spring': {'law': 'linear', 'k': 1}, 'damper': {'law': 'none'}}, 'solver': {'theta': 1}}", 1 },
        { "{'model': {'mass': 1, 'spring': {'law': 'linear', 'k': 1}, 'damper': {'law': 'none'}}, 'solver': {'theta': 0.75}}", 0.75 },
        /* a network's rope: with events located a linear spring and the contact u <= L, any theta; without,
         * its graph by backward Euler */
        { "{'model': {'masses': [1], 'elements': [{'between': ['ground', 0], 'spring': {'law': 'rope', 'k': 1,"
          " 'length': 1}}, {'between': ['ground', 0], 'spring': {'law': 'linear', 'k': 1}}]},"
          " 'initial': {'x': [0], 'v': [0]}}", 0.5 },
        { "{'model': {'masses': [1], 'elements': [{'between': ['ground', 0], 'spring': {'law': 'rope', 'k': 1,"
          " 'length': 1}}, {'between': ['ground', 0], 'spring': {'law': 'linear', 'k': 1}}]},"
          " 'initial': {'x': [0], 'v': [0]}, 'solver': {'events': 'none'}}", 1 },
        { "{'model': {'masses': [1], 'elements': [{'between': ['ground', 0], 'spring': {'law': 'rope', 'k': 1,"
          " 'length': 1}}, {'between': ['ground', 0], 'spring': {'law': 'graph', 'points': [[-1, -1], [0, 0],"
          " [0, 0.5], [1, 1]]}}]}, 'initial': {'x': [0], 'v': [0]}}", 0.5 },
        { "{'model': {'masses': [1], 'elements': [{'between': ['ground', 0], 'spring': {'law': 'rope', 'k': 1,"
          " 'length': 1}}, {'between': ['ground', 0], 'spring': {'law': 'graph', 'points': [[-1, -1], [0, 0],"
          " [0, 0.5], [1, 1]]}}]}, 'initial': {'x': [0], 'v': [0]}, 'solver': {'events': 'none'}}", 1 },
        { "{'model': {'masses': [1], 'elements': [{'between': ['ground', 0], 'spring': {'law': 'rope', 'k': 1,"
          " 'length': 1}}, {'between': ['ground', 0], 'spring': {'law': 'graph', 'points': [[-1, -1], [1, 1]]}}]},"
          " 'initial': {'x': [0], 'v': [0]}}", 0.5 },
        { "{'model': {'masses': [1, 1], 'elements': [{'between': ['ground', 0], 'spring': {'law': 'linear',"
          " 'k': 1}}, {'between': [0, 1], 'damper': {'law': 'coulomb', 'phi0': 1}}]},"
          " 'initial': {'x': [0, 0], 'v': [0, 0]}}", 0.5 },
        /* a network theta-steps a graph spring of finite slope and a compliant contact (network_smooth.c) */
        { "{'model': {'masses': [1], 'elements': [{'between': ['ground', 0], 'spring': {'law': 'graph',"
          " 'points': [[-1, -2], [0, 0], [1, 1]]}}, {'between': ['ground', 0], 'contact': {'distance': -1,"
          " 'compliance': 100}}]}, 'initial': {'x': [0], 'v': [0]}}", 0.5 },
    };
    for (size_t i = 0; i < sizeof rows / sizeof *rows; i++) {
        dp_spec s;
        parse(rows[i].doc, &s);
        CHECK(s.solver.theta == rows[i].theta, "row %zu: theta %g, expected %g", i, s.solver.theta, rows[i].theta);
        int given = strstr(rows[i].doc, "'theta'") != NULL;
        CHECK(((s.chosen & DP_CHOSEN_THETA) != 0) == !given, "row %zu: chosen %u", i, s.chosen);
        dp_spec_clear(&s);
    }
}

/* Samples of a run, counted by pulling it through. */
static unsigned long long samples_of(const char *doc)
{
    dp_spec s;
    parse(doc, &s);
    dp_errors e;
    dp_errors_init(&e);
    int st;
    dp_run *r = dp_run_alloc(&s, 0, &e, &st);
    assert_non_null(r);
    dp_record buf[512];
    size_t n;
    while ((st = dp_run_next(r, buf, 512, &n)) == DP_MORE)
        ;
    assert_int_equal(st, DP_DONE);
    unsigned long long k = dp_run_summary(r)->samples;
    dp_run_free(r);
    dp_spec_clear(&s);
    return k;
}

/* 10^5 steps and no output member: every = ceil(10^5 / 10^4) = 10, so 10 001 samples (the first and one per
 * 10 steps); an explicit every is obeyed; a run of 10^4 steps keeps every step. */
static void test_sample_budget(void **state)
{
    (void)state;
    const char *base = "{'model': {'mass': 1, 'spring': {'law': 'linear', 'k': 1}, 'damper': {'law': 'coulomb', 'phi0': 0.01}},"
                       " 'initial': {'x': 1}, 'solver': {'dt': 1e-3, 't_end': %s}%s}";
    char doc[512];
    dp_spec s;
    snprintf(doc, sizeof doc, base, "100", "");
    parse(doc, &s);
    assert_int_equal(s.output.every, 10);
    CHECK(s.chosen & DP_CHOSEN_EVERY, "chosen %u", s.chosen);
    dp_spec_clear(&s);
    unsigned long long k = samples_of(doc);
    CHECK(k <= DP_SPEC_SAMPLE_BUDGET && k == 10001, "%llu samples", k);
    snprintf(doc, sizeof doc, base, "100", ", 'output': {'every': 1}");
    assert_int_equal(samples_of(doc), 100001);
    snprintf(doc, sizeof doc, base, "10", "");
    parse(doc, &s);
    assert_int_equal(s.output.every, 1);
    dp_spec_clear(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_coarse_one_mass),  cmocka_unit_test(test_coarse_threshold),
        cmocka_unit_test(test_coarse_not_judged), cmocka_unit_test(test_coarse_chain),
        cmocka_unit_test(test_coarse_mass_matrix), cmocka_unit_test(test_default_theta),
        cmocka_unit_test(test_sample_budget),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
