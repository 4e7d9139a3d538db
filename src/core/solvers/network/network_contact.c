/* src/core/solvers/network/network_contact.c - unilateral contacts on a network (docs/systems.md §4, Cibulka 2014, §2.3): an element's
 * elongation u kept at least its distance d.
 *
 * A rigid contact is one more element of the step's convex problem, armed for a step where it closes: the
 * cone  z >= v_c  (force in (-inf, 0] at z = v_c, 0 above), with v_c = -e u'- (Newton's law on the step's end
 * velocity, Moreau-Jean: Siconos' NewtonImpactNSL). So a block that hits a stop while it sticks or slips on
 * a belt is one exact step problem, and the contact sticks to rounding (no creep) as friction does.
 *
 * With events located (network_events.c) an impact is found inside its step as a root of the gap, and at
 * that instant the velocity jumps by the impact problem  min 1/2 |v+ - v-|_M^2  over  b_c^T v+ >= -e b_c^T v-
 * for the touching contacts (the same exact solver with W = M: only contacts carry an impulse; forces of
 * bounded laws carry none in no time). A contact that rests (closed at zero relative velocity) stays armed at
 * v_c = 0 until the step's solution lets it go.
 *
 * Accumulating impacts (a ball coming to rest, Zeno): a contact's impacts k and k+1 a time tau apart predict
 * e tau / (1 - e) before the accumulation point (exact for a constant force). Once that falls below 10^-9 of
 * a step the infinitely many impacts left take less time than location resolves, and the impact is made
 * plastic: the mass rests on the stop from there, after finitely many located impacts.
 *
 * A compliant contact is a spring graph, force -k max(d - u, 0) (the Yosida approximation of the rigid one):
 * one more element with that graph, or a force in the regularized scheme (network_regularized.c).
 *
 * A rope (Babováková 2012, Fig. 1: force k u while slack, any extra tension at u = L) is, with events located,
 * a linear spring k in W (theta-weighted like any linear spring) plus the rigid constraint u <= L with
 * restitution 0: the contact between its ends swapped at distance -L, whose gap is L - u. So its going taut
 * is located as a root of that gap and is a plastic impact (the rope stops lengthening, its impulse written as
 * the element's impact event), it rests taut armed at zero rate until its multiplier would change sign (then
 * it goes slack), and a taut rope is a touching contact of the impact problem: it passes on its share of
 * another contact's impulse. Its tension k u - lambda is the element's Fs; it has no Fn. Without located
 * events it stays its graph, stepped by backward Euler (network_stepping.c).
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/band.h"
#include "solvers/network/network_run.h"

/* Located impacts in one step after which the rest of the step is plain Moreau-Jean: a guard for chatter
 * the accumulation rule does not see (a rattle between two stops, e = 1 against a contact that keeps
 * closing), so that one step stays a bounded amount of work; Moreau-Jean keeps the restitution (the
 * accumulating ball of e = 0.9 makes about 200 located impacts in its last step). */
#define IMPACTS_PER_STEP 1000

int network_run_contacts_chattering(const struct dp_network_run *nr)
{
    return nr->impacts_step >= IMPACTS_PER_STEP;
}

/* The rigid cone (vertex (0, 0), a vertical ray down, a horizontal ray right) and a compliant contact's
 * graph in u (vertex (d, 0), slope k to the left, 0 to the right). */
static int cone_graph(dp_graph *g)
{
    const double y = 0, f = 0, left[2] = { 0, 1 }, right[2] = { 1, 0 };
    return dp_graph_init(g, 1, &y, &f, left, right);
}

static int compliance_graph(dp_graph *g, const dp_contact *c)
{
    const double left[2] = { 1, c->compliance }, right[2] = { 1, 0 };
    return dp_graph_init(g, 1, &c->distance, &(double){ 0 }, left, right);
}

/* A contact's place in the order of shadows(): rigid ones by their ends, then by falling distance (then
 * index); compliant ones last. A rope's constraint is a rigid contact of its swapped ends: two ropes between
 * the same ends, the shorter binds. */
typedef struct contact_key {
    int rigid;
    long a, b;
    double d;
    size_t c;
} contact_key;

