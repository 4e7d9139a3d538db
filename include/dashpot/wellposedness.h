/* include/dashpot/wellposedness.h - what the theorems guarantee about a model (docs/mathematics.md §5).
 *
 * From the graphs' own properties, existence and uniqueness are decided separately: guaranteed (by which
 * theorem of which seed, hypotheses checked) or not guaranteed (which hypothesis fails, with a witness).
 * Two frameworks: (PC) for a linear spring and a damper F_d = F_c - gamma(v), (F_c, v) in A (Pražák & Rajagopal 2016
 * Thms 2, 3; Babováková 2012 Thms 3.2, 3.3), and (PI) for x = f(F_s), x' = g(F_d) (Babováková 2012 Thms 2.1, 2.2).
 */
#ifndef DASHPOT_WELLPOSEDNESS_H
#define DASHPOT_WELLPOSEDNESS_H

#include <stddef.h>
#include "dashpot/model.h"

#define DP_WP_MAX_CHECKS 12
#define DP_WP_TEXT 512

/* One hypothesis: its name as the source writes it, whether it holds, and why (a witness if not). */
typedef struct dp_wp_check {
    const char *name;          /* e.g. "A monotone (Pražák & Rajagopal 2016 (6))" */
    int holds;
    char detail[DP_WP_TEXT];
} dp_wp_check;

typedef struct dp_wp_verdict {
    int guaranteed;
    const char *theorem;       /* the theorem that guarantees it, or NULL */
    char reason[DP_WP_TEXT];   /* the failing hypotheses (or "all hypotheses hold") */
} dp_wp_verdict;

typedef struct dp_wp_report {
    const char *framework;     /* "PC" or "PI" */
    dp_wp_check check[DP_WP_MAX_CHECKS];
    size_t nchecks;
    dp_wp_verdict existence, uniqueness;
    /* A known counterexample of the seeds applies: solutions may branch, and the stick-slip solver offers
     * `branch: "rest" | "motion"`; counterexample names the source. NULL when none is known. */
    const char *counterexample;
} dp_wp_report;

/* Analyses a prepared (or leniently parsed) model. Never fails. */
void dp_wellposedness(const dp_model *m, dp_wp_report *rep);

#endif
