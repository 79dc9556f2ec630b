#!/bin/sh
# `make bench`: the speed-against-accuracy sweeps of each module (DESIGN §3-4). Each writes
# out/bench/NAME/bench.csv and out/bench/NAME/speed-accuracy-SCENE.png/.svg. Slow on llvmpipe
# (minutes per sweep); the frame times there are CPU times: read them as ratios within one run.
# BENCH_ARGS adds options to every sweep (e.g. BENCH_ARGS="--frames 9").
set -eu
BIN=${1:-build/gikiosk}
LGV_TEST=${2:-build/tests/gpu/test_lgv} # the harness behind lgv's Fig. 9 chart (tools/fig9_chart.sh)
OUT=${OUT:-out/bench}
ARGS=${BENCH_ARGS:-}
mkdir -p "$OUT"
run() { # name, then bench options
    name=$1; shift
    echo "bench: $name: $*"
    # shellcheck disable=SC2086
    "$BIN" bench "$@" $ARGS --roofline-csv "$OUT/roofline.csv" --out "$OUT/$name"
}
# The machine's fetch limits (the roofline): fetches per second per kind of fetch the methods do,
# the denominator of each pass's efficiency (every sweep below writes efficiency.csv and its bars,
# efficiency-SCENE.png, for the passes with a work model).
echo "bench: roofline"
"$BIN" bench --roofline --out "$OUT"
# #21's yardstick: vct's cone trace at 64³, 9 cones, trace scale 1, anisotropic mips, cornell at
# 640x360 (target: >= 30% of the tex3d_rgba16f_trilinear limit), beside the roofline it is divided by.
run efficiency --scenes cornell --methods vct --size 640x360 \
    --sweep 'vct_res=64;vct_cones=9;vct_trace_scale=1;vct_mips=aniso'
# Direct light and soft shadows: shadow method x shadow-map size (renderer core).
run shadows --scenes shadow-planes,cornell --methods none
# Voxel cone tracing: each knob one at a time, on the scenes of its issue.
if "$BIN" scenes | grep -q 'vct'; then
    run vct --scenes cornell,light-leak,atrium --methods vct
    # What a moving light or object costs: every pass every frame, per voxel resolution.
    run vct-rebuild --scenes cornell,atrium --methods vct --sweep 'vct_res=32,64,128' --rebuild-gi
    # Shadows with vct (README "Soft-shadow cone"): the cone toward the light at the thesis's
    # apertures and the light's, beside the shadow maps' methods, in one run; the cone's pass is
    # direct.vct_shadow_cone (inside the direct pass, whose time compares with the maps' lookups).
    run vct-shadows --scenes cornell,cornell-spot --methods vct \
        --sweep 'vct_shadow=map,cone9,cone6,cone3,cone0,cone;shadow=hard,pcss,vssm,cssm'
    # Algorithm 1 (vct_skip) on the shadow cone, off against on (README: the 0-degree cone gains, the
    # light-sized one loses; the specular cone's count is in tests/gpu/test_vct_skip.c).
    run vct-skip --scenes cornell,cornell-spot --methods vct --sweep 'vct_shadow=cone0,cone;vct_skip=off,on'
fi
# VPLs with clustered virtual area lights: N x M and adaptive M.
if "$BIN" scenes | grep -q 'vpl'; then
    run vpl --scenes cornell-spot,atrium --methods vpl --sweep 'vpl_n=256,512,1024;vpl_m=2,4,8,16,32,adaptive'
fi
# Caustics by image-space photon mapping, on caustic-ring's chart with the other methods: none, vct
# and vpl at their defaults beside ispm's photons x trace resolution.
if "$BIN" scenes | grep -q 'ispm'; then
    run ispm --scenes caustic-ring --methods none,vct,vpl,ispm --sweep 'ispm_photons=1024,4096,16384,65536;ispm_trace=64,128,256'
    # the seed's behaviour against the improvements behind its switches (specular chains, splat radius)
    run ispm-switches --scenes caustic-ring --methods ispm --sweep 'ispm_bounces=1,2,3;ispm_radius=seed,density,footprint'
