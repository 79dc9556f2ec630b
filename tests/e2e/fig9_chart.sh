#!/bin/sh
# lgv's Fig. 9 chart in `make bench` (tools/fig9_chart.sh, the harness tests/gpu/test_lgv.c
# fig9_chart): the CSV, the chart and its data are written, and the CSV's errors are what
# `gikiosk compare` (another code path: the CLI's metrics on the EXRs the run wrote) gives for
# the averaged image and its two halves. Small and fast: 2 frames of 16384 photons at 16 and 32
# cells (the bench's own run is 4 x 262144 at 16, 32, 48).
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless
TEST_LGV=$BUILD/tests/gpu/test_lgv
REF=tests/references/glass-indirect.exr
OUT=$TMP/fig9

check "the harness is built ($TEST_LGV)" [ -x "$TEST_LGV" ]
FIG9_PHOTONS=16384 FIG9_FRAMES=2 FIG9_SIZES=16,32 expect_exit 0 "fig9_chart.sh: 2 x 16384 photons at 16, 32 cells" \
    sh tools/fig9_chart.sh "$TEST_LGV" "$OUT"
CSV=$OUT/fig9-glass.csv
check "fig9-glass.csv: the header" \
    sh -c "head -1 '$CSV' | grep -qx 'scene,lgv_size,dims,photons,frames,rel_rmse,noise,noise_free_error,mean_ratio,gi.lgv_gather_ms,gi.lgv_trace_ms,gi_ms'"
check "fig9-glass.csv: one row per size, in order" \
    sh -c "[ \"\$(awk -F, 'NR > 1 { printf \"%s:%s \", \$2, \$3 }' '$CSV')\" = '16:16x16x16 32:32x32x32 ' ]"
check "fig9-glass.csv: the photons in all (2 x 16384) and the frames" \
    awk -F, 'NR > 1 && !($4 == 32768 && $5 == 2) { bad = 1 } END { exit bad || NR != 3 }' "$CSV"
# The times: the gather and the trace are passes nested in the method's (the frame report's
# inclusive times), so each is positive and together they are at most the method's.
check "fig9-glass.csv: lgv_gather and lgv_trace timed, inside the method's time" \
    awk -F, 'NR > 1 && !($10 > 0 && $11 > 0 && $10 + $11 <= $12) { bad = 1 } END { exit bad }' "$CSV"
for f in dat gp png svg; do
    check "fig9-glass.$f written" [ -s "$OUT/fig9-glass.$f" ]
done
check "fig9-glass.dat: the CSV's gather time, error and noise-free error per size" \
    sh -c "awk -F, 'NR > 1 { print \$10, \$6, \$8 }' '$CSV' >'$TMP/want' && grep -v '^#' '$OUT/fig9-glass.dat' | cut -d' ' -f1-3 | diff -q - '$TMP/want' >/dev/null"

rel() { # rel_rmse of the EXR against the reference, by gikiosk compare
    "$GIKIOSK" compare "$REF" "$1" --json | sed 's/.*"rel_rmse": \([^,]*\),.*/\1/'
}
for size in 16 32; do
    e=$(rel "$OUT/fig9-glass-$size.exr"); ea=$(rel "$OUT/fig9-glass-$size-a.exr"); eb=$(rel "$OUT/fig9-glass-$size-b.exr")
    row=$(awk -F, -v s=$size 'NR > 1 && $2 == s' "$CSV")
    # The CSV's error is the averaged image's, written with 6 decimals (the EXR is 32-bit float: exact;
    # measured 1.1e-6 relative apart, the decimals).
    check "size $size: rel_rmse is compare's ($e)" \
        awk -v r="$row" -v e="$e" 'BEGIN { split(r, c, ","); exit !(e > 0 && (c[6] - e) ^ 2 < (1e-5 * e) ^ 2) }'
    # The noise and the noise-free error from the three errors alone: with m the halves' average,
    # |a-r|^2 + |b-r|^2 = 2|m-r|^2 + |a-b|^2 / 2, so noise^2 = (|a-b| / 2)^2 = (ea^2 + eb^2) / 2 - e^2 and
    # bias^2 = e^2 - noise^2 (every error over the reference's mean). The CSV's come from the halves'
    # difference directly (noise_free_error). Tolerance 2e-5 relative: the CSV's 6 decimals and the
    # float sums of the average; measured at most 2.0e-6 (noise 1.4e-6, error 1.1e-6).
    check "size $size: noise and noise-free error from compare's errors of the average and its halves ($e, $ea, $eb)" \
        awk -v r="$row" -v e="$e" -v a="$ea" -v b="$eb" 'BEGIN {
            split(r, c, ","); n2 = (a * a + b * b) / 2 - e * e; n = sqrt(n2 > 0 ? n2 : 0)
            bias = sqrt(e * e - n * n > 0 ? e * e - n * n : 0)
            exit !(n > 0 && (c[7] - n) ^ 2 < (2e-5 * n) ^ 2 && (c[8] - bias) ^ 2 < (2e-5 * bias) ^ 2) }'
done
finish
