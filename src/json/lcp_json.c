/* src/json/lcp_json.c - POST /v1/lcp and `dashpot lcp`: one LCP w = Mz + q, 0 <= z ⊥ w >= 0 read from JSON
 * (with the body reader and the walker of every route, body.h and walk.h), solved by Lemke's method, every
 * solution of a small one enumerated, and what Cibulka 2016's theory says (Lemma 2.5, Theorem 2.3:
 * µ = λ_min((M + Mᵀ)/2) > 0 gives one solution, Lipschitz in q with constant 1/µ; a P-matrix gives one
 * solution for every q). Why enumerate: for a general M Lemke finds one solution or none, and the user asked
 * about the problem, not about the algorithm (Example 2.4 with a < 0 has two).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "dashpot/json.h"
#include "dashpot/lcp.h"
#include "dashpot/lcp_json.h"
#include "dashpot/lcs.h"
#include "walk.h"

/* M: a square array of m rows of m finite numbers, 1 <= m <= DP_LCP_MAX. NULL on error. */
static gsl_matrix *read_matrix(ctx *c, const cJSON *a, const at *pm)
{
    size_t m = cJSON_IsArray(a) ? (size_t)cJSON_GetArraySize(a) : 0;
    if (m == 0 || m > DP_LCP_MAX) {
        jw_fail(c, pm, "must be a square matrix: an array of 1 to %d rows, got %s", DP_LCP_MAX,
                cJSON_IsArray(a) ? (m ? "more rows" : "no rows") : jb_type_name(a));
        return NULL;
    }
    gsl_matrix *M = gsl_matrix_alloc(m, m);
    if (M == NULL) {
        c->nomem = 1;
        return NULL;
    }
    size_t i = 0, before = c->nerr;
    for (const cJSON *r = a->child; r; r = r->next, i++) {
        const at pr = { pm, NULL, i };
        if (!cJSON_IsArray(r) || (size_t)cJSON_GetArraySize(r) != m) {
            jw_fail(c, &pr, "must be a row of %zu numbers (M is square: %zu rows)", m, m);
            continue;
        }
        size_t j = 0;
        for (const cJSON *x = r->child; x; x = x->next, j++) {
            const at px = { &pr, NULL, j };
            jw_check_num(c, x, &px, &ANY, 0, M->data + i * m + j);
        }
    }
    if (c->nerr > before) {
        gsl_matrix_free(M);
        return NULL;
    }
    return M;
}

/* q: m finite numbers. NULL on error. */
static gsl_vector *read_vector(ctx *c, const cJSON *a, const at *pq, size_t m)
{
    if (!cJSON_IsArray(a) || (size_t)cJSON_GetArraySize(a) != m) {
        jw_fail(c, pq, "must be an array of %zu numbers (one per row of M), got %s", m,
                cJSON_IsArray(a) ? "another length" : jb_type_name(a));
        return NULL;
    }
    gsl_vector *q = gsl_vector_alloc(m);
    if (q == NULL) {
        c->nomem = 1;
        return NULL;
    }
    size_t i = 0, before = c->nerr;
    for (const cJSON *x = a->child; x; x = x->next, i++) {
        const at px = { pq, NULL, i };
        jw_check_num(c, x, &px, &ANY, 0, q->data + i);
    }
    if (c->nerr > before) {
        gsl_vector_free(q);
        return NULL;
    }
    return q;
}

/* {"M": [[...]], "q": [...]}, read and walked as every route's body (body.h, walk.h). */
static int read_request(const char *body, size_t len, gsl_matrix **M, gsl_vector **q, dp_errors *e)
{
    static const char *const keys[] = { "M", "q", NULL };
    ctx c = { e, 0, 0, 0 };
    int read;
    cJSON *doc = jw_read(&c, body, len, &read);
    if (doc == NULL)
        return read;
    jw_check_keys(&c, doc, NULL, keys, NULL, NULL);
    at pm, pq;
    const cJSON *a = jw_member(&c, doc, NULL, "M", "a square matrix: an array of rows of numbers", &pm);
    *M = a ? read_matrix(&c, a, &pm) : NULL;
    const cJSON *b = jw_member(&c, doc, NULL, "q", "an array of numbers, one per row of M", &pq);
    if (*M && b)
        *q = read_vector(&c, b, &pq, (*M)->size1);
    cJSON_Delete(doc);
    if (c.nomem)
        return DP_ENOMEM;
    return c.nerr > 0 ? DP_EINVAL : DP_OK;
}

/* ---- writing ---------------------------------------------------------------------------------------- */

static int put(dp_buf *b, const char *s)
{
    return dp_buf_append(b, s, strlen(s));
}

static int put_num(dp_buf *b, double x)
{
    char t[40];
    if (!isfinite(x))
        return put(b, "null");
    return dp_buf_append(b, t, dp_format_double(t, x));
}

