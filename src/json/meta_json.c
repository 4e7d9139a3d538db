/* src/json/meta_json.c - the "meta" object that opens every run's output: what was solved and how, so a
 * stored trajectory says where it came from (solver, variant, theta, dt, t_end, steps, laws). */
#include <stdio.h>

#include "dashpot/json.h"

static const char *variant_name(const dp_solver_spec *s)
{
    if (s->kind == DP_SOLVER_ANALYTIC)
        return "closed-form";
    return s->variant == DP_VARIANT_THESIS ? "thesis" : "exact";
}

size_t dp_spec_meta_json(const dp_spec *s, char *out, size_t cap)
{
    const dp_solver_spec *sv = &s->solver;
    int n = snprintf(out, cap,
        "{\"type\":\"meta\",\"version\":\"%s\",\"solver\":\"%s\",\"variant\":\"%s\",\"theta\":%.17g,"
        "\"events_mode\":\"%s\",\"dt\":%.17g,\"t_end\":%.17g,\"steps\":%.17g,\"every\":%ld,"
        "\"spring\":\"%s\",\"damper\":\"%s\"}",
        DP_VERSION, sv->kind == DP_SOLVER_ANALYTIC ? "analytic" : "stick-slip", variant_name(sv), sv->theta,
        sv->events == DP_EVENTS_LOCATE ? "locate" : "none", sv->dt, sv->t_end, dp_spec_steps(s),
        s->output.every, dp_spring_law_name(s->model.spring.law), dp_damper_law_name(s->model.damper.law));
    return n < 0 ? 0 : (size_t)n;
}
