/* src/core/analysis/newmark_limit.c - the stability limit of the Newmark rule for the model's highest mode
 * (include/dashpot/newmark.h): dt / T_min against 1 / (2 pi sqrt(gamma/2 - beta)), reported in the meta line. */
#include <math.h>

#include <gsl/gsl_eigen.h>

#include "dashpot/newmark.h"

/* The highest omega^2 of K phi = omega^2 M phi with every spring's elastic stiffness. */
static int omega2_max(const dp_spec *s, double *w2)
{
    if (s->net == NULL) {
        const dp_spring *sp = &s->model.spring;
        *w2 = sp->k / s->model.mass;
        return DP_OK;
    }
    const dp_network *net = s->net;
    size_t n = net->n;
    gsl_matrix *M = gsl_matrix_calloc(n, n), *K = gsl_matrix_calloc(n, n);
    gsl_vector *ev = gsl_vector_alloc(n);
    gsl_eigen_gensymm_workspace *ws = gsl_eigen_gensymm_alloc(n);
    int st = DP_ENOMEM;
    if (M && K && ev && ws) {
        dp_network_linear_parts(net, M->data, K->data, NULL);
        for (size_t i = 0; i < net->nel; i++) {
            const dp_element *el = &net->el[i];
            if (!el->has_spring || !dp_spring_plastic(&el->spring))
                continue;
            long a = el->a, b = el->b;
            double k = el->spring.k;
            if (a >= 0)
                *gsl_matrix_ptr(K, (size_t)a, (size_t)a) += k;
            if (b >= 0)
                *gsl_matrix_ptr(K, (size_t)b, (size_t)b) += k;
            if (a >= 0 && b >= 0)
                *gsl_matrix_ptr(K, (size_t)a, (size_t)b) -= k, *gsl_matrix_ptr(K, (size_t)b, (size_t)a) -= k;
        }
        st = gsl_eigen_gensymm(K, M, ev, ws) == 0 ? DP_OK : DP_ESOLVE;
        *w2 = 0;
        for (size_t i = 0; st == DP_OK && i < n; i++)
            *w2 = fmax(*w2, gsl_vector_get(ev, i));
    }
    gsl_eigen_gensymm_free(ws);
    gsl_vector_free(ev);
    gsl_matrix_free(M);
    gsl_matrix_free(K);
    return st;
}

int dp_newmark_limit_of(const dp_spec *s, dp_newmark_limit *out)
{
    double w2, beta = s->solver.beta, gamma = s->solver.gamma;
    int st = omega2_max(s, &w2);
    if (st != DP_OK)
        return st;
    out->omega_max = sqrt(w2);
    out->T_min = w2 > 0 ? 2 * M_PI / out->omega_max : INFINITY;
    out->ratio = s->solver.dt / out->T_min;
    out->ratio_limit = 2 * beta >= gamma ? INFINITY : 1 / sqrt(gamma / 2 - beta) / (2 * M_PI);
    out->inside = out->ratio <= out->ratio_limit;
    return DP_OK;
}
