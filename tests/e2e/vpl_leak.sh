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
# The deep-umbra test (vpl_umbra; gather.frag, val_zmax.frag, val_depth.frag) decides with exact
# geometry where the whole VAL is hidden. `on` told a blocker from the receiver's own surface by a
# depth margin scaled by its slope (r·tanφ·2.83/res): RMSE 0.0632 -> 0.0215. Measured where the
# rest landed (no blur, light-leak's pixels ray-cast onto the dark room): 77% of it on receivers
# within 0.3 m behind the wall that the margin let through, 22% on receivers over a metre behind it
# whose penumbra kernel reached the paraboloid's rim, where rasterising triangles over the horizon
# leaves false depth jumps (gaps). `plane` (the default) keeps each texel's plane and hides a
# receiver behind the plane its texels hold (concave corners, like the lit floor at the wall's
# foot, allowed; convex ones not), takes the blocker's depth from that plane, and reads rim texels
# as no gap (also for `on`: 0.0215 -> 0.0196): 0.000591, cornell, cornell-spot and atrium within
# 2e-5 (README, vpl). Where that rest came from, traced per gather pixel (which VAL, which test let
# it through): 62% through vetoes by texels outside the paraboloid's disc, on receivers within 2.2°
# above a VAL's horizon, 38% from receivers in the band between a VAL's surface and its map's
# lifted plane (4.7 cm here), which the thesis takes as lit. `horizon` (the default) is `plane`
# where rim texels without a plane do not veto and a receiver in that band is looked up at the
# horizon of its direction: exactly 0 (every pixel of the HDR capture; vsm, multires and the
# RGBA16F targets too), the other scenes within 1.4e-4 (README, vpl).
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless
L_WALL_NITS=2.94

# leak BUDGET: leak ratio of light-leak with vpl into $leak, and the capture's RMSE against the
# black ruler into $rmse (the mean's statistics print 6 digits: "black" is judged by the RMSE)
leak() {
    leak= rmse=
    rm -rf "$TMP/cap"
    "$GIKIOSK" run --platform mock --scene light-leak --method vpl --size 160x120 --frames 2 --hdr \
        --capture "$TMP/cap" --budget "$1" >"$TMP/run.log" 2>&1 || return 1
    leak=$(oiiotool "$TMP/cap/000001-light-leak-vpl.exr" --printstats 2>/dev/null |
        awk -v l=$L_WALL_NITS '/Stats Avg/ { print (0.2126 * $3 + 0.7152 * $4 + 0.0722 * $5) / l }')
    rmse=$("$GIKIOSK" compare tests/references/light-leak.exr "$TMP/cap/000001-light-leak-vpl.exr" --json 2>/dev/null |
        sed -n 's/.*"rmse": \([^,}]*\).*/\1/p')
    [ -n "$leak" ] && [ -n "$rmse" ]
}
lt() { awk -v a="$1" -v b="$2" 'BEGIN { n = "^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$"; exit !(a ~ n && b ~ n && a + 0 < b + 0) }'; }

