/* src/core/solvers/network/network_output.c - what a network run hands out: rows over its columns, element events, the
 * summary's final row, and the queue that holds what did not fit the caller's block (it grows, it never
 * drops: one step can change the phase of every element). Shared by the exact stepping and the regularized
 * scheme. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "solvers/network/network_quakes.h"
#include "solvers/network/network_run.h"

/* Row storage per block: the block holds at most this many numbers of rows. */
#define ROW_BUDGET (1u << 20)

dp_row network_run_fill_row(const struct dp_network_run *nr, double t, double *data)
{
    size_t nn = nr->cols.nodes, ne = nr->cols.elements;
    for (size_t j = 0; j < nn; j++) {
        size_t i = nr->node_pos ? nr->node_pos[nr->cols.node[j]] : nr->cols.node[j];
        data[j] = nr->x[i], data[nn + j] = nr->v[i];
    }
    for (size_t j = 0; j < ne; j++) {
        size_t i = nr->cols.element[j];
        data[2 * nn + j] = nr->Fs[i], data[2 * nn + ne + j] = nr->Fd[i], data[2 * nn + 2 * ne + j] = nr->phase[i];
    }
    for (size_t j = 0; j < nr->nep_cols; j++)
        data[2 * nn + 3 * ne + j] = nr->ep_p[nr->ep_cols[j]];
    for (size_t j = 0; nr->Fn && j < ne; j++)
        data[2 * nn + 3 * ne + nr->nep_cols + j] = nr->Fn[nr->cols.element[j]];
    return (dp_row){ .t = t, .val = data };
}

/* Queues a record for the caller: into its block while it has room and nothing waits, else the queue. */
void network_run_put(dp_run *r, const dp_record *rec)
{
    struct dp_network_run *nr = r->state;
    if (!dp_row_queue_waiting(&nr->queue) && r->out && r->out_n < r->out_cap) {
        r->out[r->out_n++] = *rec;
        return;
    }
    if (dp_row_queue_push(&nr->queue, rec, rec->type == DP_RECORD_ROW ? rec->u.row.val : NULL) != DP_OK)
        dp_run_fail(r, DP_ENOMEM, "out of memory for the events of one step");
}

void network_run_emit_row(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    r->countdown = r->spec.output.every;
    if (!r->spec.output.samples)
        return;
    dp_record rec = { .type = DP_RECORD_ROW };
    double *slot = !dp_row_queue_waiting(&nr->queue) && r->out && r->out_n < r->out_cap ? dp_row_slots_take(&nr->slots)
                                                                                         : NULL;
    if (slot != NULL) {
        rec.u.row = network_run_fill_row(nr, r->cur.t, slot);
        r->out[r->out_n++] = rec;
    } else {   /* made in the scratch row, copied by the queue */
        rec.u.row = network_run_fill_row(nr, r->cur.t, nr->pending_row);
        if (dp_row_queue_push(&nr->queue, &rec, nr->pending_row) != DP_OK)
            dp_run_fail(r, DP_ENOMEM, "out of memory for the events of one step");
    }
    r->sum.samples++;
}

void network_run_finalize_summary(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    r->sum.final_row = network_run_fill_row(nr, r->cur.t, nr->final_row);
    const dp_quake *q;
    size_t nq = r->finished ? network_quakes_finish(nr, r->cur.t, &q) : 0;
    for (size_t i = 0; i < nq; i++)    /* the quakes still going at t_end, open */
        network_run_put(r, &(dp_record){ .type = DP_RECORD_QUAKE, .u.quake = q[i] });
}


/* Counts an event of element i at time t and hands it out if events are wanted: its elongation now and the
 * rate du. */
static void element_event(dp_run *r, dp_event_kind kind, double t, size_t i, double du)
{
    struct dp_network_run *nr = r->state;
    r->sum.events++;
    if (!r->spec.output.events)
        return;
    const dp_element *e = &nr->net->el[i];
    dp_record rec = { .type = DP_RECORD_EVENT };
    rec.u.event = (dp_event){ .kind = kind, .t = t, .x = network_run_rel(e->a, e->b, nr->x), .v = du, .element = i };
    network_run_put(r, &rec);
}

void network_run_impact_event(dp_run *r, double t, size_t i, double before, double after, double impulse)
{
    struct dp_network_run *nr = r->state;
    r->sum.events++, r->sum.impacts++;
    if (!r->spec.output.events)
        return;
    const dp_element *e = &nr->net->el[i];
    dp_record rec = { .type = DP_RECORD_EVENT };
    rec.u.event = (dp_event){ .kind = DP_EVENT_IMPACT, .t = t, .x = network_run_rel(e->a, e->b, nr->x), .v = before,
                              .element = i, .v_after = after, .impulse = impulse };
    network_run_put(r, &rec);
}

/* ---- a compliant contact's touch (its gap u - d closing to zero) and separation: events of the contact's
 * element, written at the instant (located by network_smooth.c), as a rigid contact's impact is ---- */

/* Whether constraint c is a compliant contact (not a rigid one, nor a rope's or a graph's stop). */
static int compliant(const struct dp_network_run *nr, size_t c)
{
    return !nr->ct[c].rope && nr->ct[c].law.compliance > 0;
}

