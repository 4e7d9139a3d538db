/* src/json/meta_json.c - the "meta" object that opens every run's output: what was solved and how, and
 * what the theorems guarantee about it, so a stored trajectory says where it came from. */
#include <stdio.h>
#include <string.h>

#include "dashpot/json.h"

static const char *variant_name(const dp_solver_spec *s)
{
    if (s->kind == DP_SOLVER_ANALYTIC)
        return "closed-form";
    return s->variant == DP_VARIANT_THESIS ? "thesis" : "exact";
}

static const char *solver_name(const dp_solver_spec *s)
{
    switch (s->kind) {
    case DP_SOLVER_ANALYTIC: return "analytic";
    case DP_SOLVER_REGULARIZED: return "regularized";
    default: return "stick-slip";
    }
}

/* Appends "key":number with the shortest round-trip text, like every other number dashpot writes. */
static int num(dp_buf *out, const char *key, double x)
{
    char t[64];
    size_t n = (size_t)snprintf(t, sizeof t, ",\"%s\":", key);
    n += dp_format_double(t + n, x);
    return dp_buf_append(out, t, n);
}

int dp_spec_meta_json(const dp_spec *s, dp_buf *out)
{
    const dp_solver_spec *sv = &s->solver;
    char head[512], tail[256];
    int n = snprintf(head, sizeof head, "{\"type\":\"meta\",\"version\":\"%s\",\"solver\":\"%s\",\"variant\":\"%s\","
                     "\"events_mode\":\"%s\",\"branch\":\"%s\"", DP_VERSION, solver_name(sv), variant_name(sv),
                     sv->events == DP_EVENTS_LOCATE ? "locate" : "none", sv->branch == DP_BRANCH_MOTION ? "motion" : "rest");
    int m = snprintf(tail, sizeof tail, ",\"every\":%ld,\"spring\":\"%s\",\"damper\":\"%s\",\"wellposedness\":",
                     s->output.every, dp_spring_law_name(s->model.spring.law), dp_damper_law_name(s->model.damper.law));
    int st = dp_buf_append(out, head, n > 0 && (size_t)n < sizeof head ? (size_t)n : 0);
    st |= num(out, "theta", sv->theta) | num(out, "dt", sv->dt) | num(out, "t_end", sv->t_end);
    st |= num(out, "steps", dp_spec_steps(s));
    st |= dp_buf_append(out, tail, m > 0 && (size_t)m < sizeof tail ? (size_t)m : 0);
    dp_wp_report wp;
    dp_wellposedness(&s->model, &wp);
    st |= dp_wellposedness_json(&wp, out);
    st |= dp_buf_append(out, "}", 1);
    return st ? DP_ENOMEM : DP_OK;
}
