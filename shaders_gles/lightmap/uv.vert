// Light-map UV pass (app/gi/lightmap/lm_display.c): the scene drawn with its light-map
// coordinates (app/gi/lightmap/lm_atlas.h), so the compose pass knows, per pixel, where in the
// atlas the visible surface's irradiance lies.
precision highp float;
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec2 a_lightmap_uv;
uniform mat4 u_model;
uniform mat4 u_viewproj;
out vec2 v_lightmap_uv;
void main()
{
    v_lightmap_uv = a_lightmap_uv;
    gl_Position = u_viewproj * (u_model * vec4(a_position, 1.0));
}
