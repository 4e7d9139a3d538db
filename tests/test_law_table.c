/* tests/test_law_table.c - the law table (src/core/laws/law_table.c, src/core/lcp/lcs_laws.c) is complete and
 * consistent, and it alone decides: every law has an entry under its own enum value with a name, a builder and
 * members the parser reads into the fields they name; every property that names a field names a member; the
 * closed-form stick-slip path is taken exactly by the entries that say closed_form = 1, and a law value
 * without an entry is refused instead of being stepped in the closed form (which reads tau and c and never
 * the graph, so it would silently ignore the law). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "dashpot/json.h"
#include "dashpot/lcs.h"
#include "dashpot/model.h"
#include "trajectory.h"

static size_t nmembers(const dp_law_row *row)
{
    size_t n = 0;
    while (row->members[n].key)
        n++;
    return n;
}

/* A row's own checks: its name, members inside the struct and distinct, a field property naming a member. */
static void check_row(const dp_law_row *row, int law, size_t size)
{
    assert_int_equal(row->law, law);
    assert_non_null(row->name);
    assert_true(row->name[0] != '\0');
    size_t n = nmembers(row);
    assert_true(n <= DP_LAW_MAX_MEMBERS);
    for (size_t i = 0; i < n; i++) {
        const dp_law_member *m = &row->members[i];
        assert_true(m->offset > 0 && m->offset + sizeof(double) <= size);
        assert_true(m->offset % sizeof(double) == 0);
        assert_true(m->bound == DP_MEMBER_ANY || m->bound == DP_MEMBER_NONNEG || m->bound == DP_MEMBER_POSITIVE);
        assert_true(m->required || isfinite(m->def));
        for (size_t j = 0; j < i; j++) {
            assert_string_not_equal(row->members[j].key, m->key);
            assert_true(row->members[j].offset != m->offset);
        }
        assert_ptr_equal(dp_law_member_key(row, m->offset), m->key);
    }
    assert_true(row->points == NULL || n == 0);   /* a user graph is its points alone */
}

static void names_distinct(const char *const *names, size_t n)
{
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < i; j++)
            assert_string_not_equal(names[i], names[j]);
}

static void test_entries_complete(void **state)
{
    (void)state;
    const char *names[16];
    for (int i = 0; i < DP_SPRING_LAW_COUNT; i++) {
        const dp_spring_law_info *L = dp_spring_law_info_of((dp_spring_law)i);
        assert_ptr_equal(L, &dp_spring_laws[i]);
        check_row(&L->row, i, sizeof(dp_spring));
        assert_non_null(L->build);
        assert_string_equal(dp_spring_law_name((dp_spring_law)i), L->row.name);
        assert_true(L->x_max == 0 || dp_law_member_key(&L->row, L->x_max) != NULL);
        assert_false(L->linear && L->plastic);
        assert_true(!L->locate_network || L->locate);
        names[i] = L->row.name;
    }
    names_distinct(names, DP_SPRING_LAW_COUNT);
    for (int i = 0; i < DP_DAMPER_LAW_COUNT; i++) {
        const dp_damper_law_info *L = dp_damper_law_info_of((dp_damper_law)i);
        assert_ptr_equal(L, &dp_damper_laws[i]);
        check_row(&L->row, i, sizeof(dp_damper));
        assert_non_null(L->build);
        assert_string_equal(dp_damper_law_name((dp_damper_law)i), L->row.name);
        dp_law_field fields[3] = { L->viscous, L->kinetic, L->static_threshold };
        for (int f = 0; f < 3; f++)
            assert_true(fields[f] == 0 || dp_law_member_key(&L->row, fields[f]) != NULL);
        assert_true(L->static_threshold == 0 || L->kinetic != 0);   /* a static threshold above a kinetic one */
        assert_true(!L->linear || (L->kinetic == 0 && L->row.points == NULL));
        /* the closed form reads tau and c only: a user graph can never take it */
        assert_true(!L->closed_form || L->row.points == NULL);
        names[i] = L->row.name;
    }
    names_distinct(names, DP_DAMPER_LAW_COUNT);
    for (int i = 0; i < DP_LCS_LAW_COUNT; i++) {
        const dp_lcs_law_info *L = dp_lcs_law_info_of((dp_lcs_law_kind)i);
        assert_ptr_equal(L, &dp_lcs_laws[i]);
        check_row(&L->row, i, sizeof(dp_lcs_law));
        assert_true(L->shape == DP_LCS_SHAPE_CONE || L->shape == DP_LCS_SHAPE_INTERVAL ||
                    L->shape == DP_LCS_SHAPE_GRAPH);
        /* a graph law has its points or a builder, exactly one of them; the others neither */
        if (L->shape == DP_LCS_SHAPE_GRAPH)
            assert_true((L->row.points != NULL) != (L->build != NULL));
        else
            assert_true(L->row.points == NULL && L->build == NULL);
        if (L->shape == DP_LCS_SHAPE_INTERVAL) {
            assert_non_null(dp_law_member_key(&L->row, offsetof(dp_lcs_law, lo)));
            assert_non_null(dp_law_member_key(&L->row, offsetof(dp_lcs_law, hi)));
        }
        names[i] = L->row.name;
    }
    names_distinct(names, DP_LCS_LAW_COUNT);
    /* values that are no law have no entry */
    assert_null(dp_spring_law_info_of(DP_SPRING_LAW_COUNT));
    assert_null(dp_damper_law_info_of(DP_DAMPER_LAW_COUNT));
    assert_null(dp_lcs_law_info_of(DP_LCS_LAW_COUNT));
}

