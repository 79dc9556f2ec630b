#include "err.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int gk_fail(gk_err *e, int code, const char *fmt, ...)
{
    if (!e)
        return -1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
    e->code = code;
    return -1;
}

int gk_fail_prefix(gk_err *e, const char *fmt, ...)
{
    if (!e)
        return -1;
    char prefix[512], old[sizeof e->msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(prefix, sizeof prefix, fmt, ap);
    va_end(ap);
    memcpy(old, e->msg, sizeof old);
    /* Build into a buffer large enough for both, then truncate into e->msg: keeps the compiler's
       format-truncation check quiet without hiding real truncation elsewhere. */
    char combined[sizeof prefix + sizeof old];
    snprintf(combined, sizeof combined, "%s%s", prefix, old);
    snprintf(e->msg, sizeof e->msg, "%.*s", (int)sizeof e->msg - 1, combined);
    return -1;
}

void gk_err_clear(gk_err *e)
{
    if (e) {
        e->code = GK_OK;
        e->msg[0] = '\0';
    }
}
