/* src/cli/main.c - `dashpot`: the command-line front end (files and pipes) over libdashpot. */
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "commands.h"
#include "dashpot/json.h"

static int usage(FILE *to)
{
    fprintf(to,
            "dashpot %s - oscillators with implicit constitutive laws\n\n"
            "usage:\n"
            "  dashpot simulate SPEC.json|- [--format json|ndjson|csv] [--quiet]\n"
            "  dashpot stability SPEC.json|- [--format json|csv|svg]\n"
            "  dashpot wellposedness SPEC.json|-\n"
            "  dashpot convergence SPEC.json|- [--ref-dt H]\n"
            "  dashpot modes SPEC.json|-\n"
            "  dashpot response SPEC.json|- [--format json|ndjson|csv]\n"
            "  dashpot lcp PROBLEM.json|-\n"
            "  dashpot sweep SWEEP.json|- [--shard i/N] [--threads T]\n"
            "  dashpot --help | --version | COMMAND --help\n\n"
            "Exit codes: 0 success, 1 failure while running, 2 bad usage or invalid spec.\n"
            "Specs: see README.md and api/openapi.yaml.\n", DP_VERSION);
    return to == stdout ? DP_EXIT_OK : DP_EXIT_USAGE;
}

/* `dashpot COMMAND --help`: what the command takes, on stdout, exit 0. */
static const struct { const char *name, *text; } command_help[] = {
    { "simulate",
      "usage: dashpot simulate SPEC.json|- [--format json|ndjson|csv] [--quiet]\n\n"
      "Runs one simulation and writes it to standard output as it is computed.\n"
      "  --format json    one document: meta, samples, events, summary (the default)\n"
      "  --format ndjson  one object per line: meta, samples and events, summary\n"
      "  --format csv     samples only: t,x,v,Fs,Fd,Fc,phase\n"
      "  --quiet          no progress bar (one is drawn on standard error only when it is a terminal\n"
      "                   and the run has at least 2e6 steps)\n"
      "  -                read the spec from standard input\n" },
    { "stability",
      "usage: dashpot stability SPEC.json|- [--format json|csv|svg]\n\n"
      "Stability of a linear fully implicit law; csv and svg need a \"map\" (docs/stability.md).\n" },
    { "wellposedness",
      "usage: dashpot wellposedness SPEC.json|-\n\n"
      "Which existence and uniqueness theorems apply to the spec's model (docs/mathematics.md section 5).\n" },
    { "convergence",
      "usage: dashpot convergence SPEC.json|- [--ref-dt H]\n\n"
      "A convergence study of the regularized solver (docs/regularized.md); --ref-dt sets the reference step.\n" },
    { "modes",
      "usage: dashpot modes SPEC.json|-\n\n"
      "Natural modes of a network's linear part (frequencies, mass-normalized shapes, participation) and,\n"
      "with damping, the damped eigenvalues; set-valued elements are left out and listed (docs/modes.md).\n" },
    { "response",
      "usage: dashpot response SPEC.json|- [--format json|ndjson|csv]\n\n"
      "The receptance of response_node to a harmonic force at force_node over \"omega\", with the\n"
      "resonances and antiresonances located (docs/modes.md).\n" },
    { "lcp",
      "usage: dashpot lcp PROBLEM.json|-\n\n"
      "Solves w = Mz + q, 0 <= z _|_ w >= 0 for {\"M\": [[...]], \"q\": [...]} by Lemke's method, lists every\n"
      "solution when M has at most 12 rows, and says whether M is a P-matrix, mu = lambda_min((M+M^T)/2)\n"
      "(docs/lcs.md).\n" },
    { "sweep",
      "usage: dashpot sweep SWEEP.json|- [--shard i/N] [--threads T]\n\n"
      "Runs a simulate document over a grid of one or two parameters and writes one NDJSON line per run\n"
      "(its features and Poincare section) as it completes, between a meta and a summary line (docs/sweep.md).\n"
      "  --shard i/N   only the runs whose index is i mod N: N parts' run lines, sorted by index, are the whole\n"
      "  --threads T   T runs at once (default 1)\n" },
};

/* 1 when argv[2..] asks for help. */
static int wants_help(int argc, char **argv)
{
    for (int i = 2; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0)
            return 1;
    return 0;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off(); /* the library checks GSL's return codes itself */
    if (argc < 2)
        return usage(stderr);
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)
        return usage(stdout);
    if (strcmp(argv[1], "--version") == 0) {
        printf("dashpot %s\n", DP_VERSION);
        return DP_EXIT_OK;
    }
    for (size_t i = 0; i < sizeof command_help / sizeof command_help[0]; i++)
        if (strcmp(argv[1], command_help[i].name) == 0 && wants_help(argc, argv)) {
            fputs(command_help[i].text, stdout);
            return fflush(stdout) == 0 ? DP_EXIT_OK : DP_EXIT_FAIL;
        }
    if (strcmp(argv[1], "simulate") == 0)
        return dp_cli_simulate(argc - 1, argv + 1);
    if (strcmp(argv[1], "stability") == 0)
        return dp_cli_stability(argc - 1, argv + 1);
    if (strcmp(argv[1], "wellposedness") == 0)
        return dp_cli_wellposedness(argc - 1, argv + 1);
    if (strcmp(argv[1], "convergence") == 0)
        return dp_cli_convergence(argc - 1, argv + 1);
    if (strcmp(argv[1], "modes") == 0 || strcmp(argv[1], "response") == 0)
        return (argv[1][0] == 'm' ? dp_cli_modes : dp_cli_response)(argc - 1, argv + 1);
    if (strcmp(argv[1], "lcp") == 0)
        return dp_cli_lcp(argc - 1, argv + 1);
    if (strcmp(argv[1], "sweep") == 0)
        return dp_cli_sweep(argc - 1, argv + 1);
    fprintf(stderr, "dashpot: unknown command \"%s\"\n", argv[1]);
    return usage(stderr);
}
