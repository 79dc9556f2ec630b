// HUD overlay: the atlas holds glyph coverage in R (and a solid texel for rectangles); the colour's
// alpha times the coverage is blended over the final image.
precision mediump float;

uniform sampler2D u_atlas;

in vec2 v_uv;
in vec4 v_color;
out vec4 o_color;

void main()
{
    float coverage = texture(u_atlas, v_uv).r;
    o_color = vec4(v_color.rgb, v_color.a * coverage);
}
