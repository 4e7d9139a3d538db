/* tests/trajectory.h - test helper: run a spec given as JSON text and keep every record in memory.
 * Header-only so that each test program stays one file plus this. */
#ifndef DASHPOT_TESTS_TRAJECTORY_H
#define DASHPOT_TESTS_TRAJECTORY_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/json.h"
#include "dashpot/run.h"

typedef struct traj {
    dp_sample *s;
    size_t n, cap;
    dp_event *e;
    size_t ne, ecap;
    dp_summary sum;
    int status;
    char error[256];
} traj;

static void traj_free(traj *t)
{
    free(t->s);
    free(t->e);
    memset(t, 0, sizeof *t);
}

static void traj_push(traj *t, const dp_record *r)
{
    if (r->type == DP_RECORD_SAMPLE) {
        if (t->n == t->cap) {
            t->cap = t->cap ? 2 * t->cap : 1024;
            t->s = realloc(t->s, t->cap * sizeof *t->s);
        }
        t->s[t->n++] = r->u.sample;
    } else {
        if (t->ne == t->ecap) {
            t->ecap = t->ecap ? 2 * t->ecap : 64;
            t->e = realloc(t->e, t->ecap * sizeof *t->e);
        }
        t->e[t->ne++] = r->u.event;
    }
}

/* Parses and runs; returns the parse/alloc status (DP_OK) and fills t; the run's end status in t->status.
 * On a parse error the first error is printed to stderr. */
static int traj_run(const char *json, traj *t)
{
    memset(t, 0, sizeof *t);
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int s = dp_spec_parse(json, strlen(json), 0, &spec, &errs);
    if (s != DP_OK) {
        if (errs.n)
            fprintf(stderr, "spec error %s: %s\n", errs.item[0].pointer, errs.item[0].message);
        dp_spec_clear(&spec);
        return s;
    }
    dp_run *run = dp_run_alloc(&spec, 0, &errs, &s);
    dp_spec_clear(&spec);
    if (run == NULL)
        return s;
    dp_record buf[257];
    size_t n;
    do {
        s = dp_run_next(run, buf, 257, &n);
        for (size_t i = 0; i < n; i++)
            traj_push(t, &buf[i]);
    } while (s == DP_MORE);
    t->status = s;
    t->sum = *dp_run_summary(run);
    snprintf(t->error, sizeof t->error, "%s", dp_run_error(run));
    dp_run_free(run);
    return DP_OK;
}

/* printf into a static-size buffer owned by the caller. */
#define SPEC(buf, ...) (snprintf(buf, sizeof buf, __VA_ARGS__), buf)

#endif
