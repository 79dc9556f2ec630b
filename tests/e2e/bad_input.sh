#!/bin/sh
# Bad input is refused by name with exit 2, never read forever or accepted silently (issue 12):
# devices, directories and FIFOs as files; --size beyond the mock's cap; a glTF requiring an
# unsupported extension; a buffer uri outside the scene's folder (its bytes never echoed); NaN
# pixels in compare (exit 1, counted, never a success); a light too bright for the reference tracer.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless
S=config/scenes
RUN="$GIKIOSK run --platform mock --size 64x64 --scenes-dir $S --scene cornell --method none --frames 1"
# `timeout 20`: these used to read forever; each now fails within a fraction of a second, so the
# bound only turns a regression into a failure instead of a hang (it is not a measurement).
T="timeout 20"

# --- files that are not regular files
oiiotool --pattern constant:color=0.5,0.25,0.1 16x16 3 -d float -o "$TMP/a.exr"
expect_exit 2 "compare REF /dev/zero exits 2" $T "$GIKIOSK" compare "$TMP/a.exr" /dev/zero
stderr_has "/dev/zero: the image is a device, not a regular file" "compare names /dev/zero"
expect_exit 2 "--config /dev/zero exits 2" $T $RUN --config /dev/zero
stderr_has "/dev/zero: the config is a device, not a regular file" "--config names /dev/zero"
mkdir -p "$TMP/confdir"
expect_exit 2 "--config DIR exits 2" $T $RUN --config "$TMP/confdir"
stderr_has "confdir: the config is a directory, not a regular file" "--config names the directory"
mkfifo "$TMP/fifo"
expect_exit 2 "--script FIFO exits 2 (does not wait for a writer)" $T $RUN --script "$TMP/fifo"
stderr_has "fifo: the button script is a pipe, not a regular file" "--script names the FIFO"
head -c 1100000 /dev/zero | tr '\0' '#' >"$TMP/big.ini"
expect_exit 2 "a config over 1 MiB exits 2" $T $RUN --config "$TMP/big.ini"
stderr_has "big.ini: the config is larger than its limit of 1048576 bytes" "the limit is named"

# --- --size beyond the mock's documented cap
expect_exit 2 "--size 4096x4096 on mock exits 2" $RUN --size 4096x4096
stderr_has "size 4096x4096 is beyond the mock's limit" "the cap is named"

# --- glTF: a required extension gikiosk does not implement
mkdir -p "$TMP/scene/sub" "$TMP/outside"
printf '{"asset": {"version": "2.0"}, "extensionsUsed": ["EXT_mesh_gpu_instancing"], "extensionsRequired": ["EXT_mesh_gpu_instancing"]}\n' >"$TMP/scene/instancing.gltf"
expect_exit 2 "extensionsRequired EXT_mesh_gpu_instancing exits 2" $GIKIOSK scenes --check "$TMP/scene/instancing.gltf"
stderr_has "requires extension 'EXT_mesh_gpu_instancing'" "the extension is named"
printf '{"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"], "extensionsRequired": ["KHR_lights_punctual"]}\n' >"$TMP/scene/lights.gltf"
expect_exit 0 "a supported required extension is accepted" $GIKIOSK scenes --check "$TMP/scene/lights.gltf"

# --- glTF buffer uris stay inside the scene's folder; the file's bytes are never echoed
printf 'SECRET-BYTES-0123456789' >"$TMP/outside/secret.bin"
for uri in ../outside/secret.bin "$TMP/outside/secret.bin" link.bin; do
    printf '{"asset": {"version": "2.0"}, "buffers": [{"byteLength": 4, "uri": "%s"}]}\n' "$uri" >"$TMP/scene/buf.gltf"
    ln -sf "$TMP/outside/secret.bin" "$TMP/scene/link.bin"
    expect_exit 2 "buffer uri '$uri' outside the folder exits 2" $GIKIOSK scenes --check "$TMP/scene/buf.gltf"
    check "buffer uri '$uri': nothing of the file is echoed" sh -c "! grep -q SECRET '$TMP/stderr' '$TMP/stdout'"
