/* src/core/solvers/thesis.c - algorithm 4.1 of Babováková 2012 (the thesis' MATLAB algorithm), step for step.
 *
 *   p1 = m/dt; p2 = p1 + k dt; F~ = p1 v^n + F^{n+1} - F_s^n;
 *   if |F~| < phi0:  v^{n+1} = 0, F_c = F~                                   (4.11), (4.6)
 *   else:            F_c = phi0 sgn F~; v_{i+1} = (F~ - F_c + gamma(v_i))/p2,
 *                    i = 1..Z, stop when |v_i - v_{i+1}| < eps, from v_1 = v^n   (4.12), (4.13)
 *   F_s^{n+1} = F_s^n + dt k v^{n+1};  x^{n+1} = F_s^{n+1} / k.
 *
 * Kept literal (strict < in the stick test, the iteration's start and stopping rule, x recovered from F_s)
 * so that its output is the thesis' own; spec.c has already checked (4.8) and (4.10).
 */
#include <math.h>
#include <stdio.h>

#include "record/sink.h"
#include "rules/rules.h"
#include "solvers/run_types.h"
#include "solvers/stick_slip_step.h"

static int thesis_advance(dp_run *r)
{
    const dp_ss_law *L = &r->law;
    const dp_solver_spec *sv = &r->spec.solver;
    double phi0 = L->tau;
    while (dp_run_room(r)) {
        if (dp_run_stopped(r, dp_run_work(r)))
            return r->status;
        double dt = dp_run_step_length(r);
        double t1 = r->n + 1 < r->nsteps ? (double)(r->n + 1) * r->h : sv->t_end;
        double p1 = L->m / dt, p2 = p1 + L->k * dt;
        double FF = p1 * r->cur.v + dp_forcing_eval(L->F, t1) - r->cur.Fs, Fc, v1;
        dp_phase before = r->cur.phase;
        if (fabs(FF) < phi0) {
            v1 = 0;
            Fc = FF;
        } else {
            Fc = phi0 * ((FF > 0) - (FF < 0));
            double vi = r->cur.v, vn = vi;
            for (int i = 1; i <= sv->Z; i++) {
                /* Z may be 10^6: poll inside the step too, for a stop only (a yield waits for the step) */
                if (dp_run_stopped(r, dp_run_work(r)) && r->status != DP_OK)
                    return r->status;
                vn = (FF - Fc + dp_relaxation_eval(L->gamma, vi)) / p2;
                r->sum.iterations++;
                if (fabs(vi - vn) < sv->eps)
                    break;
                vi = vn;
            }
            v1 = vn;
        }
        double Fs = dt * L->k * v1 + r->cur.Fs, Fd = Fc - dp_relaxation_eval(L->gamma, v1);
        r->n++;
        if (!isfinite(Fs) || !isfinite(v1) || !isfinite(Fc) || !isfinite(Fs / L->k) || !isfinite(Fd)) {
            char msg[DP_MESSAGE_MAX];
            snprintf(msg, sizeof msg, "the solution diverged at t = %.17g", t1);
            return dp_one_mass_nonfinite(r, msg, r->cur.t, r->cur.x, r->cur.v);
        }
        dp_sample *c = &r->cur;
        c->t = t1, c->v = v1, c->Fs = Fs, c->x = Fs / L->k, c->Fc = Fc;
        c->Fd = Fd;
        c->phase = v1 == 0 ? DP_PHASE_STICK : DP_PHASE_SLIP;
        if (c->phase == DP_PHASE_STICK)
            r->sum.stick_time += dt;
        if (c->phase != before)
            dp_run_emit_event(r, c->phase == DP_PHASE_STICK ? DP_EVENT_STICK : DP_EVENT_SLIP, t1, c->x, v1);
        r->sum.steps = r->n;
        if (r->n >= r->nsteps)
            r->finished = 1;
        dp_run_emit_state(r);
    }
    return DP_OK;
}

const dp_run_type dp_run_thesis = {
    .name = "stick-slip", .variant = "thesis", .events_mode = dp_one_mass_events_mode, .check = dp_rules_thesis, .init = dp_stick_slip_init, .advance = thesis_advance,
};
