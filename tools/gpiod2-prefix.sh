#!/bin/sh
# Compile check of platform/gpiod_v2.c against libgpiod 2.x on Debian 12, which ships only 1.6:
# downloads libgpiod-dev + libgpiod3 from bookworm-backports with a private apt state (no root, no
# change to the system's sources), unpacks them under BUILD/gpiod2/, and compiles gpiod_v2.c
# against that prefix. When the archive cannot be reached it says so and exits 0 (a skip), so
# tests do not fail offline. Usage: tools/gpiod2-prefix.sh [BUILD]
set -u
BUILD=${1:-build}
PREFIX=$BUILD/gpiod2
APT=$PREFIX/apt
MIRROR=${GK_BACKPORTS_MIRROR:-http://deb.debian.org/debian}
# Its own cache directory too: apt's binary caches (pkgcache.bin, srcpkgcache.bin) would otherwise
# be rebuilt from the backports list over the system's in /var/cache/apt.
mkdir -p "$APT/lists/partial" "$APT/archives/partial" "$APT/cache" "$PREFIX/root"
echo "deb $MIRROR bookworm-backports main" >"$APT/sources.list"
: >"$APT/status"
case $APT in /*) ;; *) APT=$PWD/$APT ;; esac # apt's Dir options need absolute paths
APT_OPTS="-o Dir::Etc::sourcelist=$APT/sources.list -o Dir::Etc::sourceparts=- \
 -o Dir::State::Lists=$APT/lists -o Dir::State::status=$APT/status \
 -o Dir::Cache=$APT/cache -o Dir::Cache::pkgcache=$APT/cache/pkgcache.bin \
 -o Dir::Cache::srcpkgcache=$APT/cache/srcpkgcache.bin \
 -o Dir::Cache::archives=$APT/archives -o Debug::NoLocking=1 -o APT::Get::List-Cleanup=0"
skip() { echo "gpiod2: SKIP: $*"; exit 0; }

if [ ! -f "$PREFIX/root/usr/include/gpiod.h" ]; then
    # shellcheck disable=SC2086
    apt-get $APT_OPTS update >"$PREFIX/update.log" 2>&1 ||
        skip "apt-get update of bookworm-backports failed: $(tail -1 "$PREFIX/update.log")"
    # shellcheck disable=SC2086
    (cd "$PREFIX" && apt-get $APT_OPTS download -t bookworm-backports libgpiod-dev libgpiod3) \
        >"$PREFIX/download.log" 2>&1 ||
        skip "apt-get download libgpiod-dev libgpiod3 failed: $(tail -1 "$PREFIX/download.log")"
    for deb in "$PREFIX"/*.deb; do
        dpkg-deb -x "$deb" "$PREFIX/root" || skip "dpkg-deb -x $deb failed"
    done
fi
ROOT=$PREFIX/root
VERSION=$(sed -n 's/^Version: *//p' "$ROOT"/usr/lib/*/pkgconfig/libgpiod.pc 2>/dev/null)
case "$VERSION" in 2.*) ;; *) skip "unpacked libgpiod is '$VERSION', not 2.x" ;; esac
LIBDIR=$(dirname "$(ls "$ROOT"/usr/lib/*/libgpiod.so* | head -1)")
mkdir -p "$BUILD/obj/gpiod2"
# -DGK_GPIOD_MAJOR=2 and only the v2 prefix's gpiod.h: the system's 1.6 header must not be seen.
cc -std=c11 -O2 -Wall -Wextra -Werror -D_GNU_SOURCE -DGK_GPIOD_MAJOR=2 -I"$ROOT/usr/include" -Iapp -I. \
    -c platform/gpiod_v2.c -o "$BUILD/obj/gpiod2/gpiod_v2.o" || { echo "gpiod2: FAIL: gpiod_v2.c does not compile against libgpiod $VERSION"; exit 1; }
# Link check: every gpiod_* symbol gpiod_v2.o uses is defined by the v2 library.
missing=$(nm -u "$BUILD/obj/gpiod2/gpiod_v2.o" | awk '/gpiod_/ {print $2}' | while read -r sym; do
    nm -D --defined-only "$LIBDIR"/libgpiod.so.3* 2>/dev/null | grep -qw "$sym" || echo "$sym"; done)
[ -z "$missing" ] || { echo "gpiod2: FAIL: not in libgpiod $VERSION: $missing"; exit 1; }
echo "gpiod2: OK: platform/gpiod_v2.c compiles and its symbols resolve against libgpiod $VERSION ($ROOT)"
