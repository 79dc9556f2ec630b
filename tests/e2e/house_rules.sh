#!/bin/sh
# The rules of the house (DESIGN §1) that the include graph and the sources can show, checked on
# every #include of base/, app/ and platform/. Each include is resolved the way the compiler finds
# it: "x.h" first next to the including file, then under -Iapp, then under -I. (the Makefile's
# order); <x.h> only under -Iapp and -I. (system headers resolve to nothing and are skipped). So
# "../render/x.h", "render/x.h" and "app/render/x.h" are the same file to every rule. A failing
# rule names each offending file:line and what it includes.
#
# Rules:
#   1. GI methods include gl/ and gi.h, never render/: nothing under app/gi/ includes app/render/.
#   2. The renderer sees a method only through its interface: app/render/ includes from app/gi/
#      only gi.h and gi_catalogue.h, nothing of a method's own folder.
#   3. GI methods never call each other: nothing under app/gi/A/ includes app/gi/B/.
#   4. platform/ knows nothing of scenes or GI: nothing under platform/ (or base/) includes app/.
#   5. app/ sees the platform only through platform.h.
#   6. The commands are the top: nothing under app/ other than app/cli/ includes app/cli/.
#   7. One clock, no pass times itself: no glFinish( anywhere in app/ (the frame timer waits on a
#      fence), clock_gettime( only in the frame timer (app/gl/gl_timing.c) and the reference tracer
#      (app/ref/, which times CPU renders); the bench reads the frame report like the kiosk.
. tests/e2e/lib.sh

# file:line<TAB>resolved<TAB>as written, for every include of the tree that resolves to a file of it.
find base app platform -type f \( -name '*.c' -o -name '*.h' -o -name '*.cpp' \) | LC_ALL=C sort |
    xargs awk '
        function exists(p,    l, r) { r = (getline l < p); close(p); return r >= 0 }
        function norm(p,    n, i, a, out, k, o) {  # a/b/../c/./d -> a/c/d
            n = split(p, a, "/"); k = 0
            for (i = 1; i <= n; i++) {
                if (a[i] == "" || a[i] == ".") continue
                if (a[i] == ".." && k > 0 && o[k] != "..") { k--; continue }
                o[++k] = a[i]
            }
            out = ""
            for (i = 1; i <= k; i++) out = out (i > 1 ? "/" : "") o[i]
            return out
        }
        FNR == 1 { dir = FILENAME; sub(/\/[^\/]*$/, "", dir) }
        /^[ \t]*#[ \t]*include[ \t]*[<"]/ {
            inc = $0; sub(/^[ \t]*#[ \t]*include[ \t]*/, "", inc)
            quoted = substr(inc, 1, 1) == "\""
            inc = substr(inc, 2); sub(/[">].*$/, "", inc)
            r = ""
            if (quoted && exists(dir "/" inc)) r = norm(dir "/" inc)
            else if (exists("app/" inc)) r = norm("app/" inc)
            else if (exists(inc)) r = norm(inc)
            if (r != "") printf "%s:%d\t%s\t%s\n", FILENAME, FNR, r, inc
        }' >"$TMP/includes"
n=$(wc -l <"$TMP/includes")
check "the include table lists the tree's includes ($n)" test "$n" -gt 100

# rule DESCRIPTION AWK-CONDITION: fails, listing the matches, when a row ($1 where, $2 resolved,
# $3 as written; src = the including file) matches the condition.
rule() {
    awk -F '\t' "{ src = \$1; sub(/:[0-9]+\$/, \"\", src) } $2 { print \$1 \": includes \" \$3 \" (\" \$2 \")\" }" \
        "$TMP/includes" >"$TMP/bad"
    if [ -s "$TMP/bad" ]; then not_ok "$1"; sed 's/^/#   /' "$TMP/bad"; else ok "$1"; fi
}

rule "app/gi/ includes nothing from app/render/" 'src ~ /^app\/gi\// && $2 ~ /^app\/render\//'
rule "app/render/ reaches app/gi/ only through gi.h and gi_catalogue.h" \
    'src ~ /^app\/render\// && $2 ~ /^app\/gi\// && $2 != "app/gi/gi.h" && $2 != "app/gi/gi_catalogue.h"'
rule "a GI method includes no other method's folder" \
    'src ~ /^app\/gi\/[^\/]+\// && $2 ~ /^app\/gi\/[^\/]+\// && substr(src, 1, index(substr(src, 8), "/") + 7) != substr($2, 1, index(substr($2, 8), "/") + 7)'
rule "platform/ and base/ include nothing from app/" '(src ~ /^platform\// || src ~ /^base\//) && $2 ~ /^app\//'
rule "app/ includes from platform/ only platform.h" 'src ~ /^app\// && $2 ~ /^platform\// && $2 != "platform/platform.h"'
rule "only app/cli/ includes app/cli/" 'src ~ /^app\// && src !~ /^app\/cli\// && $2 ~ /^app\/cli\//'

# Rule 7, on the sources themselves: a call ("glFinish" / "clock_gettime" then "(" outside
# comments), not a mention. The frame's one clock (app/gl/gl_timing.c) waits on a fence and reads
# the time; nothing else of the real-time path may do either (the reference tracer, app/ref/, times
# its own CPU renders).
calls() { # FUNCTION, then the files to search
    _f=$1; shift
    awk -v f="$_f" '{ code = $0; sub(/\/\/.*/, "", code); sub(/\/\*.*/, "", code) }
               code ~ /^[ \t]*\*/ { next }   # the body of a block comment
               code ~ (f "[ \t]*\\(") { print FILENAME ":" FNR ": " $0 }' "$@"
}
find app -type f \( -name '*.c' -o -name '*.h' -o -name '*.cpp' \) | LC_ALL=C sort >"$TMP/app_files"
calls glFinish $(cat "$TMP/app_files") >"$TMP/finish"
calls clock_gettime $(grep -Ev '^app/gl/gl_timing\.c$|^app/ref/' "$TMP/app_files") >>"$TMP/finish"
if [ -s "$TMP/finish" ]; then
    not_ok "one clock: no glFinish in app/, clock_gettime only in app/gl/gl_timing.c (and app/ref/)"
    sed 's/^/#   /' "$TMP/finish"
else
    ok "one clock: no glFinish in app/, clock_gettime only in app/gl/gl_timing.c (and app/ref/)"
fi
finish
