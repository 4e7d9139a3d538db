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

int dp_spec_meta_json(const dp_spec *s, dp_buf *out)
{
    const dp_solver_spec *sv = &s->solver;
    char head[768];
    int n = snprintf(head, sizeof head,
        "{\"type\":\"meta\",\"version\":\"%s\",\"solver\":\"%s\",\"variant\":\"%s\",\"theta\":%.17g,"
        "\"events_mode\":\"%s\",\"branch\":\"%s\",\"dt\":%.17g,\"t_end\":%.17g,\"steps\":%.17g,\"every\":%ld,"
        "\"spring\":\"%s\",\"damper\":\"%s\",\"wellposedness\":",
        DP_VERSION, solver_name(sv), variant_name(sv), sv->theta, sv->events == DP_EVENTS_LOCATE ? "locate" : "none",
        sv->branch == DP_BRANCH_MOTION ? "motion" : "rest", sv->dt, sv->t_end, dp_spec_steps(s), s->output.every,
        dp_spring_law_name(s->model.spring.law), dp_damper_law_name(s->model.damper.law));
    dp_wp_report wp;
    dp_wellposedness(&s->model, &wp);
    int st = dp_buf_append(out, head, n > 0 && (size_t)n < sizeof head ? (size_t)n : 0);
    st |= dp_wellposedness_json(&wp, out);
    st |= dp_buf_append(out, "}", 1);
    return st ? DP_ENOMEM : DP_OK;
}
