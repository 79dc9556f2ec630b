#!/bin/sh
# Runs every test and prints one closing line: "N passed, N failed". Cases reported as skipped
# (TAP "ok ... # SKIP why": a tool or the network missing) are counted in neither: a line before
# the closing one says how many were skipped and why.
# Each test program speaks TAP ("ok ..." / "not ok ..."): the cmocka binaries through
# CMOCKA_MESSAGE_OUTPUT=TAP, the e2e shell tests through tests/e2e/lib.sh. A program that dies
# without reporting counts as one failure, so a crash can never pass silently.
set -u
BUILD=${1:-build}
export CMOCKA_MESSAGE_OUTPUT=TAP
export GIKIOSK=$BUILD/gikiosk
export BUILD
export EGL_PLATFORM=surfaceless
# Mesa's shader cache goes into the build tree, not the user's ~/.cache (tests/e2e/env.sh checks).
case $BUILD in /*) build_abs=$BUILD ;; *) build_abs=$PWD/$BUILD ;; esac
export MESA_SHADER_CACHE_DIR="$build_abs/mesa-shader-cache"
passed=0
failed=0
skipped=0
log=$BUILD/test-logs
mkdir -p "$log"

run_one() { # name, command...
    name=$1; shift
    out=$log/$(echo "$name" | tr '/' '_').log
    "$@" >"$out" 2>&1
    rc=$?
    s=$(grep -c '^ok .*# *SKIP' "$out")
    p=$(($(grep -c '^ok ' "$out") - s))
    f=$(grep -c '^not ok ' "$out")
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        f=1   # died (or exited non-zero) without saying which case failed
        echo "not ok - $name exited $rc without a failed case" >>"$out"
    fi
    if grep -q 'runtime error:' "$out"; then
        f=$((f + 1))   # UBSan reports and goes on: under `make asan` a report is a failure
        echo "not ok - $name: UndefinedBehaviorSanitizer reported a runtime error" >>"$out"
    fi
    if [ "$p" -eq 0 ] && [ "$f" -eq 0 ] && [ "$s" -eq 0 ]; then
        f=1
        echo "not ok - $name reported no test" >>"$out"
    fi
    passed=$((passed + p))
    failed=$((failed + f))
    skipped=$((skipped + s))
    [ "$s" -gt 0 ] && grep '^ok .*# *SKIP' "$out" | sed "s|^|    skipped in $name: |" >>"$log/skipped.txt"
    if [ "$f" -gt 0 ]; then
        echo "FAIL $name ($p passed, $f failed) — log: $out"
        grep -E '^not ok|\[  ERROR   \]|error|Error' "$out" | head -20 | sed 's/^/    /'
    else
        echo "ok   $name ($p$([ "$s" -gt 0 ] && echo ", $s skipped"))"
    fi
}

# Under `make asan`, GK_MESA_ASAN_OPTIONS applies to the programs that run Mesa (gpu tests and the
# binary in e2e tests); unit tests keep the full checks, leaks included (see the Makefile).
rm -f "$log/skipped.txt"
mesa_env() { if [ -n "${GK_MESA_ASAN_OPTIONS:-}" ]; then env ASAN_OPTIONS="$GK_MESA_ASAN_OPTIONS" "$@"; else "$@"; fi; }
for t in $(find "$BUILD/tests/unit" -type f -perm -u+x 2>/dev/null | LC_ALL=C sort); do
    run_one "${t#"$BUILD"/tests/}" "$t"
done
for t in $(find "$BUILD/tests/gpu" -type f -perm -u+x 2>/dev/null | LC_ALL=C sort); do
    run_one "${t#"$BUILD"/tests/}" mesa_env "$t"
done
for t in $(find tests/e2e -name '*.sh' ! -name 'lib.sh' 2>/dev/null | LC_ALL=C sort); do
    run_one "$t" mesa_env sh "$t"
done
# Each fuzz target briefly and reproducibly: a fixed number of executions from seed 1, about 5 s of
# each on this project's 2-core machine (measured: image ~320 execs/s, gltf ~760, gltf_files ~980,
# config ~6,700, script ~8,200), capped at FUZZ_TEST_SECONDS (120). `make fuzz` hunts, randomly.
fuzz_runs() {
    case $1 in image) echo 1500 ;; gltf) echo 3500 ;; gltf_files) echo 4500 ;; config) echo 30000 ;; *) echo 40000 ;; esac
}
for t in $(find "$BUILD/fuzz" -name 'fuzz_*' -type f -perm -u+x 2>/dev/null | LC_ALL=C sort); do
    name=${t##*/fuzz_}
    run_one "fuzz/$name" sh tests/fuzz/run_fuzz.sh "$t" "${FUZZ_TEST_SECONDS:-120}" "$(fuzz_runs "$name")"
done
if [ "$skipped" -gt 0 ]; then
    echo "$skipped skipped (counted in neither):"
    cat "$log/skipped.txt"
fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
