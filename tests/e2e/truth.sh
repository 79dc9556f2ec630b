#!/bin/sh
# The kiosk's live ground truth (issue 19, README "Live error"): on cornell at 320x180 with vct, the
# error the kiosk measures against the truth it computes itself converges to what `gikiosk compare`
# reports for the same frame against a reference rendered at that size; the stats CSV's error and
# truth_spp columns; a scene change restarts the truth; [truth] off leaves the CSV as it was.
. tests/e2e/lib.sh

json_field() { sed -n "s/.*\"$1\": \(\[[^]]*\]\|[^,}]*\).*/\1/p" "$2"; }
# within A B F: |A / B - 1| < F
within() { awk -v a="$1" -v b="$2" -v f="$3" 'BEGIN { if (a == "" || b == "" || b + 0 == 0) exit 1; r = a / b - 1; if (r < 0) r = -r; exit !(r < f) }'; }
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }
# column NAME FILE: the values of a CSV column (no quoted commas in these files)
column() { awk -F, -v n="$1" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == n) c = i; next } c { print $c }' "$2"; }

# The reference at the frame's size: 64 spp (noise floor ~0.07, far below the error measured).
t0=$(now)
"$GIKIOSK" reference --scene cornell --size 320x180 --spp 64 --threads 2 --out "$TMP/ref.exr" >"$TMP/ref.log" 2>&1
check "reference 320x180 renders" [ $? -eq 0 ]
echo "# reference 320x180, 64 spp, 2 threads: $(secs "$t0" "$(now)") s"

# The kiosk with the truth at the frame's size (sub = 1: the error is taken on the same pixels
# compare sees), the knobs pinned so the frame does not change under the measurement.
printf '[truth]\nenabled = true\nworkers = 1\nsize = 320x180\n' >"$TMP/truth.ini"
PINS=render_scale=1,vct_res=64,vct_cones=6,vct_step=1,vct_trace_scale=0.5,vct_mips=aniso
t0=$(now)
"$GIKIOSK" run --config "$TMP/truth.ini" --platform mock --scene cornell --method vct --size 320x180 \
    --frames 600 --budget "$PINS" --hdr --capture "$TMP/cap" --stats "$TMP/s.csv" >"$TMP/run.log" 2>&1
check "run with [truth] enabled exits 0" [ $? -eq 0 ]
run_s=$(secs "$t0" "$(now)")
echo "# kiosk run, 600 frames with the truth: $run_s s"
grep "truth:" "$TMP/run.log" | sed 's/^/# /'
check "the truth starts its workers at the lowest priority" grep -q "truth: 1 worker at the lowest priority, 320x180" "$TMP/run.log"
check "the truth starts on cornell" grep -q "truth: cornell restarted" "$TMP/run.log"

"$GIKIOSK" compare "$TMP/ref.exr" "$TMP/cap/000599-cornell-vct.exr" --json >"$TMP/cmp.json"
check "compare exits 0" [ $? -eq 0 ]
cmp_err=$(json_field rel_rmse "$TMP/cmp.json")
live_err=$(column error "$TMP/s.csv" | tail -1)
spp=$(column truth_spp "$TMP/s.csv" | tail -1)
echo "# compare rel_rmse $cmp_err; live error $live_err at truth $spp spp"
# The issue's bound: within 10% of compare's number. The truth's noise adds in quadrature
# (E[error^2] = error^2 + noise^2); measured (llvmpipe, this box, 2 cores shared): compare 0.1767,
# live 0.1754 at 72 spp and 0.1792 at 54 spp in two runs; first within 10% after about 300 frames
# (24 s of a 48 s run, truth noise 0.085 at 42 spp).
check "the live error is within 10% of compare's" within "$live_err" "$cmp_err" 0.10
check "the truth has samples at the end" [ "${spp:-0}" -ge 2 ]

# The CSV: error and truth_spp after the knob columns; empty before the first measurement;
# truth_spp never decreases while the view stays.
check "CSV header ends with error,truth_spp" sh -c "head -1 '$TMP/s.csv' | grep -q ',error,truth_spp\$'"
# a row has an error exactly when it has a truth_spp (the error is measured against that truth)
check "CSV error and truth_spp come together" sh -c "awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if (\$i == \"error\") e = i; if (\$i == \"truth_spp\") s = i }; next } ((\$e == \"\") != (\$s == \"\")) { exit 1 }' '$TMP/s.csv'"
check "CSV truth_spp never decreases" sh -c "column() { awk -F, -v n=\"\$1\" 'NR == 1 { for (i = 1; i <= NF; i++) if (\$i == n) c = i; next } c { print \$c }' \"\$2\"; }; column truth_spp '$TMP/s.csv' | awk '\$1 != \"\" { if (\$1 + 0 < last) exit 1; last = \$1 + 0 }'"
# How soon it converged: the first measurement within 10% of compare's number (the frame's wall
# time estimated from the run's frame rate).
first=$(awk -F, -v e="$(head -1 "$TMP/s.csv" | tr ',' '\n' | grep -n '^error$' | cut -d: -f1)" -v c="$cmp_err" \
    'NR > 1 && $e != "" { r = $e / c - 1; if (r < 0) r = -r; if (r < 0.10) { print $1; exit } }' "$TMP/s.csv")
echo "# first within 10%: frame ${first:-never} of 600 (about $(awk -v f="${first:-0}" -v t="$run_s" 'BEGIN { printf "%.1f", f / 600 * t }') s of the run)"

# A scene change restarts the truth (a new view); a split view toggles on info hold.
printf '[truth]\nenabled = true\nworkers = 1\n[playlist]\nscenes = cornell, shadow-planes\n' >"$TMP/two.ini"
printf '1 info hold 900\n2.5 next click\n' >"$TMP/script.txt"
"$GIKIOSK" run --config "$TMP/two.ini" --platform mock --size 160x90 --method none --seconds 4 \
    --script "$TMP/script.txt" >"$TMP/two.log" 2>&1
check "two-scene run exits 0" [ $? -eq 0 ]
check "the next scene restarts the truth (view 2)" grep -q "truth: shadow-planes restarted (view 2)" "$TMP/two.log"
check "info hold toggles the split view" grep -q "split view on" "$TMP/two.log"

# [truth] off (the default): no truth, the CSV as before.
"$GIKIOSK" run --platform mock --scene cornell --method none --size 160x90 --frames 3 --stats "$TMP/off.csv" \
    >"$TMP/off.log" 2>&1
check "run without the truth exits 0" [ $? -eq 0 ]
check "without the truth the CSV has no error column" sh -c "! head -1 '$TMP/off.csv' | grep -q error"
check "without the truth nothing is traced" sh -c "! grep -q 'truth:' '$TMP/off.log'"

# A bad [truth] value: exit 2 naming file and line.
printf '[truth]\nenabled = maybe\n' >"$TMP/bad.ini"
expect_exit 2 "bad [truth] enabled exits 2" "$GIKIOSK" run --config "$TMP/bad.ini" --platform mock --frames 1
stderr_has "bad.ini:2: enabled: 'maybe' is not true or false" "the error names file and line"
finish
