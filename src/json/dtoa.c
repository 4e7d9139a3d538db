/* src/json/dtoa.c - the shortest decimal that reads back as the same double, written as JavaScript's
 * Number#toString writes it: dp_format_double, and the pieces of dtoa.h the encoders use.
 *
 * Schubfach (R. Giulietti, "The Schubfach way to render doubles", 2020), written from the paper. A finite
 * v = c 2^q has the rounding interval R of the half-way points to its neighbours: every decimal in R (ends
 * included when c is even, as round-half-even then maps them to v) reads back as v. With k = floor(log10 of
 * the spacing), the decimal grid 10^k holds one or two points in R, and the coarser grid 10^(k+1) at most one;
 * Schubfach picks the point of the coarsest grid that meets R, nearest to v, from three products of 4c, and of
 * the two ends of R, with a 126-bit approximation g of 10^-k (pow10_g.h). Rounding those products to odd
 * keeps every comparison with a multiple of 4 exact (paper, section 9). No loop depends on the digits, which is
 * what makes it several times faster than printf("%.17g") and than digit-by-digit Grisu.
 *
 * Most doubles take a shorter way to the same answer (shortest_fast: one product instead of three, after the
 * fast paths of Y. Guo's yy and V. Zverovich's Zmij, here with an explicit error margin), and every path ends
 * in the same digit and layout code: 17 digits made in registers (two words of eight, by SWAR) and stored
 * once each, straight into their final place. Reading back bytes just stored at another width or offset
 * (a store-forwarding stall, ~15 cycles) was the largest cost of the earlier version.
 */
#include <stdint.h>
#include <string.h>

#include "dashpot/encode.h"
#include "dtoa.h"
#include "pow10_g.h"

__extension__ typedef unsigned __int128 u128;

/* The pieces of the common path, inlined into it whatever the optimizer's estimate. */
#define HOT static inline __attribute__((always_inline))

#define C_MIN (1ULL << 52) /* smallest significand of a normal double */
#define Q_MIN (-1074)      /* exponent of the subnormals */
#define MASK63 ((1ULL << 63) - 1)

/* floor(e log10 2), floor(e log10 2 + log10 3/4), floor(e log2 10) by fixed-point multiplication; checked
 * against exact arithmetic for |e| <= 1200, far beyond the exponents of doubles. */
static int flog10pow2(int e) { return (int)(((int64_t)e * 661971961083LL) >> 41); }
static int flog10_three_quarters_pow2(int e) { return (int)(((int64_t)e * 661971961083LL - 274743187321LL) >> 41); }
static int flog2pow10(int e) { return (int)(((int64_t)e * 913124641741LL) >> 38); }

/* floor(g cp / 2^127) with its lowest bit set when inexact (round to odd), g = g1 2^63 + g0. */
static uint64_t rop(uint64_t g1, uint64_t g0, uint64_t cp)
{
    uint64_t x1 = (uint64_t)(((u128)g0 * cp) >> 64);
    u128 y = (u128)g1 * cp;
    uint64_t z = ((uint64_t)y >> 1) + x1;
    uint64_t vbp = (uint64_t)(y >> 64) + (z >> 63);
    return vbp | (((z & MASK63) + MASK63) >> 63);
}

/* The shortest decimal f 10^*K in the rounding interval of c 2^q (c > 0), nearest to it on ties of length. */
static uint64_t shortest(uint64_t c, int q, int *K)
{
    uint64_t out = c & 1, cb = c << 2, cbr = cb + 2, cbl;
    int k;
    if (c != C_MIN || q == Q_MIN) {
        cbl = cb - 2;
        k = flog10pow2(q);
    } else { /* at a power of two the lower neighbour is twice as near: R is asymmetric */
        cbl = cb - 1;
        k = flog10_three_quarters_pow2(q);
    }
    int h = q + flog2pow10(-k) + 2;
    const uint64_t *g = pow10_g[-k - POW10_G_MIN];
    uint64_t vb = rop(g[0], g[1], cb << h), vbl = rop(g[0], g[1], cbl << h), vbr = rop(g[0], g[1], cbr << h);
    uint64_t s = vb >> 2; /* 4 vb ~ v 10^-k: s and t = s + 1 straddle v on the grid 10^k */
    *K = k;
    /* The candidates are selected with masks, not branches: the choice is a coin flip for typical data and
     * a mispredicted branch costs more than computing all of them. */
    uint64_t t = s + 1;
    int64_t cmp = (int64_t)(vb - ((s + t) << 1)); /* s and t both in R: the nearer to v, the even one on a tie */
    uint64_t nearest = s + (uint64_t)((cmp > 0) | ((cmp == 0) & (int)(s & 1)));
    int uin = vbl + out <= s << 2, win = (t << 2) + out <= vbr;
    uint64_t m = -(uint64_t)(uin ^ win); /* exactly one of s, t in R */
    uint64_t on10k = (m & (s + (uint64_t)!uin)) | (~m & nearest);
    /* One digit fewer: the multiples of 10 around s, of which at most one is in R. */
    uint64_t sp10 = s / 10 * 10, tp10 = sp10 + 10;
    int upin = vbl + out <= sp10 << 2, wpin = (tp10 << 2) + out <= vbr;
    uint64_t m10 = -(uint64_t)((s >= 10) & (upin ^ wpin));
    return (m10 & (sp10 + 10 * (uint64_t)!upin)) | (~m10 & on10k);
}

