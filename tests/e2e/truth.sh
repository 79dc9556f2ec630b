#!/bin/sh
# The kiosk's live ground truth (issue 19, README "Live error"): on cornell at 320x180 with vct, and
# on caustic-ring (mirrors: the truth's light pass) at 160x90 with ispm, the error the kiosk
# measures against the truth it computes itself converges to what `gikiosk compare` reports for the
# same frame against a reference rendered at that size; the stats CSV's error and
# truth_spp columns; a scene change restarts the truth; [truth] off leaves the CSV as it was.
. tests/e2e/lib.sh

json_field() { sed -n "s/.*\"$1\": \(\[[^]]*\]\|[^,}]*\).*/\1/p" "$2"; }
# within A B F: |A / B - 1| < F
within() { awk -v a="$1" -v b="$2" -v f="$3" 'BEGIN { if (a == "" || b == "" || b + 0 == 0) exit 1; r = a / b - 1; if (r < 0) r = -r; exit !(r < f) }'; }
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }
# column NAME FILE: the values of a CSV column (no quoted commas in these files)
column() { awk -F, -v n="$1" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == n) c = i; next } c { print $c }' "$2"; }

# live_against_compare SCENE METHOD SIZE FRAMES PINS: SCENE's reference at SIZE (64 spp), then the
# kiosk with the truth at the frame's size (sub = 1: the error is taken on the same pixels compare
# sees), the knobs pinned so the frame does not change under the measurement, and compare of its
# last frame against the reference. Sets run_s, cmp_err, live_err, spp, first_s (from when on the
# live error stayed within 10% of compare's, in seconds of the run); files in $TMP/SCENE/.
live_against_compare() {
    D="$TMP/$1"
    mkdir -p "$D"
    t0=$(now)
    "$GIKIOSK" reference --scene "$1" --size "$3" --spp 64 --threads 2 --out "$D/ref.exr" >"$D/ref.log" 2>&1
    check "$1: reference $3 renders" [ $? -eq 0 ]
    echo "# $1: reference $3, 64 spp, 2 threads: $(secs "$t0" "$(now)") s"
    printf '[truth]\nenabled = true\nworkers = 1\nsize = %s\n' "$3" >"$D/truth.ini"
    t0=$(now)
    "$GIKIOSK" run --config "$D/truth.ini" --platform mock --scene "$1" --method "$2" --size "$3" \
        --frames "$4" --budget "$5" --hdr --capture "$D/cap" --stats "$D/s.csv" >"$D/run.log" 2>&1
    check "$1: run with [truth] enabled exits 0" [ $? -eq 0 ]
    run_s=$(secs "$t0" "$(now)")
    echo "# $1: kiosk run, $4 frames with the truth: $run_s s"
    grep "truth:" "$D/run.log" | sed 's/^/# /'
    "$GIKIOSK" compare "$D/ref.exr" "$D/cap/$(printf %06d $(($4 - 1)))-$1-$2.exr" --json >"$D/cmp.json"
    check "$1: compare exits 0" [ $? -eq 0 ]
    cmp_err=$(json_field rel_rmse "$D/cmp.json")
    live_err=$(column error "$D/s.csv" | tail -1)
    spp=$(column truth_spp "$D/s.csv" | tail -1)
    echo "# $1: compare rel_rmse $cmp_err; live error $live_err at truth $spp spp"
    # the first measurement after the last one outside 10% (an early one at a few spp can land
    # near by chance), and its wall time: its share of the run's summed frame times
    first=$(awk -F, -v e="$(head -1 "$D/s.csv" | tr ',' '\n' | grep -n '^error$' | cut -d: -f1)" -v c="$cmp_err" \
        'NR > 1 && $e != "" && $e != last { last = $e; r = $e / c - 1; if (r < 0) r = -r; if (r >= 0.10) f = ""; else if (f == "") f = $1 }
         END { print f }' "$D/s.csv")
    first_s=$(awk -F, -v f="${first:--1}" -v t="$run_s" 'NR > 1 { s += $5; if ($1 == f) a = s } END { printf "%.1f", (s > 0 ? a / s * t : 0) }' "$D/s.csv")
    echo "# $1: within 10% from frame ${first:-never} of $4 on (about $first_s s into the run)"
}

live_against_compare cornell vct 320x180 600 render_scale=1,vct_res=64,vct_cones=6,vct_step=1,vct_trace_scale=0.5,vct_mips=aniso
check "the truth starts its workers at the lowest priority" grep -q "truth: 1 worker at the lowest priority, 320x180" "$TMP/cornell/run.log"
check "the truth starts on cornell" grep -q "truth: cornell restarted" "$TMP/cornell/run.log"
# The issue's bound: within 10% of compare's number. The truth's noise adds in quadrature
# (E[error^2] = error^2 + noise^2); measured (llvmpipe, this box, 2 cores shared): compare 0.1767,
# live 0.1754 at 72 spp and 0.1792 at 54 spp in two runs; first within 10% after about 300 frames
# (24 s of a 48 s run, truth noise 0.085 at 42 spp).
check "the live error is within 10% of compare's" within "$live_err" "$cmp_err" 0.10
check "the truth has samples at the end" [ "${spp:-0}" -ge 2 ]

# The CSV: error and truth_spp after the knob columns; empty before the first measurement;
# truth_spp never decreases while the view stays.
S="$TMP/cornell/s.csv"
check "CSV header ends with error,truth_spp" sh -c "head -1 '$S' | grep -q ',error,truth_spp\$'"
# a row has an error exactly when it has a truth_spp (the error is measured against that truth)
check "CSV error and truth_spp come together" sh -c "awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if (\$i == \"error\") e = i; if (\$i == \"truth_spp\") s = i }; next } ((\$e == \"\") != (\$s == \"\")) { exit 1 }' '$S'"
check "CSV truth_spp never decreases" sh -c "column() { awk -F, -v n=\"\$1\" 'NR == 1 { for (i = 1; i <= NF; i++) if (\$i == n) c = i; next } c { print \$c }' \"\$2\"; }; column truth_spp '$S' | awk '\$1 != \"\" { if (\$1 + 0 < last) exit 1; last = \$1 + 0 }'"

# A scene with mirrors: the truth runs the reference's light pass too (caustics seen directly), so
# on caustic-ring, with ispm (the caustic method) pinned, the live error converges to compare's
# as well. (tests/unit/test_truth.c checks the truth itself against the committed caustic-ring and
# glass references, inside their caustic masks.) Measured (llvmpipe, this 2-core machine shared
# with other builds): compare 0.549 against the 64-spp reference (its own noise floor 0.14 adds in
# quadrature as the truth's does); live 0.600 at 15 spp, within 10% from there on, about 14 s into
# a 70 s run; 0.5605 at 36 spp at its end; with less load beside it, 0.539 at 151 spp. Below ~15
# spp the truth's noise alone pushes the live error past 10%: the spp check says when the machine
# was too busy to get there.
live_against_compare caustic-ring ispm 160x90 900 render_scale=1,shadow=hard,shadow_map=512,env_lights=4,shadow_subdiv=0,ispm_photons=1024,ispm_trace=64,ispm_splat=0.25,ispm_pool=2
check "a scene with mirrors gets a live truth" grep -q "truth: caustic-ring restarted (view 1)" "$TMP/caustic-ring/run.log"
check "caustic-ring: the truth reached 15 spp (it got enough of a core)" [ "${spp:-0}" -ge 15 ]
check "caustic-ring: the live error is within 10% of compare's" within "$live_err" "$cmp_err" 0.10

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
