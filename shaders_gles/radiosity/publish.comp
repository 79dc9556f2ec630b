// The leaves' indirect irradiance into the texture the display's vertex shader reads (a vertex
// texture fetch: GLES 3.1 need not offer storage blocks to vertex shaders). RGBA32F images are
// write-only on the 3.1 floor, which is all this needs.
precision highp float;
precision highp int;
layout(local_size_x = 64) in;

struct rad_leaf {
    uint first, end;
    uint pad0, pad1;
    vec4 albedo;
    vec4 irradiance;
};
layout(std430, binding = 1) readonly buffer Leaves { rad_leaf leaves[]; };
layout(rgba32f, binding = 0) writeonly uniform highp image2D u_out;
uniform uint u_leaves;
uniform int u_width;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_leaves)
        return;
    imageStore(u_out, ivec2(int(i) % u_width, int(i) / u_width), vec4(leaves[i].irradiance.rgb, 1.0));
}
