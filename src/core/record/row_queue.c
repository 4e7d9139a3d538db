/* src/core/record/row_queue.c - the block's row slots and the FIFO of records that did not fit the block
 * (row_queue.h), shared by the network run and the right-hand run, which had each written their own. */
#include <stdlib.h>
#include <string.h>

#include "record/row_queue.h"

int dp_row_slots_reserve(dp_row_slots *s, size_t want)
{
    s->used = 0;
    if (want <= s->cap)
        return DP_OK;
    double *d = realloc(s->data, want * (s->width ? s->width : 1) * sizeof *d);
    if (d == NULL)
        return DP_ENOMEM;
    s->data = d, s->cap = want;
    return DP_OK;
}

int dp_row_queue_init(dp_row_queue *q, size_t width, size_t cap)
{
    *q = (dp_row_queue){ .width = width, .cap = cap ? cap : 1 };
    q->rec = calloc(q->cap, sizeof *q->rec);
    q->data = calloc(q->cap * (width ? width : 1), sizeof *q->data);
    return q->rec && q->data ? DP_OK : DP_ENOMEM;
}

void dp_row_queue_clear(dp_row_queue *q)
{
    free(q->rec);
    free(q->data);
    *q = (dp_row_queue){ 0 };
}

int dp_row_queue_push(dp_row_queue *q, const dp_record *rec, const double *row)
{
    size_t w = q->width;
    if (q->n == q->cap) {   /* a step with more records than the queue held: grow it, never drop */
        size_t cap = 2 * q->cap;
        dp_record *r = realloc(q->rec, cap * sizeof *r);
        if (r == NULL)
            return DP_ENOMEM;
        q->rec = r;
        double *d = realloc(q->data, cap * (w ? w : 1) * sizeof *d);
        if (d == NULL)
            return DP_ENOMEM;
        q->data = d, q->cap = cap;
    }
    q->rec[q->n] = *rec;
    if (row != NULL && w > 0)
        memcpy(q->data + q->n * w, row, w * sizeof *row);
    q->n++;
    return DP_OK;
}

void dp_row_queue_flush(dp_row_queue *q, dp_run *r, dp_row_slots *slots)
{
    size_t w = q->width;
    while (q->head < q->n && r->out_n < r->out_cap) {
        dp_record rec = q->rec[q->head];
        if (rec.type == DP_RECORD_ROW) {
            double *d = dp_row_slots_take(slots);
            if (d == NULL)
                break;
            memcpy(d, q->data + q->head * w, w * sizeof *d);
            rec.u.row.val = d;
        }
        r->out[r->out_n++] = rec;
        q->head++;
    }
    if (q->head == q->n)
        q->head = q->n = 0;
}
