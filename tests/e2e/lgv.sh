#!/bin/sh
# The lgv method as a user runs it: on glass and caustic-ring, on the full GLES path and on
# --gles 3.1, with its passes nested under `gi` in the stats and an HDR capture that is finite.
. tests/e2e/lib.sh
for gles in 3.2 3.1; do
    for scene in glass caustic-ring; do
        d="$TMP/$gles-$scene"
        expect_exit 0 "run lgv on $scene, --gles $gles" "$GIKIOSK" run --platform mock --size 96x72 --scene "$scene" \
            --method lgv --frames 2 --gles "$gles" --budget lgv_photons=16384,lgv_sslgv=128 --capture "$d" --hdr \
            --stats "$d.csv"
        check "$scene --gles $gles: an HDR capture" test -s "$d/000001-$scene-lgv.exr"
        check "$scene --gles $gles: lgv's passes nested under gi" sh -c \
            "head -n 1 '$d.csv' | grep -q 'gi.lgv_maps_ms,gi.lgv_trace_ms,gi.lgv_gather_ms,gi.lgv_sslgv_ms,gi.lgv_lookup_ms'"
        "$GIKIOSK" compare "$d/000001-$scene-lgv.exr" "$d/000001-$scene-lgv.exr" --json >"$TMP/cmp.json"
        check "$scene --gles $gles: no NaN or Inf in the image" grep -q '"nonfinite": 0' "$TMP/cmp.json"
    done
done
expect_exit 2 "an lgv knob value outside its list exits 2" "$GIKIOSK" run --platform mock --size 32x32 --scene glass \
    --method lgv --frames 1 --budget lgv_size=20
stderr_has "lgv_size" "the message names the knob"
finish
