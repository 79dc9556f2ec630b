// PullupEnergy (seed 001 ch. 4, Algorithm 1 step 6; app/gi/radiosity/rad_solve.h): one level of
// the hierarchy per dispatch, leaves up; a node's unshot radiance is its children's weighted by
// their share of its area. Node records come from the pointer-less index arithmetic
// (app/gi/radiosity/rad_tree.h).
precision highp float;
precision highp int;
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Nodes { uvec4 nodes[]; };  // first child, count, area bits, -
layout(std430, binding = 1) buffer Unshot { vec4 unshot[]; };
uniform uint u_first;   // the level's first node
uniform uint u_count;   // its node count

void main()
{
    uint j = gl_GlobalInvocationID.x;
    if (j >= u_count)
        return;
    uint n = u_first + j;
    uvec4 rec = nodes[n];
    float area = uintBitsToFloat(rec.z);
    vec3 s = vec3(0.0);
    for (uint c = rec.x; c < rec.x + rec.y; c++)
        s += unshot[c].rgb * uintBitsToFloat(nodes[c].z);
    unshot[n] = vec4(area > 0.0 ? s / area : vec3(0.0), 0.0);
}