static int by_ends(const void *pa, const void *pb)
{
    const contact_key *x = pa, *y = pb;
    if (x->rigid != y->rigid)
        return y->rigid - x->rigid;
    if (x->a != y->a)
        return x->a < y->a ? -1 : 1;
    if (x->b != y->b)
        return x->b < y->b ? -1 : 1;
    if (x->d != y->d)
        return x->d > y->d ? -1 : 1;
    return x->c < y->c ? -1 : x->c > y->c;
}

/* Rigid contacts between the same ends in the same order keep u >= d for each d: only the largest distance
 * can bind, the others close only where it holds already (then at the same velocity). Armed together they
 * would be parallel cones, a cycle of fixed elements the step cannot contract, and a step with no solution
 * where their vertices differ. So the ones behind it (ct_shadow) are never armed: they carry no force. */
static int shadows(struct dp_network_run *nr)
{
    contact_key *key = malloc(nr->nc * sizeof *key);
    if (key == NULL)
        return DP_ENOMEM;
    for (size_t c = 0; c < nr->nc; c++) {
        const network_bound *b = &nr->ct[c];
        key[c] = (contact_key){ b->law.compliance == 0, b->a, b->b, b->law.distance, c };
    }
    qsort(key, nr->nc, sizeof *key, by_ends);
    for (size_t k = 1; k < nr->nc; k++)
        nr->ct_shadow[key[k].c] = key[k].rigid && key[k - 1].rigid && key[k].a == key[k - 1].a &&
                                  key[k].b == key[k - 1].b;
    free(key);
    return DP_OK;
}

size_t network_run_spring_stops(const struct dp_network_run *nr, const dp_element *e)
{
    double lo, hi;
    if (!nr->ropes_bound || !e->has_spring)
        return 0;
    if (e->spring.law == DP_SPRING_ROPE)
        return 1;
    if (!dp_spring_bounded_graph(&e->spring, &lo, &hi))
        return 0;
    return (size_t)isfinite(lo) + (size_t)isfinite(hi);
}

int network_run_spring_split(const struct dp_network_run *nr, const dp_element *e)
{
    double lo, hi;
    return nr->ropes_bound && e->has_spring &&
           (e->spring.law == DP_SPRING_ROPE || dp_spring_bounded_graph(&e->spring, &lo, &hi));
}

/* Element i's constraints: its contact, then a bound rope's u <= L (its ends swapped, distance -L, plastic),
 * or a bounded graph's u <= hi (likewise) and u >= lo (its own ends, distance lo, plastic). */
static size_t element_bounds(const struct dp_network_run *nr, size_t i, network_bound *out)
{
    const dp_element *e = &nr->net->el[i];
    size_t m = 0;
    double lo = -INFINITY, hi = INFINITY;
    if (e->has_contact)
        out[m++] = (network_bound){ .a = e->a, .b = e->b, .law = e->contact };
    if (!network_run_spring_split(nr, e))
        return m;
    if (e->spring.law == DP_SPRING_ROPE)
        hi = e->spring.length;
    else
        dp_spring_bounded_graph(&e->spring, &lo, &hi);
    if (isfinite(hi))
        out[m++] = (network_bound){ .a = e->b, .b = e->a, .law = { .distance = -hi }, .rope = 1, .swapped = 1 };
    if (isfinite(lo))
        out[m++] = (network_bound){ .a = e->a, .b = e->b, .law = { .distance = lo }, .rope = 1 };
    return m;
}

