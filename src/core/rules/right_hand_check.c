/* src/core/rules/right_hand_check.c - the cross-field rules of a right-hand friction spec (docs/systems.md §6): its
 * models go with the right-hand solver and it with them; the parameters make a mechanism (masses and
 * lengths > 0, alpha in [0, pi/2], coefficients >= 0, gravity > 0) - the parser checks each number, this
 * restates them for specs built in C. */
#include <math.h>
#include <stdio.h>

#include "dashpot/right_hand.h"
#include "dashpot/spec.h"

/* A member of the model or the initial state and its value. */
typedef struct member { char ptr[24]; double v; } member;

static double decades(double v)
{
    return v == 0 || !isfinite(v) ? 0 : fabs(log10(fabs(v)));
}

/* The model's numbers and the initial state: the members an overflow of the acceleration problem is blamed
 * on (the one farthest from 1 in decades); returns how many. */
static size_t members(const dp_spec *s, member *out)
{
    const dp_right_hand_model *m = s->rh;
    size_t n = 0;
    if (m->kind == DP_RIGHT_HAND_ROD) {
        out[n++] = (member){ "/model/m", m->m }, out[n++] = (member){ "/model/length", m->length };
        out[n++] = (member){ "/model/mu", m->mu };
    } else {
        out[n++] = (member){ "/model/m1", m->m1 }, out[n++] = (member){ "/model/m2", m->m2 };
        out[n++] = (member){ "/model/J_C", m->J_C }, out[n++] = (member){ "/model/r", m->r };
        out[n++] = (member){ "/model/f1", m->f1 }, out[n++] = (member){ "/model/f2", m->f2 };
    }
    out[n++] = (member){ "/model/g", m->g };
    for (int i = 0; i < (m->kind == DP_RIGHT_HAND_ROD ? 3 : 2); i++) {
        out[n] = (member){ "", s->x0v[i] }, snprintf(out[n].ptr, sizeof out[n].ptr, "/initial/x/%d", i), n++;
        out[n] = (member){ "", s->v0v[i] }, snprintf(out[n].ptr, sizeof out[n].ptr, "/initial/v/%d", i), n++;
    }
    return n;
}

/* The acceleration problem at the initial state (every candidate's q'', N, Q) and the reach of the motion
 * over the run, |q| + t_end |q'| + t_end^2 |q''|: finite, or a 422 at the member farthest from 1 in decades
 * rather than a run that stops on an infinite reaction reported as a paradox. */
static void check_finite(const dp_spec *s, dp_errors *e)
{
    dp_right_hand_result res;
    dp_right_hand_solve(s->rh, s->x0v, s->v0v, NULL, &res);
    double T = s->solver.t_end, big = 0;
    for (int i = 0; i < res.n && i < DP_RIGHT_HAND_MAX_SOL; i++)
        for (int k = 0; k < 2; k++) {
            const dp_right_hand_sol *c = &res.sol[i];
            big = fmax(big, fmax(fabs(c->qdd[k]), fmax(fabs(c->N[k]), fabs(c->Q[k]))));
            big = fmax(big, fabs(s->x0v[k]) + T * fabs(s->v0v[k]) + T * T * fabs(c->qdd[k]));
            if (isnan(c->qdd[k]) || isnan(c->N[k]) || isnan(c->Q[k]))
                big = INFINITY;
        }
    for (int k = 0; k < 2; k++)
        big = fmax(big, fabs(s->x0v[k]) + T * fabs(s->v0v[k]));
    if (s->rh->kind == DP_RIGHT_HAND_ROD)   /* a flight's reach: its height, rate and fall */
        big = fmax(big, fabs(s->x0v[2]) + T * fabs(s->v0v[2]) + T * T * s->rh->g);
    dp_right_hand_frame fr;   /* the equations themselves, which a paradox with no candidate also reads */
    dp_right_hand_frame_at(s->rh, s->x0v, s->v0v, &fr);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double q = fr.A[i][j] + fr.b[i] + fr.w[i][j] + fr.W[i][j][0] + fr.W[i][j][1];
            big = isfinite(q) ? big : INFINITY;
        }
    if (isfinite(big))
        return;
    member f[16];
    size_t n = members(s, f), worst = 0;
    for (size_t i = 1; i < n; i++)
        if (decades(f[i].v) > decades(f[worst].v))
            worst = i;
    dp_errors_add(e, f[worst].ptr, "the acceleration problem at the initial state, or the motion's reach |q| + "
                  "t_end |q'| + t_end^2 |q''| over the run, overflows double precision: %s = %g is too large or "
                  "too small for the model's other numbers", f[worst].ptr, f[worst].v);
}

void dp_right_hand_check(const dp_spec *s, dp_errors *e)
{
    if (s->rh == NULL) {
        dp_errors_add(e, "/solver/kind", "the right-hand solver takes a model of kind \"piston-hinge\" or "
                      "\"painleve-rod\"");
        return;
    }
    size_t before = e->n + e->dropped;
    if (s->solver.kind != DP_SOLVER_RIGHT_HAND)
        dp_errors_add(e, "/solver/kind", "a %s model is solved by the solver of kind \"right-hand\"",
                      dp_right_hand_kind_name(s->rh->kind));
    const char *key, *why;
    if (!dp_right_hand_model_valid(s->rh, &key, &why)) {
        char ptr[64];
        snprintf(ptr, sizeof ptr, "/model/%s", key);
        dp_errors_add(e, ptr, "%s", why);
    }
    for (int i = 0; i < 2; i++) {
        if (s->x0v == NULL || !isfinite(s->x0v[i]))
            dp_errors_add(e, "/initial/x", "must be an array of 2 finite numbers");
        if (s->v0v == NULL || !isfinite(s->v0v[i]))
            dp_errors_add(e, "/initial/v", "must be an array of 2 finite numbers");
        if (s->x0v == NULL || s->v0v == NULL)
            break;
    }
    if (!(s->solver.rtol > 0 && s->solver.rtol < 1))
        dp_errors_add(e, "/solver/rtol", "must be in (0, 1), got %g", s->solver.rtol);
    if (s->rh->kind == DP_RIGHT_HAND_ROD && s->x0v && !(s->x0v[1] > 0 && s->x0v[1] < M_PI))
        dp_errors_add(e, "/initial/x/1", "the rod's angle to the floor must be in (0, pi) with its end A "
                      "lowest and the rod above it, got %g", s->x0v[1]);
    if (s->rh->kind == DP_RIGHT_HAND_ROD && s->x0v && !(s->x0v[2] >= 0 && isfinite(s->x0v[2])))
        dp_errors_add(e, "/initial/x/2", "the height of the rod's end A above the floor must be a finite number "
                      ">= 0, got %g", s->x0v[2]);
    if (s->rh->kind == DP_RIGHT_HAND_ROD && s->v0v && !isfinite(s->v0v[2]))
        dp_errors_add(e, "/initial/v/2", "must be a finite number, got %g", s->v0v[2]);
    if (e->n + e->dropped == before && s->x0v && s->v0v)
        check_finite(s, e);
}
