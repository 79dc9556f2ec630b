#!/bin/sh
# The test environment of tests/run.sh: Mesa's shader cache is written under the build tree, never
# into the user's home (a fresh CI machine, a read-only home), and the run really uses it.
. tests/e2e/lib.sh
export EGL_PLATFORM=surfaceless
case ${MESA_SHADER_CACHE_DIR:-} in
"") not_ok "MESA_SHADER_CACHE_DIR is set by tests/run.sh" ;;
*/"$(basename "$BUILD")"/mesa-shader-cache) ok "MESA_SHADER_CACHE_DIR is $MESA_SHADER_CACHE_DIR, in the build tree" ;;
*) not_ok "MESA_SHADER_CACHE_DIR ($MESA_SHADER_CACHE_DIR) is not in the build tree" ;;
esac
expect_exit 0 "a short run" $GIKIOSK run --platform mock --size 32x32 --scenes-dir config/scenes --scene cornell \
    --method none --frames 1
check "Mesa wrote its shader cache there" [ -d "${MESA_SHADER_CACHE_DIR:-/nonexistent}/mesa_shader_cache" ]
finish
