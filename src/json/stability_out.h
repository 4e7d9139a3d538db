/* src/json/stability_out.h - the append-only text writer the stability encoders share (JSON, CSV, SVG).
 *
 * Errors are sticky: after the first failed allocation every call is a no-op and `failed` stays set, so an
 * encoder writes straight through and checks once at the end. Numbers are written with round-trip precision
 * (dp_format_double); a non-finite number becomes null (JSON) -- the core never hands one over.
 */
#ifndef DASHPOT_JSON_STABILITY_OUT_H
#define DASHPOT_JSON_STABILITY_OUT_H

#include <stddef.h>
#include <string.h>
#include "dashpot/encode.h"
#include "dashpot/stability.h"

typedef struct stab_out {
    dp_buf *b;
    int failed;
} stab_out;

void stab_putn(stab_out *o, const char *s, size_t n);
/* Inline, so that the length of a literal is known when compiling: encoders write hundreds of pieces. */
static inline void stab_put(stab_out *o, const char *s)
{
    stab_putn(o, s, strlen(s));
}
/* An int in decimal, as %d writes it. */
void stab_int(stab_out *o, int v);
void stab_printf(stab_out *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* A number, or `null` if it is not finite. */
void stab_num(stab_out *o, double x);
/* A JSON string literal. */
void stab_str(stab_out *o, const char *s);

/* The map as an SVG heat map with the closed-form boundary overlaid (stability_svg.c). */
void stab_map_svg(stab_out *o, const dp_map *map);

#endif
