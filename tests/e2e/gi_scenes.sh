#!/bin/sh
# Every implemented GI method adds indirect light in every scene it applies to, on the default and
# on the --gles 3.1 path, at its cheapest budget and at its default budget (vct also at its richest
# automatic budget and as the thesis variant): the captured linear
# image must carry more energy than direct light alone (method none) and stay finite. Small images
# (64x48) keep this to about a minute on llvmpipe; accuracy is measured elsewhere
# (accuracy.sh, vct_cornell.sh, the bench).
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless

json_field() { sed -n "s/.*\"$1\": \(\[[^]]*\]\|[^,}]*\).*/\1/p" "$2"; }

# The methods column of `gikiosk scenes` lists what each scene needs.
"$GIKIOSK" scenes >"$TMP/scenes.txt"
check "gikiosk scenes lists scenes" [ "$(wc -l <"$TMP/scenes.txt")" -gt 5 ]

# render SCENE METHOD BUDGET [options]: capture of frame 2 (the first frame builds static data) in $TMP/out.exr
# (sh has no local variables: the r_ prefix keeps the caller's loop variables intact)
render() {
    r_scene=$1 r_method=$2 r_budget=$3
    shift 3
    rm -rf "$TMP/cap"
    "$GIKIOSK" run --platform mock --scene "$r_scene" --method "$r_method" --size 64x48 --frames 2 --hdr \
        --capture "$TMP/cap" ${r_budget:+--budget "$r_budget"} "$@" >"$TMP/run.log" 2>&1 &&
        grep -q "method $r_method" "$TMP/run.log" && mv "$TMP/cap/000001-$r_scene-$r_method.exr" "$TMP/out.exr"
}

CHEAP_vct="vct_res=32,vct_cones=4,vct_step=2,vct_trace_scale=0.25,vct_mips=iso"
CHEAP_vpl="vpl_n=256,vpl_m=2,vpl_val_map=64,vpl_block=4,vpl_res=0.25,vpl_vis=vsm"
# vct's richest budget the scheduler may pick, and the thesis variant; vpl's rich end is swept by
# tests/e2e/gi_bounce.sh and the bench.
RICH_vct="vct_res=128,vct_cones=9,vct_step=0.5,vct_trace_scale=1,vct_mips=aniso"
EXTRA_vct="rich|$RICH_vct| thesis|vct_variant=thesis|"
for method in vct vpl; do
    scenes=$(awk -v m="$method" 'NR > 1 && ("," $5 ",") ~ ("," m ",") { print $1 }' "$TMP/scenes.txt")
    for scene in $scenes; do
        check "$scene none renders" render "$scene" none "shadow=hard"
        mv "$TMP/out.exr" "$TMP/none.exr" 2>/dev/null
        eval cheap=\$CHEAP_$method
        eval extra=\$EXTRA_$method
        for variant in "cheap|$cheap|" "default||" "gles31||--gles 3.1" $extra; do
            name=${variant%%|*}
            rest=${variant#*|}
            budget=${rest%%|*}
            opts=${rest#*|}
            budget="shadow=hard${budget:+,$budget}"
            # shellcheck disable=SC2086
            if render "$scene" "$method" "$budget" $opts; then
                "$GIKIOSK" compare "$TMP/none.exr" "$TMP/out.exr" --json >"$TMP/cmp.json"
                ratio=$(json_field mean_ratio "$TMP/cmp.json")
                bad=$(json_field nonfinite "$TMP/cmp.json")
                if [ "$scene" = light-leak ]; then
                    # The camera is in the unlit room: a correct method adds nothing there, so here
                    # the check is only that the image stays finite (the leak itself is measured by
                    # tests/gpu/test_vct_leak.c and in the bench's test_mean column).
                    check "$method on light-leak ($name) renders finite values" [ "$bad" = 0 ]
                    continue
                fi
                # 1.005: the smallest gain measured is several percent (a lit room returns light
                # to itself); llvmpipe reproduces none to the bit, so any gain is the method's.
                check "$method on $scene ($name) adds light: energy x$ratio, $bad non-finite" \
                    awk -v r="$ratio" -v n="$bad" 'BEGIN { exit !(r > 1.005 && n == 0) }'
            else
                not_ok "$method on $scene ($name) renders"
                sed 's/^/#   /' "$TMP/run.log" | tail -3
            fi
        done
    done
done
finish
