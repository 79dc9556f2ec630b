#include "log.h"

#include <stdarg.h>
#include <stdio.h>

static int log_quiet; /* set once at start-up by tests; not per-frame state */

void gk_log_set_quiet(int quiet) { log_quiet = quiet; }

void gk_log(const char *fmt, ...)
{
    if (log_quiet)
        return;
    va_list ap;
    va_start(ap, fmt);
    fputs("gikiosk: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}
