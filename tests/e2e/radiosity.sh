#!/bin/sh
# Hierarchical radiosity with implicit visibility (seed 001 ch. 4, issue 18) through the program
# as a user runs it (`gikiosk run --hdr --capture` at the references' 160x120, then `gikiosk
# compare`). Every run pins radiosity_sync=lockstep, so the captured frame has its links whatever
# the worker thread's speed. Measured on llvmpipe (Mesa 22.3), defaults radiosity_tess=24,
# radiosity_bounces=4, radiosity_weight=spill (cornell 2,983 vertices, furnace 2,646):
#   cornell (2,983 surfels) vs the full reference, rel. RMSE (none: 0.326; reference noise floor 0.017):
#     6x8² 0.0628, 6x12² 0.0403, 6x16² 0.0351 (mean ratio 1.022, 1.006, 0.999)
#     -- the seed's Table 4.1 shape: 6x16² closest
#   --gles 3.1 renders the same image (RMSE 0 against the 3.2 path)
#   furnace, image mean per bounce count (analytic 2 - 0.5^k -> 2.0; the reference's mean 2.0007):
#     1: 1.491  2: 1.731  4: 1.904  8: 1.955  (mean / series - 1: -0.006 -0.011 -0.017 -0.020)
#   light-leak, RMSE against the black ruler of the dark room (none: 0): the limitation of
#     research 2.6 (light leaks through a wall the bins cannot resolve), falling with tessellation,
#     with the seed's visibility (radiosity_vis=bins):
#     radiosity_tess=16: 0.626  24: 0.562  32: 0.479  (1,716 / 3,444 / 5,882 vertices);
#     with the default radiosity_vis=rays (issue 11, rad_vis.h): 0 at all three
#   cornell-spot-anim: the indirect light (radiosity - none, same frame) follows the moving spot:
#     frame 59's against frame 29's, rel. RMSE 8.6 (the spot lights another part of the room; the
#     scheduler moves the unpinned knobs on llvmpipe, so it varies from run to run: 0.75-6.9 seen,
#     before and after issue 18's refit work).
#   env-studio (its environment through the empty leaf bins, radiosity_env), rel. RMSE against
#     env-studio.exr (none 0.0779) and the bounce's mean (radiosity - none) against env-studio-indirect.exr:
#     bins 0.0718 (mean ratio 1.165), rest 0.0617 (0.999), rays 0.0662 (1.095)
#     (with the lights shadowed by cssm_env, the 5 cm cap #11's receiver plane replaced in
#     render_env.c: none 0.0810, bins 0.0779, rest 0.0675, rays 0.0721;
#     before the environment's lights were shadowed by cssm_env: none 0.0911, bins
#     0.0991, rest 0.0882, rays 0.0928; with the uncapped slope-scaled CSSM of #11 none 0.0901,
#     rest 0.0949)
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless
REFS=tests/references

json_field() { sed -n "s/.*\"$1\": \(\[[^]]*\]\|[^,}]*\).*/\1/p" "$2"; }
awk_true() { awk "BEGIN { exit !($1) }"; }

# cap NAME SCENE METHOD BUDGETS [options]: frame 2 (index 1) as $TMP/NAME.exr
cap() {
    c_name=$1 c_scene=$2 c_method=$3 c_budget=$4
    shift 4
    rm -rf "$TMP/cap"
    "$GIKIOSK" run --platform mock --scene "$c_scene" --method "$c_method" --size 160x120 --frames 2 --hdr \
        --capture "$TMP/cap" --budget "radiosity_sync=lockstep${c_budget:+,$c_budget}" "$@" >"$TMP/$c_name.log" 2>&1 &&
        mv "$TMP/cap/000001-$c_scene-$c_method.exr" "$TMP/$c_name.exr"
}
# field NAME REF KEY: KEY of `compare REF $TMP/NAME.exr --json`
field() {
    "$GIKIOSK" compare "$2" "$TMP/$1.exr" --json >"$TMP/cmp.json" 2>/dev/null
    json_field "$3" "$TMP/cmp.json"
}

