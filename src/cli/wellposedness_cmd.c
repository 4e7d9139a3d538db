/* src/cli/wellposedness_cmd.c - `dashpot wellposedness SPEC.json`: what the theorems guarantee about a
 * model (existence, uniqueness, the hypotheses with witnesses), as JSON on stdout. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "dashpot/json.h"

int dp_cli_wellposedness(int argc, char **argv)
{
    if (argc != 2 || (argv[1][0] == '-' && argv[1][1] != '\0')) {
        fprintf(stderr, "usage: dashpot wellposedness SPEC.json|-\n");
        return DP_EXIT_USAGE;
    }
    size_t len;
    char *text = dp_cli_read_input(argv[1], &len);
    if (text == NULL)
        return DP_EXIT_USAGE;
    dp_errors errs;
    dp_errors_init(&errs);
    dp_wp_report rep;
    int s = dp_wellposedness_parse(text, len, &rep, &errs);
    free(text);
    if (s != DP_OK) {
        dp_cli_print_errors(argv[1], &errs);
        return s == DP_ENOMEM ? DP_EXIT_FAIL : DP_EXIT_USAGE;
    }
    dp_buf b = { 0 };
    int rc = DP_EXIT_OK;
    if (dp_wellposedness_json(&rep, &b) != DP_OK || fwrite(b.data, 1, b.len, stdout) != b.len || puts("") < 0)
        rc = DP_EXIT_FAIL;
    dp_buf_free(&b);
    return rc;
}
