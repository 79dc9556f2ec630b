#!/bin/sh
# The glTF conformance set (tests/gltf/, tools/gltf_conformance.py) through the command line:
# `scenes --check` says what each file uses and what it ignores, refused files exit 2 naming the
# extension, and a textured model without lights (an embedded PNG in a GLB) renders lit by the
# default studio with every method that applies, agreeing with the reference tracer's render of
# the same default lighting.
. tests/e2e/lib.sh
DIR=tests/gltf
json_field() { sed -n "s/.*\"$1\": \(\[[^]]*\]\|[^,}]*\).*/\1/p" "$2"; }

expect_exit 0 "scenes --check on a GLB with an embedded image" "$GIKIOSK" scenes --check $DIR/texture-glb.glb
check "it reports the embedded image" grep -q "^gltf reads: .*1 embedded images" "$TMP/stdout"
check "it reports the default studio" grep -q "^lights: *1 (the file has none: the default studio, its environment and a key light)" "$TMP/stdout"
check "it shows the studio's environment" grep -q "^environment: built-in studio, 128x64 lat-long, intensity 1; split into [0-9]* area lights" "$TMP/stdout"
stderr_has "scene texture-glb has no lights: using the default studio" "the studio is logged"

expect_exit 0 "scenes --check on a data: uri image" "$GIKIOSK" scenes --check $DIR/texture-data-uri.gltf
check "it reports the embedded image" grep -q "^gltf reads: .*1 embedded images" "$TMP/stdout"
expect_exit 0 "scenes --check on a sparse accessor" "$GIKIOSK" scenes --check $DIR/sparse.gltf
check "it reports the sparse accessor" grep -q "^gltf reads: .*1 sparse accessors" "$TMP/stdout"
expect_exit 0 "scenes --check on KHR_mesh_quantization" "$GIKIOSK" scenes --check $DIR/quantized.gltf
check "it names the extension read" grep -q "^gltf reads: *KHR_mesh_quantization; 3 quantized accessors" "$TMP/stdout"
expect_exit 0 "scenes --check on a triangle strip" "$GIKIOSK" scenes --check $DIR/strip.gltf
check "it reports the conversion" grep -q "^gltf reads: .*1 strips/fans converted" "$TMP/stdout"
check "the strip makes 2 triangles" grep -q "^triangles: *2 drawn" "$TMP/stdout"
expect_exit 0 "scenes --check on lines beside a triangle" "$GIKIOSK" scenes --check $DIR/lines.gltf
check "it says the lines are not drawn" grep -q "^gltf skips: *1 points/lines primitives not drawn" "$TMP/stdout"
expect_exit 0 "scenes --check on cameras" "$GIKIOSK" scenes --check $DIR/cameras.gltf
check "the perspective camera is the view" grep -q "^camera: *persp" "$TMP/stdout"
check "the ignored extension and the orthographic camera are named" \
    grep -q "^gltf skips: *KHR_materials_clearcoat; 1 orthographic cameras never used" "$TMP/stdout"
check "a file with a light gets no studio" grep -q "^lights: *1$" "$TMP/stdout"

# Draco: the fuzz corpus's seed (tests/unit/test_gltf_draco.c's grid as text, extension required)
expect_exit 0 "scenes --check on a Draco-compressed primitive" "$GIKIOSK" scenes --check tests/fuzz/corpus/gltf/draco-grid.gltf
check "it reads the extension and counts the decoded primitive" \
    grep -q "^gltf reads: *KHR_draco_mesh_compression; 1 Draco-compressed primitives decoded" "$TMP/stdout"
check "the grid's 512 triangles are drawn" grep -q "^triangles: *512 drawn" "$TMP/stdout"
# meshopt: the fuzz corpus's seed (tests/unit/test_gltf_meshopt.c's grid, gltfpack's layout)
expect_exit 0 "scenes --check on meshopt-compressed bufferViews" "$GIKIOSK" scenes --check tests/fuzz/corpus/gltf/meshopt-grid.gltf
check "it reads both extensions and counts the decoded views" \
    grep -q "^gltf reads: *EXT_meshopt_compression, KHR_mesh_quantization; .*4 meshopt-compressed bufferViews decoded" "$TMP/stdout"
