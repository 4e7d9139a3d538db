/* tests/test_encode.c - the encoders (src/json/encode.c, buf.c, dtoa.c): dp_format_double round trips
 * bit for bit through strtod and is the shortest such text; it writes byte for byte what the previous
 * implementation wrote (kept below as the reference) on 10^7 random bit patterns and on values made to sit
 * on its decision boundaries; every format's exact text for a small fixed run, and for runs of numbers that
 * repeat (the encoder's reuse of recent numbers); every JSON output parses with cJSON; dp_json_quote escapes
 * as RFC 8259 requires; the event cap.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>
#include <cmocka.h>

#include "dashpot/encode.h"
#include "../src/json/pow10_g.h"

/* ---- dp_format_double ------------------------------------------------------------------------------- */

static uint64_t rng = 0x9e3779b97f4a7c15ULL;

/* xorshift64*: reproducible, no libc state. */
static uint64_t next_u64(void)
{
    rng ^= rng >> 12;
    rng ^= rng << 25;
    rng ^= rng >> 27;
    return rng * 2685821657736338717ULL;
}

static double from_bits(uint64_t b)
{
    double x;
    memcpy(&x, &b, sizeof x);
    return x;
}

/* JSON number grammar (RFC 8259 section 6): -? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)? */
static int json_number(const char *s)
{
    if (*s == '-')
        s++;
    if (*s == '0')
        s++;
    else if (*s >= '1' && *s <= '9')
        while (*s >= '0' && *s <= '9')
            s++;
    else
        return 0;
    if (*s == '.') {
        if (!(*++s >= '0' && *s <= '9'))
            return 0;
        while (*s >= '0' && *s <= '9')
            s++;
    }
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '+' || *s == '-')
            s++;
        if (!(*s >= '0' && *s <= '9'))
            return 0;
        while (*s >= '0' && *s <= '9')
            s++;
    }
    return *s == '\0';
}

/* Significant digits of a decimal text: the mantissa's digits without leading and trailing zeros. */
static int sig_digits(const char *s)
{
    char d[40];
    int n = 0;
    for (; *s && *s != 'e' && n < 39; s++)
        if (*s >= '0' && *s <= '9' && (n > 0 || *s != '0'))
            d[n++] = *s;
    while (n > 0 && d[n - 1] == '0')
        n--;
    return n;
}

/* The fewest %.*g digits that read back as x: the shortest round trip, by brute force. */
static int shortest_digits(double x)
{
    char t[40];
    for (int p = 1; p < 17; p++) {
        snprintf(t, sizeof t, "%.*e", p - 1, x);
        if (strtod(t, NULL) == x)
            return p;
    }
    return 17;
}

/* One value: the text is a JSON number below 32 bytes, reads back bit for bit and, when `shortest` is set,
 * has no more digits than needed. Failures print the value in hex and the text. */
static void check_double(double x, int shortest)
{
    char out[64];
    memset(out, 'X', sizeof out);
    size_t n = dp_format_double(out, x);
    if (n >= 32 || strlen(out) != n || !json_number(out))
        fail_msg("%a: bad text \"%s\" (length %zu)", x, out, n);
    double y = strtod(out, NULL);
    if (memcmp(&x, &y, sizeof x) != 0)
        fail_msg("%a (%.17g): \"%s\" reads back as %a", x, x, out, y);
    if (shortest && x != 0 && sig_digits(out) > shortest_digits(x))
        fail_msg("%a: \"%s\" has %d digits, %d suffice", x, out, sig_digits(out), shortest_digits(x));
}

