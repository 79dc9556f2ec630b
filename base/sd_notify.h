/* The service manager's readiness and watchdog protocol (sd_notify(3)), spoken directly: one
 * datagram per message to the AF_UNIX socket named by $NOTIFY_SOCKET ('@' = abstract namespace).
 * No libsystemd: the protocol is a socket and a few words, and the kiosk runs the same without a
 * service manager (no NOTIFY_SOCKET: every call does nothing). */
#ifndef GK_SD_NOTIFY_H
#define GK_SD_NOTIFY_H

#include <stdbool.h>

typedef struct gk_notify {
    int fd;           /* -1: no service manager listening */
    bool watchdog;    /* $WATCHDOG_USEC set for this process: ping from the frame loop */
    bool ready_sent;
    char path[108];   /* sockaddr_un.sun_path */
    int path_len;
} gk_notify;

/* Reads NOTIFY_SOCKET, WATCHDOG_USEC and WATCHDOG_PID from the environment. */
void gk_notify_open(gk_notify *n);
/* Sends one message ("READY=1", "WATCHDOG=1", "STOPPING=1", "STATUS=..."); 0, or -1 when it could
 * not be sent (the kiosk goes on: the manager's watchdog then restarts it, as it should). */
int gk_notify_send(gk_notify *n, const char *msg);
/* After each presented frame: READY=1 the first time, then WATCHDOG=1 when a watchdog is set. */
void gk_notify_frame(gk_notify *n);
void gk_notify_close(gk_notify *n);

#endif
