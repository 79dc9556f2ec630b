// Caustic counting (seed 004 §5, app/gi/lightmap/lm_caustic_gpu.c): every caustic photon drawn as
// one point (GLES requires gl_PointSize to be written) where it projects.
precision highp float;
layout(location = 0) in vec3 a_position;
uniform mat4 u_viewproj;
out vec3 v_world;
void main()
{
    v_world = a_position;
    gl_Position = u_viewproj * vec4(a_position, 1.0);
    gl_PointSize = 1.0;
}
