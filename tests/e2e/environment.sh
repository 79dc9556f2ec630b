#!/bin/sh
# Scene environments (extras.gikiosk.environment, scene.h): bad input exits 2 naming the file and
# the key; `scenes` shows the environment; env-studio renders its environment's split (001 ch. 5
# §5.3.2: area lights shadowed with CSSM, the residual as ambient) against the path-traced
# reference, more accurately as the knob env_lights grows.
. tests/e2e/lib.sh
json_field() { sed -n "s/.*\"$1\": \(\[[^]]*\]\|[^,}]*\).*/\1/p" "$2"; }
D=$TMP/scenes
mkdir -p "$D"
cp config/scenes/env-studio.gltf config/scenes/env-studio.bin config/scenes/env-studio.exr "$D/"
variant() { # NAME SED-EXPRESSION: a copy of env-studio with its gltf edited
    sed "$2" config/scenes/env-studio.gltf >"$D/$1.gltf"
}

expect_exit 0 "scenes --check on env-studio" "$GIKIOSK" scenes --check "$D/env-studio.gltf"
check "it shows the environment and its split" \
    grep -q "^environment: env-studio.exr, 256x128 lat-long, intensity 1; split into 32 area lights" "$TMP/stdout"
check "it has no light of its own" grep -q "^lights: *0$" "$TMP/stdout"
expect_exit 0 "scenes lists env-studio" "$GIKIOSK" scenes --dir config/scenes
check "its LIGHTS column says +env" sh -c "grep '^env-studio ' '$TMP/stdout' | grep -q ' 0+env '"

variant missing 's/"uri":"env-studio.exr"/"uri":"nothing.exr"/'
expect_exit 2 "a missing environment map exits 2" "$GIKIOSK" scenes --check "$D/missing.gltf"
stderr_has "missing.gltf: scene extras gikiosk.environment.uri 'nothing.exr' is missing" "naming the file and the key"

oiiotool --pattern constant:color=1,1,1 16x16 3 -d float -o "$D/square.exr" 2>/dev/null
variant square 's/"uri":"env-studio.exr"/"uri":"square.exr"/'
expect_exit 2 "a map that is not lat-long exits 2" "$GIKIOSK" scenes --check "$D/square.gltf"
stderr_has "square.gltf: scene extras gikiosk.environment.uri 'square.exr' is 16x16 .*width = 2 x height" \
    "naming the file, the key and the layout"

oiiotool --pattern constant:color=1,-1,1 32x16 3 -d float -o "$D/negative.exr" 2>/dev/null
variant negpix 's/"uri":"env-studio.exr"/"uri":"negative.exr"/'
expect_exit 2 "negative radiance exits 2" "$GIKIOSK" scenes --check "$D/negpix.gltf"
stderr_has "negpix.gltf: .*'negative.exr': pixel \(0, 0\) channel 1 is -1" "naming the pixel"

oiiotool --pattern constant:color=1,1,1 4098x2049 3 -d half -o "$D/huge.exr" 2>/dev/null
variant huge 's/"uri":"env-studio.exr"/"uri":"huge.exr"/'
expect_exit 2 "a map wider than 4096 exits 2" "$GIKIOSK" scenes --check "$D/huge.gltf"
stderr_has "huge.gltf: .*'huge.exr' is 4098x2049; at most 4096x2048" "naming the limit"
rm -f "$D/huge.exr"

variant negint 's/"intensity":1/"intensity":-2/'
expect_exit 2 "a negative intensity exits 2" "$GIKIOSK" scenes --check "$D/negint.gltf"
stderr_has "negint.gltf: scene extras gikiosk.environment.intensity: -2 is not a finite number >= 0" \
    "naming the file and the key"

variant unknown 's/"intensity":1/"intensity":1,"rotation":30/'
expect_exit 2 "an unknown key exits 2" "$GIKIOSK" scenes --check "$D/unknown.gltf"
stderr_has "unknown.gltf: scene extras gikiosk.environment: unknown key 'rotation'" "naming it"

variant outside 's/"uri":"env-studio.exr"/"uri":"..\/env-studio.exr"/'
expect_exit 2 "a map outside the scene's folder exits 2" "$GIKIOSK" scenes --check "$D/outside.gltf"
stderr_has "outside.gltf: .*must be relative, inside the scene's folder" "saying why"

# The reference tracer renders the environment: env-studio's committed direct-light reference
# agrees with a fresh render at another seed (tests/e2e/reference.sh checks every reference the same
# way); here only that a render of the scene is lit (its mean is the reference's within 5%).
"$GIKIOSK" reference --scene env-studio --scenes-dir "$D" --size 160x120 --spp 16 --paths direct --seed 5 \
    --out "$TMP/ref.exr" 2>/dev/null
"$GIKIOSK" compare tests/references/env-studio-direct.exr "$TMP/ref.exr" --json >"$TMP/ref.json" 2>/dev/null
check "the tracer lights env-studio by its environment (mean ratio $(json_field mean_ratio "$TMP/ref.json"))" \
    awk -v r="$(json_field mean_ratio "$TMP/ref.json")" 'BEGIN { exit !(r > 0.95 && r < 1.05) }'