static void test_double_special(void **state)
{
    (void)state;
    static const struct { double x; const char *text; } cases[] = {
        { 0.0, "0" }, { -0.0, "-0" }, { 1.0, "1" }, { -1.5, "-1.5" }, { 0.1, "0.1" }, { 0.3, "0.3" },
        { 100, "100" }, { 1e15, "1000000000000000" }, { 1e21, "1e+21" }, { 1e22, "1e+22" }, { 1e23, "1e+23" },
        { 1e-7, "1e-7" }, { 0.000025, "0.000025" }, { 0.001, "0.001" }, { 0.0030000000000000001, "0.003" },
        { 5e-324, "5e-324" }, { 1e-323, "1e-323" }, { 2.2250738585072014e-308, "2.2250738585072014e-308" },
        { 1.7976931348623157e308, "1.7976931348623157e+308" }, { 9007199254740992.0, "9007199254740992" },
        { 123456789012345680.0, "123456789012345680" }, { 4.35, "4.35" }, { 1.0 / 3, "0.3333333333333333" },
        { 2.0 / 3, "0.6666666666666666" }, { 5e-7, "5e-7" }, { 123e18, "123000000000000000000" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char out[32];
        dp_format_double(out, cases[i].x);
        if (strcmp(out, cases[i].text) != 0)
            fail_msg("case %zu: %a written as \"%s\", expected \"%s\"", i, cases[i].x, out, cases[i].text);
        check_double(cases[i].x, 1);
    }
    char out[32];
    assert_int_equal(dp_format_double(out, NAN), 4);
    assert_string_equal(out, "null");
    dp_format_double(out, -INFINITY);
    assert_string_equal(out, "null");
}

/* 10^6 random bit patterns (every exponent, subnormals included) and 10^5 random subnormals. */
static void test_double_random_bits(void **state)
{
    (void)state;
    for (long i = 0; i < 1000000; i++) {
        double x = from_bits(next_u64());
        if (isfinite(x))
            check_double(x, i % 16 == 0); /* the brute-force shortest check is slow: every 16th */
    }
    for (long i = 0; i < 100000; i++)
        check_double(from_bits(next_u64() & ((1ULL << 52) - 1)), i % 16 == 0);
}

/* The smallest subnormals have few digits (5e-324, 1e-323, ..., 9.9e-323 must be 1e-322): every one of the
 * first 20000, each checked for shortness. */
static void test_double_tiny(void **state)
{
    (void)state;
    for (uint64_t c = 1; c <= 20000; c++)
        check_double(from_bits(c), 1);
}

/* Powers of ten and their neighbours, powers of two (the asymmetric intervals), integers and decimals of the
 * kind samples are made of (k * dt). */
static void test_double_structured(void **state)
{
    (void)state;
    for (int e = -323; e <= 308; e++) {
        char t[32];
        snprintf(t, sizeof t, "1e%d", e);
        double p = strtod(t, NULL);
        check_double(p, 1);
        check_double(nextafter(p, 0), 1);
        check_double(nextafter(p, INFINITY), 1);
        check_double(-p, 1);
    }
    for (int e = -1074; e <= 1023; e++) {
        double p = ldexp(1.0, e);
        check_double(p, 1);
        check_double(nextafter(p, 0), 1);
        check_double(nextafter(p, INFINITY), 1);
    }
    for (long i = 0; i < 200000; i++) {
        int64_t n = (int64_t)(next_u64() >> (next_u64() % 64));
        check_double((double)n, i % 16 == 0);
        check_double((double)(i - 100000) * 1e-3, i % 16 == 0);
        check_double((double)(next_u64() % 1000000) / pow(10, (double)(next_u64() % 40)), i % 16 == 0);
    }
}

/* ---- dp_format_double against the previous implementation ----------------------------------------------
 * The reference is dtoa.c as of 46020fd, before the one-product fast path and the new digit and layout code:
 * Schubfach with all three products for every double, its digits staged in a buffer and laid out by
 * memcpy. Names changed, and one fix: it loaded each pair of digit characters as a uint16_t, which swaps
 * them on a big-endian host (it wrote 1.32547608 for 1.2345678 on s390x); the pair is built from its two
 * bytes here, so that the reference is right everywhere. It writes up to 48 bytes past out. */

__extension__ typedef unsigned __int128 u128;

#define REF_C_MIN (1ULL << 52)
#define REF_Q_MIN (-1074)
#define REF_MASK63 ((1ULL << 63) - 1)

static int ref_flog10pow2(int e) { return (int)(((int64_t)e * 661971961083LL) >> 41); }
static int ref_flog10_three_quarters_pow2(int e) { return (int)(((int64_t)e * 661971961083LL - 274743187321LL) >> 41); }
static int ref_flog2pow10(int e) { return (int)(((int64_t)e * 913124641741LL) >> 38); }

static uint64_t ref_rop(uint64_t g1, uint64_t g0, uint64_t cp)
{
    uint64_t x1 = (uint64_t)(((u128)g0 * cp) >> 64);
    u128 y = (u128)g1 * cp;
    uint64_t z = ((uint64_t)y >> 1) + x1;
    uint64_t vbp = (uint64_t)(y >> 64) + (z >> 63);
    return vbp | (((z & REF_MASK63) + REF_MASK63) >> 63);
}

static uint64_t ref_shortest(uint64_t c, int q, int *K)
{
    uint64_t out = c & 1, cb = c << 2, cbr = cb + 2, cbl;
    int k;
    if (c != REF_C_MIN || q == REF_Q_MIN) {
        cbl = cb - 2;
        k = ref_flog10pow2(q);
    } else {
        cbl = cb - 1;
        k = ref_flog10_three_quarters_pow2(q);
    }
    int h = q + ref_flog2pow10(-k) + 2;
    const uint64_t *g = pow10_g[-k - POW10_G_MIN];
    uint64_t vb = ref_rop(g[0], g[1], cb << h), vbl = ref_rop(g[0], g[1], cbl << h), vbr = ref_rop(g[0], g[1], cbr << h);
    uint64_t s = vb >> 2;
    *K = k;
    uint64_t t = s + 1;
    int64_t cmp = (int64_t)(vb - ((s + t) << 1));
    uint64_t nearest = s + (uint64_t)((cmp > 0) | ((cmp == 0) & (int)(s & 1)));
    int uin = vbl + out <= s << 2, win = (t << 2) + out <= vbr;
    uint64_t m = -(uint64_t)(uin ^ win);
    uint64_t on10k = (m & (s + (uint64_t)!uin)) | (~m & nearest);
    uint64_t sp10 = s / 10 * 10, tp10 = sp10 + 10;
    int upin = vbl + out <= sp10 << 2, wpin = (tp10 << 2) + out <= vbr;
    uint64_t m10 = -(uint64_t)((s >= 10) & (upin ^ wpin));
    return (m10 & (sp10 + 10 * (uint64_t)!upin)) | (~m10 & on10k);
}

static const char ref_pairs[201] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

static uint64_t ref_eight_digits(uint32_t n)
{
    const uint64_t mask = (1ULL << 57) - 1;
    uint64_t y = n * 144115188076ULL, v = 0;
    for (int i = 0; i < 4; i++) {
        const char *pair = ref_pairs + 2 * (y >> 57);
        v |= (uint64_t)(unsigned char)pair[0] << (16 * i) | (uint64_t)(unsigned char)pair[1] << (16 * i + 8);
        y = (y & mask) * 100;
    }
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    v = __builtin_bswap64(v);
#endif
    return v;
}

static int ref_trailing_zero_chars(uint64_t v)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    v = __builtin_bswap64(v);
#endif
    return __builtin_clzll(v ^ 0x3030303030303030ULL) >> 3;
}

