#!/bin/sh
# The one-bounce GI methods against a one-bounce ruler, through the program as a user runs it
# (`gikiosk run --hdr --capture`, then `gikiosk compare`). vct and vpl compute ONE diffuse bounce
# (light -> surface -> surface -> eye); the full references have every bounce, so their error
# against them mixes the method's own error with the missing higher bounces. SCENE-1bounce.exr
# (`gikiosk reference --bounces 2`: direct light + exactly one bounce, tools/references.sh) is the
# fair ruler. Each method is swept over its quality knob against both references:
#   vct on cornell at vct_res 32, 64, 128 (vct_cones=6, vct_step=1, vct_trace_scale=0.5,
#       vct_mips=aniso, shadow=pcss)
#   vpl on cornell-spot at vpl_m 2, 8, 32 (vpl_n=512, vpl_res=0.5, vpl_block=2, vpl_vis=cssm,
#       shadow=pcss)
# Measured on llvmpipe (Mesa 22.3), rel. RMSE full / one-bounce, mean_ratio full / one-bounce:
#   vct 32:  0.162 / 0.126, 0.927 / 1.042      vpl 2:  0.252 / 0.116, 0.857 / 0.987
#   vct 64:  0.187 / 0.161, 0.919 / 1.033      vpl 8:  0.253 / 0.114, 0.857 / 0.987
#   vct 128: 0.217 / 0.211, 0.920 / 1.034      vpl 32: 0.253 / 0.114, 0.858 / 0.988
# Reference noise floors (tests/references/noise.csv): cornell 0.019, cornell-1bounce 0.014,
# cornell-spot 0.058, cornell-spot-1bounce 0.052 rel. RMSE.
# Indirect part (method - none) over the reference's indirect (one-bounce: 1bounce - direct):
#   vct 1.33 / 1.27 / 1.27 of the one-bounce indirect (0.68 / 0.65 / 0.65 of the full one)
#   vpl 0.93 / 0.93 / 0.94 of the one-bounce indirect (0.50 / 0.50 / 0.50 of the full one)
# NOT asserted, because it does not hold: vct's error does not fall with resolution even against
# the one-bounce ruler (0.126 -> 0.161 -> 0.211). So the missing bounces do not explain it. The
# error of 7x7-blurred images rises the same way (0.116 -> 0.153 -> 0.201) while mean_ratio stays
# flat, so it is a low-frequency redistribution of the bounce light (brighter wall edges and
# ceiling corners at 128^3), not noise and not an energy gain: most likely the cone apex offset and
# step are in voxels (shaders_gles/vct/trace.comp), so finer grids start the cones closer to the
# surface and pick up the adjacent walls' radiance.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless

json_field() { sed -n "s/.*\"$1\": \(\[[^]]*\]\|[^,}]*\).*/\1/p" "$2"; }
lt() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && b != "" && a + 0 < b + 0) }'; }
between() { lt "$1" "$2" && lt "$2" "$3"; }  # between LO X HI: LO < X < HI
REFS=tests/references

# render NAME SCENE METHOD BUDGETS: capture the 2nd frame as $TMP/NAME.exr
render() {
    rm -rf "$TMP/cap"
    "$GIKIOSK" run --platform mock --scene "$2" --method "$3" --size 160x120 --frames 2 --hdr \
        --capture "$TMP/cap" --budget "$4" >"$TMP/$1.log" 2>&1 &&
        mv "$TMP/cap/000001-$2-$3.exr" "$TMP/$1.exr"
}
# compare NAME REF: rel_rmse and mean_ratio of $TMP/NAME.exr against REF into $err, $ratio
compare() {
    "$GIKIOSK" compare "$2" "$TMP/$1.exr" --json >"$TMP/cmp.json" 2>/dev/null
    err=$(json_field rel_rmse "$TMP/cmp.json")
    ratio=$(json_field mean_ratio "$TMP/cmp.json")
}
# indirect_ratio NAME NONE REF_INDIRECT: mean_ratio of (NAME - NONE) against REF_INDIRECT
indirect_ratio() {
    oiiotool "$TMP/$1.exr" "$TMP/$2.exr" --sub -o "$TMP/$1-ind.exr" 2>/dev/null || { echo ""; return; }
    "$GIKIOSK" compare "$3" "$TMP/$1-ind.exr" --json 2>/dev/null | sed -n 's/.*"mean_ratio": \([^,}]*\).*/\1/p'
}

