/* src/cli/modes_cmd.c - `dashpot modes SPEC` and `dashpot response SPEC [--format json|ndjson|csv]`: the
 * linear analysis of a network (natural modes, damped eigenvalues; the receptance curve with its
 * resonances and antiresonances) to stdout, docs/modes.md.
 *
 * The same entry points as the daemon's POST /v1/modes and /v1/response (modes_json.h), so both answer
 * alike. Exit codes: 0 done, 2 bad usage or an invalid spec (errors on stderr with JSON Pointers), 1
 * otherwise.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "dashpot/encode.h"
#include "dashpot/modes_json.h"

static int usage(int response)
{
    fprintf(stderr, response ? "usage: dashpot response SPEC.json|- [--format json|ndjson|csv]\n"
                             : "usage: dashpot modes SPEC.json|-\n");
    return DP_EXIT_USAGE;
}

static int run(int response, int argc, char **argv)
{
    const char *path = NULL, *format = "json";
    for (int i = 1; i < argc; i++) {
        if (response && strcmp(argv[i], "--format") == 0 && i + 1 < argc)
            format = argv[++i];
        else if (response && strncmp(argv[i], "--format=", 9) == 0)
            format = argv[i] + 9;
        else if (path == NULL && (argv[i][0] != '-' || strcmp(argv[i], "-") == 0))
            path = argv[i];
        else
            return usage(response);
    }
    int f = dp_format_from_name(format);
    if (path == NULL || (f != DP_FORMAT_JSON && f != DP_FORMAT_NDJSON && f != DP_FORMAT_CSV))
        return usage(response);
    size_t len;
    char *text = dp_cli_read_input(path, &len);
    if (text == NULL)
        return DP_EXIT_USAGE;
    dp_buf out = { 0 };
    dp_errors errs;
    dp_errors_init(&errs);
    int s = response ? dp_response_respond(text, len, f, &out, &errs) : dp_modes_respond(text, len, &out, &errs);
    free(text);
    int rc = DP_EXIT_OK;
    if (s != DP_OK) {
        if (errs.n == 0)
            fprintf(stderr, "dashpot: %s: %s\n", path, dp_strerror(s));
        dp_cli_print_errors(path, &errs);
        rc = (s == DP_ESYNTAX || s == DP_EINVAL || s == DP_ELIMIT) ? DP_EXIT_USAGE : DP_EXIT_FAIL;
    } else if (fwrite(out.data, 1, out.len, stdout) != out.len || fflush(stdout) != 0) {
        fprintf(stderr, "dashpot: %s: cannot write the output\n", response ? "response" : "modes");
        rc = DP_EXIT_FAIL;
    }
    dp_buf_free(&out);
    return rc;
}

int dp_cli_modes(int argc, char **argv)
{
    return run(0, argc, argv);
}

int dp_cli_response(int argc, char **argv)
{
    return run(1, argc, argv);
}