static const uint64_t ref_pow10_u64[19] = {
    1ULL, 10ULL, 100ULL, 1000ULL, 10000ULL, 100000ULL, 1000000ULL, 10000000ULL, 100000000ULL,
    1000000000ULL, 10000000000ULL, 100000000000ULL, 1000000000000ULL, 10000000000000ULL,
    100000000000000ULL, 1000000000000000ULL, 10000000000000000ULL, 100000000000000000ULL,
    1000000000000000000ULL
};

static int ref_count_digits(uint64_t f)
{
    int t = ((64 - __builtin_clzll(f)) * 1233) >> 12;
    return t + (f >= ref_pow10_u64[t]);
}

static const char *ref_digits(uint64_t f, char *buf, int *len, int *K)
{
    uint64_t q = f / 100000000;
    uint32_t lo = (uint32_t)(f - q * 100000000), mid = (uint32_t)(q % 100000000), hi = (uint32_t)(q / 100000000);
    uint64_t vmid = ref_eight_digits(mid), vlo = ref_eight_digits(lo);
    memcpy(buf, ref_pairs + 2 * hi, 2);
    memcpy(buf + 2, &vmid, 8);
    memcpy(buf + 10, &vlo, 8);
    int n = ref_count_digits(f), tz;
    if (lo != 0)
        tz = ref_trailing_zero_chars(vlo);
    else if (mid != 0)
        tz = 8 + ref_trailing_zero_chars(vmid);
    else
        tz = 16 + (hi % 10 == 0);
    *K += tz;
    *len = n - tz;
    return buf + 18 - n;
}

static char *ref_write_exponent(char *p, int x)
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

