#!/bin/sh
# `make calibrate`: the measured model the kiosk chooses methods and budgets from
# (app/sched/calibration.h). Every scene x every GI method that applies, through
# `gikiosk bench --sweep each`: the default budgets, then every knob the scheduler may move one at a
# time through its automatic levels. Per configuration: the frame time and the time of each pass at
# the showcase's size (TIME_SIZE, default 640x360: what `make run` shows), the error at the
# references' size; the error of every method of a scene is measured against ONE ruler --
# SCENE-1bounce.exr where the scene has one (what the GI methods compute), else SCENE.exr -- so
# `none` and the GI methods are comparable (the bench's own rel_rmse judges `none` against the
# direct reference). A black ruler (light-leak) makes relative errors infinite: the absolute RMSE
# is recorded there instead (column `metric`). Writes config/calibration/CLASS.csv, CLASS from the
# GL renderer string (llvmpipe here); other platforms: run this on the board.
# Usage: tools/calibrate.sh BIN   (environment: OUT=work dir, DEST=config/calibration, FRAMES,
# SCENES=comma list and/or METHODS=comma list: measure only those scenes x methods and keep the
# existing table's rows of the others, e.g. after adding a method: METHODS=lightmap make calibrate;
# after adding a scene: SCENES=glass-fog make calibrate; without an existing table the new one covers
# only what was measured)
set -eu
BIN=${1:-build/gikiosk}
OUT=${OUT:-out/calibration}
DEST=${DEST:-config/calibration}
REFS=${REFS:-tests/references}
FRAMES=${FRAMES:-5}
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
scenes=${SCENES:-}
# every scene with a ruler (SCENE-1bounce.exr or SCENE.exr): the table's rows of a scene without one
# are dropped below (nothing to choose by), so measuring them would only cost time (and rows: the
# bench's cap on configurations was once reached by cornell-spot-anim's)
[ -n "$scenes" ] || scenes=$(ls config/scenes/*.gltf config/scenes/*.glb 2>/dev/null | sed 's|.*/||; s/\.gltf$//; s/\.glb$//' | sort -u |
    while read -r sc; do [ -f "$REFS/$sc.exr" ] || [ -f "$REFS/$sc-1bounce.exr" ] && echo "$sc"; done | tr '\n' ',' | sed 's/,$//')
size=$(oiiotool --info "$REFS/cornell.exr" | sed -n 's/.*: *\([0-9]*\) x *\([0-9]*\),.*/\1x\2/p')
rm -rf "$OUT"
mkdir -p "$(dirname "$OUT")"
TIME_SIZE=${TIME_SIZE:-640x360}
METHODS=${METHODS:-}
# SWEEP=each (default): every knob level; SWEEP=render_scale=1: the default rows only (one configuration
# per scene x method, minutes instead of the better part of an hour; the scheduler then moves those
# methods' knobs by its priors and step responses)
SWEEP=${SWEEP:-each}
only=${METHODS:+--methods $METHODS}
# The error run: lightmap in lockstep (each frame waits for its photon tick, so the image after the
# warm-up is what the kiosk converges to, not how far the worker threads got), after ERROR_WARMUP frames
# (default 40: lightmap's photons and final gather settle by then; static methods are the same at 2);
# radiosity in lockstep too (its links and direct light come from a worker thread).
# KEEP_ERRORS=1: re-time only. The error run is skipped and each row keeps the error of the same
# scene x method x knob x value in the existing table (a configuration it lacks stops the run): for a
# change that makes passes faster and leaves every image as it was (e.g. the lighting pass's two draws
# of issue 21, bit-identical), so the times are fresh without the error run's half of the hour.
KEEP_ERRORS=${KEEP_ERRORS:-0}
mkdir -p "$OUT"
if [ "$KEEP_ERRORS" != 1 ]; then
    "$BIN" bench --scenes "$scenes" $only --sweep "$SWEEP" --size "$size" --budget lightmap_sync=lockstep,radiosity_sync=lockstep \
        --frames 1 --warmup "${ERROR_WARMUP:-40}" --references "$REFS" --out "$OUT" 2>"$OUT.log" || { cat "$OUT.log" >&2; exit 1; }
fi
"$BIN" bench --scenes "$scenes" $only --sweep "$SWEEP" --size "$TIME_SIZE" \
    --frames "$FRAMES" --warmup 2 --references "$REFS" --out "$OUT/time" 2>"$OUT.time.log" ||
    { cat "$OUT.time.log" >&2; exit 1; }
renderer=$(sed -n 's/^gikiosk: OpenGL ES .* on \(.*\)$/\1/p' "$OUT.time.log" | head -1)
class=$(echo "$renderer" | awk '{ print tolower($1) }' | tr -cd 'a-z0-9_-')
[ -n "$class" ] || class=unknown
CSV=$OUT/bench.csv
if [ "$KEEP_ERRORS" = 1 ]; then
    [ -f "$DEST/$class.csv" ] || { echo "calibrate: KEEP_ERRORS=1 needs an existing $DEST/$class.csv" >&2; exit 1; }
    # scene,method,knob,value -> error,metric,ruler of the existing table
    awk -F, 'NR > 1 && !/^#/ && $1 != "scene" { print $1 "," $2 "," $9 "," $10 "|" $6 "," $7 "," $8 }' \
        "$DEST/$class.csv" >"$OUT/kept-errors"
