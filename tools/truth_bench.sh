#!/bin/sh
# make bench-truth: the frame time with the live ground truth's workers running against without
# them, side by side in one run (DESIGN §7: ratios, not absolute times on a CPU-only machine).
# Runs alternate off/on (RUNS pairs, so drift and other load hit both alike); each run is the same
# pinned cornell/vct view; a run's number is the median frame_ms of its frames after WARM.
# Usage: tools/truth_bench.sh BIN [RUNS] [FRAMES] [SIZE]
set -u
BIN=${1:-build/gikiosk}
RUNS=${2:-3}
FRAMES=${3:-240}
SIZE=${4:-320x180}
WARM=60
TMP=$(mktemp -d "${TMPDIR:-/tmp}/gikiosk-truth-bench.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
PINS=render_scale=1,vct_res=64,vct_cones=6,vct_step=1,vct_trace_scale=0.5,vct_mips=aniso
printf '[truth]\nenabled = false\n' >"$TMP/off.ini"
printf '[truth]\nenabled = true\n' >"$TMP/on.ini"   # workers = cores - 1
median_ms() { # the median frame_ms of the rows after WARM
    awk -F, -v w="$WARM" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "frame_ms") c = i; next }
        NR - 2 >= w { print $c }' "$1" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'
}
echo "truth bench: cornell vct $SIZE, $FRAMES frames a run (median after $WARM), $RUNS off/on pairs, $(nproc) cores"
ratios=""
i=1
while [ "$i" -le "$RUNS" ]; do
    for mode in off on; do
        "$BIN" run --config "$TMP/$mode.ini" --platform mock --scene cornell --method vct --size "$SIZE" \
            --frames "$FRAMES" --budget "$PINS" --stats "$TMP/$mode-$i.csv" >"$TMP/$mode-$i.log" 2>&1 ||
            { echo "run $mode $i failed:"; tail -5 "$TMP/$mode-$i.log"; exit 1; }
    done
    off=$(median_ms "$TMP/off-$i.csv")
    on=$(median_ms "$TMP/on-$i.csv")
    r=$(awk -v a="$on" -v b="$off" 'BEGIN { printf "%.3f", a / b }')
    spp=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "truth_spp") c = i; next } $c != "" { s = $c } END { print s }' "$TMP/on-$i.csv")
    echo "pair $i: median frame_ms off $off, on $on: ratio on/off $r (truth reached $spp spp)"
    ratios="$ratios $r"
    i=$((i + 1))
done
echo "$ratios" | tr ' ' '\n' | grep . | sort -g | awk '{ v[NR] = $1 } END { printf "median ratio on/off over %d pairs: %s\n", NR, v[int((NR + 1) / 2)] }'
