#!/bin/sh
# `gikiosk bench --roofline-csv` (#21): efficiency.csv holds one line per measured pass that has a
# work model, each of its numbers recomputed here another way -- the pass time from bench.csv's own
# column, the limit from roofline.csv, the rate and the efficiency from those and the fetches -- the
# bars chart is drawn per scene, vpl's gather counts agree between two visibilities, the models of
# vct, vpl (both gathers), ispm (its caustic passes too), lightmap, radiosity (its display too) and
# the renderer's own passes (the shadow maps, the G-buffer, the compose) hold across their rows, and a broken
# roofline.csv is bad input naming its file and line.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless

# A roofline of round numbers (the real one is `bench --roofline`, tests/e2e/roofline.sh): the
# recomputation below does not depend on this machine's speed.
cp tests/e2e/data/roofline-round.csv "$TMP/roofline.csv"
# --rebuild-gi: every frame voxelizes, injects and builds the mips again, so those passes are timed
expect_exit 0 "bench --roofline-csv: vct at two cone counts" sh -c "'$GIKIOSK' bench --scenes cornell --methods vct \
    --size 80x60 --frames 1 --warmup 1 --sweep 'vct_cones=4,9' --rebuild-gi --roofline-csv '$TMP/roofline.csv' \
    --out '$TMP/b' 2>'$TMP/b.log'"
EFF=$TMP/b/efficiency.csv
check "efficiency.csv: the header ends with the efficiency columns" \
    sh -c "head -1 '$EFF' | grep -q ',pass,kind,fetches,pass_ms,fetches_per_s,limit_fetches_per_s,efficiency\$'"
check "efficiency.csv: the cone trace's line in each row" [ "$(grep -c ',gi.vct_trace,tex3d_rgba16f_trilinear,' "$EFF")" -eq 2 ]
# every number of an efficiency.csv recomputed from its bench.csv and the roofline; argv[4]: the
# swept knob that tells the bench's two rows apart
cat >"$TMP/recompute.py" <<'PY'
import csv, sys
bench = list(csv.DictReader(open(sys.argv[1])))
eff = list(csv.DictReader(open(sys.argv[2])))
limits = {r["name"]: float(r["fetches_per_s"]) for r in csv.DictReader(open(sys.argv[3]))}
key = sys.argv[4]
close = lambda a, b: abs(a - b) <= 1e-5 * abs(b)   # the CSVs print %.6g
assert len(bench) == 2, len(bench)
row = {b[key]: b for b in bench}                   # the two rows differ in the swept knob only
for e in eff:
    b = row[e[key]]
    assert e["scene"] == b["scene"] and e["shadow"] == b["shadow"]
    fetches, ms = float(e["fetches"]), float(b[e["pass"] + "_ms"])
    assert fetches > 0 and close(float(e["pass_ms"]), ms), (e, ms)
    assert close(float(e["limit_fetches_per_s"]), limits[e["kind"]]), e
    assert close(float(e["fetches_per_s"]), fetches / (ms * 1e-3)), e
    assert close(float(e["efficiency"]), fetches / (ms * 1e-3) / limits[e["kind"]]), e
PY
check "efficiency.csv: every number recomputed from bench.csv and roofline.csv" \
    python3 "$TMP/recompute.py" "$TMP/b/bench.csv" "$EFF" "$TMP/roofline.csv" vct_cones
# $TMP/fetches.py reads a bench_rows run's fetches by (pass, kind) and row for the checks below.
cat >"$TMP/fetches.py" <<'PY'
import csv
def by_row(path, knob):
    f = {}
    for e in csv.DictReader(open(path)):
        f.setdefault((e["pass"], e["kind"]), {})[e[knob]] = float(e["fetches"])
    return f
PY
# bench_rows DIR KEY WHAT ARGS...: a bench of two rows (ARGS: the scene, method and sweep) at 80x60
# over the round-number roofline into $TMP/DIR, every number of its efficiency.csv recomputed (KEY:
# the swept knob that tells the two rows apart)
bench_rows() {
    dir=$1 key=$2 what=$3
    shift 3
    expect_exit 0 "bench --roofline-csv: $what" sh -c "'$GIKIOSK' bench --size 80x60 --frames 1 --warmup 1 $* \
        --roofline-csv '$TMP/roofline.csv' --out '$TMP/$dir' 2>'$TMP/$dir.log'"
    check "$what: every number of efficiency.csv recomputed" \
        python3 "$TMP/recompute.py" "$TMP/$dir/bench.csv" "$TMP/$dir/efficiency.csv" "$TMP/roofline.csv" "$key"
}
check "efficiency.csv: vct's passes and the direct pass's kind" python3 - "$EFF" <<'PY'
import csv, sys
eff = list(csv.DictReader(open(sys.argv[1])))
passes = {(e["vct_cones"], e["pass"]) for e in eff}
# each row: the cone trace, the voxelizer's atomics, the injection's shadow fetches and the mips'
# loads (rebuilt each frame), the direct pass's shadow lookups (cornell's light is shadowed), and the
# renderer's G-buffer fragments and compose lookups, and the shadow maps' fragments (--rebuild-gi
# renders them every frame too), and vct's compose (its upsample's reads)
assert passes == {(c, p) for c in ("4", "9")
                  for p in ("gi.vct_trace", "gi.vct_voxelize", "gi.vct_inject", "gi.vct_mips", "gi.vct_compose", "direct",
                            "gbuffer", "compose", "shadow.shadow_depth", "gi.blend_hold")}, passes
