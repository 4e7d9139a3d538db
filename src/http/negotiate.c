/* src/http/negotiate.c - picking a response format from the Accept header (RFC 9110 section 12.5.1).
 *
 * Each offer gets the quality of the most specific media range that matches it (type/subtype, then type
 * with a wildcard subtype, then the full wildcard); the offer with the highest quality wins, ties going to
 * the more specific match, then to the range the client listed first, then to the server's order. Quality 0
 * means "not acceptable". Malformed ranges are skipped rather than failing the request: a sloppy client
 * still gets the default.
 *
 * Two rules for the spellings clients actually send: application/ndjson (the ndjson.org spelling) is the
 * same offer as application/x-ndjson; and text/event-stream is matched only by its own name, never by the
 * range "text" with a wildcard subtype, because EventSource always asks for it by name while a client that
 * says text-anything wants text it can read: it gets text/csv where a route has it.
 */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "http.h"

typedef struct range {
    const char *type, *sub;    /* pointers into the header; lengths below */
    size_t tlen, slen;
    double q;
} range;

static int eq(const char *a, size_t alen, const char *b, size_t blen)
{
    return alen == blen && strncasecmp(a, b, alen) == 0;
}

static const char *skip_ws(const char *p, const char *end)
{
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    return p;
}

/* The q parameter of a media range's parameters [p, end); 1 when absent, -1 when malformed. */
static double quality(const char *p, const char *end)
{
    while (p < end) {
        const char *semi = memchr(p, ';', (size_t)(end - p));
        const char *stop = semi ? semi : end;
        p = skip_ws(p, stop);
        if (stop - p >= 2 && (p[0] == 'q' || p[0] == 'Q') && p[1] == '=') {
            char num[16] = { 0 }, *e;
            size_t n = (size_t)(stop - p - 2) < sizeof num - 1 ? (size_t)(stop - p - 2) : sizeof num - 1;
            memcpy(num, p + 2, n);
            double q = strtod(num, &e);
            while (*e == ' ' || *e == '\t')
                e++;
            return (*e || e == num || !(q >= 0 && q <= 1)) ? -1 : q;
        }
        p = semi ? semi + 1 : end;
    }
    return 1;
}

/* Parses one comma-separated element [p, end) into r; 0 if it is not a media range. */
static int parse_range(const char *p, const char *end, range *r)
{
    p = skip_ws(p, end);
    if (p >= end)
        return 0;
    const char *semi = memchr(p, ';', (size_t)(end - p)), *stop = semi ? semi : end;
    while (stop > p && (stop[-1] == ' ' || stop[-1] == '\t'))
        stop--;
    const char *slash = memchr(p, '/', (size_t)(stop - p));
    if (slash == NULL || slash == p || slash + 1 >= stop)
        return 0;
    r->type = p;
    r->tlen = (size_t)(slash - p);
    r->sub = slash + 1;
    r->slen = (size_t)(stop - slash - 1);
    r->q = semi ? quality(semi + 1, end) : 1;
    return r->q >= 0;
}

/* Other names of an offer, matched as if they were its own. */
static const char *alias(const char *offer)
{
    return strcmp(offer, "application/x-ndjson") == 0 ? "application/ndjson" : NULL;
}

/* How specifically r matches the offer "type/sub": 3 exact, 2 type/ *, 1 * / *, 0 no match. */
static int match(const range *r, const char *offer)
{
    const char *slash = strchr(offer, '/'), *other = alias(offer);
    size_t tlen = (size_t)(slash - offer);
    if (eq(r->type, r->tlen, "*", 1) && eq(r->sub, r->slen, "*", 1))
        return 1;
    if (other != NULL && eq(r->type, r->tlen, other, strchr(other, '/') - other)
        && eq(r->sub, r->slen, strchr(other, '/') + 1, strlen(strchr(other, '/') + 1)))
        return 3;
    if (!eq(r->type, r->tlen, offer, tlen))
        return 0;
    if (eq(r->sub, r->slen, "*", 1))
        return strcmp(offer, "text/event-stream") == 0 ? 0 : 2;
    return eq(r->sub, r->slen, slash + 1, strlen(slash + 1)) ? 3 : 0;
}

typedef struct score { double q; int spec, pos; } score;

/* The offer's quality from the most specific matching range; spec 0 when nothing matches. */
static score score_offer(const char *accept, const char *offer)
{
    score best = { 0, 0, 0 };
    const char *p = accept;
    for (int pos = 0; *p; pos++) {
        const char *comma = strchr(p, ','), *end = comma ? comma : p + strlen(p);
        range r;
        int m = parse_range(p, end, &r) ? match(&r, offer) : 0;
        if (m > best.spec)
            best = (score){ r.q, m, pos };
        p = comma ? comma + 1 : end;
    }
    return best;
}

static int better(score a, score b)
{
    if (a.q != b.q)
        return a.q > b.q;
    if (a.spec != b.spec)
        return a.spec > b.spec;
    return a.pos < b.pos;
}

int negotiate(const char *accept, const char *const *offers, int n)
{
    if (accept == NULL)
        return 0;
    const char *p = accept;
    while (isspace((unsigned char)*p))
        p++;
    if (*p == '\0')
        return 0;
    int best = -1;
    score bs = { 0, 0, 0 };
    for (int i = 0; i < n; i++) {
        score s = score_offer(accept, offers[i]);
        if (s.spec > 0 && s.q > 0 && (best < 0 || better(s, bs))) {
            best = i;
            bs = s;
        }
    }
    return best;
}
