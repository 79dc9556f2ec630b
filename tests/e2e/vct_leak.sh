#!/bin/sh
# vct on the light-leak scene (summary A.6.1 #1/#2 on the scene made for it): two rooms, a wall
# 2 cm thick between them (thinner than a voxel at every budget: 25 / 12.5 / 6.25 cm at 32^3 /
# 64^3 / 128^3 over the 8 m scene), a lamp in the left room, the camera in the right one. The
# path-traced reference is black (tests/references/light-leak.exr), so every nit in the capture is
# light that leaked through the wall. Leak ratio = mean luminance of the capture / luminance of the
# lit side of the wall at its point nearest the lamp: the lamp (50 cd, colour (1, 0.9, 0.8),
# luminance factor 0.914) is 1.99 m from it, rho = 0.8, so L = rho/pi * 50 / 1.99^2 * 0.914 =
# 2.94 nits: the brightest light there is to leak.
# Each vct_res with both variants: default (conservative voxelization, fixed-point averages,
# footprint clamp, cones clipped at the border) and thesis (the thesis as published), and the default
# with vct_level0=aniso (six directional views from level 0 on). The default's axis clamp at thin
# walls (vct_axis_clamp=thin since issue 11) renders the dark room black; the measurements of the
# other switches below were made without it and keep it off (leak pins vct_axis_clamp=off unless
# told otherwise), so that they still say what each switch does; the default's own are at the end.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless
L_WALL_NITS=2.94

# leak RES VARIANT [,KNOB=VALUE...]: leak ratio of light-leak with vct into $leak (vct_axis_clamp=off
# unless the knobs name it)
leak() {
    leak=
    rm -rf "$TMP/cap"
    clamp=,vct_axis_clamp=off
    case "$3" in *vct_axis_clamp=*) clamp= ;; esac
    "$GIKIOSK" run --platform mock --scene light-leak --method vct --size 160x120 --frames 2 --hdr \
        --capture "$TMP/cap" --budget "shadow=pcss,vct_res=$1,vct_variant=$2$clamp$3" >"$TMP/run.log" 2>&1 || return 1
    grep -q "vct_variant=$2" "$TMP/run.log" || return 1
    for kv in $(echo "${3#,}" | tr ',' ' '); do grep -q "$kv" "$TMP/run.log" || return 1; done
    leak=$(oiiotool "$TMP/cap/000001-light-leak-vct.exr" --printstats 2>/dev/null |
        awk -v l=$L_WALL_NITS '/Stats Avg/ { print (0.2126 * $3 + 0.7152 * $4 + 0.0722 * $5) / l }')
    [ -n "$leak" ]
}
# lt A B: A < B, both numbers (a missing or garbled measurement fails)
lt() { awk -v a="$1" -v b="$2" 'BEGIN { n = "^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$"; exit !(a ~ n && b ~ n && a + 0 < b + 0) }'; }

