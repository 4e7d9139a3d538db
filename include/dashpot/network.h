/* include/dashpot/network.h - many masses joined by implicit springs and dampers (docs/systems.md §1).
 *
 *     M x'' + C_l x' + K_l x + sum_e b_e (F_s,e + F_d,e) = f(t)
 *
 * An element joins two ends a, b (node indices, or DP_GROUND); its elongation is u_e = x_b - x_a, so
 * b_e = e_b - e_a with the ground's entry dropped. Each element carries the one-mass model's laws (model.h):
 * a spring (u_e, F_s,e) and a damper (u_e' - v_b, F_c,e), with the same graphs, prepared by the same code.
 * The one-mass model m x'' + F_s + F_d = F(t) is the network of one node and one element [ground, 0].
 */
#ifndef DASHPOT_NETWORK_H
#define DASHPOT_NETWORK_H

#include <stddef.h>
#include "dashpot/model.h"

#define DP_GROUND (-1L)

/* Documented limits of one network document (a Burridge-Knopoff chain of 10^4 blocks fits). */
#define DP_NETWORK_MAX_NODES 20000
#define DP_NETWORK_MAX_ELEMENTS 100000
/* The working memory of one network run, estimated before anything is allocated (dp_network_run_bytes): its
 * band matrices, n (p+1) doubles each with p the half-bandwidth after the run's reordering (M, K, C; the
 * step's W, H and factor; the impact problem's three with contacts; one more with relaxation; Newmark's two),
 * plus its per-node and per-element arrays. Past this a run is refused (DP_ELIMIT: 422 over-limit at
 * /model/elements), and a step whose contracted factor would grow past it ends the run so. 128 MiB: the
 * Kubernetes manifests give a pod 512 MiB and two worker threads, so two such runs fit with room. */
#define DP_NETWORK_MAX_RUN_BYTES (128.0 * 1024 * 1024)

/* Full matrices are n x n numbers on the wire: past this many nodes a matrix document is refused. */
#define DP_NETWORK_MAX_MATRIX_NODES 200

typedef struct dp_element {
    long a, b;          /* ends: node index or DP_GROUND */
    int has_spring, has_damper, has_contact;
    dp_spring spring;
    dp_damper damper;
    dp_contact contact;
} dp_element;

/* A load on one node. */
typedef struct dp_node_forcing {
    size_t node;
    dp_forcing f;
} dp_node_forcing;

typedef struct dp_network {
    size_t n;              /* nodes (degrees of freedom) */
    double *mass;          /* n diagonal masses, or NULL when `M` is given */
    double *M, *K, *C;     /* n*n row-major symmetric matrices: mass (SPD), stiffness and damping (PSD);
                              NULL when absent */
    size_t nel;
    dp_element *el;
    size_t nforce;
    dp_node_forcing *force;
    int one_mass_doc;      /* made from a one-mass document with a contact: errors name its members */
} dp_network;

/* Builds every element's graphs (dp_model_prepare's laws). DP_OK, DP_EINVAL, DP_ENOMEM. */
int dp_network_prepare(dp_network *net);

/* Frees what the network owns and the network itself; accepts NULL. */
void dp_network_free(dp_network *net);

/* A deep copy (NULL when out of memory). */
dp_network *dp_network_copy(const dp_network *src);

/* Whether the element's damper has a vertical piece at zero relative velocity: it can stick. */
int dp_element_can_stick(const dp_element *e);

/* The linear parts as dense n*n row-major matrices (caller-allocated, overwritten): M (masses or the mass
 * matrix), K = stiffness_matrix + sum of linear springs' k b b^T, C = damping_matrix + sum of the viscous c
 * (linear and Bingham dampers) b b^T. Any of the outputs may be NULL. */
void dp_network_linear_parts(const dp_network *net, double *M, double *K, double *C);

/* Whether the element's spring and damper are linear (or absent), its contact aside. */
int dp_element_laws_linear(const dp_element *e);

/* The elements whose laws are not linear (set-valued or nonlinear springs and dampers, relaxation, contacts):
 * what a linear analysis leaves out. Writes their indices into `out` (room for net->nel; NULL: only counts)
 * and returns how many. */
size_t dp_network_nonlinear_elements(const dp_network *net, size_t *out);

struct dp_wp_report;
/* What the theory guarantees for a checked network (network_wellposedness.c). */
void dp_network_wellposedness(const dp_network *net, struct dp_wp_report *rep);

#endif
