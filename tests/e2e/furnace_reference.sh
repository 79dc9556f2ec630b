#!/bin/sh
# The committed furnace references against the closed form (no reference needed): a closed box of
# Lambertian albedo a = 0.5 (KHR_materials_specular specularFactor 0) emitting Le = 1 nit has
# radiance Le / (1 - a) = 2 everywhere; split by path, direct (L E + L D E) = Le (1 + a) = 1.5 and
# indirect (two or more bounces) = Le a^2 / (1 - a) = 0.5. Each image's mean must be that within
# 4 standard errors of the mean: sigma_mean = noise_floor * value / sqrt(pixels) (the floor is the
# per-pixel relative RMSE the renderer measured and stored in the EXR; pixels are independent
# samples). At 160x120 and 128 spp 4 sigma is +-0.0014 on 2 (measured 2.0007): the old BRDF's 2.069 (a GGX lobe
# on top of the Lambert term, albedo above a) fails it by 170 sigma.
. tests/e2e/lib.sh

mean_of() { oiiotool "$1" --printstats 2>/dev/null | sed -n 's/.*Stats Avg: *\([^ ]*\).*/\1/p'; }
meta() { iinfo -v "$1" 2>/dev/null | sed -n "s/.*gikiosk:$2: \"\(.*\)\"/\1/p"; }

for pair in furnace:2 furnace-direct:1.5 furnace-indirect:0.5; do
    name=${pair%%:*}
    want=${pair#*:}
    ref=tests/references/$name.exr
    if [ ! -f "$ref" ]; then
        not_ok "$name.exr is missing (make references)"
        continue
    fi
    mean=$(mean_of "$ref")
    floor=$(meta "$ref" noise_floor)
    size=$(meta "$ref" size)
    verdict=$(awk -v m="$mean" -v w="$want" -v f="$floor" -v s="$size" 'BEGIN {
        split(s, d, "x"); n = d[1] * d[2];
        if (m == "" || f == "" || n <= 0) { print "unreadable"; exit }
        sigma = f * w / sqrt(n);
        dev = m - w; if (dev < 0) dev = -dev;
        printf "%s mean %.5f, expected %s, |diff| %.5f = %.1f sigma_mean (%.5f)\n", (dev <= 4 * sigma ? "ok" : "bad"), m, w, dev, dev / sigma, sigma }')
    echo "# $name: $verdict"
    case $verdict in
        ok*) ok "$name.exr mean is the closed form $want within 4 sigma" ;;
        *) not_ok "$name.exr mean is the closed form $want within 4 sigma ($verdict)" ;;
    esac
done
finish