check "the grid's 512 triangles are drawn" grep -q "^triangles: *512 drawn" "$TMP/stdout"
expect_exit 2 "a required extension gikiosk does not read exits 2" "$GIKIOSK" scenes --check $DIR/requires-instancing.gltf
stderr_has "requires-instancing.gltf: requires extension 'EXT_mesh_gpu_instancing'" "naming the file and the extension"
expect_exit 2 "a KTX2 image exits 2" "$GIKIOSK" scenes --check $DIR/texture-ktx2.glb
stderr_has "texture-ktx2.glb: texture 0 .*KHR_texture_basisu" "naming the file, the texture and the extension"
expect_exit 0 "scenes --check on KHR_texture_transform" "$GIKIOSK" scenes --check $DIR/texture-transform.glb
check "it reads the extension and counts the transform" grep -q "^gltf reads: *KHR_texture_transform; .*1 texture transforms" "$TMP/stdout"
expect_exit 0 "scenes --check on a texture on TEXCOORD_1" "$GIKIOSK" scenes --check $DIR/texcoord1.glb
check "it counts the slot on the second set" grep -q "^gltf reads: .*1 textures on TEXCOORD_1" "$TMP/stdout"
expect_exit 0 "scenes --check on alphaMode MASK" "$GIKIOSK" scenes --check $DIR/alpha-mask.glb
check "it counts the masked material" grep -q "^gltf reads: .*1 alpha-masked materials" "$TMP/stdout"
expect_exit 0 "scenes --check on alphaMode BLEND" "$GIKIOSK" scenes --check $DIR/alpha-blend.glb
check "it counts the blended material" grep -q "^gltf reads: .*1 alpha-blended materials (drawn over the opaque ones)" "$TMP/stdout"
expect_exit 0 "scenes --check on a double-sided material" "$GIKIOSK" scenes --check $DIR/double-sided.glb
check "it counts the double-sided material" grep -q "^gltf reads: .*1 double-sided materials" "$TMP/stdout"
expect_exit 0 "scenes --check on an occlusion texture" "$GIKIOSK" scenes --check $DIR/occlusion-half.glb
check "it counts the occlusion texture and says what it darkens" \
    grep -q "^gltf reads: .*1 occlusion textures (ambient and indirect light only; not the tracer's)" "$TMP/stdout"
expect_exit 2 "a texture on TEXCOORD_2 exits 2" "$GIKIOSK" scenes --check $DIR/texcoord2.glb
stderr_has "texcoord2.glb: material 0: base colour texture reads TEXCOORD_2" "naming the file, material, slot and set"
expect_exit 0 "scenes --check on a texture with a sampler" "$GIKIOSK" scenes --check $DIR/sampler-wrap.glb
check "it reports the sampler" grep -q "^gltf reads: .*1 textures with a non-default sampler" "$TMP/stdout"
expect_exit 2 "a wrap mode glTF does not have exits 2" "$GIKIOSK" scenes --check $DIR/sampler-bad-wrap.glb
stderr_has "sampler-bad-wrap.glb: sampler 0: wrapS 10241" "naming the file, the sampler and the key"
expect_exit 2 "integer positions without KHR_mesh_quantization exit 2" "$GIKIOSK" scenes --check $DIR/quantized-undeclared.gltf
stderr_has "quantized-undeclared.gltf: accessor 0 .*UNSIGNED_SHORT.*KHR_mesh_quantization" "naming the accessor and the extension"

