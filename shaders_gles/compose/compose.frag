// Upscales the HDR image (render_scale < 1) bilinearly to the output and applies the display
// transform. GK_LINEAR_OUT skips exposure and tonemap (linear captures).
// HDR_COUNT_FETCHES: the bench's counting variant (#21, app/render/render_work.c), one atomic add
// per HDR lookup (fragment-stage storage buffers capability-checked by the caller). Never in the
// kiosk's frames.
// @variant -
// @variant GK_LINEAR_OUT
// @variant HDR_COUNT_FETCHES
precision highp float;
#ifdef HDR_COUNT_FETCHES
layout(std430, binding = 6) buffer HdrFetches { highp uint lookups; } hdr_counted;
#endif
#include "common/tonemap.glsl"
in vec2 v_uv;
uniform highp sampler2D u_hdr;
uniform float u_exposure;
out vec4 o_color;
void main()
{
#ifdef HDR_COUNT_FETCHES
    atomicAdd(hdr_counted.lookups, 1u);
#endif
    vec3 c = texture(u_hdr, v_uv).rgb;
#ifdef GK_LINEAR_OUT
    o_color = vec4(c, 1.0);
#else
    o_color = vec4(gk_tonemap(c, u_exposure), 1.0);
#endif
}
