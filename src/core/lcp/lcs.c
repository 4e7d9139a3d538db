/* src/core/lcp/lcs.c - the θ-step of a linear complementarity system (Cibulka 2014, (1.10); docs/systems.md §5):
 * x+ = x + h (A (θ x+ + (1-θ) x) + B u+ + p), w+ = C x+ + D u+ + q, (u+, w+) in the laws, so
 * x+ = x^ + h W B u+ with W = (I - hθA)^-1, x^ = W ((I + h(1-θ)A) x + h p), and u+ solves one LCP
 * w+ = (D + h C W B) u+ + (C x^ + q) per step, by Lemke's method.
 *
 * An interval law u ∈ [lo, hi], w ∈ -N_[lo,hi](u) becomes two complementarity rows: z1 = u - lo ⊥ w + z2 and
 * z2 ⊥ (hi - lo) - z1, z2 = max(-w, 0) (u strictly inside forces z2 = 0 and w = 0; u = hi lets w = -z2 <= 0;
 * u = lo keeps w + z2 >= 0 with z2 = 0). The augmented matrix [[M, J], [-Jᵀ, 0]] adds a skew block, so a
 * positive (semi)definite M stays so and Lemke still decides.
 *
 * A graph law -w ∈ G(u) (G maximal monotone, piecewise linear: docs/lcs.md) is the same construction piece
 * by piece: G = ∂φ with φ convex, and φ(u) = min Σ_p φ_p(τ_p) over the splittings u = u0 + Σ_p σ_p τ_p of u
 * into the graph's non-vertical pieces (a piece p runs from its first vertex, σ_p = -1 for the left ray,
 * τ_p in [0, len_p], its force g_p(τ) = f_p + σ_p κ_p τ), because the pieces' forces increase along the
 * graph. The KKT conditions of that minimum at F = -w are one complementarity row per piece,
 * τ_p ⊥ σ_p (g_p(τ_p) - F) + μ_p, and one more per bounded piece, μ_p ⊥ len_p - τ_p: vertical pieces (force
 * jumps) are the multipliers' work and need no row. The matrix is Sᵀ M S + diag(κ) plus a skew block, so a
 * positive semidefinite M still makes it so. Complementarity (one ray, u0 = 0) and the interval (one bounded
 * piece, u0 = lo) are the special cases, with the LCP they always had.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_blas.h>
#include <gsl/gsl_linalg.h>

#include "dashpot/lcs.h"
#include "dashpot/status.h"

/* One LCP row per non-vertical piece of a component's graph (see above). */
typedef struct piece {
    size_t comp, upper;         /* the component; a bounded piece's second row (its μ), 0 for a ray */
    double sign, f, slope, len; /* σ, the force at its first vertex, κ >= 0, len (INFINITY for a ray) */
    double fend;                /* the force at its right end, from the graph's own points (a ray to the right: none) */
} piece;

/* A boundary between two modes of a component (dp_lcs_boundaries): the LCP row whose complementary pair
 * (z, w) tells the side, its margin sign (z - w), sign +1 or -1. */
typedef struct boundary {
    size_t row;
    double sign;
    int lag;    /* +1 or -1: the side of that sign where u is a multiplier (dp_lcs_boundary_lag); 0: neither */
} boundary;

struct dp_lcs_stepper {
    size_t n, m, ma, np;        /* states, components, LCP size, pieces (the first np rows) */
    gsl_matrix *E, *WB, *C, *D, *M, *Ma, *W;
    gsl_matrix *A, *B;          /* the system's, kept to discretize again at another h (dp_lcs_stepper_set_h) */
    gsl_vector *p;              /* the offset of the following steps */
    double h, theta;
    boundary *bd;               /* the modes' boundaries, component by component (first[i] .. first[i+1]-1) */
    size_t nb, *first;
    gsl_vector *Whp, *q, *u0, *lo, *hi;  /* u at the start of each graph, its domain [lo, hi] */
    piece *pc;
    gsl_vector *xh, *r, *qa, *za, *wa, *u;
    dp_lcp *lcp;                /* NULL when no component has a row (every u fixed by its law) */
};

