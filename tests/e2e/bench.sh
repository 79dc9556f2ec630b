#!/bin/sh
# `gikiosk bench` as a user runs it: a two-point sweep on shadow-planes writes bench.csv with the
# contract's columns and the speed-against-accuracy chart; bad sweeps and missing options exit 2.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless

expect_exit 0 "bench: two shadow methods on shadow-planes" "$GIKIOSK" bench --scenes shadow-planes --methods none \
    --sweep "shadow=hard,pcss;shadow_map=256" --frames 1 --warmup 0 --out "$TMP/b"
CSV=$TMP/b/bench.csv
check "bench.csv exists" [ -f "$CSV" ]
check "bench.csv header: scene,method,knobs...,frame_ms_median,frame_ms_p95,rel_rmse,ssim" \
    sh -c "head -1 '$CSV' | grep -q '^scene,method,.*shadow_map.*,frame_ms_median,frame_ms_p95,reference,rel_rmse,ssim,psnr,mean_ratio,test_mean,caustic_rel_rmse,caustic_mean_ratio,pareto'"
check "bench.csv: one row per configuration" [ "$(wc -l <"$CSV")" -eq 3 ]
check "bench.csv: method none is measured against the direct reference" \
    sh -c "awk -F, 'NR > 1 && \$0 !~ /,shadow-planes-direct,/ { bad = 1 } END { exit bad }' '$CSV'"
# Columns by name, so the test follows the header.
col() { head -1 "$CSV" | tr ',' '\n' | grep -n "^$1\$" | cut -d: -f1; }
c_shadow=$(col shadow)
c_err=$(col rel_rmse)
c_ms=$(col frame_ms_median)
check "bench.csv: the sweep's values, in order" \
    sh -c "[ \"\$(awk -F, -v c=$c_shadow 'NR > 1 { printf \"%s \", \$c }' '$CSV')\" = 'hard pcss ' ]"
check "bench.csv: error and time measured for every row" \
    sh -c "awk -F, -v e=$c_err -v t=$c_ms 'NR > 1 && (\$e == \"\" || \$t == \"\" || \$t <= 0) { bad = 1 } END { exit bad }' '$CSV'"
# PCSS is the accurate one on the analytic scene: its error must be below hard shadows'.
check "pcss is more accurate than hard shadows on shadow-planes" \
    sh -c "awk -F, -v e=$c_err -v s=$c_shadow 'NR > 1 { err[\$s] = \$e } END { exit !(err[\"pcss\"] < err[\"hard\"]) }' '$CSV'"
check "chart: speed-accuracy-shadow-planes.png" [ -s "$TMP/b/speed-accuracy-shadow-planes.png" ]
check "chart: speed-accuracy-shadow-planes.svg" [ -s "$TMP/b/speed-accuracy-shadow-planes.svg" ]

# vct: the variant switch measured side by side, judged against the one-bounce reference (vct
# computes one diffuse bounce), with the share of each of its passes in the CSV: nested under the
# renderer's gi pass, so named gi.PASS_ms as in the stats CSV.
expect_exit 0 "bench: vct default against thesis on cornell" "$GIKIOSK" bench --scenes cornell --methods vct \
    --sweep "vct_variant=default,thesis" --frames 1 --warmup 1 --out "$TMP/v"
CSV=$TMP/v/bench.csv
check "bench.csv (vct): two rows" [ "$(wc -l <"$CSV" 2>/dev/null)" = 3 ]
check "bench.csv (vct): measured against cornell-1bounce" \
    sh -c "awk -F, 'NR > 1 && \$0 !~ /,cornell-1bounce,/ { bad = 1 } END { exit bad || NR != 3 }' '$CSV'"
for pass in gi.vct_voxelize gi.vct_inject gi.vct_mips gi.vct_trace gi.vct_compose; do
    c=$(col "${pass}_ms")
    check "bench.csv (vct): column ${pass}_ms, a time in every row" \
        sh -c "[ -n '$c' ] && awk -F, -v c='$c' 'NR > 1 && !(\$c >= 0 && \$c != \"\") { bad = 1 } END { exit bad }' '$CSV'"
