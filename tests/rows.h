/* tests/rows.h - test helper: run a network (or any run with columns) given as JSON text and keep its rows
 * flattened, its events and its quake lines, for test programs that use cmocka (include it after <cmocka.h>).
 * Header-only, as trajectory.h is for one-mass samples. */
#ifndef DASHPOT_TESTS_ROWS_H
#define DASHPOT_TESTS_ROWS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/json.h"
#include "dashpot/run.h"

#define ROWS_MAX_EVENTS 8192

/* Every row flattened: t, then the row's numbers (width - 1 of them: x[nx], v[nx], the element groups);
 * the first ROWS_MAX_EVENTS events. */
typedef struct rows {
    double *d;
    size_t n, cap, width, nx, ne;
    size_t events;
    dp_event ev[ROWS_MAX_EVENTS];
    dp_quake *quakes;     /* every quake line (output.quakes), grown as they come: free(quakes) */
    size_t nquakes, quakes_cap;
    int status;
} rows;

static void rows_push(rows *r, const dp_row *w)
{
    if (r->n == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 256;
        r->d = realloc(r->d, r->cap * r->width * sizeof *r->d);
        assert_non_null(r->d);
    }
    double *o = r->d + r->n++ * r->width;
    o[0] = w->t;
    memcpy(o + 1, w->val, (r->width - 1) * sizeof *o);
}

static void rows_push_quake(rows *r, const dp_quake *q)
{
    if (r->nquakes == r->quakes_cap) {
        r->quakes_cap = r->quakes_cap ? 2 * r->quakes_cap : 64;
        r->quakes = realloc(r->quakes, r->quakes_cap * sizeof *r->quakes);
        assert_non_null(r->quakes);
    }
    r->quakes[r->nquakes++] = *q;
}

/* Runs the document to its end with blocks of `cap` records (the spec must parse and the run start) and
 * returns the run's last status, also in r->status (DP_DONE when it finished). */
static int rows_collect(const char *json, size_t cap, rows *r)
{
    memset(r, 0, sizeof *r);
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(json, strlen(json), 0, &spec, &errs);
    if (s != DP_OK && errs.n)
        fprintf(stderr, "spec error %s: %s\n", errs.item[0].pointer, errs.item[0].message);
    assert_int_equal(s, DP_OK);
    dp_run *run = dp_run_alloc(&spec, 0, &errs, &s);
    if (run == NULL && errs.n)
        fprintf(stderr, "run error %s: %s\n", errs.item[0].pointer, errs.item[0].message);
    dp_spec_clear(&spec);
    assert_non_null(run);
    const dp_columns *c = dp_run_columns(run);
    assert_non_null(c);
    r->nx = c->nodes, r->ne = c->elements, r->width = 1 + c->width;
    dp_record *buf = malloc(cap * sizeof *buf);
    assert_non_null(buf);
    size_t n;
    do {
        s = dp_run_next(run, buf, cap, &n);
        for (size_t i = 0; i < n; i++) {
            if (buf[i].type == DP_RECORD_ROW)
                rows_push(r, &buf[i].u.row);
            else if (buf[i].type == DP_RECORD_QUAKE)
                rows_push_quake(r, &buf[i].u.quake);
            else if (buf[i].type == DP_RECORD_EVENT && r->events < ROWS_MAX_EVENTS)
                r->ev[r->events++] = buf[i].u.event;
        }
    } while (s == DP_MORE);
    r->status = s;
    if (s != DP_DONE)
        fprintf(stderr, "run failed: %s\n", dp_run_error(run));
    free(buf);
    dp_run_free(run);
    return s;
}

/* What the rules say of a document: when its spec parses and a run of it starts, the events_mode its meta
 * line says (into out) and DP_OK; else the first error's pointer and the failing status. */
static inline int rows_verdict(const char *json, char *out, size_t cap)
{
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(json, strlen(json), 0, &spec, &errs);
    if (s == DP_OK) {
        const char *m = dp_spec_events_mode(&spec);
        dp_run_free(dp_run_alloc(&spec, 0, &errs, &s));
        if (s == DP_OK)
            snprintf(out, cap, "%s", m ? m : "(none)");
    }
    if (s != DP_OK)
        snprintf(out, cap, "%s", errs.n ? errs.item[0].pointer : "(no error)");
    dp_spec_clear(&spec);
    return s;
}

/* The document is accepted and its meta line says events_mode `mode`. */
static inline void rows_assert_events_mode(const char *json, const char *mode)
{
    char got[DP_POINTER_MAX];
    rows_verdict(json, got, sizeof got);
    if (strcmp(got, mode) != 0)
        fprintf(stderr, "events_mode (or error at) %s, expected %s\n", got, mode);
    assert_string_equal(got, mode);
}

/* The largest difference of the row numbers j0 <= j < j1 (1 is the first after t) between two runs of the
 * same samples. */
static inline double rows_max_difference(const rows *a, const rows *b, size_t j0, size_t j1)
{
    assert_int_equal(a->n, b->n);
    double worst = 0;
    for (size_t i = 0; i < a->n; i++)
        for (size_t j = j0; j < j1; j++)
            worst = fmax(worst, fabs(a->d[i * a->width + j] - b->d[i * b->width + j]));
    return worst;
}

#endif
