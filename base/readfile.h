/* Reading an input file without hanging or running out of memory: only a regular file is read (a
 * directory, a device such as /dev/zero, a FIFO are refused by name: they would read as empty,
 * forever, or block), and only up to a limit the caller documents. */
#ifndef GK_READFILE_H
#define GK_READFILE_H

#include <stddef.h>

#include "err.h"

/* Reads the whole file into a NUL-terminated buffer (*text, free() it; *len without the NUL).
 * what names the kind of file in messages ("config", "button script"). Errors, GK_EINPUT, each
 * naming path: cannot open (the system's reason), not a regular file, larger than max_bytes, a
 * read error, or a NUL byte (binary data in a text file). */
int gk_read_text_file(const char *path, const char *what, size_t max_bytes, char **text, size_t *len, gk_err *e);
/* Checks, without reading, that path is a regular file of at most max_bytes (for readers that
 * open files themselves, such as OpenImageIO). */
int gk_check_regular_file(const char *path, const char *what, size_t max_bytes, gk_err *e);

#endif