static char *ref_layout(char *p, const char *d, int len, int K)
{
    int kk = len + K;
    if (K >= 0 && kk <= 21) {
        memcpy(p, d, 17);
        memset(p + len, '0', (size_t)K);
        return p + kk;
    }
    if (kk > 0 && kk <= 21) {
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
    return ref_write_exponent(p + (len > 1 ? len + 1 : 1), kk - 1);
}

static size_t ref_format(char *out, double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    int biased = (int)(bits >> 52) & 0x7ff;
    uint64_t frac = bits & (REF_C_MIN - 1);
    if (biased == 0x7ff) {
        memcpy(out, "null", 5);
        return 4;
    }
    char *p = out, buf[64];
    if (bits >> 63)
        *p++ = '-';
    int K = 0, len;
    uint64_t c = biased ? frac | REF_C_MIN : frac;
    int q = biased ? biased - 1075 : REF_Q_MIN;
    if (c == 0) {
        *p++ = '0';
    } else if (q <= 0 && q > -53 && (c & ((1ULL << -q) - 1)) == 0) {
        const char *d = ref_digits(c >> -q, buf, &len, &K);
        p = ref_layout(p, d, len, K);
    } else {
        int k;
        uint64_t f = ref_shortest(c, q, &k);
        K = k;
        const char *d = ref_digits(f, buf, &len, &K);
        p = ref_layout(p, d, len, K);
    }
    *p = '\0';
    return (size_t)(p - out);
}


/* x as both write it: the same bytes, and (finite x) a text that reads back as x. */
static void check_same(double x)
{
    char got[64], want[64];
    memset(got, 'X', sizeof got);
    size_t n = dp_format_double(got, x), m = ref_format(want, x);
    if (n != m || strcmp(got, want) != 0 || strlen(got) != n)
        fail_msg("%a: \"%s\" (length %zu), the reference writes \"%s\"", x, got, n, want);
    if (isfinite(x)) {
        double y = strtod(got, NULL);
        if (memcmp(&x, &y, sizeof x) != 0)
            fail_msg("%a: \"%s\" reads back as %a", x, got, y);
    }
}

/* x and its neighbours up to 2 ulps away on either side. */
static void check_same_around(double x)
{
    double lo = x, hi = x;
    check_same(x);
    for (int i = 0; i < 2; i++) {
        check_same(lo = nextafter(lo, -INFINITY));
        check_same(hi = nextafter(hi, INFINITY));
    }
}

/* 10^7 random bit patterns: every exponent, subnormals, NaNs and infinities ("null"). */
static void test_double_vs_reference_bits(void **state)
{
    (void)state;
    for (long i = 0; i < 10000000; i++)
        check_same(from_bits(next_u64()));
}

/* Numbers made to sit on the decision boundaries of the fast path (dtoa.c, shortest_fast): decimals of
 * 1 to 17 random digits at every exponent (the shorter candidates at the edges of the rounding interval)
 * and their neighbours; small integers times powers of two (exact ties between candidates); integers;
 * powers of two and of ten and their neighbours; and what runs produce: k dt, and damped oscillations. */
static void test_double_vs_reference_boundaries(void **state)
{
    (void)state;
    char t[48];
    for (long i = 0; i < 1000000; i++) {
        int digits = 1 + (int)(next_u64() % 17), e = (int)(next_u64() % 650) - 340;
        snprintf(t, sizeof t, "%llue%d", (unsigned long long)(next_u64() % 100000000000000000ULL) %
                 (unsigned long long)pow(10, digits), e);
        check_same_around(strtod(t, NULL));
        check_same(ldexp((double)(next_u64() % 4096), (int)(next_u64() % 2100) - 1080));
        check_same((double)(int64_t)(next_u64() >> (next_u64() % 64)));
    }
    for (int e = -1074; e <= 1023; e++)
        check_same_around(ldexp(1.0, e));
    for (int e = -330; e <= 310; e++) {
        snprintf(t, sizeof t, "1e%d", e);
        check_same_around(strtod(t, NULL));
    }
    for (long i = 0; i < 1000000; i++) {
        check_same((double)i * 1e-6);
        check_same((double)i * 1e-3);
        check_same(exp(-1e-6 * (double)i) * cos(1e-3 * (double)i));
        check_same(-0.3 + 1e-9 * (double)i);
    }
}

/* ---- the encoders' reuse of recent numbers ----------------------------------------------------------- */

/* Samples whose members repeat in every pattern the encoder looks for (the same member of the previous
 * sample, one or two members before in the same sample) and in ones it does not, with values from a pool
 * of 8 (zeros of both signs, a short decimal and its neighbour, long ones): each NDJSON line and CSV row
 * must be the text of its own numbers, as dp_format_double writes them one by one. */
static void test_sample_reuse(void **state)
{
    (void)state;
    static const double pool[8] = { 0.0, -0.0, -0.3, -0.29999999999999993, 1.0 / 3, -2.5e-7, 123456.789,
                                    9.87654321e21 };
    dp_encoder nd, csv;
    dp_encoder_init(&nd, DP_FORMAT_NDJSON);
    dp_encoder_init(&csv, DP_FORMAT_CSV);
    for (int i = 0; i < 20000; i++) {
        double v[6];
        for (int j = 0; j < 6; j++)
            v[j] = pool[next_u64() % 8];
        dp_record r = { .type = DP_RECORD_SAMPLE,
                        .u.sample = { v[0], v[1], v[2], v[3], v[4], v[5], (dp_phase)(i % 3) } };
        char n[6][32], want[512];
        for (int j = 0; j < 6; j++)
            dp_format_double(n[j], v[j]);
        const char *ph = i % 3 == 1 ? ",\"phase\":\"stick\"" : i % 3 == 2 ? ",\"phase\":\"slip\"" : "";
        dp_buf b = { 0 };
        assert_int_equal(dp_encoder_record(&nd, &b, &r), DP_OK);
        snprintf(want, sizeof want, "{\"type\":\"sample\",\"t\":%s,\"x\":%s,\"v\":%s,\"Fs\":%s,\"Fd\":%s,\"Fc\":%s%s}\n",
                 n[0], n[1], n[2], n[3], n[4], n[5], ph);
        if (strcmp(b.data, want) != 0)
            fail_msg("sample %d:\n%s%s", i, b.data, want);
        b.len = 0;
        assert_int_equal(dp_encoder_record(&csv, &b, &r), DP_OK);
        snprintf(want, sizeof want, "%s,%s,%s,%s,%s,%s,%s\n", n[0], n[1], n[2], n[3], n[4], n[5],
                 i % 3 == 1 ? "stick" : i % 3 == 2 ? "slip" : "");
        if (strcmp(b.data, want) != 0)
            fail_msg("row %d:\n%s%s", i, b.data, want);
        dp_buf_free(&b);
    }
    dp_encoder_clear(&nd);
    dp_encoder_clear(&csv);
}

/* ---- dp_json_quote ---------------------------------------------------------------------------------- */

static void test_json_quote(void **state)
{
    (void)state;
    static const struct { const char *in, *out; } cases[] = {
        { "", "\"\"" },
        { "plain", "\"plain\"" },
        { "a\"b\\c", "\"a\\\"b\\\\c\"" },
        { "\n\r\t\b\f", "\"\\n\\r\\t\\b\\f\"" },
        { "\x01\x1f\x7f", "\"\\u0001\\u001f\\u007f\"" },
        { "</script>", "\"<\\/script>\"" },
        { "a/b", "\"a/b\"" },
        { "caf\xc3\xa9 \xe2\x82\xac", "\"caf\xc3\xa9 \xe2\x82\xac\"" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dp_buf b = { 0 };
        assert_int_equal(dp_json_quote(&b, cases[i].in), DP_OK);
        if (strcmp(b.data, cases[i].out) != 0)
            fail_msg("case %zu: got %s, expected %s", i, b.data, cases[i].out);
        cJSON *j = cJSON_Parse(b.data);
        assert_non_null(j);
        assert_true(cJSON_IsString(j));
        assert_string_equal(j->valuestring, cases[i].in); /* what was quoted comes back */
        cJSON_Delete(j);
        dp_buf_free(&b);
    }
    dp_buf b = { 0 };
    assert_int_equal(dp_json_quote(&b, NULL), DP_OK);
    assert_string_equal(b.data, "\"\"");
    dp_buf_free(&b);
}

/* ---- the encoders: a small fixed run --------------------------------------------------------------- */

#define META "{\"type\":\"meta\",\"solver\":\"stick-slip\",\"dt\":0.5}"

/* A stick, a breakaway event, a slip, and a sample of a damper without phases. */
static const dp_record run_records[] = {
    { .type = DP_RECORD_SAMPLE, .u.sample = { 0, 1, 0, 1, -0.5, -0.5, DP_PHASE_STICK } },
    { .type = DP_RECORD_EVENT, .u.event = { DP_EVENT_SLIP, 0.25, 1, 0 } },
    { .type = DP_RECORD_SAMPLE, .u.sample = { 0.5, 0.875, -0.5, 0.875, -1, -1, DP_PHASE_SLIP } },
    { .type = DP_RECORD_SAMPLE, .u.sample = { 1, 0.1, -0.3, 0.1, 1e-7, 0, DP_PHASE_NONE } },
};

/* Encodes the fixed run in format f, closing it with the summary or (fail) an error; returns the text. */
static char *encode_run(dp_format f, int fail, const char *extra)
{
    dp_summary sm = { .final = run_records[3].u.sample, .steps = 2, .samples = 3, .events = 1,
                      .stick_time = 0.25, .iterations = 7, .rejected = 3, .fevals = 41 };
    dp_buf b = { 0 };
    dp_encoder e;
    dp_encoder_init(&e, f);
    assert_int_equal(dp_encoder_begin(&e, &b, META), DP_OK);
    for (size_t i = 0; i < sizeof run_records / sizeof run_records[0]; i++)
        assert_int_equal(dp_encoder_record(&e, &b, &run_records[i]), DP_OK);
    if (fail)
        assert_int_equal(dp_encoder_fail(&e, &b, DP_ENONFINITE, "x left \"finite\"\nnumbers"), DP_OK);
    else
        assert_int_equal(dp_encoder_end(&e, &b, &sm, extra), DP_OK);
    dp_encoder_clear(&e);
    assert_int_equal(strlen(b.data), b.len);
    return b.data;
}

#define S0 "\"t\":0,\"x\":1,\"v\":0,\"Fs\":1,\"Fd\":-0.5,\"Fc\":-0.5,\"phase\":\"stick\""
#define S1 "\"t\":0.5,\"x\":0.875,\"v\":-0.5,\"Fs\":0.875,\"Fd\":-1,\"Fc\":-1,\"phase\":\"slip\""
#define S2 "\"t\":1,\"x\":0.1,\"v\":-0.3,\"Fs\":0.1,\"Fd\":1e-7,\"Fc\":0"
#define EV "\"kind\":\"slip\",\"t\":0.25,\"x\":1,\"v\":0"
#define SUM "\"final\":{" S2 "},\"steps\":2,\"samples\":3,\"events\":1,\"stick_time\":0.25,\"iterations\":7," \
            "\"rejected\":3,\"fevals\":41"
#define ERR "\"status\":422,\"title\":\"the solution diverged (non-finite values)\"," \
            "\"detail\":\"x left \\\"finite\\\"\\nnumbers\""

static void expect_text(dp_format f, int fail, const char *extra, const char *want)
{
    char *got = encode_run(f, fail, extra);
    if (strcmp(got, want) != 0)
        fail_msg("format %d fail %d:\n--- got\n%s--- expected\n%s", (int)f, fail, got, want);
    free(got);
}

static void test_ndjson_text(void **state)
{
    (void)state;
    const char *head = "{\"type\":\"meta\",\"solver\":\"stick-slip\",\"dt\":0.5}\n"
                       "{\"type\":\"sample\"," S0 "}\n{\"type\":\"event\"," EV "}\n"
                       "{\"type\":\"sample\"," S1 "}\n{\"type\":\"sample\"," S2 "}\n";
    char want[2048];
    snprintf(want, sizeof want, "%s{\"type\":\"summary\"," SUM "}\n", head);
    expect_text(DP_FORMAT_NDJSON, 0, NULL, want);
    snprintf(want, sizeof want, "%s{\"type\":\"summary\"," SUM ",\"wall_s\":1}\n", head);
    expect_text(DP_FORMAT_NDJSON, 0, "\"wall_s\":1", want);
    snprintf(want, sizeof want, "%s{\"type\":\"error\"," ERR "}\n", head);
    expect_text(DP_FORMAT_NDJSON, 1, NULL, want);
}

static void test_sse_text(void **state)
{
    (void)state;
    const char *head = "event: meta\ndata: {\"type\":\"meta\",\"solver\":\"stick-slip\",\"dt\":0.5}\n\n"
                       "event: sample\ndata: {\"type\":\"sample\"," S0 "}\n\n"
                       "event: event\ndata: {\"type\":\"event\"," EV "}\n\n"
                       "event: sample\ndata: {\"type\":\"sample\"," S1 "}\n\n"
                       "event: sample\ndata: {\"type\":\"sample\"," S2 "}\n\n";
    char want[2048];
    snprintf(want, sizeof want, "%sevent: summary\ndata: {\"type\":\"summary\"," SUM "}\n\n", head);
    expect_text(DP_FORMAT_SSE, 0, NULL, want);
    snprintf(want, sizeof want, "%sevent: error\ndata: {\"type\":\"error\"," ERR "}\n\n", head);
    expect_text(DP_FORMAT_SSE, 1, NULL, want);
}

static void test_json_text(void **state)
{
    (void)state;
    const char *head = "{\"meta\":{\"solver\":\"stick-slip\",\"dt\":0.5},\n\"samples\":[\n"
                       "{" S0 "},\n{" S1 "},\n{" S2 "}\n],\n\"events\":[\n{" EV "}\n],\n";
    char want[2048];
    snprintf(want, sizeof want, "%s\"summary\":{" SUM ",\"events_dropped\":0}}\n", head);
    expect_text(DP_FORMAT_JSON, 0, NULL, want);
    snprintf(want, sizeof want, "%s\"error\":{" ERR "}}\n", head);
    expect_text(DP_FORMAT_JSON, 1, NULL, want);
}

static void test_csv_text(void **state)
{
    (void)state;
    const char *rows = "t,x,v,Fs,Fd,Fc,phase\n0,1,0,1,-0.5,-0.5,stick\n0.5,0.875,-0.5,0.875,-1,-1,slip\n"
                       "1,0.1,-0.3,0.1,1e-7,0,\n";
    expect_text(DP_FORMAT_CSV, 0, NULL, rows);
    char want[1024];
    snprintf(want, sizeof want, "%s# error: 422 x left \"finite\" numbers\n", rows);
    expect_text(DP_FORMAT_CSV, 1, NULL, want);
}

/* Parses one JSON text and checks its "type" member when `type` is given. */
static void parse_json(const char *text, size_t len, const char *type)
{
    cJSON *j = cJSON_ParseWithLength(text, len);
    if (j == NULL)
        fail_msg("not JSON: %.*s", (int)len, text);
    if (type) {
        cJSON *t = cJSON_GetObjectItemCaseSensitive(j, "type");
        assert_true(cJSON_IsString(t));
        assert_string_equal(t->valuestring, type);
    }
    cJSON_Delete(j);
}

/* Every NDJSON line, every SSE data field and the JSON document parse; their types come in order. */
static void test_outputs_parse(void **state)
{
    (void)state;
    static const char *const types[] = { "meta", "sample", "event", "sample", "sample", "summary" };
    for (int fail = 0; fail < 2; fail++) {
        char *nd = encode_run(DP_FORMAT_NDJSON, fail, NULL), *line = nd;
        for (int i = 0; *line; i++) {
            char *end = strchr(line, '\n');
            assert_non_null(end);
            parse_json(line, (size_t)(end - line), i == 5 && fail ? "error" : types[i]);
            line = end + 1;
        }
        free(nd);
        char *sse = encode_run(DP_FORMAT_SSE, fail, NULL), *ev = sse;
        for (int i = 0; (ev = strstr(ev, "data: ")) != NULL; i++) {
            ev += 6;
            char *end = strstr(ev, "\n\n");
            assert_non_null(end);
            parse_json(ev, (size_t)(end - ev), i == 5 && fail ? "error" : types[i]);
        }
        free(sse);
        char *doc = encode_run(DP_FORMAT_JSON, fail, NULL);
        cJSON *j = cJSON_Parse(doc);
        assert_non_null(j);
        assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(j, "samples")), 3);
        assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(j, "events")), 1);
        assert_non_null(cJSON_GetObjectItem(j, fail ? "error" : "summary"));
        cJSON_Delete(j);
        free(doc);
    }
}

