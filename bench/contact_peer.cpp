// bench/contact_peer.cpp - the peer of bench/contact.sh: masses joined by linear springs and
// dampers, loaded by constant forces, with unilateral contacts and Newton impacts, stepped by Siconos'
// kernel in its BouncingBall formulation, so that dashpot's "events": "none" contact step has an
// independent reference (the rules it must match are in bench/contact_peer.md):
//     M v' + C v + K q = f + sum_c b_c P_c,   u_c = b_c^T q >= d_c,   Newton impact law with e_c
// one LagrangianLinearTIDS (M, K, C, constant Fext), one LagrangianLinearTIR per contact
// (y = b_c^T q - d_c, the 1 x n row b_c = e_b - e_a with the ground's entry dropped), NewtonImpactNSL(e_c),
// MoreauJeanOSI(theta) (gamma 1/2 for the index set, Siconos' default), LCP (Lemke), TimeStepping.
//
// The case is a small text file, one item a line ('#' starts a comment; an end is a node index or
// "ground"), in dashpot's conventions (zero-length springs, elongation u = x_b - x_a):
//     masses m0 m1 ...            x0 q0 q1 ...          v0 v0 v1 ...        (x0, v0 default 0)
//     spring a b k                damper a b c          force i f           contact a b d e
//     h 1e-3                      steps 1000            theta 0.5
// Usage: contact_peer CASE [quiet] [reps=R]
//   prints on stdout "t x_0 .. x_{n-1} v_0 .. v_{n-1}" for t = 0 and after every step (not with quiet);
//   on stderr "key value" lines: steps, contacts, setup_seconds, loop_seconds, ns_per_step (the fastest
//   of R runs of the loop; rows are written outside the timed calls).
#include "SiconosKernel.hpp"
#include "SolverOptions.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Contact {
    int a, b;
    double d, e;
};

struct Case {
    std::vector<double> m, q0, v0, f;
    std::vector<std::vector<double>> K, C;
    std::vector<Contact> contacts;
    double h = 1e-3, theta = 0.5;
    long long steps = 1000;
};

// An end: a node index or "ground" (-1).
int parse_end(const std::string &word, size_t n)
{
    if (word == "ground") return -1;
    char *end = nullptr;
    long i = std::strtol(word.c_str(), &end, 10);
    if (*end != '\0' || i < 0 || (size_t)i >= n) throw std::runtime_error("bad end '" + word + "'");
    return (int)i;
}

// Adds k b b^T to A, b = e_b - e_a without the ground's entry.
void add_outer(std::vector<std::vector<double>> &A, int a, int b, double k)
{
    if (a >= 0) A[a][a] += k;
    if (b >= 0) A[b][b] += k;
    if (a >= 0 && b >= 0) {
        A[a][b] -= k;
        A[b][a] -= k;
    }
}

std::vector<double> read_list(std::istringstream &in)
{
    std::vector<double> v;
    double x;
    while (in >> x) v.push_back(x);
    return v;
}

Case read_case(const char *path)
{
    std::ifstream file(path);
    if (!file) throw std::runtime_error(std::string("cannot read ") + path);
    Case c;
    std::string line;
    while (std::getline(file, line)) {
        line = line.substr(0, line.find('#'));
        std::istringstream in(line);
        std::string key;
        if (!(in >> key)) continue;
        size_t n = c.m.size();
        if (key == "masses") {
            c.m = read_list(in);
            n = c.m.size();
            c.q0.assign(n, 0.0), c.v0.assign(n, 0.0), c.f.assign(n, 0.0);
            c.K.assign(n, std::vector<double>(n, 0.0)), c.C = c.K;
        } else if (n == 0) {
            throw std::runtime_error("'masses' must come first");
        } else if (key == "x0" || key == "v0") {
            std::vector<double> v = read_list(in);
            if (v.size() != n) throw std::runtime_error(key + ": one number per node");
            (key == "x0" ? c.q0 : c.v0) = v;
        } else if (key == "spring" || key == "damper" || key == "contact") {
            std::string a, b;
            double p = 0, e = 0;
            if (!(in >> a >> b >> p) || (key == "contact" && !(in >> e)))
                throw std::runtime_error("bad " + key + " line");
            int ia = parse_end(a, n), ib = parse_end(b, n);
            if (ia == ib) throw std::runtime_error(key + ": two different ends");
            if (key == "contact") c.contacts.push_back({ia, ib, p, e});
            else add_outer(key == "spring" ? c.K : c.C, ia, ib, p);
        } else if (key == "force") {
            std::string i;
            double f = 0;
            if (!(in >> i >> f)) throw std::runtime_error("bad force line");
            c.f[(size_t)parse_end(i, n)] += f;
        } else if (key == "h") in >> c.h;
        else if (key == "theta") in >> c.theta;
        else if (key == "steps") in >> c.steps;
        else throw std::runtime_error("unknown key '" + key + "'");
    }
    if (c.m.empty() || c.h <= 0 || c.steps < 1) throw std::runtime_error("need masses, h > 0, steps >= 1");
    return c;
}

SP::SimpleMatrix matrix(const std::vector<std::vector<double>> &A, bool *nonzero)
{
    size_t n = A.size();
    SP::SimpleMatrix M(new SimpleMatrix((unsigned)n, (unsigned)n));
    *nonzero = false;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) {
            (*M)(i, j) = A[i][j];
            *nonzero = *nonzero || A[i][j] != 0;
        }
    return M;
}

