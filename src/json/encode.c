/* src/json/encode.c - runs as JSON, NDJSON, SSE or CSV (encode.h): the shapes of the wire contract.
 *
 *   NDJSON  {"type":"meta",...}\n  {"type":"sample","t":..,"x":..,"v":..,"Fs":..,"Fd":..,"Fc":..,"phase":..}\n
 *           {"type":"event","kind":"stick"|"slip","t":..,"x":..,"v":..}\n  ...  {"type":"summary",...}\n
 *           or, on failure, a last {"type":"error","status":..,"title":..,"detail":..}\n
 *   SSE     the same objects, each as "event: <type>\ndata: <object>\n\n"
 *   JSON    {"meta":{..},\n"samples":[\n{..},\n{..}\n],\n"events":[..],\n"summary":{..}}\n  (one sample a line)
 *   CSV     t,x,v,Fs,Fd,Fc,phase\n then one row per sample; a failure adds "# error: <status> <detail>".
 *
 * Samples are the hot path (millions a second): they are written with pointer arithmetic into one
 * reservation, numbers by dp_format_double, never through printf.
 */
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dashpot/encode.h"
#include "dtoa.h"

/* Bytes one sample may take in any format: 6 numbers of at most 25 characters, the keys, the phase and the
 * SSE framing come to ~260; the last number may scribble DP_DECIMAL_MAX bytes: 384 covers both. */
#define SAMPLE_MAX 384

static inline char *put_lit(char *p, const char *lit, size_t n)
{
    memcpy(p, lit, n);
    return p + n;
}

/* Appends a string literal at p (evaluated once), returns the end. */
#define PUT(p, lit) put_lit((p), (lit), sizeof(lit) - 1)

static const char *phase_name(dp_phase ph)
{
    return ph == DP_PHASE_STICK ? "stick" : ph == DP_PHASE_SLIP ? "slip" : NULL;
}

static char *put_num(char *p, double x)
{
    dp_decimal d;
    return dp_decimal_write(p, x, &d); /* may scribble DP_DECIMAL_MAX bytes: within SAMPLE_MAX */
}

/* What precedes each of a sample's six numbers, padded to 8 bytes so that it is copied in one store. */
typedef struct sample_keys {
    char text[6][8];
    unsigned char len[6];
} sample_keys;

static const sample_keys json_keys = { { "\"t\":", ",\"x\":", ",\"v\":", ",\"Fs\":", ",\"Fd\":", ",\"Fc\":" },
                                       { 4, 5, 5, 6, 6, 6 } };
static const sample_keys csv_keys = { { "", ",", ",", ",", ",", "," }, { 0, 1, 1, 1, 1, 1 } };

static uint64_t bits_of(double x)
{
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    return b;
}

/* Sets a recent-numbers cache to "nothing written yet": NaN bits, which no sample has. */
static void forget_numbers(dp_number_text recent[6])
{
    for (int i = 0; i < 6; i++) {
        recent[i].bits = bits_of(NAN);
        dp_decimal_of(&recent[i].decimal, NAN);
    }
}

/* Number i of a sample after its key. A number with the same bits as a recent one is laid out again from
 * that one's digits instead of converted (~5x cheaper): the same member of the previous sample (a force
 * constant while slipping or sticking) or one of the two members before it in this sample (F_s = x when
 * k = 1, F_c = F_d without relaxation). recent[i] holds the previous sample's number i until it is replaced
 * by this one's. Inlined with constant i: the tests of i vanish. */
static inline __attribute__((always_inline)) char *put_number(dp_number_text *recent, int i, char *p, double x,
                                                              const sample_keys *k)
{
    memcpy(p, k->text[i], 8);
    p += k->len[i];
    uint64_t bits = bits_of(x);
    dp_number_text *r = &recent[i];
    if (bits == r->bits)
        return dp_decimal_put(p, &r->decimal);
    const dp_number_text *same = i >= 1 && r[-1].bits == bits ? r - 1 : i >= 2 && r[-2].bits == bits ? r - 2 : NULL;
    r->bits = bits;
    if (same == NULL)
        return dp_decimal_write(p, x, &r->decimal);
    r->decimal = same->decimal;
    return dp_decimal_put(p, &r->decimal);
}

