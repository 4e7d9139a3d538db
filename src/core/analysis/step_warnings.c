/* src/core/analysis/step_warnings.c - the warnings of a valid spec (include/dashpot/warnings.h).
 *
 * A coarse step: a fixed-step solver (stick-slip's theta-method, Newmark) whose dt is longer than a tenth of
 * the shortest natural period 2 pi / omega_max resolves no oscillation of that mode. θ = 1 damps it away, θ = ½
 * keeps its energy at the wrong frequency, and both answer with confidence (m = 0.001, k = 1e6, dt = 1e-3: each
 * step spans five periods). omega_max^2 is the largest eigenvalue of K phi = omega^2 M phi with the linear
 * springs' stiffness; it is bounded from above without an eigensolver by Gershgorin's theorem:
 *   diagonal masses:  omega_max^2 <= max_i (sum_j |K_ij|) / m_i,
 *   a mass matrix:    omega_max^2 <= max_i (sum_j |K_ij|) / min_i (M_ii - sum_{j != i} |M_ij|)  (if > 0),
 * so the period is estimated from below and the warning errs towards warning (by at most a factor of 2 in
 * omega^2 for a chain). Graph springs, compliant contacts and the solvers that choose their own steps
 * (regularized, right-hand, analytic) are not judged. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dashpot/network.h"
#include "dashpot/warnings.h"

/* A tenth of a period: about the coarsest step at which the theta-method still follows an oscillation. */
#define DP_STEPS_PER_PERIOD 10

/* The elastic stiffness of a spring whose law-table entry names one; 0 for the others (a graph spring). */
static double spring_k(const dp_spring *sp, int has)
{
    const dp_spring_law_info *L = has ? dp_spring_law_info_of(sp->law) : NULL;
    return L && L->elastic ? fabs(dp_law_field_value(sp, L->elastic)) : 0;
}

/* Gershgorin's bound on omega_max^2 of a network; 0 when it has none (no stiffness, or M's bound <= 0). */
static double network_omega2(const dp_network *net)
{
    size_t n = net->n;
    double *row = calloc(n, sizeof *row), w2 = 0;
    if (row == NULL)
        return 0;
    for (size_t e = 0; e < net->nel; e++) {
        const dp_element *el = &net->el[e];
        double k = spring_k(&el->spring, el->has_spring);
        if (el->a >= 0)
            row[el->a] += el->b >= 0 ? 2 * k : k;
        if (el->b >= 0)
            row[el->b] += el->a >= 0 ? 2 * k : k;
    }
    for (size_t i = 0; net->K && i < n; i++)
        for (size_t j = 0; j < n; j++)
            row[i] += fabs(net->K[i * n + j]);
    double mmin = INFINITY;
    for (size_t i = 0; net->M && i < n; i++) {
        double off = 0;
        for (size_t j = 0; j < n; j++)
            off += j != i ? fabs(net->M[i * n + j]) : 0;
        mmin = fmin(mmin, net->M[i * n + i] - off);
    }
    for (size_t i = 0; i < n; i++) {
        double m = net->M ? mmin : net->mass[i];
        if (m > 0 && row[i] > 0)
            w2 = fmax(w2, row[i] / m);
    }
    free(row);
    return net->M && !(mmin > 0) ? 0 : w2;
}

static void add(dp_warnings *w, const char *code, const char *pointer, const char *fmt, double a, double b,
                double c, double d)
{
    if (w->n == DP_WARNINGS_MAX)
        return;
    dp_warning *it = &w->item[w->n++];
    it->code = code;
    snprintf(it->pointer, sizeof it->pointer, "%s", pointer);
    snprintf(it->detail, sizeof it->detail, fmt, a, b, c, d);
}

void dp_spec_warnings(const dp_spec *s, dp_warnings *w)
{
    w->n = 0;
    dp_solver_kind kind = s->solver.kind;
    if (s->lcs || s->rh || (kind != DP_SOLVER_STICK_SLIP && kind != DP_SOLVER_NEWMARK))
        return;
    double w2 = s->net ? network_omega2(s->net) : spring_k(&s->model.spring, 1) / s->model.mass;
    if (!(w2 > 0) || !isfinite(w2))
        return;
    double period = 2 * M_PI / sqrt(w2), dt = s->solver.dt;
    if (dt > period / DP_STEPS_PER_PERIOD)
        add(w, "coarse-step", "/solver/dt",
            "dt = %.6g is %.3g of the shortest natural period 2 pi/omega_max = %.6g (omega_max <= %.6g from the "
            "springs and masses): the steps resolve no oscillation of that mode; a tenth of the period or less "
            "follows it", dt, dt / period, period, sqrt(w2));
}