/* A run without samples or events, and meta objects with and without "type", with spaces, or none at all. */
static void test_empty_and_meta(void **state)
{
    (void)state;
    static const struct { const char *meta, *ndjson, *json; } cases[] = {
        { "{}", "{\"type\":\"meta\"}\n", "{\"meta\":{}," },
        { NULL, "{\"type\":\"meta\"}\n", "{\"meta\":{}," },
        { " { \"a\":1 } ", "{\"type\":\"meta\",\"a\":1 }\n", "{\"meta\":{\"a\":1 }," }, /* passed through */
        { "{\"type\":\"meta\"}", "{\"type\":\"meta\"}\n", "{\"meta\":{}," },
        { "{\"type\":\"meta\", \"a\":[1]}", "{\"type\":\"meta\",\"a\":[1]}\n", "{\"meta\":{\"a\":[1]}," },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dp_buf b = { 0 };
        dp_encoder e;
        dp_encoder_init(&e, DP_FORMAT_NDJSON);
        assert_int_equal(dp_encoder_begin(&e, &b, cases[i].meta), DP_OK);
        assert_string_equal(b.data, cases[i].ndjson);
        dp_buf_free(&b);
        dp_summary sm = { .final = { .phase = DP_PHASE_NONE } };
        dp_encoder_init(&e, DP_FORMAT_JSON);
        assert_int_equal(dp_encoder_begin(&e, &b, cases[i].meta), DP_OK);
        assert_int_equal(strncmp(b.data, cases[i].json, strlen(cases[i].json)), 0);
        assert_int_equal(dp_encoder_end(&e, &b, &sm, NULL), DP_OK);
        parse_json(b.data, b.len, NULL);
        assert_non_null(strstr(b.data, "\"samples\":[],\n\"events\":[],\n"));
        dp_encoder_clear(&e);
        dp_buf_free(&b);
    }
}

