#!/bin/sh
# vct through the real program: the Cornell box at the reference's size, compared with the path
# tracer (tests/references/cornell.exr, all paths, 1024 spp, noise floor rel. RMSE 0.017). vct is one
# diffuse bounce (thesis: LDDE), the reference has every bounce, so vct stays darker than the
# reference; it must still be clearly closer to it than direct light alone.
. tests/e2e/lib.sh

json_field() { sed -n "s/.*\"$1\": \(\[[^]]*\]\|[^,}]*\).*/\1/p" "$2"; }
# lt A B: A < B (floats)
lt() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && b != "" && a + 0 < b + 0) }'; }

REF=tests/references/cornell.exr
for m in none vct; do
    "$GIKIOSK" run --platform mock --scene cornell --method "$m" --size 160x120 --hdr --capture "$TMP/$m" \
        --frames 2 --budget vct_res=64,vct_cones=6,vct_step=1,vct_trace_scale=0.5,vct_mips=aniso \
        >"$TMP/$m.log" 2>&1
    check "run --method $m exits 0" [ $? -eq 0 ]
    check "run --method $m used $m" grep -q "method $m" "$TMP/$m.log"
    "$GIKIOSK" compare "$REF" "$TMP/$m/000001-cornell-$m.exr" --json >"$TMP/$m.json"
    check "compare $m exits 0" [ $? -eq 0 ]
done
none_err=$(json_field rel_rmse "$TMP/none.json")
vct_err=$(json_field rel_rmse "$TMP/vct.json")
vct_ratio=$(json_field mean_ratio "$TMP/vct.json")
none_ratio=$(json_field mean_ratio "$TMP/none.json")
echo "# cornell 160x120: rel_rmse none $none_err, vct $vct_err; mean_ratio none $none_ratio, vct $vct_ratio"
# Measured (llvmpipe, 64^3, 6 cones, step 1, trace scale 0.5): none 0.326 / 0.789, vct 0.198 / 0.878
# (the full reference has every bounce; against the one-bounce one vct is at 0.074, gi_bounce.sh).
# Before issue 11, with isotropic level-1 views: 0.153 / 0.916 (0.080 against one bounce); the
# directional views the default has since (vct.c, why: cornell-spot) lose light where a cone
# crosses a wall obliquely, which the full reference's every-bounce energy makes look larger here.
check "vct is closer to the reference than direct light alone" lt "$vct_err" "$none_err"
# bound: 1.25x the measured error (the reference's own noise floor is 0.017)
check "vct rel_rmse below 0.25" lt "$vct_err" 0.25
# one bounce misses energy but must add most of what direct light lacks: ratio in (0.85, 1.02)
check "vct mean_ratio above 0.85" lt 0.85 "$vct_ratio"
check "vct mean_ratio below 1.02 (no energy gain beyond the reference)" lt "$vct_ratio" 1.02

# The second bounce (vct_bounces=2, vct/bounce.comp): the first gather injected back into the
# voxels, so the pixels gather direct + one bounce from them (two bounces in all). Issue 11's target
# against the full reference: rel_rmse <= 0.12 (one bounce: 0.198 here, 0.153 with isotropic views).
"$GIKIOSK" run --platform mock --scene cornell --method vct --size 160x120 --hdr --capture "$TMP/vct2" \
    --frames 2 --budget vct_res=64,vct_cones=6,vct_step=1,vct_trace_scale=0.5,vct_mips=aniso,vct_bounces=2 \
    >"$TMP/vct2.log" 2>&1
check "run vct_bounces=2 exits 0" [ $? -eq 0 ]
check "run vct_bounces=2 used the knob" grep -q "vct_bounces=2" "$TMP/vct2.log"
"$GIKIOSK" compare "$REF" "$TMP/vct2/000001-cornell-vct.exr" --json >"$TMP/vct2.json"
check "compare vct_bounces=2 exits 0" [ $? -eq 0 ]
b2_err=$(json_field rel_rmse "$TMP/vct2.json")
b2_ratio=$(json_field mean_ratio "$TMP/vct2.json")
echo "# cornell 160x120, vct_bounces=2: rel_rmse $b2_err, mean_ratio $b2_ratio (one bounce: $vct_err, $vct_ratio)"
# Measured (llvmpipe, same budgets): one bounce 0.198 / 0.878, two 0.082 / 0.986 (the 1.4% still
# missing is the third and later bounces). Bounds: the issue's 0.12 (1.46x the measurement), the
# second bounce must buy at least a third of the one-bounce error, and adds no energy beyond the
# reference (a third bounce would only add more).
check "vct_bounces=2 rel_rmse <= 0.12 ($b2_err)" lt "$b2_err" 0.12
check "vct_bounces=2 cuts the one-bounce error by a third ($b2_err < 2/3 x $vct_err)" \
    lt "$b2_err" "$(awk -v e="$vct_err" 'BEGIN { print e * 2 / 3 }')"
check "vct_bounces=2 brighter than one bounce ($b2_ratio > $vct_ratio)" lt "$vct_ratio" "$b2_ratio"
check "vct_bounces=2 mean_ratio below 1.0 (no energy beyond every bounce)" lt "$b2_ratio" 1.0
finish
