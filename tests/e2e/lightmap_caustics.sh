#!/bin/sh
# The lightmap method's caustics (seed 004 §5) as a user runs them on caustic-ring, at the
# references' size (160x120), lockstep (each frame waits for its photon tick: deterministic), frame 11:
#  - the caustic term alone is the capture minus the capture with lightmap_caustics=0 (the method
#    adds it last, eq. (5)); against tests/references/caustic-ring-caustics.exr (L S+ D paths):
#    its energy (mean ratio, whole image and inside the caustic mask) and rel. RMSE inside the mask;
#  - a static scene: W = 8 (progressive) and W = 1 (every photon every frame) give the identical
#    image (a retraced photon lands where it was);
#  - the GLES 3.1 path (R8 counts, stencil, occlusion queries are 3.0 core) gives the identical image;
#  - M13: the caustic's energy does not depend on the pixel size (the filter divides by each pixel's
#    footprint; the seed's constant scale would give 1/4 of it at twice the resolution): 320x240
#    box-filtered to 160x120 against 160x120;
#  - M14, the seed's 8-bit count: glass's refraction caustic focuses more than 255 photons into a
#    pixel at 40,000 photons and loses energy; lightmap_count=float (R16F) keeps it; on caustic-ring,
#    where no pixel saturates, float gives the identical image.
. tests/e2e/lib.sh
REFS=tests/references
MASK=$REFS/caustic-ring-caustics-mask.png
# a whole-image field (the part before the mask's)
json_field() { sed 's/, "mask".*//' "$2" | sed -n "s/.*\"$1\": \([^,}]*\).*/\1/p"; }
# identical A B: the two captures' pixels are equal (the files differ in their recorded command)
identical() { "$GIKIOSK" compare "$1" "$2" --json >"$TMP/i.json" && [ "$(json_field max_error "$TMP/i.json")" = 0 ]; }
inside_field() { sed -n "s/.*\"inside\": {[^}]*\"$1\": \([^,}]*\).*/\1/p" "$2"; }
in_range() { awk -v v="$1" -v lo="$2" -v hi="$3" 'BEGIN { n = "^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$"; exit !(v ~ n && v + 0 >= lo && v + 0 <= hi) }'; }
# every knob the scheduler could move is pinned: the caustic term is the difference of two runs
PIN=lightmap_sync=lockstep,lightmap_aim=80,lightmap_gather=16,lightmap_groups=77,lightmap_iim=20
PIN=$PIN,render_scale=1,shadow=pcss,shadow_map=1024,shadow_subdiv=3

# shot NAME BUDGET [ARGS...]: frame 11's HDR capture as $TMP/NAME.exr
shot() {
    n=$1 b=$2
    shift 2
    rm -rf "$TMP/cap"
    "$GIKIOSK" run --platform mock --scene caustic-ring --method lightmap --size 160x120 --frames 12 \
        --capture-every 11 --target-ms 1000 --hdr --capture "$TMP/cap" --stats "$TMP/$n.csv" --budget "$PIN,$b" "$@" \
        >"$TMP/$n.log" 2>&1 &&
        mv "$TMP/cap/000010-caustic-ring-lightmap.exr" "$TMP/$n.exr"
}

check "caustic-ring lightmap without caustics renders" shot off lightmap_caustics=0
check "caustic-ring lightmap with 10,000 caustic photons renders" shot on lightmap_caustics=10000
check "the caustic passes are nested under gi in the stats" grep -q "gi.lightmap_caustic_filter_ms" "$TMP/on.csv"
oiiotool "$TMP/on.exr" "$TMP/off.exr" --sub -o "$TMP/caustics.exr"
"$GIKIOSK" compare "$REFS/caustic-ring-caustics.exr" "$TMP/caustics.exr" --mask "$MASK" --json >"$TMP/c.json"
all=$(json_field mean_ratio "$TMP/c.json") in_ratio=$(inside_field mean_ratio "$TMP/c.json")
in_err=$(inside_field rel_rmse "$TMP/c.json")
echo "# caustic-ring caustics: energy ratio $all (whole image), $in_ratio inside the mask; rel_rmse inside $in_err"
# Measured (llvmpipe, 160x120): whole image 0.892, in the mask 0.822 and rel_rmse 0.345; at 2,500 and
# 40,000 photons 0.895 / 0.832 / 0.337 and 0.895 / 0.829 / 0.337: the error is the 7x7 screen filter's
# blur of a caustic a few pixels wide (energy moves out of the mask), not photon noise (the
# reference's own noise in the mask: 0.013). Bounds: the measurements +- 0.04, rel_rmse + 0.05.
check "caustic energy over the image within [0.85, 0.93] of the reference ($all)" in_range "$all" 0.85 0.93
check "caustic energy in the mask within [0.78, 0.87] of the reference ($in_ratio)" in_range "$in_ratio" 0.78 0.87
check "caustic rel_rmse in the mask under 0.40 ($in_err)" in_range "$in_err" 0 0.40