/* Each law's members with values 1, 2, ... (a user graph: three points) as JSON members. */
static void members_json(const dp_law_row *row, char *out, size_t cap, const char *skip)
{
    size_t len = (size_t)snprintf(out, cap, "{\"law\":\"%s\"", row->name);
    for (size_t i = 0; row->members[i].key; i++)
        if (skip == NULL || strcmp(skip, row->members[i].key) != 0)
            len += (size_t)snprintf(out + len, cap - len, ",\"%s\":%zu", row->members[i].key, i + 1);
    if (row->points)
        len += (size_t)snprintf(out + len, cap - len, ",\"points\":[[-1,-1],[0,0],[1,1]]");
    snprintf(out + len, cap - len, "}");
}

static int parse(const char *doc, dp_spec *spec, dp_errors *errs)
{
    dp_spec_init(spec);
    dp_errors_init(errs);
    return dp_spec_parse(doc, strlen(doc), 0, spec, errs);
}

/* The parser reads every member of every law into the field its row names, and misses none. */
static void test_parser_reads_the_rows(void **state)
{
    (void)state;
    char law[256], doc[1024];
    dp_spec spec;
    dp_errors errs;
    for (int part = 0; part < 2; part++) {
        int n = part ? DP_DAMPER_LAW_COUNT : DP_SPRING_LAW_COUNT;
        for (int i = 0; i < n; i++) {
            const dp_law_row *row = part ? &dp_damper_laws[i].row : &dp_spring_laws[i].row;
            members_json(row, law, sizeof law, NULL);
            snprintf(doc, sizeof doc, "{\"model\":{\"mass\":1,\"spring\":%s,\"damper\":%s},"
                     "\"solver\":{\"dt\":0.1,\"t_end\":1}}", part ? "{\"law\":\"linear\",\"k\":1}" : law,
                     part ? law : "{\"law\":\"none\"}");
            assert_int_equal(parse(doc, &spec, &errs), DP_OK);
            const void *base = part ? (const void *)&spec.model.damper : (const void *)&spec.model.spring;
            assert_int_equal(part ? (int)spec.model.damper.law : (int)spec.model.spring.law, i);
            for (size_t k = 0; row->members[k].key; k++)
                assert_true(dp_law_field_value(base, row->members[k].offset) == (double)(k + 1));
            const dp_graph *g = part ? &spec.model.damper.graph : &spec.model.spring.graph;
            assert_true(g->n > 0);   /* built, or read from the points */
            dp_spec_clear(&spec);
            /* each required member left out: one error at its own pointer */
            for (size_t k = 0; row->members[k].key; k++) {
                if (!row->members[k].required)
                    continue;
                members_json(row, law, sizeof law, row->members[k].key);
                snprintf(doc, sizeof doc, "{\"model\":{\"mass\":1,\"spring\":%s,\"damper\":%s},"
                         "\"solver\":{\"dt\":0.1,\"t_end\":1}}", part ? "{\"law\":\"linear\",\"k\":1}" : law,
                         part ? law : "{\"law\":\"none\"}");
                assert_int_equal(parse(doc, &spec, &errs), DP_EINVAL);
                char ptr[64];
                snprintf(ptr, sizeof ptr, "/model/%s/%s", part ? "damper" : "spring", row->members[k].key);
                assert_int_equal(errs.n, 1);
                assert_string_equal(errs.item[0].pointer, ptr);
                assert_non_null(strstr(errs.item[0].message, "missing required key"));
                dp_spec_clear(&spec);
            }
        }
    }
    for (int i = 0; i < DP_LCS_LAW_COUNT; i++) {
        const dp_law_row *row = &dp_lcs_laws[i].row;
        members_json(row, law, sizeof law, NULL);
        snprintf(doc, sizeof doc, "{\"model\":{\"lcs\":{\"A\":[[0,1],[-1,-0.1]],\"B\":[[0],[1]],\"C\":[[0,1]],"
                 "\"D\":[[0.5]]},\"laws\":[%s]},\"initial\":{\"x\":[0,0]},\"solver\":{\"dt\":0.01,\"t_end\":1}}", law);
        assert_int_equal(parse(doc, &spec, &errs), DP_OK);
        assert_int_equal((int)spec.lcs->law[0].kind, i);
        for (size_t k = 0; row->members[k].key; k++)
            assert_true(dp_law_field_value(&spec.lcs->law[0], row->members[k].offset) == (double)(k + 1));
        assert_int_equal(dp_lcs_law_is_graph(&spec.lcs->law[0]), dp_lcs_laws[i].shape == DP_LCS_SHAPE_GRAPH);
        dp_spec_clear(&spec);
    }
}

