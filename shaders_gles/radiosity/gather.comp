// ComputeIlluminateLeafNodes (seed 001 ch. 4, Algorithm 1 step 5; app/gi/radiosity/rad_solve.h):
// each leaf gathers the unshot radiance of the nodes its links name, weighted by the links'
// weights (irradiance per unit radiance, rad_links.h), accumulates the irradiance it shows and
// keeps rho/pi of it as its own unshot radiance for the next bounce. Four storage blocks: the GLES
// 3.1 floor for compute shaders.
precision highp float;
precision highp int;
layout(local_size_x = 64) in;

struct rad_leaf {
    uint first, end;        // its links: [first, end)
    uint pad0, pad1;
    vec4 albedo;            // rho (rgb)
    vec4 irradiance;        // E_ind accumulated over the bounces (rgb)
};
layout(std430, binding = 0) readonly buffer Links { uvec2 links[]; };   // x: node, y: weight bits
layout(std430, binding = 1) buffer Leaves { rad_leaf leaves[]; };
layout(std430, binding = 2) readonly buffer UnshotIn { vec4 unshot_in[]; };
layout(std430, binding = 3) writeonly buffer UnshotOut { vec4 unshot_out[]; };
uniform uint u_leaves;
uniform int u_first_bounce;   // 1: the irradiance starts over

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_leaves)
        return;
    rad_leaf l = leaves[i];
    vec3 E = vec3(0.0);
    for (uint k = l.first; k < l.end; k++) {
        uvec2 link = links[k];
        E += uintBitsToFloat(link.y) * unshot_in[link.x].rgb;
    }
    leaves[i].irradiance = vec4(u_first_bounce != 0 ? E : l.irradiance.rgb + E, 1.0);
    unshot_out[i] = vec4(l.albedo.rgb * (1.0 / 3.14159265358979) * E, 0.0);
}