/* The six numbers of a sample, each after its key. */
static char *put_numbers(dp_number_text *recent, char *p, const dp_sample *s, const sample_keys *k)
{
    p = put_number(recent, 0, p, s->t, k);
    p = put_number(recent, 1, p, s->x, k);
    p = put_number(recent, 2, p, s->v, k);
    p = put_number(recent, 3, p, s->Fs, k);
    p = put_number(recent, 4, p, s->Fd, k);
    return put_number(recent, 5, p, s->Fc, k);
}

/* "t":..,"x":..,"v":..,"Fs":..,"Fd":..,"Fc":..[,"phase":".."] */
static char *put_sample_members(dp_number_text *recent, char *p, const dp_sample *s)
{
    p = put_numbers(recent, p, s, &json_keys);
    if (s->plastic)
        p = put_num(PUT(p, ",\"p\":"), s->p);
    if (s->phase == DP_PHASE_STICK)
        p = PUT(p, ",\"phase\":\"stick\"");
    else if (s->phase == DP_PHASE_SLIP)
        p = PUT(p, ",\"phase\":\"slip\"");
    return p;
}

/* A linear complementarity system's mode change: "kind":"on"|"off","component":i,"t":..,"mode":k,"u":..,"w":.. */
static char *put_mode_change(char *p, const dp_event *ev)
{
    char num[48];
    int len = snprintf(num, sizeof num, "\",\"component\":%zu", ev->element);
    p = ev->kind == DP_EVENT_ON ? PUT(p, "\"kind\":\"on") : PUT(p, "\"kind\":\"off");
    p = put_lit(p, num, (size_t)len);
    p = put_num(PUT(p, ",\"t\":"), ev->t);
    len = snprintf(num, sizeof num, ",\"mode\":%zu", ev->mode);
    p = put_lit(p, num, (size_t)len);
    p = put_num(PUT(p, ",\"u\":"), ev->x);
    return put_num(PUT(p, ",\"w\":"), ev->v);
}

static char *put_event_members(char *p, const dp_event *ev, int network)
{
    if (ev->kind == DP_EVENT_ON || ev->kind == DP_EVENT_OFF)
        return put_mode_change(p, ev);
    p = ev->kind == DP_EVENT_STICK ? PUT(p, "\"kind\":\"stick\"") : ev->kind == DP_EVENT_SLIP ? PUT(p, "\"kind\":\"slip\"")
      : ev->kind == DP_EVENT_YIELD ? PUT(p, "\"kind\":\"yield\"") : ev->kind == DP_EVENT_IMPACT ? PUT(p, "\"kind\":\"impact\"")
      : ev->kind == DP_EVENT_LIFTOFF ? PUT(p, "\"kind\":\"liftoff\"") : ev->kind == DP_EVENT_TOUCH ? PUT(p, "\"kind\":\"touch\"")
      : ev->kind == DP_EVENT_SEPARATE ? PUT(p, "\"kind\":\"separate\"") : PUT(p, "\"kind\":\"unload\"");
    if (network) {   /* the element, when, and its elongation u and rate du at that instant */
        char num[24];
        int len = snprintf(num, sizeof num, "%zu", ev->element);
        p = put_lit(PUT(p, ",\"element\":"), num, (size_t)len);
        p = put_num(PUT(p, ",\"t\":"), ev->t);
        p = put_num(PUT(p, ",\"u\":"), ev->x);
        p = put_num(PUT(p, ",\"du\":"), ev->v);
        if (ev->kind != DP_EVENT_IMPACT)
            return p;
        /* an impact: the rate just after and the impulse that made the jump */
        p = put_num(PUT(p, ",\"du_after\":"), ev->v_after);
        return put_num(PUT(p, ",\"impulse\":"), ev->impulse);
    }
    p = put_num(PUT(p, ",\"t\":"), ev->t);
    p = put_num(PUT(p, ",\"x\":"), ev->x);
    return put_num(PUT(p, ",\"v\":"), ev->v);
}

static char *put_csv_row(dp_number_text *recent, char *p, const dp_sample *s)
{
    p = put_numbers(recent, p, s, &csv_keys);
    *p++ = ',';
    const char *ph = phase_name(s->phase);
    if (ph) {
        size_t n = strlen(ph);
        memcpy(p, ph, n);
        p += n;
    }
    if (s->plastic)
        p = put_num(PUT(p, ","), s->p);
    *p++ = '\n';
    return p;
}