# The rasterizer's split against the direct-light reference (method none: direct light only), every
# other knob pinned. Measured at 160x120 on llvmpipe (README, "Environment lighting"):
#   env_lights   4: rel_rmse 0.089, mean ratio 1.037     16: 0.070, 1.020
#               8:          0.082,            1.032     32: 0.064, 1.013
# (the lights shadowed by cssm_plane, render_env.c: the final kernel tested against the receiver
# plane in sub-kernels. Before it, cssm_env's slope-scaled shift capped at 5 cm: 0.092, 0.086,
# 0.076, 0.071; uncapped, as the cssm knob level has it, the lights lost their contact shadows:
# 16 lights 0.104 / 1.049; the thesis's CSSM 0.099 / 1.031)
# The residual ambient is unshadowed (no sky occlusion under the objects): most of what is left at
# 32. Bounds: each N's rel_rmse its measured value + 12% (4: 0.100, 16: 0.079, 32: 0.072; the
# uncapped slope-scaled CSSM's 0.104 at 16 fails), its mean ratio in [0.97, 1.04] (the residual ambient
# only adds light; 1.049 with the slope-scaled CSSM fails); 32 lights at least 0.01 better than 4
# (measured 0.025; the render is deterministic, the margin is for another Mesa).
for n in 4 16 32; do
    "$GIKIOSK" run --platform mock --scenes-dir "$D" --scene env-studio --method none --frames 2 --size 160x120 \
        --budget render_scale=1,shadow=pcss,shadow_map=1024,shadow_subdiv=3,env_lights=$n \
        --capture "$TMP/n$n" --hdr >/dev/null 2>&1
    exr=$(ls "$TMP/n$n"/*.exr 2>/dev/null | tail -1)
    check "env_lights=$n renders" test -n "$exr"
    [ -n "$exr" ] || continue
    "$GIKIOSK" compare tests/references/env-studio-direct.exr "$exr" --json >"$TMP/n$n.json"
    eval "err$n=$(json_field rel_rmse "$TMP/n$n.json")"
    ratio=$(json_field mean_ratio "$TMP/n$n.json")
    echo "# env_lights=$n: rel_rmse $(eval echo \$err$n), mean_ratio $ratio"
    case $n in 4) bound=0.100 ;; 16) bound=0.079 ;; *) bound=0.072 ;; esac
    check "env_lights=$n: rel_rmse $(eval echo \$err$n) within $bound" awk -v e="$(eval echo \$err$n)" -v b=$bound 'BEGIN { exit !(e != "" && e <= b) }'
    check "env_lights=$n: mean ratio $ratio in [0.97, 1.04]" awk -v r="$ratio" 'BEGIN { exit !(r != "" && r >= 0.97 && r <= 1.04) }'
done
check "32 lights are more accurate than 4 ($err32 vs $err4)" awk -v a="$err32" -v b="$err4" 'BEGIN { exit !(a <= b - 0.01) }'
# A uniform environment (L = 0.5 x intensity 2 = 1 nit) over a Lambertian quad (specularFactor 0,
# base (0.8, 0.6, 0.4), 20 x 20 m): nothing is above the map's mean, so the split has no light and the
# whole map is ambient, E = pi L, and the quad's radiance is exactly base x L; beyond the quad's far
# edge the top rows see the map itself, 1 nit. Checks the SH ambient and the background of
# shaders_gles/direct/environment.frag against the closed form (float16 HDR target: 1e-3).
U=$TMP/uniform
mkdir -p "$U"
oiiotool --pattern constant:color=0.5,0.5,0.5 128x64 3 -d float -o "$U/uniform.exr" 2>/dev/null
cat >"$U/quad.gltf" <<'GLTF'
{
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_materials_specular"],
  "scene": 0,
  "scenes": [{"nodes": [0, 1], "extras": {"gikiosk": {"environment": {"uri": "uniform.exr", "intensity": 2}}}}],
  "nodes": [
    {"mesh": 0, "scale": [10, 1, 10]},
    {"translation": [0, 2, 3], "rotation": [-0.2297529, 0, 0, 0.9732489], "camera": 0}
  ],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 50}}],
  "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.4, 1], "metallicFactor": 0, "roughnessFactor": 1},
                 "extensions": {"KHR_materials_specular": {"specularFactor": 0}}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
  "buffers": [{"byteLength": 110, "uri": "data:application/octet-stream;base64,AACAvwAAAAAAAIC/AACAPwAAAAAAAIC/AACAPwAAAAAAAIA/AACAvwAAAAAAAIA/AAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAACAAEAAAADAAIAAAA="}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 48},
    {"buffer": 0, "byteOffset": 48, "byteLength": 48},
    {"buffer": 0, "byteOffset": 96, "byteLength": 12}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}
  ]
}
GLTF
expect_exit 0 "a quad under a uniform environment loads" "$GIKIOSK" scenes --check "$U/quad.gltf"
check "its environment has no light above the mean" grep -q "split into 0 area lights" "$TMP/stdout"
"$GIKIOSK" run --platform mock --scenes-dir "$U" --scene quad --method none --frames 2 --size 160x120 \
    --budget render_scale=1 --capture "$TMP/uq" --hdr >/dev/null 2>&1
exr=$(ls "$TMP/uq"/*.exr 2>/dev/null | tail -1)
check "the quad renders" test -n "$exr"
avg() { oiiotool "$exr" --crop "$1" --printstats 2>/dev/null | sed -n 's/.*Stats Avg: *\([^ ]*\) *\([^ ]*\) *\([^ ]*\).*/\1 \2 \3/p'; }
sky=$(avg 160x2+0+0) floor=$(avg 160x10+0+110)
echo "# uniform environment: top rows $sky (expected 1 1 1), bottom rows $floor (expected 0.8 0.6 0.4)"
near() { echo "$1" | awk -v a="$2" -v b="$3" -v c="$4" '{ exit !(NF == 3 && ($1 - a) ^ 2 < 1e-6 && ($2 - b) ^ 2 < 1e-6 && ($3 - c) ^ 2 < 1e-6) }'; }
check "the background is the map's radiance ($sky)" near "$sky" 1 1 1
check "the quad is base x L ($floor)" near "$floor" 0.8 0.6 0.4
finish
