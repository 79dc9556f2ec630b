// Shadow-map depth: only alpha-masked materials (glTF alphaMode MASK) do anything here: where the
// base colour's alpha (factor x texture x COLOR_0) is below the cutoff the surface is not there and
// casts no shadow, as the G-buffer (gbuffer/gbuffer.frag) and the tracer's any-hit test see it.
precision highp float;
in vec2 v_uv;
in vec2 v_uv1;
in float v_alpha;
uniform int u_mat_flags;            // GK_MAT_* in app/render/scene_gpu.h
uniform vec4 u_base_color;
uniform mediump sampler2D u_base_tex;
uniform float u_alpha_cutoff;
uniform vec3 u_tex_xf[12];          // the base colour slot's rows are 0 and 1 (gbuffer.frag)
uniform int u_tex_uv1;
const int MAT_BASE_TEX = 1;
const int MAT_ALPHA_MASK = 256;
void main()
{
    if ((u_mat_flags & MAT_ALPHA_MASK) == 0)
        return;
    float a = u_base_color.a * v_alpha;
    if ((u_mat_flags & MAT_BASE_TEX) != 0) {
        vec3 uv = vec3((u_tex_uv1 & 1) != 0 ? v_uv1 : v_uv, 1.0);
        a *= texture(u_base_tex, vec2(dot(u_tex_xf[0], uv), dot(u_tex_xf[1], uv))).a;
    }
    if (a < u_alpha_cutoff)
        discard;
}