void dp_lcs_stepper_free(dp_lcs_stepper *st)
{
    if (st == NULL)
        return;
    gsl_matrix *mats[] = { st->E, st->WB, st->C, st->D, st->M, st->Ma, st->W, st->A, st->B };
    gsl_vector *vecs[] = { st->Whp, st->q, st->u0, st->lo, st->hi, st->xh, st->r, st->qa, st->za, st->wa, st->u,
                           st->p };
    for (size_t i = 0; i < sizeof mats / sizeof mats[0]; i++)
        gsl_matrix_free(mats[i]);
    for (size_t i = 0; i < sizeof vecs / sizeof vecs[0]; i++)
        gsl_vector_free(vecs[i]);
    free(st->pc);
    free(st->bd);
    free(st->first);
    dp_lcp_free(st->lcp);
    free(st);
}

static dp_lcs_shape shape_of(const dp_lcs_law *law)
{
    const dp_lcs_law_info *L = dp_lcs_law_info_of(law->kind);
    return L ? L->shape : DP_LCS_SHAPE_NONE;
}

int dp_lcs_law_is_graph(const dp_lcs_law *law)
{
    return shape_of(law) == DP_LCS_SHAPE_GRAPH;
}

/* The direction of the graph into vertex v (from v - 1, or the left ray) and out of it. */
static void directions(const dp_graph *g, size_t v, double in[2], double out[2])
{
    size_t k = g->n;
    in[0] = v ? g->y[v] - g->y[v - 1] : g->left[0], in[1] = v ? g->f[v] - g->f[v - 1] : g->left[1];
    out[0] = v + 1 < k ? g->y[v + 1] - g->y[v] : g->right[0];
    out[1] = v + 1 < k ? g->f[v + 1] - g->f[v] : g->right[1];
}

/* Whether the graph turns at vertex v. A user graph's end points only set its rays' directions (the ray
 * continues the end segment), so they never are; merging straight runs keeps one row per real piece. The
 * directions are scaled to a largest component of 1 first, so that tiny ones do not underflow to "parallel". */
static int turns(const dp_graph *g, size_t v)
{
    double in[2], out[2];
    directions(g, v, in, out);
    double si = fmax(in[0], in[1]), so = fmax(out[0], out[1]);
    if (!(si > 0 && so > 0))
        return 1;     /* a repeated vertex: kept, it adds no piece */
    return (in[0] / si) * (out[1] / so) != (in[1] / si) * (out[0] / so);
}

/* A law's pieces into out (NULL: only count them), its start u0 and domain [lo, hi]; the number of pieces,
 * *bounded of them bounded (each a second row). */
static size_t law_pieces(const dp_lcs_law *law, size_t comp, piece *out, double *u0, double *lo, double *hi,
                         size_t *bounded)
{
    if (!dp_lcs_law_is_graph(law)) {
        int iv = shape_of(law) == DP_LCS_SHAPE_INTERVAL;   /* else a complementarity row: u in [0, inf) */
        *u0 = *lo = iv ? law->lo : 0.0;
        *hi = iv ? law->hi : INFINITY;
        if (out)
            out[0] = (piece){ comp, 0, 1.0, 0.0, 0.0, iv ? law->hi - law->lo : INFINITY, iv ? 0.0 : INFINITY };
        *bounded = iv;
        return 1;
    }
    const dp_graph *g = &law->graph;
    size_t k = g->n, np = 0, first = k, last = 0;
    for (size_t v = 0; v < k; v++)
        if (turns(g, v))
            first = first < k ? first : v, last = v;
    if (first == k)
        first = last = 0;     /* a straight line: anchored at its first point */
    double in[2], dir[2];
    directions(g, first, in, dir);
    *u0 = g->y[first];
    *lo = g->left[0] > 0 ? -INFINITY : g->y[first];
    *hi = g->right[0] > 0 ? INFINITY : g->y[last];
    *bounded = 0;
    if (in[0] > 0 && out)
        out[np] = (piece){ comp, 0, -1.0, g->f[first], in[1] / in[0], INFINITY, g->f[first] };
    np += in[0] > 0;
    for (size_t v = first, next = first + 1; v < last; v = next++) {
        while (next < last && !turns(g, next))
            next++;
        double dy = g->y[next] - g->y[v];
        if (dy > 0 && out)
            out[np] = (piece){ comp, 0, 1.0, g->f[v], isfinite(dy) ? (g->f[next] - g->f[v]) / dy : NAN, dy, g->f[next] };
        np += dy > 0, *bounded += dy > 0;
    }
    directions(g, last, in, dir);
    if (dir[0] > 0 && out)
        out[np] = (piece){ comp, 0, 1.0, g->f[last], dir[1] / dir[0], INFINITY, INFINITY };
    return np + (dir[0] > 0);
}

