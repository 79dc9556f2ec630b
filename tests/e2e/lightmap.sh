#!/bin/sh
# The lightmap method (seed 004) as a user runs it, against the path-traced references at their
# size (160x120). Captures at frame 11 with --budget lightmap_sync=lockstep (each frame waits for
# its photon tick: a deterministic image; the kiosk's default, async, shows the last complete
# result), target 1000 ms so the scheduler keeps the default budgets:
#  - steady-state accuracy on cornell and cornell-spot, whole image against SCENE.exr and the
#    indirect term alone (the capture minus `none`'s, oiiotool) against SCENE-indirect.exr, at the
#    seed's 77 x 40 photons and at 616 x 40;
#  - the GLES 3.1 path gives the identical image;
#  - the async default: the photon work runs beside the frames and the image gains indirect light;
#    its passes are nested under `gi` in the stats; [cpu] workers = 1 runs;
#  - light-leak, a known failure measured: the atlas's floor, ceiling and side-wall charts span
#    both rooms under the 2 cm wall, so the lit room's photons reach the dark room's texels.
. tests/e2e/lib.sh
REFS=tests/references
json_field() { sed -n "s/.*\"$1\": \([^,}]*\).*/\1/p" "$2"; }
in_range() { awk -v v="$1" -v lo="$2" -v hi="$3" 'BEGIN { n = "^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$"; exit !(v ~ n && v + 0 >= lo && v + 0 <= hi) }'; }

# shot DIR SCENE METHOD [ARGS...]: the frame-11 HDR capture
shot() {
    d=$1 s=$2 m=$3
    shift 3
    mkdir -p "$d"
    "$GIKIOSK" run --platform mock --scene "$s" --method "$m" --size 160x120 --frames 12 --target-ms 1000 --hdr \
        --capture "$d" "$@" >"$d.log" 2>&1
}
# metric REF TEST FIELD
metric() { "$GIKIOSK" compare "$1" "$2" --json >"$TMP/c.json" 2>/dev/null && json_field "$3" "$TMP/c.json"; }

LOCK=lightmap_sync=lockstep
for s in cornell cornell-spot; do
    shot "$TMP/$s-none" "$s" none
    for groups in 77 616; do
        d="$TMP/$s-$groups"
        expect_exit 0 "$s: lightmap runs ($groups groups, lockstep)" shot "$d" "$s" lightmap --budget "$LOCK,lightmap_groups=$groups"
        img="$d/000011-$s-lightmap.exr"
        full=$(metric "$REFS/$s.exr" "$img" rel_rmse)
        oiiotool "$img" "$TMP/$s-none/000011-$s-none.exr" --sub -o "$TMP/$s-$groups-ind.exr"
        ind=$(metric "$REFS/$s-indirect.exr" "$TMP/$s-$groups-ind.exr" rel_rmse)
        ratio=$(metric "$REFS/$s-indirect.exr" "$TMP/$s-$groups-ind.exr" mean_ratio)
        echo "# $s, $groups x 40 photons: rel_rmse $full (whole image), indirect $ind, indirect energy $ratio"
        eval "full_${groups}_$(echo $s | tr - _)=\$full ind_${groups}_$(echo $s | tr - _)=\$ind ratio_${groups}_$(echo $s | tr - _)=\$ratio"
    done
done
# Bounds: measured (llvmpipe, lockstep: deterministic) + about 10%. Whole image: cornell 0.097 and
# 0.055, cornell-spot 0.123 and 0.095 (none: 0.326 and 0.465; vpl 0.199 and 0.224). Indirect alone:
# cornell 0.439 (energy 0.77) and 0.228 (0.995); cornell-spot 0.46 (0.87) and 0.35 (0.995). The seed's 3,080
# photons leave the walls' indirect 23% short on cornell by chance; 24,640 reach the energy.
check "cornell whole image ($full_77_cornell <= 0.107)" in_range "$full_77_cornell" 0 0.107
check "cornell whole image, 616 groups ($full_616_cornell <= 0.061)" in_range "$full_616_cornell" 0 0.061
check "cornell-spot whole image ($full_77_cornell_spot <= 0.136)" in_range "$full_77_cornell_spot" 0 0.136
check "cornell-spot whole image, 616 groups ($full_616_cornell_spot <= 0.105)" in_range "$full_616_cornell_spot" 0 0.105
check "cornell indirect ($ind_77_cornell <= 0.49)" in_range "$ind_77_cornell" 0 0.49
check "cornell indirect, 616 groups ($ind_616_cornell <= 0.25)" in_range "$ind_616_cornell" 0 0.25
check "cornell indirect energy, 616 groups ($ratio_616_cornell within 3%)" in_range "$ratio_616_cornell" 0.97 1.03
check "cornell-spot indirect ($ind_77_cornell_spot <= 0.52)" in_range "$ind_77_cornell_spot" 0 0.52

# GLES 3.1: the same image, bit for bit
shot "$TMP/g31" cornell lightmap --gles 3.1 --budget "$LOCK"
e31=$(metric "$TMP/cornell-77/000011-cornell-lightmap.exr" "$TMP/g31/000011-cornell-lightmap.exr" rmse)
check "--gles 3.1 gives the identical image (rmse $e31)" in_range "$e31" 0 0

# async (the default): 40 frames, the image gains the indirect light, passes nested under gi
d="$TMP/async"
mkdir -p "$d"
expect_exit 0 "async run (the default sync)" "$GIKIOSK" run --platform mock --scene cornell --method lightmap \
    --size 160x120 --frames 40 --target-ms 1000 --hdr --capture "$d" --stats "$d.csv"
gain=$(metric "$TMP/cornell-none/000011-cornell-none.exr" "$d/000039-cornell-lightmap.exr" mean_ratio)
# the lockstep image is 1.21x none's mean (0.951 / 0.789 of the reference): async must get there too
check "async: the image gained indirect light (mean $gain x none's)" in_range "$gain" 1.1 10
check "async: lightmap's passes nested under gi" grep -q 'gi.lightmap_compose_ms' "$d.csv"
printf '[cpu]\nworkers = 1\n' >"$TMP/one.ini"
expect_exit 0 "[cpu] workers = 1" "$GIKIOSK" run --config "$TMP/one.ini" --platform mock --scene cornell \
    --method lightmap --size 64x48 --frames 3 --budget "$LOCK"

# light-leak: measured rmse 0.966 (absolute: the ruler is black; none 0, vpl 0.063, vct 0.127)
shot "$TMP/leak" light-leak lightmap --budget "$LOCK"
leak=$(metric "$REFS/light-leak.exr" "$TMP/leak/000011-light-leak-lightmap.exr" rmse)
echo "# light-leak: rmse $leak (known: charts span the thin wall)"
check "light-leak: the known leak as measured ($leak in 0.87..1.07)" in_range "$leak" 0.87 1.07
finish
