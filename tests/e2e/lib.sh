# Helpers for end-to-end tests: TAP output, one line per check.
# Usage: . tests/e2e/lib.sh; then check "description" command...; finish
GIKIOSK=${GIKIOSK:-build/gikiosk}
BUILD=${BUILD:-build}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/gikiosk-e2e.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
_n=0
_failed=0
ok() { _n=$((_n + 1)); echo "ok $_n - $1"; }
not_ok() { _n=$((_n + 1)); _failed=$((_failed + 1)); echo "not ok $_n - $1"; }
# sh has no local variables: the helpers' own start with _ so they never clobber a test's.
# check DESCRIPTION COMMAND... : passes when the command exits 0
check() { _d=$1; shift; if "$@"; then ok "$_d"; else not_ok "$_d"; fi; }
# expect_exit CODE DESCRIPTION COMMAND... : passes when the command exits with CODE; its stderr is in $TMP/stderr
expect_exit() {
    _code=$1; _d=$2; shift 2
    "$@" >"$TMP/stdout" 2>"$TMP/stderr"
    _rc=$?
    if [ "$_rc" -eq "$_code" ]; then ok "$_d"; else not_ok "$_d (exit $_rc, wanted $_code)"; sed 's/^/#   /' "$TMP/stderr" | head -5; fi
}
# stderr_has REGEX DESCRIPTION : the last expect_exit's stderr matches
stderr_has() { if grep -Eq "$1" "$TMP/stderr"; then ok "$2"; else not_ok "$2"; sed 's/^/#   /' "$TMP/stderr" | head -5; fi; }
finish() { echo "1..$_n"; [ "$_failed" -eq 0 ]; }
