#!/bin/sh
# Renders the path-traced references into tests/references/ (run by `make references`):
#   SCENE.exr, SCENE-direct.exr, SCENE-indirect.exr and SCENE-caustics.exr (the last only where the
#   scene has caustic paths, i.e. its caustics render is not black), and for the scenes the one-bounce
#   GI methods are measured on (cornell, cornell-spot) SCENE-1bounce.exr = `--bounces 2`, all path
#   types: direct light + exactly one diffuse bounce, the ruler for vct and vpl, which compute one
#   bounce (tests/e2e/gi_bounce.sh), and where the scene has caustics SCENE-caustics1.exr =
#   `--paths caustics --caustic-specular 1`: the caustics of one mirror/glass bounce, L S D E, the
#   ruler of ispm with the seed's single bounce (ispm_bounces=1). Fixed size and seed; each one's noise floor is recorded in
#   tests/references/noise.csv (file,spp,seed,rel_rmse_floor).
# The floor is measured by the renderer itself from two independent halves of the samples (see
# app/ref/render.h) and is also stored in each EXR (gikiosk:noise_floor).
# Each SCENE-caustics.exr gets its caustic mask beside it, SCENE-caustics-mask.png (pixels above 1/4
# of the caustic's peak luminance, `gikiosk reference --caustic-mask`), and its floor inside and
# outside that mask, with the render time, in tests/references/noise-regions.csv
# (file,spp,seed,mask,mask_pixels,floor_in_mask,floor_outside_mask,render_seconds).
# Caustic photons are aimed at the mirrors (--caustic-emit guided, the default; app/ref/caustic_emit.h).
# Scenes with a participating medium (extras.gikiosk.medium) get, instead of the path-class variants,
# the seed 001 ch. 8 image terms (`--terms`, app/ref/trace.h): SCENE-airlight.exr, SCENE-vcaustics.exr
# (with its mask SCENE-vcaustics-mask.png and in/out-of-mask floors), SCENE-surfaces.exr and
# SCENE-multiple.exr, beside SCENE.exr (all terms), and SCENE-scaustics.exr (with its mask): the
# surface caustics inside (C) of the paths volcaustics follows, `--terms surfaces --paths caustics
# --caustic-specular 1` (L S D E, attenuated; glass-fog: 2, L S S D E, two refractions), the ruler of
# volcaustics' surface caustics.
#
# usage: tools/references.sh BIN [SCENE...]      (default: every scene of the list below)
#        tools/references.sh --bench BIN          (cornell, 1 vs 2 threads: samples/s, rays/s)
# env:   SCENES_DIR (default config/scenes; built into a temp dir if it has no scenes),
#        OUT_DIR (default tests/references), SIZE (default 160x120), SPP_SCALE (default 1),
#        VARIANTS (default "all direct indirect caustics caustics1 1bounce": which images to render),
#        TERMS (default "airlight vcaustics surfaces multiple scaustics": the images of scenes with a medium)
set -eu

bench=0
if [ "${1:-}" = "--bench" ]; then bench=1; shift; fi
BIN=${1:?usage: tools/references.sh [--bench] BIN [SCENE...]}
shift
SCENES_DIR=${SCENES_DIR:-config/scenes}
OUT_DIR=${OUT_DIR:-tests/references}
SIZE=${SIZE:-160x120}
SPP_SCALE=${SPP_SCALE:-1}
VARIANTS=${VARIANTS:-all direct indirect caustics caustics1 1bounce}
TERMS=${TERMS:-airlight vcaustics surfaces multiple scaustics}
SEED=1

if [ ! -f "$SCENES_DIR/cornell.gltf" ] && [ ! -f "$SCENES_DIR/cornell.glb" ]; then
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/gikiosk-scenes.XXXXXX")
    trap 'rm -rf "$tmp"' EXIT
    "$BIN" build-scenes "$tmp" >/dev/null
    SCENES_DIR=$tmp
fi

if [ "$bench" -eq 1 ]; then
    for t in 1 2; do
        "$BIN" reference --scene cornell --scenes-dir "$SCENES_DIR" --size 160x120 --spp 32 --threads $t \
            --out "${TMPDIR:-/tmp}/gikiosk-bench-$$.exr" --bench
    done
    rm -f "${TMPDIR:-/tmp}/gikiosk-bench-$$.exr"
    exit 0
fi

# Samples per pixel per scene, chosen so the whole set renders in about 15 minutes on 2 cores
# (measured: cornell ~50k samples/s/core; caustic-ring and furnace are 3-5x slower per sample).
spp_for() {
    case $1 in
        cornell) echo 1024 ;;
        cornell-spot) echo 2048 ;;
        shadow-planes) echo 512 ;;
        light-leak) echo 32 ;;   # the right room is black by design: the image is exactly 0
        caustic-ring) echo 2048 ;;   # caustics: guided light tracing, floor ~0.012 inside the caustic mask
        furnace) echo 128 ;;
        caustic-ring-fog) echo 1024 ;;   # floors at 1024 spp: all 0.09, airlight 0.08, vcaustics 0.05, surfaces 0.05, multiple 0.14
        atrium) echo 512 ;;
        env-studio) echo 1024 ;;  # environment light only (no light node): floor measured below, noise.csv
        glass-fog) echo 1024 ;;   # 64 spp renders the vcaustics term in 3.4 s (floor 0.18): 1024 spp ~1 min a term
        glass) echo 2048 ;;  # caustics: floor 0.0045 inside the caustic mask at 128 spp (15 s); 2048 for the indirect (0.20 at 512)
        *) echo 128 ;;
    esac
}

