/* src/core/solvers/network/network_quakes.h - internal: the slip-event catalogue of a network run
 * (output.quakes, docs/quakes.md). The network run calls it where the state has moved over a (sub-)step and
 * the elements' phases are known; it hands out a quake record when an episode ends, and the open ones at
 * t_end. Memory is a few numbers per node and element, whatever the run's length. */
#ifndef DASHPOT_CORE_NETWORK_QUAKES_H
#define DASHPOT_CORE_NETWORK_QUAKES_H

#include "record/sink.h"

struct dp_network_run;
typedef struct dp_quakes dp_quakes;

/* The catalogue at the run's start (state and phases at t = 0 set): elements slipping then start quakes at
 * 0. Stores it in the run's state; DP_OK or DP_ENOMEM. */
int network_quakes_begin(dp_run *r);

/* After the state moved from the last call's time to t: the slip of every element that slipped at the
 * (sub-)step's start (`before`) or end (the run's phases now) goes to its quake, elements that start to slip
 * join or start quakes, quakes whose elements all stick again are handed out. */
void network_quakes_step(dp_run *r, const unsigned char *before, double t);

/* At t_end: every quake still going, handed out open, in the order of their start. */
void network_quakes_finish(dp_run *r);

void network_quakes_free(dp_quakes *q);

#endif
