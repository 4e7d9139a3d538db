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
            "  dashpot --help | --version\n\n"
            "Exit codes: 0 success, 1 failure while running, 2 bad usage or invalid spec.\n"
            "Specs: see README.md and api/openapi.yaml.\n", DP_VERSION);
    return to == stdout ? DP_EXIT_OK : DP_EXIT_USAGE;
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
    fprintf(stderr, "dashpot: unknown command \"%s\"\n", argv[1]);
    return usage(stderr);
}
