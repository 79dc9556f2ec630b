// Cross-fade of the GI contribution after a method/budget change (render_gi_blend.c):
// out = pre + mix(held, cur - pre, t). pre and cur are this frame's image before and after GI (same
// size as the output); held may be from a frame of another render scale (sampled by uv, bilinear).
// @variant -
precision highp float;
in vec2 v_uv;
uniform highp sampler2D u_pre;
uniform highp sampler2D u_cur;
uniform highp sampler2D u_held;
uniform float u_t;
out vec4 o_color;
void main()
{
    vec4 cur = texture(u_cur, v_uv);
    vec3 pre = texture(u_pre, v_uv).rgb;
    vec3 gi = mix(texture(u_held, v_uv).rgb, cur.rgb - pre, u_t);
    o_color = vec4(pre + gi, cur.a);
}
