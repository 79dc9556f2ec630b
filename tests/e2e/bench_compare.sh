#!/bin/sh
# tools/bench_compare.sh (`make bench-compare REV=...`) without building anything: its table from
# fabricated stats CSVs (medians past the warm-up, a blank cell as 0, the ratio new / old), and its
# failure paths (bad usage and an unknown REV exit 2 naming the fault; a CSV with no PASS_ms column
# or no frame past the warm-up exits 1 naming the file).
. tests/e2e/lib.sh
BC=tools/bench_compare.sh
mkdir -p "$TMP/old" "$TMP/new"
hdr=frame,time_s,scene,method,frame_ms,gi_ms,gi.vct_trace_ms,vct_res
# old runs: frame 0 is a warm-up outlier (1000 ms); past it the medians are 100/80 and 120/90
printf '%s\n0,0,cornell,vct,1000,900,800,64\n1,0,cornell,vct,100,90,80,64\n2,0,cornell,vct,110,,82,64\n3,0,cornell,vct,90,88,78,64\n' "$hdr" >"$TMP/old/run-1.csv"
printf '%s\n0,0,cornell,vct,1000,900,800,64\n1,0,cornell,vct,120,90,90,64\n2,0,cornell,vct,120,90,90,64\n' "$hdr" >"$TMP/old/run-2.csv"
printf '%s\n0,0,cornell,vct,1000,900,800,64\n1,0,cornell,vct,130,90,95,64\n2,0,cornell,vct,130,90,95,64\n' "$hdr" >"$TMP/old/run-3.csv"
# new runs: 50/30, 40/20, 60/40 -> medians of the runs 50 and 30
for r in 1:50:30 2:40:20 3:60:40; do
    printf '%s\n0,0,cornell,vct,999,9,9,64\n1,0,cornell,vct,%s,5,%s,64\n' "$hdr" "$(echo $r | cut -d: -f2)" "$(echo $r | cut -d: -f3)" >"$TMP/new/run-$(echo $r | cut -d: -f1).csv"
done
expect_exit 0 "--summarize: fabricated runs" sh $BC --summarize "$TMP/old" "$TMP/new" 1
row() { awk -v k="$1" '$1 == k { print $2, $3, $4 }' "$TMP/stdout"; }
# old frame_ms: run medians 100 (100,110,90), 120, 130 -> 120; new: 50, 40, 60 -> 50; 50/120 = 0.417
check "frame_ms: median of run medians, old 120, new 50, ratio 0.417" [ "$(row frame_ms)" = "120.000 50.000 0.417" ]
# gi.vct_trace: old run medians 80, 90, 95 -> 90; new 30, 20, 40 -> 30; 30/90 = 0.333
check "gi.vct_trace_ms: old 90, new 30, ratio 0.333" [ "$(row gi.vct_trace_ms)" = "90.000 30.000 0.333" ]
# gi_ms old run 1 has a blank cell (the pass did not run): 0, 88, 90 -> 88; runs 88, 90, 90 -> 90
check "a blank cell counts 0 (gi_ms old 90)" [ "$(row gi_ms | cut -d' ' -f1)" = "90.000" ]
check "non-time columns are not in the table" sh -c "! grep -q vct_res '$TMP/stdout'"
expect_exit 1 "--summarize: no frame past a 3-frame warm-up" sh $BC --summarize "$TMP/old" "$TMP/new" 3
stderr_has "run-[0-9].csv: no frame after the 3 warm-up frames" "the error names the CSV and the warm-up"
mkdir -p "$TMP/bad"
printf 'frame,time_s\n0,0\n' >"$TMP/bad/run-1.csv"
expect_exit 1 "--summarize: a CSV without PASS_ms columns" sh $BC --summarize "$TMP/bad" "$TMP/new" 0
stderr_has "bad/run-1.csv:1: no PASS_ms column" "the error names the file and line"
mkdir -p "$TMP/empty"
expect_exit 1 "--summarize: a folder without runs" sh $BC --summarize "$TMP/empty" "$TMP/new" 0
stderr_has "empty: no run-\*.csv stats files" "the error names the folder"
expect_exit 2 "no REV" sh $BC "$GIKIOSK"
stderr_has "usage: bench_compare.sh NEW_BIN REV" "usage is printed"
expect_exit 2 "empty REV (make bench-compare without REV=)" sh $BC "$GIKIOSK" ""
stderr_has "REV is empty" "the error says REV is missing"
expect_exit 2 "an unknown REV" sh $BC "$GIKIOSK" no-such-commit-xyz
stderr_has "'no-such-commit-xyz' is not a commit" "the error names the REV"
expect_exit 2 "an unknown option" sh $BC "$GIKIOSK" HEAD --sceen cornell
stderr_has "unknown option '--sceen'" "the error names the option"
expect_exit 2 "--runs not a number" sh $BC "$GIKIOSK" HEAD --runs 3x
stderr_has "runs '3x' is not a whole number" "the error names the value"
expect_exit 2 "--frames not above --warmup" sh $BC "$GIKIOSK" HEAD --frames 2 --warmup 2
stderr_has "frames \(2\) must exceed --warmup \(2\)" "the error says why"
finish