# Models whose material comes from more than factors, each rendered by every method that applies
# and by the reference tracer: the checker texture in a GLB lit by the studio, the same checker as
# an emissive texture (drawn flat white before), vertex colours lit by the studio, and a normal
# map tilting a white quad toward +u and toward +v (generated tangents), and the checker clamped
# along u and mirrored along v with nearest texels (sampler-wrap: 0.0907 against the tracer's own
# 0.127, the residual 0.012), the checker through KHR_texture_transform (0.0720 against 0.101) and
# read through TEXCOORD_1 (0.0735 against 0.103; through set 0 it is one red texel). The budgets the scheduler
# would trade (render scale, shadow filter, map size and subdivision, the studio's environment
# lights) are pinned: on a loaded machine it halves the render scale, and the comparison is of
# materials, not of the scheduler. (env_lights was not pinned until the full suite, two jobs at a
# time, moved it on sampler-wrap; its error against the tracer depends on it -- 4: 0.038, 8: 0.054,
# 16: 0.049, 32: 0.054 (with cssm_env's 5 cm cap before #11's receiver plane: 0.042, 0.060, 0.057,
# 0.064) -- as more sky lights bring more grazing ones, under which the lone quad shadows itself
# a little: render_env.c.) The normal maps run
# at shadow_map=2048 and with vct: with the mapped normal in place of the geometric one (the
# G-buffer's 5th target) the shadow offset made the tilted quad shadow itself there (mean ratio
# 0.956; 0.998 at 1024) and vct's cones started inside the quad's own voxels (1.10 on normal-map,
# 2.15 on normal-map-v); with it, 0.9999 and 1.0009 (none and vct alike). Two
# references (seeds 1 and 2) measure the tracer's own noise, so the renderer's error is judged
# against it rather than against a fixed number.
for sc in ${CONFORMANCE_SCENES:-texture-glb emissive-texture vertex-colors normal-map normal-map-v sampler-wrap texture-transform texcoord1}; do
    "$GIKIOSK" reference --scenes-dir $DIR --scene $sc --size 160x120 --spp 512 --out "$TMP/$sc-ref1.exr" 2>/dev/null
    "$GIKIOSK" reference --scenes-dir $DIR --scene $sc --size 160x120 --spp 512 --seed 2 --out "$TMP/$sc-ref2.exr" 2>/dev/null
    "$GIKIOSK" compare "$TMP/$sc-ref1.exr" "$TMP/$sc-ref2.exr" --json >"$TMP/noise.json"
    noise=$(json_field rel_rmse "$TMP/noise.json")
    methods=$("$GIKIOSK" scenes --dir $DIR 2>/dev/null | awk -v s=$sc '$1 == s { print $5 }' | tr ',' ' ')
    check "$sc: methods apply ($methods)" test -n "$methods"
    for m in $methods; do
        map=1024
        case "$sc" in normal-map*) map=2048 ;; esac
        "$GIKIOSK" run --platform mock --scenes-dir $DIR --scene $sc --method "$m" --frames 12 --size 160x120 \
            --budget render_scale=1,shadow=pcss,shadow_map=$map,shadow_subdiv=3,env_lights=16 \
            --capture "$TMP/$sc-$m" --hdr >/dev/null 2>&1
        exr=$(ls "$TMP/$sc-$m"/*.exr 2>/dev/null | tail -1)
        check "$sc: $m renders" test -n "$exr"
        [ -n "$exr" ] || continue
        "$GIKIOSK" compare "$TMP/$sc-ref1.exr" "$exr" --json >"$TMP/$m.json"
        err=$(json_field rel_rmse "$TMP/$m.json")
        ratio=$(json_field mean_ratio "$TMP/$m.json")
        echo "# $sc $m: rel_rmse $err vs the reference (its own noise: ref-vs-ref $noise), mean_ratio $ratio"
        # Lit, and lit as the tracer lights it: the energy within 3% (measured 0.980 to 1.020 on
        # the five models under the studio's environment and key, 0.9988 to 0.9995 on three under
        # its former three directional lights; a renderer that ignored the texture or the vertex
        # colours is off by 30% or more, the flat white emitter by 2x).
        check "$sc: $m: lit like the reference (mean ratio $ratio in [0.97, 1.03])" \
            awk -v r="$ratio" 'BEGIN { exit !(r >= 0.97 && r <= 1.03) }'
        # The renderer's own error: rel_rmse(gpu, ref1)^2 - rel_rmse(ref1, ref2)^2 / 2 removes ref1's
        # noise (measured: 0.0735^2 - 0.103^2 / 2, about 0.01 left on the checker; 0.0013 on the
        # emitter). Bound 0.06: the residual is edge aliasing of a 1-spp raster against a
        # supersampled one; nearest texels in one renderer and bilinear in the other gave 1.2.
        check "$sc: $m: the error beyond the reference's noise is at most 0.06" \
            awk -v e="$err" -v n="$noise" 'BEGIN { x = e * e - n * n / 2; exit !(x <= 0.06 * 0.06) }'
    done
done

# alphaMode MASK: a quad cut by its texture's alpha in front of a wall (alpha-mask.glb), against
# the same file with alphaMode OPAQUE (alpha-opaque.glb), direct light only (method none): the
# G-buffer's and the shadow maps' discard against the tracer's any-hit test. Two planes and a
# shadow have more edges than the lone quads above: the opaque control's own error against the
# tracer is 0.107 (mean 0.984), over the 0.06 residual of the loop above, so the masked file is
# held to its control: the mask may add no error (measured 0.095 against the control's 0.107).
# The GI methods' own scene passes cut them too: alpha-mask-gi below.
# One file under the studio, method none against the tracer (512 spp, seed 1): $TMP/SC-ref1.exr,
# $TMP/SC-gpu.exr and $TMP/SC.json (their comparison); the energy within 3% as above.
# A field of `compare A B --json`.
compare_field() { "$GIKIOSK" compare "$1" "$2" --json >"$TMP/cmp.json"; json_field "$3" "$TMP/cmp.json"; }
# One file under the studio, method none at 160 x 120 into $TMP/SC-gpu.exr.
render_none() {
    "$GIKIOSK" run --platform mock --scenes-dir $DIR --scene $1 --method none --frames 12 --size 160x120 \
        --budget render_scale=1,shadow=pcss,shadow_map=1024,shadow_subdiv=3,env_lights=16 --capture "$TMP/$1-none" --hdr >/dev/null 2>&1
    exr=$(ls "$TMP/$1-none"/*.exr 2>/dev/null | tail -1)
    check "$1: renders" test -n "$exr"
    cp "$exr" "$TMP/$1-gpu.exr" 2>/dev/null
}
# ... and against the tracer (512 spp, seed 1: $TMP/SC-ref1.exr; the comparison in $TMP/SC.json),
# the energy within 3% as above.
none_vs_reference() {
    sc=$1
    "$GIKIOSK" reference --scenes-dir $DIR --scene $sc --size 160x120 --spp 512 --out "$TMP/$sc-ref1.exr" 2>/dev/null
    render_none $sc
    "$GIKIOSK" compare "$TMP/$sc-ref1.exr" "$TMP/$sc-gpu.exr" --json >"$TMP/$sc.json"
    ratio=$(json_field mean_ratio "$TMP/$sc.json")
    echo "# $sc none: rel_rmse $(json_field rel_rmse "$TMP/$sc.json") vs the reference, mean_ratio $ratio"
    check "$sc: lit like the reference (mean ratio $ratio in [0.97, 1.03])" \
        awk -v r="$ratio" 'BEGIN { exit !(r >= 0.97 && r <= 1.03) }'
}
for sc in alpha-mask alpha-opaque; do
    none_vs_reference $sc
done
em=$(json_field rel_rmse "$TMP/alpha-mask.json")
eo=$(json_field rel_rmse "$TMP/alpha-opaque.json")
check "the mask adds no error against the tracer (rel_rmse $em, the opaque control $eo)" \
    awk -v m="$em" -v o="$eo" 'BEGIN { exit !(m <= 1.05 * o) }'
# The holes are in both pictures: the tracer's masked image differs from its opaque control by
# far more than the tracer's own noise (the control against itself at another seed, measured here),
# and the rasterizer's masked-vs-opaque difference is the tracer's (the same holes, the same wall
# seen through them). Under the default studio (environment + key light, since h-env; 0.48 under the
# former three directional lights) measured: tracer 0.164, its noise 0.029, rasterizer 0.165.
# Bounds: the tracer's difference over 3x its noise; the rasterizer's within 25% of the tracer's.
"$GIKIOSK" reference --scenes-dir $DIR --scene alpha-opaque --size 160x120 --spp 512 --seed 2 \
    --out "$TMP/alpha-opaque-ref2.exr" 2>/dev/null
"$GIKIOSK" compare "$TMP/alpha-opaque-ref1.exr" "$TMP/alpha-opaque-ref2.exr" --json >"$TMP/an.json"
an=$(json_field rel_rmse "$TMP/an.json")
"$GIKIOSK" compare "$TMP/alpha-opaque-ref1.exr" "$TMP/alpha-mask-ref1.exr" --json >"$TMP/am.json"
am=$(json_field rel_rmse "$TMP/am.json")
check "the tracer cuts holes the opaque control does not have (rel_rmse $am, over 3x its noise $an)" \
    awk -v r="$am" -v n="$an" 'BEGIN { exit !(r != "" && n != "" && r > 3 * n) }'
"$GIKIOSK" compare "$TMP/alpha-opaque-gpu.exr" "$TMP/alpha-mask-gpu.exr" --json >"$TMP/amg.json"
amg=$(json_field rel_rmse "$TMP/amg.json")
check "the G-buffer and shadow maps cut the same holes (rel_rmse $amg, the tracer's $am within 25%)" \
    awk -v r="$amg" -v t="$am" 'BEGIN { exit !(r != "" && t != "" && r >= 0.75 * t && r <= 1.25 * t) }'

# The normal maps change the picture (tilted toward +u the quad faces the key light more, toward
# +v less), so agreeing with the reference above is about the map, not about a flat quad (which
# gives 1). Measured 0.10 under the studio's former three directional lights, 0.62 since its
# environment fills the side the key misses; bound 0.8. The ratio must be a number.
"$GIKIOSK" compare "$TMP/normal-map-ref1.exr" "$TMP/normal-map-v-ref1.exr" --json >"$TMP/nm.json"
ratio=$(json_field mean_ratio "$TMP/nm.json")
check "the two tilts give different pictures (mean ratio $ratio, measured 0.62)" \
    awk -v r="$ratio" 'BEGIN { exit !(r ~ /^[0-9.]+$/ && r + 0 < 0.8) }'
# doubleSided: a red quad showing the camera its back face in front of a grey wall. Single-sided,
# the G-buffer culls it and the tracer's camera rays pass it: both show the wall (with the quad's
# shadow, which both faces cast); double-sided, both show the red quad. Each file against the
# tracer (the energy within 3%, above), and the two files differ in the rasterizer as in the tracer
# (bounds as for the mask: the tracer's difference over 3x its noise, the rasterizer's within 25%).
for sc in single-sided double-sided; do
    none_vs_reference $sc
done
sd=$(compare_field "$TMP/single-sided-ref1.exr" "$TMP/double-sided-ref1.exr" rel_rmse)
sdg=$(compare_field "$TMP/single-sided-gpu.exr" "$TMP/double-sided-gpu.exr" rel_rmse)
echo "# single- vs double-sided: tracer $sd, rasterizer $sdg (the tracer's noise $an)"
check "the tracer sees through the single-sided back face only (rel_rmse $sd, over 3x its noise $an)" \
    awk -v r="$sd" -v n="$an" 'BEGIN { exit !(r != "" && n != "" && r > 3 * n) }'
check "the G-buffer culls it as the tracer passes it (rel_rmse $sdg, the tracer's $sd within 25%)" \
    awk -v r="$sdg" -v t="$sd" 'BEGIN { exit !(r != "" && t != "" && r >= 0.75 * t && r <= 1.25 * t) }'
# A mirroring node (single-sided-mirrored: the single-sided quad under scale (-1, 1, 1)): its
# triangles' winding is reversed, and glTF makes its front faces clockwise, so its front still faces
# the wall: both renderers show the wall, as for single-sided (a renderer that ignores the
# determinant shows the red quad, as for double-sided). Measured: rasterizer 9.9e-6, tracer 1.3e-9 (single vs double 0.153, 0.130). Bound: under a
# tenth of the single- vs double-sided difference, in each renderer.
none_vs_reference single-sided-mirrored
smg=$(compare_field "$TMP/single-sided-gpu.exr" "$TMP/single-sided-mirrored-gpu.exr" rel_rmse)
smr=$(compare_field "$TMP/single-sided-ref1.exr" "$TMP/single-sided-mirrored-ref1.exr" rel_rmse)
echo "# mirrored vs single-sided: rasterizer $smg, tracer $smr (single vs double: $sdg, $sd)"
check "a mirrored single-sided quad is culled as the unmirrored one (rasterizer rel_rmse $smg < $sdg / 10)" \
    awk -v m="$smg" -v d="$sdg" 'BEGIN { exit !(m != "" && d != "" && m < 0.1 * d) }'
check "and the tracer's camera rays pass it (rel_rmse $smr < $sd / 10)" \
    awk -v m="$smr" -v d="$sd" 'BEGIN { exit !(m != "" && d != "" && m < 0.1 * d) }'
# occlusionTexture, ambient light (method none under a uniform 1-nit sky, all of it the
# environment's SH ambient, the view filled by a quad of albedo 0.5): the texture's 0.502 (grey
# 128) scales the image by 0.502, strength 0 leaves it as it is, and the untextured file agrees
# with the tracer (which ignores the texture: measured 0.985, the SH fit of the 8 x 4 map). The
# ratio's bound 0.002: the G-buffer keeps (1 - ao) / 2 in half float (2.4e-4 on ao; measured 0.5017).
none_vs_reference occlusion-none
render_none occlusion-half
render_none occlusion-strength0
oh=$(compare_field "$TMP/occlusion-none-gpu.exr" "$TMP/occlusion-half-gpu.exr" mean_ratio)
check "an occlusion texture of 0.502 scales the ambient-only image by $oh (0.502 +- 0.002)" \
    awk -v r="$oh" 'BEGIN { exit !(r ~ /^[0-9.]+$/ && r >= 0.500 && r <= 0.504) }'
o0=$(compare_field "$TMP/occlusion-none-gpu.exr" "$TMP/occlusion-strength0-gpu.exr" rel_rmse)
check "strength 0 leaves it unchanged (rel_rmse $o0)" awk -v r="$o0" 'BEGIN { exit !(r ~ /^[0-9.e-]+$/ && r + 0 == 0) }'
# ... and the GI methods' light (a wall and floor under a sun, no ambient): method none is the same
# with or without the texture (direct light is never occluded by it), and what vct and vpl add is
# 0.502 as much with it. Measured 0.499 (vct) and 0.499 (vpl); bound 0.03 (half-float HDR: the GI
# is a tenth of the image). Without the occlusion pass the ratio is 1. (lightmap 0.487 and
# radiosity 0.473 were measured once and are not held to it: not investigated.) Every knob of the
# two methods is pinned at its default: the scheduler moved vct's on a loaded machine (0.557).
GI_PINNED=vct_res=64,vct_cones=6,vct_step=1,vct_trace_scale=0.5,vct_mips=aniso,vct_bounces=1
GI_PINNED=$GI_PINNED,vpl_n=256,vpl_m=8,vpl_val_map=64,vpl_block=4,vpl_res=0.5,vpl_blur=4,vpl_vis=cssm,vpl_gather=interleaved
for f in none half; do
    for m in none vct vpl; do
        "$GIKIOSK" run --platform mock --scenes-dir $DIR --scene occlusion-gi-$f --method $m --frames 12 --size 160x120 \
            --budget render_scale=1,shadow=pcss,shadow_map=1024,shadow_subdiv=3,$GI_PINNED --capture "$TMP/ogi-$f-$m" --hdr >/dev/null 2>&1
        cp "$(ls "$TMP/ogi-$f-$m"/*.exr 2>/dev/null | tail -1)" "$TMP/ogi-$f-$m.exr" 2>/dev/null
        check "occlusion-gi-$f: $m renders" test -s "$TMP/ogi-$f-$m.exr"
    done
done
# mean of an image over the untextured file's direct light
rel_mean() { compare_field "$TMP/ogi-none-none.exr" "$TMP/ogi-$1.exr" mean_ratio; }
d=$(rel_mean half-none)
check "the texture leaves direct light alone (mean ratio $d)" awk -v r="$d" 'BEGIN { exit !(r ~ /^[0-9.]+$/ && r == 1) }'
for m in vct vpl; do
    gn=$(rel_mean none-$m)
    gh=$(rel_mean half-$m)
    check "$m: the GI with the texture is 0.502 of it without ((${gh} - ${d}) / (${gn} - 1), within 0.03)" \
        awk -v n="$gn" -v h="$gh" -v d="$d" 'BEGIN { if (!(n > 1.02)) exit 1; r = (h - d) / (n - 1); exit !(r >= 0.472 && r <= 0.532) }'
done
# ... and alphaMode MASK on the GI methods' light (alpha-mask-gi.glb: the red holes quad between
# the sun and the floor of occlusion-gi's corner; alpha-opaque-gi.glb its control): vct's voxelizer
# and vpl's RSMs cut the holes too. Knobs pinned as above; the tracer at 512 spp, seed 1.
# (1) The masked file's error against the tracer may exceed its control's by no more than it does
# for method none plus a margin: the holes add indirect light (the lit floor under them) that none
# lacks altogether (none: 0.370 against 0.308, x1.20). Measured (x ratio, mask/control): vct 0.218 /
# 0.174 (x1.25), vpl 0.239 / 0.174 (x1.38); with the quad solid in their passes vct x1.25 (its
# error is dominated by what cone tracing misses, so this does not see the holes) and vpl x1.54.
# Bound: none's ratio + 0.25 (vpl's 0.18 with 0.07 of room; the renders are deterministic).
# (2) The wall's indirect light (method - none over the wall above the quad, pixels 55..104 x
# 22..51) is whiter through the holes: its red/green ratio, masked over control, is 0.45 in the
# tracer; vct 0.42, vpl 0.56; with the quad solid in their passes 0.82 (vct) and 1.00 (vpl: the
# RSM saw no difference at all). Bound 0.70, between the two.
for sc in alpha-mask-gi alpha-opaque-gi; do
    "$GIKIOSK" reference --scenes-dir $DIR --scene $sc --size 160x120 --spp 512 --out "$TMP/$sc-ref1.exr" 2>/dev/null
    for m in none vct vpl; do
        "$GIKIOSK" run --platform mock --scenes-dir $DIR --scene $sc --method $m --frames 12 --size 160x120 \
            --budget render_scale=1,shadow=pcss,shadow_map=1024,shadow_subdiv=3,$GI_PINNED --capture "$TMP/$sc-$m" --hdr >/dev/null 2>&1
        cp "$(ls "$TMP/$sc-$m"/*.exr 2>/dev/null | tail -1)" "$TMP/$sc-$m.exr" 2>/dev/null
        check "$sc: $m renders" test -s "$TMP/$sc-$m.exr"
    done
done
mask_ratio() { # mask/control rel_rmse against the tracer of method $1
    em=$(compare_field "$TMP/alpha-mask-gi-ref1.exr" "$TMP/alpha-mask-gi-$1.exr" rel_rmse)
    eo=$(compare_field "$TMP/alpha-opaque-gi-ref1.exr" "$TMP/alpha-opaque-gi-$1.exr" rel_rmse)
    awk -v m="$em" -v o="$eo" 'BEGIN { if (m ~ /^[0-9.e-]+$/ && o + 0 > 0) printf "%.3f", m / o }'
}
rn=$(mask_ratio none)
for m in vct vpl; do
    r=$(mask_ratio $m)
    echo "# alpha-mask-gi $m: rel_rmse mask/control x$r (none x$rn)"
    check "alpha-mask-gi: $m's holes add no more error than none's (x$r, none x$rn + 0.25)" \
        awk -v r="$r" -v n="$rn" 'BEGIN { exit !(r != "" && n != "" && r <= n + 0.25) }'
done
if command -v oiiotool >/dev/null; then
    # red/green of the wall's indirect light: image $1 minus method none's of scene $2
    wall_rg() {
        oiiotool "$1" "$TMP/$2-none.exr" --sub --crop 50x30+55+22 --printstats 2>/dev/null |
            awk '/Avg:/ { sub(/.*Avg: */, ""); if ($2 > 0) printf "%.4f", $1 / $2; exit }'
    }
    whiter() { awk -v m="$1" -v o="$2" 'BEGIN { if (m != "" && o + 0 > 0) printf "%.3f", m / o }'; }
    q=$(whiter "$(wall_rg "$TMP/alpha-mask-gi-ref1.exr" alpha-mask-gi)" "$(wall_rg "$TMP/alpha-opaque-gi-ref1.exr" alpha-opaque-gi)")
    check "the tracer's indirect light on the wall is whiter through the holes (red/green x$q, at most 0.70)" \
        awk -v q="$q" 'BEGIN { exit !(q != "" && q <= 0.70) }'
    for m in vct vpl; do
        q=$(whiter "$(wall_rg "$TMP/alpha-mask-gi-$m.exr" alpha-mask-gi)" "$(wall_rg "$TMP/alpha-opaque-gi-$m.exr" alpha-opaque-gi)")
        check "$m's indirect light on the wall is whiter through the holes (red/green x$q, at most 0.70)" \
            awk -v q="$q" 'BEGIN { exit !(q != "" && q <= 0.70) }'
    done
