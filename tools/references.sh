#!/bin/sh
# Renders the path-traced references into tests/references/ (run by `make references`):
#   SCENE.exr, SCENE-direct.exr, SCENE-indirect.exr and SCENE-caustics.exr (the last only where the
#   scene has caustic paths, i.e. its caustics render is not black), and for the scenes the one-bounce
#   GI methods are measured on (cornell, cornell-spot) SCENE-1bounce.exr = `--bounces 2`, all path
#   types: direct light + exactly one diffuse bounce, the ruler for vct and vpl, which compute one
#   bounce (tests/e2e/gi_bounce.sh). Fixed size and seed; each one's noise floor is recorded in
#   tests/references/noise.csv (file,spp,seed,rel_rmse_floor).
# The floor is measured by the renderer itself from two independent halves of the samples (see
# app/ref/render.h) and is also stored in each EXR (gikiosk:noise_floor).
#
# usage: tools/references.sh BIN [SCENE...]      (default: every scene of the list below)
#        tools/references.sh --bench BIN          (cornell, 1 vs 2 threads: samples/s, rays/s)
# env:   SCENES_DIR (default config/scenes; built into a temp dir if it has no scenes),
#        OUT_DIR (default tests/references), SIZE (default 160x120), SPP_SCALE (default 1),
#        VARIANTS (default "all direct indirect caustics 1bounce": which images to render)
set -eu

bench=0
if [ "${1:-}" = "--bench" ]; then bench=1; shift; fi
BIN=${1:?usage: tools/references.sh [--bench] BIN [SCENE...]}
shift
SCENES_DIR=${SCENES_DIR:-config/scenes}
OUT_DIR=${OUT_DIR:-tests/references}
SIZE=${SIZE:-160x120}
SPP_SCALE=${SPP_SCALE:-1}
VARIANTS=${VARIANTS:-all direct indirect caustics 1bounce}
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
        caustic-ring) echo 2048 ;;   # caustics come from light tracing: rel. noise is high where the ring focuses
        furnace) echo 128 ;;
        atrium) echo 512 ;;
        *) echo 128 ;;
    esac
}

scenes=${*:-"cornell cornell-spot shadow-planes light-leak caustic-ring furnace atrium"}
mkdir -p "$OUT_DIR"
csv=$OUT_DIR/noise.csv
[ -f "$csv" ] || echo "file,spp,seed,rel_rmse_floor" >"$csv"

floor_of() { iinfo -v "$1" 2>/dev/null | sed -n 's/.*gikiosk:noise_floor: "\(.*\)"/\1/p'; }
max_of() { oiiotool "$1" --printstats 2>/dev/null | sed -n 's/.*Stats Max: *\([^ ]*\) *\([^ ]*\) *\([^ ]*\).*/\1 \2 \3/p'; }

for scene in $scenes; do
    if [ ! -f "$SCENES_DIR/$scene.gltf" ] && [ ! -f "$SCENES_DIR/$scene.glb" ]; then
        echo "references: no scene '$scene' in $SCENES_DIR, skipped" >&2
        continue
    fi
    spp=$(( $(spp_for "$scene") * SPP_SCALE ))
    for variant in $VARIANTS; do
        paths=$variant bounces=unlimited
        if [ "$variant" = 1bounce ]; then
            case $scene in cornell | cornell-spot) ;; *) continue ;; esac
            paths=all bounces=2   # D vertices: the first surface seen + one bounce
        fi
        if [ "$variant" = all ]; then file=$scene.exr; else file=$scene-$variant.exr; fi
        out=$OUT_DIR/$file
        start=$(date +%s)
        "$BIN" reference --scene "$scene" --scenes-dir "$SCENES_DIR" --size "$SIZE" --spp "$spp" \
            --paths "$paths" --bounces "$bounces" --seed "$SEED" --out "$out"
        if [ "$paths" = caustics ] && [ "$(max_of "$out")" = "0.000000 0.000000 0.000000" ]; then
            rm -f "$out"   # no caustic paths in this scene
            echo "references: $scene has no caustics"
            continue
        fi
        floor=$(floor_of "$out")
        [ -n "$floor" ] || floor=nan   # black image: no relative error defined
        grep -v "^$file," "$csv" >"$csv.tmp" || true
        echo "$file,$spp,$SEED,$floor" >>"$csv.tmp"
        { head -n 1 "$csv.tmp"; tail -n +2 "$csv.tmp" | LC_ALL=C sort; } >"$csv"
        rm -f "$csv.tmp"
        echo "references: $file spp $spp floor $floor ($(( $(date +%s) - start )) s)"
    done
done
