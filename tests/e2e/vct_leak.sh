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
# footprint clamp, cones clipped at the border) and thesis (the thesis as published).
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless
L_WALL_NITS=2.94

# leak RES VARIANT: leak ratio of light-leak with vct into $leak
leak() {
    leak=
    rm -rf "$TMP/cap"
    "$GIKIOSK" run --platform mock --scene light-leak --method vct --size 160x120 --frames 2 --hdr \
        --capture "$TMP/cap" --budget "shadow=pcss,vct_res=$1,vct_variant=$2$3" >"$TMP/run.log" 2>&1 || return 1
    grep -q "vct_variant=$2" "$TMP/run.log" || return 1
    leak=$(oiiotool "$TMP/cap/000001-light-leak-vct.exr" --printstats 2>/dev/null |
        awk -v l=$L_WALL_NITS '/Stats Avg/ { print (0.2126 * $3 + 0.7152 * $4 + 0.0722 * $5) / l }')
    [ -n "$leak" ]
}
# lt A B: A < B, both numbers (a missing or garbled measurement fails)
lt() { awk -v a="$1" -v b="$2" 'BEGIN { n = "^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$"; exit !(a ~ n && b ~ n && a + 0 < b + 0) }'; }

for res in 32 64 128; do
    check "light-leak vct_res=$res default renders" leak "$res" default
    leak_default=$leak
    check "light-leak vct_res=$res thesis renders" leak "$res" thesis
    leak_thesis=$leak
    echo "# light-leak vct_res=$res: leak ratio default $leak_default, thesis $leak_thesis"
    # Measured (llvmpipe): default 2.3% / 2.6% / 2.8%, thesis 13.2% / 15.1% / 14.9% at 32 / 64 / 128
    # (default with directional level-1 views since issue 11; with isotropic ones 3.3% / 3.9% / 4.3%)
    # (before the glTF Appendix B BRDF, whose (1 - F) lowers the walls' diffuse reflection, 10%
    # more: 3.7% / 4.3% / 4.8% and 13.9% / 15.9% / 15.7%).
    # Most of the default's leak is level 0: the wall's lit face and its dark face fall in two
    # neighbouring voxels, and a trilinear sample between their centres sees half the lit voxel's
    # (isotropic) radiance at full opacity. Directional injection halves it (measured 2.2-2.5%)
    # (gk_vct_options.directional_injection, the default with one bounce); an anisotropic level 0
    # (6x its memory) would remove the rest. Bound 1.5x the measurement.
    check "vct_res=$res: default leaks under 4.2% of the lit wall ($leak_default)" lt "$leak_default" 0.042
    # the improvements must show: less than half the thesis's leak
    check "vct_res=$res: default leaks < half the thesis ($leak_default vs $leak_thesis)" \
        lt "$leak_default" "$(awk -v t="$leak_thesis" 'BEGIN { print t / 2 }')"
done

# The second bounce (vct_bounces=2) gathers what leaked into the dark room's voxels and re-emits it
# there; the wall's own voxels (both faces in one voxel, mean normal < 0.25) gather nothing.
# Measured at 64^3: 2.6% one bounce (directional views), 6.7% two (isotropic views, vct.c says why).
# Bound 1.5x the measurement.
check "light-leak vct_res=64 vct_bounces=2 renders" leak 64 default ,vct_bounces=2
echo "# light-leak vct_res=64 vct_bounces=2: leak ratio $leak"
check "vct_res=64 vct_bounces=2: leaks under 10% of the lit wall ($leak)" lt "$leak" 0.10
finish