/* The properties the solvers read, for each law as the table has them today. A change here is a change of
 * what a law does: it must be deliberate. */
static void test_properties_as_today(void **state)
{
    (void)state;
    int closed = 0, linear = 0, viscous = 0, analytic = 0, thesis = 0, statics = 0;
    for (int i = 0; i < DP_DAMPER_LAW_COUNT; i++) {
        const dp_damper_law_info *L = &dp_damper_laws[i];
        closed |= L->closed_form << i, linear |= L->linear << i, viscous |= (L->viscous != 0) << i;
        analytic |= L->analytic << i, thesis |= L->thesis << i, statics |= (L->static_threshold != 0) << i;
    }
#define BIT(x) (1 << DP_DAMPER_##x)
    /* the closed form: exactly the threshold dampers (a stick interval [-tau, tau] plus c), not a user graph */
    assert_int_equal(closed, BIT(NONE) | BIT(LINEAR) | BIT(COULOMB) | BIT(BINGHAM) | BIT(GENERALIZED_COULOMB));
    assert_int_equal(linear, BIT(NONE) | BIT(LINEAR));
    assert_int_equal(viscous, BIT(LINEAR) | BIT(BINGHAM));
    assert_int_equal(analytic, BIT(NONE) | BIT(COULOMB));
    assert_int_equal(thesis, BIT(COULOMB));
    assert_int_equal(statics, BIT(GENERALIZED_COULOMB));
#undef BIT
    int slinear = 0, plastic = 0, locate = 0, locate_net = 0, xmax = 0;
    for (int i = 0; i < DP_SPRING_LAW_COUNT; i++) {
        const dp_spring_law_info *L = &dp_spring_laws[i];
        slinear |= L->linear << i, plastic |= L->plastic << i, locate |= L->locate << i;
        locate_net |= L->locate_network << i, xmax |= (L->x_max != 0) << i;
    }
#define BIT(x) (1 << DP_SPRING_##x)
    assert_int_equal(slinear, BIT(LINEAR));
    assert_int_equal(plastic, BIT(ELASTOPLASTIC));
    assert_int_equal(locate, BIT(LINEAR) | BIT(ROPE) | BIT(GRAPH) | BIT(ELASTOPLASTIC));
    /* a rope on a network with events located: a linear spring and the contact u <= L (network_contact.c) */
    assert_int_equal(locate_net, BIT(LINEAR) | BIT(ROPE) | BIT(ELASTOPLASTIC));
    assert_int_equal(xmax, BIT(ROPE));
#undef BIT
    /* the reads: Bingham's c and tau, generalized Coulomb's two thresholds, a linear spring's k */
    dp_damper b = { .law = DP_DAMPER_BINGHAM, .tau = 0.3, .c = 0.2, .phi0 = 9, .phi1 = 9 };
    assert_true(dp_damper_viscous(&b) == 0.2 && dp_damper_kinetic(&b) == 0.3 && dp_damper_static(&b) == 0.3);
    dp_damper g = { .law = DP_DAMPER_GENERALIZED_COULOMB, .phi0 = 0.3, .phi1 = 0.5, .c = 9, .tau = 9 };
    assert_true(dp_damper_viscous(&g) == 0 && dp_damper_kinetic(&g) == 0.3 && dp_damper_static(&g) == 0.5);
    dp_spring r = { .law = DP_SPRING_ROPE, .k = 2, .length = 1 }, l = { .law = DP_SPRING_LINEAR, .k = 2 };
    assert_true(dp_spring_stiffness(&r) == 0 && dp_spring_stiffness(&l) == 2);
}

