/* bench/contact_floor.c - the physical floor of a contact step: Moreau-Jean's theta-step of the bouncing ball
 * (bench/contact_peer.md's rules for one mass and one rigid stop) as a bare C loop, constants hoisted, no
 * spec, no run object, no records, no event logic; bench/contact.sh prints it beside dashpot's cost per step,
 * as bench/floor.c is printed beside the stick-slip step.
 *
 *     armed for the step when  x + h/2 v <= d,   then  v+ = max(v_free, -e v),   else  v+ = v_free,
 *     v_free = v + h g,   x+ = x + h ((1 - theta) v + theta v+)
 *
 * (one mass under a constant load g per unit mass, the stop at d: Newton's impact law on the step's end
 * velocity, Moreau 1988, Jean 1999). Usage: contact_floor key=value ... (g e d x0 v0 dt steps theta reps).
 * Prints ns_per_step (best of reps), maxrss_kb and the final state.
 */
#include <float.h>
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

static state run(double g, double e, double d, double x, double v, double h, double th, long long steps)
{
    double a = h * (1 - th), b = h * th, hg = h * g, half = 0.5 * h;
    for (long long n = 0; n < steps; n++) {
        double v1 = v + hg;
        if (fabs(v) < DBL_MIN)
            v = 0;   /* as dashpot: a resting rate decays by e a step into subnormals, taken as 0 */
        if (x + half * v <= d && v1 < -e * v)
            v1 = -e * v;
        x += a * v + b * v1;
        v = v1;
    }
    return (state){ x, v };
}

int main(int argc, char **argv)
{
    const char *keys[] = { "g", "e", "d", "x0", "v0", "dt", "steps", "theta", "reps" };
    double val[] = { -9.81, 0.9, 0, 1, 0, 1e-3, 1000, 0.5, 1 };
    enum { NKEYS = sizeof keys / sizeof keys[0] };
    for (int i = 1; i < argc; i++) {
        char *eq = strchr(argv[i], '=');
        int j = 0;
        while (j < NKEYS && !(eq && strlen(keys[j]) == (size_t)(eq - argv[i])
                              && strncmp(argv[i], keys[j], strlen(keys[j])) == 0))
            j++;
        if (j == NKEYS) {
            fprintf(stderr, "contact_floor: bad argument '%s'\n", argv[i]);
            return 2;
        }
        val[j] = strtod(eq + 1, NULL);
    }
    long long steps = (long long)val[6], reps = (long long)val[8];
    double best = INFINITY;
    state s = { 0, 0 };
    for (long long r = 0; r < reps; r++) {
        double t0 = now();
        s = run(val[0], val[1], val[2], val[3], val[4], val[5], val[7], steps);
        best = fmin(best, now() - t0);
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    /* Printing the final state also keeps the compiler from discarding the loop. */
    printf("steps %lld\nns_per_step %.4g\nmaxrss_kb %ld\nfinal_x %.17g\nfinal_v %.17g\n", steps,
           1e9 * best / (double)steps, ru.ru_maxrss, s.x, s.v);
    return 0;
}