static int put_vec(dp_buf *b, const double *x, size_t m)
{
    int s = put(b, "[");
    for (size_t i = 0; i < m && s == DP_OK; i++)
        s = (i ? put(b, ",") : DP_OK) || put_num(b, x[i] == 0 ? 0.0 : x[i]);
    return s ? s : put(b, "]");
}

/* {"z":[...],"w":[...]}: a listed solution, settled and checked by the enumeration. */
static int put_pair(dp_buf *b, const dp_lcp_solutions *sol, size_t k)
{
    size_t m = sol->m;
    return put(b, "{\"z\":") || put_vec(b, sol->z + k * m, m) || put(b, ",\"w\":") ||
           put_vec(b, sol->w + k * m, m) || put(b, "}");
}

static int put_theory(dp_buf *b, const dp_lcp_theory *t, size_t m)
{
    int s = put(b, ",\"theory\":{\"p_matrix\":");
    s = s || put(b, t->p_matrix == 1 ? "true" : t->p_matrix == 0 ? "false" : "null");
    if (t->p_matrix == 0) {
        s = s || put(b, ",\"minor_witness\":{\"rows\":[");
        int first = 1;
        for (size_t i = 0; i < m && !s; i++)
            if (t->minor_set & (1u << i)) {
                char k[24];
                snprintf(k, sizeof k, "%s%zu", first ? "" : ",", i);
                s = put(b, k);
                first = 0;
            }
        s = s || put(b, "],\"minor\":") || put_num(b, t->minor) || put(b, "}");
    }
    s = s || put(b, ",\"mu\":") || put_num(b, t->mu);
    s = s || put(b, ",\"positive_definite_symmetric_part\":") || put(b, t->pd_symmetric ? "true" : "false");
    s = s || put(b, ",\"positive_semidefinite\":") || put(b, t->psd ? "true" : "false");
    s = s || put(b, ",\"lipschitz\":") || put_num(b, t->lipschitz);
    return s || put(b, "}");
}

/* Lemke's run as the answer reports it: its outcome, or that it took its pivot limit (the enumeration then
 * answers). */
typedef struct lemke_run {
    dp_lcp_result r;
    int limit;           /* it took dp_lcp_pivot_limit(m) pivots */
} lemke_run;

static const char *outcome_name(const lemke_run *l)
{
    if (l->limit)
        return "pivot-limit";
    return l->r.outcome == DP_LCP_SOLVED ? "solved" : l->r.outcome == DP_LCP_RAY ? "ray" : "inaccurate";
}

static const char *lemke_words(const lemke_run *l)
{
    if (l->limit)
        return "took its pivot limit";
    return l->r.outcome == DP_LCP_SOLVED ? "found a solution" : l->r.outcome == DP_LCP_RAY
           ? "ended on a ray (no solution found)" : "ended on a basis whose answer fails its check (rounding)";
}

/* One sentence: how many solutions, and whether the theory had promised it; never more or fewer than the
 * answer lists. */
static void verdict(char *v, size_t cap, const dp_lcp_theory *t, const dp_lcp_solutions *s, int enumerated,
                    const lemke_run *l)
{
    const char *why = t->pd_symmetric ? "positive definite symmetric part (Cibulka 2014, Lemma 2.5, Theorem 2.3)"
                      : t->p_matrix == 1 ? "M is a P-matrix" : NULL;
    int solved = !l->limit && l->r.outcome == DP_LCP_SOLVED;
    if (!enumerated && why)
        snprintf(v, cap, "exactly one solution: %s%s%s", why, solved ? "" : "; Lemke ", solved ? "" : lemke_words(l));
    else if (!enumerated)
        snprintf(v, cap, "uniqueness not guaranteed (M not known to be a P-matrix); Lemke %s", lemke_words(l));
    else if (why && s->n == 1)
        snprintf(v, cap, "exactly one solution: %s", why);
    else if (why)
        snprintf(v, cap, "%zu solutions found at regular bases although %s promises exactly one: M is too "
                 "ill-conditioned for the rounding of this answer", s->n, why);
    else if (s->n == 0 && solved)
        snprintf(v, cap, "Lemke's solution lies at a basis singular to rounding, which the enumeration does not "
                 "search; none at a regular basis");
    else if (s->n == 0 && !l->limit && l->r.outcome == DP_LCP_RAY && t->psd)
        snprintf(v, cap, "no solution: Lemke's ray proves it for a positive semidefinite M");
    else if (s->n == 0)
        snprintf(v, cap, "no solution%s", s->singular ? " at a regular complementary basis (singular ones not searched)" : "");
    else
        snprintf(v, cap, "%zu solution%s%s; uniqueness not guaranteed (M is not a P-matrix)", s->n,
                 s->n == 1 ? "" : "s", s->singular ? " at regular bases, a continuum may pass through singular ones" : "");
}

