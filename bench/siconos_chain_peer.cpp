// bench/siconos_chain_peer.cpp - the peer of bench/network.sh: a chain of n blocks with Coulomb friction,
// stepped by Siconos' kernel (EulerMoreauOSI + one Relay row per Coulomb element), as bench/siconos_peer.cpp
// does for one mass. The chain (the same words as bench/network_bench.c, which builds the same network as a
// dashpot document; the heterogeneity formulas below are repeated there and must stay identical):
//     m x_i'' + kg x_i + kc (2 x_i - x_{i-1} - x_{i+1}) + Fc_i + (pair friction) = F0 [i = n-1]
//     Fc_i in phi0_i Sgn(x_i' - vb),   phi0_i = phi0 (1 + het sin(2.3 i))      (ground element i)
//     pair element i (i < n-1, when phic > 0): Fp_i in phic Sgn(x_{i+1}' - x_i')  (no belt)
//     x_i(0) = xamp cos(1.3 i),   v_i(0) = 0.
// Elements in dashpot's order: the n ground elements, then the n-1 neighbour elements (spring kc, and the
// pair friction when phic > 0). Every Coulomb element is one Relay row here.
//
// Formulation (first order, state z = (x, v) in R^2n, one FirstOrderLinearTIDS):
//     z' = A z + b + sum_e B_e lambda_e,   A = [0 I; -M^-1 K 0],  b = [0; F/m],  B_e = [0; M^-1 b_e]
//     y_e = C_e z + e_e = b_e^T v - vb_e,   RelayNSL on [-phi_e, phi_e]    (dashpot's F_c,e = -lambda_e)
// with b_e the element's incidence vector (e_b - e_a, the ground's entry dropped).
//
// Usage: siconos_chain_peer key=value ...   keys: n m kg kc phi0 het phic vb F0 xamp dt steps theta
//        out=FILE (optional: per step t, x[n], v[n], Fc per Coulomb element in element order, native doubles)
//        reps=R (default 1): build and run R times, report the fastest loop (not with out=)
// Prints "key value" lines: setup_seconds, loop_seconds, ns_per_step, maxrss_kb, relay_rows, final_x0.
#include "SiconosKernel.hpp"
#include "SolverOptions.h"

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Case {
    long n;
    double m, kg, kc, phi0, het, phic, vb, F0, xamp, h, theta;
    long long steps;
    bool joint;
    double tol;
};

// One Coulomb element: its ends (a = -1: the ground), bound and belt speed.
struct Friction {
    long a, b;
    double phi, vb;
};

std::vector<Friction> frictions(const Case &c)
{
    std::vector<Friction> f;
    for (long i = 0; i < c.n; i++)
        f.push_back({-1, i, c.phi0 * (1 + c.het * std::sin(2.3 * (double)i)), c.vb});
    for (long i = 0; c.phic > 0 && i + 1 < c.n; i++)
        f.push_back({i, i + 1, c.phic, 0});
    return f;
}

// Builds the model and the simulation and steps it; returns the loop's wall time (setup in *setup).
double run_once(const Case &c, FILE *out, double *setup, double *x0f)
{
    auto t_setup = std::chrono::steady_clock::now();
    const unsigned n = (unsigned)c.n;
    SP::SiconosMatrix A(new SimpleMatrix(2 * n, 2 * n));
    for (unsigned i = 0; i < n; i++) {
        (*A)(i, n + i) = 1.0;
        double diag = c.kg + (i > 0 ? c.kc : 0) + (i + 1 < n ? c.kc : 0);
        (*A)(n + i, i) = -diag / c.m;
        if (i > 0)
            (*A)(n + i, i - 1) = c.kc / c.m;
        if (i + 1 < n)
            (*A)(n + i, i + 1) = c.kc / c.m;
    }
    SP::SiconosVector z0(new SiconosVector(2 * n));
    for (unsigned i = 0; i < n; i++)
        (*z0)(i) = c.xamp * std::cos(1.3 * (double)i);

    SP::FirstOrderLinearDS ds;
    if (c.F0 != 0) {
        SP::SiconosVector b(new SiconosVector(2 * n));
        (*b)(2 * n - 1) = c.F0 / c.m;
        ds.reset(new FirstOrderLinearTIDS(z0, A, b));
    } else {
        ds.reset(new FirstOrderLinearTIDS(z0, A));
    }
    SP::NonSmoothDynamicalSystem nsds(new NonSmoothDynamicalSystem(0.0, (double)(c.steps + 1) * c.h));
    nsds->insertDynamicalSystem(ds);

    // layout=joint (default, Siconos' fastest here): one Interaction whose Relay has one row per Coulomb
    // element; RelayNSL has one bound for all rows, so row e carries lambda_e = phi_e mu_e with mu_e in
    // [-1, 1] (B's column scaled by phi_e; -y in N_[-1,1](mu) is the same law). layout=split: one
    // Interaction per element with its own RelayNSL [-phi_e, phi_e]; Siconos then assembles the e x e'
    // blocks C_e W^-1 B_e' one pair at a time (measured 12x slower at 100 blocks: 0.6 s a step).
    std::vector<Friction> fr = frictions(c);
    std::vector<SP::Interaction> inters;
    const unsigned rows = c.joint ? (unsigned)fr.size() : 1;
    for (size_t first = 0; first < fr.size(); first += rows) {
        SP::SimpleMatrix C(new SimpleMatrix(rows, 2 * n)), B(new SimpleMatrix(2 * n, rows));
        SP::SiconosVector e(new SiconosVector(rows));
        bool belt = false;
        for (unsigned r = 0; r < rows; r++) {
            const Friction &f = fr[first + r];
            double scale = c.joint ? f.phi : 1.0;
            (*C)(r, n + f.b) = 1.0;
            (*B)(n + f.b, r) = scale / c.m;
            if (f.a >= 0) {
                (*C)(r, n + f.a) = -1.0;
                (*B)(n + f.a, r) = -scale / c.m;
            }
            (*e)(r) = -f.vb;
            belt = belt || f.vb != 0;
        }
        SP::FirstOrderLinearTIR rel(new FirstOrderLinearTIR(C, B));
        if (belt)
            rel->setePtr(e);
        double bound = c.joint ? 1.0 : fr[first].phi;
        SP::NonSmoothLaw law(new RelayNSL(rows, -bound, bound));
        SP::Interaction inter(new Interaction(law, rel));
        nsds->link(inter, ds);
        inters.push_back(inter);
    }

    SP::TimeDiscretisation td(new TimeDiscretisation(0.0, c.h));
    SP::TimeStepping sim(new TimeStepping(nsds, td));
    sim->setNewtonOptions(SICONOS_TS_LINEAR); // linear system: one Newton iteration is exact
    SP::EulerMoreauOSI osi(new EulerMoreauOSI(c.theta));
    sim->insertIntegrator(osi);
    // Lemke's pivoting method: exact up to rounding (its tolerance only gates the a-posteriori check).
    SP::Relay relay(new Relay(SICONOS_RELAY_LEMKE));
    relay->numericsSolverOptions()->dparam[SICONOS_DPARAM_TOL] = c.tol;
    sim->insertNonSmoothProblem(relay);
    sim->initialize();
    *setup = seconds_since(t_setup);

    SP::SiconosVector z = ds->x();
    std::vector<double> rec(1 + 2 * n + fr.size());
    auto t_loop = std::chrono::steady_clock::now();
    for (long long s = 0; s < c.steps; s++) {
        sim->computeOneStep();
        if (out != nullptr) {
            rec[0] = sim->nextTime();
            for (unsigned i = 0; i < 2 * n; i++)
                rec[1 + i] = (*z)(i);
            for (size_t e = 0; e < fr.size(); e++)
                rec[1 + 2 * n + e] = c.joint ? -fr[e].phi * (*inters[0]->lambda(0))(e)
                                             : -(*inters[e]->lambda(0))(0);
            std::fwrite(rec.data(), sizeof(double), rec.size(), out);
        }
        sim->nextStep();
    }
    double loop = seconds_since(t_loop);
    *x0f = (*z)(0);
    return loop;
}

}  // namespace