int network_run_contacts_setup(struct dp_network_run *nr)
{
    const dp_network *net = nr->net;
    size_t m = 0, ropes = 0;
    network_bound two[3];
    for (size_t i = 0; i < nr->nel; i++) {
        m += element_bounds(nr, i, two);
        ropes += network_run_spring_stops(nr, &net->el[i]);
    }
    nr->nact_el = nr->nact;
    if (m == 0)
        return DP_OK;
    nr->nc = m, nr->nrope = ropes;
    nr->ct = calloc(m, sizeof *nr->ct);
    nr->ct_el = calloc(m, sizeof *nr->ct_el);
    nr->ct_soft = calloc(m, sizeof *nr->ct_soft);
    nr->ct_on = calloc(m, 1);
    nr->ct_last = calloc(m, sizeof *nr->ct_last);
    nr->ct_before = calloc(m, sizeof *nr->ct_before);
    nr->ct_kicked = calloc(m, 1);
    nr->ct_shadow = calloc(m, 1);
    nr->ct_pre = calloc(m, sizeof *nr->ct_pre);
    nr->ct_touch = calloc(m, 1);
    /* the contacts' forces, a row's Fn columns: none for ropes alone (their tension is Fs) */
    nr->Fn = m > ropes ? calloc(nr->nel, sizeof *nr->Fn) : NULL;
    nr->imp = calloc(m, sizeof *nr->imp);
    nr->iforce = calloc(m, sizeof *nr->iforce);
    nr->iv = calloc(2 * nr->n, sizeof *nr->iv);
    if (!nr->ct_before || !nr->ct_kicked || !nr->ct_shadow)
        return DP_ENOMEM;
    if (!nr->ct || !nr->ct_el || !nr->ct_soft || !nr->ct_on || !nr->ct_last || !nr->ct_pre || !nr->ct_touch ||
        (m > ropes && !nr->Fn) || !nr->imp ||
        !nr->iforce || !nr->iv || cone_graph(&nr->cone) != DP_OK)
        return DP_ENOMEM;
    size_t c = 0;
    for (size_t i = 0; i < nr->nel; i++) {
        size_t k = element_bounds(nr, i, two);
        for (size_t j = 0; j < k; j++, c++) {
            nr->ct[c] = two[j];
            const network_bound *b = &nr->ct[c];
            nr->ct_el[c] = i, nr->ct_last[c] = nr->ct_before[c] = -INFINITY;
            dp_network_step_element *a = &nr->act[nr->nact];
            *a = (dp_network_step_element){ .a = b->a, .b = b->b };
            if (b->law.compliance > 0) {
                if (compliance_graph(&nr->ct_soft[c], &b->law) != DP_OK)
                    return DP_ENOMEM;
                a->S = &nr->ct_soft[c];
            }
            nr->imp[c] = (dp_network_step_element){ .a = b->a, .b = b->b };
            nr->act_el[nr->nact++] = i;
        }
    }
    if (shadows(nr) != DP_OK)
        return DP_ENOMEM;
    nr->iws = dp_network_step_alloc(nr->n, nr->p, m, nr->imp);
    if (nr->iws == NULL)
        return DP_ENOMEM;
    memcpy(dp_network_step_W(nr->iws), nr->M, nr->n * (nr->p + 1) * sizeof(double));
    dp_network_step_W_changed(nr->iws);
    return DP_OK;
}

void network_run_contacts_free(struct dp_network_run *nr)
{
    for (size_t c = 0; nr->ct_soft && c < nr->nc; c++)
        dp_graph_clear(&nr->ct_soft[c]);
    dp_graph_clear(&nr->cone);
    dp_network_step_free(nr->iws);
    void *p[] = { nr->ct, nr->ct_before, nr->ct_kicked, nr->ct_shadow, nr->ct_el, nr->ct_soft, nr->ct_on, nr->ct_last, nr->ct_pre, nr->ct_touch, nr->Fn, nr->imp, nr->iforce, nr->iv };
    for (size_t i = 0; i < sizeof p / sizeof *p; i++)
        free(p[i]);
}

double network_run_compliant_force(const dp_contact *c, double u)
{
    return -c->compliance * fmax(c->distance - u, 0);
}

static int rigid(const struct dp_network_run *nr, size_t c)
{
    return nr->ct[c].law.compliance == 0;
}

/* Contact c's rate: the relative velocity of its ends in its own order (a rope's: -u'). */
static double rate(const struct dp_network_run *nr, size_t c, const double *v)
{
    return network_run_rel(nr->ct[c].a, nr->ct[c].b, v);
}

/* A bound rope's spring part k u (0, not the -0 of 0 times a negative elongation, as network_stepping.c); a
 * split graph's, its sloped part at u and the jumps below u. */
static double spring_force(const struct dp_network_run *nr, size_t i)
{
    const dp_element *e = &nr->net->el[i];
    double u = network_run_rel(e->a, e->b, nr->x), lo, hi;
    if (nr->stop_S && nr->stop_S[i].n) {
        dp_graph_force(&nr->stop_S[i], u, &lo, &hi);
        for (size_t k = 0; nr->jump && k < nr->nact_el; k++)
            if (nr->jump[k] && nr->act_el[k] == i && u > nr->act[k].S->y[0])
                lo += nr->act[k].S->f[1];
        return lo;
    }
    return nr->k[i] != 0 ? nr->k[i] * u : 0;
}

