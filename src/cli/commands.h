/* src/cli/commands.h - the subcommands of the `dashpot` CLI and what they share. */
#ifndef DASHPOT_CLI_COMMANDS_H
#define DASHPOT_CLI_COMMANDS_H

#include <stddef.h>

#include "dashpot/spec.h"
#include "dashpot/status.h"

/* Exit codes: 0 success, 1 a failure while running, 2 bad usage or an invalid spec. */
enum { DP_EXIT_OK = 0, DP_EXIT_FAIL = 1, DP_EXIT_USAGE = 2 };

/* Largest spec document the CLI reads (a graph of 10^4 points is ~400 KiB). */
#define DP_CLI_MAX_INPUT (64u << 20)

/* Reads a whole file, or standard input for "-", into a malloc'd NUL-terminated buffer; NULL on failure
 * with a message on stderr. */
char *dp_cli_read_input(const char *path, size_t *len);

/* Reads and parses the spec at path ("-": stdin) into spec (always to be dp_spec_clear'ed), printing any
 * error to stderr. Returns dp_spec_parse's status (DP_EINVAL when the input cannot be read). */
int dp_cli_parse_spec(const char *path, dp_spec *spec);

/* Prints located errors to stderr as "dashpot: POINTER: message" lines. */
void dp_cli_print_errors(const char *what, const dp_errors *errs);

int dp_cli_simulate(int argc, char **argv);
int dp_cli_stability(int argc, char **argv);
int dp_cli_wellposedness(int argc, char **argv);
int dp_cli_convergence(int argc, char **argv);
int dp_cli_modes(int argc, char **argv);
int dp_cli_response(int argc, char **argv);
int dp_cli_lcp(int argc, char **argv);
int dp_cli_sweep(int argc, char **argv);

#endif