# sweep SCENE METHOD KNOB "V1 V2 V3" FIXED_BUDGETS
sweep() {
    scene=$1 method=$2 knob=$3 values=$4 fixed=$5
    full=$REFS/$scene.exr one=$REFS/$scene-1bounce.exr
    check "$scene $method: one-bounce reference $one exists" [ -f "$one" ]
    [ -f "$one" ] || return
    check "$scene none renders" render "$scene-none" "$scene" none "$fixed"
    oiiotool "$one" "$REFS/$scene-direct.exr" --sub -o "$TMP/$scene-1ind.exr" 2>/dev/null
    first_err=
    for v in $values; do
        name=$scene-$method-$v
        check "$scene $method $knob=$v renders" render "$name" "$scene" "$method" "$fixed,$knob=$v"
        compare "$name" "$full"; err_full=$err ratio_full=$ratio
        compare "$name" "$one"; err_one=$err ratio_one=$ratio
        ind_one=$(indirect_ratio "$name" "$scene-none" "$TMP/$scene-1ind.exr")
        ind_full=$(indirect_ratio "$name" "$scene-none" "$REFS/$scene-indirect.exr")
        echo "# $scene $method $knob=$v: rel_rmse full $err_full, one-bounce $err_one;" \
            "mean_ratio full $ratio_full, one-bounce $ratio_one; indirect energy vs one-bounce $ind_one, vs full $ind_full"
        # The missing higher bounces are a bias against the full reference that the one-bounce
        # one does not have: the error against it is lower (measured margins 0.006-0.14).
        check "$method $knob=$v: error vs one-bounce ($err_one) < vs full ($err_full)" lt "$err_one" "$err_full"
        # Energy: against the full reference the one-bounce methods lack 8-14% (mean_ratio
        # 0.86-0.93); against the one-bounce ruler they are within 5% (measured 0.987-1.042). Bound
        # 0.95-1.06 keeps about 1.5x the measured deviation and still excludes every full-reference
        # ratio; the ruler's mean itself is exact to ~1e-4 (noise floor / sqrt(pixels)).
        check "$method $knob=$v: mean_ratio vs one-bounce within (0.95, 1.06): $ratio_one" between 0.95 "$ratio_one" 1.06
        if [ "$method" = vpl ] && [ -n "$ind_one" ]; then
            # vpl's bounce (vpl - none) carries 0.93-0.94 of the one-bounce indirect energy (0.50 of
            # the full one's): the remaining 6-7% is its clamped, clustered VPL gather.
            check "vpl $knob=$v: indirect energy is one bounce's (0.85 < $ind_one < 1.05)" between 0.85 "$ind_one" 1.05
        fi
        [ -n "$first_err" ] || first_err=$err_one
        last_err=$err_one
    done
}

sweep cornell vct vct_res "32 64 128" "vct_cones=6,vct_step=1,vct_trace_scale=0.5,vct_mips=aniso,shadow=pcss"
vct_first=$first_err vct_last=$last_err
sweep cornell-spot vpl vpl_m "2 8 32" "shadow=pcss,vpl_n=512,vpl_res=0.5,vpl_block=2,vpl_vis=cssm"

# vpl: more VAL clusters per block (vpl_m 2 -> 32) must not make it worse against the one-bounce
# ruler. Measured 0.1156 -> 0.1143 (flat: the gather is dominated by vpl_n and the reference's own
# floor 0.052); tolerance 0.01 = about 1/5 of that floor, far below what a broken cluster
# assignment costs (the none image is at 0.376).
check "vpl error vs one-bounce does not rise with vpl_m ($first_err at 2 -> $last_err at 32)" \
    lt "$last_err" "$(awk -v e="$first_err" 'BEGIN { print e + 0.01 }')"
# vct: reported, not asserted (see the header): it rises with vct_res even against the ruler.
echo "# vct error vs one-bounce over vct_res 32 -> 128: $vct_first -> $vct_last (not asserted: rises)"
finish
