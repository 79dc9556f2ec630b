/* Error reporting shared by every module, the platform layer included (base/ sits below both
 * platform/ and app/, so the platform reports errors without reaching up into app/): a failing function fills a gk_err with a message that
 * names what is wrong and where (file:line when there is one) and the exit class it belongs to.
 * main() prints the message and exits with the code: 2 for bad usage or bad input, 1 for runtime
 * failures (GPU, display, I/O). */
#ifndef GK_ERR_H
#define GK_ERR_H

#include <stddef.h>

enum { GK_OK = 0, GK_ERUNTIME = 1, GK_EINPUT = 2 };

typedef struct gk_err {
    int code;        /* GK_OK, GK_ERUNTIME or GK_EINPUT */
    char msg[1024];
} gk_err;

/* Sets e (if not NULL) and returns -1, so callers can write `return gk_fail(e, GK_EINPUT, ...)`. */
int gk_fail(gk_err *e, int code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Prefixes the message already in e with more context ("config/kiosk.ini: " + msg). */
int gk_fail_prefix(gk_err *e, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void gk_err_clear(gk_err *e);

#endif
