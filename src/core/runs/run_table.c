/* src/core/runs/run_table.c - the one table of run types: which solver runs a spec, by its model family
 * (a linear complementarity system, a right-hand friction model, a network, one mass) and the solver it
 * names. Nothing else in the core chooses between solvers: the iterator (run.c) and the rules
 * (dp_spec_check) ask this table, and each type carries its own rules, state and records.
 *
 * Adding a solver kind: its file in solvers/ defining a dp_run_type, its rules in rules/, one row here. */
#include "runs/run_table.h"
#include "rules/rules.h"
#include "solvers/run_types.h"

static int is_lcs(const dp_spec *s) { return s->lcs != NULL; }
/* a right-hand model, or the right-hand solver asked for without one (its rules refuse that) */
static int is_right_hand(const dp_spec *s) { return s->rh != NULL || s->solver.kind == DP_SOLVER_RIGHT_HAND; }
static int is_network(const dp_spec *s) { return s->net != NULL; }
static int is_analytic(const dp_spec *s) { return s->solver.kind == DP_SOLVER_ANALYTIC; }
static int is_regularized(const dp_spec *s) { return s->solver.kind == DP_SOLVER_REGULARIZED; }
static int is_newmark(const dp_spec *s) { return s->solver.kind == DP_SOLVER_NEWMARK; }
static int is_thesis(const dp_spec *s) { return s->solver.variant == DP_VARIANT_THESIS; }
static int always(const dp_spec *s) { (void)s; return 1; }
static int is_regularized_network(const dp_spec *s) { return is_network(s) && is_regularized(s); }
static int is_newmark_network(const dp_spec *s) { return is_network(s) && is_newmark(s); }

/* In order: the first row that selects a spec runs it. Model families first (their documents choose their
 * solver themselves), then the one-mass solvers by the solver's kind and variant. */
static const struct run_row {
    int (*selects)(const dp_spec *s);
    const dp_run_type *type;
} run_table[] = {
    { is_lcs, &dp_run_lcs },
    { is_right_hand, &dp_run_right_hand },
    { dp_network_is_one_mass, &dp_run_network_one_mass }, /* one mass on one element: the one-mass step */
    { dp_network_is_one_node_contact, &dp_run_network_contact_lean }, /* the bouncing ball: the lean step */
    { dp_network_is_grounded_chain, &dp_run_network_grounded_chain }, /* stop and friction chains: the lean step */
    { is_regularized_network, &dp_run_network_regularized },
    { is_newmark_network, &dp_run_network_newmark },
    { is_network, &dp_run_network },
    { is_analytic, &dp_run_analytic },
    { is_regularized, &dp_run_regularized },
    { is_newmark, &dp_run_newmark },
    { is_thesis, &dp_run_thesis },
    { always, &dp_run_stick_slip },
};

const dp_run_type *dp_run_type_of(const dp_spec *spec)
{
    size_t i = 0;
    while (!run_table[i].selects(spec))
        i++;      /* the last row selects every spec */
    return run_table[i].type;
}

int dp_spec_check(const dp_spec *s, double max_steps, dp_errors *e)
{
    return dp_run_type_of(s)->check(s, max_steps, e);
}

const char *dp_spec_solver(const dp_spec *s)
{
    return dp_run_type_of(s)->name;
}

const char *dp_spec_variant(const dp_spec *s)
{
    return dp_run_type_of(s)->variant;
}

const char *dp_spec_events_mode(const dp_spec *s)
{
    const dp_run_type *t = dp_run_type_of(s);
    return t->events_mode ? t->events_mode(s) : NULL;
}
