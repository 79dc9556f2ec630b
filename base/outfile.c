/* Temporary file + rename for every output (see outfile.h). */
#include "outfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* DIR/.NAME.XXXXXX.EXT for path DIR/NAME.EXT; *suffix_len: the length of ".EXT" for mkstemps. */
static char *temp_template(const char *path, int *suffix_len)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    if (!dot || dot == base)
        dot = base + strlen(base);
    size_t dir_len = (size_t)(base - path), name_len = (size_t)(dot - base), ext_len = strlen(dot);
    char *t = malloc(dir_len + 1 + name_len + 8 + ext_len + 1);
    if (!t)
        return NULL;
    memcpy(t, path, dir_len);
    t[dir_len] = '.';
    memcpy(t + dir_len + 1, base, name_len);
    memcpy(t + dir_len + 1 + name_len, ".XXXXXX", 7);
    memcpy(t + dir_len + 1 + name_len + 7, dot, ext_len + 1);
    *suffix_len = (int)ext_len;
    return t;
}

static int create(gk_outfile *o, const char *path, bool open_stream, gk_err *e)
{
    memset(o, 0, sizeof *o);
    int suffix_len = 0;
    if (!path || !*path)
        return gk_fail(e, GK_EINPUT, "empty output file name");
    o->path = strdup(path);
    o->tmp = temp_template(path, &suffix_len);
    if (!o->path || !o->tmp) {
        gk_outfile_discard(o);
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory", path);
    }
    int fd = mkstemps(o->tmp, suffix_len);
    if (fd < 0) {
        int err = errno;
        free(o->tmp);
        o->tmp = NULL;
        gk_outfile_discard(o);
        return gk_fail(e, GK_ERUNTIME, "%s: cannot write: %s", path, strerror(err));
    }
    /* mkstemps makes it 0600; an output is an ordinary file for its user (0666 less the umask). */
    mode_t mask = umask(0);
    umask(mask);
    fchmod(fd, 0666 & ~mask);
    if (!open_stream) {
        close(fd);
        return 0;
    }
    if (!(o->f = fdopen(fd, "w"))) {
        int err = errno;
        close(fd);
        gk_outfile_discard(o);
        return gk_fail(e, GK_ERUNTIME, "%s: cannot write: %s", path, strerror(err));
    }
    return 0;
}

int gk_outfile_open(gk_outfile *o, const char *path, gk_err *e) { return create(o, path, true, e); }

int gk_outfile_reserve(gk_outfile *o, const char *path, gk_err *e) { return create(o, path, false, e); }

/* fsync through a fresh descriptor: the writer (OIIO, gnuplot) closed its own. */
static int sync_file(const char *p)
{
    int fd = open(p, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return -1;
    int rc = fsync(fd);
    int err = errno;
    close(fd);
    errno = err;
    return rc;
}

int gk_outfile_commit(gk_outfile *o, gk_err *e)
{
    if (!o->tmp)
        return gk_fail(e, GK_ERUNTIME, "%s: output already closed", o->path ? o->path : "?");
    int err = 0;
    if (o->f) {
        /* ferror catches a write that failed earlier (the stream keeps the flag); fflush and fsync
           the ones still buffered; fclose the last. */
        errno = 0;
        if (fflush(o->f) != 0 || ferror(o->f))
            err = errno ? errno : EIO;
        if (!err && fsync(fileno(o->f)) != 0 && errno != EINVAL) /* EINVAL: a file that cannot sync */
            err = errno;
        if (fclose(o->f) != 0 && !err)
            err = errno;
        o->f = NULL;
    } else if (sync_file(o->tmp) != 0 && errno != EINVAL) {
        err = errno;
    }
    if (!err && rename(o->tmp, o->path) != 0)
        err = errno;
    if (err) {
        int rc = gk_fail(e, GK_ERUNTIME, "%s: cannot write: %s", o->path, strerror(err));
        gk_outfile_discard(o);
        return rc;
    }
    free(o->tmp);
    o->tmp = NULL;
    gk_outfile_discard(o);
    return 0;
}

void gk_outfile_discard(gk_outfile *o)
{
    if (o->f)
        fclose(o->f);
    if (o->tmp)
        unlink(o->tmp);
    free(o->tmp);
    free(o->path);
    memset(o, 0, sizeof *o);
}
