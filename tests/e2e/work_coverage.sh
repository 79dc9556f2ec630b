#!/bin/sh
# Every timed pass has a work model (#21): in benches of every method on the scenes below, each
# pass the bench times (a leaf of the frame report with a median time above 0) in a row has a line
# of efficiency.csv in that row, but for the exceptions listed in $TMP/coverage.py, each with why;
# an exception no run times any more fails too (the list must not go stale), and the checker is
# shown to fail on an efficiency.csv with a modelled pass's lines taken out. gi.occlusion's count is
# checked against the render size.
# --rebuild-gi: the passes that rebuild what a static scene keeps (vct's voxels, lgv's maps, the
# shadow maps and VSSM's prefilter) run and are timed in every frame; without it they are timed as
# empty brackets (about 1 us, no work) in the frames that keep their data.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless

# a roofline of round numbers (as tests/e2e/efficiency.sh's): which passes have lines does not
# depend on this machine's limits
cp tests/e2e/data/roofline-round.csv "$TMP/roofline.csv"

cat >"$TMP/coverage.py" <<'PY'
import csv, sys
# Timed passes without a work model, by name, and why none can be given: each is CPU work, which
# no roofline kind measures.
EXCEPTIONS = {
    # the render thread's hand-over to the lightmap worker and the upload of its newest atlas
    # (glTexSubImage from the CPU): no shader fetches anything
    "gi.lightmap_upload",
    # the same for radiosity's worker and its published radiosities
    "gi.radiosity_upload",
    # vpl's VPL clustering (k-means over the VPLs read back, on the CPU; vpl_method.c cluster)
    "gi.vpl_cluster",
}
# (scene, pass) exceptions: a modelled pass whose model counts nothing in that scene (efficiency.csv
# has no line for a pass with no fetches)
SCENE_EXCEPTIONS = {
    # lit by its uniform sky alone, unshadowed: the direct pass's model counts shadow lookups, and
    # there are none; its G-buffer reads and BRDF evaluation are not modelled
    ("blend-half", "direct"),
}
missing, timed_exceptions = [], set()
for d in sys.argv[1:]:
    bench = list(csv.DictReader(open(d + "/bench.csv")))
    effr = csv.reader(open(d + "/efficiency.csv"))
    header = next(effr)
    knobs = header[:header.index("pass")]          # scene, method, every knob: a row's key
    modelled = {tuple(e[:len(knobs)]) + (e[len(knobs)],) for e in effr}
    passes = [c[:-3] for c in bench[0] if c.endswith("_ms") and not c.startswith("frame_ms")]
    leaves = [p for p in passes if not any(o.startswith(p + ".") for o in passes)]
    for b in bench:
        key = tuple(b[k] for k in knobs)
        for p in leaves:
            if not b[p + "_ms"] or float(b[p + "_ms"]) <= 0.0:
                continue
            if p in EXCEPTIONS or (b["scene"], p) in SCENE_EXCEPTIONS:
                timed_exceptions.add(p if p in EXCEPTIONS else (b["scene"], p))
            elif key + (p,) not in modelled:
                missing.append("%s %s %s (%s ms)" % (b["scene"], b["method"], p, b[p + "_ms"]))
for m in sorted(set(missing)):
    print("# no work model: " + m)
stale = (EXCEPTIONS | SCENE_EXCEPTIONS) - timed_exceptions
for x in sorted(map(str, stale)):
    print("# exception %s is timed in no run: take it off the list" % x)
sys.exit(1 if missing or stale else 0)
PY

# bench_run NAME WHAT ARGS...: a bench at 80x60, one frame after one, into $TMP/NAME
runs=""
bench_run() {
    name=$1 what=$2
    shift 2
    expect_exit 0 "bench --roofline-csv --rebuild-gi: $what" sh -c "'$GIKIOSK' bench --size 80x60 --frames 1 --warmup 1 \
        --rebuild-gi --roofline-csv '$TMP/roofline.csv' $* --out '$TMP/$name' 2>'$TMP/$name.log'"
    runs="$runs $TMP/$name"
}
# lockstep: lightmap's and radiosity's frames wait for their workers, so their GPU passes run in
# the one timed frame (asynchronous, the worker has published nothing yet and only the upload runs)
SYNC=shadow_map=256,lightmap_sync=lockstep,radiosity_sync=lockstep
bench_run cornell "cornell, every method, four shadow methods" --scenes cornell \
    --methods none,vct,vpl,lightmap,radiosity --sweep "'shadow=hard,pcss,vssm,cssm'" --budget $SYNC
bench_run bounce "cornell, vct's second bounce" --scenes cornell --methods vct --sweep vct_bounces=2
bench_run caustic "caustic-ring, ispm, lgv and lightmap's caustics" --scenes caustic-ring \
    --methods ispm,lgv,lightmap --sweep shadow=pcss --budget $SYNC
bench_run fog "glass-fog, the glass pass and volcaustics" --scenes glass-fog --methods none,volcaustics \
    --sweep shadow=pcss
# the passes only some glTF scenes call for: the occlusion texture on GI (every GI method) and the
# alpha-blended surfaces' forward pass
bench_run gltf "occlusion-gi-half and blend-half: gi.occlusion and blend" --scenes-dir tests/gltf \
    --scenes occlusion-gi-half,blend-half --sweep shadow=pcss --budget $SYNC

# shellcheck disable=SC2086 # $runs: the runs' folders, one word each
check "every timed pass of every run has a work model (or is a listed exception, still timed)" \
    python3 "$TMP/coverage.py" $runs
# gi.occlusion from the render size (render_work.c): one pre-GI texel and one depth read a pixel
check "gi.occlusion: 80 x 60 texels and depth reads in every GI row of occlusion-gi-half" python3 - "$TMP/gltf/efficiency.csv" <<'PY'
import csv, sys
occ = [e for e in csv.DictReader(open(sys.argv[1])) if e["pass"] == "gi.occlusion"]
rows = {e["method"] for e in occ}
assert rows == {"vct", "vpl", "lightmap", "radiosity"}, rows
assert sorted(e["kind"] for e in occ) == sorted(["tex2d_rgba32f_nearest", "tex2d_depth32f_nearest"] * 4), occ
assert all(float(e["fetches"]) == 80 * 60 for e in occ), occ
PY
# the checker can fail: the first run's efficiency.csv without vct's trace lines
mkdir -p "$TMP/cut"
first=$TMP/cornell
cp "$first/bench.csv" "$TMP/cut/bench.csv"
grep -v ',gi\.vct_trace,' "$first/efficiency.csv" >"$TMP/cut/efficiency.csv"
check "the checker fails on an efficiency.csv without vct's trace lines" \
    sh -c "! python3 '$TMP/coverage.py' '$TMP/cut' >/dev/null"
finish
