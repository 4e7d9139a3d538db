/* src/json/dtoa.c - dp_format_double: the shortest decimal that reads back as the same double.
 *
 * Schubfach (R. Giulietti, "The Schubfach way to render doubles", 2020), written from the paper. A finite
 * v = c 2^q has the rounding interval R of the half-way points to its neighbours: every decimal in R (ends
 * included when c is even, as round-half-even then maps them to v) reads back as v. With k = floor(log10 of
 * the spacing), the decimal grid 10^k holds one or two points in R, and the coarser grid 10^(k+1) at most one;
 * Schubfach picks the point of the coarsest grid that meets R, nearest to v, from three products of 4c, and of
 * the two ends of R, with a 126-bit approximation g of 10^-k (pow10_g.h). Rounding those products to odd
 * keeps every comparison with a multiple of 4 exact (paper, section 9). No loop depends on the digits, which is
 * what makes it several times faster than printf("%.17g") and than digit-by-digit Grisu.
 */
#include <stdint.h>
#include <string.h>

#include "dashpot/encode.h"
#include "dtoa.h"
#include "pow10_g.h"

__extension__ typedef unsigned __int128 u128;

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

static const char pairs[201] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

/* n < 10^8 as 8 ASCII digits in a register, first digit in the lowest byte (the memory order of a little
 * endian store). y / 2^57 ~ n / 10^6 in fixed point with a multiplier rounded up (error below
 * 10^8 / 2^57 ~ 7e-10, so even after three multiplications by 100 it cannot carry into a digit): each step
 * takes the integral part as the next pair of digits and scales the fraction by 100. Building the digits in
 * a register and storing once avoids reading back bytes just stored in pieces (a store-forwarding stall). */
static uint64_t eight_digits(uint32_t n)
{
    const uint64_t mask = (1ULL << 57) - 1;
    uint64_t y = n * 144115188076ULL, v = 0; /* ceil(2^57 / 10^6) */
    for (int i = 0; i < 4; i++) {
        uint16_t pair;
        memcpy(&pair, pairs + 2 * (y >> 57), 2);
        v |= (uint64_t)pair << (16 * i);
        y = (y & mask) * 100;
    }
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    v = __builtin_bswap64(v);
#endif
    return v;
}

/* Trailing '0' characters of 8 digits (from eight_digits) that are not all '0': the zero bytes at the top
 * of (digits XOR "00000000"), one clz instead of a loop. */
static int trailing_zero_chars(uint64_t v)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    v = __builtin_bswap64(v);
#endif
    return __builtin_clzll(v ^ 0x3030303030303030ULL) >> 3;
}

static const uint64_t pow10_u64[19] = {
    1ULL, 10ULL, 100ULL, 1000ULL, 10000ULL, 100000ULL, 1000000ULL, 10000000ULL, 100000000ULL,
    1000000000ULL, 10000000000ULL, 100000000000ULL, 1000000000000ULL, 10000000000000ULL,
    100000000000000ULL, 1000000000000000ULL, 10000000000000000ULL, 100000000000000000ULL,
    1000000000000000000ULL
};

/* Number of decimal digits of 0 < f < 10^18 without a loop: 1233 / 4096 ~ log10 2 estimates it from the
 * bit length, one comparison corrects it. */
static int count_digits(uint64_t f)
{
    int t = ((64 - __builtin_clzll(f)) * 1233) >> 12;
    return t + (f >= pow10_u64[t]);
}

/* Writes the 18 decimal digits of 0 < f < 10^18 into buf (>= 64 bytes, so that layout may copy fixed
 * lengths) and returns a pointer to the first non-zero one; *len receives the count of digits up to the
 * last non-zero one, and *K grows by the trailing zeros cut. */
static const char *digits(uint64_t f, char *buf, int *len, int *K)
{
    uint64_t q = f / 100000000;
    uint32_t lo = (uint32_t)(f - q * 100000000), mid = (uint32_t)(q % 100000000), hi = (uint32_t)(q / 100000000);
    uint64_t vmid = eight_digits(mid), vlo = eight_digits(lo);
    memcpy(buf, pairs + 2 * hi, 2);
    memcpy(buf + 2, &vmid, 8);
    memcpy(buf + 10, &vlo, 8);
    int n = count_digits(f), tz;
    if (lo != 0)
        tz = trailing_zero_chars(vlo);
    else if (mid != 0)
        tz = 8 + trailing_zero_chars(vmid);
    else
        tz = 16 + (hi % 10 == 0);
    *K += tz;
    *len = n - tz;
    return buf + 18 - n;
}

static char *write_exponent(char *p, int x)
{
    *p++ = 'e';
    *p++ = x < 0 ? '-' : '+';
    if (x < 0)
        x = -x;
    if (x >= 100) {
        *p++ = (char)('0' + x / 100);
        x %= 100;
        *p++ = (char)('0' + x / 10);
    } else if (x >= 10) {
        *p++ = (char)('0' + x / 10);
    }
    *p++ = (char)('0' + x % 10);
    return p;
}

/* Lays out d[0..len) * 10^K as JavaScript's Number#toString does: plain notation while the decimal point is
 * at most 21 places after the first digit and at most 6 places before it, exponent notation (1.5e+300) beyond.
 * Copies are of fixed length (17 or 16 bytes, len <= 17), cheaper than exact ones: d must be readable and p
 * writable 48 bytes on; bytes past the returned end are scratch. */
static char *layout(char *p, const char *d, int len, int K)
{
    int kk = len + K; /* position of the decimal point relative to the first digit */
    if (K >= 0 && kk <= 21) {
        memcpy(p, d, 17);
        memset(p + len, '0', (size_t)K);
        return p + kk;
    }
    if (kk > 0 && kk <= 21) { /* K < 0: the point falls inside the digits, 1 <= kk <= 16 */
        memcpy(p, d, 16);
        p[kk] = '.';
        memcpy(p + kk + 1, d + kk, 16);
        return p + len + 1;
    }
    if (kk > -6 && kk <= 0) {
        memcpy(p, "0.00000", 8);
        memcpy(p + 2 - kk, d, 17);
        return p + 2 - kk + len;
    }
    p[0] = d[0];
    p[1] = '.';
    memcpy(p + 2, d + 1, 16);
    return write_exponent(p + (len > 1 ? len + 1 : 1), kk - 1);
}

size_t dp_format_double_wide(char *out, double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    int biased = (int)(bits >> 52) & 0x7ff;
    uint64_t frac = bits & (C_MIN - 1);
    if (biased == 0x7ff) {
        memcpy(out, "null", 5);
        return 4;
    }
    char *p = out, buf[64];
    if (bits >> 63)
        *p++ = '-';
    int K = 0, len;
    uint64_t c = biased ? frac | C_MIN : frac;
    int q = biased ? biased - 1075 : Q_MIN;
    if (c == 0) {
        *p++ = '0';
    } else if (q <= 0 && q > -53 && (c & ((1ULL << -q) - 1)) == 0) { /* an integer below 2^53 */
        const char *d = digits(c >> -q, buf, &len, &K);
        p = layout(p, d, len, K);
    } else {
        int k;
        uint64_t f = shortest(c, q, &k);
        K = k;
        const char *d = digits(f, buf, &len, &K);
        p = layout(p, d, len, K);
    }
    *p = '\0';
    return (size_t)(p - out);
}

size_t dp_format_double(char *out, double x)
{
    char wide[DP_DTOA_WIDE];
    size_t n = dp_format_double_wide(wide, x);
    memcpy(out, wide, 32); /* n < 26: the text and its NUL fit the caller's 32 bytes */
    return n;
}
