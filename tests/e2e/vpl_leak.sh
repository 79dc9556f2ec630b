#!/bin/sh
# vpl on the light-leak scene (failure table of 001 ch. 6 / issue 11): two rooms, a 2 cm wall
# between them, the lamp in the left room, the camera in the right one; the path-traced reference
# is black, so every nit in the capture leaked through the wall. Leak ratio as in vct_leak.sh:
# mean luminance of the capture / 2.94 nits (the lit side of the wall nearest the lamp, rho/pi E).
# The VPLs themselves sit on the lit side; what leaks is their visibility: each virtual area light
# is shadowed by its paraboloid CSSM map (vpl_vis=cssm, the default; vsm likewise), a filtered
# approximation that lets light through a 2 cm wall. With per-VPL exact visibility
# (vpl_vis=exact, the reference mode) the leak all but vanishes, which locates the cause there.
# Which part of the visibility (issue 11; absolute RMSE against the black ruler, 160x120, frame 2,
# 0.0632 without the deep-umbra test; each change alone, shader edits not kept): most of it is
# CSSM's receiver offset (CSM_OFFSET in gather.frag, 0.07 of the map's far distance = 0.73 m here,
# so a dark-room receiver within ~0.7 m of the wall tests as in front of it, and the series' ramp
# reaches "dark" only 0.064 further): without it 0.0105, but cornell's one-bounce error rises
# 0.078 -> 0.117 (every receiver shadows itself). Not the cause: r_near (geometry near the VAL's
# centre left out of its map; 0 -> 0.0630) and the VAL's negative half-space (taken as shadowed
# -> 0.0632). exact: 0.0074 (its hard test's bias, 0.01 of the far distance = 10 cm, is five times
# the wall). A correct image needs exactly 0.
# The deep-umbra test (vpl_umbra=on, the default; gather.frag, val_zmax.frag) decides with exact
# depths where the whole VAL is hidden: RMSE 0.0632 -> 0.0215 (vsm 0.153 -> 0.083), cornell,
# cornell-spot and atrium unchanged to 1e-6 (README, vpl). What stays is where a receiver lies
# behind the wall by less than its margin against its own surface in the map (r·tanφ·2.83/res,
# ~0.1-0.3 m on the dark room's floor and ceiling, estimated): 0.0130 at vpl_val_map=256, where the
# margin is a quarter.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless
L_WALL_NITS=2.94

# leak BUDGET: leak ratio of light-leak with vpl into $leak
leak() {
    leak=
    rm -rf "$TMP/cap"
    "$GIKIOSK" run --platform mock --scene light-leak --method vpl --size 160x120 --frames 2 --hdr \
        --capture "$TMP/cap" --budget "$1" >"$TMP/run.log" 2>&1 || return 1
    leak=$(oiiotool "$TMP/cap/000001-light-leak-vpl.exr" --printstats 2>/dev/null |
        awk -v l=$L_WALL_NITS '/Stats Avg/ { print (0.2126 * $3 + 0.7152 * $4 + 0.0722 * $5) / l }')
    [ -n "$leak" ]
}
lt() { awk -v a="$1" -v b="$2" 'BEGIN { n = "^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$"; exit !(a ~ n && b ~ n && a + 0 < b + 0) }'; }

check "light-leak vpl (default budgets) renders" leak "shadow=pcss"
leak_default=$leak
check "light-leak vpl vpl_umbra=off renders" leak "shadow=pcss,vpl_umbra=off"
leak_filtered=$leak
check "light-leak vpl vpl_vis=exact renders" leak "shadow=pcss,vpl_vis=exact"
leak_exact=$leak
check "light-leak vpl vpl_vis=vsm renders" leak "shadow=pcss,vpl_vis=vsm"
leak_vsm=$leak
check "light-leak vpl vpl_vis=vsm,vpl_umbra=off renders" leak "shadow=pcss,vpl_vis=vsm,vpl_umbra=off"
leak_vsm_filtered=$leak
echo "# light-leak vpl: leak ratio default (cssm, deep umbra) $leak_default, without the deep-umbra test $leak_filtered, exact visibility $leak_exact, vsm $leak_vsm (without $leak_vsm_filtered)"
# Measured (llvmpipe, 160x120, vpl_n 256, vpl_m 8): cssm 0.335% (1.09% without the deep-umbra test;
# vpl_m 2: 1.75%, 2.33% without), exact 0.087%, vsm 2.08% (4.17% without). Bounds 1.5x the
# measurements; the test must keep cutting the filtered leak to under half.
check "vpl default leaks under 0.5% of the lit wall ($leak_default)" lt "$leak_default" 0.005
check "vpl without the deep-umbra test leaks under 1.6% ($leak_filtered)" lt "$leak_filtered" 0.016
check "the deep-umbra test halves the leak at least ($leak_default < $leak_filtered / 2)" \
    lt "$leak_default" "$(awk -v a="$leak_filtered" 'BEGIN { print a / 2 }')"
check "vpl with exact visibility leaks under 0.13% ($leak_exact)" lt "$leak_exact" 0.0013
check "vpl vsm visibility leaks under 3.1% ($leak_vsm)" lt "$leak_vsm" 0.031
check "vpl vsm without the deep-umbra test leaks under 6.3% ($leak_vsm_filtered)" lt "$leak_vsm_filtered" 0.063
# The deep-umbra test costs no accuracy where nothing leaks: rel. RMSE with and without it
# (cornell against its one-bounce reference, atrium against the full one; measured 0.0776258 /
# 0.0776257 and 0.4085140 / 0.4085146). Bound 0.001, a tenth of the cornell reference's own noise
# floor (0.013).
rel_err() {
    rel=
    rm -rf "$TMP/cap"
    "$GIKIOSK" run --platform mock --scene "$1" --method vpl --size 160x120 --frames 2 --hdr \
        --capture "$TMP/cap" --budget "$3" >"$TMP/run.log" 2>&1 || return 1
    rel=$("$GIKIOSK" compare "tests/references/$2.exr" "$TMP/cap/000001-$1-vpl.exr" --json 2>/dev/null |
        sed -n 's/.*"rel_rmse": \([^,}]*\).*/\1/p')
    [ -n "$rel" ]
}
close() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; exit !(d < 0.001 && d > -0.001) }'; }
for pair in cornell:cornell-1bounce atrium:atrium; do
    scene=${pair%%:*} ruler=${pair#*:}
    check "$scene vpl renders with the deep-umbra test" rel_err "$scene" "$ruler" vpl_umbra=on
    on=$rel
    check "$scene vpl renders without it" rel_err "$scene" "$ruler" vpl_umbra=off
    off=$rel
    check "$scene vpl: the deep-umbra test costs no accuracy ($on against $off, within 0.001)" close "$on" "$off"
done
finish
