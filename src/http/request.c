/* src/http/request.c - a request's lifetime: created on its first callback, shared by reference with the
 * worker that runs it, freed by whoever lets go last; and the monotonic clock the deadlines read. Below the
 * server, the routes and the deadline sweeper, which all use them (no circle between them). */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "http.h"

double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* snprintf(dst, cap, "%s", src) without printf: src cut to cap - 1 bytes. */
static void copy_cut(char *dst, size_t cap, const char *src)
{
    size_t n = strnlen(src, cap - 1);
    memcpy(dst, src, n);
    dst[n] = '\0';
}

request *request_new(server *s, const char *method, const char *url)
{
    request *r = calloc(1, sizeof *r);
    if (r == NULL)
        return NULL;
    r->srv = s;
    atomic_init(&r->refs, 1);
    r->t_start = now_seconds();
    copy_cut(r->method, sizeof r->method, method);
    copy_cut(r->path, sizeof r->path, url);
    return r;
}

void request_release(request *r)
{
    if (r == NULL || atomic_fetch_sub(&r->refs, 1) != 1)
        return;
    dp_buf_free(&r->body);
    free(r);
}