fi
# Hierarchical radiosity with implicit visibility: bin resolution (the seed's Table 4.1: 6x16²
# closest to the reference, cost rising) and bounces, each against the full reference (multi-bounce);
# lockstep so every measured frame has its links (the worker builds them during the warm-up).
if "$BIN" scenes | grep -q 'radiosity'; then
    run radiosity --scenes cornell,furnace --methods radiosity --budget radiosity_sync=lockstep \
        --sweep 'radiosity_bins=8,12,16;radiosity_bounces=1,2,4,8'
    # The seed's Table 4.1: the whole per-frame pipeline every frame (--rebuild-gi: refit, link
    # creation, refinement and push-down, direct light on the worker, which the lockstep frame waits
    # for in its radiosity_upload pass; then the bounces), one series per bin resolution.
    run radiosity-bins --scenes cornell --methods radiosity --budget radiosity_sync=lockstep \
        --sweep 'radiosity_bins=8,12,16' --rebuild-gi
fi
# CPU photon mapping into light maps: photon groups x sync on cornell (async: the frame never waits
# for the photon work; lockstep: it does), and the render thread's frame with one photon thread
# against [cpu] workers (default cores - 1) on cornell-spot-anim, whose turning spot keeps the
# workers busy every frame (M2): the frame_ms ratio of the two rows is the photon work's cost to the
# frame.
if "$BIN" scenes | grep -q 'lightmap'; then
    run lightmap --scenes cornell --methods lightmap --sweep 'lightmap_groups=77,154,308,616;lightmap_sync=async,lockstep'
    run lightmap-workers --scenes cornell-spot-anim --methods lightmap --sweep 'lightmap_workers=1,config;lightmap_groups=77,616'
fi
# Volume caustics in fog (seed 001 ch. 8) on the two fog scenes, beside none: the caustic buffer x
# the caustic lights, then the filter support and the march resolution, each against the scene's full
# reference (multiple scattering included: the model's missing share is in every point's error).
if "$BIN" scenes | grep -q 'volcaustics'; then
    run volcaustics --scenes caustic-ring-fog,glass-fog --methods none,volcaustics --sweep 'vc_buffer=128,256,512,1024;vc_lights=1,2'
    run volcaustics-filter --scenes caustic-ring-fog,glass-fog --methods volcaustics --sweep 'vc_filter=0.1,0.5,1,2;vc_march=0.25,0.5,1'
    # its multiple-scattering limitation: error against the full reference as albedo and density grow
    echo "bench: volcaustics-multiple"
    sh tools/volcaustics_multiple.sh "$BIN" "$OUT/volcaustics-multiple"
fi
# Photon tracing against distance cube-maps with SH grids (seed 002): the LGV sizes of its Fig. 9
# (16³/32³/48³) on glass, the whole image against glass.exr (speed-accuracy-glass.png), at the default
# photons and at 16x them; the lgv_gather pass's time is the grid's. Over the whole image the LGV's
# part is small and noisy; Fig. 9's trend is in its indirect light alone, charted by fig9_chart.sh
# (fig9-glass.png: the GPU test's harness, which draws the LGV's light alone). lgv beside the other
# methods is on the `methods` run's charts below.
if "$BIN" scenes | grep -q 'lgv'; then
    run lgv --scenes glass --methods lgv --sweep 'lgv_size=16,32,48;lgv_photons=65536,1048576'
    # Fig. 9 itself: the indirect light alone against glass-indirect.exr per size, as measured and
    # without the photon noise, against the lgv_gather pass (fig9-glass.png; ~20 s).
    echo "bench: lgv fig9"
    sh tools/fig9_chart.sh "$LGV_TEST" "$OUT/lgv"
fi
# Choosing a method: per scene ONE chart with every method's default sweep against one ruler
# (SCENE-1bounce.exr where it exists, else SCENE.exr), the Pareto front over all of them, each
# point's spread (median to p95 of its frames) and the kiosk's automatic choice at 400 ms, 640x360
# (from config/calibration/CLASS.csv) marked.
scenes=$(ls config/scenes/*.gltf config/scenes/*.glb 2>/dev/null | sed 's|.*/||; s/\.gltf$//; s/\.glb$//' | sort -u |
    tr '\n' ',' | sed 's/,$//')
run methods --scenes "$scenes" --one-ruler
echo "bench: results in $OUT/*/bench.csv and $OUT/*/speed-accuracy-*.png"
