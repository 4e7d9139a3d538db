/* src/http/auth.c - the optional bearer token (RFC 6750) that the /v1/ routes require when one is set.
 *
 * The token comes from --token-file (DASHPOT_TOKEN_FILE: its first line) or, failing that, from the
 * environment variable DASHPOT_TOKEN; there is deliberately no --token flag, which would show the secret
 * in `ps`. Health, readiness, metrics, the OpenAPI document and the page stay open, so that probes and
 * scrapers need no secret. A request without the token is answered 401 before its body is read.
 *
 * The comparison runs over the whole configured token whatever the presented one holds, so its time
 * says nothing about how many leading bytes were right.
 */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "http.h"

/* RFC 6750 section 2.1: b64token = 1*( ALPHA / DIGIT / "-" / "." / "_" / "~" / "+" / "/" ) *"=" */
static int b64token(const char *t)
{
    size_t n = strspn(t, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-._~+/");
    if (n == 0)
        return 0;
    n += strspn(t + n, "=");
    return t[n] == '\0';
}

/* The first line of a file, without its line break, into out (cap bytes); 0 or -1. */
static int first_line(const char *path, char *out, size_t cap)
{
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return -1;
    int ok = fgets(out, (int)cap, f) != NULL;
    fclose(f);
    if (!ok)
        return -1;
    size_t n = strcspn(out, "\r\n");
    if (out[n] == '\0' && n + 1 >= cap)
        return -1; /* longer than cap: refuse rather than cut the secret */
    out[n] = '\0';
    return 0;
}

int auth_load(config *c)
{
    const char *env = getenv("DASHPOT_TOKEN");
    c->token[0] = '\0';
    if (c->token_file[0]) {
        if (first_line(c->token_file, c->token, sizeof c->token) != 0) {
            fprintf(stderr, "dashpotd: --token-file %s: cannot read a token line (at most %zu bytes)\n",
                    c->token_file, sizeof c->token - 1);
            return -1;
        }
    } else if (env && *env) {
        if (strlen(env) >= sizeof c->token) {
            fprintf(stderr, "dashpotd: DASHPOT_TOKEN: longer than %zu bytes\n", sizeof c->token - 1);
            return -1;
        }
        memcpy(c->token, env, strlen(env) + 1);
    } else {
        return 0;
    }
    if (!b64token(c->token)) {
        fprintf(stderr, "dashpotd: the token must be 1 or more of A-Z a-z 0-9 - . _ ~ + / (then = only), "
                        "as RFC 6750 allows\n");
        c->token[0] = '\0';
        return -1;
    }
    return 0;
}

/* Equal in time that depends on the length of `want` only. */
static int same(const char *got, size_t glen, const char *want, size_t wlen)
{
    volatile unsigned char d = glen != wlen;
    for (size_t i = 0; i < wlen; i++)
        d |= (unsigned char)(want[i] ^ (i < glen ? got[i] : 0));
    return d == 0;
}

int auth_ok(const server *s, struct MHD_Connection *c, const char *url)
{
    const char *want = s->cfg.token;
    if (want[0] == '\0' || strncmp(url, "/v1/", 4) != 0)
        return 1;
    const char *h = MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_AUTHORIZATION);
    if (h == NULL || strncasecmp(h, "Bearer ", 7) != 0)
        return 0;
    h += 7;
    while (*h == ' ')
        h++;
    size_t n = strlen(h);
    while (n > 0 && (h[n - 1] == ' ' || h[n - 1] == '\t'))
        n--;
    return same(h, n, want, strlen(want));
}
