/* src/core/solvers/run_types.h - internal: the run types the solvers define, one per file, for the table
 * in runs/run_table.c. */
#ifndef DASHPOT_CORE_SOLVERS_RUN_TYPES_H
#define DASHPOT_CORE_SOLVERS_RUN_TYPES_H

#include "record/sink.h"

extern const dp_run_type dp_run_stick_slip;        /* stick_slip.c: the exact theta-step, located events */
extern const dp_run_type dp_run_thesis;            /* thesis.c: the thesis' algorithm 4.1 (Babovakova 2012) */
extern const dp_run_type dp_run_analytic;          /* analytic.c: the closed form of Coulomb friction */
extern const dp_run_type dp_run_regularized;       /* regularized.c: the regularized ODE (GSL odeiv2) */
extern const dp_run_type dp_run_newmark;           /* newmark.c: Hoschl's incremental Newmark, one mass */
extern const dp_run_type dp_run_network;           /* network/network_run.c: networks of masses */
extern const dp_run_type dp_run_network_regularized; /* network/network_run.c: their regularized ODE */
extern const dp_run_type dp_run_network_newmark;   /* network/network_run.c: Newmark on networks */
extern const dp_run_type dp_run_network_one_mass;  /* network/network_one_mass.c: one mass, one element */
extern const dp_run_type dp_run_network_contact_lean; /* network/network_contact_lean.c: the bouncing ball */
extern const dp_run_type dp_run_network_grounded_chain; /* network/network_grounded_chain.c: stop and
                                                          * friction chains */
extern const dp_run_type dp_run_lcs;               /* lcs_run.c: linear complementarity systems */
extern const dp_run_type dp_run_right_hand;        /* right_hand_run.c: friction with motion-dependent N */

/* How a one-mass stick-slip run reports its events (stick_slip.c): "none" when not asked, "step" when a law's
 * entry does not locate them (every entry does today: an elastoplastic spring's yield and unload too,
 * event_location.c), else "locate". */
const char *dp_one_mass_events_mode(const dp_spec *s);

#endif
