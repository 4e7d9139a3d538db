/* src/json/dtoa.h - the encoders' entry to dtoa.c: a double's shortest decimal as a value (dp_decimal, defined
 * in dashpot/encode.h for the encoder's state), apart from writing it out, so that an encoder can keep the
 * decimals of recent numbers and lay a repeated one out again without redoing its digits, and without
 * reading back text it has just written. */
#ifndef DASHPOT_JSON_DTOA_H
#define DASHPOT_JSON_DTOA_H

#include "dashpot/encode.h"

/* dp_decimal: the value is 0.d0d1...d16 10^point, 17 digits zero-padded after the last significant one.
 *   lo, hi  d1..d8 and d9..d16 as ASCII, d1 (d9) in the lowest byte whatever the byte order
 *   head    d0 (ASCII; 'n' for a non-finite value, written "null") | minus sign (0 or 1) << 8 |
 *           significant digits (1..17) << 16 | point (int32) << 32
 * Three whole words, so that copies and loads never straddle stores of another width. */

/* Bytes dp_decimal_put may write at p: the text (at most 25) plus scratch; bytes past its end are scratch. */
#define DP_DECIMAL_MAX 26

void dp_decimal_of(dp_decimal *d, double x);

/* Writes d as JavaScript's Number#toString would (no NUL); returns the end. */
char *dp_decimal_put(char *p, const dp_decimal *d);

/* dp_decimal_of and dp_decimal_put in one call (the digits stay in registers). */
char *dp_decimal_write(char *p, double x, dp_decimal *d);

#endif