/* Wraps members written by `put` as a line object of the streaming formats, or as a JSON array element. */
static char *put_object(const dp_encoder *e, char *p, const char *type, size_t tlen)
{
    if (e->format == DP_FORMAT_SSE) {
        p = PUT(p, "event: ");
        memcpy(p, type, tlen);
        p = PUT(p + tlen, "\ndata: ");
    }
    p = PUT(p, "{\"type\":\"");
    memcpy(p, type, tlen);
    return PUT(p + tlen, "\",");
}

static char *put_close(const dp_encoder *e, char *p)
{
    return e->format == DP_FORMAT_SSE ? PUT(p, "}\n\n") : PUT(p, "}\n");
}

/* b has room for `extra` more bytes, the test inlined (every record makes it). */
static inline int room(dp_buf *b, size_t extra)
{
    return b->cap - b->len > extra ? DP_OK : dp_buf_reserve(b, extra);
}

static int encode_sample(dp_encoder *e, dp_buf *b, const dp_sample *s)
{
    if (room(b, SAMPLE_MAX) != DP_OK)
        return DP_ENOMEM;
    char *p = b->data + b->len;
    switch (e->format) {
    case DP_FORMAT_CSV:
        if (e->csv_header_due) {   /* the one-mass header, with p when the spring is elastoplastic */
            p = s->plastic ? PUT(p, "t,x,v,Fs,Fd,Fc,phase,p\n") : PUT(p, "t,x,v,Fs,Fd,Fc,phase\n");
            e->csv_header_due = 0;
        }
        p = put_csv_row(e->recent, p, s);
        break;
    case DP_FORMAT_JSON:
        p = e->nsamples_written ? PUT(p, ",\n{") : PUT(p, "\n{");
        p = PUT(put_sample_members(e->recent, p, s), "}");
        break;
    case DP_FORMAT_SSE:
        p = PUT(p, "event: sample\ndata: {\"type\":\"sample\",");
        p = PUT(put_sample_members(e->recent, p, s), "}\n\n");
        break;
    default:
        p = PUT(put_sample_members(e->recent, PUT(p, "{\"type\":\"sample\","), s), "}\n");
    }
    e->nsamples_written = 1;
    b->len = (size_t)(p - b->data);
    b->data[b->len] = '\0';
    return DP_OK;
}

/* JSON holds events until the samples array closes; past DP_ENCODER_MAX_EVENTS they are only counted. */
static int hold_event(dp_encoder *e, const dp_event *ev)
{
    if (e->nevents == e->events_cap) {
        if (e->events_cap >= DP_ENCODER_MAX_EVENTS) {
            e->events_dropped++;
            return DP_OK;
        }
        size_t cap = e->events_cap ? 2 * e->events_cap : 64;
        if (cap > DP_ENCODER_MAX_EVENTS)
            cap = DP_ENCODER_MAX_EVENTS;
        dp_event *ne = realloc(e->events, cap * sizeof *ne);
        if (ne == NULL)
            return DP_ENOMEM;
        e->events = ne;
        e->events_cap = cap;
    }
    e->events[e->nevents++] = *ev;
    return DP_OK;
}

static int encode_event(dp_encoder *e, dp_buf *b, const dp_event *ev)
{
    if (e->format == DP_FORMAT_CSV)
        return DP_OK;
    if (e->format == DP_FORMAT_JSON)
        return hold_event(e, ev);
    if (dp_buf_reserve(b, SAMPLE_MAX) != DP_OK)
        return DP_ENOMEM;
    char *p = put_close(e, put_event_members(put_object(e, b->data + b->len, "event", 5), ev, e->cols != NULL));
    b->len = (size_t)(p - b->data);
    b->data[b->len] = '\0';
    return DP_OK;
}

/* ---- quakes: the slip-event catalogue of a network run (docs/quakes.md) ------------------------------- */

static char *put_size(char *p, const char *key, size_t klen, size_t n)
{
    char num[24];
    int len = snprintf(num, sizeof num, "%zu", n);
    return put_lit(put_lit(p, key, klen), num, (size_t)len);
}

/* "t":..,"duration":..,"size":..,"hypocentre":..,"first":..,"last":..,"moment":..,"magnitude":..,
 * "peak_rate":..,"open":..; the magnitude ln(moment) is null for a quake that did not move (moment 0). */
