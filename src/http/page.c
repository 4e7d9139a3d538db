/* src/http/page.c - the browser page: GET / and the files beside it (web/index.html, app.js, style.css, ...).
 *
 * At start-up every regular file directly inside --web-dir (default "web": relative to the working
 * directory, else to the binary's directory or its parent, else for the default an installed
 * ../share/dashpot/web beside the binary's directory; data_path in config.c) whose name is plain
 * ([A-Za-z0-9_-][A-Za-z0-9._-]*, at most 63 bytes) and whose extension has a known content type is read into
 * memory, with a strong ETag (64-bit FNV-1a of its bytes). Requests are answered from that table only, by
 * exact name: "/" is index.html, "/NAME" is NAME. Nothing a URL says ever reaches the file system, so "..",
 * "%2e%2e", subdirectories, dot files and symlinks (opened with O_NOFOLLOW) cannot be served; any other
 * path is the ordinary 404 problem document.
 *
 * Caching: Cache-Control: no-cache with the ETag (a browser revalidates and gets 304 while the file is
 * unchanged), so a new daemon with new files is picked up on the next load. The page gets a
 * Content-Security-Policy that allows nothing but the daemon itself ('self'), and blob: images (the
 * stability map's SVG): no CDN, no fonts from the web. Changed files are read again on restart.
 */
#include <dirent.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "http.h"

#define WEB_MAX_FILES 64
#define WEB_MAX_BYTES (4u << 20) /* per file */
#define WEB_NAME_MAX 64

typedef struct web_file {
    char name[WEB_NAME_MAX];
    const char *type;
    char *data;
    size_t len;
    char etag[20]; /* "\"" 16 hex digits "\"" */
} web_file;

struct web {
    int n;
    char dir[4096]; /* where the files were found (for the start-up line) */
    web_file file[WEB_MAX_FILES];
};

static const struct {
    const char *ext, *type;
} types[] = {
    { ".html", "text/html; charset=utf-8" },
    { ".js", "text/javascript; charset=utf-8" },
    { ".mjs", "text/javascript; charset=utf-8" },
    { ".css", "text/css; charset=utf-8" },
    { ".svg", "image/svg+xml" },
    { ".png", "image/png" },
    { ".ico", "image/x-icon" },
    { ".json", "application/json" },
    { ".txt", "text/plain; charset=utf-8" },
};

#define CSP "default-src 'self'; img-src 'self' blob: data:; object-src 'none'; base-uri 'none'; form-action 'none'"

/* The content type of a plain file name, NULL if the name is not one the page may serve. */
static const char *type_of(const char *name)
{
    size_t n = strlen(name);
    if (n == 0 || n >= WEB_NAME_MAX || name[0] == '.')
        return NULL;
    for (size_t i = 0; i < n; i++) {
        char ch = name[i];
        if (!((ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_' ||
              ch == '-' || ch == '.'))
            return NULL;
    }
    if (strstr(name, "..") != NULL)
        return NULL;
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++) {
        size_t e = strlen(types[i].ext);
        if (n > e && strcmp(name + n - e, types[i].ext) == 0)
            return types[i].type;
    }
    return NULL;
}

/* Reads a regular file (no symlink) below the directory fd; NULL if it cannot or it is over the limit. */
static char *read_at(int dfd, const char *name, size_t *len)
{
    int fd = openat(dfd, name, O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0)
        return NULL;
    struct stat st;
    char *data = NULL;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && (size_t)st.st_size <= WEB_MAX_BYTES &&
        (data = malloc((size_t)st.st_size + 1)) != NULL) {
        size_t got = 0, want = (size_t)st.st_size;
        ssize_t k = 0;
        while (got < want && (k = read(fd, data + got, want - got)) > 0)
            got += (size_t)k;
        if (k < 0 || got != want) {
            free(data);
            data = NULL;
        } else {
            *len = got;
        }
    }
    close(fd);
    return data;
}

static void etag_of(web_file *f)
{
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < f->len; i++)
        h = (h ^ (unsigned char)f->data[i]) * 1099511628211ull;
    snprintf(f->etag, sizeof f->etag, "\"%016llx\"", (unsigned long long)h);
}

