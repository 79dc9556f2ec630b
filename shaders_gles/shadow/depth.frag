// Shadow-map depth: only alpha-masked materials (glTF alphaMode MASK) do anything here: where the
// base colour's alpha (factor x texture x COLOR_0) is below the cutoff the surface is not there and
// casts no shadow, as the G-buffer (gbuffer/gbuffer.frag) and the tracer's any-hit test see it.
// Compiled with GK_ALPHA_MASK 1 only for scenes that have such a material (gk_scene_gpu_depth_defines):
// elsewhere the shader stays empty, so no draw pays for a discard (it can cost early depth tests).
// @variant GK_ALPHA_MASK=0
// @variant GK_ALPHA_MASK=1
#ifndef GK_ALPHA_MASK
#define GK_ALPHA_MASK 0
#endif
precision highp float;
in vec2 v_uv;
in vec2 v_uv1;
in float v_alpha;
uniform int u_mat_flags;            // GK_MAT_* in app/render/scene_gpu.h
uniform vec4 u_base_color;
uniform mediump sampler2D u_base_tex;
uniform float u_alpha_cutoff;
uniform vec3 u_tex_xf[14];          // the base colour slot's rows are 0 and 1 (gbuffer.frag)
uniform int u_tex_uv1;
const int MAT_BASE_TEX = 1;
const int MAT_ALPHA_MASK = 256;
void main()
{
#if GK_ALPHA_MASK
    if ((u_mat_flags & MAT_ALPHA_MASK) == 0)
        return;
    float a = u_base_color.a * v_alpha;
    if ((u_mat_flags & MAT_BASE_TEX) != 0) {
        vec3 uv = vec3((u_tex_uv1 & 1) != 0 ? v_uv1 : v_uv, 1.0);
        a *= texture(u_base_tex, vec2(dot(u_tex_xf[0], uv), dot(u_tex_xf[1], uv))).a;
    }
    if (a < u_alpha_cutoff)
        discard;
#endif
}