check "gikiosk scenes offers radiosity on cornell" sh -c "'$GIKIOSK' scenes | awk '\$1 == \"cornell\" && \$5 ~ /radiosity/' | grep -q ."
check "gikiosk scenes does not offer radiosity on atrium (79,808 triangles: past the method's size)" \
    sh -c "! '$GIKIOSK' scenes | awk '\$1 == \"atrium\" && \$5 ~ /radiosity/' | grep -q ."

# --- cornell: bin resolution against the full reference --------------------------------------
prev=1
for n in 8 12 16; do
    check "cornell radiosity_bins=$n renders" cap "cornell-$n" cornell radiosity "radiosity_bins=$n"
    e=$(field "cornell-$n" "$REFS/cornell.exr" rel_rmse)
    echo "# cornell 6x$n²: rel_rmse $e"
    case $n in 8) bound=0.079 ;; 12) bound=0.050 ;; 16) bound=0.044 ;; esac # measured + 25%
    check "cornell 6x$n²: rel_rmse $e < $bound" awk_true "\"$e\" != \"\" && $e < $bound"
    check "cornell 6x$n²: finer bins closer to the reference ($e < $prev)" awk_true "\"$e\" != \"\" && $e < $prev"
    prev=${e:-0}
done
check "cornell --gles 3.1 renders" cap cornell-31 cornell radiosity "" --gles 3.1
r=$(field cornell-31 "$TMP/cornell-12.exr" rmse)
check "cornell: the GLES 3.1 path renders what the 3.2 path does (rmse $r < 1e-5)" awk_true "\"$r\" != \"\" && $r < 1e-5"

# --- furnace: the mean converges to the analytic 2.0 with bounces ------------------------------
prev=0
for k in 1 2 4 8; do
    check "furnace radiosity_bounces=$k renders" cap "furnace-$k" furnace radiosity "radiosity_bounces=$k"
    m=$(field "furnace-$k" "$REFS/furnace.exr" test_mean)
    series=$(awk "BEGIN { print 2 - 0.5 ^ $k }")
    echo "# furnace $k bounce(s): mean $m, series $series"
    # bound: worst measured (-0.020) with 50% room
    check "furnace $k bounce(s): mean $m within 3% of 2 - 0.5^$k = $series" \
        awk_true "\"$m\" != \"\" && $m / $series - 1 < 0.03 && $m / $series - 1 > -0.03"
    check "furnace: every bounce adds light ($m > $prev)" awk_true "\"$m\" != \"\" && $m > $prev"
    prev=${m:-0}
done
check "furnace 8 bounces: mean $prev within 3% of the analytic 2.0" awk_true "$prev > 1.94 && $prev < 2.06"

# --- light-leak: the seed's implicit visibility (radiosity_vis=bins) leaks, falling with
# tessellation; the default (rays: walls split the surfaces, a shadow ray per link, rad_vis.h)
# leaves the dark room black at every tessellation (measured RMSE exactly 0) ------------------------
prev=1
for t in 16 24 32; do
    check "light-leak radiosity_tess=$t vis=bins renders" cap "leak-$t" light-leak radiosity "radiosity_tess=$t,radiosity_vis=bins"
    l=$(field "leak-$t" "$REFS/light-leak.exr" rmse)
    echo "# light-leak radiosity_tess=$t vis=bins: rmse $l against the black ruler"
    check "light-leak tess $t vis=bins: leaks (rmse $l in 0.3 .. 0.8, measured 0.48 .. 0.63)" \
        awk_true "\"$l\" != \"\" && $l > 0.3 && $l < 0.8"
    check "light-leak vis=bins: finer tessellation leaks less ($l < $prev)" awk_true "\"$l\" != \"\" && $l < $prev"
    prev=${l:-0}
    check "light-leak radiosity_tess=$t vis=rays renders" cap "leak-rays-$t" light-leak radiosity "radiosity_tess=$t,radiosity_vis=rays"
    grep -q "radiosity_vis=rays" "$TMP/leak-rays-$t.log" || check "the run reports radiosity_vis=rays" false
    r=$(field "leak-rays-$t" "$REFS/light-leak.exr" rmse)
    echo "# light-leak radiosity_tess=$t vis=rays: rmse $r"
    check "light-leak tess $t vis=rays: the dark room is black (rmse $r = 0)" awk_true "\"$r\" != \"\" && $r == 0"