done
c_err=$(col rel_rmse)
c_var=$(col vct_variant)
# measured 0.100 (default) vs 0.621 (thesis: its cone weights 1/0.607 and alpha_GI add 38% energy)
check "vct default is more accurate than the thesis variant on cornell" \
    sh -c "awk -F, -v e=$c_err -v v=$c_var 'NR > 1 { err[\$v] = \$e } END { exit !(err[\"default\"] + 0 > 0 && err[\"default\"] < err[\"thesis\"]) }' '$CSV'"

# Steady state of a static scene: voxelized and injected once, so those passes cost nothing per
# frame; with --rebuild-gi every pass runs every frame (the cost of a moving light or object).
# (a pass with nothing to do is not begun, so it is exactly 0 in steady state; a re-voxelization at
# 64^3 costs ~15 ms + ~24 ms inject against a 26-38 ms trace pass)
c_vox=$(col gi.vct_voxelize_ms)
c_inj=$(col gi.vct_inject_ms)
c_trace=$(col gi.vct_trace_ms)
check "bench.csv (vct): static cornell is not re-voxelized or re-injected in the timed frames" \
    sh -c "awk -F, -v v=$c_vox -v i=$c_inj -v t=$c_trace 'NR > 1 && !(\$v + \$i < 0.01 * \$t) { bad = 1 } END { exit bad }' '$CSV'"
expect_exit 0 "bench --rebuild-gi: vct on cornell" "$GIKIOSK" bench --scenes cornell --methods vct \
    --sweep "vct_res=32" --frames 1 --warmup 1 --rebuild-gi --out "$TMP/r"
CSV=$TMP/r/bench.csv
c_vox=$(col gi.vct_voxelize_ms)
c_inj=$(col gi.vct_inject_ms)
c_mips=$(col gi.vct_mips_ms)
check "bench.csv (--rebuild-gi): voxelize, inject and mips timed every frame" \
    sh -c "awk -F, -v v=$c_vox -v i=$c_inj -v m=$c_mips 'NR > 1 && !(\$v > 0 && \$i > 0 && \$m > 0) { bad = 1 } END { exit bad || NR != 2 }' '$CSV'"

# A value the renderer cannot run is reported as what ran: llvmpipe's 128 MiB storage-buffer limit
# holds vct's 256^3 scratch buffer, so vct_res=256 runs (and is written, and charted) as 128.
expect_exit 0 "bench: vct_res=256 on cornell" "$GIKIOSK" bench --scenes cornell --methods vct \
    --sweep "vct_res=256" --size 32x24 --frames 1 --warmup 0 --out "$TMP/clamp"
CSV=$TMP/clamp/bench.csv
c_res=$(col vct_res)
if grep -q "does not fit this GPU's storage-buffer limit, using 128" "$TMP/stderr"; then
    check "bench.csv: the clamped vct_res is written as the 128 that ran" \
        sh -c "[ \"\$(awk -F, -v c=$c_res 'NR == 2 { print \$c }' '$CSV')\" = 128 ]"
else
    check "bench.csv: vct_res=256 ran unclamped and is written as 256" \
        sh -c "[ \"\$(awk -F, -v c=$c_res 'NR == 2 { print \$c }' '$CSV')\" = 256 ]"
fi

# One chart per scene for choosing a method: every method against one ruler, the kiosk's automatic
# choice marked. The mark must be what the kiosk itself picks (its log, another code path), and it
# must not be worse than none in the bench's own measurement.
expect_exit 0 "bench --one-ruler: none, vct, vpl on cornell-spot" "$GIKIOSK" bench --scenes cornell-spot \
    --methods none,vct,vpl --one-ruler --frames 1 --warmup 1 --sweep "render_scale=1" --out "$TMP/choice"
