#!/bin/sh
# `gikiosk bench` as a user runs it: a two-point sweep on shadow-planes writes bench.csv with the
# contract's columns and the speed-against-accuracy chart; bad sweeps and missing options exit 2.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless

expect_exit 0 "bench: two shadow methods on shadow-planes" "$GIKIOSK" bench --scenes shadow-planes --methods none \
    --sweep "shadow=hard,pcss;shadow_map=256" --frames 1 --warmup 0 --out "$TMP/b"
CSV=$TMP/b/bench.csv
check "bench.csv exists" [ -f "$CSV" ]
check "bench.csv header: scene,method,knobs...,frame_ms_median,frame_ms_p95,rel_rmse,ssim" \
    sh -c "head -1 '$CSV' | grep -q '^scene,method,.*shadow_map.*,frame_ms_median,frame_ms_p95,reference,rel_rmse,ssim,psnr,mean_ratio,test_mean,pareto'"
check "bench.csv: one row per configuration" [ "$(wc -l <"$CSV")" -eq 3 ]
check "bench.csv: method none is measured against the direct reference" \
    sh -c "awk -F, 'NR > 1 && \$0 !~ /,shadow-planes-direct,/ { bad = 1 } END { exit bad }' '$CSV'"
# Columns by name, so the test follows the header.
col() { head -1 "$CSV" | tr ',' '\n' | grep -n "^$1\$" | cut -d: -f1; }
c_shadow=$(col shadow)
c_err=$(col rel_rmse)
c_ms=$(col frame_ms_median)
check "bench.csv: the sweep's values, in order" \
    sh -c "[ \"\$(awk -F, -v c=$c_shadow 'NR > 1 { printf \"%s \", \$c }' '$CSV')\" = 'hard pcss ' ]"
check "bench.csv: error and time measured for every row" \
    sh -c "awk -F, -v e=$c_err -v t=$c_ms 'NR > 1 && (\$e == \"\" || \$t == \"\" || \$t <= 0) { bad = 1 } END { exit bad }' '$CSV'"
# PCSS is the accurate one on the analytic scene: its error must be below hard shadows'.
check "pcss is more accurate than hard shadows on shadow-planes" \
    sh -c "awk -F, -v e=$c_err -v s=$c_shadow 'NR > 1 { err[\$s] = \$e } END { exit !(err[\"pcss\"] < err[\"hard\"]) }' '$CSV'"
check "chart: speed-accuracy-shadow-planes.png" [ -s "$TMP/b/speed-accuracy-shadow-planes.png" ]
check "chart: speed-accuracy-shadow-planes.svg" [ -s "$TMP/b/speed-accuracy-shadow-planes.svg" ]

expect_exit 2 "bench: unknown knob in --sweep exits 2" "$GIKIOSK" bench --scenes shadow-planes --sweep "shadows=hard" --out "$TMP/c"
stderr_has "unknown knob 'shadows'" "bench: the message names the knob"
expect_exit 2 "bench: missing --out exits 2" "$GIKIOSK" bench --scenes shadow-planes
expect_exit 2 "bench: unknown scene exits 2" "$GIKIOSK" bench --scenes no-such-scene --out "$TMP/d"
stderr_has "no-such-scene" "bench: the message names the scene"
finish
