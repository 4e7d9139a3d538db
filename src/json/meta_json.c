/* src/json/meta_json.c - the "meta" object that opens every run's output: what was solved and how, and
 * what the theorems guarantee about it, so a stored trajectory says where it came from. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dashpot/json.h"
#include "dashpot/lcp_json.h"
#include "dashpot/newmark.h"
#include "dashpot/regularized.h"
#include "dashpot/warnings.h"

static int lit(dp_buf *out, const char *s)
{
    return dp_buf_append(out, s, strlen(s));
}

/* Appends "key":number with the shortest round-trip text, like every other number dashpot writes. */
static int num(dp_buf *out, const char *key, double x)
{
    char t[40];
    return lit(out, ",\"") | lit(out, key) | lit(out, "\":") | dp_buf_append(out, t, dp_format_double(t, x));
}

/* A long in decimal, as %ld writes it. */
static int whole(dp_buf *out, long v)
{
    char t[24], *p = t + sizeof t;
    unsigned long u = v < 0 ? 0ul - (unsigned long)v : (unsigned long)v;
    do
        *--p = (char)('0' + u % 10);
    while ((u /= 10) != 0);
    if (v < 0)
        *--p = '-';
    return dp_buf_append(out, p, (size_t)(t + sizeof t - p));
}

static int regularized_fields(const dp_solver_spec *sv, dp_buf *out);

/* ,"warnings":[{"code","pointer","detail"}, ...] when the spec has any (dp_spec_warnings), else nothing: a
 * run without warnings keeps its meta line as it was. */
static int warnings_json(const dp_spec *s, dp_buf *out)
{
    dp_warnings w;
    dp_spec_warnings(s, &w);
    if (w.n == 0)
        return 0;
    int st = lit(out, ",\"warnings\":[");
    for (size_t i = 0; i < w.n; i++) {
        st |= lit(out, i ? ",{\"code\":" : "{\"code\":") | dp_json_quote(out, w.item[i].code);
        st |= lit(out, ",\"pointer\":") | dp_json_quote(out, w.item[i].pointer);
        st |= lit(out, ",\"detail\":") | dp_json_quote(out, w.item[i].detail) | lit(out, "}");
    }
    return st | lit(out, "]");
}

/* Newmark's parameters and the stability limit for the model's highest mode (newmark.h):
 * "beta","gamma","stability":{"omega_max","T_min","dt_over_T_min","limit","inside"}; limit null when
 * the rule is unconditionally stable (2 beta >= gamma), T_min null without stiffness. */
static int newmark_fields(const dp_spec *s, dp_buf *out)
{
    dp_newmark_limit L;
    int st = lit(out, "\"") | num(out, "beta", s->solver.beta) | num(out, "gamma", s->solver.gamma);
    if (dp_newmark_limit_of(s, &L) != DP_OK)
        return st | lit(out, ",\"stability\":null");
    st |= lit(out, ",\"stability\":{\"omega_max\":");
    char t[40];
    st |= dp_buf_append(out, t, dp_format_double(t, L.omega_max));
    if (isfinite(L.T_min))
        st |= num(out, "T_min", L.T_min) | num(out, "dt_over_T_min", L.ratio);
    else
        st |= lit(out, ",\"T_min\":null,\"dt_over_T_min\":0");
    if (isfinite(L.ratio_limit))
        st |= num(out, "limit", L.ratio_limit);
    else
        st |= lit(out, ",\"limit\":null");
    return st | lit(out, L.inside ? ",\"inside\":true}" : ",\"inside\":false}");
}

/* After "solver":"NAME: the solver's own members, in the order each family's meta line has always had them.
 * One row per family and solver kind; NULL rows do not occur (the rules refuse those pairs). */
static int one_mass_theta_fields(const dp_spec *s, dp_buf *out)
{
    const dp_solver_spec *sv = &s->solver;
    int st = lit(out, "\",\"variant\":\"") | lit(out, dp_spec_variant(s));
    st |= lit(out, "\",\"events_mode\":\"") | lit(out, dp_spec_events_mode(s));
    st |= lit(out, sv->branch == DP_BRANCH_MOTION ? "\",\"branch\":\"motion\"" : "\",\"branch\":\"rest\"");
    return st | num(out, "theta", sv->theta);
}

static int one_mass_regularized_fields(const dp_spec *s, dp_buf *out)
{
    return regularized_fields(&s->solver, out);
}

static int one_mass_newmark_fields(const dp_spec *s, dp_buf *out)
{
    return newmark_fields(s, out) | lit(out, ",\"events_mode\":\"") | lit(out, dp_spec_events_mode(s)) | lit(out, "\"");
}

static int network_theta_fields(const dp_spec *s, dp_buf *out)
{
    int st = lit(out, "\",\"variant\":\"") | lit(out, dp_spec_variant(s));
    st |= lit(out, "\",\"events_mode\":\"") | lit(out, dp_spec_events_mode(s));
    return st | lit(out, "\",\"model\":\"network\"") | num(out, "theta", s->solver.theta);
}

static int network_regularized_fields(const dp_spec *s, dp_buf *out)
{
    return regularized_fields(&s->solver, out) | lit(out, ",\"model\":\"network\"");
}

static int network_newmark_fields(const dp_spec *s, dp_buf *out)
{
    return newmark_fields(s, out) | lit(out, ",\"model\":\"network\"");
}