check "light-leak vpl (default budgets) renders" leak "shadow=pcss"
leak_default=$leak
rmse_default=$rmse
check "light-leak vpl vpl_umbra=plane renders" leak "shadow=pcss,vpl_umbra=plane"
leak_plane=$leak
check "light-leak vpl vpl_umbra=on renders" leak "shadow=pcss,vpl_umbra=on"
leak_margin=$leak
check "light-leak vpl vpl_umbra=off renders" leak "shadow=pcss,vpl_umbra=off"
leak_filtered=$leak
check "light-leak vpl vpl_vis=exact renders" leak "shadow=pcss,vpl_vis=exact"
leak_exact=$leak
check "light-leak vpl vpl_vis=vsm renders" leak "shadow=pcss,vpl_vis=vsm"
leak_vsm=$leak rmse_vsm=$rmse
check "light-leak vpl vpl_vis=vsm,vpl_umbra=plane renders" leak "shadow=pcss,vpl_vis=vsm,vpl_umbra=plane"
leak_vsm_plane=$leak
check "light-leak vpl vpl_vis=vsm,vpl_umbra=on renders" leak "shadow=pcss,vpl_vis=vsm,vpl_umbra=on"
leak_vsm_margin=$leak
check "light-leak vpl vpl_vis=vsm,vpl_umbra=off renders" leak "shadow=pcss,vpl_vis=vsm,vpl_umbra=off"
leak_vsm_filtered=$leak
echo "# light-leak vpl: leak ratio default (cssm, deep umbra by planes and the horizon) $leak_default, by planes only $leak_plane, by a depth margin $leak_margin, without the deep-umbra test $leak_filtered, exact visibility $leak_exact, vsm $leak_vsm (planes only $leak_vsm_plane, margin $leak_vsm_margin, without $leak_vsm_filtered)"
# Measured (llvmpipe, 160x120, vpl_n 256, vpl_m 8): cssm 0 (vpl_umbra=plane 0.0058%, on 0.245%, off
# 1.09%; vpl_m 2: 1.58%, the VALs' negative half-spaces and kernels over whole walls), exact
# 0.087%, vsm 0 (plane 0.0081%, on 0.416%, off 4.17%). The default must stay exactly black, as the
# path-traced ruler and `none` are; the other bounds 1.5x the measurements; the planes must keep
# cutting the margin's leak tenfold (measured 42x), the margin the filtered leak to under half (4.5x).
zero() { awk -v a="$1" 'BEGIN { exit !(a ~ /^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$/ && a + 0 == 0) }'; }
check "vpl default leaks nothing: the dark room is black (leak $leak_default, RMSE $rmse_default)" zero "$rmse_default"
check "vpl with the planes only leaks under 0.009% of the lit wall ($leak_plane)" lt "$leak_plane" 0.00009
check "the horizon's part of the test is what blackens it (planes only: $leak_plane > 0)" lt 0 "$leak_plane"
check "vpl with the depth margin leaks under 0.37% ($leak_margin)" lt "$leak_margin" 0.0037
check "vpl without the deep-umbra test leaks under 1.6% ($leak_filtered)" lt "$leak_filtered" 0.016
check "the planes cut the margin's leak tenfold at least ($leak_plane < $leak_margin / 10)" \
    lt "$leak_plane" "$(awk -v a="$leak_margin" 'BEGIN { print a / 10 }')"
check "the depth margin halves the leak at least ($leak_margin < $leak_filtered / 2)" \
    lt "$leak_margin" "$(awk -v a="$leak_filtered" 'BEGIN { print a / 2 }')"
check "vpl with exact visibility leaks under 0.13% ($leak_exact)" lt "$leak_exact" 0.0013
check "vpl vsm visibility leaks nothing (leak $leak_vsm, RMSE $rmse_vsm)" zero "$rmse_vsm"
check "vpl vsm with the planes only leaks under 0.012% ($leak_vsm_plane)" lt "$leak_vsm_plane" 0.00012
check "vpl vsm with the depth margin leaks under 0.62% ($leak_vsm_margin)" lt "$leak_vsm_margin" 0.0062
check "vpl vsm without the deep-umbra test leaks under 6.3% ($leak_vsm_filtered)" lt "$leak_vsm_filtered" 0.063
# The deep-umbra test costs no accuracy where nothing leaks: rel. RMSE with each test and without
# (cornell against its one-bounce reference, atrium against the full one; measured horizon / plane /
# on / off 0.0776027 / 0.0776266 / 0.0776258 / 0.0776258 and 0.4085318 / 0.4085297 / 0.4085140 /
# 0.4085146). Bound 0.001, a tenth of the cornell reference's own noise floor (0.013).
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
    check "$scene vpl renders without the deep-umbra test" rel_err "$scene" "$ruler" vpl_umbra=off
    off=$rel
    for mode in on plane horizon; do
        check "$scene vpl renders with vpl_umbra=$mode" rel_err "$scene" "$ruler" vpl_umbra=$mode
        check "$scene vpl: vpl_umbra=$mode costs no accuracy ($rel against $off, within 0.001)" close "$rel" "$off"
    done
done
finish
