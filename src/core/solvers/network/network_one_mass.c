/* src/core/solvers/network/network_one_mass.c - a network that is one mass on one element [ground, 0] is the one-mass model
 * (docs/systems.md §1), so it is stepped by the one-mass solver: the same answers, bit for bit, at the same speed
 * (a general network step costs some 20 times the soft threshold's few nanoseconds). Its samples and events
 * are rewritten as the network's rows and element events on their way out.
 */
#include <stdlib.h>
#include <string.h>

#include "rules/rules.h"
#include "solvers/network/network_run.h"

/* The network's laws and loads as the run's one-mass model (deep copies: the run owns them). */
static int as_model(dp_run *r)
{
    const dp_network *n = r->spec.net;
    const dp_element *e = &n->el[0];
    dp_model m = { .mass = n->mass[0] };
    m.spring = e->has_spring ? e->spring : (dp_spring){ .law = DP_SPRING_LINEAR, .k = 0 };
    m.damper = e->has_damper ? e->damper : (dp_damper){ .law = DP_DAMPER_NONE };
    if (!e->has_spring)
        memset(&m.spring.graph, 0, sizeof m.spring.graph);
    if (!e->has_damper)
        memset(&m.damper.graph, 0, sizeof m.damper.graph);
    dp_forcing sum = { .kind = DP_FORCING_SUM, .nterms = n->nforce };
    dp_forcing *terms = n->nforce > 1 ? calloc(n->nforce, sizeof *terms) : NULL;
    if (n->nforce > 1 && terms == NULL)
        return DP_ENOMEM;
    for (size_t i = 0; n->nforce > 1 && i < n->nforce; i++)
        terms[i] = n->force[i].f;          /* shallow: dp_model_copy below copies them */
    sum.terms = terms;
    m.forcing = n->nforce == 1 ? n->force[0].f : n->nforce > 1 ? sum : (dp_forcing){ .kind = DP_FORCING_NONE };
    dp_model copy;
    int s = dp_model_copy(&copy, &m);
    free(terms);
    if (s != DP_OK)
        return s;
    dp_model_clear(&r->spec.model);
    r->spec.model = copy;
    r->spec.x0 = r->spec.x0v[0];
    r->spec.v0 = r->spec.v0v[0];
    return dp_model_prepare(&r->spec.model);
}

static int one_mass_init(dp_run *r)
{
    int s = network_run_setup(r);
    if (s != DP_OK)
        return s;
    s = as_model(r);
    if (s != DP_OK)
        return s;
    network_run_of(r)->one_mass = 1;
    return dp_stick_slip_init(r);
}

/* The network's state from the one-mass sample s: what rows and the summary are made of. */
static void take_sample(struct dp_network_run *nr, const dp_sample *s)
{
    nr->x[0] = s->x, nr->v[0] = s->v;
    nr->Fs[0] = s->Fs, nr->Fd[0] = s->Fd;
    nr->phase[0] = (unsigned char)s->phase;
}

/* Rewrites the block's one-mass records as network records: samples as rows in the run's row slots,
 * events with their element (0; u = x, du = v on [ground, 0]). */
static int one_mass_rows(dp_run *r, dp_record *buf, size_t n)
{
    struct dp_network_run *nr = r->state;
    r->out_cap = n;
    if (network_run_reserve_rows(r) != DP_OK)
        return DP_ENOMEM;
    for (size_t i = 0; i < n; i++) {
        if (buf[i].type == DP_RECORD_EVENT) {
            buf[i].u.event.element = 0;
            continue;
        }
        double *slot = buf[i].type == DP_RECORD_SAMPLE ? dp_row_slots_take(&nr->slots) : NULL;
        if (slot == NULL)
            continue;
        double t = buf[i].u.sample.t;
        take_sample(nr, &buf[i].u.sample);
        buf[i].type = DP_RECORD_ROW;
        buf[i].u.row = network_run_fill_row(nr, t, slot);
    }
    take_sample(nr, &r->sum.final);
    r->sum.final_row = network_run_fill_row(nr, r->sum.final.t, nr->final_row);
    return DP_OK;
}

/* The network's own setup (rows, columns, the reordering), then the one-mass solver's steps, each block
 * rewritten as the network's rows. */
const dp_run_type dp_run_network_one_mass = {
    .name = "stick-slip", .variant = "exact", .events_mode = network_run_events_mode, .check = dp_rules_network, .init = one_mass_init, .advance = dp_stick_slip_advance,
    .pending = network_run_pending, .block = one_mass_rows, .free = network_run_free,
};