# Measured (llvmpipe) at 32 / 64 / 128: default 0.264% / 0.132% / 0.096%, vct_level0=aniso
# 0.121% / 0.087% / 0.081%, thesis 5.18% / 4.80% / 3.87%. Bounds: 1.5x the measurement.
# Until the injection's two faults were fixed (vct/inject.comp, tests/gpu/test_vct_inject.c) the
# default leaked 2.3% / 2.6% / 2.8% and the thesis 13.2% / 15.1% / 14.9%; what leaked was not the
# wall but the dark room's own voxels, injected lit: (1) the lamp's light map (render_gi.c: one
# 160-degree face pointing down) does not reach the dark room's ceiling and upper walls, and a voxel
# outside it counted as lit (now a ray through the voxels decides there); (2) the shadow bias was
# 0.0015 of window depth, which in that perspective map (near plane 1 cm) is 0.7 m of depth at the
# wall's foot (1 m along the light's ray), so the dark floor behind the wall was lit (now a quarter
# voxel of distance).
# What is left is the wall's own voxels, which hold the lit room's surfaces next to the dark room's:
# with them injected dark the default leaks 0.021% / 0.026% / 0.032% (a diagnosis run, not a
# mode). The wall (x in +-1 cm) lies on a voxel boundary at every resolution (the grid is centred on
# the scene), so its lit face and the lit room's floor, ceiling and side walls next to it are in
# the column of voxels just behind the dark face, and a trilinear sample in the dark room between
# the two columns' centres sees part of the lit column at full opacity. An anisotropic level 0 hides
# the lit face from the dark side (its views weight radiance by the mean normal: mip_aniso.comp) but
# not the lit floor and ceiling next to it, which face the dark room's cones as a lit floor faces
# any viewer above it; so it cuts the leak by 54% / 34% / 16%, and the rest falls with the voxel.
LEAK_BOUND_default="0.0040 0.0020 0.0015"
LEAK_BOUND_aniso0="0.0019 0.0013 0.0013"
LEAK_BOUND_thesis="0.078 0.072 0.059"
# vct_thick (solid voxels behind every surface, level 0 only: voxelize.comp, mip_aniso.comp), 1.5 and
# 3 voxels, measured 0.102% / 0.0775% / 0.0774% and 0.0637% / 0.0497% / 0.0654% at 32 / 64 / 128
# (the runs repeat bit for bit on llvmpipe; bounds 1.5x the measurement, as above). 1.5 voxels fill
# the column in front of the dark face, so a trilinear sample between it and the wall's column is
# opaque before it reaches the lit column behind; 3 also fill a level-1 texel there. What stays is the
# coarse levels (the solid voxels are left out of them: cornell's error rose 11% with them in).
LEAK_BOUND_thick15="0.0015 0.0012 0.0012"
LEAK_BOUND_thick3="0.0010 0.00075 0.0010"
nth() { echo "$1" | cut -d' ' -f"$2"; }
lt3() { lt "$1" "$2" && lt "$2" "$3"; }
i=0
for res in 32 64 128; do
    i=$((i + 1))
    check "light-leak vct_res=$res default renders" leak "$res" default
    leak_default=$leak
    check "light-leak vct_res=$res vct_level0=aniso renders" leak "$res" default ,vct_level0=aniso
    leak_aniso0=$leak
    check "light-leak vct_res=$res thesis renders" leak "$res" thesis
    leak_thesis=$leak
    check "light-leak vct_res=$res vct_thick=1.5 renders" leak "$res" default ,vct_thick=1.5
    leak_thick15=$leak
    check "light-leak vct_res=$res vct_thick=3 renders" leak "$res" default ,vct_thick=3
    leak_thick3=$leak
    echo "# light-leak vct_res=$res: leak ratio vct_thick=1.5 $leak_thick15, vct_thick=3 $leak_thick3"
    check "vct_res=$res: vct_thick=1.5 leaks under $(nth "$LEAK_BOUND_thick15" $i) ($leak_thick15)" \
        lt "$leak_thick15" "$(nth "$LEAK_BOUND_thick15" $i)"
    check "vct_res=$res: vct_thick=3 leaks under $(nth "$LEAK_BOUND_thick3" $i) ($leak_thick3)" \
        lt "$leak_thick3" "$(nth "$LEAK_BOUND_thick3" $i)"
    # the solid voxels must show, the more so the thicker
    check "vct_res=$res: vct_thick=3 < vct_thick=1.5 < default ($leak_thick3 < $leak_thick15 < $leak_default)" \
        lt3 "$leak_thick3" "$leak_thick15" "$leak_default"
    [ "$res" = 64 ] && leak_thick3_64=$leak_thick3
    echo "# light-leak vct_res=$res: leak ratio default $leak_default, vct_level0=aniso $leak_aniso0, thesis $leak_thesis"
    check "vct_res=$res: default leaks under $(nth "$LEAK_BOUND_default" $i) of the lit wall ($leak_default)" \
        lt "$leak_default" "$(nth "$LEAK_BOUND_default" $i)"
    check "vct_res=$res: vct_level0=aniso leaks under $(nth "$LEAK_BOUND_aniso0" $i) ($leak_aniso0)" \
        lt "$leak_aniso0" "$(nth "$LEAK_BOUND_aniso0" $i)"
    check "vct_res=$res: thesis leaks under $(nth "$LEAK_BOUND_thesis" $i) ($leak_thesis)" \
        lt "$leak_thesis" "$(nth "$LEAK_BOUND_thesis" $i)"
    # the anisotropic level 0 must show: less than the isotropic one
    check "vct_res=$res: vct_level0=aniso leaks less than the default ($leak_aniso0 < $leak_default)" \
        lt "$leak_aniso0" "$leak_default"
    # the improvements must show: less than a tenth of the thesis's leak (measured a 20th to a 40th)
    check "vct_res=$res: default leaks < a tenth of the thesis ($leak_default vs $leak_thesis)" \
        lt "$leak_default" "$(awk -v t="$leak_thesis" 'BEGIN { print t / 10 }')"
done

