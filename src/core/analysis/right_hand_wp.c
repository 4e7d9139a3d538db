/* src/core/analysis/right_hand_wp.c - which of Matrosov & Finogenko's theorems (Matrosov & Finogenko 1995) cover a right-hand friction
 * model from its initial state, as a well-posedness report (wellposedness.h) with each hypothesis and its
 * margin:
 *   Theorem 3.1: a local right-hand solution where (2.3) holds at a solution of (1.1) with |N_s| != 0
 *     (s not strictly stuck); with (1.2) it solves the equations of motion;
 *   Theorems 4.1, 4.2: (2.3) uniformly (here: the example's (6.4) for every beta, the rod's mu < 4/3):
 *     unique accelerations everywhere, solutions from the set A extend until they leave A;
 *   Theorem 5.1: right uniqueness where moreover no resting coordinate sits on its cone (N1 empty).
 * The enumeration (right_hand.c) says in addition whether the initial acceleration problem has exactly one
 * solution, which none of the theorems needs to assume and each of them implies.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dashpot/right_hand.h"
#include "dashpot/wellposedness.h"

/* A margin as text: %.6g when finite; an extreme model (a 5e-324 radius, a 1e308 coefficient) makes some
 * overflow, and a report says so rather than printing inf or nan. Each call writes its own buffer. */
typedef struct num_text {
    char s[40];
} num_text;

static num_text num(double x)
{
    num_text t;
    if (isfinite(x))
        snprintf(t.s, sizeof t.s, "%.6g", x);
    else
        snprintf(t.s, sizeof t.s, "(overflows double precision)");
    return t;
}

static dp_wp_check *add(dp_wp_report *rep, const char *name, int holds)
{
    dp_wp_check *c = &rep->check[rep->nchecks++];
    c->name = name, c->holds = holds;
    return c;
}

/* Theorem 4.1's hypothesis, (2.3) for every state: the paper's sufficient (6.4) at its worst beta, or for
 * the rod (k* = 1, |J_11| = (3m/4)|sin^2 -+ mu sin cos| < m) mu < min (1 + 3cos^2)/(3 sin cos) = 4/3. */
static int uniform(const dp_right_hand_model *m, dp_wp_report *rep)
{
    if (m->kind == DP_RIGHT_HAND_ROD) {
        int ok = m->mu < 4.0 / 3.0;
        dp_wp_check *c = add(rep, "(2.3) for every state (Theorem 4.1): mu < 4/3", ok);
        snprintf(c->detail, sizeof c->detail, "mu = %g %s 4/3 = min over theta of (1 + 3cos^2)/(3 sin cos), at "
                 "tan(theta) = 2", m->mu, ok ? "<" : ">=");
        return ok;
    }
    double J = m->J_C + m->m2 * m->r * m->r, mm = m->m1 + m->m2, mr = m->m2 * m->r;
    double h1 = mm / 2 - mr * sqrt(1 + m->f1 * m->f1), h2 = J / 2 - m->m2 * (m->r + m->f2);
    double h3 = J / 2 - sqrt(2) * mr * m->f2;
    int ok = h1 > 0 && h2 > 0 && h3 > 0;
    dp_wp_check *c = add(rep, "(2.3) for every state (Theorem 4.1): (6.4) at its worst beta", ok);
    snprintf(c->detail, sizeof c->detail, "margins m/2 - m2 r sqrt(1 + f1^2) = %s, J/2 - m2 (r + f2) = %s, "
             "J/2 - sqrt(2) m2 r f2 = %s (units e_sv = 1)", num(h1).s, num(h2).s, num(h3).s);
    return ok;
}

static const char *mode_word(dp_right_hand_mode m)
{
    static const char *const w[] = { "free", "stick", "slip+", "slip-" };
    return w[m];
}

