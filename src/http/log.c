/* src/http/log.c - dashpotd's log: one line per request on stderr, start-up and shutdown lines.
 *
 *   2026-11-21T08:00:00.123Z POST "/v1/simulate" 200 1234567B 812.345ms
 *
 * The method and path come from the client: every byte outside printable ASCII, and the quote and backslash,
 * is written as \xHH, so a request cannot forge log lines or terminal escapes. Each line goes out in one
 * write(2), so lines from different threads never interleave.
 *
 * The request line is put together by hand (the date from the day count, digits by division): gmtime_r
 * takes glibc's time-zone lock and printf's %.3f is slow, and together they were a tenth of a small
 * request's CPU. Durations are written from whole microseconds, rounded.
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "http.h"

/* v in exactly `width` decimal digits (zero-padded; v < 10^width); returns the end. */
static char *digits(char *p, unsigned long long v, int width)
{
    for (int i = width - 1; i >= 0; i--, v /= 10)
        p[i] = (char)('0' + v % 10);
    return p + width;
}

/* v in decimal, as many digits as it takes; returns the end. */
static char *decimal(char *p, unsigned long long v)
{
    int width = 1;
    for (unsigned long long t = v; t >= 10; t /= 10)
        width++;
    return digits(p, v, width);
}

/* "YYYY-MM-DDTHH:MM:SS.mmmZ " (UTC, 25 bytes) into out, which has room for 32. The civil date of a day
 * count is H. Hinnant's days_from_civil inverted (proleptic Gregorian, eras of 400 years). */
static size_t timestamp(char out[32])
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    long long days = ts.tv_sec / 86400, secs = ts.tv_sec % 86400;
    if (secs < 0)
        secs += 86400, days--;
    long long z = days + 719468, era = (z >= 0 ? z : z - 146096) / 146097;
    long long doe = z - era * 146097;                                  /* [0, 146096] */
    long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365; /* [0, 399] */
    long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100), mp = (5 * doy + 2) / 153;
    long long d = doy - (153 * mp + 2) / 5 + 1, m = mp < 10 ? mp + 3 : mp - 9, y = yoe + era * 400 + (m <= 2);
    char *p = out;
    if (y < 0 || y > 9999)
        y = 0; /* outside what the format can say; never on a real clock */
    p = digits(p, (unsigned long long)y, 4);
    *p++ = '-';
    p = digits(p, (unsigned long long)m, 2);
    *p++ = '-';
    p = digits(p, (unsigned long long)d, 2);
    *p++ = 'T';
    p = digits(p, (unsigned long long)(secs / 3600), 2);
    *p++ = ':';
    p = digits(p, (unsigned long long)(secs / 60 % 60), 2);
    *p++ = ':';
    p = digits(p, (unsigned long long)(secs % 60), 2);
    *p++ = '.';
    p = digits(p, (unsigned long long)(ts.tv_nsec / 1000000), 3);
    *p++ = 'Z';
    *p++ = ' ';
    return (size_t)(p - out);
}

/* Copies s into out escaped, within cap bytes (NUL included); returns the length written. */
static size_t escape(char *out, size_t cap, const char *s)
{
    static const char hex[] = "0123456789abcdef";
    size_t n = 0;
    for (; *s && n + 5 < cap; s++) {
        unsigned char c = (unsigned char)*s;
        if (c < 0x20 || c >= 0x7f || c == '"' || c == '\\') {
            out[n++] = '\\';
            out[n++] = 'x';
            out[n++] = hex[c >> 4];
            out[n++] = hex[c & 15];
        } else {
            out[n++] = (char)c;
        }
    }
    out[n] = '\0';
    return n;
}

static void emit(const char *line, size_t n)
{
    ssize_t w = write(STDERR_FILENO, line, n);
    (void)w; /* nowhere left to report a failing stderr */
}

/* "METHOD \"PATH\" STATUS BYTESB MS.mmmms\n" after the time; the escaped method and path are at most 75
 * and 1023 bytes, so the line fits. */
void log_request(const request *r, double seconds)
{
    char line[1536];
    char *p = line + timestamp(line);
    p += escape(p, 80, r->method);
    *p++ = ' ';
    *p++ = '"';
    p += escape(p, 1100, r->path);
    *p++ = '"';
    *p++ = ' ';
    p = decimal(p, (unsigned long long)(r->status > 0 ? r->status : 0));
    *p++ = ' ';
    p = decimal(p, r->bytes);
    *p++ = 'B';
    *p++ = ' ';
    double us = seconds > 0 ? seconds * 1e6 + 0.5 : 0;
    unsigned long long u = us < 1e18 ? (unsigned long long)us : 0;
    p = decimal(p, u / 1000);
    *p++ = '.';
    p = digits(p, u % 1000, 3);
    memcpy(p, "ms\n", 3);
    emit(line, (size_t)(p + 3 - line));
}

void log_line(const char *fmt, ...)
{
    char line[1024];
    size_t n = timestamp(line);
    va_list ap;
    va_start(ap, fmt);
    int m = vsnprintf(line + n, sizeof line - n - 1, fmt, ap);
    va_end(ap);
    if (m < 0)
        return;
    n += (size_t)m < sizeof line - n - 1 ? (size_t)m : sizeof line - n - 2;
    line[n++] = '\n';
    emit(line, n);
}
