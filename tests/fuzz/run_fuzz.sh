#!/bin/sh
# Runs the glTF loader fuzz target for a short time on a copy of the seed corpus and prints one TAP
# line: "ok 1 - fuzz gltf loader 20 s, N execs" or "not ok" (with the crashing input kept under
# $BUILD/fuzz-artifacts/). Usage: tests/fuzz/run_fuzz.sh FUZZ_BIN [SECONDS]
set -u
BIN=$1
SECS=${2:-20}
ART=${BUILD:-build}/fuzz-artifacts
WORK=$(mktemp -d "${TMPDIR:-/tmp}/gikiosk-fuzz.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
mkdir -p "$ART" "$WORK/corpus"
cp tests/fuzz/corpus/* "$WORK/corpus/"
# -rss_limit_mb: the loader caps what it allocates; 2 GB catches a runaway allocation.
# -timeout: one input taking 10 s is a hang.
"$BIN" -max_total_time="$SECS" -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$ART/" "$WORK/corpus" >"$WORK/log" 2>&1
rc=$?
execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$WORK/log" | tail -1)
echo "1..1"
if [ "$rc" -eq 0 ] && [ -n "$execs" ]; then
    echo "ok 1 - fuzz gltf loader $SECS s, $execs execs"
else
    echo "not ok 1 - fuzz gltf loader (exit $rc; inputs in $ART)"
    grep -E 'ERROR|SUMMARY|crash-|leak-|timeout-|#0 |#1 |#2 ' "$WORK/log" | head -20 | sed 's/^/# /'
    exit 1
fi