else
    # The two runs measured the same configurations in the same order: row i of one is row i of the other.
    [ "$(wc -l <"$CSV")" -eq "$(wc -l <"$OUT/time/bench.csv")" ] || { echo "calibrate: the two runs differ" >&2; exit 1; }
fi
# Per row of the time run: scene, method, the knob changed from the method's default row (its first)
# and its value ("-" for the default row), the median frame time, the passes that ran (PATH=MS).
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { h[i] = $i; if ($i == "render_scale") k0 = i
                       if ($i == "frame_ms_median") { k1 = i - 1; t = i }; if ($i == "chosen") p0 = i + 1 }
                   next }
    { group = $1 "," $2
      if (group != last) { for (i = k0; i <= k1; i++) def[i] = $i; last = group }
      knob = "-"; value = "-"
      for (i = k0; i <= k1; i++) if ($i != def[i]) { knob = h[i]; value = $i }
      passes = ""
      for (i = p0; i <= NF; i++) if ($i + 0 > 0) { name = h[i]; sub(/_ms$/, "", name)
          passes = passes (passes == "" ? "" : " ") name "=" sprintf("%.3f", $i) }
      print NR - 2, $1, $2, knob, value, $t, (passes == "" ? "-" : passes) }' "$OUT/time/bench.csv" >"$OUT/rows"
mkdir -p "$DEST"
tmp=$(mktemp "$DEST/.calibration.XXXXXX")
{
    echo "# gikiosk calibration, made by \`make calibrate\` (tools/calibrate.sh) on $renderer"
    echo "# per scene x method: the default budgets (knob and value empty), then each knob the scheduler may move, alone,"
    echo "# at each automatic level; frame time and pass times at ${TIME_SIZE} (median of $FRAMES frames after 2 warm-up); error at"
    echo "# ${size} against the scene's ruler (SCENE-1bounce.exr where it exists, else SCENE.exr): rel_rmse, or rmse where the ruler is black"
    [ "$KEEP_ERRORS" = 1 ] && echo "# frame and pass times re-measured with KEEP_ERRORS=1: the errors are the previous table's, images unchanged"
    echo "scene,method,width,height,frame_ms,error,metric,ruler,knob,value,passes"
    if { [ -n "$METHODS" ] || [ -n "${SCENES:-}" ]; } && [ -f "$DEST/$class.csv" ]; then
        # the rows of the scene x method pairs not measured now, as they were (an earlier run)
        awk -F, -v m=",$METHODS," -v s=",${SCENES:-}," 'NR > 1 && !/^#/ && $1 != "scene" &&
            !((s == ",," || index(s, "," $1 ",")) && (m == ",," || index(m, "," $2 ",")))' "$DEST/$class.csv"
    fi
    while read -r row scene method knob value ms passes; do
        [ "$knob" = "-" ] && knob= && value=
        [ "$passes" = "-" ] && passes=
        ruler=$scene-1bounce
        [ -f "$REFS/$ruler.exr" ] || ruler=$scene
        [ -f "$REFS/$ruler.exr" ] || continue   # no reference: nothing to choose by
        if [ "$KEEP_ERRORS" = 1 ]; then
            kept=$(awk -v k="$scene,$method,$knob,$value" -F'|' '$1 == k { print $2; exit }' "$OUT/kept-errors")
            [ -n "$kept" ] || { echo "calibrate: KEEP_ERRORS=1: $scene $method ${knob:-default} ${value} has no row in $DEST/$class.csv" >&2; exit 1; }
            printf '%s,%s,%s,%s,%s,%s,%s,%s\n' "$scene" "$method" "${TIME_SIZE%x*}" "${TIME_SIZE#*x}" "$ms" "$kept" "$knob" "$value,$passes"
            continue
        fi
        exr=$(printf '%s/captures/%s-%s-%03d.exr' "$OUT" "$scene" "$method" "$row")
        json=$("$BIN" compare "$REFS/$ruler.exr" "$exr" --json)
        echo "$json" | awk -v sc="$scene" -v me="$method" -v ms="$ms" -v ru="$ruler" -v sz="$TIME_SIZE" \
            -v kn="$knob" -v va="$value" -v pa="$passes" '
            { if (match($0, /"rel_rmse": *[^,}]*/)) rel = substr($0, RSTART, RLENGTH)
              if (match($0, /"rmse": *[^,}]*/)) abs = substr($0, RSTART, RLENGTH) }
            END { sub(/.*: */, "", rel); sub(/.*: */, "", abs); split(sz, d, "x")
                  if (rel ~ /^[0-9.eE+-]+$/ && rel + 0 < 1e30) printf "%s,%s,%s,%s,%s,%s,rel_rmse,%s,%s,%s,%s\n", sc, me, d[1], d[2], ms, rel, ru, kn, va, pa
                  else printf "%s,%s,%s,%s,%s,%s,rmse,%s,%s,%s,%s\n", sc, me, d[1], d[2], ms, abs, ru, kn, va, pa }'
    done <"$OUT/rows"
} >"$tmp"
mv "$tmp" "$DEST/$class.csv"
echo "calibrate: $(grep -c '^[^#]' "$DEST/$class.csv") lines (header included) -> $DEST/$class.csv"
