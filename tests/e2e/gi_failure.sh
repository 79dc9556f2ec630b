#!/bin/sh
# A GI method that fails (here: a vct shader that does not compile, from --shader-dir) is reported
# once per scene visit, the kiosk shows the scene without it (the stats name the method really
# shown), it is not retried or logged every frame, and it is tried again on the next visit.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless

cp -r shaders_gles "$TMP/shaders"
printf 'this is not GLSL;\n' >>"$TMP/shaders/vct/trace.comp"
printf '[playlist]\nscenes = cornell, cornell-spot\ndwell_s = 1\n' >"$TMP/k.ini"

# Two visits of each scene: 0-1 s cornell, 1-2 s cornell-spot, 2-3 s cornell, ... (dwell 1 s).
expect_exit 0 "run with a broken vct shader exits 0" "$GIKIOSK" run --config "$TMP/k.ini" --platform mock \
    --size 64x48 --method vct --seconds 4 --target-ms 1000 --shader-dir "$TMP/shaders" --stats "$TMP/s.csv"
visits=$(grep -c '^gikiosk: scene [a-z-]* (method' "$TMP/stderr")
fails=$(grep -c 'GI method vct failed' "$TMP/stderr")
echo "# $visits scene visits, $fails failure reports"
check "the failure names the shader file" grep -q 'vct/trace.comp' "$TMP/stderr"
check "reported once per visit ($fails reports, $visits visits)" test "$fails" -eq "$visits" -a "$visits" -ge 3
check "the kiosk says what it shows instead" grep -q 'method vct failed, showing the scene with none' "$TMP/stderr"
rows=$(awk -F, 'NR > 1' "$TMP/s.csv" | wc -l)
vct_rows=$(awk -F, 'NR > 1 && $4 == "vct"' "$TMP/s.csv" | wc -l)
echo "# $rows frames, $vct_rows recorded as vct"
check "only the failing frame of each visit is recorded as vct" test "$vct_rows" -eq "$visits" -a "$rows" -gt "$vct_rows"
finish
