#!/bin/sh
# The limitation of volcaustics that research dong-001.md §6.8 names first, charted: the method is
# single scattering (D = A + B + C), so against the full reference its error grows with the share of
# multiply scattered light, which grows with the medium's albedo and density.
#
# For each medium setting it writes a copy of the scene (default caustic-ring-fog) with that medium
# (extras.gikiosk.medium sigma_s, sigma_a; g and bounds kept), renders with the path tracer the
# full image (`--terms all`) and the multiple-scattering term (`--terms multiple`), renders
# volcaustics' D on the mock platform, and measures with `gikiosk compare`:
#   multiple_share  = mean(multiple) / mean(all): the light the model leaves out;
#   d_mean_ratio    = mean(D) / mean(all);
#   d_rel_rmse      = D against all;
#   d_single_ratio  = mean(D) / mean(all - multiple): D against the path space it models.
# Two sweeps: albedo (sigma_t held at the scene's 0.27 /m) and density (sigma_t x 0.25 .. 2 at the
# scene's albedo 0.93). Output: OUT/multiple.csv and OUT/multiple-scattering.png (gnuplot, when
# installed). Small renders: SIZE (default 80x60), SPP (default 256).
#
# usage: tools/volcaustics_multiple.sh BIN [OUT]       env: SCENE, SIZE, SPP, SETTINGS, SCENES_DIR
#   SETTINGS: "sweep:sigma_s:sigma_a ..." (default the two sweeps below)
set -eu
BIN=${1:?usage: tools/volcaustics_multiple.sh BIN [OUT]}
OUT=${2:-out/volcaustics-multiple}
SCENE=${SCENE:-caustic-ring-fog}
SIZE=${SIZE:-80x60}
SPP=${SPP:-256}
SCENES_DIR=${SCENES_DIR:-config/scenes}
# albedo 0.3, 0.6, 0.93, 0.99 at sigma_t 0.27; density x0.25, x0.5, x1, x2 at albedo 0.93 (x1 is the
# scene's own medium, in both sweeps)
SETTINGS=${SETTINGS:-"albedo:0.081:0.189 albedo:0.162:0.108 albedo:0.25:0.02 albedo:0.2673:0.0027
density:0.0625:0.005 density:0.125:0.01 density:0.25:0.02 density:0.5:0.04"}

src=$SCENES_DIR/$SCENE.gltf
[ -f "$src" ] || { echo "volcaustics_multiple: no scene $src" >&2; exit 2; }
grep -q '"medium":{"sigma_s":\[' "$src" || { echo "volcaustics_multiple: $src has no extras.gikiosk.medium" >&2; exit 2; }
mkdir -p "$OUT"
work=$(mktemp -d "${TMPDIR:-/tmp}/gikiosk-multiple.XXXXXX")
trap 'rm -rf "$work"' EXIT
json() { sed -n "s/.*\"$1\": \([^,}]*\).*/\1/p" "$2"; }

csv=$OUT/multiple.csv
echo "sweep,sigma_s,sigma_a,albedo,sigma_t,multiple_share,d_mean_ratio,d_rel_rmse,d_single_ratio" >"$csv.part"
for setting in $SETTINGS; do
    sweep=${setting%%:*} rest=${setting#*:}
    ss=${rest%%:*} sa=${rest#*:}
    dir=$work/$sweep-$ss
    mkdir -p "$dir"
    cp "$SCENES_DIR/$SCENE.bin" "$dir/"
    sed "s/\"medium\":{\"sigma_s\":\[[^]]*\],\"sigma_a\":\[[^]]*\]/\"medium\":{\"sigma_s\":[$ss,$ss,$ss],\"sigma_a\":[$sa,$sa,$sa]/" \
        "$src" >"$dir/$SCENE.gltf"
    for terms in all multiple; do
        "$BIN" reference --scene "$SCENE" --scenes-dir "$dir" --size "$SIZE" --spp "$SPP" --terms "$terms" --seed 1 \
            --out "$dir/ref-$terms.exr" 2>/dev/null
    done
    EGL_PLATFORM=surfaceless "$BIN" run --platform mock --scenes-dir "$dir" --scene "$SCENE" --method volcaustics \
        --size "$SIZE" --frames 2 --hdr --capture "$dir/cap" >"$dir/run.log" 2>&1
    d=$dir/cap/000001-$SCENE-volcaustics.exr
    oiiotool "$dir/ref-all.exr" "$dir/ref-multiple.exr" --sub -o "$dir/ref-single.exr"
    "$BIN" compare "$dir/ref-all.exr" "$dir/ref-multiple.exr" --json >"$dir/m.json"
    "$BIN" compare "$dir/ref-all.exr" "$d" --json >"$dir/d.json"
    "$BIN" compare "$dir/ref-single.exr" "$d" --json >"$dir/s.json"
    row=$(awk -v ss="$ss" -v sa="$sa" -v m="$(json mean_ratio "$dir/m.json")" -v r="$(json mean_ratio "$dir/d.json")" \
        -v e="$(json rel_rmse "$dir/d.json")" -v s="$(json mean_ratio "$dir/s.json")" \
        'BEGIN { printf "%g,%g,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f", ss, sa, ss / (ss + sa), ss + sa, m, r, e, s }')
    echo "$sweep,$row" >>"$csv.part"
    echo "volcaustics_multiple: $sweep sigma_s $ss sigma_a $sa: $row"
done
mv "$csv.part" "$csv"
if command -v gnuplot >/dev/null 2>&1; then
    grep '^albedo' "$csv" | tr ',' ' ' >"$work/albedo.dat"
    grep '^density' "$csv" | tr ',' ' ' >"$work/density.dat"
    gnuplot <<EOF
set terminal pngcairo size 960,400
set output "$OUT/multiple-scattering.png.part"
set multiplot layout 1,2 title "volcaustics (single scattering) against the full reference: $SCENE, $SIZE, $SPP spp"
set key top left
set yrange [0:1.2]
set xlabel "albedo (sigma_t 0.27 /m)"
plot "$work/albedo.dat" using 4:6 with linespoints title "multiple-scattering share", \
     "" using 4:(1-\$7) with linespoints title "1 - mean(D)/mean(all)", \
     "" using 4:8 with linespoints title "rel. RMSE of D"
set xlabel "sigma_t (/m, albedo 0.93)"
plot "$work/density.dat" using 5:6 with linespoints title "multiple-scattering share", \
     "" using 5:(1-\$7) with linespoints title "1 - mean(D)/mean(all)", \
     "" using 5:8 with linespoints title "rel. RMSE of D"
unset multiplot
EOF
    mv "$OUT/multiple-scattering.png.part" "$OUT/multiple-scattering.png"
fi
echo "volcaustics_multiple: $csv"