/* Schubfach's answer from one product instead of three, for a normal double with a symmetric interval (c not a
 * power of two). X = c 2^q 10^-k is formed to 64 fractional bits (y), and the half-width of the rounding
 * interval in the same scale, H = 2^(q-1) 10^-k in [0.5, 5), to 60 (half). Then the shorter candidates are
 * in R when X mod 10 <= H (sp10) or >= 10 - H (tp10), and otherwise Schubfach's longer answer is the integer
 * nearest to X (within H of it, so in R). Each comparison is decided from the approximations (errors below
 * 2^-59: g is 10^-k to 2^-125, and y drops g0 m's bits below 2^63) unless it falls within a margin
 * M = 2^-52 of equality, where only the exact computation can decide which side, or whether R's end is in:
 * returns 0 then. The last test, X within M of a multiple of 1/2, takes the ties between two candidates
 * (1702440449935834.25) and, with them, an X at an integer, whose s might be one off. About 1e-15 of random
 * doubles, and a few in 10^5 of a run's samples, go that way. */
HOT int shortest_fast(uint64_t c, int q, uint64_t *f, int *K)
{
    const uint64_t M = 1 << 8, ten = 10ULL << 60;
    int k = flog10pow2(q), h = q + flog2pow10(-k) + 2; /* 2 <= h <= 5 */
    const uint64_t *g = pow10_g[-k - POW10_G_MIN];
    uint64_t m = c << h;
    u128 y = (u128)g[0] * m + (uint64_t)(((u128)g[1] * m) >> 63); /* floor(g m / 2^63) ~ X 2^64 */
    uint64_t s = (uint64_t)(y >> 64), fr = (uint64_t)y >> 4, d = s % 10;
    uint64_t u = d << 60 | fr, half = g[0] >> (5 - h); /* X mod 10 and H, 60 fractional bits */
    int near = (u - half + M < 2 * M) | (u + half - ten + M < 2 * M) /* X mod 10 = H or 10 - H */
             | (((fr - M) & ((1ULL << 59) - 1)) > (1ULL << 59) - 2 * M); /* X a half-integer: a tie */
    *f = u < half ? s - d : u + half > ten ? s - d + 10 : s + (fr >> 59);
    *K = k;
    return !near;
}

/* ---- digits: the significand as 17 ASCII digits in registers ------------------------------------------- */

static const uint64_t pow10_u64[18] = {
    1ULL, 10ULL, 100ULL, 1000ULL, 10000ULL, 100000ULL, 1000000ULL, 10000000ULL, 100000000ULL,
    1000000000ULL, 10000000000ULL, 100000000000ULL, 1000000000000ULL, 10000000000000ULL,
    100000000000000ULL, 1000000000000000ULL, 10000000000000000ULL, 100000000000000000ULL
};

#define ZEROS 0x3030303030303030ULL            /* "00000000" */
#define NULL_TAIL (ZEROS << 24 | 0x6c6c75ULL) /* "ull00000" */

/* Number of decimal digits of 0 < f < 10^17 without a loop: 1233 / 4096 ~ log10 2 estimates it from the
 * bit length, one comparison corrects it. */
static int count_digits(uint64_t f)
{
    int t = ((64 - __builtin_clzll(f)) * 1233) >> 12;
    return t + (f >= pow10_u64[t]);
}

