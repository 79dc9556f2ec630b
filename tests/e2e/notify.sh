#!/bin/sh
# sd_notify from the kiosk (board/gikiosk.service is Type=notify with WatchdogSec): against a fake
# service manager -- a datagram socket in $NOTIFY_SOCKET, read by python3 -- a 5-frame mock run
# sends READY=1 after its first frame, one WATCHDOG=1 per later frame (the pings come from the frame
# loop, so frames that stop mean pings that stop), and STOPPING=1 at the end; no watchdog pings
# when WATCHDOG_PID names another process; an abstract socket ('@name') works the same.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless
if ! command -v python3 >/dev/null 2>&1; then
    ok "sd_notify against a fake manager # SKIP no python3 for the fake manager"
    finish
    exit
fi
RUN="$GIKIOSK run --platform mock --size 32x32 --scenes-dir config/scenes --scene cornell --method none --frames 5"

# listen ADDRESS OUT: receives datagrams until STOPPING=1 (or 120 s), one per line into OUT
listen() {
    python3 - "$1" "$2" <<'PY' &
import socket, sys
addr, out = sys.argv[1], sys.argv[2]
s = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
s.bind("\0" + addr[1:] if addr.startswith("@") else addr)
open(out + ".ready", "w").close()
s.settimeout(120)
with open(out, "w") as f:
    try:
        while True:
            m = s.recv(4096).decode()
            f.write(m + "\n")
            f.flush()
            if m == "STOPPING=1":
                break
    except socket.timeout:
        pass
PY
    listener=$!
    i=0
    while [ $i -lt 100 ] && [ ! -e "$2.ready" ]; do sleep 0.1; i=$((i + 1)); done
}

listen "$TMP/notify.sock" "$TMP/msgs"
NOTIFY_SOCKET=$TMP/notify.sock WATCHDOG_USEC=30000000 $RUN >/dev/null 2>&1
rc=$?
wait $listener
check "the run exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "READY=1 first, 4 WATCHDOG=1 (frames 2-5), STOPPING=1 last" \
    [ "$(tr '\n' ' ' <"$TMP/msgs")" = "READY=1 WATCHDOG=1 WATCHDOG=1 WATCHDOG=1 WATCHDOG=1 STOPPING=1 " ]

listen "$TMP/notify2.sock" "$TMP/msgs2"
NOTIFY_SOCKET=$TMP/notify2.sock WATCHDOG_USEC=30000000 WATCHDOG_PID=1 $RUN >/dev/null 2>&1
wait $listener
check "WATCHDOG_PID of another process: no pings" [ "$(tr '\n' ' ' <"$TMP/msgs2")" = "READY=1 STOPPING=1 " ]

name="@gikiosk-test-$$"
listen "$name" "$TMP/msgs3"
NOTIFY_SOCKET=$name $RUN >/dev/null 2>&1
wait $listener
check "abstract socket, no watchdog: READY=1 and STOPPING=1" [ "$(tr '\n' ' ' <"$TMP/msgs3")" = "READY=1 STOPPING=1 " ]
finish
