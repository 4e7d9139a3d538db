/* src/core/solvers/network/network_quakes.h - internal: the slip-event catalogue of a network run
 * (output.quakes, docs/quakes.md). The network run calls it where the state has moved over a (sub-)step and
 * the elements' phases are known; it says which quakes ended, and at t_end which are open, and the run hands
 * them out (network_output.c: this file calls nothing of the run's, so the two make no circle). Memory is a few numbers per node and element, whatever the run's length. */
#ifndef DASHPOT_CORE_NETWORK_QUAKES_H
#define DASHPOT_CORE_NETWORK_QUAKES_H

#include "dashpot/run.h"

struct dp_network_run;
typedef struct dp_quakes dp_quakes;

/* The catalogue at the run's start, time t (state and phases set): elements slipping then start quakes at t.
 * Stores it in nr->quakes; DP_OK or DP_ENOMEM. */
int network_quakes_begin(struct dp_network_run *nr, double t);

/* After the state moved from the last call's time to t: the slip of every element that slipped at the
 * (sub-)step's start (`before`) or end (the run's phases now) goes to its quake, elements that start to slip
 * join or start quakes. Returns how many quakes ended (all their elements stick again), in *ended, valid
 * until the next call; the run hands them out. 0 without a catalogue. */
size_t network_quakes_step(struct dp_network_run *nr, const unsigned char *before, double t,
                           const dp_quake **ended);

/* At t_end: every quake still going, open, in the order of their start (once; 0 after). */
size_t network_quakes_finish(struct dp_network_run *nr, double t, const dp_quake **open);

void network_quakes_free(dp_quakes *q);

#endif
