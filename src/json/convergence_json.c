/* src/json/convergence_json.c - a convergence study (regularized.h) as one JSON object, shared by
 * `dashpot convergence` and the daemon. Numbers round-trip (dp_format_double); an undefined rate or the
 * first row's distance to a previous n is null. */
#include <stdio.h>
#include <string.h>

#include "dashpot/encode.h"
#include "dashpot/regularized.h"

/* Appends `,"key":` (no comma when first) and a double. */
static int put_num(dp_buf *b, int first, const char *key, double x)
{
    char t[96];
    int n = snprintf(t, 48, "%s\"%s\":", first ? "" : ",", key);
    if (n < 0 || n >= 48)
        return DP_ENOMEM;
    return dp_buf_append(b, t, (size_t)n + dp_format_double(t + n, x));
}

static int put_count(dp_buf *b, const char *key, unsigned long long x)
{
    char t[80];
    int n = snprintf(t, sizeof t, ",\"%s\":%llu", key, x);
    return n < 0 || n >= (int)sizeof t ? DP_ENOMEM : dp_buf_append(b, t, (size_t)n);
}

static int put_text(dp_buf *b, const char *s)
{
    return dp_buf_append(b, s, strlen(s));
}

static int put_row(dp_buf *b, const dp_convergence_row *r, int first)
{
    int s = put_text(b, first ? "{" : ",\n{");
    s = s ? s : put_num(b, 1, "n", r->n);
    s = s ? s : put_num(b, 0, "err_x", r->err_x);
    s = s ? s : put_num(b, 0, "err_v", r->err_v);
    s = s ? s : put_num(b, 0, "diff_x", r->diff_x);
    s = s ? s : put_num(b, 0, "diff_v", r->diff_v);
    s = s ? s : put_num(b, 0, "rate_x", r->rate_x);
    s = s ? s : put_num(b, 0, "rate_v", r->rate_v);
    s = s ? s : put_count(b, "steps", r->steps);
    s = s ? s : put_count(b, "rejected", r->rejected);
    s = s ? s : put_count(b, "fevals", r->fevals);
    s = s ? s : put_count(b, "jevals", r->jevals);
    return s ? s : put_text(b, "}");
}

static int put_head(dp_buf *b, const dp_convergence *c)
{
    char t[160];
    snprintf(t, sizeof t, "{\"scheme\":\"%s\",\"stepper\":\"%s\"", dp_scheme_name(c->scheme),
             dp_stepper_name(c->stepper));
    int s = put_text(b, t);
    s = s ? s : put_num(b, 0, "rtol", c->rtol);
    s = s ? s : put_num(b, 0, "atol", c->atol);
    s = s ? s : put_num(b, 0, "dt", c->dt);
    s = s ? s : put_num(b, 0, "t_end", c->t_end);
    snprintf(t, sizeof t, ",\"reference\":{\"solver\":\"%s\"",
             c->reference == DP_REFERENCE_ANALYTIC ? "analytic" : "stick-slip");
    s = s ? s : put_text(b, t);
    s = s ? s : put_num(b, 0, "dt", c->ref_dt);
    s = s ? s : put_num(b, 0, "theta", c->ref_theta);
    s = s ? s : put_text(b, "}");
    s = s ? s : put_count(b, "samples", c->samples);
    s = s ? s : put_num(b, 0, "rate_x", c->rate_x);
    return s ? s : put_num(b, 0, "rate_v", c->rate_v);
}

int dp_convergence_json(const dp_convergence *c, struct dp_buf *b)
{
    int s = put_head(b, c);
    s = s ? s : put_text(b, ",\"rows\":[\n");
    for (size_t i = 0; i < c->nrows && s == DP_OK; i++)
        s = put_row(b, &c->row[i], i == 0);
    return s ? s : put_text(b, "]}\n");
}