/* Pressed: the gap below zero, or at zero and closing; at zero within the touching tolerance (the rounding of
 * the positions and a billionth of what the gap moves in a step h: a located instant's root tolerance). */
static int pressed(const struct dp_network_run *nr, size_t c, double h)
{
    const network_bound *b = &nr->ct[c];
    double g = network_run_bound_gap(b, nr->x), tol = network_run_touch_tol(b, nr->x, nr->v, h);
    return g < -tol || (g <= tol && network_run_rel(b->a, b->b, nr->v) < 0);
}

void network_run_touch_start(struct dp_network_run *nr, double h)
{
    for (size_t c = 0; nr->sm_pressed && c < nr->nc; c++)
        nr->sm_pressed[c] = compliant(nr, c) && pressed(nr, c, h);
}

void network_run_touch_events(dp_run *r, double t)
{
    struct dp_network_run *nr = r->state;
    for (size_t c = 0; nr->sm_pressed && c < nr->nc; c++) {
        const network_bound *b = &nr->ct[c];
        if (!compliant(nr, c))
            continue;
        int now = pressed(nr, c, r->h);
        if (now == nr->sm_pressed[c])
            continue;
        nr->sm_pressed[c] = (unsigned char)now;
        r->sum.events++;
        if (!r->spec.output.events)
            continue;
        dp_record rec = { .type = DP_RECORD_EVENT };
        rec.u.event = (dp_event){ .kind = now ? DP_EVENT_TOUCH : DP_EVENT_SEPARATE, .t = t,
                                  .x = network_run_rel(b->a, b->b, nr->x), .v = network_run_rel(b->a, b->b, nr->v),
                                  .element = nr->ct_el[c] };
        network_run_put(r, &rec);
    }
}

/* Events at time t for the elements whose phase differs from `before`. */
void network_run_step_events(dp_run *r, const unsigned char *before, double t)
{
    struct dp_network_run *nr = r->state;
    const unsigned char *phase = nr->phase;
    for (size_t i = 0, nel = nr->nel; i < nel; i++) {
        if (phase[i] == before[i] || phase[i] == DP_PHASE_NONE)
            continue;
        const dp_element *e = &nr->net->el[i];
        /* a stick holds the belt's speed exactly; the state carries its rounding */
        double du = nr->phase[i] == DP_PHASE_STICK && e->has_damper ? e->damper.belt_velocity
                                                                    : network_run_rel(e->a, e->b, nr->v);
        element_event(r, nr->phase[i] == DP_PHASE_STICK ? DP_EVENT_STICK : DP_EVENT_SLIP, t, i, du);
    }
    network_run_touch_events(r, t);
    const dp_quake *q;
    size_t nq = network_quakes_step(nr, before, t, &q);
    for (size_t i = 0; i < nq; i++)    /* the quakes this (sub-)step ended */
        network_run_put(r, &(dp_record){ .type = DP_RECORD_QUAKE, .u.quake = q[i] });
}

/* An elastoplastic spring's slider starting to slide (yield: from elastic, or reversed from the other
 * yield force) or stopping (unload), at the end of the step that did it. */
void network_run_plastic_events(dp_run *r, double t)
{
    struct dp_network_run *nr = r->state;
    for (size_t i = 0; nr->has_ep && i < nr->nel; i++) {
        int before = nr->ep_flow_prev[i], now = nr->ep_flow[i];
        if (nr->ep_graph[i] == NULL || before == now)
            continue;
        const dp_element *e = &nr->net->el[i];
        element_event(r, now ? DP_EVENT_YIELD : DP_EVENT_UNLOAD, t, i, network_run_rel(e->a, e->b, nr->v));
    }
}

/* Time spent sticking over a (sub-)step of length h by the elements whose phase is `ph`. */
void network_run_stick_time(dp_run *r, const unsigned char *ph, double h)
{
    for (size_t i = 0; i < network_run_of(r)->nel; i++)
        if (ph[i] == DP_PHASE_STICK)
            r->sum.stick_time += h;
}


int network_run_state_finite(const struct dp_network_run *nr)
{
    for (size_t i = 0; i < nr->n; i++)
        if (!(fabs(nr->x[i]) < 1e300 && fabs(nr->v[i]) < 1e300))
            return 0;
    for (size_t i = 0; i < nr->nel; i++)
        if (!isfinite(nr->Fs[i]) || !isfinite(nr->Fd[i]))
            return 0;
    return 1;
}

/* Moves queued records into the caller's block (a queued row into a block slot of its own). */
void network_run_flush(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    dp_row_queue_flush(&nr->queue, r, &nr->slots);
}

/* Row slots for this block: one per record the caller can take, within ROW_BUDGET numbers. */
int network_run_reserve_rows(dp_run *r)
{
    struct dp_network_run *nr = r->state;
    size_t want = r->out_cap, fit = ROW_BUDGET / (nr->row_len ? nr->row_len : 1);
    if (want > fit)
        want = fit ? fit : 1;
    return dp_row_slots_reserve(&nr->slots, want);
}
