#!/bin/sh
# make tsan: ThreadSanitizer runs of the live ground truth's threads (see the Makefile). Any report
# fails the run (exitcode 66); tests/tsan.supp holds the suppressions, each with its reason.
set -u
BUILD=${1:-build-tsan}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/gikiosk-tsan.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
export TSAN_OPTIONS="suppressions=$(pwd)/tests/tsan.supp exitcode=66 halt_on_error=0 second_deadlock_stack=1"
# Mesa's shader cache in the build tree, as the test suite keeps it
export MESA_SHADER_CACHE_DIR="$BUILD/mesa-shader-cache"
fail=0
echo "tsan: the truth's unit test (2 workers, 20 restarts and stops, convergence)"
"$BUILD/tests/unit/test_truth" >"$TMP/unit.log" 2>&1 || { fail=1; tail -40 "$TMP/unit.log"; }
grep -q "WARNING: ThreadSanitizer" "$TMP/unit.log" && { fail=1; grep -A20 "WARNING: ThreadSanitizer" "$TMP/unit.log" | head -60; }
# The kiosk with the truth on: two scenes (a restart mid-run), the split view, the HUD plot, the
# stats CSV -- every path where the render thread reads what the workers write.
printf '[truth]\nenabled = true\nworkers = 2\n[playlist]\nscenes = cornell, shadow-planes\n' >"$TMP/truth.ini"
printf '0.5 info hold 900\n1.5 next click\n2.5 prev click\n' >"$TMP/script.txt"
echo "tsan: the kiosk with [truth] enabled (2 workers, 2 scene changes, split view), mock platform"
"$BUILD/gikiosk" run --config "$TMP/truth.ini" --platform mock --size 160x90 --method none --seconds 3.5 \
    --script "$TMP/script.txt" --stats "$TMP/s.csv" >"$TMP/run.log" 2>&1 || { fail=1; tail -40 "$TMP/run.log"; }
grep -q "WARNING: ThreadSanitizer" "$TMP/run.log" && { fail=1; grep -A30 "WARNING: ThreadSanitizer" "$TMP/run.log" | head -80; }
grep -q "truth: shadow-planes restarted" "$TMP/run.log" || { fail=1; echo "tsan: the run did not reach the second scene"; }
# An animated scene paused and resumed twice (prev held): the truth starts at the frozen time and
# stops on the resume, while the render thread goes on drawing.
# (holds fire 0.8 s after the press: paused at 1.0 and 3.2 s, resumed at 2.1 and 4.3 s)
printf '0.2 prev hold 900\n1.3 prev hold 900\n2.4 prev hold 900\n3.5 prev hold 900\n' >"$TMP/pause.txt"
echo "tsan: the kiosk with an animated scene paused and resumed twice (2 workers), mock platform"
"$BUILD/gikiosk" run --config "$TMP/truth.ini" --platform mock --size 160x90 --method none --seconds 5 \
    --scene cornell-spot-anim --script "$TMP/pause.txt" --stats "$TMP/p.csv" >"$TMP/pause.log" 2>&1 || { fail=1; tail -40 "$TMP/pause.log"; }
grep -q "WARNING: ThreadSanitizer" "$TMP/pause.log" && { fail=1; grep -A30 "WARNING: ThreadSanitizer" "$TMP/pause.log" | head -80; }
[ "$(grep -c "moves again; its ground truth stopped" "$TMP/pause.log")" -eq 2 ] || { fail=1; echo "tsan: the run did not pause and resume twice"; }
if [ "$fail" -eq 0 ]; then echo "tsan: clean"; else echo "tsan: FAILED"; fi
exit "$fail"