CSV=$TMP/choice/bench.csv
c_ch=$(col chosen); c_m=$(col method); c_ref=$(col reference); c_err=$(col rel_rmse)
check "bench.csv (--one-ruler): every method against cornell-spot-1bounce" \
    sh -c "awk -F, -v r=$c_ref 'NR > 1 && \$r != \"cornell-spot-1bounce\" { bad = 1 } END { exit bad || NR != 4 }' '$CSV'"
chosen=$(awk -F, -v c="$c_ch" -v m="$c_m" 'NR > 1 && $c == 1 { print $m }' "$CSV")
check "bench.csv: exactly one row marked as the kiosk's choice" [ "$(echo "$chosen" | grep -c .)" = 1 ]
"$GIKIOSK" run --platform mock --size 640x360 --scene cornell-spot --frames 1 --target-ms 400 2>"$TMP/kiosk.log" >/dev/null
kiosk_pick=$(sed -n 's/.*scene cornell-spot: automatic choice \([a-z0-9_]*\):.*/\1/p' "$TMP/kiosk.log" | head -1)
check "the marked choice ($chosen) is the kiosk's own at 400 ms, 640x360 (${kiosk_pick:-none logged})" \
    [ -n "$kiosk_pick" ] && [ "$chosen" = "$kiosk_pick" ]
check "the marked choice is not worse than none against the same ruler" \
    sh -c "awk -F, -v c=$c_ch -v m=$c_m -v e=$c_err 'NR > 1 { err[\$m] = \$e; if (\$c == 1) pick = \$m } END { exit !(pick != \"\" && err[pick] <= err[\"none\"]) }' '$CSV'"
check "chart: the choice is drawn" grep -q "kiosk's choice at 400 ms, 640x360" "$TMP/choice/speed-accuracy-cornell-spot.gp"

# The caustic error: where the scene has a caustic mask (caustic-ring-caustics-mask.png), each row's
# error inside it, against the row's ruler (for none, whose direct reference has no caustic, the one
# ruler: SCENE-1bounce.exr, else SCENE.exr) -- the same number `gikiosk compare --mask` gives for
# the captured image (another code path: the CLI's JSON); a chart of it beside the whole-image one.
expect_exit 0 "bench: none and ispm on caustic-ring" "$GIKIOSK" bench --scenes caustic-ring --methods none,ispm \
    --sweep "render_scale=1" --frames 1 --warmup 1 --out "$TMP/caustic"
CSV=$TMP/caustic/bench.csv
c_cr=$(col caustic_rel_rmse); c_cm=$(col caustic_mean_ratio); c_ref=$(col reference); c_m=$(col method)
check "bench.csv (caustic-ring): a caustic error in every row" \
    sh -c "awk -F, -v c=$c_cr -v m=$c_cm 'NR > 1 && !(\$c > 0 && \$m > 0) { bad = 1 } END { exit bad || NR != 3 }' '$CSV'"
for row in 2 3; do
    method=$(awk -F, -v c="$c_m" -v r=$row 'NR == r { print $c }' "$CSV")
    ruler=tests/references/$(awk -F, -v c="$c_ref" -v r=$row 'NR == r { print $c }' "$CSV").exr
    case $ruler in
        *-direct.exr) ruler=tests/references/caustic-ring-1bounce.exr
                      [ -f "$ruler" ] || ruler=tests/references/caustic-ring.exr ;;
    esac
    capture=$(ls "$TMP"/caustic/captures/caustic-ring-"$method"-*.exr | head -1)
    "$GIKIOSK" compare "$ruler" "$capture" --mask tests/references/caustic-ring-caustics-mask.png \
        --json >"$TMP/caustic-$method.json"
    inside=$(sed 's/.*"inside": {\([^}]*\)}.*/\1/' "$TMP/caustic-$method.json")
    want_e=$(echo "$inside" | sed 's/^"rel_rmse": \([^,]*\),.*/\1/')
    want_m=$(echo "$inside" | sed 's/.*"mean_ratio": \([^,]*\),.*/\1/')
    check "bench.csv (caustic-ring, $method): caustic_rel_rmse and caustic_mean_ratio are compare --mask's ($want_e, $want_m)" \
        awk -F, -v r=$row -v c=$c_cr -v m=$c_cm -v we="$want_e" -v wm="$want_m" \
        'NR == r { exit !(we > 0 && ($c - we) ^ 2 < (1e-5 * we) ^ 2 && ($m - wm) ^ 2 < (1e-5 * wm) ^ 2) }' "$CSV"
