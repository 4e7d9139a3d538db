/* src/core/network/newmark_step.h - internal: one Newmark step in Höschl's incremental tangent-stiffness form
 * (include/dashpot/newmark.h) over band matrices, shared by the one-mass run (newmark.c) and networks
 * (network_run.c). */
#ifndef DASHPOT_CORE_NEWMARK_STEP_H
#define DASHPOT_CORE_NEWMARK_STEP_H

#include <stddef.h>
#include "dashpot/newmark.h"

typedef struct dp_nm {
    size_t n, p, nep;
    double beta, gamma;
    const double *M, *C, *K;     /* the linear parts, band storage n x (p+1) (GSL's symmetric band) */
    const long *ea, *eb;         /* elastoplastic elements: ends (-1: the ground) and stiffness */
    const double *ek;
    double *a;                   /* the acceleration at the current state */
    double *Khat, *Mfac, *r, *tmp, *Pold;
    unsigned char *tan;          /* per elastoplastic element: its tangent is k (1) or 0 in the factored K^ */
    double h_fac;
    int factored;
} dp_nm;

dp_nm *dp_nm_alloc(size_t n, size_t p, size_t nep);
void dp_nm_free(dp_nm *w);

/* Factors M and takes the acceleration from the equation of motion at (x, v) with load P and the
 * elastoplastic forces Fep; P is remembered as the step's starting load. DP_OK or DP_ESOLVE. */
int dp_nm_start(dp_nm *w, const double *x, const double *v, const double *P, const double *Fep);

/* Moves (x, v) by one step of length h to the load Pnew; flow[i] != 0 where elastoplastic element i slid
 * in the last step (its tangent stiffness is then 0). DP_OK or DP_ESOLVE. */
int dp_nm_step(dp_nm *w, double h, const double *Pnew, const signed char *flow, double *x, double *v);

/* After the caller's return mapping: the acceleration from the equation of motion at the step's end. */
void dp_nm_accel(dp_nm *w, const double *x, const double *v, const double *P, const double *Fep);

#endif