/* Contact c's impact event, in its element's terms: a rope's rates are the element's u' (its own are -u'),
 * its impulse (>= 0) the tension's, pulling the ends together. */
static void bound_event(dp_run *r, double t, size_t c, double before, double after, double impulse)
{
    struct dp_network_run *nr = r->state;
    if (nr->ct[c].swapped)
        before = 0.0 - before, after = 0.0 - after;   /* 0 - x: never a -0 */
    network_run_impact_event(r, t, nr->ct_el[c], before, after, impulse);
}

/* Contact c's gap u - d, its rate, and how close to zero a gap counts as touching: the rounding of the
 * positions and a billionth of what the gap moves in a step. */
static double gap(const struct dp_network_run *nr, size_t c, const double *x)
{
    return network_run_bound_gap(&nr->ct[c], x);
}

static double touch_tol(const struct dp_network_run *nr, size_t c, double h)
{
    return network_run_touch_tol(&nr->ct[c], nr->x, nr->v, h);
}

/* Arms contact c for the coming step with the cone at v_c, or disarms it (a zero law). */
static int arm(struct dp_network_run *nr, size_t c, int on, double vc)
{
    on = on && !nr->ct_shadow[c];
    dp_network_step_element *a = &nr->act[nr->nact_el + c];
    int changed = (a->A != NULL) != on;
    a->A = on ? &nr->cone : NULL;
    a->vb = on ? vc : 0;
    nr->ct_on[c] = (unsigned char)on;
    return changed;
}

/* Moreau-Jean's rule (Siconos' MoreauJeanOSI index set): armed for the step from t where the gap predicted
 * half a step on, g + h/2 g', has closed; the cone at -e g'. */
void network_run_contacts_arm_mj(struct dp_network_run *nr, double h)
{
    int changed = 0;
    for (size_t c = 0; c < nr->nc; c++) {
        if (!rigid(nr, c))
            continue;
        double g = gap(nr, c, nr->x), gd = rate(nr, c, nr->v);
        if (fabs(gd) < DBL_MIN)
            gd = 0;   /* a resting contact's rate decays by e per step into subnormals: 0, not a slow tail */
        int was = nr->ct_on[c];
        changed |= arm(nr, c, g + 0.5 * h * gd <= 0, -nr->ct[c].law.restitution * gd);
        nr->ct_pre[c] = was ? 0 : gd;      /* an impact closes a contact; a closed one rests */
    }
    if (changed)
        dp_network_step_W_changed(nr->ws);
}

/* After a Moreau-Jean step from t of length h: an impact event at its end for each contact the step closed
 * (armed now, not in the step before) while approaching, that took an impulse. */
void network_run_contacts_mj_events(dp_run *r, double t, double h)
{
    struct dp_network_run *nr = r->state;
    for (size_t c = 0; c < nr->nc; c++) {
        size_t k = nr->nact_el + c;
        if (!(nr->ct_on[c] && nr->ct_pre[c] < 0 && nr->force[k].lambda < 0))
            continue;
        bound_event(r, t + h, c, nr->ct_pre[c], nr->force[k].z, -h * nr->force[k].lambda);
        /* an impact inside the step, not located: its own history starts again, and it may have turned
         * every other contact round (steady_chatter must not take that for the forces' doing) */
        nr->ct_last[c] = nr->ct_before[c] = -INFINITY;
        for (size_t o = 0; o < nr->nc; o++)
            nr->ct_kicked[o] |= o != c;
    }
}

/* Steady chatter: contact c impacts again less than a step h after its last impact, its rate turned round
 * by the forces alone (no other contact's impulse changed it since: not a rattle between two stops), and
 * not sooner than the last interval (a bounce that does not shrink: no accumulation for the rule above to
 * end). Such a bounce lasts less than a step, so its speed is below what the forces change in one step: at
 * the step's resolution the contact is closed (Moreau's sweeping process), and its impact is made plastic.
 * Without this an e = 1 contact in a stack pressed by gravity rebounds every 0.8 ms for ever, each rebound
 * an impact event of every contact of the stack (thousands of events a second, none of them resolved by the
 * rows). */
static int steady_chatter(const struct dp_network_run *nr, size_t c, double t, double h)
{
    double tau = t - nr->ct_last[c], before = nr->ct_last[c] - nr->ct_before[c];
    return tau < h && !nr->ct_kicked[c] && tau >= (1 - 1e-6) * before;
}

