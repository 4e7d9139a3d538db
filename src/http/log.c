/* src/http/log.c - dashpotd's log: one line per request on stderr, start-up and shutdown lines.
 *
 *   2026-11-21T08:00:00.123Z POST "/v1/simulate" 200 1234567B 812.345ms
 *
 * The method and path come from the client: every byte outside printable ASCII, and the quote and backslash,
 * is written as \xHH, so a request cannot forge log lines or terminal escapes. Each line goes out in one
 * write(2), so lines from different threads never interleave.
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "http.h"

static size_t timestamp(char *out, size_t cap)
{
    struct timespec ts;
    struct tm tm;
    clock_gettime(CLOCK_REALTIME, &ts);
    gmtime_r(&ts.tv_sec, &tm);
    size_t n = strftime(out, cap, "%Y-%m-%dT%H:%M:%S", &tm);
    int m = snprintf(out + n, cap - n, ".%03ldZ ", ts.tv_nsec / 1000000);
    return n + (m > 0 ? (size_t)m : 0);
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

void log_request(const request *r, double seconds)
{
    char line[1536], method[80], path[1100];
    escape(method, sizeof method, r->method);
    escape(path, sizeof path, r->path);
    size_t n = timestamp(line, sizeof line);
    int m = snprintf(line + n, sizeof line - n, "%s \"%s\" %d %lluB %.3fms\n", method, path, r->status,
                     r->bytes, seconds * 1e3);
    if (m > 0)
        emit(line, n + ((size_t)m < sizeof line - n ? (size_t)m : sizeof line - n - 1));
}

void log_line(const char *fmt, ...)
{
    char line[1024];
    size_t n = timestamp(line, sizeof line);
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