static char *put_quake_members(char *p, const dp_quake *q)
{
    p = put_num(PUT(p, "\"t\":"), q->t);
    p = put_num(PUT(p, ",\"duration\":"), q->duration);
    p = put_size(p, ",\"size\":", 8, q->size);
    p = put_size(p, ",\"hypocentre\":", 14, q->hypocentre);
    p = put_size(p, ",\"first\":", 9, q->first);
    p = put_size(p, ",\"last\":", 8, q->last);
    p = put_num(PUT(p, ",\"moment\":"), q->moment);
    p = q->moment > 0 ? put_num(PUT(p, ",\"magnitude\":"), log(q->moment)) : PUT(p, ",\"magnitude\":null");
    p = put_num(PUT(p, ",\"peak_rate\":"), q->peak_rate);
    return q->open ? PUT(p, ",\"open\":true") : PUT(p, ",\"open\":false");
}

/* JSON holds quakes, as events, until the samples array closes; past DP_ENCODER_MAX_EVENTS only counted. */
static int hold_quake(dp_encoder *e, const dp_quake *q)
{
    if (e->nquakes == e->quakes_cap) {
        if (e->quakes_cap >= DP_ENCODER_MAX_EVENTS) {
            e->quakes_dropped++;
            return DP_OK;
        }
        size_t cap = e->quakes_cap ? 2 * e->quakes_cap : 64;
        if (cap > DP_ENCODER_MAX_EVENTS)
            cap = DP_ENCODER_MAX_EVENTS;
        dp_quake *nq = realloc(e->quakes, cap * sizeof *nq);
        if (nq == NULL)
            return DP_ENOMEM;
        e->quakes = nq;
        e->quakes_cap = cap;
    }
    e->quakes[e->nquakes++] = *q;
    return DP_OK;
}

static int encode_quake(dp_encoder *e, dp_buf *b, const dp_quake *q)
{
    if (e->format == DP_FORMAT_CSV)
        return DP_OK;
    if (e->format == DP_FORMAT_JSON)
        return hold_quake(e, q);
    if (dp_buf_reserve(b, SAMPLE_MAX) != DP_OK)
        return DP_ENOMEM;
    char *p = put_close(e, put_quake_members(put_object(e, b->data + b->len, "quake", 5), q));
    b->len = (size_t)(p - b->data);
    b->data[b->len] = '\0';
    return DP_OK;
}

/* JSON: the held quakes as a "quakes" member after the events, written only when a run made some. */
static int close_quakes(dp_encoder *e, dp_buf *b)
{
    if (e->nquakes == 0 && e->quakes_dropped == 0)
        return DP_OK;
    int s = dp_buf_append(b, "\"quakes\":[", 10);
    for (size_t i = 0; i < e->nquakes && s == DP_OK; i++) {
        if ((s = dp_buf_reserve(b, SAMPLE_MAX)) != DP_OK)
            break;
        char *p = b->data + b->len;
        p = i ? PUT(p, ",\n{") : PUT(p, "\n{");
        p = PUT(put_quake_members(p, &e->quakes[i]), "}");
        b->len = (size_t)(p - b->data);
        b->data[b->len] = '\0';
    }
    return s ? s : e->nquakes ? dp_buf_append(b, "\n],\n", 4) : dp_buf_append(b, "],\n", 3);
}

/* ---- rows: named groups of numbers over the run's columns (dp_columns, docs/systems.md §1) ---------- */

/* Bytes a row may take: every number at most 25 characters plus a separator, a phase word, the keys and
 * framing, and DP_DECIMAL_MAX of scribble room after the last number. */
static size_t row_bytes(const dp_columns *c)
{
    size_t keys = 0;
    for (size_t g = 0; g < c->ngroups; g++)
        keys += strlen(c->group[g].name) + 8;
    return 32 * (c->width + 1) + keys + 128;
}

static char *put_phase(char *p, double code, int csv)
{
    const char *name = phase_name((dp_phase)(int)code);
    if (name == NULL)
        return csv ? p : PUT(p, "null");
    if (!csv)
        *p++ = '"';
    p = put_lit(p, name, strlen(name));
    if (!csv)
        *p++ = '"';
    return p;
}

