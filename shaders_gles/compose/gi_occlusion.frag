// glTF occlusionTexture on the GI methods' indirect light (app/render/render_gi_occlusion.c): the
// GI contribution is the HDR image now minus the image before the method (u_pre), and it is scaled
// by the surface's ao (common/gbuffer.glsl gb_occlusion) with blending (ONE, SRC_ALPHA):
//   hdr' = pre (1 - ao) + hdr ao = pre + ao (hdr - pre)
// so the direct light the image held before GI is left as it was.
// @variant -
precision highp float;
#include "common/gbuffer.glsl"
uniform highp sampler2D u_pre;
out vec4 o_color;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    highp float ao = gb_background(gb_depth(px)) ? 1.0 : gb_occlusion(px);
    o_color = vec4(texelFetch(u_pre, px, 0).rgb * (1.0 - ao), ao);
}