static int answer(dp_buf *b, const gsl_vector *z, const gsl_vector *w, const lemke_run *l,
                  const dp_lcp_solutions *sol, int enumerated, const dp_lcp_theory *t)
{
    size_t m = z->size;
    char head[112], v[400];
    int solved = !l->limit && l->r.outcome == DP_LCP_SOLVED;
    snprintf(head, sizeof head, "{\"m\":%zu,\"lemke\":{\"outcome\":\"%s\",\"z\":", m, outcome_name(l));
    int s = put(b, head);
    if (solved)
        s = s || put_vec(b, z->data, m) || put(b, ",\"w\":") || put_vec(b, w->data, m);
    else
        s = s || put(b, "null,\"w\":null");
    snprintf(head, sizeof head, ",\"pivots\":%zu,\"residual\":", l->r.pivots);
    int has_residual = solved || (!l->limit && l->r.outcome == DP_LCP_INACCURATE);
    s = s || put(b, head) || put_num(b, has_residual ? l->r.residual : NAN) || put(b, "}");
    s = s || put(b, ",\"solutions\":");
    if (!enumerated)
        s = s || put(b, "null,\"count\":null,\"singular_bases\":null");
    else {
        s = s || put(b, "[");
        for (size_t k = 0; k < sol->n && !s; k++)
            s = (k ? put(b, ",") : DP_OK) || put_pair(b, sol, k);
        snprintf(head, sizeof head, "],\"count\":%zu,\"singular_bases\":%zu", sol->n, sol->singular);
        s = s || put(b, head);
    }
    s = s || put_theory(b, t, m);
    verdict(v, sizeof v, t, sol, enumerated, l);
    s = s || put(b, ",\"verdict\":") || dp_json_quote(b, v);
    return s ? DP_ENOMEM : put(b, "}\n");
}

/* A failure of the solvers as a located error: which member made it, and which limit. */
static int located(int s, size_t m, const lemke_run *l, dp_errors *e)
{
    if (s == DP_ENONFINITE) {
        dp_errors_add(e, "/q", "a solution z, or its w = Mz + q, is beyond the double range (above 1.8e308): q is "
                      "too large for M; scale the problem down");
        return DP_EINVAL;
    }
    if (s == DP_ELIMIT) {
        dp_errors_add(e, "/M", "Lemke's method took its limit of %zu pivots (1000 + 200 m, m = %zu) without "
                      "ending, and M is too large to enumerate its complementary bases instead (m > %d)",
                      l->r.pivots, m, DP_LCP_ENUM_MAX);
        return DP_ELIMIT;
    }
    return s;
}

static int solve(const gsl_matrix *M, const gsl_vector *q, const dp_stop *stop, dp_buf *out, dp_errors *e)
{
    size_t m = q->size;
    dp_lcp *ws = dp_lcp_alloc(m);
    gsl_vector *z = gsl_vector_alloc(m), *w = gsl_vector_alloc(m);
    dp_lcp_solutions sol = { 0 };
    dp_lcp_theory t;
    lemke_run l = { { DP_LCP_SOLVED, 0, 0.0 }, 0 };
    int enumerated = m <= DP_LCP_ENUM_MAX;
    int s = ws && z && w ? DP_OK : DP_ENOMEM;
    s = s ? s : dp_lcp_lemke_until(ws, M, q, z, w, &l.r, stop);
    if (s == DP_ELIMIT && enumerated) /* the enumeration answers instead (Murty 1978's matrices) */
        s = DP_OK, l.limit = 1;
    s = s ? s : enumerated ? dp_lcp_enumerate_until(M, q, &sol, stop) : DP_OK;
    s = located(s, m, &l, e);
    if (s == DP_OK && (s = dp_lcp_theory_of(M, &t)) == DP_ENONFINITE) {
        dp_errors_add(e, "/M", "mu = lambda_min((M + M^T)/2) is beyond the double range (above 1.8e308)");
        s = DP_EINVAL;
    }
    s = s ? s : answer(out, z, w, &l, &sol, enumerated, &t);
    dp_lcp_solutions_clear(&sol);
    gsl_vector_free(z);
    gsl_vector_free(w);
    dp_lcp_free(ws);
    return s;
}

int dp_lcp_respond(const char *body, size_t len, dp_buf *out, dp_errors *errs)
{
    return dp_lcp_respond_until(body, len, NULL, out, errs);
}

int dp_lcp_respond_until(const char *body, size_t len, const dp_stop *stop, dp_buf *out, dp_errors *errs)
{
    gsl_matrix *M = NULL;
    gsl_vector *q = NULL;
    size_t mark = out->len;
    int s = read_request(body, len, &M, &q, errs);
    s = s ? s : solve(M, q, stop, out, errs);
    if (s != DP_OK)
        out->len = mark;
    gsl_matrix_free(M);
    gsl_vector_free(q);
    return s;
}

