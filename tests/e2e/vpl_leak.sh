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
# default 0.0632; each change alone, shader edits not kept): most of it is CSSM's receiver offset
# (CSM_OFFSET in gather.frag, 0.07 of the map's far distance = 0.73 m here, so a dark-room receiver
# within ~0.7 m of the wall tests as in front of it): without it 0.0105, but cornell's one-bounce
# error rises 0.078 -> 0.117 (every receiver shadows itself). Not the cause: r_near (geometry near
# the VAL's centre left out of its map; 0 -> 0.0630) and the VAL's negative half-space (taken as
# shadowed -> 0.0632). A deep-umbra test on the raw depth map (visibility 0 where 5 texels around
# the receiver's are all >= 1 cm in front of it) leaves 0.0030 but costs cornell 0.078 -> 0.083 and
# atrium 0.409 -> 0.414 (rel. RMSE): not a win, so not kept. exact: 0.0074 (its hard test's bias,
# 0.01 of the far distance = 10 cm, is five times the wall). A correct image needs exactly 0.
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
check "light-leak vpl vpl_vis=exact renders" leak "shadow=pcss,vpl_vis=exact"
leak_exact=$leak
check "light-leak vpl vpl_vis=vsm renders" leak "shadow=pcss,vpl_vis=vsm"
leak_vsm=$leak
echo "# light-leak vpl: leak ratio default (cssm) $leak_default, exact visibility $leak_exact, vsm $leak_vsm"
# Measured (llvmpipe, 160x120, vpl_n 256, vpl_m 8): cssm 1.09% (vpl_n 512: 1.08%, vpl_m 32: 1.10%,
# vpl_m 2: 2.33%), exact 0.087%, vsm 4.17%. Bounds 1.5x the measurements.
check "vpl default leaks under 1.6% of the lit wall ($leak_default)" lt "$leak_default" 0.016
check "vpl with exact visibility leaks under 0.13% ($leak_exact)" lt "$leak_exact" 0.0013
check "vpl vsm visibility leaks under 6.3% ($leak_vsm)" lt "$leak_vsm" 0.063
finish