# the GI cross-fade's copy of the image before GI (render_work.c; tests/gpu/test_gi_blend.c): one
# texel a pixel in every GI row (gi_blend=4 by default); the bench cuts between rows, so no row blends
assert all(float(e["fetches"]) == 80 * 60 for e in eff if e["pass"] == "gi.blend_hold"), eff
# the cones do not change the voxels nor the light's view: the same voxelization, injection, mips
# and shadow maps at both counts
for p in ("gi.vct_voxelize", "gi.vct_inject", "gi.vct_mips", "shadow.shadow_depth"):
    f = {e["vct_cones"]: float(e["fetches"]) for e in eff if e["pass"] == p}
    assert f["4"] == f["9"] > 0, (p, f)
# nor what the compose upsamples: the same texels and depth reads, of both kinds, at both counts
for k in ("tex2d_rgba32f_nearest", "tex2d_depth32f_nearest"):
    f = {e["vct_cones"]: float(e["fetches"]) for e in eff if e["pass"] == "gi.vct_compose" and e["kind"] == k}
    assert f["4"] == f["9"] > 0, (k, f)
# the default shadows (PCSS) read the depth map only, at the depth kind's limit
assert {e["kind"] for e in eff if e["pass"] == "direct"} == {"tex2d_depth32f_nearest"}, eff
# more cones, more samples: 9 cones fetch more than 4 at the same resolution
by = {e["vct_cones"]: float(e["fetches"]) for e in eff if e["pass"] == "gi.vct_trace"}
assert by["9"] > by["4"], by
PY
if command -v gnuplot >/dev/null 2>&1; then
    check "efficiency-cornell.png and .svg drawn" sh -c "[ -s '$TMP/b/efficiency-cornell.png' ] && [ -s '$TMP/b/efficiency-cornell.svg' ]"
    check "the chart's data: a bar per row and pass" \
        sh -c "[ \"\$(grep -c 'gi.vct_trace' '$TMP/b/efficiency-cornell.dat')\" -eq 2 ] && [ \"\$(grep -c 'gi.vct_inject' '$TMP/b/efficiency-cornell.dat')\" -eq 2 ] && [ \"\$(wc -l <'$TMP/b/efficiency-cornell.dat')\" -eq \"\$(( \$(wc -l <'$EFF') - 1 ))\" ]"
fi
# vpl's gather counts (app/gi/vpl/vpl_work.c) checked against each other: VSM and CSSM visibility
# share the VPLs and their clusters, so the unfiltered fetches (VPL and VAL tables) are equal; per VPL
# past the VAL's early-out VSM reads 2 moments and CSSM 2 RGBA8 bases, and where it finds blockers
# CSSM adds 3 16-bit and 2 RGBA8 lookups: VSM's 16-bit count = CSSM's RGBA8 - 2/3 of its 16-bit.
# The deep-umbra test is off here: its unfiltered lookups (4 or 8 per VPL that reaches it) follow
# each visibility's own filtered answer, so the two would no longer share their unfiltered count.
expect_exit 0 "bench --roofline-csv: vpl with VSM and CSSM visibility" sh -c "'$GIKIOSK' bench --scenes cornell \
    --methods vpl --size 80x60 --frames 1 --warmup 1 --sweep 'vpl_vis=vsm,cssm' --budget vpl_umbra=off \
    --roofline-csv '$TMP/roofline.csv' \
    --out '$TMP/v' 2>'$TMP/v.log'"
check "vpl's efficiency.csv: every number recomputed" \
    python3 "$TMP/recompute.py" "$TMP/v/bench.csv" "$TMP/v/efficiency.csv" "$TMP/roofline.csv" vpl_vis
check "vpl_gather: VSM's and CSSM's counts agree" python3 - "$TMP/v/efficiency.csv" <<'PY'
import csv, sys
f = {}
for e in csv.DictReader(open(sys.argv[1])):
    if e["pass"] == "gi.vpl_gather":
        f[(e["vpl_vis"], e["kind"])] = float(e["fetches"])
    # the VAL maps: fragments at the fill rate, their depth draws' (counted) and the basis pass's
    # (res^2 per map), the same maps under both visibilities (tests/gpu/test_vpl_work.c replays them)
    if e["pass"] == "gi.vpl_valsm" and e["kind"] == "raster_r16f_depth_fill":
        f[(e["vpl_vis"], "valsm")] = float(e["fetches"])
    # ... and their mips (vpl_work.c, from the parameters; tests/gpu/test_vpl_work.c hand-counts
    # them): VSM's one 16-bit moment chain, CSSM's 2 RGBA8 and 3 16-bit chains, of the same maps
    if e["pass"] == "gi.vpl_valsm" and e["kind"] != "raster_r16f_depth_fill":
        f[(e["vpl_vis"], "mips", e["kind"])] = float(e["fetches"])
