#!/bin/sh
# `gikiosk scenes`: the table lists every committed scene; `scenes --check FILE` prints one scene's
# summary, and a broken or missing file exits 2 with a message naming the file.
. tests/e2e/lib.sh

"$GIKIOSK" scenes --dir config/scenes >"$TMP/list" 2>"$TMP/list.err"
check "scenes lists the committed scenes (exit 0)" test $? -eq 0
for s in cornell cornell-spot cornell-spot-anim shadow-planes light-leak caustic-ring atrium furnace glass env-studio; do
    check "scenes lists $s" grep -q "^$s " "$TMP/list"
done
n=$(grep -c '^[a-z]' "$TMP/list")
check "scenes lists 7 or more scenes ($n)" test "$n" -ge 7
check "caustic-ring offers ispm" sh -c "grep '^caustic-ring ' '$TMP/list' | grep -q ispm"
check "glass has glass and caustics" sh -c "grep '^glass ' '$TMP/list' | grep -q 'glass,caustics'"
check "shadow-planes offers only none" sh -c "grep '^shadow-planes ' '$TMP/list' | grep -q ' none  *-  *Dong'"

expect_exit 0 "scenes --check on cornell" "$GIKIOSK" scenes --check config/scenes/cornell.gltf
check "the summary gives 32 triangles" grep -q "^triangles: *32 drawn" "$TMP/stdout"
# radiosity's refined vertex counts: tests/unit/test_radiosity_mesh.c counts them another way
# (Euler's formula over the refined triangles): cornell 1502 / 2983 / 5135 at radiosity_tess 16/24/32
check "the summary gives radiosity's refined vertices" \
    grep -q "^radiosity: *refined at load to 1502 / 2983 / 5135 vertices at radiosity_tess 16 / 24 / 32" "$TMP/stdout"
check "the table gives cornell's at the default radiosity_tess 24 (2983)" \
    sh -c "awk '\$1 == \"cornell\" { print \$6 }' '$TMP/list' | grep -qx 2983"
check "the table gives - where radiosity does not run (shadow-planes)" \
    sh -c "awk '\$1 == \"shadow-planes\" { print \$6 }' '$TMP/list' | grep -qx -- -"

# A broken scene: an accessor that reads past its buffer view.
cp config/scenes/furnace.bin "$TMP/broken.bin"
sed 's/"furnace.bin"/"broken.bin"/; s/"count":[0-9]*,"type":"VEC3","min"/"count":99999,"type":"VEC3","min"/' \
    config/scenes/furnace.gltf >"$TMP/broken.gltf"
expect_exit 2 "a broken scene exits 2" "$GIKIOSK" scenes --check "$TMP/broken.gltf"
stderr_has "broken.gltf: accessor [0-9]+ .*reads past" "the message names the file and the accessor"

printf 'not json at all' >"$TMP/garbage.gltf"
expect_exit 2 "a file that is not glTF exits 2" "$GIKIOSK" scenes --check "$TMP/garbage.gltf"
stderr_has "garbage.gltf: " "the message names the file"

expect_exit 2 "a missing file exits 2" "$GIKIOSK" scenes --check "$TMP/none.gltf"
stderr_has "none.gltf: .*no such file" "the message says the file is missing"

mkdir -p "$TMP/dir" && cp config/scenes/cornell.gltf config/scenes/cornell.bin "$TMP/broken.gltf" "$TMP/broken.bin" "$TMP/dir/"
expect_exit 2 "a folder with a broken scene lists the rest and exits 2" "$GIKIOSK" scenes --dir "$TMP/dir"
check "the good scene is still listed" grep -q "^cornell " "$TMP/stdout"

expect_exit 2 "an unknown option exits 2" "$GIKIOSK" scenes --frobnicate

# build-scenes writes the same bytes as the committed files (deterministic builders).
mkdir -p "$TMP/built"
expect_exit 0 "build-scenes writes every scene" "$GIKIOSK" build-scenes "$TMP/built"
check "rebuilt scenes are byte-identical to config/scenes" sh -c "
    for f in '$TMP'/built/*; do cmp -s \"\$f\" config/scenes/\$(basename \"\$f\") || exit 1; done"
finish
