#!/bin/sh
# `make install` into a DESTDIR gives a kiosk that runs from anywhere: binary, scenes, config,
# systemd unit and udev rules in place, and the installed binary finds its installed scenes.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless
ROOT=$TMP/root
check "make install DESTDIR=... PREFIX=/usr" sh -c "make --no-print-directory BUILD='$BUILD' install DESTDIR='$ROOT' PREFIX=/usr >'$TMP/install.log' 2>&1"
for f in usr/bin/gikiosk usr/share/gikiosk/scenes/cornell.gltf etc/gikiosk/kiosk.ini \
    lib/systemd/system/gikiosk.service lib/udev/rules.d/99-gikiosk.rules; do
    check "installed $f" [ -f "$ROOT/$f" ]
done
# From / there is no config/scenes: the binary must find PREFIX/share/gikiosk/scenes.
check "installed gikiosk lists its installed scenes" sh -c "cd / && '$ROOT/usr/bin/gikiosk' scenes | grep -q '^cornell '"
check "installed gikiosk runs a scene with the installed config" sh -c \
    "cd / && '$ROOT/usr/bin/gikiosk' run --config '$ROOT/etc/gikiosk/kiosk.ini' --platform mock --size 32x24 --frames 1 --scene cornell --method none >/dev/null 2>&1"
finish