/* "t":..,"<group>":[..],... (CSV: the same values, comma-separated). */
static char *put_row_members(const dp_columns *c, char *p, const dp_row *r, int csv)
{
    p = put_num(csv ? p : PUT(p, "\"t\":"), r->t);
    const double *v = r->val;
    for (size_t g = 0; g < c->ngroups; g++) {
        const dp_column_group *grp = &c->group[g];
        if (!csv) {
            p = PUT(p, ",\"");
            p = put_lit(p, grp->name, strlen(grp->name));
            p = PUT(p, "\":[");
        }
        for (size_t i = 0; i < grp->n; i++, v++) {
            if (i || csv)
                *p++ = ',';
            p = grp->phase ? put_phase(p, *v, csv) : put_num(p, *v);
        }
        if (!csv)
            *p++ = ']';
    }
    return p;
}

static int encode_row(dp_encoder *e, dp_buf *b, const dp_row *r)
{
    if (e->cols == NULL)
        return DP_EINVAL;
    if (room(b, row_bytes(e->cols)) != DP_OK)
        return DP_ENOMEM;
    char *p = b->data + b->len;
    switch (e->format) {
    case DP_FORMAT_CSV:
        p = put_row_members(e->cols, p, r, 1);
        *p++ = '\n';
        break;
    case DP_FORMAT_JSON:
        p = e->nsamples_written ? PUT(p, ",\n{") : PUT(p, "\n{");
        p = PUT(put_row_members(e->cols, p, r, 0), "}");
        break;
    default:
        p = put_object(e, p, "sample", 6);
        p = put_close(e, put_row_members(e->cols, p, r, 0));
    }
    e->nsamples_written = 1;
    b->len = (size_t)(p - b->data);
    b->data[b->len] = '\0';
    return DP_OK;
}

/* The CSV header of a run with columns: t, then <group><index> for every entry of every group. */
static int csv_row_header(dp_buf *b, const dp_columns *c)
{
    int s = dp_buf_append(b, "t", 1);
    char cell[64];
    for (size_t g = 0; g < c->ngroups && s == DP_OK; g++)
        for (size_t i = 0; i < c->group[g].n && s == DP_OK; i++) {
            size_t idx = c->group[g].index ? c->group[g].index[i] : i;
            int len = snprintf(cell, sizeof cell, ",%s%zu", c->group[g].name, idx);
            s = dp_buf_append(b, cell, (size_t)len);
        }
    return s ? s : dp_buf_append(b, "\n", 1);
}

int dp_encoder_record(dp_encoder *e, dp_buf *b, const dp_record *r)
{
    if (r->type == DP_RECORD_ROW)
        return encode_row(e, b, &r->u.row);
    if (r->type == DP_RECORD_SAMPLE)
        return encode_sample(e, b, &r->u.sample);
    if (r->type == DP_RECORD_EVENT)
        return encode_event(e, b, &r->u.event);
    if (r->type == DP_RECORD_QUAKE)
        return encode_quake(e, b, &r->u.quake);
    return DP_OK;
}

/* ---- framing: the opening, the closing summary, the error; not hot, so plain appends ---- */

static int put_str(dp_buf *b, const char *s)
{
    return dp_buf_append(b, s, strlen(s));
}

static int put_double(dp_buf *b, double x)
{
    char t[32];
    return dp_buf_append(b, t, dp_format_double(t, x));
}

static int put_ull(dp_buf *b, unsigned long long n)
{
    char t[24];
    int len = snprintf(t, sizeof t, "%llu", n);
    return dp_buf_append(b, t, (size_t)len);
}

/* The caller's meta object with "type":"meta" as its first member (line formats) or without it (JSON, where
 * the member name already says it). A missing or non-object meta counts as {}. */
static int put_meta(dp_buf *b, const char *meta, int with_type)
{
    static const char type_member[] = "\"type\":\"meta\"";
    const char *body = "}";
    if (meta) {
        meta += strspn(meta, " \t\r\n");
        if (*meta == '{')
            body = meta + 1 + strspn(meta + 1, " \t\r\n");
    }
    int has_type = strncmp(body, type_member, sizeof type_member - 1) == 0;
    if (has_type) {
        body += sizeof type_member - 1;
        body += strspn(body, " \t\r\n");
        body += *body == ',';
        body += strspn(body, " \t\r\n");
    }
    size_t n = strlen(body);
    while (n > 0 && strchr(" \t\r\n", body[n - 1]))
        n--;
    int empty = n <= 1; /* just the closing brace */
    int s = put_str(b, with_type ? (empty ? "{\"type\":\"meta\"" : "{\"type\":\"meta\",") : "{");
    return s ? s : dp_buf_append(b, body, n);
}

