/* src/http/bench_static.c - GET /bench/static (only with --bench-static FILE): the peer of the simulate
 * stream in bench/http.sh. It sends a file's bytes through the very path a stream takes (chunked, a content
 * reader called as the socket drains, blocks of the same size), so the benchmark's ratio isolates what
 * running the solver and encoding cost against merely moving bytes.
 */
#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include "http.h"

#define READ_BLOCK (64u << 10)

typedef struct file_stream {
    int fd;
    request *r;
} file_stream;

static ssize_t file_read(void *cls, uint64_t pos, char *buf, size_t max)
{
    file_stream *fs = cls;
    ssize_t n = pread(fs->fd, buf, max, (off_t)pos);
    if (n == 0)
        return MHD_CONTENT_READER_END_OF_STREAM;
    if (n < 0)
        return MHD_CONTENT_READER_END_WITH_ERROR;
    fs->r->bytes += (unsigned long long)n;
    return n;
}

static void file_free(void *cls)
{
    file_stream *fs = cls;
    close(fs->fd);
    request_release(fs->r);
    free(fs);
}

enum MHD_Result handle_bench_static(struct MHD_Connection *c, request *r)
{
    file_stream *fs = malloc(sizeof *fs);
    if (fs == NULL)
        return respond_status(c, r, DP_ENOMEM, NULL, NULL);
    fs->fd = open(r->srv->cfg.bench_static, O_RDONLY | O_CLOEXEC);
    if (fs->fd < 0) {
        free(fs);
        return respond_problem(c, r, 404, NULL, "the --bench-static file cannot be opened", NULL, NULL);
    }
    fs->r = r;
    atomic_fetch_add(&r->refs, 1);
    struct MHD_Response *resp = MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, READ_BLOCK, file_read, fs,
                                                                  file_free);
    if (resp == NULL) {
        file_free(fs);
        return MHD_NO;
    }
    MHD_add_response_header(resp, MHD_HTTP_HEADER_CONTENT_TYPE, "application/x-ndjson");
    r->status = 200;
    enum MHD_Result ok = MHD_queue_response(c, 200, resp);
    MHD_destroy_response(resp);
    return ok;
}