void dp_right_hand_wellposedness(const dp_right_hand_model *m, const double q[2], const double qd[2], dp_wp_report *rep)
{
    memset(rep, 0, sizeof *rep);
    rep->framework = "right-hand solutions (Matrosov & Finogenko 1995)";
    dp_right_hand_result res;
    dp_right_hand_solve(m, q, qd, NULL, &res);
    int unique = res.n == 1 && !res.continuum;
    dp_wp_check *c = add(rep, "one acceleration at the initial state (every stick/slip mode enumerated)", unique);
    if (unique)
        snprintf(c->detail, sizeof c->detail, "qdd = [%s, %s], modes (%s, %s), N = [%s, %s]",
                 num(res.sol[0].qdd[0]).s, num(res.sol[0].qdd[1]).s, mode_word(res.sol[0].mode[0]),
                 mode_word(res.sol[0].mode[1]), num(res.sol[0].N[0]).s, num(res.sol[0].N[1]).s);
    else
        snprintf(c->detail, sizeof c->detail, "Painleve %s: %d solutions%s", res.n ? "indeterminacy" :
                 "inconsistency", res.n, res.continuum ? " and a continuum" : "");
    dp_right_hand_conditions k = { 0 };
    int c12 = 0, c23 = 0, nonzero = 0, n1empty = 0;
    if (res.n >= 1) {
        const dp_right_hand_sol *s = &res.sol[0];
        dp_right_hand_conditions_at(m, q, qd, s, &k);
        c12 = k.c12 > 0, c23 = k.c23 > 0;
        nonzero = k.in_A, n1empty = 1;
        dp_right_hand_frame fr;
        dp_right_hand_frame_at(m, q, qd, &fr);
        for (int i = 0; i < 2; i++) {
            int stuck = s->mode[i] == DP_RIGHT_HAND_STICK;
            int on_cone = stuck && fabs(s->Q[i]) >= fr.f[i] * fabs(s->N[i]) - dp_right_hand_force_tol(&fr);
            if (fr.fric[i] && (!stuck || on_cone) && fabs(s->N[i]) <= dp_right_hand_force_tol(&fr))
                nonzero = 0;
            n1empty &= !on_cone;
        }
    }
    const char *none = "not evaluated: no acceleration solves the initial problem";
    if (res.n < 1) {
        snprintf(add(rep, "(1.2) at the initial state", 0)->detail, DP_WP_TEXT, "%s", none);
        snprintf(add(rep, "(2.3) at the initial state (Theorem 3.1)", 0)->detail, DP_WP_TEXT, "%s", none);
        snprintf(add(rep, "|N_s| != 0 for the coordinates not strictly stuck (Theorem 3.1, the set A)", 0)->detail,
                 DP_WP_TEXT, "%s", none);
    } else {
        snprintf(add(rep, "(1.2) at the initial state", c12)->detail, DP_WP_TEXT, "margin %s", num(k.c12).s);
        snprintf(add(rep, "(2.3) at the initial state (Theorem 3.1)", c23)->detail, DP_WP_TEXT,
                 "margin %s (min over s, v of a_ss/k* - |a_ss dF_s/dq''_v|)", num(k.c23).s);
        snprintf(add(rep, "|N_s| != 0 for the coordinates not strictly stuck (Theorem 3.1, the set A)",
                     nonzero)->detail, DP_WP_TEXT, "N = [%s, %s]", num(res.sol[0].N[0]).s, num(res.sol[0].N[1]).s);
    }
    snprintf(add(rep, "no resting coordinate on its friction cone, N1 empty (Theorem 5.1)", n1empty)->detail,
             DP_WP_TEXT, "%s", res.n < 1 ? none : n1empty ? "every resting coordinate strictly inside or sliding"
                                                           : "a resting coordinate holds exactly f|N|");
    if (m->kind == DP_RIGHT_HAND_PISTON_HINGE && res.n >= 1) {
        snprintf(add(rep, "(6.2) at the initial state", k.c62 > 0)->detail, DP_WP_TEXT, "margin %s", num(k.c62).s);
        snprintf(add(rep, "(6.3)", k.c63 > 0)->detail, DP_WP_TEXT, "margin %s", num(k.c63).s);
        snprintf(add(rep, "(6.4) at the initial state", k.c64 > 0)->detail, DP_WP_TEXT, "margin %s", num(k.c64).s);
    }
    int uni = uniform(m, rep);
    int exist = unique && c23 && nonzero;
    rep->existence.guaranteed = exist || (uni && nonzero);
    rep->existence.theorem = uni && nonzero ? "Matrosov-Finogenko Theorems 4.1, 4.2"
                             : exist ? "Matrosov-Finogenko Theorem 3.1" : NULL;
    snprintf(rep->existence.reason, DP_WP_TEXT, "%s", rep->existence.guaranteed
             ? (uni ? "(2.3) holds everywhere: a right-hand solution from every state of A, extendable until it "
                      "leaves A" : "(2.3) holds at the initial state: a local right-hand solution")
             : !unique ? "the initial acceleration problem has no unique solution (Painleve's paradox)"
                       : "(2.3) or |N_s| != 0 fails at the initial state");
    rep->uniqueness.guaranteed = rep->existence.guaranteed && c23 && n1empty;
    rep->uniqueness.theorem = rep->uniqueness.guaranteed ? "Matrosov-Finogenko Theorem 5.1" : NULL;
    snprintf(rep->uniqueness.reason, DP_WP_TEXT, "%s", rep->uniqueness.guaranteed
             ? "right uniqueness of the R-right-hand solution at the initial state"
             : "Theorem 5.1 needs (2.3) and N1 empty at the initial state");
}
