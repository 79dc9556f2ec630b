#!/bin/sh
# Faults a kiosk meets (issue 12): nothing lost and no silent success. A run that fails at start
# keeps the previous stats CSV; SIGHUP and SIGQUIT end a run like SIGTERM (exit 0, CSV written);
# SIGKILL leaves the spool, a valid CSV with the rows so far; a capture that cannot be written
# completely (a file-size limit: write(2) fails as on a full disk) exits 1 leaving the previous
# file whole and no temporary file; stdout on a full disk, closed, or a dead pipe is exit 1
# naming standard output (never death by SIGPIPE, exit 141); stderr closed is exit 1 too.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless
S=config/scenes
lines() { if [ -f "$1" ]; then wc -l <"$1"; else echo 0; fi; }
RUN="$GIKIOSK run --platform mock --size 64x64 --scenes-dir $S --scene cornell --method none"

# --- a run that fails at start leaves the previous CSV as it was
echo "previous run" >"$TMP/keep.csv"
expect_exit 2 "a run with a missing scene exits 2" $RUN --scene nowhere --frames 1 --stats "$TMP/keep.csv"
check "failed start: the previous CSV is untouched" grep -qx "previous run" "$TMP/keep.csv"
check "failed start: no spool left" [ ! -e "$TMP/keep.csv.part" ]

# --- SIGHUP and SIGQUIT: a clean end, the CSV written, the spool gone
for sig in HUP QUIT; do
    $RUN --seconds 100000 --stats "$TMP/$sig.csv" >"$TMP/$sig.out" 2>"$TMP/$sig.err" &
    pid=$!
    i=0
    while [ $i -lt 600 ] && [ "$(lines "$TMP/$sig.csv.part")" -lt 3 ]; do sleep 0.1; i=$((i + 1)); done
    kill -$sig $pid
    wait $pid
    rc=$?
    check "SIG$sig ends the run with exit 0 (got $rc)" [ "$rc" -eq 0 ]
    check "SIG$sig: the CSV has the header and rows" \
        sh -c "head -1 '$TMP/$sig.csv' | grep -q '^frame,time_s,scene,method,frame_ms,' && [ \$(wc -l <'$TMP/$sig.csv') -ge 3 ]"
    check "SIG$sig: the spool is removed" [ ! -e "$TMP/$sig.csv.part" ]
done

# --- SIGKILL: the spool survives as a CSV (7 fields a row), the log names it
echo "previous run" >"$TMP/kill.csv"
$RUN --seconds 100000 --stats "$TMP/kill.csv" >/dev/null 2>"$TMP/kill.err" &
pid=$!
i=0
while [ $i -lt 600 ] && [ "$(lines "$TMP/kill.csv.part")" -lt 3 ]; do sleep 0.1; i=$((i + 1)); done
kill -KILL $pid
wait $pid 2>/dev/null
check "SIGKILL: the log named the spool" grep -q "rows spooled to $TMP/kill.csv.part" "$TMP/kill.err"
check "SIGKILL: the previous CSV is untouched" grep -qx "previous run" "$TMP/kill.csv"
check "SIGKILL: the spool's header" sh -c "head -1 '$TMP/kill.csv.part' | grep -qx 'frame,time_s,scene,method,frame_ms,passes_ms,budgets'"
check "SIGKILL: every spooled row has 7 fields, frames 0, 1, 2... in order" \
    awk -F, 'NR > 1 { if (NF != 7 || $1 != NR - 2) bad = 1; n++ } END { exit bad || n < 2 }' "$TMP/kill.csv.part"
# the next run spools beside the killed run's spool, never over it
expect_exit 0 "a run after the killed one" $RUN --frames 2 --stats "$TMP/kill.csv"
stderr_has "rows spooled to .*kill.csv.part-2" "the next run's spool is FILE.part-2"
check "the killed run's spool is kept" [ "$(wc -l <"$TMP/kill.csv.part")" -ge 3 ]
check "the next run's CSV is written" [ "$(wc -l <"$TMP/kill.csv")" -eq 3 ]

# --- a capture that cannot be written whole: exit 1, the previous file whole, no temporary file
mkdir -p "$TMP/cap"
echo "previous capture" >"$TMP/cap/000001-cornell-none.png"
# bash counts ulimit -f in KiB, dash in 512-byte blocks: 2 units are at most 2 KiB, and a 64x64
# capture of cornell is about 4 KiB (PNG) and 13 KiB (EXR).
(ulimit -f 2 && exec $RUN --frames 2 --capture "$TMP/cap" --hdr) >"$TMP/stdout" 2>"$TMP/stderr"
rc=$?
check "capture beyond the file-size limit exits 1 (got $rc)" [ "$rc" -eq 1 ]
stderr_has "capture: .*000001-cornell-none.(png|exr).*(cannot write|File too large)" "the failing capture is named"
check "the previous capture is untouched" grep -qx "previous capture" "$TMP/cap/000001-cornell-none.png"
check "no temporary file is left" [ "$(ls -A "$TMP/cap" | wc -l)" -eq 1 ]

# --- stdout: full disk, closed, a dead pipe
expect_exit 1 "scenes with stdout on a full disk exits 1" sh -c "exec $GIKIOSK scenes --dir $S >/dev/full"
stderr_has "cannot write to standard output: No space left on device" "full stdout is named"
expect_exit 1 "--version with stdout closed exits 1" sh -c "exec $GIKIOSK --version >&-"
stderr_has "cannot write to standard output: it was closed" "closed stdout is named"
# stderr closed: the log cannot be written (exit 1), and it never lands in a file the run opens
sh -c "exec $RUN --frames 2 --stats '$TMP/noerr.csv' >/dev/null 2>&-"
rc=$?
check "run with stderr closed exits 1 (got $rc)" [ "$rc" -eq 1 ]
check "stderr closed: the CSV holds only the header and 2 rows" \
    sh -c "[ \$(wc -l <'$TMP/noerr.csv') -eq 3 ] && ! grep -q gikiosk: '$TMP/noerr.csv'"
# the reader is gone before the kiosk prints its summary: exit 1 (not 141), the CSV still written
{ sleep 0.5; $RUN --frames 2 --stats "$TMP/pipe.csv" 2>"$TMP/pipe.err"; echo $? >"$TMP/pipe.rc"; } | true
check "run into a dead pipe exits 1, not killed by SIGPIPE (got $(cat "$TMP/pipe.rc"))" [ "$(cat "$TMP/pipe.rc")" = 1 ]
check "dead pipe: reported" grep -q "cannot write to standard output" "$TMP/pipe.err"
check "dead pipe: the stats CSV is written" [ "$(wc -l <"$TMP/pipe.csv")" -eq 3 ]
finish
