/* src/core/laws/model.c - the model's lifetime: its laws' graphs built (by the law table, law_table.c), cleared and
 * copied.
 */
#include <string.h>

#include "dashpot/model.h"
#include "dashpot/status.h"

/* A law's graph is built by its entry in the law table (law_table.c); a value that is no law is refused. */
int dp_spring_prepare(dp_spring *s)
{
    const dp_spring_law_info *L = dp_spring_law_info_of(s->law);
    return L && L->build ? L->build(s) : DP_EINVAL;
}

int dp_damper_prepare(dp_damper *d)
{
    const dp_damper_law_info *L = dp_damper_law_info_of(d->law);
    return L && L->build ? L->build(d) : DP_EINVAL;
}

int dp_model_prepare(dp_model *m)
{
    int s = dp_spring_prepare(&m->spring);
    if (s != DP_OK)
        return s;
    return dp_damper_prepare(&m->damper);
}

void dp_model_clear(dp_model *m)
{
    if (m == NULL)
        return;
    dp_graph_clear(&m->spring.graph);
    dp_graph_clear(&m->damper.graph);
    dp_forcing_clear(&m->forcing);
}

int dp_model_copy(dp_model *dst, const dp_model *src)
{
    *dst = *src;
    memset(&dst->spring.graph, 0, sizeof dst->spring.graph);
    memset(&dst->damper.graph, 0, sizeof dst->damper.graph);
    memset(&dst->forcing, 0, sizeof dst->forcing);
    int s = dp_graph_copy(&dst->spring.graph, &src->spring.graph);
    if (s == DP_OK)
        s = dp_graph_copy(&dst->damper.graph, &src->damper.graph);
    if (s == DP_OK)
        s = dp_forcing_copy(&dst->forcing, &src->forcing);
    if (s != DP_OK)
        dp_model_clear(dst);
    return s;
}
