#!/bin/sh
# gikiosk compare end to end: exact zero for a file with itself, the energy ratio of a scaled copy,
# RMSE and the max-error location against idiff (an independent oracle), and the exit codes of
# bad usage and bad files. Test images come from oiiotool (openimageio-tools).
. tests/e2e/lib.sh

# json_field NAME FILE: the raw value of a top-level key of the one-line JSON object.
json_field() { sed -n "s/.*\"$1\": \(\[[^]]*\]\|[^,}]*\).*/\1/p" "$2"; }
# near A B TOL: |A - B| <= TOL
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a != "" && b != "" && d <= t) }'; }

A=$TMP/a.exr; S=$TMP/scaled.exr; N=$TMP/noise.exr
oiiotool --pattern constant:color=0.5,0.25,0.1 64x64 3 -d float -o "$A"
oiiotool "$A" --mulc 1.25 -d float -o "$S"
oiiotool --pattern noise:type=gaussian:mean=0.3:stddev=0.1:seed=3 64x64 3 -d float -o "$N"
oiiotool --pattern constant:color=1,1,1 32x64 3 -d float -o "$TMP/small.exr"
oiiotool --pattern constant:color=1,1,1,1 64x64 4 -d float -o "$TMP/rgba.exr"

# 1. A file with itself: exactly zero error, psnr capped at 999 in JSON, ssim exactly 1.
"$GIKIOSK" compare "$A" "$A" --json >"$TMP/self.json"
check "self compare exits 0" [ $? -eq 0 ]
check "self: rel_rmse is exactly 0" [ "$(json_field rel_rmse "$TMP/self.json")" = 0 ]
check "self: rmse is exactly 0" [ "$(json_field rmse "$TMP/self.json")" = 0 ]
check "self: max_error is exactly 0" [ "$(json_field max_error "$TMP/self.json")" = 0 ]
check "self: psnr prints as 999" [ "$(json_field psnr "$TMP/self.json")" = 999 ]
check "self: ssim is exactly 1" [ "$(json_field ssim "$TMP/self.json")" = 1 ]
check "self: mean_ratio is exactly 1" [ "$(json_field mean_ratio "$TMP/self.json")" = 1 ]
check "self: max_error_at is a 2-array" grep -q '"max_error_at": \[0, 0\]' "$TMP/self.json"
if command -v jq >/dev/null 2>&1; then
    check "self: JSON parses (jq)" sh -c 'jq -e . "$1" >/dev/null' sh "$TMP/self.json"
elif command -v python3 >/dev/null 2>&1; then
    check "self: JSON parses (python3)" sh -c 'python3 -m json.tool "$1" >/dev/null' sh "$TMP/self.json"
else
    ok "self: JSON parses # SKIP no jq or python3"
fi

# 2. A copy scaled by 1.25: mean_ratio 1.25; rel_rmse = 0.25 sqrt(mean r^2) / mean r over the
# channels (0.5, 0.25, 0.1). Float EXR, so the only error is float rounding: 1e-6.
"$GIKIOSK" compare "$A" "$S" --json >"$TMP/scaled.json"
check "scaled: mean_ratio is 1.25" near "$(json_field mean_ratio "$TMP/scaled.json")" 1.25 1e-6
want=$(awk 'BEGIN { printf "%.9g", 0.25 * sqrt((0.25 + 0.0625 + 0.01) / 3) / (0.85 / 3) }')
check "scaled: rel_rmse is $want" near "$(json_field rel_rmse "$TMP/scaled.json")" "$want" 1e-6
check "scaled: ssim below 1" near "$(json_field ssim "$TMP/scaled.json")" 0.5 0.4999

# 3. RMSE and max-error place against idiff -v (it prints 6 significant digits).
idiff -v "$A" "$N" >"$TMP/idiff.txt" 2>&1
"$GIKIOSK" compare "$A" "$N" --json >"$TMP/noise.json"
idiff_rms=$(sed -n 's/.*RMS error = \([0-9.e+-]*\).*/\1/p' "$TMP/idiff.txt")
idiff_at=$(sed -n 's/.*Max error.*@ (\([0-9]*\), \([0-9]*\),.*/[\1, \2]/p' "$TMP/idiff.txt")
echo "# rmse $(json_field rmse "$TMP/noise.json") (idiff $idiff_rms), max at $(json_field max_error_at "$TMP/noise.json") (idiff $idiff_at)"
check "rmse agrees with idiff" near "$(json_field rmse "$TMP/noise.json")" "$idiff_rms" 2e-6
check "max_error_at agrees with idiff" [ "$(json_field max_error_at "$TMP/noise.json")" = "$idiff_at" ]

# 4. Text output: one aligned line per metric, psnr inf for identical images.
"$GIKIOSK" compare "$A" "$A" >"$TMP/self.txt"
check "text: psnr inf" grep -Eq '^psnr +inf dB$' "$TMP/self.txt"
check "text: aligned metric lines" [ "$(grep -Ec '^(rel_rmse|rmse|psnr|ssim|mean_ratio|max_error) +[^ ]' "$TMP/self.txt")" -eq 6 ]
"$GIKIOSK" compare "$A" "$S" --exposure 2 --json >"$TMP/exp.json"
check "--exposure is used" [ "$(json_field exposure "$TMP/exp.json")" = 2 ]