/* JSON keeps at most DP_ENCODER_MAX_EVENTS events and counts the rest; NDJSON writes every one. */
static void test_event_cap(void **state)
{
    (void)state;
    dp_record r = { .type = DP_RECORD_EVENT, .u.event = { DP_EVENT_STICK, 1, 2, 0 } };
    dp_buf b = { 0 };
    dp_encoder e;
    dp_encoder_init(&e, DP_FORMAT_JSON);
    assert_int_equal(dp_encoder_begin(&e, &b, "{}"), DP_OK);
    for (long i = 0; i < DP_ENCODER_MAX_EVENTS + 5; i++)
        assert_int_equal(dp_encoder_record(&e, &b, &r), DP_OK);
    dp_summary sm = { .events = DP_ENCODER_MAX_EVENTS + 5 };
    assert_int_equal(dp_encoder_end(&e, &b, &sm, NULL), DP_OK);
    cJSON *j = cJSON_Parse(b.data);
    assert_non_null(j);
    assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(j, "events")), DP_ENCODER_MAX_EVENTS);
    cJSON *dropped = cJSON_GetObjectItem(cJSON_GetObjectItem(j, "summary"), "events_dropped");
    assert_true(cJSON_IsNumber(dropped));
    assert_int_equal((long)dropped->valuedouble, 5);
    cJSON_Delete(j);
    dp_encoder_clear(&e);
    dp_encoder_clear(&e); /* idempotent */
    dp_encoder_clear(NULL);
    dp_buf_free(&b);
    dp_buf_free(NULL);
}