size_t dp_lcs_law_rows(const dp_lcs_law *law)
{
    if (dp_lcs_law_is_graph(law) && law->graph.n == 0)
        return 0;
    double u0, lo, hi;
    size_t bounded, np = law_pieces(law, 0, NULL, &u0, &lo, &hi, &bounded);
    return np + bounded;
}

static int finite_all(const double *a, size_t k)
{
    for (size_t i = 0; i < k; i++)
        if (!isfinite(a[i]))
            return 0;
    return 1;
}

/* Every piece of a graph law has a finite start force, slope and length (or is a ray): a graph spanning
 * nearly the whole double range can overflow a slope even though its points are finite. */
static int pieces_finite(const dp_lcs_law *l)
{
    double u0, lo, hi;
    size_t bounded, np = law_pieces(l, 0, NULL, &u0, &lo, &hi, &bounded), ok = 1;
    piece *pc = malloc((np ? np : 1) * sizeof *pc);
    if (pc == NULL)
        return 1;     /* not decided here: the stepper's own allocation reports the lack of memory */
    law_pieces(l, 0, pc, &u0, &lo, &hi, &bounded);
    for (size_t a = 0; a < np; a++)
        ok &= isfinite(pc[a].f) && isfinite(pc[a].slope);   /* a segment too long for a double has a NaN slope */
    free(pc);
    return (int)ok;
}

int dp_lcs_law_valid(const dp_lcs_law *l)
{
    if (dp_lcs_law_is_graph(l))
        return l->graph.n > 0 && l->graph.y && l->graph.f && pieces_finite(l);
    return shape_of(l) == DP_LCS_SHAPE_CONE ||
           (shape_of(l) == DP_LCS_SHAPE_INTERVAL && isfinite(l->lo) && isfinite(l->hi) && l->lo <= l->hi);
}

static int valid(const dp_lcs *s, double h, double theta)
{
    if (s->n == 0 || s->m == 0 || s->m > DP_LCP_MAX / 2 || s->n > 4096 || !(h >= 0) || !isfinite(h) ||
        !(theta >= 0 && theta <= 1))
        return 0;
    size_t n = s->n, m = s->m, rows = 0;
    if (!finite_all(s->A, n * n) || !finite_all(s->B, n * m) || !finite_all(s->C, m * n) ||
        !finite_all(s->D, m * m) || !finite_all(s->p, n) || !finite_all(s->q, m))
        return 0;
    for (size_t i = 0; i < m; i++) {
        if (!dp_lcs_law_valid(&s->law[i]))
            return 0;
        rows += dp_lcs_law_rows(&s->law[i]);
    }
    return rows <= DP_LCP_MAX;
}

/* Why a stepper was refused: the member of an LCS document that made it, and a sentence. */
typedef struct refusal {
    const char *where, *why;
} refusal;

static int refuse(refusal *no, const char *where, const char *why)
{
    no->where = where, no->why = why;
    return 0;
}

static int finite_matrix(const gsl_matrix *A)
{
    for (size_t i = 0; i < A->size1; i++)
        if (!finite_all(A->data + i * A->tda, A->size2))
            return 0;
    return 1;
}

/* L = I - hθA, R = I + h(1-θ)A, each entry checked finite where formed. */
static int step_operators(const dp_lcs *s, double h, double theta, gsl_matrix *L, gsl_matrix *R, refusal *no)
{
    size_t n = s->n;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) {
            double a = s->A[i * n + j], d = i == j;
            gsl_matrix_set(L, i, j, d - h * theta * a);
            gsl_matrix_set(R, i, j, d + h * (1 - theta) * a);
        }
    if (!finite_matrix(L) || !finite_matrix(R))
        return refuse(no, "/model/lcs/A", "h θ A or h (1 - θ) A is beyond the double range at this dt");
    return 1;
}

/* W = (I - hθA)^-1, E = W (I + h(1-θ)A), WB = h W B, Whp = h W p, each checked finite where formed; 0 with
 * the member to blame when I - hθA is singular or a product leaves the doubles. */
