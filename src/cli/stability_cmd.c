/* src/cli/stability_cmd.c - `dashpot stability SPEC.json|- [--format json|csv|svg]`: the stability analysis
 * of a linear implicit law (thesis chapter 1), or a stability map when the spec has a "map", to stdout.
 *
 * The same entry point as the daemon's POST /v1/stability (dp_stability_respond), so both answer alike.
 * Exit codes: 0 done, 2 bad usage or an invalid spec (errors on stderr with their JSON Pointers), 1 otherwise.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "dashpot/stability_json.h"

static int usage(void)
{
    fprintf(stderr, "usage: dashpot stability SPEC.json|- [--format json|csv|svg]\n"
                    "  csv and svg need a \"map\" in the spec; see docs/stability.md\n");
    return DP_EXIT_USAGE;
}

static int format_of(const char *name)
{
    static const char *const names[] = { "json", "csv", "svg" };
    for (int i = 0; i < 3; i++)
        if (strcmp(name, names[i]) == 0)
            return i;
    return -1;
}

int dp_cli_stability(int argc, char **argv)
{
    const char *path = NULL, *format = "json";
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--format") == 0 && i + 1 < argc)
            format = argv[++i];
        else if (strncmp(argv[i], "--format=", 9) == 0)
            format = argv[i] + 9;
        else if (path == NULL && (argv[i][0] != '-' || strcmp(argv[i], "-") == 0))
            path = argv[i];
        else
            return usage();
    }
    int want = format_of(format);
    if (path == NULL || want < 0)
        return usage();
    size_t len;
    char *text = dp_cli_read_input(path, &len);
    if (text == NULL)
        return DP_EXIT_USAGE;
    dp_buf out = { 0 };
    dp_errors errs;
    dp_errors_init(&errs);
    int s = dp_stability_respond(text, len, want, &out, &errs);
    free(text);
    int rc = DP_EXIT_OK;
    if (s != DP_OK) {
        dp_cli_print_errors(path, &errs);
        rc = (s == DP_ESYNTAX || s == DP_EINVAL || s == DP_ELIMIT) ? DP_EXIT_USAGE : DP_EXIT_FAIL;
    } else if (fwrite(out.data, 1, out.len, stdout) != out.len || fflush(stdout) != 0) {
        fprintf(stderr, "dashpot: stability: cannot write the output\n");
        rc = DP_EXIT_FAIL;
    }
    dp_buf_free(&out);
    return rc;
}
