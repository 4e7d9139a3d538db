// bench/siconos_peer.cpp - the peer of bench/siconos.sh: a 1-DOF Coulomb oscillator
//     m x'' + k x + Fc = F0 + A cos(omega t + phase),   Fc in phi0 Sgn(x' - vb)
// stepped by Siconos' kernel (EulerMoreauOSI + Relay, the formulation of Siconos' FrictionOscillator
// example), written against its public C++ API.
//
// Formulation (first order, state z = (x, v)):
//     z' = A z + b(t) + B lambda,   A = [0 1; -k/m 0],  b = [0; F(t)/m],  B = [0; 1/m]
//     y  = C z + e = v - vb,        C = [0 1],          e = -vb         (the belt enters as the offset e)
//     RelayNSL on [-phi0, phi0]:    -y in N_[-phi0, phi0](lambda), so lambda = -phi0 sgn(v - vb) in slip
// lambda is the friction force on the right-hand side, i.e. Fc = -lambda in dashpot's sign convention.
//
// Usage: siconos_peer key=value ...   keys: m k phi0 vb F0 amp omega phase x0 v0 dt steps theta
//        out=FILE (optional: every step's t, x, v, Fc as 4 native doubles, streamed, nothing kept)
//        solver=lemke|enum|avi (Relay solver, default lemke), tol=1e-14 (its tolerance)
//        newton=linear|nonlinear (TimeStepping's Newton option, default linear: one iteration)
//        reps=R (default 1): build and run the simulation R times, report the fastest loop (not with out=)
// Prints "key value" lines: setup_seconds, loop_seconds, ns_per_step, maxrss_kb, final_x, final_v.
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

namespace {

// The load's parameters: Siconos calls b(t) through a plain function pointer, so they live here.
double g_m = 1, g_F0 = 0, g_amp = 0, g_omega = 0, g_phase = 0;

// b(t) = [0; F(t)/m]; the signature is FirstOrderLinearDS::LDSPtrFunction.
void load(double t, unsigned int size, double *b, unsigned int, double *)
{
    if (size >= 2) {
        b[0] = 0;
        b[1] = (g_F0 + g_amp * std::cos(g_omega * t + g_phase)) / g_m;
    }
}

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The case, read once from the command line.
struct Case {
    double m, k, phi0, vb, x0, v0, h, theta, tol;
    long long steps;
    int solver;
    bool linear_newton;
};

// Builds the model and the simulation and steps it; returns the loop's wall time (setup in *setup), the
// final state in xf, vf; with `out`, writes every step's t, x, v, Fc.
double run_once(const Case &c, FILE *out, double *setup, double *xf, double *vf)
{
    auto t_setup = std::chrono::steady_clock::now();
    SP::SiconosMatrix A(new SimpleMatrix(2, 2));
    (*A)(0, 1) = 1.0;
    (*A)(1, 0) = -c.k / c.m;
    SP::SiconosVector z0(new SiconosVector(2));
    (*z0)(0) = c.x0;
    (*z0)(1) = c.v0;

    // The cheapest dynamical system that expresses the load: time-invariant when it is constant, a b(t)
    // callback only when it is not (Siconos then evaluates it at every step).
    SP::FirstOrderLinearDS ds;
    if (g_amp != 0) {
        ds.reset(new FirstOrderLinearDS(z0, A));
        ds->setComputebFunction(load);
    } else if (g_F0 != 0) {
        SP::SiconosVector b(new SiconosVector(2));
        (*b)(1) = g_F0 / c.m;
        ds.reset(new FirstOrderLinearTIDS(z0, A, b));
    } else {
        ds.reset(new FirstOrderLinearTIDS(z0, A));
    }

    SP::SimpleMatrix C(new SimpleMatrix(1, 2)), B(new SimpleMatrix(2, 1));
    (*C)(0, 1) = 1.0;
    (*B)(1, 0) = 1.0 / c.m;
    SP::FirstOrderLinearTIR rel(new FirstOrderLinearTIR(C, B));
    if (c.vb != 0) {
        SP::SiconosVector e(new SiconosVector(1));
        (*e)(0) = -c.vb;
        rel->setePtr(e);
    }
    SP::NonSmoothLaw law(new RelayNSL(1, -c.phi0, c.phi0));
    SP::Interaction inter(new Interaction(law, rel));

    // The horizon is one step past the last so that Siconos never clips the final step.
    SP::NonSmoothDynamicalSystem nsds(new NonSmoothDynamicalSystem(0.0, (double)(c.steps + 1) * c.h));
    nsds->insertDynamicalSystem(ds);
    nsds->link(inter, ds);

    SP::TimeDiscretisation td(new TimeDiscretisation(0.0, c.h));
    SP::TimeStepping sim(new TimeStepping(nsds, td));
    // The system is linear: one Newton iteration per step is exact (the default iterates to a convergence
    // test; measured, it makes no difference to time or result here).
    sim->setNewtonOptions(c.linear_newton ? SICONOS_TS_LINEAR : SICONOS_TS_NONLINEAR);
    SP::EulerMoreauOSI osi(new EulerMoreauOSI(c.theta));
    sim->insertIntegrator(osi);
    // Lemke (pivoting, as in the FrictionOscillator example) solves the 1x1 relay exactly up to rounding;
    // its tolerance only gates the a-posteriori error check, set tight so that a sloppy answer would be
    // reported, not accepted.
    SP::Relay relay(new Relay(c.solver));
    relay->numericsSolverOptions()->dparam[SICONOS_DPARAM_TOL] = c.tol;
    sim->insertNonSmoothProblem(relay);
    sim->initialize();
    *setup = seconds_since(t_setup);

    SP::SiconosVector z = ds->x();
    SP::SiconosVector lambda = inter->lambda(0);
    auto t_loop = std::chrono::steady_clock::now();
    for (long long n = 0; n < c.steps; n++) {
        sim->computeOneStep();
        if (out != nullptr) {
            double rec[4] = {sim->nextTime(), (*z)(0), (*z)(1), -(*lambda)(0)};
            std::fwrite(rec, sizeof rec, 1, out);
        }
        sim->nextStep();
    }
    double loop = seconds_since(t_loop);
    *xf = (*z)(0), *vf = (*z)(1);
    return loop;
}

}  // namespace