typedef int (*fields_writer)(const dp_spec *s, dp_buf *out);
static const fields_writer one_mass_fields[] = {
    [DP_SOLVER_STICK_SLIP] = one_mass_theta_fields, [DP_SOLVER_ANALYTIC] = one_mass_theta_fields,
    [DP_SOLVER_REGULARIZED] = one_mass_regularized_fields, [DP_SOLVER_NEWMARK] = one_mass_newmark_fields,
};
static const fields_writer network_fields[] = {
    [DP_SOLVER_STICK_SLIP] = network_theta_fields, [DP_SOLVER_REGULARIZED] = network_regularized_fields,
    [DP_SOLVER_NEWMARK] = network_newmark_fields,
};

/* {"type":"meta","version":...,"solver":"NAME and the solver's own members from the family's row. */
static int head(const dp_spec *s, const fields_writer *rows, size_t nrows, dp_buf *out)
{
    size_t k = (size_t)s->solver.kind;
    int st = lit(out, "{\"type\":\"meta\",\"version\":\"" DP_VERSION "\",\"solver\":\"") | lit(out, dp_spec_solver(s));
    return k < nrows && rows[k] ? st | rows[k](s, out) : DP_EINVAL;
}

/* A network run's meta: its size and the columns its rows hold, so an array member can be read by name. */
static int network_meta(const dp_spec *s, dp_buf *out)
{
    const dp_solver_spec *sv = &s->solver;
    const dp_network *net = s->net;
    int st = head(s, network_fields, sizeof network_fields / sizeof *network_fields, out);
    st |= num(out, "dt", sv->dt) | num(out, "t_end", sv->t_end);
    st |= num(out, "steps", dp_spec_steps(s));
    st |= lit(out, ",\"every\":") | whole(out, s->output.every) | dp_chosen_json(s, out);
    st |= lit(out, ",\"nodes\":") | whole(out, (long)net->n) | lit(out, ",\"elements\":") | whole(out, (long)net->nel);
    st |= lit(out, ",\"columns\":{\"nodes\":[");
    size_t nn = s->output.nodes ? s->output.nnodes : net->n, ne = s->output.elements ? s->output.nelements : net->nel;
    for (size_t i = 0; i < nn; i++)
        st |= lit(out, i ? "," : "") | whole(out, (long)(s->output.nodes ? s->output.nodes[i] : i));
    st |= lit(out, "],\"elements\":[");
    for (size_t i = 0; i < ne; i++)
        st |= lit(out, i ? "," : "") | whole(out, (long)(s->output.elements ? s->output.elements[i] : i));
    /* the elastoplastic elements among them: the "p" group's columns */
    size_t np = 0;
    for (size_t i = 0; i < ne; i++) {
        size_t k = s->output.elements ? s->output.elements[i] : i;
        if (net->el[k].has_spring && dp_spring_plastic(&net->el[k].spring))
            st |= lit(out, np++ ? "," : "],\"p\":[") | whole(out, (long)k);
    }
    st |= lit(out, "]},\"wellposedness\":");
    dp_wp_report wp;
    dp_network_wellposedness(net, &wp);
    st |= dp_wellposedness_json(&wp, out);
    st |= warnings_json(s, out);
    st |= dp_buf_append(out, "}", 1);
    return st ? DP_ENOMEM : DP_OK;
}

/* The regularized solver's own parameters in place of the stick-slip ones (variant, events, branch, theta),
 * which it does not have: "scheme":"PC","n":N (PI: "k"),"stepper":...,"rtol":...,"atol":... */
static int regularized_fields(const dp_solver_spec *sv, dp_buf *out)
{
    int pi = sv->scheme == DP_SCHEME_PI;
    int st = lit(out, "\",\"scheme\":\"") | lit(out, pi ? "PI\"" : "PC\"");
    st |= num(out, pi ? "k" : "n", sv->n_list[0]);
    st |= lit(out, ",\"stepper\":\"") | lit(out, dp_stepper_name(sv->stepper)) | lit(out, "\"");
    return st | num(out, "rtol", sv->rtol) | num(out, "atol", sv->atol);
}

/* The one-mass model's meta: its solver, its laws by name and what the theorems guarantee. */
static int one_mass_meta(const dp_spec *s, dp_buf *out)
{
    const dp_solver_spec *sv = &s->solver;
    int st = head(s, one_mass_fields, sizeof one_mass_fields / sizeof *one_mass_fields, out);
    st |= num(out, "dt", sv->dt) | num(out, "t_end", sv->t_end);
    st |= num(out, "steps", dp_spec_steps(s));
    st |= lit(out, ",\"every\":") | whole(out, s->output.every) | dp_chosen_json(s, out);
    st |= lit(out, ",\"spring\":\"") | lit(out, dp_spring_law_name(s->model.spring.law));
    st |= lit(out, "\",\"damper\":\"") | lit(out, dp_damper_law_name(s->model.damper.law));
    st |= lit(out, "\",\"wellposedness\":");
    dp_wp_report wp;
    dp_wellposedness(&s->model, &wp);
    st |= dp_wellposedness_json(&wp, out);
    st |= warnings_json(s, out);
    st |= dp_buf_append(out, "}", 1);
    return st ? DP_ENOMEM : DP_OK;
}

/* One writer per model family. Written piece by piece rather than with snprintf: this object opens every
 * run, small ones included. */
static int (*const family_meta[])(const dp_spec *s, dp_buf *out) = {
    [DP_FAMILY_ONE_MASS] = one_mass_meta, [DP_FAMILY_NETWORK] = network_meta,
    [DP_FAMILY_LCS] = dp_lcs_meta_json, [DP_FAMILY_RIGHT_HAND] = dp_right_hand_meta_json,
};

int dp_spec_meta_json(const dp_spec *s, dp_buf *out)
{
    return family_meta[dp_spec_family(s)](s, out);
}
