#!/bin/sh
# `make bench-compare REV=<commit>`: the same scene, method, size and pinned budgets rendered by this
# tree's binary and by REV's, their runs interleaved (old, new, old, new, ...) so that a noisy,
# shared machine slows both alike, and per pass the ratio new / old of the median times.
#
#   sh tools/bench_compare.sh NEW_BIN REV [--scene S] [--method M] [--size WxH] [--runs N]
#                             [--frames F] [--warmup W] [--budget K=V,...]
#   sh tools/bench_compare.sh --summarize OLD_DIR NEW_DIR     (the table from existing stats CSVs)
#
# REV is built once into build/compare-REV (its own `git archive`, its own build tree, so the two
# never share objects). Each run writes `gikiosk run --stats` CSVs; a run's time for a pass is the
# median over its frames after the first W (warm-up: voxelization, shader compiles), a pass missing
# from a frame counts 0 there (it had nothing to do); the table's old and new are the medians of
# the runs' medians, and the ratio is new / old. Exit 2: bad usage, an unknown REV; exit 1: a
# build or a run failed, or a stats CSV had no frame past the warm-up.
set -eu

die() { echo "bench-compare: $1" >&2; exit "${2:-2}"; }

# Per stats CSV: "PASS value" lines, the median over frames after the warm-up of each *_ms column.
run_medians() { # csv warmup
    [ -f "$1" ] || die "$1: no stats CSV (the run wrote none)" 1
    awk -F, -v warm="$2" -v file="$1" '
        NR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /_ms$/) { col[++nc] = i; name[nc] = $i }
                  if (nc == 0) { printf "bench-compare: %s:1: no PASS_ms column in the header\n", file > "/dev/stderr"; bad = 1; exit 1 }
                  next }
        NR - 2 >= warm { nf++; for (c = 1; c <= nc; c++) v[c, nf] = ($col[c] == "" ? 0 : $col[c] + 0) }
        END {
            if (bad) exit 1
            if (nf == 0) { printf "bench-compare: %s: no frame after the %d warm-up frames\n", file, warm > "/dev/stderr"; exit 1 }
            for (c = 1; c <= nc; c++) {
                n = 0; for (f = 1; f <= nf; f++) a[++n] = v[c, f]
                for (i = 2; i <= n; i++) { x = a[i]; for (j = i - 1; j >= 1 && a[j] > x; j--) a[j + 1] = a[j]; a[j + 1] = x }
                m = (n % 2) ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
                printf "%s %.6f\n", name[c], m
            }
        }' "$1"
}

# The table: every pass that either binary reported, old and new medians of the runs, new / old.
summarize() { # old_dir new_dir warmup
    all=$(mktemp) || exit 1
    for side in old new; do
        dir=$1; [ "$side" = new ] && dir=$2
        found=0
        for csv in "$dir"/run-*.csv; do
            [ -f "$csv" ] || continue
            found=1
            m=$(run_medians "$csv" "$3") || { rm -f "$all"; exit 1; }
            echo "$m" | sed "s/^/$side /" >>"$all"
        done
        [ "$found" -eq 1 ] || { rm -f "$all"; die "$dir: no run-*.csv stats files" 1; }
    done
    awk '
        { key = $2; n[$1, key]++; v[$1, key, n[$1, key]] = $3; if (!(key in seen)) { seen[key] = 1; order[++k] = key } }
        function median(side, key,   m, i, j, x, a) {
            m = n[side, key]; if (m == 0) return -1
            for (i = 1; i <= m; i++) a[i] = v[side, key, i]
            for (i = 2; i <= m; i++) { x = a[i]; for (j = i - 1; j >= 1 && a[j] > x; j--) a[j + 1] = a[j]; a[j + 1] = x }
            return (m % 2) ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2
        }
        END {
            printf "%-28s %12s %12s %10s\n", "pass", "old_ms", "new_ms", "new/old"
            for (i = 1; i <= k; i++) {
                key = order[i]; o = median("old", key); w = median("new", key)
                os = (o < 0) ? "-" : sprintf("%.3f", o); ws = (w < 0) ? "-" : sprintf("%.3f", w)
                r = (o > 0 && w >= 0) ? sprintf("%.3f", w / o) : "-"
                printf "%-28s %12s %12s %10s\n", key, os, ws, r
            }
        }' "$all"
    rm -f "$all"
}

