#!/bin/sh
# Seed 002's Fig. 9, the LGV size trade-off, as a chart (`make bench`, README lgv): per LGV size,
# glass's indirect light (the LGV alone) against tests/references/glass-indirect.exr, as measured
# and without the photon noise (the bias), against the grid's own cost, the lgv_gather pass.
# The numbers come from the GPU test's harness (tests/gpu/test_lgv.c, fig9_chart: the LGV's
# lookup drawn alone, which the kiosk's frame never shows), written to OUT/fig9-glass.csv with the
# averaged images beside it (fig9-glass-SIZE.exr and its halves -a/-b); this script draws
# OUT/fig9-glass.png/.svg from OUT/fig9-glass.dat (`gnuplot OUT/fig9-glass.gp` redraws them).
# Usage: tools/fig9_chart.sh TEST_LGV OUT. FIG9_PHOTONS (per frame, an lgv_photons value),
# FIG9_FRAMES (even) and FIG9_SIZES override the test's 4 x 262144 photons at 16,32,48 cells.
# About 20 s on llvmpipe (2 loaded cores) at the defaults; run from the repository root.
set -eu
TEST=$1
OUT=$2
mkdir -p "$OUT"
export EGL_PLATFORM=${EGL_PLATFORM:-surfaceless}
GK_LGV_FIG9_OUT=$OUT GK_LGV_FIG9_PHOTONS=${FIG9_PHOTONS:-262144} GK_LGV_FIG9_FRAMES=${FIG9_FRAMES:-4} \
    GK_LGV_FIG9_SIZES=${FIG9_SIZES:-16,32,48} CMOCKA_MESSAGE_OUTPUT=TAP "$TEST" >"$OUT/fig9-glass.log" 2>&1 || {
    cat "$OUT/fig9-glass.log" >&2
    echo "fig9_chart: $TEST failed (its output above)" >&2
    exit 1
}
CSV=$OUT/fig9-glass.csv
DAT=$OUT/fig9-glass.dat
GP=$OUT/fig9-glass.gp
# Columns by name, so the script follows the CSV's header.
col() { head -1 "$CSV" | tr ',' '\n' | grep -n "^$1\$" | cut -d: -f1; }
c_size=$(col lgv_size); c_err=$(col rel_rmse); c_bias=$(col noise_free_error); c_gather=$(col gi.lgv_gather_ms)
c_gi=$(col gi_ms); c_ph=$(col photons); c_fr=$(col frames)
# One row per size: the gather time, both errors, and the point's label (the grid, the method's time).
awk -F, -v s="$c_size" -v e="$c_err" -v b="$c_bias" -v g="$c_gather" -v t="$c_gi" '
    NR == 1 { print "# lgv_gather_ms rel_rmse noise_free_error label (from fig9-glass.csv)"; next }
    { printf "%s %s %s \"%s^3, lgv %.0f ms\"\n", $g, $e, $b, $s, $t }' "$CSV" >"$DAT"
# printf, not echo: sh's echo would turn the title's \n into a line break of the script
say() { printf '%s\n' "$*"; }
photons=$(awk -F, -v c="$c_ph" 'NR == 2 { print $c }' "$CSV")
frames=$(awk -F, -v c="$c_fr" 'NR == 2 { print $c }' "$CSV")
{
    say "# Seed Fig. 9, the LGV size trade-off: regenerate with \`gnuplot $GP\`."
    say "set title \"glass: the LGV size trade-off (seed Fig. 9), indirect light vs glass-indirect.exr\\n$photons photons in $frames frames per size; labels: the grid, the method's passes per frame;\\nllvmpipe CPU times (the renderer's clock): compare as ratios\""
    say "set xlabel \"the grid's cost: lgv_gather pass (ms, log scale), median of the frames after the first\""
    say "set ylabel \"indirect rel. RMSE vs glass-indirect.exr\""
    say "set logscale x"
    say "set grid"
    say "set key outside right top"
    say "set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05"
    for term in png svg; do
        if [ $term = png ]; then
            say "set terminal pngcairo size 1000,640 font \"DejaVu Sans,10\" noenhanced"
        else
            say "set terminal svg size 1000,640 font \"DejaVu Sans,10\" noenhanced"
        fi
        say "set output \"$OUT/fig9-glass.$term\""
        say "plot \"$DAT\" using 1:2 with linespoints pt 7 ps 1.2 lc 1 title \"measured ($photons photons)\", \\"
        say "     \"$DAT\" using 1:2:4 with labels offset 0,0.8 font \",8\" notitle, \\"
        say "     \"$DAT\" using 1:3 with linespoints pt 5 ps 1.2 lc 2 title \"without the photon noise (the bias)\""
    done
} >"$GP"
gnuplot "$GP"
echo "fig9_chart: $CSV and $OUT/fig9-glass.png/.svg"