/* ---- the meta line of an LCS run ------------------------------------------------------------------------ */

static int put_kv(dp_buf *b, const char *key, double x)
{
    return put(b, ",\"") || put(b, key) || put(b, "\":") || put_num(b, x);
}

/* "theory":{...} of one matrix, with a sentence on the uniqueness of u it gives. */
static int put_matrix_theory(dp_buf *b, const char *key, const gsl_matrix *M)
{
    dp_lcp_theory t;
    int s = dp_lcp_theory_of(M, &t);
    if (s != DP_OK)
        return put(b, ",\"") || put(b, key) || put(b, "\":null");
    s = put(b, ",\"") || put(b, key) || put(b, "\":{\"matrix\":[");
    for (size_t i = 0; i < M->size1 && !s; i++)
        s = (i ? put(b, ",") : DP_OK) || put_vec(b, M->data + i * M->tda, M->size2);
    s = s || put(b, "]");
    s = s || put_theory(b, &t, M->size1);
    const char *u = t.pd_symmetric ? "one u per step: positive definite symmetric part (Cibulka 2014, Lemma 2.5, Theorem 2.3)"
                  : t.p_matrix == 1 ? "one u per step: a P-matrix"
                  : "uniqueness of u not guaranteed: Lemke's solution is taken when there are several";
    return s || put(b, ",\"uniqueness\":") || dp_json_quote(b, u) || put(b, "}");
}

/* A law as the document gave it (its entry's name and members, dashpot/lcs.h); a user graph with its points,
 * and a graph law with the LCP rows it adds to a step. */
static int put_law(dp_buf *b, const dp_lcs_law *l)
{
    const dp_lcs_law_info *L = dp_lcs_law_info_of(l->kind);
    if (L == NULL)
        return DP_EINVAL;
    int s = put(b, "{\"law\":\"") || put(b, L->row.name) || put(b, "\"");
    for (const dp_law_member *m = L->row.members; m->key && !s; m++)
        s = put(b, ",\"") || put(b, m->key) || put(b, "\":") || put_num(b, dp_law_field_value(l, m->offset));
    if (L->row.points) {
        s = s || put(b, ",\"points\":[");
        for (size_t v = 0; v < l->graph.n && !s; v++) {
            double pt[2] = { l->graph.y[v], l->graph.f[v] };
            s = (v ? put(b, ",") : DP_OK) || put_vec(b, pt, 2);
        }
        s = s || put(b, "]");
    }
    if (dp_lcs_law_is_graph(l))
        s = s || put_kv(b, "lcp_rows", (double)dp_lcs_law_rows(l));
    return s || put(b, "}");
}

int dp_lcs_meta_json(const struct dp_spec *sp, dp_buf *b)
{
    const dp_lcs_model *lm = sp->lcs;
    const dp_solver_spec *sv = &sp->solver;
    char head[160];
    snprintf(head, sizeof head, "{\"type\":\"meta\",\"version\":\"%s\",\"solver\":\"stick-slip\","
             "\"variant\":\"exact\",\"model\":\"lcs\"", DP_VERSION);
    int s = put(b, head) || put_kv(b, "theta", sv->theta) || put_kv(b, "dt", sv->dt) || put_kv(b, "t_end", sv->t_end);
    s = s || put_kv(b, "steps", dp_spec_steps(sp)) || put_kv(b, "every", (double)sp->output.every) || dp_chosen_json(sp, b);
    s = s || put(b, ",\"events_mode\":\"") || put(b, dp_spec_events_mode(sp)) || put(b, "\"");
    s = s || put_kv(b, "states", (double)lm->n) || put_kv(b, "components", (double)lm->m) || put(b, ",\"laws\":[");
    for (size_t i = 0; i < lm->m && !s; i++)
        s = put(b, i ? "," : "") || put_law(b, &lm->law[i]);
    s = s || put(b, "]");
    gsl_matrix_const_view D = gsl_matrix_const_view_array(lm->D, lm->m, lm->m);
    s = s || put_matrix_theory(b, "D", &D.matrix);
    dp_lcs sys = dp_lcs_model_system(lm);
    int st;
    dp_lcs_stepper *step = dp_lcs_stepper_alloc(&sys, sv->dt, sv->theta, &st);
    if (step == NULL)
        return st == DP_ENOMEM ? DP_ENOMEM : DP_EINVAL;
    s = s || put_matrix_theory(b, "step", dp_lcs_step_matrix(step));
    dp_lcs_stepper_free(step);
    return s ? DP_ENOMEM : put(b, "}");
}
