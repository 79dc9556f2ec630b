#!/bin/sh
# Runs one fuzz target for a set time on a copy of its seed corpus (tests/fuzz/corpus/TARGET/,
# TARGET = the binary's name without "fuzz_") and prints one TAP line:
# "ok 1 - fuzz TARGET S s, N execs" or "not ok" (the crashing input kept under
# $BUILD/fuzz-artifacts/TARGET-*). Usage: tests/fuzz/run_fuzz.sh FUZZ_BIN [SECONDS [RUNS]]
# With RUNS (as `make test` runs them) the run is a fixed one: RUNS executions from seed 1, so a test
# run passes or fails by the code, not by how far a random walk got in the time (CI once failed on an
# input a 5-s run happened to reach). Nearly the same inputs each time, not exactly: two 3,500-run
# gltf runs here ended at coverage 5500 and 5504, as coverage feedback sees the libraries' own
# variation. SECONDS is then a cap, and hitting it before RUNS is a failure (an input got slow). Without RUNS it is a
# hunt for SECONDS from a random seed (`make fuzz`), which is where new inputs are found.
set -u
BIN=$1
SECS=${2:-5}
RUNS=${3:-}
TARGET=$(basename "$BIN")
TARGET=${TARGET#fuzz_}
ART=${BUILD:-build}/fuzz-artifacts
WORK=$(mktemp -d "${TMPDIR:-/tmp}/gikiosk-fuzz.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
mkdir -p "$ART" "$WORK/corpus"
echo "1..1"
if ! cp tests/fuzz/corpus/"$TARGET"/* "$WORK/corpus/" 2>/dev/null; then
    echo "not ok 1 - fuzz $TARGET: no seed corpus in tests/fuzz/corpus/$TARGET/"
    exit 1
fi
# -rss_limit_mb / -malloc_limit_mb: the readers cap what they allocate; 2 GB catches a runaway
# allocation. -timeout: one input taking 10 s is a hang. The fuzzers' own files go under TMPDIR.
# fast_unwind_on_malloc=0: leak reports get whole stacks through the libraries (built without
# frame pointers), so tests/fuzz/lsan.supp can match the library function a known leak is in.
ASAN_OPTIONS=${ASAN_OPTIONS:-fast_unwind_on_malloc=0} LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan.supp \
TMPDIR=$WORK "$BIN" -max_total_time="$SECS" ${RUNS:+-runs="$RUNS" -seed=1} -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$ART/$TARGET-" "$WORK/corpus" >"$WORK/log" 2>&1
rc=$?
execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$WORK/log" | tail -1)
if [ "$rc" -eq 0 ] && [ -n "$RUNS" ] && [ "${execs:-0}" -lt "$RUNS" ]; then
    echo "not ok 1 - fuzz $TARGET: ${execs:-0} of $RUNS execs (seed 1) before the $SECS s cap"
    exit 1
elif [ "$rc" -eq 0 ] && [ -n "$RUNS" ]; then
    echo "ok 1 - fuzz $TARGET $execs execs from seed 1"
elif [ "$rc" -eq 0 ] && [ -n "$execs" ]; then
    echo "ok 1 - fuzz $TARGET $SECS s, $execs execs"
else
    echo "not ok 1 - fuzz $TARGET (exit $rc; inputs in $ART/$TARGET-*)"
    grep -E 'ERROR|SUMMARY|fuzz:|crash-|leak-|timeout-|oom-|#0 |#1 |#2 |#3 ' "$WORK/log" | head -24 | sed 's/^/# /'
    exit 1
fi