void dp_encoder_init(dp_encoder *e, dp_format f)
{
    memset(e, 0, sizeof *e);
    e->format = f;
    forget_numbers(e->recent);
}

void dp_encoder_set_columns(dp_encoder *e, const dp_columns *cols)
{
    e->cols = cols;
}

void dp_encoder_clear(dp_encoder *e)
{
    if (e == NULL)
        return;
    free(e->events);
    e->events = NULL;
    e->nevents = e->events_cap = 0;
    free(e->quakes);
    e->quakes = NULL;
    e->nquakes = e->quakes_cap = 0;
}

int dp_encoder_begin(dp_encoder *e, dp_buf *b, const char *meta_json)
{
    switch (e->format) {
    case DP_FORMAT_CSV:
        if (e->cols)
            return csv_row_header(b, e->cols);
        e->csv_header_due = 1;    /* written with the first sample, which says whether p is a column */
        return DP_OK;
    case DP_FORMAT_JSON: {
        int s = put_str(b, "{\"meta\":");
        s = s ? s : put_meta(b, meta_json, 0);
        return s ? s : put_str(b, ",\n\"samples\":[");
    }
    case DP_FORMAT_SSE: {
        int s = put_str(b, "event: meta\ndata: ");
        s = s ? s : put_meta(b, meta_json, 1);
        return s ? s : put_str(b, "\n\n");
    }
    default: {
        int s = put_meta(b, meta_json, 1);
        return s ? s : put_str(b, "\n");
    }
    }
}

/* JSON: closes the samples array and writes the held events (and quakes). */
static int close_samples(dp_encoder *e, dp_buf *b)
{
    int s = put_str(b, e->nsamples_written ? "\n],\n\"events\":[" : "],\n\"events\":[");
    for (size_t i = 0; i < e->nevents && s == DP_OK; i++) {
        if ((s = dp_buf_reserve(b, SAMPLE_MAX)) != DP_OK)
            break;
        char *p = b->data + b->len;
        p = i ? PUT(p, ",\n{") : PUT(p, "\n{");
        p = PUT(put_event_members(p, &e->events[i], e->cols != NULL), "}");
        b->len = (size_t)(p - b->data);
        b->data[b->len] = '\0';
    }
    s = s ? s : put_str(b, e->nevents ? "\n],\n" : "],\n");
    return s ? s : close_quakes(e, b);
}

static int summary_members(const dp_encoder *e, dp_buf *b, const dp_summary *sm)
{
    int s = dp_buf_reserve(b, e->cols ? row_bytes(e->cols) : SAMPLE_MAX);
    if (s)
        return s;
    dp_number_text none[6];
    forget_numbers(none);
    char *p = PUT(b->data + b->len, "\"final\":{");
    p = e->cols ? put_row_members(e->cols, p, &sm->final_row, 0) : put_sample_members(none, p, &sm->final);
    b->len = (size_t)(PUT(p, "},\"steps\":") - b->data);
    s = put_ull(b, sm->steps);
    s = s ? s : put_str(b, ",\"samples\":");
    s = s ? s : put_ull(b, sm->samples);
    s = s ? s : put_str(b, ",\"events\":");
    s = s ? s : put_ull(b, sm->events);
    s = s ? s : put_str(b, ",\"stick_time\":");
    s = s ? s : put_double(b, sm->stick_time);
    s = s ? s : put_str(b, ",\"iterations\":");
    s = s ? s : put_ull(b, sm->iterations);
    s = s ? s : put_str(b, ",\"rejected\":");
    s = s ? s : put_ull(b, sm->rejected);
    s = s ? s : put_str(b, ",\"fevals\":");
    return s ? s : put_ull(b, sm->fevals);
}

/* A CSV document that had no sample still opens with its header. */
static int csv_header_if_due(dp_encoder *e, dp_buf *b)
{
    if (!e->csv_header_due)
        return DP_OK;
    e->csv_header_due = 0;
    return put_str(b, "t,x,v,Fs,Fd,Fc,phase\n");
}