int main(int argc, char **argv)
{
    std::map<std::string, std::string> arg = {
        {"m", "1"},     {"k", "1"},   {"phi0", "1"},  {"vb", "0"},     {"F0", "0"},
        {"amp", "0"},   {"omega", "0"}, {"phase", "0"}, {"x0", "0"},   {"v0", "0"},
        {"dt", "1e-3"}, {"steps", "1000"}, {"theta", "0.5"}, {"out", ""}, {"solver", "lemke"},
        {"tol", "1e-14"}, {"newton", "linear"}, {"reps", "1"}};
    for (int i = 1; i < argc; i++) {
        const char *eq = std::strchr(argv[i], '=');
        std::string key = eq ? std::string(argv[i], (size_t)(eq - argv[i])) : std::string();
        if (eq == nullptr || arg.count(key) == 0) {
            std::fprintf(stderr, "siconos_peer: bad argument '%s'\n", argv[i]);
            return 2;
        }
        arg[key] = eq + 1;
    }
    auto num = [&](const char *key) { return std::strtod(arg[key].c_str(), nullptr); };
    Case c;
    c.m = num("m"), c.k = num("k"), c.phi0 = num("phi0"), c.vb = num("vb"), c.x0 = num("x0"), c.v0 = num("v0");
    c.h = num("dt"), c.theta = num("theta"), c.tol = num("tol");
    c.steps = std::strtoll(arg["steps"].c_str(), nullptr, 10);
    c.solver = arg["solver"] == "enum" ? SICONOS_RELAY_ENUM
             : arg["solver"] == "avi" ? SICONOS_RELAY_AVI_CAOFERRIS : SICONOS_RELAY_LEMKE;
    c.linear_newton = arg["newton"] != "nonlinear";
    g_m = c.m, g_F0 = num("F0"), g_amp = num("amp"), g_omega = num("omega"), g_phase = num("phase");
    const long long reps = std::strtoll(arg["reps"].c_str(), nullptr, 10);
    if (c.steps < 1 || reps < 1 || (reps > 1 && !arg["out"].empty())) {
        std::fprintf(stderr, "siconos_peer: steps and reps must be >= 1, and reps 1 with out=\n");
        return 2;
    }

    FILE *out = nullptr;
    static char iobuf[1 << 20];
    if (!arg["out"].empty()) {
        out = std::fopen(arg["out"].c_str(), "wb");
        if (out == nullptr) {
            std::perror(arg["out"].c_str());
            return 1;
        }
        std::setvbuf(out, iobuf, _IOFBF, sizeof iobuf);
    }

    double best_setup = INFINITY, best_loop = INFINITY, xf = 0, vf = 0;
    try {
        for (long long rep = 0; rep < reps; rep++) {
            double setup;
            best_loop = std::fmin(best_loop, run_once(c, out, &setup, &xf, &vf));
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
    std::printf("setup_seconds %.9g\nloop_seconds %.9g\nns_per_step %.6g\nmaxrss_kb %ld\nfinal_x %.17g\n"
                "final_v %.17g\n", best_setup, best_loop, 1e9 * best_loop / (double)c.steps, ru.ru_maxrss, xf, vf);
    return 0;
}