u, h = "tex2d_rgba32f_nearest", "tex2d_rgba16f_trilinear"
assert f[("vsm", u)] > 0 and f[("vsm", u)] == f[("cssm", u)], f
assert f[("vsm", h)] > 0 and f[("vsm", h)] == f[("cssm", "tex2d_rgba8_trilinear")] - 2 * f[("cssm", h)] / 3, f
assert f[("vsm", "valsm")] > 64 * 64 and f[("vsm", "valsm")] == f[("cssm", "valsm")], f
m16, m8 = "tex2d_rgba16f_trilinear", "tex2d_rgba8_trilinear"
assert ("vsm", "mips", m8) not in f and f[("vsm", "mips", m16)] % 1365 == 0, f   # 1365 texels a map at 64^2
assert f[("cssm", "mips", m16)] == 3 * f[("vsm", "mips", m16)] and f[("cssm", "mips", m8)] == 2 * f[("vsm", "mips", m16)], f
PY
# the multi-resolution gather counts its regions' VPL loops (tests/gpu/test_vpl_work.c: regions x the
# dense gather's reads a pixel): both gathers' rows recomputed; the VAL maps do not depend on the gather
bench_rows m vpl_gather "vpl's interleaved and multires gathers" --scenes cornell --methods vpl \
    --sweep "'vpl_gather=interleaved,multires'"
check "vpl_gather=multires: its gather counted, the VAL maps as the interleaved row's" python3 - "$TMP/m/efficiency.csv" <<'PY'
import csv, sys
f = {}
for e in csv.DictReader(open(sys.argv[1])):
    f[(e["vpl_gather"], e["pass"], e["kind"])] = float(e["fetches"])
# the interleaved gather reads a 1/16 subset of the VPLs per pixel (vpl_block=4), the multires one all
# of them per region: more unless it shades under 1/16 of the pixels (measured 632 699 against 50 832
# table reads on cornell at 80x60)
u = "tex2d_rgba32f_nearest"
assert f[("multires", "gi.vpl_gather", u)] > f[("interleaved", "gi.vpl_gather", u)] > 0, f
v = ("gi.vpl_valsm", "raster_r16f_depth_fill")
assert f[("multires",) + v] == f[("interleaved",) + v] > 0, f
PY
# the blur's and the compose's texels (vpl_work.c; tests/gpu/test_vpl_work.c replays the blur's taps
# and hand-counts the compose): they read the targets the gather leaves, whose positions and normals
# are the G-buffer's whatever the gather and the visibility, so each is the same in both rows of the
# visibility run and of the gather run; the blur at most 2 passes x (2 + 3 per tap) at each of the
# 40x30 indirect pixels (vpl_res=0.5, vpl_blur=4: 9 taps), the compose at most 12 a pixel of 80x60
check "vpl_blur and vpl_compose: their texels the same under both visibilities and both gathers" \
    env PYTHONPATH="$TMP" python3 - "$TMP/v/efficiency.csv" vpl_vis "$TMP/m/efficiency.csv" vpl_gather <<'PY'
import sys
from fetches import by_row
for path, knob in zip(sys.argv[1::2], sys.argv[2::2]):
    f = by_row(path, knob)
    blur, compose = f[("gi.vpl_blur", "tex2d_rgba32f_nearest")], f[("gi.vpl_compose", "tex2d_rgba32f_nearest")]
    assert len(set(blur.values())) == 1 and 0 < min(blur.values()) <= 2 * 40 * 30 * (2 + 3 * 9), (path, blur)
    assert len(set(compose.values())) == 1 and 0 < min(compose.values()) <= 12 * 80 * 60, (path, compose)
PY
# ispm's diffuse indirect part is vpl's (its passes by vpl's models): the same at any photon count
bench_rows i ispm_photons "ispm at two photon counts" --scenes caustic-ring --methods ispm \
    --sweep "'ispm_photons=1024,4096'"
# ... and its caustic passes (app/gi/ispm/ispm_work.c; tests/gpu/test_ispm_work.c replays them): the
# lists see the same frustum fragments at both photon counts, five atomics each (none dropped at the
# default pool); more photons march more steps and draw more splats
check "ispm: vpl's passes equal at both photon counts, the caustic passes by their models" python3 - "$TMP/i/efficiency.csv" <<'PY'
import csv, sys
f = {}
for e in csv.DictReader(open(sys.argv[1])):
    f.setdefault((e["pass"], e["kind"]), {})[e["ispm_photons"]] = float(e["fetches"])
assert ("gi.vpl_valsm", "raster_r16f_depth_fill") in f and ("gi.vpl_gather", "tex2d_rgba32f_nearest") in f, f
caustic = {("gi.ispm_lists", "ssbo_r32ui_atomic"), ("gi.ispm_trace", "ssbo_rgba32f_load"),
           ("gi.ispm_splat", "raster_r16f_depth_fill")}