/* The velocity jump at time t for the touching contacts (located events), plastic where the impacts have
 * accumulated or chatter steadily. Emits the events; returns 1 when some contact was approaching (v changed), 0 if none, or
 * -status. The impact problem's elements have no spring graph, so the elongations it is given are unused. */
static int impact(dp_run *r, double t, const unsigned char *touch)
{
    struct dp_network_run *nr = r->state;
    size_t n = nr->n;
    int any = 0;
    for (size_t c = 0; c < nr->nc; c++) {
        double gd = rate(nr, c, nr->v), en = nr->ct[c].law.restitution;
        /* approaching faster than rounding: a touching contact whose rate is within what the touching test
         * leaves to rounding (contacts_instant arms it at rest) takes no impact of its own */
        int approaching = touch[c] && gd < -touch_tol(nr, c, r->h) / r->h;
        if (approaching && en > 0 && en * (t - nr->ct_last[c]) / (1 - en) <= 1e-9 * r->h)
            en = 0;                                   /* accumulated (Zeno): the rest of it is plastic */
        if (approaching && en > 0 && steady_chatter(nr, c, t, r->h))
            en = 0;
        nr->imp[c].A = touch[c] ? &nr->cone : NULL;
        nr->imp[c].vb = approaching ? -en * gd : 0;
        any |= approaching;
    }
    if (!any)
        return 0;
    double *rhs = nr->iv, *vplus = nr->iv + n;
    dp_band_symv(nr->M, n, nr->p, nr->v, rhs);
    dp_network_step_W_changed(nr->iws);
    int s = dp_network_step_solve(nr->iws, 1, rhs, nr->u, nr->v, vplus, nr->iforce, &r->sum.iterations);
    if (s != DP_OK)
        return -s;
    /* every touching contact that took an impulse (to rounding of the largest): the approaching ones and
     * those that passed it on (Newton's cradle), so the events balance the momentum */
    double most = 0;
    for (size_t c = 0; c < nr->nc; c++)
        most = touch[c] ? fmax(most, -nr->iforce[c].lambda) : most;
    for (size_t c = 0; c < nr->nc; c++) {
        double before = rate(nr, c, nr->v), impulse = -nr->iforce[c].lambda;
        if (!touch[c] || !(impulse > 1e-12 * most)) {
            double after = rate(nr, c, vplus);
            if (fabs(after - before) > 1e-6 * (fabs(before) + fabs(after)))
                nr->ct_kicked[c] = 1;     /* its rate changed by the others' impulses */
            continue;
        }
        nr->impacts_step++;
        nr->ct_before[c] = nr->ct_last[c];
        nr->ct_last[c] = t;
        nr->ct_kicked[c] = 0;
        bound_event(r, t, c, before, nr->iforce[c].z, impulse);
    }
    memcpy(nr->v, vplus, n * sizeof *nr->v);
    return 1;
}

/* At a sub-step's start t (events located; h the run's step): the impacts of the touching contacts (a gap
 * within rounding), then which contacts are armed for the sub-step: the touching ones that do not separate
 * (they rest, or a plastic impact just closed them). Returns 1 when velocities jumped (the caller renews
 * the assignment), 0, or -status. */
int network_run_contacts_instant(dp_run *r, double t, double h)
{
    struct dp_network_run *nr = r->state;
    if (nr->nc == 0)
        return 0;
    unsigned char *touch = nr->ct_touch;
    for (size_t c = 0; c < nr->nc; c++)
        touch[c] = rigid(nr, c) && !nr->ct_shadow[c] && gap(nr, c, nr->x) <= touch_tol(nr, c, h);
    int jumped = impact(r, t, touch);
    if (jumped < 0)
        return jumped;
    int changed = 0;
    for (size_t c = 0; c < nr->nc; c++) {
        double gd = rate(nr, c, nr->v);
        changed |= arm(nr, c, touch[c] && gd <= touch_tol(nr, c, h) / h, 0);
        nr->ct_pre[c] = 0;    /* armed at rest, or open: closing it later in a step is its impact */
    }
    if (changed)
        dp_network_step_W_changed(nr->ws);
    return jumped;
}

