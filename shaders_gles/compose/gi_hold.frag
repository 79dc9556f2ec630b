// The GI contribution the last frame before a method/budget change showed: shown - (image before
// GI). Held by render_gi_blend.c and faded out over the next frames (compose/gi_blend.frag).
// Signed RGBA16F: a method may darken (vct's compose scales the direct light by its occlusion).
// @variant -
precision highp float;
in vec2 v_uv;
uniform highp sampler2D u_shown;
uniform highp sampler2D u_pre;
out vec4 o_delta;
void main()
{
    o_delta = vec4(texture(u_shown, v_uv).rgb - texture(u_pre, v_uv).rgb, 0.0);
}
