/* src/cli/convergence_cmd.c - `dashpot convergence SPEC.json [--ref-dt H]`: the convergence study of the
 * regularized solver (one run per n of the spec's list against the exact solution; regularized.h) as JSON
 * on stdout. The output is deterministic: no timings in it (bench/regularized.sh measures those). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "dashpot/encode.h"
#include "dashpot/json.h"
#include "dashpot/regularized.h"

static int usage(void)
{
    fprintf(stderr, "usage: dashpot convergence SPEC.json|- [--ref-dt H]\n");
    return DP_EXIT_USAGE;
}

/* The reference step from argv, 0 (automatic) when absent; -1 when malformed. */
static double ref_dt_arg(int argc, char **argv)
{
    if (argc == 2)
        return 0;
    if (argc != 4 || strcmp(argv[2], "--ref-dt") != 0)
        return -1;
    char *end;
    double h = strtod(argv[3], &end);
    return *end == '\0' && h > 0 && h < 1e300 ? h : -1;
}

static int study(const dp_spec *spec, double ref_dt, const char *path)
{
    dp_errors errs;
    dp_errors_init(&errs);
    dp_convergence *c = malloc(sizeof *c);
    int s = c ? dp_convergence_study(spec, 0, ref_dt, c, &errs) : DP_ENOMEM;
    if (s != DP_OK) {
        if (errs.n == 0)
            dp_errors_add(&errs, "", "%s", dp_strerror(s));
        dp_cli_print_errors(path, &errs);
        free(c);
        return s == DP_EINVAL || s == DP_ELIMIT ? DP_EXIT_USAGE : DP_EXIT_FAIL;
    }
    dp_buf b = { 0 };
    int rc = dp_convergence_json(c, &b) == DP_OK && fwrite(b.data, 1, b.len, stdout) == b.len ? DP_EXIT_OK
                                                                                           : DP_EXIT_FAIL;
    dp_buf_free(&b);
    free(c);
    return rc;
}

int dp_cli_convergence(int argc, char **argv)
{
    double ref_dt = argc >= 2 ? ref_dt_arg(argc, argv) : -1;
    if (ref_dt < 0 || (argv[1][0] == '-' && argv[1][1] != '\0'))
        return usage();
    dp_spec spec;
    int s = dp_cli_parse_spec(argv[1], &spec);
    int rc = s == DP_OK ? study(&spec, ref_dt, argv[1]) : DP_EXIT_USAGE;
    dp_spec_clear(&spec);
    return s == DP_ENOMEM ? DP_EXIT_FAIL : rc;
}