# M13: at 320x240 (box-filtered to the references' size)
check "caustic-ring at 320x240 without caustics renders" shot off2 lightmap_caustics=0 --size 320x240
check "caustic-ring at 320x240 with caustics renders" shot on2 lightmap_caustics=10000 --size 320x240
oiiotool "$TMP/on2.exr" "$TMP/off2.exr" --sub --resize:filter=box 160x120 -o "$TMP/caustics2.exr"
"$GIKIOSK" compare "$TMP/caustics.exr" "$TMP/caustics2.exr" --json >"$TMP/r.json"
res_ratio=$(json_field mean_ratio "$TMP/r.json")
echo "# caustic energy at 320x240 / at 160x120: $res_ratio"
# measured 1.03 (0.920 against 0.892 of the reference: the 7x7 kernel blurs half as far at 320x240,
# in the mask 0.920 and rel_rmse 0.256); bound 5%
check "the caustic's energy does not depend on the resolution ($res_ratio within 5%)" in_range "$res_ratio" 0.95 1.05

check "W = 1 renders" shot w1 lightmap_caustics=10000,lightmap_window=1
check "static scene: W = 8 and W = 1 give the identical image" identical "$TMP/on.exr" "$TMP/w1.exr"
check "--gles 3.1 renders" shot g31 lightmap_caustics=10000 --gles 3.1
check "--gles 3.1 gives the identical image" identical "$TMP/on.exr" "$TMP/g31.exr"
check "lightmap_count=float renders" shot f32 lightmap_caustics=10000,lightmap_count=float
check "caustic-ring: float counts give the identical image (no pixel saturates)" identical "$TMP/on.exr" "$TMP/f32.exr"

# glass: the caustic term at 40,000 photons, 8-bit against float counts
glass() {
    n=$1 b=$2
    rm -rf "$TMP/cap"
    "$GIKIOSK" run --platform mock --scene glass --method lightmap --size 160x120 --frames 12 --capture-every 11 \
        --target-ms 1000 --hdr --capture "$TMP/cap" --budget "$PIN,$b" >"$TMP/$n.log" 2>&1 &&
        mv "$TMP/cap/000010-glass-lightmap.exr" "$TMP/$n.exr"
}
check "glass without caustics renders" glass goff lightmap_caustics=0
for cnt in 8bit float; do
    check "glass, 40,000 caustic photons, lightmap_count=$cnt renders" glass "g$cnt" "lightmap_caustics=40000,lightmap_count=$cnt"
    oiiotool "$TMP/g$cnt.exr" "$TMP/goff.exr" --sub -o "$TMP/gc$cnt.exr"
    "$GIKIOSK" compare "$REFS/glass-caustics.exr" "$TMP/gc$cnt.exr" --json >"$TMP/g.json"
    eval "e_$cnt=\$(json_field mean_ratio \"\$TMP/g.json\")"
done
echo "# glass caustic energy at 40,000 photons: 8-bit counts $e_8bit, float counts $e_float"
# Measured: 8bit 0.423 (10,000 photons: 0.905), float 0.948 (10,000: 0.941). Bounds: 8bit under 0.6 (the
# saturation is the seed's M14, shown, not hidden), float within [0.90, 0.99].
check "glass, 8-bit counts saturate: energy $e_8bit under 0.6" in_range "$e_8bit" 0 0.6
check "glass, float counts keep the energy: $e_float in [0.90, 0.99]" in_range "$e_float" 0.90 0.99
finish
