#!/bin/sh
# Both libgpiod APIs must compile: the build uses Debian 12's libgpiod 1.6 (platform/gpiod_v1.c);
# this compiles platform/gpiod_v2.c against libgpiod 2.x from bookworm-backports, unpacked into a
# private prefix (tools/gpiod2-prefix.sh, also `make gpiod2-check`). Without network access to the
# archive it reports a TAP skip, naming why.
. tests/e2e/lib.sh
fresh=true
[ -f "$BUILD/gpiod2/root/usr/include/gpiod.h" ] && fresh=false
out=$(sh tools/gpiod2-prefix.sh "$BUILD" 2>&1)
rc=$?
echo "$out" | sed 's/^/# /'
case $out in
*"gpiod2: OK"*) ok "platform/gpiod_v2.c compiles and links against libgpiod 2.x" ;;
*"gpiod2: SKIP"*) ok "platform/gpiod_v2.c against libgpiod 2.x # SKIP $(echo "$out" | sed -n 's/.*gpiod2: SKIP: //p' | head -1)" ;;
*) not_ok "platform/gpiod_v2.c against libgpiod 2.x (exit $rc)" ;;
esac
# When its private apt ran (a fresh prefix), apt's binary caches went to the private directory,
# not over the system's /var/cache/apt.
if $fresh && echo "$out" | grep -q "gpiod2: OK"; then
    check "the private apt kept its caches in $BUILD/gpiod2/apt/cache" \
        [ -f "$BUILD/gpiod2/apt/cache/pkgcache.bin" -a -f "$BUILD/gpiod2/apt/cache/srcpkgcache.bin" ]
fi
finish
