#!/bin/sh
# `make run`: the showcase. With a display (a /dev/dri/card*), the kiosk on KMS with the board's
# config, until stopped. Without one, a bounded offscreen tour on the mock platform: every scene of
# the playlist for DWELL virtual seconds (default 1, i.e. 60 frames) at 640x360, one capture per
# scene in out/, per-frame stats in out/showcase-stats.csv, and a summary line per scene (frames,
# warm-up frames apart, median, p95 and p99 of the judged frames, method, budgets) printed by the
# kiosk at the end.
# Usage: tools/showcase.sh BIN   (environment: DWELL=seconds, SIZE=WxH, CONFIG=file)
set -eu
BIN=${1:-build/gikiosk}
CONFIG=${CONFIG:-config/kiosk.ini}
DWELL=${DWELL:-1}
SIZE=${SIZE:-640x360}

if ls /dev/dri/card* >/dev/null 2>&1; then
    echo "showcase: display device found; running the kiosk on KMS (Ctrl-C ends it)"
    exec "$BIN" run --platform auto --config "$CONFIG"
fi

export EGL_PLATFORM=surfaceless
mkdir -p out
tmp=$(mktemp "${TMPDIR:-/tmp}/gikiosk-showcase.XXXXXX")
trap 'rm -f "$tmp"' EXIT
# The board's config with a short dwell (a later key overrides an earlier one) and no input pause.
{ cat "$CONFIG"; printf '\n[playlist]\ndwell_s = %s\npause_after_input_s = 0\n' "$DWELL"; } >"$tmp"

# The playlist: [playlist] scenes when set, else every scene file in config/scenes.
list=$(sed -n 's/^[[:space:]]*scenes[[:space:]]*=[[:space:]]*//p' "$CONFIG" | tail -1)
if [ -n "$list" ]; then
    n=$(echo "$list" | tr ',' '\n' | grep -c .)
else
    n=$(ls config/scenes 2>/dev/null | sed -n 's/\.\(gltf\|glb\)$//p' | sort -u | grep -c . || true)
fi
if [ "$n" -eq 0 ]; then
    echo "showcase: no scenes in config/scenes (make scenes builds them)" >&2
    exit 1
fi
seconds=$(awk -v n="$n" -v d="$DWELL" 'BEGIN { printf "%.3f", n * d - 0.001 }')
echo "showcase: no display; $n scenes x $DWELL s on the mock platform at $SIZE -> out/"
# The frame-time target: llvmpipe on 2 CPU cores is one to two orders of magnitude slower than a
# board's GPU, so the board's target (16.7-33 ms) would push every budget to its floor and the
# captures would show only the cheapest level of each method. TARGET_MS (default 400) gives the
# scheduler a CPU-sized target instead; set TARGET_MS=33 to watch it degrade as on a slow board.
"$BIN" run --platform mock --config "$tmp" --size "$SIZE" --seconds "$seconds" \
    --target-ms "${TARGET_MS:-400}" --capture out --stats out/showcase-stats.csv