assert caustic <= set(f), f
# the RSM's fragments (tests/gpu/test_ispm_work.c replays them): the light's view of the ring, the
# same at both photon counts (checked with vpl's passes below), at most a few times its 256^2 texels
assert 0 < f[("gi.ispm_photons", "raster_r16f_depth_fill")]["1024"] <= 4 * 256 * 256, f
# the mask pyramid and the emission in the same pass (ispm_work.c ispm_photons_model, from the photon
# header; tests/gpu/test_ispm_work.c checks it against the shaders' counting variant): the pyramid's
# 256² mask texels and 4 (128² + ... + 1²) = 87 380 count loads at both counts, plus the emission's
# (256 >> l)² count loads at its level l, and a depth read per photon, at most the budget
emission = {("gi.ispm_photons", k) for k in ("tex2d_r32f_nearest", "tex2d_depth32f_nearest", "ssbo_rgba32f_load",
                                            "ssbo_r32ui_atomic")}
assert emission <= set(f), f
for n in ("1024", "4096"):
    blocks = f[("gi.ispm_photons", "ssbo_rgba32f_load")][n] - 87380
    side = round(blocks ** 0.5)
    assert side * side == blocks and side & (side - 1) == 0 and side <= 256, (n, blocks)
    photons = f[("gi.ispm_photons", "tex2d_depth32f_nearest")][n]
    assert 0 < photons <= int(n) and f[("gi.ispm_photons", "tex2d_r32f_nearest")][n] >= 256 * 256 + 4 * photons, (n, f)
assert f[("gi.ispm_photons", "tex2d_depth32f_nearest")]["4096"] > f[("gi.ispm_photons", "tex2d_depth32f_nearest")]["1024"]
for k, v in f.items():
    if k not in caustic | emission or k[0] == "gi.ispm_lists":
        assert v["1024"] == v["4096"] > 0, (k, v)
lists = f[("gi.ispm_lists", "ssbo_r32ui_atomic")]["1024"]
assert lists % 5 == 0, lists
# the upsample (counted; tests/gpu/test_ispm_work.c): the splat texels of each lit pixel's bilinear
# footprint, at most 2 a side at ispm_splat=0.5 (3 next to the edge), the same view at both counts
up = f[("gi.ispm_upsample", "tex2d_rgba32f_nearest")]
assert 0 < up["1024"] <= (2 * 80 + 2) * (2 * 60 + 2), up
for k in caustic - {("gi.ispm_lists", "ssbo_r32ui_atomic")}:
    assert f[k]["4096"] > f[k]["1024"] > 0, (k, f[k])
PY
# lightmap's GPU passes (app/gi/lightmap/lm_work.c): the compose's light-map lookups (counted; at most
# one a pixel, the same view at both caustic budgets) and the caustic filter's count texels (from the
# filtered tiles: at most the whole screen's, per axis 7 n - 12 of them, tests/gpu/
# test_lightmap_caustics.c); lockstep, so every row's frames show the light map and the caustics
bench_rows l lightmap_caustics "lightmap at two caustic budgets" --scenes caustic-ring --methods lightmap \
    --budget lightmap_sync=lockstep --sweep "'lightmap_caustics=2500,10000'"
check "lightmap: the compose's lookups and the caustic filter's reads" python3 - "$TMP/l/efficiency.csv" <<'PY'
import csv, sys
f = {}
for e in csv.DictReader(open(sys.argv[1])):
    f[(e["pass"], e["kind"], e["lightmap_caustics"])] = float(e["fetches"])
c = [f[("gi.lightmap_compose", "tex2d_rgba16f_trilinear", k)] for k in ("2500", "10000")]
assert 0 < c[0] == c[1] <= 80 * 60, f
for k in ("2500", "10000"):
    reads = f[("gi.lightmap_caustic_filter", "tex2d_r16f_nearest", k)]
    assert 0 < reads <= (7 * 80 - 12) * (7 * 60 - 12), f
# the UV pass's fragments (counted; the charted geometry, at least the compose's pixels) and the IIM
# blend's two reads per atlas texel (tests/gpu/test_lightmap_work.c): the same view and atlas in both
uv = [f[("gi.lightmap_uv", "raster_r16f_depth_fill", k)] for k in ("2500", "10000")]
assert uv[0] == uv[1] >= c[0], (uv, c)
blend = [f[("gi.lightmap_blend", "tex2d_rgba32f_nearest", k)] for k in ("2500", "10000")]
assert blend[0] == blend[1] > 0 and blend[0] % 2 == 0, blend
# the caustic count's point fragments (counted: one per photon on the screen, so at most the
# budget, and more with 4x the photons) and the cull's tile queries (the dilated tiles' areas:
# the same screen in both rows, at least the screen once) (tests/gpu/test_lightmap_caustics.c)
pts = [f[("gi.lightmap_caustic_count", "raster_r16f_depth_fill", k)] for k in ("2500", "10000")]
assert 0 < pts[0] <= 2500 and pts[0] < pts[1] <= 10000, pts
cull = [f[("gi.lightmap_caustic_cull", "raster_r16f_depth_fill", k)] for k in ("2500", "10000")]
assert cull[0] == cull[1] >= 80 * 60, cull
# the final gather's reduction (counted, tests/gpu/test_lightmap_gather.c): lightmap_gather² tile
# texels per texel gathered, at most lightmap_iim texels a frame; and its draws (counted by
# gather.frag's variant, tests/gpu/test_lightmap_gather_work.c): the tiles' fragments, and an AIM
# lookup for each that is a charted surface's (which texels are gathered, and so what their tiles
# see, follows the worker's priorities: not the same in both rows)
for e in csv.DictReader(open(sys.argv[1])):
    if e["pass"] == "gi.lightmap_gather" and e["kind"] == "tex2d_rgba32f_nearest":
        res2, texels = int(e["lightmap_gather"]) ** 2, float(e["fetches"])
        assert texels % res2 == 0, e
        assert 0 < texels / res2 <= int(e["lightmap_iim"]), e
