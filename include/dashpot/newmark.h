/* include/dashpot/newmark.h - Newmark's method (beta, gamma) in Höschl's incremental tangent-stiffness form
 * (Höschl 1983 §15, Ex. 40; docs/systems.md §3): beta = 1/6, gamma = 1/2 is his linear-acceleration method,
 * beta = 1/4 the average-acceleration rule.
 *
 *     K^ = K_T + (gamma / (beta h)) C + (1 / (beta h^2)) M
 *     dP^ = dP + M (v / (beta h) + a / (2 beta)) + C ((gamma / beta) v + h (gamma / (2 beta) - 1) a)
 *     dx = K^-1 dP^,   dv = (gamma / (beta h)) dx - (gamma / beta) v + h (1 - gamma / (2 beta)) a
 *
 * and the acceleration from the equation of motion at the step's end (no drift). For linear systems this
 * is the standard Newmark method exactly; elastoplastic springs enter K_T with k while elastic and 0 while
 * their slider slides, and their force is the return mapping at the new elongation.
 */
#ifndef DASHPOT_NEWMARK_H
#define DASHPOT_NEWMARK_H

#include "dashpot/spec.h"

/* The incremental form's coefficients for one step h:
 * K^ = K_T + kC C + kM M;  dP^ = dP + M (pMv v + pMa a) + C (pCv v + pCa a);  dv = vx dx + vv v + va a. */
typedef struct dp_newmark_coef {
    double kM, kC, pMv, pMa, pCv, pCa, vx, vv, va;
} dp_newmark_coef;

void dp_newmark_coef_init(double beta, double gamma, double h, dp_newmark_coef *c);

/* Stability of an undamped linear system (the elastic stiffness of every spring): unconditional when
 * 2 beta >= gamma, else omega_max h <= 1 / sqrt(gamma/2 - beta), i.e. dt / T_min <= that / (2 pi)
 * (sqrt(3)/pi for beta = 1/6, gamma = 1/2). */
typedef struct dp_newmark_limit {
    double omega_max;     /* the highest natural circular frequency (elastic stiffness) */
    double T_min;         /* 2 pi / omega_max (INFINITY without stiffness) */
    double ratio;         /* dt / T_min */
    double ratio_limit;   /* the largest stable dt / T_min; INFINITY when unconditional */
    int inside;           /* ratio <= ratio_limit */
} dp_newmark_limit;

/* For a checked spec with solver newmark (one mass or a network). DP_OK, DP_ENOMEM or DP_ESOLVE. */
int dp_newmark_limit_of(const dp_spec *s, dp_newmark_limit *out);

/* The newmark solver's rules (linear and elastoplastic springs, linear dampers, beta and gamma ranges). */
void dp_newmark_check(const dp_spec *s, dp_errors *errs);

#endif