scenes=${*:-"cornell cornell-spot shadow-planes light-leak caustic-ring furnace atrium glass caustic-ring-fog env-studio glass-fog"}
mkdir -p "$OUT_DIR"
csv=$OUT_DIR/noise.csv
[ -f "$csv" ] || echo "file,spp,seed,rel_rmse_floor" >"$csv"
regions=$OUT_DIR/noise-regions.csv
[ -f "$regions" ] || echo "file,spp,seed,mask,mask_pixels,floor_in_mask,floor_outside_mask,render_seconds" >"$regions"

attr_of() { iinfo -v "$1" 2>/dev/null | sed -n "s/.*gikiosk:$2: \"\(.*\)\"/\1/p"; }
# Replaces FILE's row of a CSV (first column) with ROW, keeping the header first and rows sorted.
put_row() {
    grep -v "^$2," "$1" >"$1.tmp" || true
    echo "$3" >>"$1.tmp"
    { head -n 1 "$1.tmp"; tail -n +2 "$1.tmp" | LC_ALL=C sort; } >"$1"
    rm -f "$1.tmp"
}

floor_of() { iinfo -v "$1" 2>/dev/null | sed -n 's/.*gikiosk:noise_floor: "\(.*\)"/\1/p'; }
max_of() { oiiotool "$1" --printstats 2>/dev/null | sed -n 's/.*Stats Max: *\([^ ]*\) *\([^ ]*\) *\([^ ]*\).*/\1 \2 \3/p'; }

for scene in $scenes; do
    if [ ! -f "$SCENES_DIR/$scene.gltf" ] && [ ! -f "$SCENES_DIR/$scene.glb" ]; then
        echo "references: no scene '$scene' in $SCENES_DIR, skipped" >&2
        continue
    fi
    spp=$(( $(spp_for "$scene") * SPP_SCALE ))
    medium=0
    if grep -q '"medium"' "$SCENES_DIR/$scene.gltf" 2>/dev/null; then medium=1; fi
    variants=$VARIANTS
    if [ "$medium" -eq 1 ]; then variants="$VARIANTS $TERMS"; fi
    for variant in $variants; do
        paths=$variant bounces=unlimited specular=unlimited terms=all
        case $variant in
            airlight | vcaustics | surfaces | multiple) paths=all terms=$variant ;;
            # the specular vertices of the real-time method's paths: one mirror bounce, or glass's two refractions
            scaustics) paths=caustics terms=surfaces specular=1; [ "$scene" != glass-fog ] || specular=2 ;;
            direct | indirect | caustics | caustics1 | 1bounce) [ "$medium" -eq 0 ] || continue ;;
        esac
        if [ "$variant" = caustics1 ]; then
            paths=caustics specular=1   # one specular vertex: the seed's single bounce
        fi
        if [ "$variant" = 1bounce ]; then
            case $scene in cornell | cornell-spot) ;; *) continue ;; esac
            paths=all bounces=2   # D vertices: the first surface seen + one bounce
        fi
        if [ "$variant" = all ]; then file=$scene.exr; else file=$scene-$variant.exr; fi
        out=$OUT_DIR/$file
        start=$(date +%s)
        mask=
        if [ "$paths" = caustics ] || [ "$terms" = vcaustics ]; then mask=$scene-$variant-mask.png; fi
        "$BIN" reference --scene "$scene" --scenes-dir "$SCENES_DIR" --size "$SIZE" --spp "$spp" \
            --paths "$paths" --bounces "$bounces" --caustic-specular "$specular" --terms "$terms" --seed "$SEED" \
            --out "$out" \
            ${mask:+--caustic-mask "$OUT_DIR/$mask"}
        if [ "$paths" = caustics ] && [ "$(max_of "$out")" = "0.000000 0.000000 0.000000" ]; then
            rm -f "$out" "$OUT_DIR/$mask"   # no caustic paths in this scene
            echo "references: $scene has no caustics"
            continue
        fi
        floor=$(floor_of "$out")
        [ -n "$floor" ] || floor=nan   # black image: no relative error defined
        put_row "$csv" "$file" "$file,$spp,$SEED,$floor"
        if [ -n "$mask" ]; then
            put_row "$regions" "$file" "$file,$spp,$SEED,$mask,$(attr_of "$out" caustic_mask_pixels),$(attr_of "$out" \
                noise_floor_in_mask),$(attr_of "$out" noise_floor_outside_mask),$(attr_of "$out" render_seconds)"
        fi
        echo "references: $file spp $spp floor $floor ($(( $(date +%s) - start )) s)"
    done
done