static int discretize(dp_lcs_stepper *st, const dp_lcs *s, double h, double theta, refusal *no)
{
    size_t n = s->n, m = s->m;
    gsl_matrix *L = gsl_matrix_alloc(n, n), *R = gsl_matrix_alloc(n, n);
    gsl_permutation *p = gsl_permutation_alloc(n);
    int ok = L && R && p, sign;
    if (!ok)
        refuse(no, "", "out of memory");
    ok = ok && step_operators(s, h, theta, L, R, no);
    if (ok && !(gsl_linalg_LU_decomp(L, p, &sign) == GSL_SUCCESS && gsl_linalg_LU_det(L, sign) != 0 &&
                gsl_linalg_LU_invert(L, p, st->W) == GSL_SUCCESS && finite_matrix(st->W)))
        ok = refuse(no, "/solver/dt", "I - h θ A is singular at this step: choose another dt");
    for (size_t j = 0; ok && j < n; j++) {
        gsl_vector_view col = gsl_matrix_column(R, j), out = gsl_matrix_column(st->E, j);
        ok = gsl_linalg_LU_solve(L, p, &col.vector, &out.vector) == GSL_SUCCESS;
    }
    if (ok && !finite_matrix(st->E))
        ok = refuse(no, "/model/lcs/A", "the step's map E = (I - h θ A)^-1 (I + h (1 - θ) A) is beyond the double range");
    for (size_t j = 0; ok && j < m; j++) {
        gsl_vector_view out = gsl_matrix_column(st->WB, j);
        for (size_t i = 0; i < n; i++)
            gsl_vector_set(st->xh, i, h * s->B[i * m + j]);
        ok = gsl_linalg_LU_solve(L, p, st->xh, &out.vector) == GSL_SUCCESS;
    }
    if (ok && !finite_matrix(st->WB))
        ok = refuse(no, "/model/lcs/B", "h (I - h θ A)^-1 B is beyond the double range");
    for (size_t i = 0; ok && i < n; i++)
        gsl_vector_set(st->xh, i, h * s->p[i]);
    ok = ok && gsl_linalg_LU_solve(L, p, st->xh, st->Whp) == GSL_SUCCESS;
    if (ok && !finite_all(st->Whp->data, n))
        ok = refuse(no, "/model/lcs/p", "h (I - h θ A)^-1 p is beyond the double range");
    gsl_matrix_free(L);
    gsl_matrix_free(R);
    gsl_permutation_free(p);
    return ok;
}

/* The boundaries between the modes of one component, whose pieces are pc[a0 .. a1-1] in order along its graph
 * (docs/lcs.md, "Mode changes"): before the first piece when it is no left ray (u held at its lowest value), after
 * each piece but the right ray, and where the graph jumps (a vertical piece between two pieces) before the next
 * one too. A boundary's side is read from one LCP row whose margin has a strict sign on either side: after a
 * left ray w - z of its row (w > 0 once F passes its end force), after a bounded piece μ - (len - τ) of its
 * second row, before a piece τ - w of its row (w > 0 while F is below its start force). At a kink (no jump) the
 * one boundary is read after the piece when the next one rises (F then passes the end force) and before the
 * next one otherwise (the piece then rises into it). Appends to bd; returns the count. */
static size_t component_boundaries(const piece *pc, size_t a0, size_t a1, int held, boundary *bd)
{
    size_t nb = 0;
    if (a1 > a0 && pc[a0].sign > 0)
        bd[nb++] = (boundary){ a0, 1.0, held && pc[a0].slope == 0 };
    for (size_t j = a0; j < a1; j++) {
        const piece *P = &pc[j];
        if (P->sign > 0 && !isfinite(P->len))
            continue;      /* the right ray: nothing after it */
        int lag = held && P->slope == 0 ? -1 : 0;
        boundary after = P->sign < 0 ? (boundary){ j, -1.0, lag } : (boundary){ P->upper, 1.0, lag };
        if (j + 1 == a1 || pc[j + 1].f > P->fend || pc[j + 1].slope > 0)
            bd[nb++] = after;
        if (j + 1 < a1 && (pc[j + 1].f > P->fend || !(pc[j + 1].slope > 0)))
            bd[nb++] = (boundary){ j + 1, 1.0, held && pc[j + 1].slope == 0 };
    }
    return nb;
}

/* Whether component i's w does not depend on u algebraically (D's row and column i zero): on a flat piece its
 * u is then a multiplier of a held w, which the θ-step takes as the mean of u over the step. */
