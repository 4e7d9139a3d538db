/* src/http/config.c - dashpotd's settings: defaults, then DASHPOT_* environment variables, then flags.
 *
 * One table describes every option (flag, variable, kind, range, help), so --help, the environment and the
 * flags cannot drift apart. Numbers are parsed whole (no trailing garbage, no silent wrap-around) and
 * range-checked; a bad value stops the daemon before it binds anything.
 */
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "dashpot/json.h"
#include "http.h"

typedef enum kind { K_UINT, K_DOUBLE, K_SIZE, K_STRING } kind;

typedef struct option {
    const char *flag, *env;
    kind kind;
    size_t offset, size;   /* where in struct config; size for strings */
    double min, max;
    const char *help;
} option;

#define OPT(f, e, k, field, lo, hi, h) { f, e, k, offsetof(config, field), sizeof(((config *)0)->field), lo, hi, h }

static const option options[] = {
    OPT("port", "DASHPOT_PORT", K_UINT, port, 0, 65535, "TCP port (0: any free port, printed at start)"),
    OPT("bind", "DASHPOT_BIND", K_STRING, bind, 0, 0, "address to listen on (IPv4 or IPv6 literal)"),
    OPT("threads", "DASHPOT_THREADS", K_UINT, threads, 1, 1024,
        "computations at once: compute threads and solver slots (default: one per CPU)"),
    OPT("max-connections", "DASHPOT_MAX_CONNECTIONS", K_UINT, max_connections, 1, 100000,
        "connections served at once; more get 503"),
    OPT("max-steps", "DASHPOT_MAX_STEPS", K_DOUBLE, max_steps, 1, 1e9, "time steps one request may ask for"),
    OPT("max-map-points", "DASHPOT_MAX_MAP_POINTS", K_DOUBLE, max_map_points, 1, 4004001,
        "grid points one stability map may ask for"),
    OPT("max-wall", "DASHPOT_MAX_WALL", K_DOUBLE, max_wall, 0.001, 86400, "seconds one request may run"),
    OPT("timeout", "DASHPOT_TIMEOUT", K_UINT, timeout, 1, 86400,
        "seconds a connection may stay idle or take to send a request"),
    OPT("body-limit", "DASHPOT_BODY_LIMIT", K_SIZE, body_limit, 1, 1073741824.0,
        "bytes of a request body; larger gets 413"),
    OPT("shutdown-grace", "DASHPOT_SHUTDOWN_GRACE", K_DOUBLE, shutdown_grace, 0, 3600,
        "seconds runs in flight may take to finish after SIGTERM"),
    OPT("openapi", "DASHPOT_OPENAPI", K_STRING, openapi, 0, 0, "the OpenAPI document served at /openapi.yaml"),
    OPT("bench-static", "DASHPOT_BENCH_STATIC", K_STRING, bench_static, 0, 0,
        "benchmarks only: serve this file at GET /bench/static"),
    OPT("web-dir", "DASHPOT_WEB_DIR", K_STRING, web_dir, 0, 0, "the browser page's files, served at /"),
    OPT("token-file", "DASHPOT_TOKEN_FILE", K_STRING, token_file, 0, 0,
        "file whose first line is the bearer token /v1/ requires"),
};
enum { NOPTIONS = sizeof options / sizeof options[0] };

static void defaults(config *c)
{
    memset(c, 0, sizeof *c);
    c->port = 8080;
    snprintf(c->bind, sizeof c->bind, "127.0.0.1");
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    c->threads = ncpu > 0 && ncpu < 64 ? (unsigned)ncpu : 4;
    c->max_connections = 256;
    c->max_steps = 1e8;
    c->max_map_points = 40000;
    c->max_wall = 120;
    c->timeout = 30;
    c->body_limit = 1u << 20;
    c->shutdown_grace = 10;
    snprintf(c->openapi, sizeof c->openapi, DEFAULT_OPENAPI);
    snprintf(c->web_dir, sizeof c->web_dir, DEFAULT_WEB_DIR);
}

/* The value of an option's field as text (for --help). */
static void show(const config *c, const option *o, char *out, size_t cap)
{
    const char *field = (const char *)c + o->offset;
    switch (o->kind) {
    case K_UINT: snprintf(out, cap, "%u", *(const unsigned *)(const void *)field); break;
    case K_SIZE: snprintf(out, cap, "%zu", *(const size_t *)(const void *)field); break;
    case K_DOUBLE: snprintf(out, cap, "%g", *(const double *)(const void *)field); break;
    default: snprintf(out, cap, "%s", *field ? field : "(none)");
    }
}