# 5. Errors: exit 2 and a message naming what is wrong.
expect_exit 2 "size mismatch exits 2" "$GIKIOSK" compare "$A" "$TMP/small.exr"
stderr_has "64x64 with 3 channels.*32x64 with 3 channels" "size mismatch names both sizes"
expect_exit 2 "channel mismatch exits 2" "$GIKIOSK" compare "$A" "$TMP/rgba.exr"
stderr_has "64x64 with 4 channels" "channel mismatch names both"
expect_exit 2 "missing file exits 2" "$GIKIOSK" compare "$A" "$TMP/missing.exr"
stderr_has "missing\.exr" "missing file is named"
printf 'not an image at all\n' >"$TMP/corrupt.exr"
expect_exit 2 "corrupt file exits 2" "$GIKIOSK" compare "$TMP/corrupt.exr" "$A"
stderr_has "corrupt\.exr" "corrupt file is named"
expect_exit 2 "one argument exits 2" "$GIKIOSK" compare "$A"
stderr_has "usage: gikiosk compare" "bad usage prints usage"
expect_exit 2 "unknown option exits 2" "$GIKIOSK" compare "$A" "$A" --jsn
stderr_has "unknown option '--jsn'" "unknown option is named"
expect_exit 2 "bad exposure exits 2" "$GIKIOSK" compare "$A" "$A" --exposure zero
expect_exit 0 "--help exits 0" "$GIKIOSK" compare --help

# 6. --mask: metrics inside and outside a mask, on a synthetic pair whose error is known exactly.
# Reference 1 everywhere; the test is 1.5 on the left half (x < 32), the mask's region, and exact on
# the right: inside rel_rmse 0.5 and mean_ratio 1.5, outside exactly 0 and 1, the whole image
# rel_rmse sqrt(0.5 * 0.25) = 0.353553 and mean_ratio 1.25.
R=$TMP/mref.exr; T=$TMP/mtest.exr; M=$TMP/mask.png
oiiotool --pattern constant:color=1,1,1 64x64 3 -d float -o "$R"
# oiiotool --paste: the first image is the foreground, pasted into the second.
oiiotool --pattern constant:color=1.5,1.5,1.5 32x64 3 "$R" --paste +0+0 -d float -o "$T"
oiiotool --pattern constant:color=1,1,1 32x64 3 --pattern constant:color=0,0,0 64x64 3 --paste +0+0 -d uint8 -o "$M"
"$GIKIOSK" compare "$R" "$T" --mask "$M" --json >"$TMP/mask.json"
check "--mask exits 0" [ $? -eq 0 ]
# part NAME: the members of the "NAME": {...} object of the mask report, on one line.
part() { sed -n "s/.*\"$1\": {\([^}]*\)}.*/\1/p" "$TMP/mask.json" >"$TMP/part.json"; echo "$TMP/part.json"; }
whole() { sed 's/, "mask": .*//' "$TMP/mask.json" >"$TMP/whole.json"; echo "$TMP/whole.json"; }
check "mask: whole-image rel_rmse 0.353553" near "$(json_field rel_rmse "$(whole)")" 0.35355339 1e-6
check "mask: whole-image mean_ratio 1.25" near "$(json_field mean_ratio "$(whole)")" 1.25 1e-6
check "mask: 2048 pixels selected" grep -q '"mask": {"file": "[^"]*mask.png", "pixels": 2048' "$TMP/mask.json"
check "mask: inside rel_rmse 0.5" near "$(json_field rel_rmse "$(part inside)")" 0.5 1e-6
check "mask: inside mean_ratio 1.5" near "$(json_field mean_ratio "$(part inside)")" 1.5 1e-6
check "mask: inside max error at [0, 0]" [ "$(json_field max_error_at "$(part inside)")" = "[0, 0]" ]
check "mask: inside pixels 2048" [ "$(json_field pixels "$(part inside)")" = 2048 ]
check "mask: outside rel_rmse exactly 0" [ "$(json_field rel_rmse "$(part outside)")" = 0 ]
check "mask: outside mean_ratio exactly 1" [ "$(json_field mean_ratio "$(part outside)")" = 1 ]
check "mask: outside pixels 2048" [ "$(json_field pixels "$(part outside)")" = 2048 ]
"$GIKIOSK" compare "$R" "$T" --mask "$M" >"$TMP/mask.txt"
check "mask: text has the inside section" grep -q '^inside the mask .*mask.png (2048 pixels):$' "$TMP/mask.txt"
check "mask: text has the outside section" grep -q '^outside the mask (2048 pixels):$' "$TMP/mask.txt"
check "mask: text rel_rmse lines whole/inside/outside" [ "$(grep -c '^rel_rmse' "$TMP/mask.txt")" -eq 3 ]
oiiotool --pattern constant:color=1,1,1 64x64 3 -d uint8 -o "$TMP/all.png"
"$GIKIOSK" compare "$R" "$T" --mask "$TMP/all.png" --json >"$TMP/mask.json"
check "mask selecting everything: outside is null" grep -q '"outside": null}' "$TMP/mask.json"
check "mask selecting everything: inside = whole" near "$(json_field rel_rmse "$(part inside)")" 0.35355339 1e-6
oiiotool --pattern constant:color=0,0,0 64x64 3 -d uint8 -o "$TMP/none.png"
expect_exit 2 "empty mask exits 2" "$GIKIOSK" compare "$R" "$T" --mask "$TMP/none.png"
stderr_has "none\.png selects no pixel" "empty mask is named"
oiiotool --pattern constant:color=1,1,1 32x64 3 -d uint8 -o "$TMP/smallmask.png"
expect_exit 2 "mask of another size exits 2" "$GIKIOSK" compare "$R" "$T" --mask "$TMP/smallmask.png"
stderr_has "smallmask\.png is 32x64, the images are 64x64" "mask size mismatch names both sizes"
expect_exit 2 "missing mask exits 2" "$GIKIOSK" compare "$R" "$T" --mask "$TMP/nomask.png"
stderr_has "nomask\.png" "missing mask is named"
expect_exit 2 "--mask without a file exits 2" "$GIKIOSK" compare "$R" "$T" --mask
finish