for k in ("2500", "10000"):
    assert ("gi.lightmap_gather", "tex2d_rgba32f_nearest", k) in f, f
    frags, lookups = f[("gi.lightmap_gather", "raster_r16f_depth_fill", k)], f[("gi.lightmap_gather", "tex2d_rgba16f_trilinear", k)]
    assert 0 < lookups <= frags, (k, frags, lookups)
assert {e[1] for e in f if e[0] == "gi.lightmap_gather"} == {"tex2d_rgba32f_nearest", "raster_r16f_depth_fill",
                                                             "tex2d_rgba16f_trilinear"}, f
PY
# radiosity's bounces (app/gi/radiosity/rad_work.c): one radiance load per link per bounce, so with
# the same links (lockstep: the worker's first link set in both rows) 4 bounces load twice what 2 do
expect_exit 0 "bench --roofline-csv: radiosity at 2 and 4 bounces" sh -c "'$GIKIOSK' bench --scenes cornell \
    --methods radiosity --size 80x60 --frames 1 --warmup 1 --budget radiosity_sync=lockstep \
    --sweep 'radiosity_bounces=2,4' --roofline-csv '$TMP/roofline.csv' --out '$TMP/r' 2>'$TMP/r.log'"
check "radiosity's efficiency.csv: every number recomputed" \
    python3 "$TMP/recompute.py" "$TMP/r/bench.csv" "$TMP/r/efficiency.csv" "$TMP/roofline.csv" radiosity_bounces
check "radiosity_bounce: twice the loads at twice the bounces" python3 - "$TMP/r/efficiency.csv" <<'PY'
import csv, sys
f = {e["radiosity_bounces"]: float(e["fetches"]) for e in csv.DictReader(open(sys.argv[1]))
     if e["pass"] == "gi.radiosity_bounce" and e["kind"] == "ssbo_rgba32f_load"}
assert f["2"] > 0 and f["4"] == 2 * f["2"], f
PY
# ... and its display (rad_work.c; tests/gpu/test_radiosity_work.c counts a lone floor's pixels):
# the mesh's fragments, at the fill rate, the same view and mesh at both bounce counts; drawn
# without culling or depth test, the same surfaces as the G-buffer's, which culls back faces: at
# least the G-buffer's fragments (measured 4606 against 4061 at 80x60)
check "radiosity_display: the mesh's fragments, the same at both bounce counts" python3 - "$TMP/r/efficiency.csv" <<'PY'
import csv, sys
f = {(e["pass"], e["radiosity_bounces"]): (e["kind"], float(e["fetches"])) for e in csv.DictReader(open(sys.argv[1]))}
d = [f[("gi.radiosity_display", b)] for b in ("2", "4")]
assert d[0] == d[1] and d[0][0] == "raster_r16f_depth_fill", d
assert d[0][1] >= f[("gbuffer", "2")][1] > 0, f
PY
# ... and the deep-umbra test against off. `on` reads only its chain of maxima (4 unfiltered
# lookups per level, level 0 and at most one coarser one per VPL whose filtered visibility found
# blockers and is above 0), after the filtered lookups it leaves as they were. Measured on cornell
# at 160x120: filtered counts equal, unfiltered 200106 -> 272882 (+4 x 18194; R16F-nearest since the
# efficiency kinds split by format: 0 -> 72776). `plane` reads the 4 texels' planes
# (RGBA32F here, unfiltered) instead of level 0 of the chain, and the chain only at the kernel's level:
# at 80x60 off / on / plane R16F 0 / 18712 / 2620, RGBA32F 50832 / 50832 / 67000 (+4 x 4042) with
# the visibility per VPL; per VAL (gather.frag VIS_PER_VAL, the default here: 8 VALs, 16 VPLs a
# receiver, every VAL's lookups at every receiver) 0 / 22096 / 4196, 60144 / 60144 / 78380 (+4 x 4559).
# `horizon` (the default since issue 11) reads what `plane` does plus the lookups of the receivers in
# the band below each map's plane, which the others take as lit without one (80x60: RGBA8 16950 ->
# 17130, 16-bit 12522 -> 12657, RGBA32F 67000 -> 67180, R16F 2620 -> 2624, measured with the visibility
# per VPL), so it is not in the equalities below.
expect_exit 0 "bench --roofline-csv: vpl with and without the deep-umbra test" sh -c "'$GIKIOSK' bench \
    --scenes cornell --methods vpl --size 80x60 --frames 1 --warmup 1 --sweep 'vpl_umbra=off,on,plane' \
    --roofline-csv '$TMP/roofline.csv' --out '$TMP/u' 2>'$TMP/u.log'"
