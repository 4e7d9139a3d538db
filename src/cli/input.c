/* src/cli/input.c - reading a spec from a file or a pipe, and reporting located errors, for every
 * subcommand alike. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "dashpot/json.h"

char *dp_cli_read_input(const char *path, size_t *len)
{
    FILE *f = strcmp(path, "-") == 0 ? stdin : fopen(path, "rb");
    if (f == NULL) {
        fprintf(stderr, "dashpot: cannot open %s: %s\n", path, strerror(errno));
        return NULL;
    }
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    const char *why = buf == NULL ? "out of memory" : NULL;
    while (why == NULL) {
        if (n == DP_CLI_MAX_INPUT) { /* full: the input may still end right here */
            char extra;
            why = fread(&extra, 1, 1, f) == 1 ? "larger than 64 MiB" : ferror(f) ? strerror(errno) : "";
            break;
        }
        if (n + 1 == cap) { /* grow, to at most DP_CLI_MAX_INPUT bytes and the NUL */
            size_t grown = cap * 2 > DP_CLI_MAX_INPUT + 1 ? DP_CLI_MAX_INPUT + 1 : cap * 2;
            char *bigger = realloc(buf, grown);
            if (bigger == NULL) {
                why = "out of memory";
                break;
            }
            buf = bigger;
            cap = grown;
        }
        size_t got = fread(buf + n, 1, cap - n - 1, f);
        n += got;
        if (got == 0)
            why = ferror(f) ? strerror(errno) : "";
    }
    if (f != stdin)
        fclose(f);
    if (why[0] != '\0') {
        fprintf(stderr, "dashpot: cannot read %s: %s\n", path, why);
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    *len = n;
    return buf;
}

void dp_cli_print_errors(const char *what, const dp_errors *errs)
{
    for (size_t i = 0; i < errs->n; i++)
        fprintf(stderr, "dashpot: %s: %s: %s\n", what,
                errs->item[i].pointer[0] ? errs->item[i].pointer : "(document)", errs->item[i].message);
    if (errs->dropped)
        fprintf(stderr, "dashpot: %s: ... and %zu more errors\n", what, errs->dropped);
}

int dp_cli_parse_spec(const char *path, dp_spec *spec)
{
    size_t len;
    char *text = dp_cli_read_input(path, &len);
    dp_spec_init(spec);
    if (text == NULL)
        return DP_EINVAL;
    dp_errors errs;
    dp_errors_init(&errs);
    int s = dp_spec_parse(text, len, 0, spec, &errs);
    free(text);
    if (s != DP_OK)
        dp_cli_print_errors(path, &errs);
    return s;
}