done

# --- the link update rate (radiosity_link_every): a knob like the others, in the stats ----------
# (its effect is measured where meshes move: tests/unit/test_radiosity_refit.c)
check "radiosity_link_every=4 runs (cornell-spot-anim, async)" "$GIKIOSK" run --platform mock \
    --scene cornell-spot-anim --method radiosity --size 64x48 --frames 3 --budget radiosity_link_every=4 \
    --stats "$TMP/link.csv"
v=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "radiosity_link_every") c = i } NR == 4 { print $c }' "$TMP/link.csv")
check "the stats give radiosity_link_every=4 ($v)" test "$v" = 4
expect_exit 2 "radiosity_link_every=3 is refused (not a level)" "$GIKIOSK" run --platform mock --scene cornell \
    --method radiosity --frames 1 --budget radiosity_link_every=3

# --- a moving mesh: radiosity is offered and refits it (tests/unit/test_radiosity_refit.c measures
# the refit and the links; here the program as a user runs it). The fixture: the fuzz corpus's
# embedded cornell-spot-anim with its animation channel moved from the spot to the short block,
# which then turns about the room's corner. Measured: radiosity / none mean 1.20-1.31 at frames 19
# and 39 over three runs (the scheduler moves the unpinned knobs: it varies); bound 1.1 -- the
# bounce is shown while the block moves.
mkdir -p "$TMP/moving"
sed 's/"target":{"node":8,"path":"rotation"}/"target":{"node":5,"path":"rotation"}/' \
    tests/fuzz/corpus/gltf/spot-anim-embedded.gltf >"$TMP/moving/block-anim.gltf"
check "the fixture animates the short block (node 5)" grep -q '"target":{"node":5,"path":"rotation"}' "$TMP/moving/block-anim.gltf"
check "gikiosk scenes offers radiosity where a mesh moves" \
    sh -c "'$GIKIOSK' scenes --dir '$TMP/moving' | awk '\$1 == \"block-anim\" && \$4 ~ /animated/ && \$5 ~ /radiosity/' | grep -q ."
moving() { # METHOD [options]: frames 19 and 39 as $TMP/moving-METHOD-19.exr, -39.exr
    m_method=$1
    shift
    rm -rf "$TMP/cap"
    "$GIKIOSK" run --platform mock --scenes-dir "$TMP/moving" --scene block-anim --method "$m_method" --size 80x60 \
        --frames 40 --capture-every 20 --hdr --capture "$TMP/cap" \
        --budget radiosity_sync=lockstep,radiosity_tess=16,radiosity_bins=8 "$@" >"$TMP/moving.log" 2>&1 &&
        mv "$TMP/cap/000019-block-anim-$m_method.exr" "$TMP/moving-$m_method-19.exr" &&
        mv "$TMP/cap/000039-block-anim-$m_method.exr" "$TMP/moving-$m_method-39.exr"
}
check "block-anim: none renders" moving none
check "block-anim: radiosity renders while the block moves" moving radiosity
for f in 19 39; do
    r=$(field "moving-radiosity-$f" "$TMP/moving-none-$f.exr" mean_ratio)
    check "block-anim frame $f: radiosity adds the bounce (mean ratio to none $r > 1.1)" awk_true "\"$r\" != \"\" && $r > 1.1"
done
check "block-anim: radiosity renders at --gles 3.1" moving radiosity --gles 3.1