if [ "${1:-}" = "--summarize" ]; then
    [ $# -ge 3 ] || die "usage: bench_compare.sh --summarize OLD_DIR NEW_DIR [WARMUP]"
    summarize "$2" "$3" "${4:-0}"
    exit 0
fi

[ $# -ge 2 ] || die "usage: bench_compare.sh NEW_BIN REV [--scene S] [--method M] [--size WxH] [--runs N] [--frames F] [--warmup W] [--budget K=V,...] (make bench-compare REV=<commit>)"
NEW_BIN=$1; REV=$2; shift 2
[ -n "$REV" ] || die "REV is empty: make bench-compare REV=<commit>"
[ -x "$NEW_BIN" ] || die "$NEW_BIN: not an executable (build it first: make)" 1
SCENE=cornell METHOD=vct SIZE=640x360 RUNS=5 FRAMES=6 WARMUP=2
# The configuration: 64^3, 9 cones, every pixel traced, anisotropic mips, PCSS at 1024.
BUDGET=vct_res=64,vct_cones=9,vct_step=1,vct_trace_scale=1,vct_mips=aniso,vct_variant=default,render_scale=1,shadow=pcss,shadow_map=1024,shadow_subdiv=3
while [ $# -gt 0 ]; do
    [ $# -ge 2 ] || die "option $1 needs a value"
    case $1 in
        --scene) SCENE=$2 ;; --method) METHOD=$2 ;; --size) SIZE=$2 ;; --budget) BUDGET=$2 ;;
        --runs) RUNS=$2 ;; --frames) FRAMES=$2 ;; --warmup) WARMUP=$2 ;;
        *) die "unknown option '$1'" ;;
    esac
    shift 2
done
for n in "$RUNS:--runs" "$FRAMES:--frames" "$WARMUP:--warmup"; do
    case ${n%%:*} in ''|*[!0-9]*) die "${n#*:} '${n%%:*}' is not a whole number" ;; esac
done
[ "$RUNS" -ge 1 ] || die "--runs must be at least 1"
[ "$FRAMES" -gt "$WARMUP" ] || die "--frames ($FRAMES) must exceed --warmup ($WARMUP)"

SHA=$(git rev-parse --verify --quiet "$REV^{commit}") || die "'$REV' is not a commit of this repository"
SHORT=$(printf %.12s "$SHA")
BUILD=${BUILD:-build}
CMP=$BUILD/compare-$SHORT
OLD_BIN=$CMP/build/gikiosk
if [ ! -x "$OLD_BIN" ]; then
    echo "bench-compare: building $SHORT into $CMP" >&2
    rm -rf "$CMP" && mkdir -p "$CMP"
    git archive "$SHA" | tar -x -C "$CMP" || die "git archive $SHORT failed" 1
    nice -n 10 make -C "$CMP" -j2 all >"$CMP/build.log" 2>&1 || die "building $SHORT failed: see $CMP/build.log" 1
fi
OUT=${OUT:-out/bench-compare}
rm -rf "$OUT" && mkdir -p "$OUT/old" "$OUT/new"
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
echo "bench-compare: $SCENE / $METHOD at $SIZE, budgets $BUDGET; $RUNS runs of $FRAMES frames each (first $WARMUP dropped), old = $SHORT, new = $NEW_BIN" >&2
i=1
while [ "$i" -le "$RUNS" ]; do
    for side in old new; do
        bin=$OLD_BIN; [ "$side" = new ] && bin=$NEW_BIN
        # the largest target (1000 ms), so the scheduler rarely moves a knob the budget list does not pin
        "$bin" run --platform mock --scene "$SCENE" --method "$METHOD" --size "$SIZE" --frames "$FRAMES" \
            --target-ms 1000 --budget "$BUDGET" --stats "$OUT/$side/run-$i.csv" >"$OUT/$side/run-$i.log" 2>&1 ||
            die "$side binary failed on run $i: see $OUT/$side/run-$i.log" 1
    done
    i=$((i + 1))
done
summarize "$OUT/old" "$OUT/new" "$WARMUP" | tee "$OUT/ratios.txt"
