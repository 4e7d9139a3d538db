/* src/cli/lcp_cmd.c - `dashpot lcp PROBLEM`: one linear complementarity problem {"M", "q"} solved and
 * analysed (docs/lcs.md), by the same entry point as the daemon's POST /v1/lcp (lcp_json.h).
 * Exit codes: 0 done, 2 bad usage or an invalid problem (errors on stderr with JSON Pointers), 1 otherwise.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "dashpot/lcp_json.h"

int dp_cli_lcp(int argc, char **argv)
{
    if (argc != 2 || (argv[1][0] == '-' && strcmp(argv[1], "-") != 0)) {
        fprintf(stderr, "usage: dashpot lcp PROBLEM.json|-\n");
        return DP_EXIT_USAGE;
    }
    size_t len;
    char *text = dp_cli_read_input(argv[1], &len);
    if (text == NULL)
        return DP_EXIT_USAGE;
    dp_buf out = { 0 };
    dp_errors errs;
    dp_errors_init(&errs);
    int s = dp_lcp_respond(text, len, &out, &errs);
    free(text);
    int rc = DP_EXIT_OK;
    if (s != DP_OK) {
        if (errs.n == 0)
            fprintf(stderr, "dashpot: %s: %s\n", argv[1], dp_strerror(s));
        dp_cli_print_errors(argv[1], &errs);
        rc = (s == DP_ESYNTAX || s == DP_EINVAL) ? DP_EXIT_USAGE : DP_EXIT_FAIL;
    } else if (fwrite(out.data, 1, out.len, stdout) != out.len || fflush(stdout) != 0) {
        fprintf(stderr, "dashpot: lcp: cannot write the output\n");
        rc = DP_EXIT_FAIL;
    }
    dp_buf_free(&out);
    return rc;
}