static void test_names_and_statuses(void **state)
{
    (void)state;
    assert_int_equal(dp_format_from_name("json"), DP_FORMAT_JSON);
    assert_int_equal(dp_format_from_name("ndjson"), DP_FORMAT_NDJSON);
    assert_int_equal(dp_format_from_name("sse"), DP_FORMAT_SSE);
    assert_int_equal(dp_format_from_name("csv"), DP_FORMAT_CSV);
    assert_int_equal(dp_format_from_name("xml"), -1);
    assert_int_equal(dp_format_from_name(NULL), -1);
    assert_string_equal(dp_format_content_type(DP_FORMAT_NDJSON), "application/x-ndjson");
    assert_string_equal(dp_format_content_type(DP_FORMAT_SSE), "text/event-stream");
    assert_string_equal(dp_format_content_type(DP_FORMAT_JSON), "application/json");
    assert_int_equal(dp_status_http(DP_ESYNTAX), 400);
    assert_int_equal(dp_status_http(DP_EINVAL), 422);
    assert_int_equal(dp_status_http(DP_ELIMIT), 422);
    assert_int_equal(dp_status_http(DP_ENONFINITE), 422);
    assert_int_equal(dp_status_http(DP_ESOLVE), 422);
    assert_int_equal(dp_status_http(DP_ENOMEM), 503);
    assert_int_equal(dp_status_http(DP_ECANCEL), 503);
    assert_int_equal(dp_status_http(413), 413);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_double_special),
        cmocka_unit_test(test_double_random_bits),
        cmocka_unit_test(test_double_structured),
        cmocka_unit_test(test_double_tiny),
        cmocka_unit_test(test_double_vs_reference_bits),
        cmocka_unit_test(test_double_vs_reference_boundaries),
        cmocka_unit_test(test_sample_reuse),
        cmocka_unit_test(test_json_quote),
        cmocka_unit_test(test_ndjson_text),
        cmocka_unit_test(test_sse_text),
        cmocka_unit_test(test_json_text),
        cmocka_unit_test(test_csv_text),
        cmocka_unit_test(test_outputs_parse),
        cmocka_unit_test(test_empty_and_meta),
        cmocka_unit_test(test_event_cap),
        cmocka_unit_test(test_names_and_statuses),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
