// Upscales the HDR image (render_scale < 1) bilinearly to the output and applies the display
// transform. GK_LINEAR_OUT skips exposure and tonemap (linear captures).
// @variant -
// @variant GK_LINEAR_OUT
precision highp float;
#include "common/tonemap.glsl"
in vec2 v_uv;
uniform highp sampler2D u_hdr;
uniform float u_exposure;
out vec4 o_color;
void main()
{
    vec3 c = texture(u_hdr, v_uv).rgb;
#ifdef GK_LINEAR_OUT
    o_color = vec4(c, 1.0);
#else
    o_color = vec4(gk_tonemap(c, u_exposure), 1.0);
#endif
}