SP::SiconosVector vector(const std::vector<double> &v)
{
    SP::SiconosVector x(new SiconosVector((unsigned)v.size()));
    for (size_t i = 0; i < v.size(); i++) (*x)(i) = v[i];
    return x;
}

// The dynamical system: M, and K, C, Fext only when they are not zero (as the BouncingBall example).
SP::LagrangianLinearTIDS make_system(const Case &c)
{
    size_t n = c.m.size();
    std::vector<std::vector<double>> Mv(n, std::vector<double>(n, 0.0));
    for (size_t i = 0; i < n; i++) Mv[i][i] = c.m[i];
    bool nz;
    SP::LagrangianLinearTIDS ds(new LagrangianLinearTIDS(vector(c.q0), vector(c.v0), matrix(Mv, &nz)));
    SP::SimpleMatrix K = matrix(c.K, &nz);
    if (nz) ds->setKPtr(K);
    SP::SimpleMatrix C = matrix(c.C, &nz);
    if (nz) ds->setCPtr(C);
    bool loaded = false;
    for (double f : c.f) loaded = loaded || f != 0;
    if (loaded) ds->setFExtPtr(vector(c.f));
    return ds;
}

// One interaction per contact: y = b^T q - d, Newton impact law with e.
SP::Interaction make_contact(const Contact &k, size_t n)
{
    SP::SimpleMatrix B(new SimpleMatrix(1, (unsigned)n));
    if (k.a >= 0) (*B)(0, k.a) = -1.0;
    if (k.b >= 0) (*B)(0, k.b) = 1.0;
    SP::SiconosVector off(new SiconosVector(1));
    (*off)(0) = -k.d;
    SP::LagrangianLinearTIR rel(new LagrangianLinearTIR(B, off));
    SP::NonSmoothLaw law(new NewtonImpactNSL(k.e));
    return SP::Interaction(new Interaction(law, rel));
}

void print_row(double t, const SiconosVector &q, const SiconosVector &v)
{
    std::printf("%.17g", t);
    for (unsigned i = 0; i < q.size(); i++) std::printf(" %.17g", q(i));
    for (unsigned i = 0; i < v.size(); i++) std::printf(" %.17g", v(i));
    std::printf("\n");
}

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Builds and steps the case once; returns the time spent in Siconos' step calls (setup in *setup).
double run_once(const Case &c, bool rows, double *setup)
{
    auto t0 = std::chrono::steady_clock::now();
    SP::LagrangianLinearTIDS ds = make_system(c);
    // The horizon is one step past the last so that Siconos never clips the final step.
    SP::NonSmoothDynamicalSystem nsds(new NonSmoothDynamicalSystem(0.0, (double)(c.steps + 1) * c.h));
    nsds->insertDynamicalSystem(ds);
    for (const Contact &k : c.contacts) nsds->link(make_contact(k, c.m.size()), ds);
    SP::TimeDiscretisation td(new TimeDiscretisation(0.0, c.h));
    SP::TimeStepping sim(new TimeStepping(nsds, td));
    sim->setNewtonOptions(SICONOS_TS_LINEAR); // linear system: one iteration is the whole step
    sim->insertIntegrator(SP::MoreauJeanOSI(new MoreauJeanOSI(c.theta)));
    SP::LCP lcp(new LCP(SICONOS_LCP_LEMKE));
    lcp->numericsSolverOptions()->dparam[SICONOS_DPARAM_TOL] = 1e-14;
    sim->insertNonSmoothProblem(lcp);
    sim->initialize();
    *setup = seconds_since(t0);

    const SiconosVector &q = *ds->q(), &v = *ds->velocity();
    if (rows) print_row(0.0, q, v);
    double loop = 0;
    for (long long k = 0; k < c.steps; k++) {
        auto ts = std::chrono::steady_clock::now();
        sim->computeOneStep();
        double t = sim->nextTime();
        sim->nextStep();
        loop += seconds_since(ts);
        if (rows) print_row(t, q, v);
    }
    return loop;
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc < 2) {
        std::fprintf(stderr, "usage: contact_peer CASE [quiet] [reps=R]\n");
        return 2;
    }
    bool rows = true;
    long reps = 1;
    for (int i = 2; i < argc; i++) {
        if (std::strcmp(argv[i], "quiet") == 0) rows = false;
        else if (std::strncmp(argv[i], "reps=", 5) == 0) reps = std::strtol(argv[i] + 5, nullptr, 10);
        else {
            std::fprintf(stderr, "contact_peer: bad argument '%s'\n", argv[i]);
            return 2;
        }
    }
    try {
        Case c = read_case(argv[1]);
        double best = 1e300, setup = 0;
        for (long r = 0; r < (reps < 1 ? 1 : reps); r++) {
            double loop = run_once(c, rows && r == 0, &setup);
            if (loop < best) best = loop;
        }
        std::fprintf(stderr, "steps %lld\ncontacts %zu\nsetup_seconds %.6g\nloop_seconds %.6g\nns_per_step %.6g\n",
                     c.steps, c.contacts.size(), setup, best, best / (double)c.steps * 1e9);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "contact_peer: %s\n", e.what());
        return 1;
    }
    return 0;
}
