#!/bin/sh
# `gikiosk bench --roofline` as `make bench` runs it: roofline.csv with one row per kind of fetch,
# each rate equal to its fetches over its time (recomputed here), the shader's own count of the
# fetches it did equal to what was asked (from the log), and a missing --out is bad usage.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless

expect_exit 0 "bench --roofline" sh -c "'$GIKIOSK' bench --roofline --out '$TMP/r' 2>'$TMP/r.log'"
CSV=$TMP/r/roofline.csv
check "roofline.csv header" sh -c "head -1 '$CSV' | grep -qx 'name,format,size,fetches,median_ms,fetches_per_s'"
for kind in tex3d_rgba8_trilinear tex3d_rgba16f_trilinear tex2d_rgba8_trilinear tex2d_rgba16f_trilinear \
    tex2d_rgba32f_nearest tex2d_depth32f_nearest tex2d_r32f_nearest tex2d_r32ui_nearest tex2d_r16f_nearest \
    image3d_rgba8_load image3d_rgba16f_load ssbo_rgba32f_load ssbo_r32ui_atomic raster_r16f_depth_fill; do
    check "roofline.csv: a row for $kind" grep -q "^$kind," "$CSV"
done
check "roofline.csv: fourteen kinds" [ "$(wc -l <"$CSV")" -eq 15 ]
# the rate is fetches / time: recomputed from the row's own columns (within the %.6g print)
check "roofline.csv: fetches_per_s = fetches / median_ms, positive" \
    sh -c "awk -F, 'NR > 1 { r = \$4 / (\$5 * 1e-3); if (!(\$6 > 0) || (\$6 - r) > 1e-4 * r || (r - \$6) > 1e-4 * r) bad = 1 } END { exit bad }' '$CSV'"
# 64^3 invocations x 64 fetches per dispatch, 5 timed dispatches: the shader counted each one; the
# raster kind's counting run: 64 triangles over a 512x512 target, once
check "the shader counted 5 x 64^3 x 64 fetches per fetch kind" \
    sh -c "[ \"\$(grep -c 'counted 83886080 of 83886080)' '$TMP/r.log')\" -eq 13 ]"
check "the fill's counting run counted 64 x 512^2 fragments" grep -q 'raster_r16f_depth_fill .*M fragments/s .*counted 16777216 of 16777216)' "$TMP/r.log"
# The log prints each rate with %.1f from the double, the CSV with %.6g: rounding twice can differ by one
# in the last printed digit (a rate of 123.44999 M is 123.4 in the log and 1.2345e8, so 123.5, from the
# CSV), so each log rate must be within 0.05 M of the CSV's plus the CSV's own half-unit in 6 digits.
check "roofline.csv: the log prints the CSV's rates" \
    sh -c "sed -n 's/.*roofline \\([a-z0-9_]*\\) *\\([0-9.]*\\) M f[a-z]*\\/s.*/\\1 \\2/p' '$TMP/r.log' >'$TMP/log_rates' &&
           [ \"\$(wc -l <'$TMP/log_rates')\" -eq 14 ] &&
           awk -F, 'NR == FNR { split(\$0, f, \" \"); log_rate[f[1]] = f[2]; next }
                    FNR > 1 { if (!(\$1 in log_rate)) bad = 1; m = \$6 * 1e-6; d = log_rate[\$1] - m; if (d < 0) d = -d;
                              if (d > 0.05 + 5e-6 * m + 1e-9) bad = 1; n++ }
                    END { exit bad || n != 14 }' '$TMP/log_rates' '$CSV'"
expect_exit 2 "bench --roofline without --out" "$GIKIOSK" bench --roofline
: >"$TMP/a-file"
expect_exit 1 "bench --roofline into a folder that cannot be made" sh -c "'$GIKIOSK' bench --roofline --out '$TMP/a-file/r' 2>'$TMP/bad.log'"
check "the error names the folder" grep -q "cannot create $TMP/a-file" "$TMP/bad.log"
finish
