// bench/lcs_peer.cpp - the peer of bench/lcs.sh: a linear complementarity system
//     x' = A x + B u,   w = C x + D u,   0 <= u ⊥ w >= 0
// stepped by Siconos' kernel (FirstOrderLinearTIDS + FirstOrderLinearTIR + ComplementarityConditionNSL,
// EulerMoreauOSI(theta), LCP with Lemke), written against its public C++ API. EulerMoreauOSI takes
// x+ = x + h (theta A x+ + (1 - theta) A x) + h B u+ and w+ = C x+ + D u+: dashpot's θ-step exactly, so the
// two trajectories must agree to rounding.
//
// With the offsets p and q of dashpot's model (x' = A x + B u + p, w = C x + D u + q) as the system's
// constant b (FirstOrderLinearTIDS(x0, A, b)) and the relation's e (FirstOrderLinearTIR::setePtr), both
// given to Siconos only when non-zero, so the circuits' runs are what they were.
//
// Usage: lcs_peer FILE   where FILE holds whitespace-separated numbers:
//     n m  A (n x n, by rows)  B (n x m)  C (m x n)  D (m x m)  x0 (n)  h  steps  theta  p (n)  q (m)
// Prints every step's t, x (n), u (m) on one line (%.17g), then "ns_per_step N" on stderr.
#include "SiconosKernel.hpp"
#include "SolverOptions.h"

#include <chrono>
#include <cstdio>
#include <vector>

int main(int argc, char **argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: lcs_peer FILE\n");
        return 2;
    }
    FILE *in = std::fopen(argv[1], "r");
    if (in == nullptr) {
        std::perror(argv[1]);
        return 1;
    }
    unsigned n = 0, m = 0;
    auto num = [&]() {
        double v = 0;
        if (std::fscanf(in, "%lf", &v) != 1) {
            std::fprintf(stderr, "lcs_peer: short input\n");
            std::exit(2);
        }
        return v;
    };
    n = (unsigned)num(), m = (unsigned)num();
    SP::SiconosMatrix A(new SimpleMatrix(n, n));
    SP::SimpleMatrix B(new SimpleMatrix(n, m)), C(new SimpleMatrix(m, n)), D(new SimpleMatrix(m, m));
    for (unsigned i = 0; i < n; i++)
        for (unsigned j = 0; j < n; j++)
            (*A)(i, j) = num();
    for (unsigned i = 0; i < n; i++)
        for (unsigned j = 0; j < m; j++)
            (*B)(i, j) = num();
    for (unsigned i = 0; i < m; i++)
        for (unsigned j = 0; j < n; j++)
            (*C)(i, j) = num();
    for (unsigned i = 0; i < m; i++)
        for (unsigned j = 0; j < m; j++)
            (*D)(i, j) = num();
    SP::SiconosVector x0(new SiconosVector(n));
    for (unsigned i = 0; i < n; i++)
        (*x0)(i) = num();
    double h = num();
    long long steps = (long long)num();
    double theta = num();
    SP::SiconosVector p(new SiconosVector(n)), q(new SiconosVector(m));
    bool has_p = false, has_q = false;
    for (unsigned i = 0; i < n; i++)
        has_p |= ((*p)(i) = num()) != 0.0;
    for (unsigned i = 0; i < m; i++)
        has_q |= ((*q)(i) = num()) != 0.0;
    std::fclose(in);

    try {
        SP::FirstOrderLinearTIDS ds(has_p ? new FirstOrderLinearTIDS(x0, A, p) : new FirstOrderLinearTIDS(x0, A));
        SP::FirstOrderLinearTIR rel(new FirstOrderLinearTIR(C, B));
        rel->setDPtr(D);
        if (has_q)
            rel->setePtr(q);
        SP::NonSmoothLaw law(new ComplementarityConditionNSL(m));
        SP::Interaction inter(new Interaction(law, rel));
        SP::NonSmoothDynamicalSystem nsds(new NonSmoothDynamicalSystem(0.0, (double)(steps + 1) * h));
        nsds->insertDynamicalSystem(ds);
        nsds->link(inter, ds);
        SP::TimeDiscretisation td(new TimeDiscretisation(0.0, h));
        SP::TimeStepping sim(new TimeStepping(nsds, td));
        sim->setNewtonOptions(SICONOS_TS_LINEAR);
        SP::EulerMoreauOSI osi(new EulerMoreauOSI(theta));
        sim->insertIntegrator(osi);
        SP::LCP lcp(new LCP(SICONOS_LCP_LEMKE));
        sim->insertNonSmoothProblem(lcp);
        sim->initialize();
        SP::SiconosVector x = ds->x();
        SP::SiconosVector lambda = inter->lambda(0);
        std::vector<double> rows;
        rows.reserve((size_t)steps * (1 + n + m));
        auto t0 = std::chrono::steady_clock::now();
        for (long long k = 0; k < steps; k++) {
            sim->computeOneStep();
            rows.push_back(sim->nextTime());
            for (unsigned i = 0; i < n; i++)
                rows.push_back((*x)(i));
            for (unsigned i = 0; i < m; i++)
                rows.push_back((*lambda)(i));
            sim->nextStep();
        }
        double loop = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (size_t r = 0; r < rows.size(); r += 1 + n + m) {
            for (unsigned j = 0; j < 1 + n + m; j++)
                std::printf(j ? " %.17g" : "%.17g", rows[r + j]);
            std::printf("\n");
        }
        std::fprintf(stderr, "ns_per_step %.6g\n", 1e9 * loop / (double)steps);
    } catch (...) {
        Siconos::exception::process();
        return 1;
    }
    return 0;
}