static int multiplier(const dp_lcs *s, size_t i)
{
    for (size_t j = 0; j < s->m; j++)
        if (s->D[i * s->m + j] != 0 || s->D[j * s->m + i] != 0)
            return 0;
    return 1;
}

/* Every component's pieces, rows first, then the second rows of the bounded ones; returns the LCP size. */
static size_t layout(dp_lcs_stepper *st, const dp_lcs *s)
{
    size_t np = 0, ma;
    for (size_t i = 0; i < s->m; i++) {
        double u0, lo, hi;
        size_t bounded;
        np += law_pieces(&s->law[i], i, st->pc + np, &u0, &lo, &hi, &bounded);
        gsl_vector_set(st->u0, i, u0);
        gsl_vector_set(st->lo, i, lo);
        gsl_vector_set(st->hi, i, hi);
    }
    ma = np;
    for (size_t a = 0; a < np; a++)
        if (isfinite(st->pc[a].len))
            st->pc[a].upper = ma++;
    st->np = np;
    size_t a0 = 0;
    st->nb = 0;
    for (size_t i = 0; i < s->m; i++) {
        size_t a1 = a0;
        while (a1 < np && st->pc[a1].comp == i)
            a1++;
        st->first[i] = st->nb;
        st->nb += component_boundaries(st->pc, a0, a1, multiplier(s, i), st->bd + st->nb);
        a0 = a1;
    }
    st->first[s->m] = st->nb;
    return ma;
}

/* Whether every entry of the product A B is finite: which factor of the step's matrix to blame. */
static int product_finite(const gsl_matrix *A, const gsl_matrix *B)
{
    for (size_t i = 0; i < A->size1; i++)
        for (size_t j = 0; j < B->size2; j++) {
            double acc = 0;
            for (size_t k = 0; k < A->size2; k++)
                acc += gsl_matrix_get(A, i, k) * gsl_matrix_get(B, k, j);
            if (!isfinite(acc))
                return 0;
        }
    return 1;
}

/* M = D + C WB, and the augmented matrix Sᵀ M S + diag(κ) with each bounded piece's skew pair of rows; each
 * checked finite where formed (0 with the member to blame). */
static int assemble(dp_lcs_stepper *st, refusal *no)
{
    gsl_matrix_memcpy(st->M, st->D);
    gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, st->C, st->WB, 1.0, st->M);
    if (!finite_matrix(st->M))
        return refuse(no, product_finite(st->C, st->WB) ? "/model/lcs/D" : "/model/lcs/C",
                      "the step's matrix D + h C (I - h θ A)^-1 B is beyond the double range");
    if (st->ma == 0)
        return 1;
    gsl_matrix_set_zero(st->Ma);
    for (size_t a = 0; a < st->np; a++) {
        const piece *pa = &st->pc[a];
        for (size_t b = 0; b < st->np; b++) {
            const piece *pb = &st->pc[b];
            double mab = pa->sign * pb->sign * gsl_matrix_get(st->M, pa->comp, pb->comp);
            gsl_matrix_set(st->Ma, a, b, a == b ? mab + pa->slope : mab);
        }
        if (pa->upper) {
            gsl_matrix_set(st->Ma, a, pa->upper, 1.0);
            gsl_matrix_set(st->Ma, pa->upper, a, -1.0);
        }
    }
    if (!finite_matrix(st->Ma))
        return refuse(no, "/model/laws", "a law's slope added to the step's matrix is beyond the double range");
    return 1;
}

dp_lcs_stepper *dp_lcs_stepper_alloc(const dp_lcs *s, double h, double theta, int *status)
{
    const char *where, *why;
    return dp_lcs_stepper_alloc_why(s, h, theta, status, &where, &why);
}

