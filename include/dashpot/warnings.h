/* include/dashpot/warnings.h - what a valid spec probably did not mean: a step too coarse for the fastest
 * oscillation it holds. The meta line carries them ("warnings"), the page shows them; a run goes on. */
#ifndef DASHPOT_WARNINGS_H
#define DASHPOT_WARNINGS_H

#include "dashpot/spec.h"

#define DP_WARNINGS_MAX 8

typedef struct dp_warning {
    const char *code;               /* a stable word for programs: "coarse-step" */
    char pointer[DP_POINTER_MAX];   /* the member to change (JSON Pointer) */
    char detail[DP_MESSAGE_MAX];    /* what and why, for a person */
} dp_warning;

typedef struct dp_warnings {
    size_t n;
    dp_warning item[DP_WARNINGS_MAX];
} dp_warnings;

/* The warnings of a checked spec into w (emptied first). Cheap: O(nodes + elements), no eigensolver, so that
 * it can run wherever the meta line is written. Never fails. */
void dp_spec_warnings(const dp_spec *s, dp_warnings *w);

#endif
