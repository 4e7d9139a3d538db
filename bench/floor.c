/* bench/floor.c - the physical floor of a stick-slip step: the theta-method step of docs/mathematics.md §4 as a
 * bare C loop, constants hoisted, no spec, no run object, no records, no event logic. What is left is the
 * loop-carried dependency chain v -> v_free -> soft threshold -> v+ (and the load's cos() when there is one),
 * which no solver can beat; bench/siconos.sh divides dashpot's output-off cost by it.
 *
 *     W = m + h theta c + h^2 theta^2 k   (c = 0 here: a Coulomb damper has no viscous part)
 *     u = [m v - h k (x + h theta (1 - theta) v) + h F(t + theta h)] / W - vb
 *     v+ = vb + sgn(u) max(|u| - h phi0 / W, 0),   x+ = x + h ((1 - theta) v + theta v+)
 *
 * Usage: floor key=value ... (the keys of stick_slip_bench: m k phi0 vb F0 amp omega phase x0 v0 dt steps
 * theta reps). Prints ns_per_step (best of reps), maxrss_kb and the final state, which the script checks
 * against dashpot's so that the floor is known to compute the same trajectory.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct state { double x, v; } state;

/* The loop. `harmonic` is a compile-time constant at each call site, so the constant-load loop carries no
 * cos() and no test for it. */
static inline state run(double m, double k, double phi0, double vb, double F0, double amp, double omega,
                        double phase, double x, double v, double h, double th, long long steps, int harmonic)
{
    double W = m + h * h * th * th * k, iW = 1 / W;
    double cv = (m - h * h * k * th * (1 - th)) * iW, cx = -h * k * iW, cf = h * iW, thr = h * phi0 * iW;
    double cf0 = cf * F0 - vb, a = h * (1 - th), b = h * th;
    for (long long n = 0; n < steps; n++) {
        double u = cv * v + cx * x + cf0;
        if (harmonic)
            u += cf * amp * cos(omega * ((double)n * h + th * h) + phase);
        /* Branches, not fmax/copysign: while the mass sticks they are predicted, v+ = vb is known before u
         * is, and the chain through v breaks; a branch-free select would wait for u at every step. */
        double v1 = vb;
        if (u > thr)
            v1 += u - thr;
        else if (u < -thr)
            v1 += u + thr;
        x += a * v + b * v1;
        v = v1;
    }
    return (state){ x, v };
}

int main(int argc, char **argv)
{
    const char *keys[] = { "m", "k", "phi0", "vb", "F0", "amp", "omega", "phase", "x0", "v0", "dt", "theta",
                           "steps", "reps" };
    double val[] = { 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 1e-3, 0.5, 1000, 1 };
    enum { NKEYS = sizeof keys / sizeof keys[0] };
    for (int i = 1; i < argc; i++) {
        char *eq = strchr(argv[i], '=');
        int j = 0;
        while (j < NKEYS && !(eq && strlen(keys[j]) == (size_t)(eq - argv[i])
                              && strncmp(argv[i], keys[j], strlen(keys[j])) == 0))
            j++;
        if (j == NKEYS) {
            fprintf(stderr, "floor: bad argument '%s'\n", argv[i]);
            return 2;
        }
        val[j] = strtod(eq + 1, NULL);
    }
    long long steps = (long long)val[12], reps = (long long)val[13];
    double best = INFINITY;
    state s = { 0, 0 };
    for (long long r = 0; r < reps; r++) {
        double t0 = now();
        if (val[5] != 0)
            s = run(val[0], val[1], val[2], val[3], val[4], val[5], val[6], val[7], val[8], val[9], val[10],
                    val[11], steps, 1);
        else
            s = run(val[0], val[1], val[2], val[3], val[4], 0, 0, 0, val[8], val[9], val[10], val[11], steps, 0);
        best = fmin(best, now() - t0);
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    /* Printing the final state also keeps the compiler from discarding the loop. */
    printf("steps %lld\nns_per_step %.4g\nmaxrss_kb %ld\nfinal_x %.17g\nfinal_v %.17g\n", steps,
           1e9 * best / (double)steps, ru.ru_maxrss, s.x, s.v);
    return 0;
}
