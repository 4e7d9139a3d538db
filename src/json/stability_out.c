/* src/json/stability_out.c - the sticky-error text writer of the stability encoders (stability_out.h), a
 * thin layer over dp_buf (buf.c) so that an encoder writes straight through and checks once at the end.
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "stability_out.h"

void stab_putn(stab_out *o, const char *s, size_t n)
{
    if (!o->failed && dp_buf_append(o->b, s, n) != DP_OK)
        o->failed = 1;
}

void stab_int(stab_out *o, int v)
{
    char t[16], *p = t + sizeof t;
    unsigned u = v < 0 ? 0u - (unsigned)v : (unsigned)v;
    do
        *--p = (char)('0' + u % 10);
    while ((u /= 10) != 0);
    if (v < 0)
        *--p = '-';
    stab_putn(o, p, (size_t)(t + sizeof t - p));
}

void stab_printf(stab_out *o, const char *fmt, ...)
{
    char small[256];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(small, sizeof small, fmt, ap);
    va_end(ap);
    if (n < 0 || o->failed) {
        o->failed = 1;
        return;
    }
    if ((size_t)n < sizeof small) {
        stab_putn(o, small, (size_t)n);
        return;
    }
    if (dp_buf_reserve(o->b, (size_t)n) != DP_OK) {
        o->failed = 1;
        return;
    }
    va_start(ap, fmt);
    vsnprintf(o->b->data + o->b->len, (size_t)n + 1, fmt, ap);
    va_end(ap);
    o->b->len += (size_t)n;
}

void stab_num(stab_out *o, double x)
{
    char t[40];
    stab_putn(o, t, dp_format_double(t, x));
}

void stab_str(stab_out *o, const char *s)
{
    if (!o->failed && dp_json_quote(o->b, s) != DP_OK)
        o->failed = 1;
}
