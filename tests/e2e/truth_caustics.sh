#!/bin/sh
# The live ground truth on a scene with mirrors (issue 19; README "Live error"): the truth runs the
# reference's light pass too, so on caustic-ring the kiosk's live error converges to what
# `gikiosk compare` reports for the same frame against a reference rendered at that size, as
# truth.sh checks on cornell. (tests/unit/test_truth.c checks the truth itself against the committed
# caustic-ring and glass references, inside their caustic masks.)
. tests/e2e/lib.sh

within() { awk -v a="$1" -v b="$2" -v f="$3" 'BEGIN { if (a == "" || b == "" || b + 0 == 0) exit 1; r = a / b - 1; if (r < 0) r = -r; exit !(r < f) }'; }
json_field() { sed -n "s/.*\"$1\": \([^,}]*\).*/\1/p" "$2"; }
column() { awk -F, -v n="$1" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == n) c = i; next } c { print $c }' "$2"; }
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

# The reference at the frame's size: 64 spp (noise floor 0.14: it adds in quadrature to compare's
# number as the truth's noise adds to the live error's).
t0=$(now)
"$GIKIOSK" reference --scene caustic-ring --size 160x90 --spp 64 --threads 2 --out "$TMP/ref.exr" >/dev/null 2>&1
check "reference 160x90 renders" [ $? -eq 0 ]
echo "# reference 160x90, 64 spp, 2 threads: $(secs "$t0" "$(now)") s"

# ispm (the caustic method) with its knobs pinned, so the frame does not change under the
# measurement; the truth at the frame's size (sub = 1, not the committed 160x120 reference).
printf '[truth]\nenabled = true\nworkers = 1\nsize = 160x90\n' >"$TMP/truth.ini"
PINS=render_scale=1,shadow=hard,shadow_map=512,env_lights=4,shadow_subdiv=0,ispm_photons=1024,ispm_trace=64,ispm_splat=0.25,ispm_pool=2
t0=$(now)
"$GIKIOSK" run --config "$TMP/truth.ini" --platform mock --scene caustic-ring --method ispm --size 160x90 \
    --frames 900 --budget "$PINS" --hdr --capture "$TMP/cap" --stats "$TMP/s.csv" >"$TMP/run.log" 2>&1
check "run with [truth] enabled exits 0" [ $? -eq 0 ]
run_s=$(secs "$t0" "$(now)")
echo "# kiosk run, 900 frames with the truth: $run_s s"
grep "truth:" "$TMP/run.log" | sed 's/^/# /'
check "a scene with mirrors gets a live truth" grep -q "truth: caustic-ring restarted (view 1)" "$TMP/run.log"

"$GIKIOSK" compare "$TMP/ref.exr" "$TMP/cap/000899-caustic-ring-ispm.exr" --json >"$TMP/cmp.json"
cmp_err=$(json_field rel_rmse "$TMP/cmp.json")
live_err=$(column error "$TMP/s.csv" | tail -1)
spp=$(column truth_spp "$TMP/s.csv" | tail -1)
echo "# compare rel_rmse $cmp_err; live error $live_err at truth $spp spp"
# Measured (llvmpipe, this 2-core machine shared with other builds): compare 0.549, live 0.5605 at
# 36 spp (noise ~0.18); 0.600 at 15 spp, the first within 10%, about 23% into the run (~15 s of the
# run's ~65 s); 0.699 at 5 spp (noise 0.45). Below ~15 spp the truth's noise alone pushes the live
# error past 10%: the spp check says when the machine was too busy to get there.
check "the truth reached 15 spp (it got enough of a core)" [ "${spp:-0}" -ge 15 ]
check "the live error is within 10% of compare's" within "$live_err" "$cmp_err" 0.10
# From when on it stayed within 10%: the first measurement after the last one outside (an early
# measurement at a few spp can land near by chance).
first=$(awk -F, -v e="$(head -1 "$TMP/s.csv" | tr ',' '\n' | grep -n '^error$' | cut -d: -f1)" -v c="$cmp_err" \
    'NR > 1 && $e != "" && $e != last { last = $e; r = $e / c - 1; if (r < 0) r = -r; if (r >= 0.10) f = ""; else if (f == "") f = $1 }
     END { print f }' "$TMP/s.csv")
# the wall time of that frame: its share of the run's summed frame times
share=$(awk -F, -v f="${first:-0}" 'NR > 1 { s += $5; if ($1 == f) a = s } END { print (s > 0 ? a / s : 0) }' "$TMP/s.csv")
echo "# within 10% from frame ${first:-never} of 900 on (about $(awk -v p="$share" -v t="$run_s" 'BEGIN { printf "%.1f", p * t }') s into the run)"
finish