/* What the closed form assumes of a law, checked on its built graph: the graph is the stick interval
 * [-tau, tau] at zero with flat rays (tau its kinetic threshold), the viscous part outside it. A law whose
 * graph were anything else must not say closed_form. A viscous law's graph has at most two vertices
 * (wellposedness.c adds c to a copy of that size). */
static void test_closed_form_graphs_are_thresholds(void **state)
{
    (void)state;
    char law[256], doc[1024];
    for (int i = 0; i < DP_DAMPER_LAW_COUNT; i++) {
        const dp_damper_law_info *L = &dp_damper_laws[i];
        if (!L->closed_form && !L->viscous)
            continue;
        members_json(&L->row, law, sizeof law, NULL);
        snprintf(doc, sizeof doc, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":%s},"
                 "\"solver\":{\"dt\":0.1,\"t_end\":1}}", law);
        dp_spec spec;
        dp_errors errs;
        assert_int_equal(parse(doc, &spec, &errs), DP_OK);
        const dp_damper *d = &spec.model.damper;
        const dp_graph *A = &d->graph;
        assert_true(A->n <= 2);
        if (L->closed_form) {
            double tau = dp_damper_kinetic(d), lo, hi;
            dp_graph_force(A, 0, &lo, &hi);
            assert_true(lo == -tau && hi == tau);
            for (double v = 0.25; v < 4; v *= 2) {
                dp_graph_force(A, v, &lo, &hi);
                assert_true(lo == tau && hi == tau);
                dp_graph_force(A, -v, &lo, &hi);
                assert_true(lo == -tau && hi == -tau);
            }
        }
        dp_spec_clear(&spec);
    }
}

/* Runs a one-mass document with a linear spring, no relaxation and no event location; its summary. */
static dp_summary run_damper(const char *damper)
{
    char doc[1024];
    snprintf(doc, sizeof doc, "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},\"damper\":%s,"
             "\"forcing\":{\"kind\":\"harmonic\",\"amplitude\":0.5,\"omega\":1.3}},\"initial\":{\"x\":1},"
             "\"solver\":{\"dt\":0.01,\"t_end\":5,\"events\":\"none\"}}", damper);
    traj t;
    assert_int_equal(traj_run(doc, &t), DP_OK);
    assert_int_equal(t.status, DP_DONE);
    dp_summary s = t.sum;
    traj_free(&t);
    return s;
}