int dp_encoder_end(dp_encoder *e, dp_buf *b, const dp_summary *sm, const char *extra_json)
{
    if (e->format == DP_FORMAT_CSV)
        return csv_header_if_due(e, b);
    int s = DP_OK;
    if (e->format == DP_FORMAT_JSON) {
        s = close_samples(e, b);
        s = s ? s : put_str(b, "\"summary\":{");
    } else {
        s = dp_buf_reserve(b, 64);
        if (s == DP_OK)
            b->len = (size_t)(put_object(e, b->data + b->len, "summary", 7) - b->data);
    }
    s = s ? s : summary_members(e, b, sm);
    if (e->format == DP_FORMAT_JSON) {
        s = s ? s : put_str(b, ",\"events_dropped\":");
        s = s ? s : put_ull(b, e->events_dropped);
        if (e->quakes_dropped) {
            s = s ? s : put_str(b, ",\"quakes_dropped\":");
            s = s ? s : put_ull(b, e->quakes_dropped);
        }
    }
    if (extra_json && *extra_json) {
        s = s ? s : put_str(b, ",");
        s = s ? s : put_str(b, extra_json);
    }
    return s ? s : put_str(b, e->format == DP_FORMAT_JSON ? "}}\n" : e->format == DP_FORMAT_SSE ? "}\n\n" : "}\n");
}

/* "status":..,"title":..,"detail":.. */
static int error_members(dp_buf *b, int status, const char *message)
{
    int s = put_str(b, "\"status\":");
    s = s ? s : put_ull(b, (unsigned long long)dp_status_http(status));
    s = s ? s : put_str(b, ",\"title\":");
    s = s ? s : dp_json_quote(b, status < 0 ? dp_strerror(status) : "error");
    s = s ? s : put_str(b, ",\"detail\":");
    return s ? s : dp_json_quote(b, message ? message : "");
}

/* CSV has no place for an object: a comment line, with the message's line breaks flattened. */
static int csv_error(dp_buf *b, int status, const char *message)
{
    char line[DP_MESSAGE_MAX + 64];
    int n = snprintf(line, sizeof line, "# error: %d %s\n", dp_status_http(status), message ? message : "");
    if (n < 0)
        return DP_ENOMEM;
    size_t len = (size_t)n < sizeof line ? (size_t)n : sizeof line - 1;
    for (size_t i = 0; i + 1 < len; i++)
        if ((unsigned char)line[i] < 0x20)
            line[i] = ' ';
    line[len - 1] = '\n';
    return dp_buf_append(b, line, len);
}

int dp_encoder_fail(dp_encoder *e, dp_buf *b, int status, const char *message)
{
    int s;
    switch (e->format) {
    case DP_FORMAT_CSV:
        s = csv_header_if_due(e, b);
        return s ? s : csv_error(b, status, message);
    case DP_FORMAT_JSON:
        s = close_samples(e, b);
        s = s ? s : put_str(b, "\"error\":{");
        s = s ? s : error_members(b, status, message);
        return s ? s : put_str(b, "}}\n");
    default:
        s = dp_buf_reserve(b, 64);
        if (s == DP_OK)
            b->len = (size_t)(put_object(e, b->data + b->len, "error", 5) - b->data);
        s = s ? s : error_members(b, status, message);
        return s ? s : put_str(b, e->format == DP_FORMAT_SSE ? "}\n\n" : "}\n");
    }
}

int dp_format_from_name(const char *name)
{
    static const char *const names[] = { "json", "ndjson", "sse", "csv" };
    for (int i = 0; name && i < 4; i++)
        if (strcmp(name, names[i]) == 0)
            return i;
    return -1;
}

const char *dp_format_content_type(dp_format f)
{
    switch (f) {
    case DP_FORMAT_NDJSON: return "application/x-ndjson";
    case DP_FORMAT_SSE: return "text/event-stream";
    case DP_FORMAT_CSV: return "text/csv; charset=utf-8";
    default: return "application/json";
    }
}

int dp_status_http(int status)
{
    if (status >= 100 && status <= 599)
        return status;
    switch (status) {
    case DP_ESYNTAX: return 400;
    case DP_EINVAL: case DP_ELIMIT: case DP_ESOLVE: case DP_ENONFINITE: return 422;
    case DP_ENOMEM: case DP_ECANCEL: return 503;
    default: return 422;
    }
}
