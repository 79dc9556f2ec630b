#!/bin/sh
# `make calibrate`: the measured model the kiosk chooses methods from (app/sched/calibration.h).
# Every scene x every GI method that applies, at the default budgets, through `gikiosk bench`: the
# frame time at the showcase's size (TIME_SIZE, default 640x360: what `make run` shows), the error
# at the references' size; the error of every method of a scene is measured against ONE ruler --
# SCENE-1bounce.exr where the scene has one (what the GI methods compute), else SCENE.exr -- so
# `none` and the GI methods are comparable (the bench's own rel_rmse judges `none` against the
# direct reference). A black ruler (light-leak) makes relative errors infinite: the absolute RMSE
# is recorded there instead (column `metric`). Writes config/calibration/CLASS.csv, CLASS from the
# GL renderer string (llvmpipe here); other platforms: run this on the board.
# Usage: tools/calibrate.sh BIN   (environment: OUT=work dir, DEST=config/calibration)
set -eu
BIN=${1:-build/gikiosk}
OUT=${OUT:-out/calibration}
DEST=${DEST:-config/calibration}
REFS=${REFS:-tests/references}
FRAMES=${FRAMES:-5}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
scenes=$(ls config/scenes/*.gltf config/scenes/*.glb 2>/dev/null | sed 's|.*/||; s/\.gltf$//; s/\.glb$//' | sort -u |
    tr '\n' ',' | sed 's/,$//')
size=$(oiiotool --info "$REFS/cornell.exr" | sed -n 's/.*: *\([0-9]*\) x *\([0-9]*\),.*/\1x\2/p')
rm -rf "$OUT"
mkdir -p "$(dirname "$OUT")"
TIME_SIZE=${TIME_SIZE:-640x360}
"$BIN" bench --scenes "$scenes" --methods none,vct,vpl,ispm --sweep "render_scale=1" --size "$size" \
    --frames 1 --warmup 2 --references "$REFS" --out "$OUT" 2>"$OUT.log" || { cat "$OUT.log" >&2; exit 1; }
"$BIN" bench --scenes "$scenes" --methods none,vct,vpl,ispm --sweep "render_scale=1" --size "$TIME_SIZE" \
    --frames "$FRAMES" --warmup 2 --references "$REFS" --out "$OUT/time" 2>"$OUT.time.log" ||
    { cat "$OUT.time.log" >&2; exit 1; }
renderer=$(sed -n 's/^gikiosk: OpenGL ES .* on \(.*\)$/\1/p' "$OUT.log" | head -1)
class=$(echo "$renderer" | awk '{ print tolower($1) }' | tr -cd 'a-z0-9_-')
[ -n "$class" ] || class=unknown
CSV=$OUT/bench.csv
col() { head -1 "$CSV" | tr ',' '\n' | grep -n "^$1\$" | cut -d: -f1; }
c_scene=$(col scene); c_method=$(col method); c_ms=$(col frame_ms_median)
# scene method -> frame time at TIME_SIZE
awk -F, -v s="$c_scene" -v m="$c_method" -v t="$c_ms" 'NR > 1 { print $s, $m, $t }' "$OUT/time/bench.csv" >"$OUT/times"
mkdir -p "$DEST"
tmp=$(mktemp "$DEST/.calibration.XXXXXX")
{
    echo "# gikiosk calibration, made by \`make calibrate\` (tools/calibrate.sh) on $renderer"
    echo "# default budgets; frame time at ${TIME_SIZE} (median of $FRAMES frames after 2 warm-up); error at ${size} against the scene's"
    echo "# ruler (SCENE-1bounce.exr where it exists, else SCENE.exr): rel_rmse, or rmse where the ruler is black"
    echo "scene,method,width,height,frame_ms,error,metric,ruler"
    n=0
    awk -F, -v s="$c_scene" -v m="$c_method" 'NR > 1 { print NR - 2, $s, $m }' "$CSV" |
    while read -r row scene method; do
        ms=$(awk -v s="$scene" -v m="$method" '$1 == s && $2 == m { print $3 }' "$OUT/times")
        ruler=$scene-1bounce
        [ -f "$REFS/$ruler.exr" ] || ruler=$scene
        [ -f "$REFS/$ruler.exr" ] || continue   # no reference: nothing to choose by
        exr=$(printf '%s/captures/%s-%s-%03d.exr' "$OUT" "$scene" "$method" "$row")
        json=$("$BIN" compare "$REFS/$ruler.exr" "$exr" --json)
        echo "$json" | awk -v sc="$scene" -v me="$method" -v ms="$ms" -v ru="$ruler" -v sz="$TIME_SIZE" '
            { if (match($0, /"rel_rmse": *[^,}]*/)) rel = substr($0, RSTART, RLENGTH)
              if (match($0, /"rmse": *[^,}]*/)) abs = substr($0, RSTART, RLENGTH) }
            END { sub(/.*: */, "", rel); sub(/.*: */, "", abs); split(sz, d, "x")
                  if (rel ~ /^[0-9.eE+-]+$/ && rel + 0 < 1e30) printf "%s,%s,%s,%s,%s,%s,rel_rmse,%s\n", sc, me, d[1], d[2], ms, rel, ru
                  else printf "%s,%s,%s,%s,%s,%s,rmse,%s\n", sc, me, d[1], d[2], ms, abs, ru }'
    done
} >"$tmp"
mv "$tmp" "$DEST/$class.csv"
echo "calibrate: $(($(wc -l <"$DEST/$class.csv") - 4)) rows -> $DEST/$class.csv"
