/* src/core/record/row_queue.h - internal: the rows of a block and the records that did not fit it, for the
 * run types whose samples are rows (networks, right-hand models). A row handed to the caller lives in a slot
 * of the block (dp_row_slots, one per record the caller can take); a record that does not fit waits in a FIFO
 * that grows rather than drop (dp_row_queue), a row's numbers copied with it. Once written by each of them. */
#ifndef DASHPOT_CORE_RECORD_ROW_QUEUE_H
#define DASHPOT_CORE_RECORD_ROW_QUEUE_H

#include "record/sink.h"

/* Row slots of the block being produced: cap rows of width numbers, used so far. */
typedef struct dp_row_slots {
    double *data;
    size_t width, used, cap;
} dp_row_slots;

/* Empties the slots for a new block and makes room for `want` rows (kept when already there). DP_OK or
 * DP_ENOMEM (the slots are then as they were, emptied). */
int dp_row_slots_reserve(dp_row_slots *s, size_t want);

/* The next free slot, or NULL when the block's slots are used up. */
static inline double *dp_row_slots_take(dp_row_slots *s)
{
    return s->used < s->cap ? s->data + s->used++ * s->width : NULL;
}

/* Records waiting for the caller, in order; a row's numbers in data (width per record). */
typedef struct dp_row_queue {
    dp_record *rec;
    double *data;
    size_t width, head, n, cap;
} dp_row_queue;

/* A queue for rows of `width` numbers with room for `cap` records (it grows past them). DP_OK or DP_ENOMEM. */
int dp_row_queue_init(dp_row_queue *q, size_t width, size_t cap);
void dp_row_queue_clear(dp_row_queue *q);

/* Appends rec (a row's numbers from `row`, NULL for other records). DP_OK or DP_ENOMEM (nothing queued). */
int dp_row_queue_push(dp_row_queue *q, const dp_record *rec, const double *row);

/* Whether records wait. */
static inline int dp_row_queue_waiting(const dp_row_queue *q)
{
    return q->n > q->head;
}

/* Moves waiting records into r's block while it has room, each row into a slot of its own (it stops when the
 * slots are used up). */
void dp_row_queue_flush(dp_row_queue *q, dp_run *r, dp_row_slots *slots);

#endif
