#!/bin/sh
# Glass in the real-time image (render_glass.c): a scene with a transmissive material gets the
# top-level `glass` pass in its stats, a scene without none; the pass changes only the pixels the
# glass covers (the glass scene with the sphere's ior 1.5 and with ior 1, index-matched, agree
# exactly in two bands left and right of the sphere) and inside them the refraction bends what is
# seen (the two differ: measured rel_rmse 0.235 at 160x120).
. tests/e2e/lib.sh
mkdir -p "$TMP/s"
cp config/scenes/glass.gltf config/scenes/glass.bin "$TMP/s/"
sed 's/"ior":1.5/"ior":1/' config/scenes/glass.gltf >"$TMP/s/glass-matched.gltf"
check "the index-matched copy has ior 1" grep -q '"ior":1}' "$TMP/s/glass-matched.gltf"
for v in glass glass-matched; do
    expect_exit 0 "run $v (method none)" "$GIKIOSK" run --platform mock --size 160x120 --scenes-dir "$TMP/s" \
        --scene "$v" --method none --frames 1 --capture "$TMP/$v" --hdr --stats "$TMP/$v.csv"
done
check "the glass scene's stats have the glass pass" sh -c "head -n 1 '$TMP/glass.csv' | grep -q ',glass_ms,'"
expect_exit 0 "run cornell" "$GIKIOSK" run --platform mock --size 160x120 --scene cornell --method none --frames 1 \
    --stats "$TMP/cornell.csv"
check "cornell (no glass) has no glass pass" sh -c "! head -n 1 '$TMP/cornell.csv' | grep -q 'glass_ms'"
a=$TMP/glass/000000-glass-none.exr b=$TMP/glass-matched/000000-glass-matched-none.exr
"$GIKIOSK" compare "$b" "$a" --json >"$TMP/cmp.json"
err=$(sed 's/.*"rel_rmse": *\([0-9.e+-]*\).*/\1/' "$TMP/cmp.json")
check "ior 1.5 bends the view through the sphere (rel_rmse vs ior 1: $err > 0.05)" \
    awk -v e="$err" 'BEGIN { exit !(e > 0.05) }'
# The sphere covers x 55..105 of 160 in this camera; the bands x 0..39 and 120..159 hold no glass.
for band in 40x120+0+0 40x120+120+0; do
    max=$(oiiotool "$a" "$b" --absdiff --cut "$band" --printstats 2>/dev/null |
        sed -n 's/.*Stats Max: *\([^ ]*\) *\([^ ]*\) *\([^ ]*\).*/\1 \2 \3/p')
    check "pixels without glass are untouched by it (band $band: max difference $max)" test "$max" = "0.000000 0.000000 0.000000"
done
finish