/* The held step's margins for the contacts that are not armed: the gap at its end (x + s ((1-theta) v +
 * theta v1)), measured from the start's gap where that is already (to rounding) below zero. */
void network_run_contacts_margins(struct dp_network_run *nr, double s)
{
    for (size_t c = 0; c < nr->nc; c++) {
        size_t k = nr->nact_el + c;
        if (!rigid(nr, c) || nr->ct_on[c])
            continue;
        if (nr->ct_shadow[c]) {
            nr->margin[k] = INFINITY;    /* behind another: it never closes first */
            continue;
        }
        double g0 = nr->u[k] - nr->ct[c].law.distance;
        double mean = (1 - nr->theta) * rate(nr, c, nr->v) + nr->theta * rate(nr, c, nr->v1);
        nr->margin[k] = g0 + s * mean - fmin(g0, 0);
    }
}

/* Whether a step of length h just solved (v1) carries a contact that is not armed through its stop. */
int network_run_contacts_penetrate(struct dp_network_run *nr, double h)
{
    if (nr->nc == 0)
        return 0;
    network_run_contacts_margins(nr, h);
    for (size_t c = 0; c < nr->nc; c++)
        if (rigid(nr, c) && !nr->ct_on[c] && nr->margin[nr->nact_el + c] < 0)
            return 1;
    return 0;
}

/* Arms, Moreau-Jean's way (the cone at -e g'), every contact that is not armed and that the step of length h
 * just solved (v1) carries through its stop: where location cannot split the step (a gap closing within a
 * billionth of it, or a step with too many changes) the impact is taken inside the step. Returns how many. */
size_t network_run_contacts_arm_closing(struct dp_network_run *nr, double h)
{
    if (!network_run_contacts_penetrate(nr, h))
        return 0;
    size_t m = 0;
    for (size_t c = 0; c < nr->nc; c++) {
        if (nr->ct_on[c] || !rigid(nr, c) || nr->ct_shadow[c] || !(nr->margin[nr->nact_el + c] < 0))
            continue;
        double gd = rate(nr, c, nr->v);
        arm(nr, c, 1, -nr->ct[c].law.restitution * fmin(gd, 0));
        nr->ct_pre[c] = gd;
        m++;
    }
    dp_network_step_W_changed(nr->ws);
    return m;
}

/* After the run's initial probe (a step of a billionth of dt from the initial state, which says what holds
 * at t = 0): a contact that approaches at t = 0 takes an impact there, so its force before it is 0, not the
 * probe's impulse over its billionth of a step (a rope's tension is then its spring's alone); and no contact
 * counts as armed before the first step, whose closing of it is then an impact (Moreau-Jean's events). */
void network_run_contacts_after_probe(struct dp_network_run *nr)
{
    for (size_t c = 0; c < nr->nc; c++) {
        size_t i = nr->ct_el[c];
        if (rigid(nr, c) && rate(nr, c, nr->v) < 0 && nr->ct[c].rope)
            nr->Fs[i] = spring_force(nr, i);
        else if (rigid(nr, c) && rate(nr, c, nr->v) < 0)
            nr->Fn[i] = 0;
        nr->ct_on[c] = 0;
    }
}

/* Each contact's force at the current state into Fn (per element): a rigid one's from the last solution
 * (in a Moreau-Jean step with an impact, the impulse over the step), a compliant one's from its gap. A rope's
 * constraint adds its multiplier to the element's Fs (k u, network_stepping.c): the tension k u - lambda. */
void network_run_contacts_forces(struct dp_network_run *nr, int stepped)
{
    for (size_t c = 0; c < nr->nc; c++) {
        size_t i = nr->ct_el[c], k = nr->nact_el + c;
        const dp_contact *ct = &nr->ct[c].law;
        if (nr->ct[c].rope) {    /* a bounded graph's second stop adds to its first */
            double lam = stepped && nr->ct_on[c] ? nr->force[k].lambda : 0;
            double fs = nr->Fs[i];   /* the spring's part (and the other stop's), element_forces */
            nr->Fs[i] = nr->ct[c].swapped ? fs - lam : fs + lam;
            continue;
        }
        if (ct->compliance > 0)
            nr->Fn[i] = network_run_compliant_force(ct, rate(nr, c, nr->x));
        else
            nr->Fn[i] = stepped && nr->ct_on[c] ? nr->force[k].lambda : 0;
    }
}