# max8_of BUDGET: the 8-bit image's max error against the black ruler (what a visitor sees; gikiosk
# compare's max_error of the PNG capture, --capture without --hdr), light-leak at 160x120, 2nd frame.
max8_of() {
    rm -rf "$TMP/ldr"
    "$GIKIOSK" run --platform mock --scene light-leak --method vct --size 160x120 --frames 2 --capture "$TMP/ldr" \
        --budget "$1" >/dev/null 2>&1 &&
        "$GIKIOSK" compare tests/references/light-leak.exr "$TMP/ldr/000001-light-leak-vct.png" --json 2>/dev/null |
        sed -n 's/.*"max_error": \([^,]*\),.*/\1/p'
}

# vct_thick=3 with vct_level0=aniso at 64^3, the least leak of the switches: 0.0428% (bound 1.5x),
# below either alone (0.0497%, 0.087%); in the 8-bit image a visitor sees, 5/255 at most where the
# default shows 32/255 (gikiosk compare's max_error, --capture without --hdr; bound 8/255, 1.5x).
check "light-leak vct_res=64 vct_thick=3 vct_level0=aniso renders" leak 64 default ,vct_thick=3,vct_level0=aniso
echo "# light-leak vct_res=64 vct_thick=3 vct_level0=aniso: leak ratio $leak"
check "vct_thick=3 vct_level0=aniso leaks under 0.00064 ($leak)" lt "$leak" 0.00064
check "vct_thick=3 vct_level0=aniso leaks less than vct_thick=3 alone ($leak < $leak_thick3_64)" lt "$leak" "$leak_thick3_64"
max8=$(max8_of "shadow=pcss,vct_res=64,vct_thick=3,vct_level0=aniso,vct_axis_clamp=off")
echo "# light-leak vct_res=64 vct_thick=3 vct_level0=aniso: 8-bit max error $max8"
check "vct_thick=3 vct_level0=aniso: 8-bit max error under 8/255 ($max8)" lt "$max8" "$(awk 'BEGIN { print 8 / 255 }')"

# vct_axis_clamp (not in the thesis; vct/cone_lib.glsl axis_clamp, README "The axis clamp"): what the
# switches above leave is the coarse levels' trilinear filtering. The wall (x = 0) is a texel boundary
# at every level, so no mip voxel straddles it; but a fetch at level k reads the two texels whose
# centres bracket the sample, so a dark-room sample within half a level-k texel of the wall reads the
# lit side's texel beside it, a lateral blend that no directional opacity in front of it stops. Split
# by sample (a diagnosis run: each class's radiance alone, the sums match to fp16), of the 0.043% of
# vct_thick=3 with vct_level0=aniso at 64^3: 57.7% samples whose finer level's pair holds a lit texel
# (lod 0 13.5%, 1 17.9%, 2 21.6%, 3 4.6%), 33.1% those whose coarser level's alone does (lods 1-3),
# 9.1% samples already past the wall (lods 1-2), and exactly 0 from samples whose pairs hold no lit
# texel. With the clamp no sample reads a texel past the first occupied voxel along an axis (first),
# or holding the second (second), level 0 is read from the sample's side, and no step carries a
# sample past the wall's first voxel; with the solid voxels of vct_thick=1.5 for it to stop at, the
# dark room is black: 0 exactly at every vct_res, in the HDR image and in 8 bits (measured; the
# bound is the measurement itself, since a correct image is 0). The clamp alone leaves level-0
# samples past the wall (all of what stays, from scattered receivers on the ceiling and the side
# wall): 0.058% at 64^3 with second, 8-bit max 2/255 (bounds 1.5x: 0.00087, 3/255). It is not the
# default: it narrows the cones' samples near walls, and the six cones then resolve the voxels
# instead of averaging them (cornell 0.074 -> 0.094 with second, 0.113 with vct_thick=1.5; README).
zero() { awk -v a="$1" 'BEGIN { n = "^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$"; exit !(a ~ n && a + 0 == 0) }'; }
for res in 32 64 128; do
    check "light-leak vct_res=$res vct_axis_clamp=second vct_thick=1.5 renders" leak "$res" default ,vct_axis_clamp=second,vct_thick=1.5
    echo "# light-leak vct_res=$res vct_axis_clamp=second vct_thick=1.5: leak ratio $leak"
    check "vct_res=$res: vct_axis_clamp=second with vct_thick=1.5 leaks nothing ($leak)" zero "$leak"
