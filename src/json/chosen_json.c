/* src/json/chosen_json.c - the meta line's "chosen": the members dashpot chose because the document left them
 * out (dp_spec_choose). Every family's meta writer (meta_json.c, lcp_json.c, right_hand_meta.c) writes it, so
 * it lives below them all. */
#include <string.h>

#include "dashpot/json.h"

static int lit(dp_buf *out, const char *s)
{
    return dp_buf_append(out, s, strlen(s));
}

/* ,"chosen":["theta","every"]: the members dashpot chose because the document left them out (dp_spec_choose);
 * nothing when it chose none. */
int dp_chosen_json(const dp_spec *s, dp_buf *out)
{
    if (s->chosen == 0)
        return 0;
    int st = lit(out, ",\"chosen\":[");
    if (s->chosen & DP_CHOSEN_THETA)
        st |= lit(out, "\"theta\"");
    if (s->chosen & DP_CHOSEN_EVERY)
        st |= lit(out, s->chosen & DP_CHOSEN_THETA ? ",\"every\"" : "\"every\"");
    return st | lit(out, "]");
}
