/* sd_notify protocol without libsystemd (see sd_notify.h). */
#include "sd_notify.h"

#include <errno.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

void gk_notify_open(gk_notify *n)
{
    memset(n, 0, sizeof *n);
    n->fd = -1;
    const char *sock = getenv("NOTIFY_SOCKET");
    size_t len = sock ? strlen(sock) : 0;
    if (len == 0 || len >= sizeof n->path || (sock[0] != '/' && sock[0] != '@'))
        return;
    memcpy(n->path, sock, len);
    if (n->path[0] == '@')
        n->path[0] = '\0'; /* abstract socket: no NUL terminator counted */
    n->path_len = (int)len;
    n->fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    /* The watchdog is ours when WATCHDOG_USEC is set and WATCHDOG_PID, if set, names us. */
    const char *usec = getenv("WATCHDOG_USEC"), *pid = getenv("WATCHDOG_PID");
    n->watchdog = usec && strtoull(usec, NULL, 10) > 0 && (!pid || strtol(pid, NULL, 10) == (long)getpid());
}

int gk_notify_send(gk_notify *n, const char *msg)
{
    if (n->fd < 0)
        return 0;
    struct sockaddr_un addr;
    memset(&addr, 0, sizeof addr);
    addr.sun_family = AF_UNIX;
    memcpy(addr.sun_path, n->path, (size_t)n->path_len);
    socklen_t addr_len = (socklen_t)(offsetof(struct sockaddr_un, sun_path) + (size_t)n->path_len +
                                     (n->path[0] ? 1 : 0));
    ssize_t sent;
    do
        sent = sendto(n->fd, msg, strlen(msg), MSG_NOSIGNAL, (struct sockaddr *)&addr, addr_len);
    while (sent < 0 && errno == EINTR);
    return sent == (ssize_t)strlen(msg) ? 0 : -1;
}

void gk_notify_frame(gk_notify *n)
{
    if (n->fd < 0)
        return;
    if (!n->ready_sent) {
        /* ready: the display shows the first frame */
        n->ready_sent = gk_notify_send(n, "READY=1") == 0;
        return;
    }
    /* One datagram a frame (a sendto of 10 bytes): a frame loop that stops, a GPU that hangs in a
       draw or a flip, stops the pings, and the manager restarts the kiosk after WatchdogSec. */
    if (n->watchdog)
        gk_notify_send(n, "WATCHDOG=1");
}

void gk_notify_close(gk_notify *n)
{
    if (n->fd >= 0) {
        gk_notify_send(n, "STOPPING=1");
        close(n->fd);
    }
    n->fd = -1;
}
