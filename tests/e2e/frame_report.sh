#!/bin/sh
# The one frame report as a user sees it in `run --stats` (issue: GI frames were counted 1.7x):
# on cornell with vct and with vpl, every row's frame_ms equals the sum of the top-level pass
# columns (names without a dot) within 1%; the GI method's passes are nested columns `gi.NAME_ms`
# that add up to no more than `gi_ms` (they are inside it, not beside it), so the sum of every
# column is larger than frame_ms by exactly the nested ones -- a pass counted twice would break
# one of the two. Got another way: the frames' total cannot exceed the wall time of the whole run.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless

# Columns: checks every data row of CSV $1; prints the failures, exits non-zero on any.
rows_add_up() {
    awk -F, '
        NR == 1 { for (i = 1; i <= NF; i++) { name[i] = $i; col[$i] = i; if ($i == "frame_ms") fcol = i }
                  for (i = 1; i <= NF; i++) if (name[i] ~ /_ms$/ && i != fcol) {
                      if (name[i] ~ /\./) { nested[i] = 1; p = name[i]; sub(/\.[^.]*$/, "", p); parent[i] = p "_ms" }
                      else top[i] = 1 } next }
        {
            t = 0; g = 0; delete inner
            for (i in top) t += $i
            for (i in nested) { inner[parent[i]] += $i; if (name[i] ~ /^gi\./) g += $i }
            if ($fcol <= 0) { print "# row " NR ": frame_ms " $fcol; bad++ }
            d = $fcol - t; if (d < 0) d = -d
            if (d > 0.01 * $fcol + 0.002) { print "# row " NR ": frame_ms " $fcol " != top-level sum " t; bad++ }
            for (p in inner) if (inner[p] > $col[p] * 1.001 + 0.002) {
                print "# row " NR ": nested passes of " p " sum to " inner[p] " > " $col[p]; bad++ }
            if (g <= 0) { print "# row " NR ": no nested GI pass"; bad++ }
            rows++
        }
        END { if (rows < 1) { print "# no rows"; bad++ } exit bad > 0 }' "$1"
}

for m in vct vpl; do
    csv=$TMP/$m.csv
    t0=$(date +%s.%N)
    check "run --stats cornell $m" "$GIKIOSK" run --platform mock --size 96x72 --scene cornell --method $m \
        --frames 5 --target-ms 1000 --stats "$csv"
    t1=$(date +%s.%N)
    head -1 "$csv" | sed 's/^/# /'
    check "$m: nested GI columns are named gi.NAME_ms" grep -Eq ",gi_ms,(gi\.[a-z_]+_ms,)*gi\.${m}_[a-z]+_ms" "$csv"
    check "$m: frame_ms is the sum of the top-level passes in every row, nested passes within their parent" rows_add_up "$csv"
    total=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "frame_ms") c = i; next } { s += $c } END { print s }' "$csv")
    check "$m: frames ($total ms) fit in the run's wall time" \
        awk -v s="$total" -v a="$t0" -v b="$t1" 'BEGIN { exit !(s > 0 && s <= (b - a) * 1000) }'
done
# vct's soft-shadow cone runs inside the direct pass (README "vct: the soft-shadow cone"): its column
# is nested under direct, and the direct pass holds it.
csv=$TMP/vct-cone.csv
check "run --stats cornell vct vct_shadow=cone" "$GIKIOSK" run --platform mock --size 96x72 --scene cornell --method vct \
    --frames 5 --target-ms 1000 --budget vct_shadow=cone --stats "$csv"
check "vct_shadow=cone: the cone's pass is the nested column direct.vct_shadow_cone_ms" \
    grep -Eq ",direct_ms,(direct\.[a-z_]+_ms,)*direct\.vct_shadow_cone_ms" "$csv"
check "vct_shadow=cone: frame_ms is the sum of the top-level passes, the cone within direct" rows_add_up "$csv"
finish
