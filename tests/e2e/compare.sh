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
finish