/* n < 10^8 as 8 one-digit bytes, the last digit in the lowest byte. Each step splits every lane in two with
 * one multiply-add, quotient and remainder at once: a + (2^32 - 10^4) floor(a / 10^4) = floor(a / 10^4) 2^32 +
 * a mod 10^4, then the same on 32-bit lanes by 100 and on 16-bit lanes by 10, the quotients by multiplication
 * with a rounded-up reciprocal (2^40 / 10^4, 2^19 / 100, 2^10 / 10: exact below 10^8, 10^4 and 100) and a
 * mask that drops the neighbouring lane (X. JunBo's, as used in Zmij). Three dependent multiply-adds, no
 * table, no division. */
HOT uint64_t bcd8(uint32_t n)
{
    uint64_t x = n;
    x += ((1ULL << 32) - 10000) * ((x * 109951163) >> 40);
    x += ((1ULL << 16) - 100) * (((x * 5243) >> 19) & 0x0000007f0000007fULL);
    return x + ((1ULL << 8) - 10) * (((x * 103) >> 10) & 0x000f000f000f000fULL);
}

/* Stores a word of digits (dp_decimal's order: the first in the lowest byte) at p, whatever the byte order. */
HOT void store8(char *p, uint64_t v)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    v = __builtin_bswap64(v);
#endif
    memcpy(p, &v, 8);
}

/* The fields of dp_decimal's head word (dtoa.h). */
HOT uint64_t make_head(unsigned d0, int len, int point)
{
    return d0 | (uint64_t)len << 16 | (uint64_t)(uint32_t)point << 32;
}
HOT int head_len(uint64_t head) { return (int)(head >> 16) & 0xff; }
HOT int head_point(uint64_t head) { return (int32_t)(head >> 32); }

/* F, exactly 17 digits d0..d16 (10^16 <= F < 10^17), with the decimal point after `point` of them. Split at
 * 10^16 and 10^8 (multiplications by reciprocals); the trailing zero digits are the zero bytes at the bottom
 * of the digit words, the second's only when the first is all zero. */
HOT dp_decimal digits_of(uint64_t F, int point)
{
    uint64_t top = F / 100000000; /* d0..d8, below 10^9 */
    uint32_t d0 = (uint32_t)(top / 100000000);
    uint64_t lo = bcd8((uint32_t)(top - d0 * 100000000ULL)), hi = bcd8((uint32_t)(F - top * 100000000));
    int tz = hi ? __builtin_ctzll(hi) >> 3 : lo ? 8 + (__builtin_ctzll(lo) >> 3) : 16;
    return (dp_decimal){ __builtin_bswap64(lo) | ZEROS, __builtin_bswap64(hi) | ZEROS,
                         make_head('0' + d0, 17 - tz, point) };
}

/* ---- layout: JavaScript's Number#toString --------------------------------------------------------------- */
/* Every case stores all 17 digits with fixed-length stores straight into their final place. Bytes past the
 * returned end are scratch; no case writes more than DP_DECIMAL_MAX bytes (dtoa.h). */

/* The 17 digits at p: d0, then the two words. */
HOT void put17(char *p, uint64_t lo, uint64_t hi, uint64_t head)
{
    p[0] = (char)head;
    store8(p + 1, lo);
    store8(p + 9, hi);
}

/* An integer below 10^21: the digits, then '0' up to the point (at most 4 more than the 17 stored). */
HOT char *put_integer(char *p, uint64_t lo, uint64_t hi, uint64_t head)
{
    put17(p, lo, hi, head);
    memcpy(p + 17, "0000", 4);
    return p + head_point(head);
}

/* The 8 digits of w with '.' inserted before digit j (0 <= j < 8); the last digit is pushed out. */
HOT uint64_t insert_point(uint64_t w, int j)
{
    uint64_t below = (1ULL << 8 * j) - 1;
    return (w & below) | (uint64_t)'.' << 8 * j | ((w << 8) & ~below << 8);
}

/* 1 <= point < len: the point falls among d1..d16, in lo or in hi; the digits after it move up a byte, d16
 * to p[17]. */
HOT char *put_fraction(char *p, uint64_t lo, uint64_t hi, uint64_t head)
{
    int j = head_point(head) - 1; /* digits of d1..d16 before the point */
    uint64_t a = lo, b = (hi << 8) | (lo >> 56);
    if (j < 8)
        a = insert_point(lo, j);
    else
        b = insert_point(hi, j - 8);
    p[0] = (char)head;
    store8(p + 1, a);
    store8(p + 9, b);
    p[17] = (char)(hi >> 56);
    return p + head_len(head) + 1;
}