done
check "bench.csv (caustic-ring): ispm's caustic is better than none's (none draws no caustic)" \
    sh -c "awk -F, -v c=$c_cr -v m=$c_m 'NR > 1 { e[\$m] = \$c } END { exit !(e[\"ispm\"] < e[\"none\"]) }' '$CSV'"
check "chart: speed-caustic-caustic-ring.png" [ -s "$TMP/caustic/speed-caustic-caustic-ring.png" ]
check "no caustic chart where there is no mask (shadow-planes)" [ ! -e "$TMP/b/speed-caustic-shadow-planes.dat" ]

expect_exit 2 "bench: unknown knob in --sweep exits 2" "$GIKIOSK" bench --scenes shadow-planes --sweep "shadows=hard" --out "$TMP/c"
stderr_has "unknown knob 'shadows'" "bench: the message names the knob"
expect_exit 2 "bench: missing --out exits 2" "$GIKIOSK" bench --scenes shadow-planes
expect_exit 2 "bench: unknown scene exits 2" "$GIKIOSK" bench --scenes no-such-scene --out "$TMP/d"
stderr_has "no-such-scene" "bench: the message names the scene"
expect_exit 2 "bench: unknown knob in --budget exits 2" "$GIKIOSK" bench --scenes shadow-planes --budget "shadows=hard" --out "$TMP/e"
stderr_has "unknown knob 'shadows'" "bench: the --budget message names the knob"
# --budget pins a knob in every configuration: each row of a shadow_map sweep has shadow=hard
expect_exit 0 "bench: --budget shadow=hard under a shadow_map sweep" "$GIKIOSK" bench --scenes shadow-planes \
    --methods none --budget shadow=hard --sweep "shadow_map=256,512" --frames 1 --warmup 0 --out "$TMP/f"
c_shadow=$(head -1 "$TMP/f/bench.csv" | tr ',' '\n' | grep -n '^shadow$' | cut -d: -f1)
check "bench: every row ran with the pinned shadow=hard" \
    awk -F, -v c="$c_shadow" 'NR > 1 { n++; if ($c != "hard") bad = 1 } END { exit bad || n != 2 }' "$TMP/f/bench.csv"
# A long --budget (a run's whole printed budget line, 281 characters) is taken whole: the field
# was 256 characters and cut it to "...,lightmap_workers=c", refused as a value nobody wrote.
long="render_scale=1,shadow=hard,shadow_map=1024,shadow_subdiv=3,gi_blend=4,env_lights=16,lightmap_groups=77,lightmap_aim=80,lightmap_iim=20,lightmap_gather=16,lightmap_texels=5,lightmap_sync=lockstep,lightmap_caustics=10000,lightmap_window=8,lightmap_workers=config,lightmap_count=float"
expect_exit 0 "bench: a ${#long}-character --budget is taken whole" "$GIKIOSK" bench --scenes shadow-planes \
    --methods none --budget "$long" --sweep "shadow_map=256" --frames 1 --warmup 0 --out "$TMP/g"
c_count=$(head -1 "$TMP/g/bench.csv" | tr ',' '\n' | grep -n '^lightmap_count$' | cut -d: -f1)
check "bench: the long --budget's last pin is in the row (lightmap_count=float)" \
    awk -F, -v c="$c_count" 'NR == 2 { ok = $c == "float" } END { exit !ok }' "$TMP/g/bench.csv"
expect_exit 2 "bench: a --budget longer than its 1,023 characters exits 2" "$GIKIOSK" bench --scenes shadow-planes \
    --budget "$long,$long,$long,$long" --out "$TMP/h"
stderr_has "too long" "bench: the message says the value is too long"
finish
