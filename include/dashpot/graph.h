/* include/dashpot/graph.h - constitutive relations as monotone graphs in the (kinematic, force) plane.
 *
 * One representation serves every law (docs/mathematics.md §1): a piecewise-linear curve through vertices
 * (y_i, F_i), non-decreasing in both coordinates, extended at both ends by rays. Vertical pieces (equal y)
 * make the force multi-valued (Coulomb's stick interval, the taut rope); horizontal pieces make the kinematic
 * variable multi-valued (Bingham's yield plateau seen from the force side). A curve that is monotone and
 * unbounded at both ends is a maximal monotone graph, so every law built here is one, and the implicit
 * step, the resolvent J_l = (I + l A)^-1 and the Yosida approximation are exact for it (no iteration).
 */
#ifndef DASHPOT_GRAPH_H
#define DASHPOT_GRAPH_H

#include <stddef.h>

#define DP_GRAPH_MAX_POINTS 10000

typedef struct dp_graph {
    size_t n;          /* number of vertices, >= 1 */
    double *y;         /* kinematic coordinates (x for springs, v for dampers), non-decreasing */
    double *f;         /* forces, non-decreasing */
    double left[2];    /* direction (dy, dF) >= 0 of the ray that leaves vertex 0 towards -infinity */
    double right[2];   /* direction (dy, dF) >= 0 of the ray that leaves vertex n-1 towards +infinity */
} dp_graph;

/* Builds a graph from n vertices and end-ray directions; copies the arrays. Rays with dy = dF = 0 are
 * invalid. Returns DP_OK, DP_EINVAL (not monotone, not finite, n == 0) or DP_ENOMEM; on error g is empty. */
int dp_graph_init(dp_graph *g, size_t n, const double *y, const double *f,
                  const double left[2], const double right[2]);

/* Builds a graph through user points, extending the first and last segments as the end rays.
 * Needs n >= 2 and a non-degenerate first and last segment. */
int dp_graph_init_points(dp_graph *g, size_t n, const double *y, const double *f);

/* Stores points as they are, unchecked (NaN rows mark gaps), for the well-posedness analysis only: a raw
 * graph may be non-monotone and must never reach a solver. Rays continue the end segments. */
int dp_graph_init_raw(dp_graph *g, size_t n, const double *y, const double *f);

/* Frees the vertex arrays; accepts an empty or zeroed graph. */
void dp_graph_clear(dp_graph *g);

/* Deep copy; dst must be empty. */
int dp_graph_copy(dp_graph *dst, const dp_graph *src);

/* The force interval [*lo, *hi] at kinematic value y (lo == hi where the graph is single-valued).
 * Outside the graph's domain (a vertical end ray) lo = hi = +/-INFINITY on the side it lies. Returns DP_OK,
 * or DP_ENONFINITE with lo = hi = NaN when y is not finite (no lookup is made with it). */
int dp_graph_force(const dp_graph *g, double y, double *lo, double *hi);

/* The kinematic interval [*lo, *hi] at force F (the inverse graph); DP_ENONFINITE as dp_graph_force. */
int dp_graph_kinematic(const dp_graph *g, double F, double *lo, double *hi);

/* Resolvent J_l(s): the unique y with y + l*F = s for some F in A(y), l > 0 (1-Lipschitz in s); NaN when
 * s or l is not finite. */
double dp_graph_resolvent(const dp_graph *g, double l, double s);

/* Yosida approximation A_l(y) = (y - J_l(y)) / l: single-valued, monotone, (1/l)-Lipschitz. */
double dp_graph_yosida(const dp_graph *g, double l, double y);

/* Largest slope dF/dy over the graph: its Lipschitz constant as a force law (INFINITY with a vertical piece). */
double dp_graph_lipschitz(const dp_graph *g);

/* The piece of the curve leaving y in direction dir (+1: growing y, -1: falling y): F = f + slope (y' - y)
 * for y' between y and `next` (the next vertex's y, +/-INFINITY on an end ray). blocked: the graph's domain
 * ends at y on that side (a vertical end ray), so y cannot move that way. */
typedef struct dp_graph_piece_t {
    int blocked;
    double slope, f, next;
} dp_graph_piece_t;
void dp_graph_piece(const dp_graph *g, double y, int dir, dp_graph_piece_t *pc);

/* Whether y is exactly one of the graph's vertices. */
int dp_graph_has_vertex(const dp_graph *g, double y);

#endif