/* Loads every servable file of dir into w; returns 0 if the directory could be opened. */
static int load_dir(struct web *w, const char *dir)
{
    DIR *d = opendir(dir);
    if (d == NULL)
        return -1;
    snprintf(w->dir, sizeof w->dir, "%s", dir);
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        const char *type = type_of(e->d_name);
        if (type == NULL)
            continue;
        if (w->n == WEB_MAX_FILES) {
            log_line("warning: %s: more than %d files; %s and the rest are not served", dir, WEB_MAX_FILES,
                     e->d_name);
            break;
        }
        web_file *f = &w->file[w->n];
        if ((f->data = read_at(dirfd(d), e->d_name, &f->len)) == NULL)
            continue; /* not a regular file, a symlink, unreadable or too large */
        snprintf(f->name, sizeof f->name, "%s", e->d_name);
        f->type = type;
        etag_of(f);
        w->n++;
    }
    closedir(d);
    return 0;
}

void page_load(server *s)
{
    struct web *w = calloc(1, sizeof *w);
    if (w == NULL)
        return;
    const char *dir = s->cfg.web_dir;
    char path[sizeof w->dir];
    int is_default = strcmp(dir, DEFAULT_WEB_DIR) == 0;
    int ok = data_path(dir, is_default ? INSTALLED_WEB_DIR : NULL, 1, path, sizeof path) == 0 &&
             load_dir(w, path) == 0;
    if (!ok)
        log_line("warning: web directory %s not found; / will answer 404", dir);
    else
        log_line("serving %d web file%s from %s", w->n, w->n == 1 ? "" : "s", w->dir);
    s->web = w;
}

void page_free(server *s)
{
    if (s->web == NULL)
        return;
    for (int i = 0; i < s->web->n; i++)
        free(s->web->file[i].data);
    free(s->web);
    s->web = NULL;
}

static const web_file *lookup(const server *s, const char *url)
{
    if (s->web == NULL || url[0] != '/')
        return NULL;
    const char *name = url[1] ? url + 1 : "index.html";
    for (int i = 0; i < s->web->n; i++)
        if (strcmp(s->web->file[i].name, name) == 0)
            return &s->web->file[i];
    return NULL;
}

int page_route(const server *s, const char *url)
{
    return strcmp(url, "/") == 0 || lookup(s, url) != NULL;
}

/* If-None-Match lists the ETag (or is "*"): weak comparison, as RFC 9110 section 13.1.2 asks. */
static int not_modified(struct MHD_Connection *c, const char *etag)
{
    const char *inm = MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_IF_NONE_MATCH);
    if (inm == NULL)
        return 0;
    size_t elen = strlen(etag);
    for (const char *p = inm; *p;) {
        while (*p == ' ' || *p == '\t' || *p == ',')
            p++;
        if (*p == '*')
            return 1;
        if (strncmp(p, "W/", 2) == 0)
            p += 2;
        if (strncmp(p, etag, elen) == 0 && (p[elen] == '\0' || p[elen] == ',' || p[elen] == ' ' || p[elen] == '\t'))
            return 1;
        while (*p && *p != ',')
            p++;
    }
    return 0;
}

enum MHD_Result handle_page(struct MHD_Connection *c, request *r)
{
    const web_file *f = lookup(r->srv, r->path);
    if (f == NULL)
        return respond_problem(c, r, 404, NULL,
                               strcmp(r->path, "/") == 0 ? "the web page was not found at start-up (--web-dir)"
                                                         : "no such route",
                               NULL, NULL);
    int fresh = not_modified(c, f->etag);
    struct MHD_Response *resp = fresh ? MHD_create_response_from_buffer(0, (char *)"", MHD_RESPMEM_PERSISTENT)
                                      : MHD_create_response_from_buffer(f->len, f->data, MHD_RESPMEM_PERSISTENT);
    if (resp == NULL)
        return MHD_NO;
    if (!fresh) /* (MHD writes Content-Length: 0 on the 304; clients take no body from a 304 either way) */
        MHD_add_response_header(resp, MHD_HTTP_HEADER_CONTENT_TYPE, f->type);
    MHD_add_response_header(resp, MHD_HTTP_HEADER_CACHE_CONTROL, "no-cache");
    MHD_add_response_header(resp, MHD_HTTP_HEADER_ETAG, f->etag);
    MHD_add_response_header(resp, MHD_HTTP_HEADER_X_CONTENT_TYPE_OPTIONS, "nosniff");
    if (strncmp(f->type, "text/html", 9) == 0) {
        MHD_add_response_header(resp, MHD_HTTP_HEADER_CONTENT_SECURITY_POLICY, CSP);
        MHD_add_response_header(resp, "Referrer-Policy", "no-referrer");
    }
    int status = fresh ? MHD_HTTP_NOT_MODIFIED : MHD_HTTP_OK;
    r->status = status;
    r->bytes = fresh ? 0 : f->len;
    enum MHD_Result ok = MHD_queue_response(c, (unsigned)status, resp);
    MHD_destroy_response(resp);
    return ok;
}