dp_lcs_stepper *dp_lcs_stepper_alloc_why(const dp_lcs *s, double h, double theta, int *status, const char **where,
                                         const char **why)
{
    refusal no = { "", "invalid system" };
    *where = no.where, *why = no.why;
    *status = DP_EINVAL;
    if (!valid(s, h, theta))
        return NULL;
    *status = DP_ENOMEM;
    dp_lcs_stepper *st = calloc(1, sizeof *st);
    if (st == NULL)
        return NULL;
    size_t n = s->n, m = s->m, np = 0, ma = 0;
    for (size_t i = 0; i < m; i++) {
        double u0, lo, hi;
        size_t bounded;
        np += law_pieces(&s->law[i], i, NULL, &u0, &lo, &hi, &bounded);
        ma += dp_lcs_law_rows(&s->law[i]);
    }
    size_t ka = ma ? ma : 1;     /* GSL allocates no empty matrix: a dummy row when every u is fixed */
    st->n = n, st->m = m, st->ma = ma;
    st->E = gsl_matrix_alloc(n, n), st->WB = gsl_matrix_alloc(n, m), st->C = gsl_matrix_alloc(m, n);
    st->D = gsl_matrix_alloc(m, m), st->M = gsl_matrix_alloc(m, m), st->Ma = gsl_matrix_alloc(ka, ka);
    st->W = gsl_matrix_alloc(n, n), st->h = h;
    st->Whp = gsl_vector_alloc(n), st->q = gsl_vector_alloc(m), st->u0 = gsl_vector_alloc(m);
    st->lo = gsl_vector_alloc(m), st->hi = gsl_vector_alloc(m), st->xh = gsl_vector_alloc(n);
    st->r = gsl_vector_alloc(m), st->qa = gsl_vector_alloc(ka), st->za = gsl_vector_alloc(ka);
    st->wa = gsl_vector_alloc(ka), st->u = gsl_vector_alloc(m), st->pc = calloc(np ? np : 1, sizeof *st->pc);
    st->A = gsl_matrix_alloc(n, n), st->B = gsl_matrix_alloc(n, m), st->p = gsl_vector_alloc(n);
    st->bd = calloc(2 * np + m, sizeof *st->bd), st->first = calloc(m + 1, sizeof *st->first);
    st->lcp = ma ? dp_lcp_alloc(ma) : NULL;
    if (!st->E || !st->WB || !st->W || !st->C || !st->D || !st->M || !st->Ma || !st->Whp || !st->q || !st->u0 ||
        !st->lo || !st->hi || !st->xh || !st->r || !st->qa || !st->za || !st->wa || !st->u || !st->pc ||
        !st->A || !st->B || !st->p || !st->bd || !st->first || (ma && !st->lcp)) {
        dp_lcs_stepper_free(st);
        *why = "out of memory";
        return NULL;
    }
    memcpy(st->C->data, s->C, m * n * sizeof(double));
    memcpy(st->D->data, s->D, m * m * sizeof(double));
    memcpy(st->q->data, s->q, m * sizeof(double));
    memcpy(st->A->data, s->A, n * n * sizeof(double));
    memcpy(st->B->data, s->B, n * m * sizeof(double));
    memcpy(st->p->data, s->p, n * sizeof(double));
    st->theta = theta;
    layout(st, s);
    if (!discretize(st, s, h, theta, &no) || !assemble(st, &no)) {
        *status = no.where[0] ? DP_EINVAL : DP_ENOMEM;
        *where = no.where, *why = no.why;
        dp_lcs_stepper_free(st);
        return NULL;
    }
    *status = DP_OK;
    return st;
}

void dp_lcs_stepper_set_p(dp_lcs_stepper *st, const double *p)
{
    memcpy(st->p->data, p, st->n * sizeof *p);
    gsl_blas_dgemv(CblasNoTrans, st->h, st->W, st->p, 0.0, st->Whp);
}

int dp_lcs_stepper_set_h(dp_lcs_stepper *st, double h)
{
    if (!(h >= 0) || !isfinite(h))
        return DP_EINVAL;
    /* the system as discretize and assemble read it: its A, B and the current p (C, D, q, the pieces kept) */
    dp_lcs sys = { st->n, st->m, st->A->data, st->B->data, NULL, NULL, st->p->data, NULL, NULL };
    refusal no = { "", "" };
    st->h = h;
    if (!discretize(st, &sys, h, st->theta, &no) || !assemble(st, &no))
        return no.where[0] ? DP_EINVAL : DP_ENOMEM;
    return DP_OK;
}

size_t dp_lcs_boundaries(const dp_lcs_stepper *st, const size_t **first)
{
    *first = st->first;
    return st->nb;
}

int dp_lcs_boundary_lag(const dp_lcs_stepper *st, size_t b)
{
    return b < st->nb ? st->bd[b].lag : 0;
}

void dp_lcs_margins(const dp_lcs_stepper *st, double *margin)
{
    for (size_t b = 0; b < st->nb; b++) {
        const boundary *bd = &st->bd[b];
        margin[b] = bd->sign * (gsl_vector_get(st->za, bd->row) - gsl_vector_get(st->wa, bd->row));
    }
}