int main(int argc, char **argv)
{
    std::map<std::string, std::string> arg = {
        {"n", "10"},   {"m", "1"},     {"kg", "1"},    {"kc", "1"},    {"phi0", "0.5"}, {"het", "0"},
        {"phic", "0"}, {"vb", "0"},    {"F0", "0"},    {"xamp", "1"},  {"dt", "1e-3"},  {"steps", "1000"},
        {"theta", "0.5"}, {"out", ""}, {"reps", "1"}, {"layout", "joint"}, {"tol", "1e-10"}};
    for (int i = 1; i < argc; i++) {
        const char *eq = std::strchr(argv[i], '=');
        std::string key = eq ? std::string(argv[i], (size_t)(eq - argv[i])) : std::string();
        if (eq == nullptr || arg.count(key) == 0) {
            std::fprintf(stderr, "siconos_chain_peer: bad argument '%s'\n", argv[i]);
            return 2;
        }
        arg[key] = eq + 1;
    }
    auto num = [&](const char *key) { return std::strtod(arg[key].c_str(), nullptr); };
    Case c;
    c.n = std::strtol(arg["n"].c_str(), nullptr, 10);
    c.m = num("m"), c.kg = num("kg"), c.kc = num("kc"), c.phi0 = num("phi0"), c.het = num("het");
    c.phic = num("phic"), c.vb = num("vb"), c.F0 = num("F0"), c.xamp = num("xamp");
    c.h = num("dt"), c.theta = num("theta");
    c.steps = std::strtoll(arg["steps"].c_str(), nullptr, 10);
    c.joint = arg["layout"] != "split", c.tol = num("tol");
    const long long reps = std::strtoll(arg["reps"].c_str(), nullptr, 10);
    if (c.n < 1 || c.steps < 1 || reps < 1 || (reps > 1 && !arg["out"].empty())) {
        std::fprintf(stderr, "siconos_chain_peer: n, steps and reps must be >= 1, and reps 1 with out=\n");
        return 2;
    }
    FILE *out = nullptr;
    if (!arg["out"].empty() && (out = std::fopen(arg["out"].c_str(), "wb")) == nullptr) {
        std::perror(arg["out"].c_str());
        return 1;
    }
    double best_setup = INFINITY, best_loop = INFINITY, x0f = 0;
    try {
        for (long long rep = 0; rep < reps; rep++) {
            double setup;
            best_loop = std::fmin(best_loop, run_once(c, out, &setup, &x0f));
            best_setup = std::fmin(best_setup, setup);
        }
    } catch (...) {
        Siconos::exception::process();
        return 1;
    }
    if (out != nullptr && std::fclose(out) != 0) {
        std::perror(arg["out"].c_str());
        return 1;
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    std::printf("steps %lld\nsetup_seconds %.6g\nloop_seconds %.6g\nns_per_step %.6g\nmaxrss_kb %ld\n"
                "relay_rows %zu\nfinal_x0 %.17g\n", c.steps, best_setup, best_loop,
                1e9 * best_loop / (double)c.steps, ru.ru_maxrss, frictions(c).size(), x0f);
    return 0;
}