check "vpl_gather: the deep-umbra test adds whole unfiltered lookups and no filtered ones" python3 - "$TMP/u/efficiency.csv" <<'PY'
import csv, sys
f = {}
for e in csv.DictReader(open(sys.argv[1])):
    if e["pass"] == "gi.vpl_gather":
        f[(e["vpl_umbra"], e["kind"])] = float(e["fetches"])
u, p = "tex2d_r16f_nearest", "tex2d_rgba32f_nearest"   # the chain is RG16F, the planes RGBA32F
for k in ("tex2d_rgba8_trilinear", "tex2d_rgba16f_trilinear"):
    assert f[("on", k)] == f[("off", k)] == f[("plane", k)] > 0, f
assert f[("on", p)] == f[("off", p)] > 0, f
for mode, kind in (("on", u), ("plane", p)):
    extra = f[(mode, kind)] - f.get(("off", kind), 0.0)
    assert extra > 0 and extra % 4 == 0, (mode, kind, f)
assert f.get(("plane", u), 0.0) % 4 == 0, f
print("# vpl_gather fetches (off / on / plane): R16F %g / %g / %g, RGBA32F %g / %g / %g" % (
    f.get(("off", u), 0.0), f[("on", u)], f.get(("plane", u), 0.0), f[("off", p)], f[("on", p)], f[("plane", p)]))
PY
# the chain of maxima's reduction in gi.vpl_valsm (vpl_work.c vpl_zmax_reads, from the map's size;
# tests/gpu/test_vpl_work.c checks it against val_zmax.frag's counting variant): 13 652 R16F reads a
# 64² map (the default vpl_val_map) under `on` and `plane` alike, none without the test
check "vpl_valsm: the deep-umbra chain's reads, 13652 a map under on and plane, none off" python3 - "$TMP/u/efficiency.csv" <<'PY'
import csv, sys
f = {}
for e in csv.DictReader(open(sys.argv[1])):
    if e["pass"] == "gi.vpl_valsm":
        f[(e["vpl_umbra"], e["kind"])] = float(e["fetches"])
u = "tex2d_r16f_nearest"
assert ("off", u) not in f and ("off", "raster_r16f_depth_fill") in f, f
assert f[("on", u)] == f[("plane", u)] > 0 and f[("on", u)] % 13652 == 0, f
print("# vpl_valsm chain reads (on / plane): %g / %g" % (f[("on", u)], f[("plane", u)]))
PY
# lgv's passes (app/gi/lgv/lgv_work.c), the maps rendered each frame (--rebuild-gi), without and with
# the gathering iterations: the maps' fragments and the lookup's volume reads do not depend on them,
# the gathering's loads grow by 2 x (4 per neighbour pair + 3 per cell), whose pairs and cells must be
# those of a grid of at most 32 cells a side (lgv_size=32); the maps' min mips and the geometry volume
# (tests/gpu/test_lgv.c hand-counts both on the furnace box)
bench_rows lg lgv_iters "lgv with 0 and 2 gathering iterations" --scenes glass --methods lgv \
    --sweep "'lgv_iters=0,2'" --budget lgv_photons=16384 --rebuild-gi
check "lgv: each pass's kinds, the maps and lookup alike in both rows, the gathering's loads a grid's" \
    env PYTHONPATH="$TMP" python3 - "$TMP/lg/efficiency.csv" <<'PY'
import sys
from fetches import by_row
f = by_row(sys.argv[1], "lgv_iters")
assert {k for k in f if k[0].startswith("gi.")} == {
    ("gi.blend_hold", "tex2d_rgba32f_nearest"),
    ("gi.lgv_maps", "raster_r16f_depth_fill"), ("gi.lgv_maps", "image3d_rgba16f_load"),
    ("gi.lgv_gather", "tex2d_r32ui_nearest"), ("gi.lgv_gather", "ssbo_r32ui_atomic"),
    ("gi.lgv_trace", "tex2d_r32ui_nearest"),
    ("gi.lgv_trace", "ssbo_r32ui_atomic"), ("gi.lgv_gather", "ssbo_rgba32f_load"),
    ("gi.lgv_sslgv", "ssbo_r32ui_atomic"), ("gi.lgv_sslgv", "ssbo_rgba32f_load"),
    ("gi.lgv_sslgv", "tex2d_depth32f_nearest"), ("gi.lgv_lookup", "tex3d_rgba16f_trilinear"),
    ("gi.lgv_lookup", "tex2d_rgba16f_trilinear")}, sorted(f)
for k in (("gi.lgv_maps", "raster_r16f_depth_fill"), ("gi.lgv_maps", "image3d_rgba16f_load"),
          ("gi.lgv_lookup", "tex3d_rgba16f_trilinear")):
    assert f[k]["0"] == f[k]["2"] > 0, (k, f[k])