done
check "light-leak vct_res=64 vct_axis_clamp=first vct_thick=1.5 renders" leak 64 default ,vct_axis_clamp=first,vct_thick=1.5
echo "# light-leak vct_res=64 vct_axis_clamp=first vct_thick=1.5: leak ratio $leak"
check "vct_axis_clamp=first with vct_thick=1.5 leaks nothing ($leak)" zero "$leak"
check "light-leak vct_res=64 vct_axis_clamp=second renders" leak 64 default ,vct_axis_clamp=second
echo "# light-leak vct_res=64 vct_axis_clamp=second: leak ratio $leak"
check "vct_axis_clamp=second alone leaks under 0.00087 ($leak)" lt "$leak" 0.00087
check "vct_axis_clamp=second alone leaks, the solid voxels stop what passes through ($leak > 0)" lt 0 "$leak"
for extra in "" ",vct_thick=1.5"; do
    max8=$(max8_of "shadow=pcss,vct_res=64,vct_axis_clamp=second$extra")
    echo "# light-leak vct_res=64 vct_axis_clamp=second$extra: 8-bit max error $max8"
    if [ -z "$extra" ]; then
        check "vct_axis_clamp=second: 8-bit max error under 3/255 ($max8)" lt "$max8" "$(awk 'BEGIN { print 3 / 255 }')"
    else
        check "vct_axis_clamp=second$extra: 8-bit max error 0 ($max8)" zero "$max8"
    fi
done

# The second bounce (vct_bounces=2) gathers what leaked into the dark room's voxels and re-emits it
# there; the wall's own voxels (both faces in one voxel, mean normal < 0.25) gather nothing.
# Measured at 64^3: 0.132% one bounce (directional views), 1.28% two (isotropic views, vct.c says
# why; 6.7% before the injection's fixes). Bound 1.5x the measurement.
check "light-leak vct_res=64 vct_bounces=2 renders" leak 64 default ,vct_bounces=2
echo "# light-leak vct_res=64 vct_bounces=2: leak ratio $leak"
check "vct_res=64 vct_bounces=2: leaks under 1.9% of the lit wall ($leak)" lt "$leak" 0.019
leak_bounce2_off=$leak

# The default: vct_axis_clamp=thin (not in the thesis; vct/thin_flag.comp, README "The axis clamp at
# thin walls"). The clamp above, but stopped only at thin walls' voxels (a fragment with one facing
# away from it in its voxel or the next two behind it: both faces of light-leak's wall) and at the
# voxels up to 16 behind their fragments (limits, not opaque), so scenes without thin walls render
# as before, bit for bit (gi_not_worse.sh's header). Measured: 0 exactly at 32^3 and 64^3 (the
# scene's default), in HDR and so in 8 bits; the bound is the measurement, since a correct image is
# 0. At 128^3 0.0054% stays (RMSE 0.0010, off: 0.096%; bound 1.5x); the second bounce's gather
# (vct/bounce.comp) has no clamp: 0.131% with two bounces (off: 1.28%; bound 1.5x), so the dark
# room's voxels still receive what its cones gather there.
for res in 32 64; do
    check "light-leak vct_res=$res default (vct_axis_clamp=thin) renders" leak "$res" default ,vct_axis_clamp=thin
    echo "# light-leak vct_res=$res vct_axis_clamp=thin: leak ratio $leak"
    check "vct_res=$res: the default leaks nothing ($leak)" zero "$leak"
done
rm -rf "$TMP/ldr"
max8=$("$GIKIOSK" run --platform mock --scene light-leak --method vct --size 160x120 --frames 2 --capture "$TMP/ldr" \
    --budget "shadow=pcss" >"$TMP/run.log" 2>&1 && grep -q "vct_axis_clamp=thin" "$TMP/run.log" &&
    "$GIKIOSK" compare tests/references/light-leak.exr "$TMP/ldr/000001-light-leak-vct.png" --json 2>/dev/null |
    sed -n 's/.*"max_error": \([^,]*\),.*/\1/p')
echo "# light-leak default budget: 8-bit max error $max8"
check "the default budget is vct_axis_clamp=thin and its 8-bit image is black ($max8)" zero "$max8"
check "light-leak vct_res=128 vct_axis_clamp=thin renders" leak 128 default ,vct_axis_clamp=thin
echo "# light-leak vct_res=128 vct_axis_clamp=thin: leak ratio $leak"
check "vct_res=128: vct_axis_clamp=thin leaks under 0.000081 ($leak)" lt "$leak" 0.000081
check "light-leak vct_res=64 vct_axis_clamp=thin vct_bounces=2 renders" leak 64 default ,vct_axis_clamp=thin,vct_bounces=2
echo "# light-leak vct_res=64 vct_axis_clamp=thin vct_bounces=2: leak ratio $leak"
check "vct_axis_clamp=thin vct_bounces=2 leaks under 0.00196 ($leak)" lt "$leak" 0.00196
check "vct_axis_clamp=thin vct_bounces=2 leaks less than off ($leak < $leak_bounce2_off)" lt "$leak" "$leak_bounce2_off"
finish