/* The closed form takes no bracketing evaluations; the inclusion path does. So with a linear spring and no
 * relaxation, each law's run shows which path its entry sent it down: the closed form exactly when the entry
 * says closed_form = 1. */
static void test_closed_form_path_is_the_entry(void **state)
{
    (void)state;
    char law[256];
    for (int i = 0; i < DP_DAMPER_LAW_COUNT; i++) {
        members_json(&dp_damper_laws[i].row, law, sizeof law, NULL);
        dp_summary s = run_damper(law);
        assert_int_equal(s.iterations == 0, dp_damper_laws[i].closed_form);
    }
    /* and the closed form agrees with the same law given as a graph, stepped by the inclusion */
    dp_summary a = run_damper("{\"law\":\"coulomb\",\"phi0\":0.4}");
    dp_summary b = run_damper("{\"law\":\"graph\",\"points\":[[-1,-0.4],[0,-0.4],[0,0.4],[1,0.4]]}");
    assert_true(a.iterations == 0 && b.iterations > 0);
    assert_true(fabs(a.final.x - b.final.x) < 1e-9 && fabs(a.final.v - b.final.v) < 1e-9);
    assert_true(fabs(a.stick_time - b.stick_time) < 1e-9);
}

/* The trap the table closes: a damper law with no entry (a law added to the enum and nowhere else) was sent
 * down the closed form, whose tau and c it does not have, and answered as if it were no damper. Now the run
 * is refused. Likewise its graph cannot be built, and it is not linear, viscous or closed-form anywhere. */
static void test_law_without_entry_is_refused(void **state)
{
    (void)state;
    dp_spec spec;
    dp_errors errs;
    const char *doc = "{\"model\":{\"mass\":1,\"spring\":{\"law\":\"linear\",\"k\":1},"
                      "\"damper\":{\"law\":\"coulomb\",\"phi0\":0.4}},\"initial\":{\"x\":1},"
                      "\"solver\":{\"dt\":0.01,\"t_end\":1}}";
    assert_int_equal(parse(doc, &spec, &errs), DP_OK);
    spec.model.damper.law = DP_DAMPER_LAW_COUNT;   /* the graph stays Coulomb's, as a new law's would be built */
    int status = DP_OK;
    dp_run *run = dp_run_alloc(&spec, 0, &errs, &status);
    assert_null(run);
    assert_int_equal(status, DP_EINVAL);
    dp_damper d = { .law = DP_DAMPER_LAW_COUNT, .c = 1, .phi0 = 1, .tau = 1 };
    assert_int_equal(dp_damper_prepare(&d), DP_EINVAL);
    assert_false(dp_damper_closed_form(&d) || dp_damper_linear(&d) || dp_damper_has_viscous(&d));
    assert_true(dp_damper_viscous(&d) == 0 && dp_damper_kinetic(&d) == 0);
    dp_spring s = { .law = DP_SPRING_LAW_COUNT, .k = 1 };
    assert_int_equal(dp_spring_prepare(&s), DP_EINVAL);
    assert_false(dp_spring_linear(&s) || dp_spring_plastic(&s));
    dp_lcs_law l = { .kind = DP_LCS_LAW_COUNT };
    assert_false(dp_lcs_law_valid(&l));
    dp_spec_clear(&spec);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_entries_complete),
        cmocka_unit_test(test_parser_reads_the_rows),
        cmocka_unit_test(test_properties_as_today),
        cmocka_unit_test(test_closed_form_graphs_are_thresholds),
        cmocka_unit_test(test_closed_form_path_is_the_entry),
        cmocka_unit_test(test_law_without_entry_is_refused),
    };
    return cmocka_run_group_tests_name("law table", tests, NULL, NULL);
}