const gsl_matrix *dp_lcs_step_matrix(const dp_lcs_stepper *st)
{
    return st->M;
}

/* The LCP's q from r: σ_p (f_p + r_i + (M u0)_i) in a piece's row, len_p in its second row. */
static void offsets(dp_lcs_stepper *st)
{
    size_t m = st->m;
    for (size_t i = 0; i < m; i++) {
        double s = gsl_vector_get(st->r, i);
        for (size_t j = 0; j < m; j++)
            s += gsl_matrix_get(st->M, i, j) * gsl_vector_get(st->u0, j);
        gsl_vector_set(st->u, i, s);        /* scratch: r + M u0 */
    }
    for (size_t a = 0; a < st->np; a++) {
        const piece *pa = &st->pc[a];
        gsl_vector_set(st->qa, a, pa->sign * (pa->f + gsl_vector_get(st->u, pa->comp)));
        if (pa->upper)
            gsl_vector_set(st->qa, pa->upper, pa->len);
    }
}

/* u+ from one LCP (none when every u is fixed by its law): u0 + Σ σ_p τ_p, kept in the law's domain against
 * rounding. DP_ESOLVE when Lemke ends on a ray or on an answer that fails its check (res->outcome says
 * which), DP_ENONFINITE when the LCP's offsets leave the doubles, Lemke's DP_ELIMIT and DP_ECANCEL. */
static int solve_pieces(dp_lcs_stepper *st, dp_lcp_result *res, const dp_stop *stop)
{
    *res = (dp_lcp_result){ DP_LCP_SOLVED, 0, 0.0 };
    if (st->ma > 0) {
        offsets(st);
        if (!finite_all(st->qa->data, st->ma))
            return DP_ENONFINITE;
        int s = dp_lcp_lemke_until(st->lcp, st->Ma, st->qa, st->za, st->wa, res, stop);
        if (s != DP_OK)
            return s;
        if (res->outcome != DP_LCP_SOLVED)
            return DP_ESOLVE;
    }
    gsl_vector_memcpy(st->u, st->u0);
    for (size_t a = 0; a < st->np; a++) {
        const piece *pa = &st->pc[a];
        gsl_vector_set(st->u, pa->comp, gsl_vector_get(st->u, pa->comp) + pa->sign * gsl_vector_get(st->za, a));
    }
    for (size_t i = 0; i < st->m; i++)
        gsl_vector_set(st->u, i, fmax(fmin(gsl_vector_get(st->u, i), gsl_vector_get(st->hi, i)),
                                      gsl_vector_get(st->lo, i)));
    return DP_OK;
}

int dp_lcs_step(dp_lcs_stepper *st, double *x, double *u, double *w, dp_lcp_result *res)
{
    return dp_lcs_step_until(st, x, u, w, res, NULL);
}

int dp_lcs_step_until(dp_lcs_stepper *st, double *x, double *u, double *w, dp_lcp_result *res, const dp_stop *stop)
{
    size_t n = st->n, m = st->m;
    int s;
    gsl_vector_view xv = gsl_vector_view_array(x, n);
    /* x^ = E x + h W p; r = C x^ + q */
    gsl_blas_dgemv(CblasNoTrans, 1.0, st->E, &xv.vector, 0.0, st->xh);
    gsl_vector_add(st->xh, st->Whp);
    gsl_vector_memcpy(st->r, st->q);
    gsl_blas_dgemv(CblasNoTrans, 1.0, st->C, st->xh, 1.0, st->r);
    if ((s = solve_pieces(st, res, stop)) != DP_OK)
        return s;
    /* x+ = x^ + h W B u+, w+ = C x+ + D u+ + q */
    gsl_vector_memcpy(&xv.vector, st->xh);
    gsl_blas_dgemv(CblasNoTrans, 1.0, st->WB, st->u, 1.0, &xv.vector);
    gsl_vector_view wv = gsl_vector_view_array(w, m);
    gsl_vector_memcpy(&wv.vector, st->q);
    gsl_blas_dgemv(CblasNoTrans, 1.0, st->C, &xv.vector, 1.0, &wv.vector);
    gsl_blas_dgemv(CblasNoTrans, 1.0, st->D, st->u, 1.0, &wv.vector);
    memcpy(u, st->u->data, m * sizeof *u);
    return DP_OK;
}