done
printf 'ABCD' >"$TMP/scene/sub/in.bin"
printf '{"asset": {"version": "2.0"}, "buffers": [{"byteLength": 4, "uri": "sub/in.bin"}]}\n' >"$TMP/scene/inside.gltf"
expect_exit 0 "a buffer inside the scene's folder is read" $GIKIOSK scenes --check "$TMP/scene/inside.gltf"

# --- image uris too: a symlink in the folder that points out of it is refused, not read (found by
# tests/fuzz/fuzz_gltf_files.c: images were confined by name only)
oiiotool --pattern constant:color=1,0,0 2x2 3 -d uint8 -o "$TMP/outside/secret.png"
cp "$TMP/outside/secret.png" "$TMP/scene/in.png"
ln -sf "$TMP/outside/secret.png" "$TMP/scene/link.png"
for img in link.png in.png; do
    printf '{"asset": {"version": "2.0"}, "images": [{"uri": "%s"}], "textures": [{"source": 0}], "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]}\n' "$img" >"$TMP/scene/img-$img.gltf"
done
expect_exit 2 "image uri 'link.png' (a symlink out of the folder) exits 2" $GIKIOSK scenes --check "$TMP/scene/img-link.png.gltf"
stderr_has "image 'link.png' lies outside the scene's folder" "the image is named"
expect_exit 0 "an image inside the scene's folder is read" $GIKIOSK scenes --check "$TMP/scene/img-in.png.gltf"

# --- compare: NaN pixels are counted and never a success
# an all-NaN 16x16 RGB image: a PFM (float32, little-endian quiet NaN 0x7fc00000) made EXR
{ printf 'PF\n16 16\n-1.0\n'; i=0; while [ $i -lt 768 ]; do printf '\000\000\300\177'; i=$((i + 1)); done; } >"$TMP/nan.pfm"
oiiotool "$TMP/nan.pfm" -d float -o "$TMP/nan.exr"
expect_exit 1 "compare with a NaN test image exits 1" "$GIKIOSK" compare "$TMP/a.exr" "$TMP/nan.exr" --json
stderr_has "nan.exr: 768 NaN/inf values in the test image" "the NaN values are counted (16x16 pixels x 3 channels)"
check "the JSON carries the count and no NaN value" sh -c "grep -q '\"nonfinite\": 768' '$TMP/stdout' && ! grep -Eqi ': *-?(nan|inf)' '$TMP/stdout'"
expect_exit 2 "compare with a NaN reference exits 2" "$GIKIOSK" compare "$TMP/nan.exr" "$TMP/a.exr"
stderr_has "nan.exr: 768 NaN/inf values in the reference" "the reference's NaN values are named"

# --- the reference tracer refuses a light it cannot sum in float (1e38 cd rendered black, exit 0)
mkdir -p "$TMP/hot"
sed -n '/cat >"\$S\/a.gltf" <<.GLTF./,/^GLTF$/p' tests/e2e/run.sh | sed '1d;$d' |
    sed 's/"intensity": 20/"intensity": 1e38, "name": "blinding"/' >"$TMP/hot/hot.gltf"
sed 's/1e38/20/' "$TMP/hot/hot.gltf" >"$TMP/hot/fine.gltf"
expect_exit 2 "reference with a 1e38 cd light exits 2" $GIKIOSK reference --scene hot --scenes-dir "$TMP/hot" --size 8x8 --spp 1 --out "$TMP/hot.exr"
stderr_has "light 0 \('blinding'\): emission 1e\+38 beyond" "the light is named"
check "no reference is written" [ ! -e "$TMP/hot.exr" ]
expect_exit 0 "the same scene at 20 cd renders" $GIKIOSK reference --scene fine --scenes-dir "$TMP/hot" --size 8x8 --spp 1 --out "$TMP/fine.exr"
finish
