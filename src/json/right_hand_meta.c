/* src/json/right_hand_meta.c - the meta line of a right-hand friction run (docs/systems.md §6): the model
 * and its parameters, what each row's groups hold, the conditions (1.2), (2.3), (6.2)-(6.4) with their
 * margins at the initial state, and the theorems of Matrosov & Finogenko 1995 that cover it
 * (src/core/analysis/right_hand_wp.c). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dashpot/json.h"
#include "dashpot/right_hand.h"
#include "dashpot/wellposedness.h"

static int lit(dp_buf *out, const char *s)
{
    return dp_buf_append(out, s, strlen(s));
}

/* ,"key":x (null when x is not finite: a condition that does not apply). */
static int num(dp_buf *out, const char *key, double x)
{
    char t[40];
    int s = lit(out, ",\"") | lit(out, key) | lit(out, "\":");
    return s | (isfinite(x) ? dp_buf_append(out, t, dp_format_double(t, x)) : lit(out, "null"));
}

static int parameters(const dp_right_hand_model *m, dp_buf *out)
{
    int st = lit(out, ",\"parameters\":{\"g\":");
    char t[40];
    st |= dp_buf_append(out, t, dp_format_double(t, m->g));
    if (m->kind == DP_RIGHT_HAND_ROD)
        return st | num(out, "m", m->m) | num(out, "length", m->length) | num(out, "mu", m->mu) |
               num(out, "restitution", m->e) | lit(out, "}");
    st |= num(out, "m1", m->m1) | num(out, "m2", m->m2) | num(out, "J_C", m->J_C) | num(out, "r", m->r);
    return st | num(out, "alpha", m->alpha) | num(out, "f1", m->f1) | num(out, "f2", m->f2) | lit(out, "}");
}

static int conditions(const dp_spec *s, dp_buf *out)
{
    dp_right_hand_result res;
    dp_right_hand_solve(s->rh, s->x0v, s->v0v, NULL, &res);
    int st = lit(out, ",\"conditions\":");
    if (res.n < 1)
        return st | lit(out, "null");
    dp_right_hand_conditions c;
    dp_right_hand_conditions_at(s->rh, s->x0v, s->v0v, &res.sol[0], &c);
    st |= lit(out, "{\"at\":\"initial state\"") | num(out, "1.2", c.c12) | num(out, "2.3", c.c23);
    if (s->rh->kind == DP_RIGHT_HAND_PISTON_HINGE)
        st |= num(out, "6.2", c.c62) | num(out, "6.3", c.c63) | num(out, "6.4", c.c64);
    return st | lit(out, c.in_A ? ",\"in_A\":true}" : ",\"in_A\":false}");
}

int dp_right_hand_meta_json(const dp_spec *s, dp_buf *out)
{
    const dp_solver_spec *sv = &s->solver;
    const dp_right_hand_model *m = s->rh;
    int rod = m->kind == DP_RIGHT_HAND_ROD;
    int st = lit(out, "{\"type\":\"meta\",\"version\":\"" DP_VERSION "\",\"solver\":\"right-hand\",\"stepper\":"
                      "\"rk8pd\",\"events_mode\":\"locate\",\"model\":\"") | lit(out, dp_right_hand_kind_name(m->kind));
    st |= lit(out, "\"") | num(out, "rtol", sv->rtol) | num(out, "atol", sv->atol);
    st |= num(out, "dt", sv->dt) | num(out, "t_end", sv->t_end) | num(out, "steps", dp_spec_steps(s));
    st |= num(out, "every", (double)s->output.every) | dp_chosen_json(s, out);
    st |= parameters(m, out);
    st |= lit(out, rod ? ",\"columns\":{\"q\":[\"x_A\",\"theta\"],\"N\":[\"N\"],\"margin\":[\"1.2\",\"2.3\"],"
                         "\"gap\":[\"y_A\",\"yd_A\"]}"
                       : ",\"columns\":{\"q\":[\"x\",\"beta\"],\"N\":[\"N1\",\"N2\"],"
                         "\"margin\":[\"1.2\",\"2.3\",\"6.2\",\"6.4\"]}");
    st |= conditions(s, out);
    dp_wp_report wp;
    dp_right_hand_wellposedness(m, s->x0v, s->v0v, &wp);
    st |= lit(out, ",\"wellposedness\":") | dp_wellposedness_json(&wp, out) | lit(out, "}");
    return st ? DP_ENOMEM : DP_OK;
}
