/* src/json/dtoa.h - the encoders' entry to dtoa.c: dp_format_double writing into a wider buffer, so that it
 * can copy digits in fixed-length blocks (no variable-length memcpy on the hot path). */
#ifndef DASHPOT_JSON_DTOA_H
#define DASHPOT_JSON_DTOA_H

#include <stddef.h>

/* Bytes dp_format_double_wide may write past out (the text itself is at most 25 plus a NUL). */
#define DP_DTOA_WIDE 48

/* dp_format_double into out[0..DP_DTOA_WIDE); bytes past the returned length are scratch. */
size_t dp_format_double_wide(char *out, double x);

#endif