fi
# alphaMode BLEND: a red quad of alpha 0.5 over a white wall, filling the view, ambient light only:
# the blend pass gives half the opaque quad's colour plus half the wall's (the same file OPAQUE, and
# MASKed away), per channel. Bound rel_rmse 0.002: the HDR target is half float (its step is 4.9e-4
# between 0.5 and 1; measured 5.1e-4). The tracer (stochastic transparency) is compared and printed,
# not bounded: the quad's partial shadow on the wall, which the rasterizer lacks (render_blend.c).
for sc in blend-half blend-opaque blend-cut; do
    render_none $sc
done
if command -v oiiotool >/dev/null; then
    oiiotool "$TMP/blend-opaque-gpu.exr" "$TMP/blend-cut-gpu.exr" --add --mulc 0.5 -o "$TMP/blend-expected.exr"
    bl=$(compare_field "$TMP/blend-expected.exr" "$TMP/blend-half-gpu.exr" rel_rmse)
    check "a 50% red quad over the wall is half of each (rel_rmse $bl against the mix, at most 0.002)" \
        awk -v r="$bl" 'BEGIN { exit !(r ~ /^[0-9.e-]+$/ && r + 0 <= 0.002) }'
    bo=$(compare_field "$TMP/blend-opaque-gpu.exr" "$TMP/blend-half-gpu.exr" rel_rmse)
    check "and not the opaque quad (rel_rmse $bo against it, over 0.2)" awk -v r="$bo" 'BEGIN { exit !(r > 0.2) }'
fi
"$GIKIOSK" reference --scenes-dir $DIR --scene blend-half --size 160x120 --spp 256 --out "$TMP/blend-half-ref.exr" 2>/dev/null
echo "# blend-half none vs the tracer: rel_rmse $(compare_field "$TMP/blend-half-ref.exr" "$TMP/blend-half-gpu.exr" rel_rmse)," \
    "mean_ratio $(compare_field "$TMP/blend-half-ref.exr" "$TMP/blend-half-gpu.exr" mean_ratio)"
finish