/* -6 < point <= 0: "0.", -point zeros, the digits. */
HOT char *put_small(char *p, uint64_t lo, uint64_t hi, uint64_t head)
{
    memcpy(p, "0.000000", 8);
    p += 2 - head_point(head);
    put17(p, lo, hi, head);
    return p + head_len(head);
}

static const char pairs[201] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

/* d0[.d1..]e+X / e-X, |X| <= 324. */
static char *put_exponent(char *p, uint64_t lo, uint64_t hi, uint64_t head)
{
    int len = head_len(head), x = head_point(head) - 1;
    p[0] = (char)head;
    p[1] = '.';
    store8(p + 2, lo);
    store8(p + 10, hi);
    p += len > 1 ? len + 1 : 1;
    unsigned e = (unsigned)(x < 0 ? -x : x);
    memcpy(p, x < 0 ? "e-" : "e+", 2);
    /* 1, 2 or 3 digits: the hundreds digit (overwritten when there is none), then the last two digits' pair,
     * entered one byte late for a single digit. */
    p[2] = (char)('0' + e / 100);
    memcpy(p + 2 + (e >= 100), pairs + 2 * (e % 100) + (e < 10), 2);
    return p + 3 + (e >= 10) + (e >= 100);
}

HOT char *put_decimal(char *p, uint64_t lo, uint64_t hi, uint64_t head)
{
    int point = head_point(head);
    *p = '-';
    p += (head >> 8) & 1;
    if (point > 0 && point <= 21)
        return head_len(head) <= point ? put_integer(p, lo, hi, head) : put_fraction(p, lo, hi, head);
    return point > -6 && point <= 0 ? put_small(p, lo, hi, head) : put_exponent(p, lo, hi, head);
}

/* ---- the entry points ------------------------------------------------------------------------------------ */

/* What the fast path leaves: 0, non-finite values, subnormals, powers of two (an asymmetric interval),
 * integers below 2^53 (a whole X, which shortest_fast declines) and the values it cannot decide. Out of line,
 * so that the common path stays short. */
static __attribute__((noinline)) dp_decimal decimal_rare(uint64_t bits)
{
    int biased = (int)(bits >> 52) & 0x7ff, k = 0;
    uint64_t frac = bits & (C_MIN - 1), c = biased ? frac | C_MIN : frac, neg = (bits >> 63) << 8;
    int q = biased ? biased - 1075 : Q_MIN;
    if (biased == 0x7ff) /* "null", laid out as an integer of 4 digits: "n" then "ull0..." */
        return (dp_decimal){ NULL_TAIL, ZEROS, make_head('n', 4, 4) };
    if (c == 0)
        return (dp_decimal){ ZEROS, ZEROS, make_head('0', 1, 1) | neg };
    uint64_t f = q <= 0 && q > -53 && (c & ((1ULL << -q) - 1)) == 0 ? c >> -q /* an integer below 2^53 */
               : shortest(c, q, &k);
    int n = count_digits(f);
    dp_decimal d = digits_of(f * pow10_u64[17 - n], n + k);
    d.head |= neg;
    return d;
}

/* A normal double that is not a power of two and that shortest_fast decides: its answer has 16 or 17
 * digits. Returns 0 for the others. */
HOT int decimal_fast(dp_decimal *d, uint64_t bits)
{
    int biased = (int)(bits >> 52) & 0x7ff, k;
    uint64_t frac = bits & (C_MIN - 1), f;
    if ((unsigned)(biased - 1) >= 0x7fe || frac == 0 || !shortest_fast(frac | C_MIN, biased - 1075, &f, &k))
        return 0;
    int short16 = f < pow10_u64[16];
    *d = digits_of(short16 ? f * 10 : f, k + 17 - short16);
    d->head |= (bits >> 63) << 8;
    return 1;
}

static uint64_t bits_of(double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

void dp_decimal_of(dp_decimal *d, double x)
{
    uint64_t bits = bits_of(x);
    if (!decimal_fast(d, bits))
        *d = decimal_rare(bits);
}

char *dp_decimal_put(char *p, const dp_decimal *d)
{
    return put_decimal(p, d->lo, d->hi, d->head);
}

char *dp_decimal_write(char *p, double x, dp_decimal *d)
{
    uint64_t bits = bits_of(x);
    dp_decimal v;
    if (!decimal_fast(&v, bits))
        v = decimal_rare(bits);
    *d = v;
    return put_decimal(p, v.lo, v.hi, v.head);
}

size_t dp_format_double(char *out, double x)
{
    dp_decimal d;
    char *p = dp_decimal_write(out, x, &d);
    *p = '\0';
    return (size_t)(p - out);
}
