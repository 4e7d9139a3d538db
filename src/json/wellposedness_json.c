/* src/json/wellposedness_json.c - the well-posedness report (wellposedness.h) as a JSON object, for
 * /v1/wellposedness, `dashpot wellposedness` and the meta of every simulation. */
#include <stdio.h>
#include <string.h>

#include "dashpot/encode.h"
#include "dashpot/json.h"

static int lit(dp_buf *b, const char *s)
{
    return dp_buf_append(b, s, strlen(s));
}

static int verdict(dp_buf *b, const char *name, const dp_wp_verdict *v)
{
    int s = lit(b, "\"") | lit(b, name) | lit(b, v->guaranteed ? "\":{\"guaranteed\":true,\"theorem\":"
                                                                : "\":{\"guaranteed\":false,\"theorem\":");
    s |= v->theorem ? dp_json_quote(b, v->theorem) : lit(b, "null");
    s |= lit(b, ",\"reason\":") | dp_json_quote(b, v->reason) | lit(b, "}");
    return s;
}

int dp_wellposedness_json(const dp_wp_report *r, dp_buf *b)
{
    int s = lit(b, "{\"framework\":") | dp_json_quote(b, r->framework) | lit(b, ",");
    s |= verdict(b, "existence", &r->existence) | lit(b, ",");
    s |= verdict(b, "uniqueness", &r->uniqueness) | lit(b, ",\"checks\":[");
    for (size_t i = 0; i < r->nchecks; i++) {
        const dp_wp_check *c = &r->check[i];
        s |= lit(b, i ? ",{\"hypothesis\":" : "{\"hypothesis\":") | dp_json_quote(b, c->name);
        s |= lit(b, c->holds ? ",\"holds\":true,\"detail\":" : ",\"holds\":false,\"detail\":");
        s |= dp_json_quote(b, c->detail) | lit(b, "}");
    }
    s |= lit(b, "],\"counterexample\":");
    s |= r->counterexample ? dp_json_quote(b, r->counterexample) : lit(b, "null");
    s |= lit(b, r->counterexample ? ",\"branches\":[\"rest\",\"motion\"]}" : "}");
    return s ? DP_ENOMEM : DP_OK;
}
