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
#   vct 32:  0.169 / 0.083, 0.900 / 1.012      vpl 2:  0.252 / 0.116, 0.857 / 0.987
#   vct 64:  0.177 / 0.078, 0.895 / 1.005      vpl 8:  0.253 / 0.114, 0.857 / 0.987
#   vct 128: 0.186 / 0.078, 0.889 / 1.000      vpl 32: 0.253 / 0.114, 0.858 / 0.988
# none against the one-bounce ruler: cornell 0.221, cornell-spot 0.376.
# Reference noise floors (tests/references/noise.csv): cornell 0.019, cornell-1bounce 0.014,
# cornell-spot 0.058, cornell-spot-1bounce 0.052 rel. RMSE.
# Indirect part (method - none) over the reference's indirect (one-bounce: 1bounce - direct):
#   vct 1.10 / 1.05 / 1.01 of the one-bounce indirect (0.57 / 0.54 / 0.52 of the full one)
#   vpl 0.93 / 0.93 / 0.94 of the one-bounce indirect (0.50 / 0.50 / 0.50 of the full one)
# Against the FULL reference vct's error rises with vct_res (0.162 -> 0.185): coarse grids add
# light that is not there (a surface's coarse voxels light the surface itself), which happens to
# stand in for some of the missing higher bounces. The one-bounce ruler is the fair one for a
# one-bounce method (summary C.1: "VCT computes one diffuse bounce", compare it with max diffuse
# bounces 1), so the monotonicity is asserted there. Before the footprint clamp
# (shaders_gles/vct/cone_lib.glsl) the error rose against the ruler too (0.126 -> 0.161 -> 0.211):
# the cone apex offset is in voxels, so on finer grids the wide cones' coarse samples reached the
# receiver's own surface sooner.
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
# indirect NAME NONE REF_INDIRECT: (NAME - NONE) against REF_INDIRECT into $ind_err (rel_rmse) and
# $ind_ratio (mean_ratio)
indirect() {
    ind_err= ind_ratio=
    oiiotool "$TMP/$1.exr" "$TMP/$2.exr" --sub -o "$TMP/$1-ind.exr" 2>/dev/null || return
    "$GIKIOSK" compare "$3" "$TMP/$1-ind.exr" --json >"$TMP/cmp-ind.json" 2>/dev/null
    ind_err=$(json_field rel_rmse "$TMP/cmp-ind.json")
    ind_ratio=$(json_field mean_ratio "$TMP/cmp-ind.json")
}

# sweep SCENE METHOD KNOB "V1 V2 V3" FIXED_BUDGETS
sweep() {
    scene=$1 method=$2 knob=$3 values=$4 fixed=$5
    full=$REFS/$scene.exr one=$REFS/$scene-1bounce.exr
    check "$scene $method: one-bounce reference $one exists" [ -f "$one" ]
    [ -f "$one" ] || return
    check "$scene none renders" render "$scene-none" "$scene" none "$fixed"
    oiiotool "$one" "$REFS/$scene-direct.exr" --sub -o "$TMP/$scene-1ind.exr" 2>/dev/null
    compare "$scene-none" "$one"; none_err=$err
    errs= ind_errs=
    for v in $values; do
        name=$scene-$method-$v
        check "$scene $method $knob=$v renders" render "$name" "$scene" "$method" "$fixed,$knob=$v"
        compare "$name" "$full"; err_full=$err ratio_full=$ratio
        compare "$name" "$one"; err_one=$err ratio_one=$ratio
        indirect "$name" "$scene-none" "$REFS/$scene-indirect.exr"; ind_full=$ind_ratio
        indirect "$name" "$scene-none" "$TMP/$scene-1ind.exr"; ind_one=$ind_ratio
        echo "# $scene $method $knob=$v: rel_rmse full $err_full, one-bounce $err_one;" \
            "mean_ratio full $ratio_full, one-bounce $ratio_one; indirect component vs one-bounce:" \
            "rel_rmse $ind_err, energy $ind_one (vs full $ind_full)"
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
        # The method must be well below doing nothing (none vs the one-bounce ruler: cornell 0.221,
        # cornell-spot 0.376): at most half of it.
        check "$method $knob=$v: error vs one-bounce $err_one < half of none's $none_err" \
            lt "$err_one" "$(awk -v e="$none_err" 'BEGIN { print e / 2 }')"
        errs="$errs $err_one" ind_errs="$ind_errs $ind_err"
    done
}

# not_worse "E1 E2 E3" TOL: each value at most a fraction TOL above the one before
not_worse() {
    echo "$1" | awk -v t="$2" '{ for (i = 2; i <= NF; i++) if (!($i ~ /^[0-9.]+$/ && $i + 0 <= ($(i - 1) + 0) * (1 + t))) exit 1
                                 exit !(NF >= 2) }'
}

sweep cornell vct vct_res "32 64 128" "vct_cones=6,vct_step=1,vct_trace_scale=0.5,vct_mips=aniso,shadow=pcss"
vct_errs=$errs vct_ind_errs=$ind_errs
sweep cornell-spot vpl vpl_m "2 8 32" "shadow=pcss,vpl_n=512,vpl_res=0.5,vpl_block=2,vpl_vis=cssm"
vpl_errs=$errs

# A richer budget must not make a method worse against its ruler: each step at most 3% above
# the one before. Two renders of one budget agree to the bit on llvmpipe and the ruler is the same
# image for every budget, so its noise (floor 0.014 for the image, 0.115 for its indirect part)
# shifts all errors alike; what it adds to a difference (the cross term of method error and
# noise over 19,200 pixels) is ~0.1%. The 3% is for the plateau: past 64^3 what remains is the
# cone set's angular error, which finer voxels do not reduce.
# vct, vct_res 32 -> 64 -> 128, measured: image 0.0833 -> 0.0777 -> 0.0782 (+0.6% at the plateau;
# 9 cones 0.0713 -> 0.0665 -> 0.0683, +2.7%); indirect component 0.605 -> 0.559 -> 0.564 (+1.0%;
# the ruler's indirect part is the difference of two noisy images, hence the high level). Thesis
# cone sampling (no footprint clamp): 0.126 -> 0.161 -> 0.211, +28% and +31% per step.
check "vct error vs one-bounce does not rise with vct_res:$vct_errs" not_worse "$vct_errs" 0.03
check "vct indirect-component error vs one-bounce does not rise with vct_res:$vct_ind_errs" not_worse "$vct_ind_errs" 0.03
# vpl, vpl_m 2 -> 8 -> 32, measured 0.1156 -> 0.1143 -> 0.1143 (flat: the gather is dominated by
# vpl_n and the reference's own floor 0.052).
check "vpl error vs one-bounce does not rise with vpl_m:$vpl_errs" not_worse "$vpl_errs" 0.03
finish
