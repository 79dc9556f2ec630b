/* Bounded reads of regular files (see readfile.h). */
#include "readfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *kind(mode_t m)
{
    return S_ISDIR(m) ? "a directory" : S_ISFIFO(m) ? "a pipe" : S_ISCHR(m) || S_ISBLK(m) ? "a device"
           : S_ISSOCK(m) ? "a socket" : "not a regular file";
}

/* O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused right after. */
static int open_regular(const char *path, const char *what, size_t max_bytes, struct stat *st, gk_err *e)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return gk_fail(e, GK_EINPUT, "%s: cannot open the %s: %s", path, what, strerror(errno));
    if (fstat(fd, st) != 0) {
        int err = errno;
        close(fd);
        return gk_fail(e, GK_EINPUT, "%s: cannot read the %s: %s", path, what, strerror(err));
    }
    if (!S_ISREG(st->st_mode)) {
        close(fd);
        return gk_fail(e, GK_EINPUT, "%s: the %s is %s, not a regular file", path, what, kind(st->st_mode));
    }
    if ((unsigned long long)st->st_size > max_bytes) {
        close(fd);
        return gk_fail(e, GK_EINPUT, "%s: the %s is larger than its limit of %zu bytes (%lld bytes)", path, what,
                       max_bytes, (long long)st->st_size);
    }
    return fd;
}

int gk_check_regular_file(const char *path, const char *what, size_t max_bytes, gk_err *e)
{
    struct stat st;
    int fd = open_regular(path, what, max_bytes, &st, e);
    if (fd < 0)
        return -1;
    close(fd);
    return 0;
}

int gk_read_text_file(const char *path, const char *what, size_t max_bytes, char **text, size_t *len, gk_err *e)
{
    *text = NULL;
    *len = 0;
    struct stat st;
    int fd = open_regular(path, what, max_bytes, &st, e);
    if (fd < 0)
        return -1;
    /* read up to the limit + 1: a file that grows while being read is still bounded */
    size_t cap = (size_t)st.st_size + 1, n = 0;
    char *buf = malloc(cap + 1);
    if (!buf) {
        close(fd);
        return gk_fail(e, GK_ERUNTIME, "%s: out of memory", path);
    }
    for (;;) {
        if (n == cap) {
            if (cap > max_bytes)
                break;
            size_t grown = cap * 2 > max_bytes + 1 ? max_bytes + 1 : cap * 2;
            char *b = realloc(buf, grown + 1);
            if (!b) {
                free(buf);
                close(fd);
                return gk_fail(e, GK_ERUNTIME, "%s: out of memory", path);
            }
            buf = b;
            cap = grown;
        }
        ssize_t got = read(fd, buf + n, cap - n);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0) {
            int err = errno;
            free(buf);
            close(fd);
            return gk_fail(e, GK_EINPUT, "%s: cannot read the %s: %s", path, what, strerror(err));
        }
        if (got == 0)
            break;
        n += (size_t)got;
    }
    close(fd);
    if (n > max_bytes) {
        free(buf);
        return gk_fail(e, GK_EINPUT, "%s: the %s is larger than its limit of %zu bytes", path, what, max_bytes);
    }
    buf[n] = '\0';
    if (memchr(buf, '\0', n)) {
        free(buf);
        return gk_fail(e, GK_EINPUT, "%s: binary data (a NUL byte) in the %s, a text file", path, what);
    }
    *text = buf;
    *len = n;
    return 0;
}
