// Display (seed 001 ch. 4, Algorithm 1 step 7): the refined mesh, each vertex fetching its surfel's
// indirect irradiance from the radiosity texture (a vertex texture, core GLES 3.0); interpolated
// across the triangles as the seed's per-vertex colours are.
precision highp float;
precision highp int;
layout(location = 0) in vec3 a_position;   // world (the mesh is built in world space)
uniform mat4 u_viewproj;
uniform highp sampler2D u_irradiance;      // RGBA32F, leaf i at (i % width, i / width)
uniform int u_width;
out vec3 v_irradiance;
out vec3 v_world;

void main()
{
    int i = gl_VertexID;   // indexed draw: the index, which is the vertex's leaf
    v_irradiance = texelFetch(u_irradiance, ivec2(i % u_width, i / u_width), 0).rgb;
    v_world = a_position;
    gl_Position = u_viewproj * vec4(a_position, 1.0);
}