static void help(void)
{
    config d;
    defaults(&d);
    printf("usage: dashpotd [--FLAG VALUE | --FLAG=VALUE]...\n\n"
           "The dashpot HTTP daemon: POST /v1/simulate, /v1/stability, /v1/wellposedness, /v1/convergence; GET /healthz,\n"
           "/readyz, /metrics, /openapi.yaml. Every flag can also be set by its environment variable; a flag wins.\n\n"
           "  %-17s %-25s %-17s %s\n", "flag", "variable", "default", "");
    for (int i = 0; i < NOPTIONS; i++) {
        char value[64];
        show(&d, &options[i], value, sizeof value);
        printf("  --%-15s %-25s %-17s %s\n", options[i].flag, options[i].env, value, options[i].help);
    }
    printf("  --%-15s %-25s %-17s %s\n  --%-15s %-25s %-17s %s\n", "help", "", "", "this text", "version", "", "",
           "the version");
    printf("\nA relative --openapi or --web-dir that does not exist from the working directory is looked for beside\n"
           "the binary, then in its parent directory; the defaults also in <binary's directory>/../share/dashpot/\n"
           "(%s, %s/), where make install puts them. The start-up log names the files served.\n",
           INSTALLED_OPENAPI, INSTALLED_WEB_DIR);
    printf("\nDASHPOT_TOKEN: the bearer token itself, when no --token-file is given (no flag: it would show in ps).\n"
           "With a token, /v1/ answers 401 without \"Authorization: Bearer TOKEN\"; the other routes stay open.\n");
    printf("\nSIGTERM, SIGINT or SIGHUP: stop accepting, let runs finish (--shutdown-grace), then exit 0.\n");
}

/* Parses and range-checks one value into its field. */
static int set(config *c, const option *o, const char *value, const char *from)
{
    char *field = (char *)c + o->offset, *end;
    if (o->kind == K_STRING) {
        if (strlen(value) >= o->size) {
            fprintf(stderr, "dashpotd: %s: value too long\n", from);
            return -1;
        }
        memcpy(field, value, strlen(value) + 1);
        return 0;
    }
    errno = 0;
    double v = strtod(value, &end);
    int integral = o->kind != K_DOUBLE;
    if (errno || end == value || *end != '\0' || !isfinite(v) || v < o->min || v > o->max ||
        (integral && v != floor(v))) {
        fprintf(stderr, "dashpotd: %s: expected %s in [%g, %g], got \"%s\"\n", from,
                integral ? "an integer" : "a number", o->min, o->max, value);
        return -1;
    }
    if (o->kind == K_UINT)
        *(unsigned *)(void *)field = (unsigned)v;
    else if (o->kind == K_SIZE)
        *(size_t *)(void *)field = (size_t)v;
    else
        *(double *)(void *)field = v;
    return 0;
}

static const option *find(const char *name, size_t len)
{
    for (int i = 0; i < NOPTIONS; i++)
        if (strlen(options[i].flag) == len && strncmp(options[i].flag, name, len) == 0)
            return &options[i];
    return NULL;
}

static int from_env(config *c)
{
    for (int i = 0; i < NOPTIONS; i++) {
        const char *v = getenv(options[i].env);
        if (v && *v && set(c, &options[i], v, options[i].env) != 0)
            return -1;
    }
    return 0;
}

static int exists(const char *path, int want_dir)
{
    struct stat st;
    return stat(path, &st) == 0 && (want_dir ? S_ISDIR(st.st_mode) : S_ISREG(st.st_mode));
}

int data_path(const char *given, const char *installed, int want_dir, char *out, size_t cap)
{
    char exe[4096];
    snprintf(out, cap, "%s", given);
    if (exists(given, want_dir))
        return 0;
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (given[0] == '/' || n <= 0)
        return -1;
    exe[n] = '\0';
    *strrchr(exe, '/') = '\0'; /* the kernel gives an absolute path */
    const char *const forms[] = { "%s/%s", "%s/../%s", "%s/../share/dashpot/%s" };
    for (int i = 0; i < 3; i++) {
        const char *name = i < 2 ? given : installed;
        if (name == NULL || snprintf(out, cap, forms[i], exe, name) >= (int)cap)
            continue;
        if (exists(out, want_dir))
            return 0;
    }
    snprintf(out, cap, "%s", given);
    return -1;
}

int config_load(config *c, int argc, char **argv)
{
    defaults(c);
    if (from_env(c) != 0)
        return -1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            help();
            return 1;
        }
        if (strcmp(a, "--version") == 0) {
            printf("dashpotd %s\n", DP_VERSION);
            return 1;
        }
        const char *eq = strchr(a, '=');
        const option *o = strncmp(a, "--", 2) == 0 ? find(a + 2, eq ? (size_t)(eq - a - 2) : strlen(a + 2)) : NULL;
        if (o == NULL || (!eq && i + 1 >= argc)) {
            fprintf(stderr, "dashpotd: %s: unknown flag or missing value (see --help)\n", a);
            return -1;
        }
        if (set(c, o, eq ? eq + 1 : argv[++i], a) != 0)
            return -1;
    }
    return 0;
}
