#!/bin/sh
# Budgets belong to a scene's visit (issue: after atrium every scene of the tour ran at the floor).
# cornell with vct under an impossible 1 ms target drives its knobs down; shadow-planes after it
# starts from the defaults (every knob, as on the run's first frame), not from cornell's levels;
# back on cornell the kiosk starts from cornell's remembered levels instead of from scratch. The summary
# reports warm-up frames apart from the judged ones.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless

printf '[playlist]\nscenes = cornell, shadow-planes\ndwell_s = 1\n' >"$TMP/k.ini"
expect_exit 0 "tour cornell -> shadow-planes -> cornell at a 1 ms target" "$GIKIOSK" run --config "$TMP/k.ini" \
    --platform mock --size 64x48 --method vct --seconds 2.4 --target-ms 1 --stats "$TMP/s.csv"
cp "$TMP/stdout" "$TMP/summary"
# The knob columns (render_scale to the end) of the first and last frame of each visit.
c_knobs=$(head -1 "$TMP/s.csv" | tr ',' '\n' | grep -n '^render_scale$' | cut -d: -f1)
awk -F, -v k="$c_knobs" 'NR > 1 { levels = ""; for (i = k; i <= NF; i++) levels = levels "/" $i
        if ($3 != prev) { v++; first[v] = levels; name[v] = $3 }
        last[v] = levels; prev = $3 }
    END { for (i = 1; i <= v; i++) print i, name[i], first[i], last[i] }' "$TMP/s.csv" >"$TMP/visits"
sed 's/^/# visit /' "$TMP/visits"
check "three visits" test "$(wc -l <"$TMP/visits")" -eq 3
check "cornell's first visit ends below its defaults (the target is impossible)" \
    awk '$1 == 1 && $3 != $4 { ok = 1 } END { exit !ok }' "$TMP/visits"
check "shadow-planes starts from the defaults, not from cornell's levels" \
    awk '$1 == 1 { d = $3 } $1 == 2 && $3 == d { ok = 1 } END { exit !ok }' "$TMP/visits"
check "cornell's second visit starts where its first ended" \
    awk '$1 == 1 { end1 = $4 } $1 == 3 { start3 = $3 } END { exit !(end1 != "" && start3 == end1) }' "$TMP/visits"
check "the summary reports warm-up frames apart from the judged ones" \
    grep -Eq '^scene cornell: [0-9]+ frames \([1-9][0-9]* warm-up, max [0-9.]+ ms\), judged: median [0-9.]+ ms, p95 [0-9.]+ ms, p99' "$TMP/summary"
finish