# the min mips: 4 loads per texel of levels 1 and 2 of the 6 faces of each map at lgv_map_res=64
assert f[("gi.lgv_maps", "image3d_rgba16f_load")]["0"] % (4 * 6 * (32 * 32 + 16 * 16)) == 0, f
# the geometry volume, rebuilt with the maps only where the gathering iterates (the occlusion): a
# distance read per texel of the 6 faces of each lattice map (64^2), 3 atomics per texel that sees
# an opaque surface (glass transmits)
reads, atomics = f[("gi.lgv_gather", "tex2d_r32ui_nearest")], f[("gi.lgv_gather", "ssbo_r32ui_atomic")]
assert set(reads) == set(atomics) == {"2"} and reads["2"] % (6 * 64 * 64) == 0, (reads, atomics)
assert 0 < atomics["2"] <= 3 * reads["2"] and atomics["2"] % 3 == 0, (reads, atomics)
# the lookup: 3 volume reads per shaded pixel, at most every pixel of 80x60
look = f[("gi.lgv_lookup", "tex3d_rgba16f_trilinear")]["0"]
assert look % 3 == 0 and look <= 3 * 80 * 60, look
g = f[("gi.lgv_gather", "ssbo_rgba32f_load")]
cells = g["0"] / 6                       # the resolve's and the volume's 3 vec4s a cell
pairs = ((g["2"] - g["0"]) / 2 - 3 * cells) / 4
grids = [(a, b, c) for a in range(1, 33) for b in range(1, 33) for c in range(1, 33)
         if a * b * c == cells and 2 * ((a - 1) * b * c + a * (b - 1) * c + a * b * (c - 1)) == pairs]
assert cells == int(cells) and grids, (g, cells, pairs)
PY
# volcaustics' passes (app/gi/volcaustics/vc_work.c) at two airlight resolutions: the rays (vc_light),
# the lines and the surface splats do not depend on it, the airlight reads each march pixel's G-buffer depth and at most
# one shadow texel per step (48) and light (glass-fog's 2 spots); each ray generation invocation reads
# its own light-view texel, the 2 lights' 256^2 at least, and at most 64 march steps, 32 + 10 glass
# steps and 2 more texels besides
bench_rows vc vc_march "volcaustics at two airlight resolutions" --scenes glass-fog --methods volcaustics \
    --sweep "'vc_march=0.25,0.5'"
check "volcaustics: the rays, lines and splats alike at both airlight resolutions, each count within its bounds" \
    env PYTHONPATH="$TMP" python3 - "$TMP/vc/efficiency.csv" <<'PY'
import sys
from fetches import by_row
f = by_row(sys.argv[1], "vc_march")
rays, lines = f[("gi.vc_light", "tex2d_depth32f_nearest")], f[("gi.vc_lines", "raster_r16f_depth_fill")]
air = f[("gi.vc_airlight", "tex2d_depth32f_nearest")]
splats = f[("gi.vc_surface", "raster_r16f_depth_fill")]
assert rays["0.25"] == rays["0.5"] and lines["0.25"] == lines["0.5"] > 0 and splats["0.25"] == splats["0.5"] > 0, \
    (rays, lines, splats)
texels = 2 * 256 * 256
assert texels <= rays["0.25"] <= texels * (1 + 64 + 32 + 10 + 2), rays
# the light views' fragments (tests/gpu/test_vc_work.c hand-counts them): 3 views of 256^2 per light,
# each filled by the room at least once (measured 552 228 = 1.40 x 3 x 2 x 256^2), alike in both rows
views = f[("gi.vc_light", "raster_r16f_depth_fill")]
assert views["0.25"] == views["0.5"] >= 3 * texels, views
for march, (w, h) in (("0.25", (20, 15)), ("0.5", (40, 30))):
    assert w * h < air[march] <= w * h * (1 + 48 * 2), (march, air)
# the composite (tests/gpu/test_vc_work.c hand-counts it): per pixel of 80x60 two depth reads, one
# bilinear airlight lookup (its image upsampled, whatever its resolution), one lines' texel and one
# surface caustics' texel where a surface is
comp = {k: f[("gi.vc_composite", k)] for k in ("tex2d_depth32f_nearest", "tex2d_rgba16f_trilinear",
                                               "tex2d_rgba32f_nearest")}
for march in ("0.25", "0.5"):
    assert comp["tex2d_depth32f_nearest"][march] == 2 * 80 * 60, comp
    assert comp["tex2d_rgba16f_trilinear"][march] == 80 * 60, comp
    assert 80 * 60 < comp["tex2d_rgba32f_nearest"][march] <= 2 * 80 * 60, comp
PY
# the renderer's own passes (app/render/render_work.c; tests/gpu/test_render_work.c hand-counts
# them): the G-buffer's fragments follow the render size, the compose reads the HDR image once per
# output pixel whatever the render scale (its bilinear upsample); in every run above, every row
# has both, the same in rows that share the view
bench_rows s render_scale "the renderer's passes at two render scales" --scenes cornell --methods none \
    --sweep "'render_scale=0.5,1'"
