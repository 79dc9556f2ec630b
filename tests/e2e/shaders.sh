#!/bin/sh
# Validates every shader under shaders_gles/ and the test-only ones under tests/shaders/ with
# glslangValidator as GLSL ES, after the same
# assembly the renderer does (app/render/shader_source.c): "#version 310 es" (and 320 es),
# "#define GK_GLES N", the variant's #defines, then the file with each #include "path" (relative
# to shaders_gles/; for a test shader, to tests/shaders/ and then shaders_gles/, as the GPU tests'
# shader root holds both) replaced by that file, each file at most once per program.
# Variants: every line "// @variant NAME[=VALUE] ..." in a shader file is one set of defines to
# validate; a file without such lines is validated once without extra defines. The stage comes
# from the extension (.vert .frag .comp .geom). A deliberately broken shader must be rejected, so
# the check can fail.
. tests/e2e/lib.sh
ROOT=shaders_gles
BASE=shaders_gles   # where an include not found under ROOT is looked up

# expand FILE SEENFILE: prints FILE with includes expanded (one awk process: a shell loop per
# line was too slow); SEENFILE receives the files in inclusion order, line K + 1 being the
# source-string number K of "#line N K" (as the C loader numbers them).
expand() {
    awk -v root="$ROOT" -v base="$BASE" -v top="$1" -v seenfile="$2" '
        function emit(path, from, at,    k, line, n, inc, file) {
            if (path in seen) return 1
            file = root "/" path
            if ((getline line < file) < 0) file = base "/" path
            else close(file)
            if ((getline line < file) < 0) { printf "%s:%d: missing include %s\n", from, at, path > "/dev/stderr"; return 0 }
            close(file)
            k = nfiles++; seen[path] = k; print path > seenfile
            print "#line 1 " k
            n = 0
            while ((getline line < file) > 0) {
                n++
                if (line ~ /^[ \t]*#include[ \t]*"/) {
                    inc = line; sub(/^[ \t]*#include[ \t]*"/, "", inc); sub(/".*$/, "", inc)
                    if (!emit(inc, path, n)) return 0
                    print "#line " (n + 1) " " k
                } else print line
            }
            close(file)
            return 1
        }
        BEGIN { nfiles = 0; printf "" > seenfile; if (!emit(top, top, 0)) exit 1 }'
}

# Rewrites glslang's "ERROR: K:LINE:" into "ERROR: ROOT/FILE:LINE:" using SEENFILE.
map_log() {
    awk -v seen="$1" -v root="$ROOT" 'BEGIN { k = 0; while ((getline f < seen) > 0) name[k++] = f }
        { if (match($0, /[0-9]+:[0-9]+:/)) { s = substr($0, RSTART, RLENGTH); split(s, a, ":");
              if (a[1] in name) $0 = substr($0, 1, RSTART - 1) root "/" name[a[1]] ":" a[2] ":" substr($0, RSTART + RLENGTH) }
          print }'
}

# assemble REL GLES "DEFINES" OUT
assemble() {
    : >"$TMP/seen"
    {
        if head -n 5 "$ROOT/$1" | grep -q '^#version'; then
            : # a file that carries its own #version (not assembled by the renderer's loader)
        else
            echo "#version ${2}0 es"
            echo "#define GK_GLES $2"
        fi
        for _def in $3; do
            echo "#define $(echo "$_def" | sed 's/=/ /')"
        done
        expand "$1" "$TMP/seen"
    } >"$4"
}

validate() { # REL GLES DEFINES
    _ext=${1##*.}
    out="$TMP/shader.$_ext"
    if ! assemble "$1" "$2" "$3" "$out"; then
        echo "#   $1: include expansion failed"
        return 1
    fi
    if ! glslangValidator -S "$_ext" "$out" >"$TMP/glslang.log" 2>&1; then
        grep -v '^/' "$TMP/glslang.log" | map_log "$TMP/seen" | sed 's/^/#   /' | head -8
        return 1
    fi
    return 0
}

if ! command -v glslangValidator >/dev/null 2>&1; then
    not_ok "glslangValidator is installed (package glslang-tools)"
    finish
    exit 1
fi

count=0
for f in $(find shaders_gles tests/shaders -type f \( -name '*.vert' -o -name '*.frag' -o -name '*.comp' -o -name '*.geom' \) | LC_ALL=C sort); do
    case $f in tests/shaders/*) ROOT=tests/shaders ;; *) ROOT=shaders_gles ;; esac
    rel=${f#"$ROOT"/}
    variants=$(sed -n 's#^[[:space:]]*//[[:space:]]*@variant[[:space:]]*##p' "$f" | tr ' ' ',')
    [ -n "$variants" ] || variants="-"
    ext=${rel##*.}
    for v in $variants; do
        defs=$(echo "$v" | sed 's/^-$//' | tr ',' ' ')
        for gles in 31 32; do
            [ "$ext" = geom ] && [ "$gles" = 31 ] && continue
            count=$((count + 1))
            check "$ROOT/$rel [${defs:-no defines}] GLES $gles validates" validate "$rel" "$gles" "$defs"
        done
    done
done
[ "$count" -gt 0 ] || not_ok "found shaders to validate"

# The check itself must be able to fail: a shader with an undeclared identifier is rejected.
mkdir -p "$TMP/bad"
printf 'precision highp float;\nout vec4 o;\nvoid main() { o = vec4(undeclared_thing); }\n' >"$TMP/bad/bad.frag"
if ROOT=$TMP/bad validate bad.frag 31 "" >/dev/null; then
    not_ok "a broken shader is rejected"
else
    ok "a broken shader is rejected"
fi
finish
