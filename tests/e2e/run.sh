#!/bin/sh
# End-to-end tests of `gikiosk run` on the mock platform (llvmpipe): scripted scene changes seen in
# --stats and in capture names, --budget pins in the stats columns, exit 2 with file:line for bad
# configs, scripts and command lines, exit 0 on SIGTERM, exit 1 when no scene loads.
# Runs are tiny (64x64, a dozen frames) on two hand-written one-quad scenes.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless

S=$TMP/scenes
mkdir -p "$S"
cat >"$S/a.gltf" <<'GLTF'
{
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 20, "color": [1, 1, 1]}]}},
  "scene": 0,
  "scenes": [{"nodes": [0, 1, 2]}],
  "nodes": [
    {"mesh": 0},
    {"translation": [0, 1.5, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"translation": [0, 2, 3], "rotation": [-0.2297529, 0, 0, 0.9732489], "camera": 0}
  ],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 50}}],
  "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.4, 1], "metallicFactor": 0, "roughnessFactor": 0.8}, "doubleSided": true}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
  "buffers": [{"byteLength": 110, "uri": "data:application/octet-stream;base64,AACAvwAAAAAAAIC/AACAPwAAAAAAAIC/AACAPwAAAAAAAIA/AACAvwAAAAAAAIA/AAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAACAAEAAAADAAIAAAA="}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 48},
    {"buffer": 0, "byteOffset": 48, "byteLength": 48},
    {"buffer": 0, "byteOffset": 96, "byteLength": 12}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}
  ]
}
GLTF
sed 's/0.8, 0.6, 0.4, 1/0.3, 0.5, 0.9, 1/' "$S/a.gltf" >"$S/b.gltf"
printf '[playlist]\nscenes = a, b\ndwell_s = 30\n' >"$TMP/ok.ini"
# --method none: these tests are about the kiosk, not GI (and the capture names carry the method).
RUN="$GIKIOSK run --platform mock --size 64x64 --scenes-dir $S --method none"

# --- a scripted run: `next` at 0.05 s; the click's release (50 ms later) lands at 0.10 s, i.e.
# frame 6 at 60 virtual frames per second. Frames 0..5 show a, 6..11 b.
printf '# scripted\n0.05 next click\n\n0.12 info click\n' >"$TMP/next.script"
expect_exit 0 "scripted mock run exits 0" $RUN --config "$TMP/ok.ini" --frames 12 --script "$TMP/next.script" \
    --capture "$TMP/cap" --stats "$TMP/s.csv" --budget shadow_map=512,shadow=hard
scenes=$(awk -F, 'NR > 1 { printf "%s", $3 }' "$TMP/s.csv")
check "stats: frames 0-5 show a, 6-11 show b" [ "$scenes" = "aaaaaabbbbbb" ]
check "stats: header starts frame,time_s,scene,method,frame_ms" grep -q '^frame,time_s,scene,method,frame_ms,' "$TMP/s.csv"
check "stats: one PASS_ms column at least" sh -c "head -1 '$TMP/s.csv' | grep -q '_ms,.*_ms'"
check "capture: last frame of each scene visit" [ -f "$TMP/cap/000005-a-none.png" -a -f "$TMP/cap/000011-b-none.png" ]
check "capture: nothing else" [ "$(ls "$TMP/cap" | wc -l)" -eq 2 ]
col=$(head -1 "$TMP/s.csv" | tr ',' '\n' | grep -n '^shadow_map$' | cut -d: -f1)
check "stats: --budget pin shadow_map=512 in every row" \
    sh -c "[ -n '$col' ] && awk -F, -v c='$col' 'NR > 1 && \$c != \"512\" { bad = 1 } END { exit bad || NR != 13 }' '$TMP/s.csv'"
check "summary: one line per scene on stdout" sh -c "grep -q '^scene a: 6 frames' '$TMP/stdout' && grep -q '^scene b: 6 frames' '$TMP/stdout'"
stderr_has 'input: next click at 0.10 s' "log: the input event"
stderr_has 'HUD off' "log: info toggles the HUD"

# --- --capture-every and --hdr
expect_exit 0 "--capture-every 2 --hdr" $RUN --scene a --frames 4 --capture "$TMP/cap2" --capture-every 2 --hdr
check "capture-every: frames 1 and 3, png + exr" \
    [ -f "$TMP/cap2/000001-a-none.png" -a -f "$TMP/cap2/000003-a-none.exr" -a "$(ls "$TMP/cap2" | wc -l)" -eq 4 ]

# --- bad config: the line is named
printf '[display]\nsize = 64x64\n[frame]\ntagret_ms = 16\n' >"$TMP/typo.ini"
expect_exit 2 "misspelled config key exits 2" $RUN --config "$TMP/typo.ini" --frames 1
stderr_has "typo.ini:4: unknown key 'tagret_ms' in \[frame\]" "misspelled key: file:line named"
printf '[budgets]\nshadow_map = 256..512\nvoxel_res = 1..2\n' >"$TMP/knob.ini"
expect_exit 2 "unknown [budgets] knob exits 2" $RUN --config "$TMP/knob.ini" --frames 1
stderr_has "knob.ini:3: \[budgets\] unknown budget knob 'voxel_res'" "unknown knob: file:line named"

# --- bad command lines
expect_exit 2 "--size 12x exits 2" $RUN --size 12x
stderr_has "[-]-size: '12x' is not WxH" "--size names the value"
expect_exit 2 "--frames with --seconds exits 2" $RUN --frames 2 --seconds 1
expect_exit 2 "unknown --method exits 2" $RUN --method raytrace
stderr_has "[-]-method: 'raytrace' is not a method" "--method names the value"
expect_exit 2 "unknown --budget knob exits 2" $RUN --scene a --frames 1 --budget warp=9
stderr_has "unknown knob 'warp'" "--budget names the knob"
expect_exit 2 "missing --scene exits 2" $RUN --scene nowhere --frames 1
stderr_has "no scene 'nowhere'" "--scene names the scene"
expect_exit 0 "--help exits 0" $GIKIOSK run --help

# --- garbage script
printf '0.5 next click\n1 sideways click\n' >"$TMP/bad.script"
expect_exit 2 "garbage script exits 2" $RUN --scene a --frames 2 --script "$TMP/bad.script"
stderr_has "bad.script:2:" "garbage script: file:line named"

# --- no loadable scene: a broken file is skipped with a message, then exit 1
mkdir -p "$TMP/broken"
echo '{"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 7}}]}]}' >"$TMP/broken/x.gltf"
expect_exit 1 "no loadable scene exits 1" $GIKIOSK run --platform mock --size 64x64 --scenes-dir "$TMP/broken" --frames 2
stderr_has "scene x skipped" "broken scene is named"

# --- SIGTERM ends a run cleanly with exit 0
$RUN --config "$TMP/ok.ini" --seconds 100000 >"$TMP/term.out" 2>"$TMP/term.err" &
pid=$!
i=0
while [ $i -lt 300 ] && ! grep -q 'scene a' "$TMP/term.err" 2>/dev/null; do sleep 0.1; i=$((i + 1)); done
sleep 0.3
kill -TERM $pid
wait $pid
rc=$?
check "SIGTERM during a run exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "SIGTERM: the summary is still printed" grep -q '^scene a: ' "$TMP/term.out"
finish