# --- cornell-spot-anim: the indirect light follows the spot -----------------------------------
anim() { # METHOD: frames 29 and 59 (--capture-every takes every 30th) as $TMP/anim-METHOD-0.exr, -30.exr
    rm -rf "$TMP/cap"
    "$GIKIOSK" run --platform mock --scene cornell-spot-anim --method "$1" --size 160x120 --frames 60 \
        --capture-every 30 --hdr --capture "$TMP/cap" --budget radiosity_sync=lockstep >"$TMP/anim.log" 2>&1 &&
        mv "$TMP/cap/000029-cornell-spot-anim-$1.exr" "$TMP/anim-$1-0.exr" &&
        mv "$TMP/cap/000059-cornell-spot-anim-$1.exr" "$TMP/anim-$1-30.exr"
}
check "cornell-spot-anim: none renders frames 29 and 59" anim none
check "cornell-spot-anim: radiosity renders frames 29 and 59" anim radiosity
if oiiotool "$TMP/anim-radiosity-0.exr" "$TMP/anim-none-0.exr" --sub -o "$TMP/ind-0.exr" 2>/dev/null &&
    oiiotool "$TMP/anim-radiosity-30.exr" "$TMP/anim-none-30.exr" --sub -o "$TMP/ind-30.exr" 2>/dev/null; then
    m0=$("$GIKIOSK" compare "$TMP/ind-0.exr" "$TMP/ind-30.exr" --json | sed -n 's/.*"rel_rmse": \([^,]*\).*/\1/p')
    echo "# cornell-spot-anim: indirect light frame 59 against frame 29: rel_rmse $m0"
    check "cornell-spot-anim: the indirect light changes as the spot moves (rel_rmse $m0 > 0.05)" \
        awk_true "\"$m0\" != \"\" && $m0 > 0.05"
else
    check "oiiotool subtracts the captures" false
fi
# --- env-studio: the environment through the empty leaf bins (radiosity_env) -------------------
check "env-studio: none renders" cap env-none env-studio none ""
en=$(field env-none "$REFS/env-studio.exr" rel_rmse)
for v in bins rest rays; do
    check "env-studio radiosity_env=$v renders" cap "env-$v" env-studio radiosity "radiosity_env=$v"
    e=$(field "env-$v" "$REFS/env-studio.exr" rel_rmse)
    if oiiotool "$TMP/env-$v.exr" "$TMP/env-none.exr" --sub -o "$TMP/env-ind-$v.exr" 2>/dev/null; then
        "$GIKIOSK" compare "$REFS/env-studio-indirect.exr" "$TMP/env-ind-$v.exr" --json >"$TMP/cmp.json" 2>/dev/null
        mr=$(json_field mean_ratio "$TMP/cmp.json")
    else
        mr=""
    fi
    echo "# env-studio radiosity_env=$v: rel_rmse $e (none $en), bounce mean ratio to the indirect reference $mr"
    case $v in # measured (header) + 10%; the bounce's mean within the measured +- 0.05
        bins) bound=0.079 lo=1.11 hi=1.22 ;;
        rest) bound=0.068 lo=0.95 hi=1.05 ;;
        rays) bound=0.073 lo=1.04 hi=1.15 ;;
    esac
    check "env-studio $v: rel_rmse $e < $bound" awk_true "\"$e\" != \"\" && $e < $bound"
    check "env-studio $v: the bounce's mean ratio $mr in [$lo, $hi]" awk_true "\"$mr\" != \"\" && $mr >= $lo && $mr <= $hi"
done
# the seed's bins leak the environment through what the links miss (their bounce is 1.165x the
# reference's); rest scales them to what the links leave: closest of all, and every switch is
# closer than none (gi_not_worse.sh asserts that of the default, bins)
eb=$(field env-bins "$REFS/env-studio.exr" rel_rmse)
er=$(field env-rest "$REFS/env-studio.exr" rel_rmse)
check "env-studio: rest ($er) is closer to the reference than none ($en) and than bins ($eb)" \
    awk_true "\"$er\" != \"\" && $er < $en && $er < $eb"
expect_exit 2 "radiosity_env=sky is refused (not a level)" "$GIKIOSK" run --platform mock --scene env-studio \
    --method radiosity --frames 1 --budget radiosity_env=sky
finish
