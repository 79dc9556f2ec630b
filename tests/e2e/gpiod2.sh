#!/bin/sh
# Both libgpiod APIs must compile: the build uses Debian 12's libgpiod 1.6 (platform/gpiod_v1.c);
# this compiles platform/gpiod_v2.c against libgpiod 2.x from bookworm-backports, unpacked into a
# private prefix (tools/gpiod2-prefix.sh, also `make gpiod2-check`). Without network access to the
# archive it reports a TAP skip, naming why.
. tests/e2e/lib.sh
out=$(sh tools/gpiod2-prefix.sh "$BUILD" 2>&1)
rc=$?
echo "$out" | sed 's/^/# /'
case $out in
*"gpiod2: OK"*) ok "platform/gpiod_v2.c compiles and links against libgpiod 2.x" ;;
*"gpiod2: SKIP"*) ok "platform/gpiod_v2.c against libgpiod 2.x # SKIP $(echo "$out" | sed -n 's/.*gpiod2: SKIP: //p' | head -1)" ;;
*) not_ok "platform/gpiod_v2.c against libgpiod 2.x (exit $rc)" ;;
esac
finish