check "gbuffer and compose: fragments by the render size, lookups by the output size" python3 - $TMP/b $TMP/v $TMP/m \
    $TMP/i $TMP/l $TMP/r $TMP/u $TMP/lg $TMP/vc $TMP/s <<'PY'
import csv, sys
for d in sys.argv[1:]:
    rows = {}
    for e in csv.DictReader(open(d + "/efficiency.csv")):
        if e["pass"] in ("gbuffer", "compose"):
            rows.setdefault(e["pass"], []).append((e["render_scale"], e["kind"], float(e["fetches"])))
    # one of each per row: two rows a run (three in the deep-umbra run)
    assert len(rows["gbuffer"]) == len(rows["compose"]) == (3 if d.endswith("/u") else 2), (d, rows)
    assert all(k == "tex2d_rgba16f_trilinear" and n == 80 * 60 for _, k, n in rows["compose"]), (d, rows)
    assert all(k == "raster_r16f_depth_fill" for _, k, _n in rows["gbuffer"]), (d, rows)
    g = {s: n for s, _, n in rows["gbuffer"]}
    if d.endswith("/s"):
        # half the scale, a quarter of the fragments, up to the pixel centres along the edges:
        # measured 1000 / 4061 = 0.246 (the open box leaves some of the view empty); bound 5x that
        assert g["1"] > 40 * 30 and abs(g["0.5"] / g["1"] - 0.25) < 0.02, g
    else:
        assert len(set(n for _, _, n in rows["gbuffer"])) == 1, (d, rows)
PY
# the shadow maps' depth draws (render_work.c; tests/gpu/test_shadow_map_work.c hand-counts them):
# a shadow sweep renders them every frame; their fragments at the fill rate, the same light's view
# at both sizes, so 4 x the fragments at twice the size, but for the texels whose centres an edge
# crosses (measured 2 805 040 / 699 995 = 4.007 on cornell; bound 0.02, 3 x that); nothing counted
# in the runs above that keep a static scene's maps
bench_rows sm shadow_map "the shadow maps at two sizes" --scenes cornell --methods none \
    --sweep "'shadow_map=512,1024'"
check "shadow.shadow_depth: 4 x the fragments at twice the map size, only where the maps are drawn" \
    env PYTHONPATH="$TMP" python3 - "$TMP/sm/efficiency.csv" $TMP/v $TMP/m $TMP/i $TMP/l $TMP/r $TMP/s <<'PY'
import csv, sys
from fetches import by_row
f = by_row(sys.argv[1], "shadow_map")[("shadow.shadow_depth", "raster_r16f_depth_fill")]
assert f["512"] > 0 and abs(f["1024"] / f["512"] - 4) < 0.02, f
for d in sys.argv[2:]:
    assert not [e for e in csv.DictReader(open(d + "/efficiency.csv")) if e["pass"].startswith("shadow")], d
PY
# the glass pass (render_work.c; tests/gpu/test_render_work.c hand-counts it): per glass fragment
# one depth read, per one in front of the opaque scene two lookups of the image behind, and the copy
# of that image, one lookup a pixel of the render size -- so W x H <= lookups <= W x H + 2 x depth
# reads; at half the scale about a quarter of the fragments (measured 132 / 526 on glass at 80x60,
# 0.251; bound 0.03, the glass sphere's rim pixels at this size); no glass pass on cornell
bench_rows g render_scale "the glass pass at two render scales" --scenes glass --methods none \
    --sweep "'render_scale=0.5,1'"
check "glass: a depth read per fragment, two lookups per visible one and the copy's one a pixel" \
    env PYTHONPATH="$TMP" python3 - "$TMP/g/efficiency.csv" $TMP/s $TMP/sm <<'PY'
import csv, sys
from fetches import by_row
f = by_row(sys.argv[1], "render_scale")
depth, look = f[("glass", "tex2d_depth32f_nearest")], f[("glass", "tex2d_rgba16f_trilinear")]
for scale, (w, h) in (("0.5", (40, 30)), ("1", (80, 60))):
    assert depth[scale] > 0 and w * h < look[scale] <= w * h + 2 * depth[scale], (scale, depth, look)
assert abs(depth["0.5"] / depth["1"] - 0.25) < 0.03, depth
for d in sys.argv[2:]:
    assert not [e for e in csv.DictReader(open(d + "/efficiency.csv")) if e["pass"] == "glass"], d
PY
printf 'name,format,size,fetches,median_ms,fetches_per_s\ntex3d_rgba16f_trilinear,rgba16f,64,1,1,fast\n' >"$TMP/bad.csv"
expect_exit 2 "a roofline.csv with a rate that is not a number" "$GIKIOSK" bench --scenes cornell --methods vct \
    --roofline-csv "$TMP/bad.csv" --out "$TMP/bad"
stderr_has "bad.csv:2: fetches_per_s 'fast'" "the error names the file, line and value"
expect_exit 1 "a roofline.csv that is not there" "$GIKIOSK" bench --roofline-csv "$TMP/none.csv" --out "$TMP/none"
stderr_has "none.csv: cannot read" "the error names the file"
finish
