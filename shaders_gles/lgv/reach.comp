// Each refractor map's reach (trace.comp within_reach): the largest distance its level 0 holds over
// its six faces, as float bits (distances are >= 0, so their bits order as unsigned integers; an
// empty texel, LGV_FAR, leaves a reach that bounds nothing useful, still a bound). Every surface the
// map holds lies within it: a point of a ray farther from the map's centre is in front of them all.
precision highp float;
precision highp int;
layout(local_size_x = 8, local_size_y = 8) in;
layout(r32ui, binding = 0) readonly uniform highp uimage2DArray u_src;
layout(std430, binding = 6) buffer Reach { highp uint reach[]; };   // one per refractor map, zeroed
uniform int u_res;
uniform int u_first_layer;   // 6 x the first refractor map
void main()
{
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (p.x >= u_res || p.y >= u_res)
        return;
    atomicMax(reach[p.z / 6], imageLoad(u_src, ivec3(p.xy, u_first_layer + p.z)).r);
}
