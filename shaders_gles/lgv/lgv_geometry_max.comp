// One lattice map's projected areas (lgv_geometry.comp) merged into the geometry volume: the maximum
// over the maps, not the sum, because several maps see the same surface and a sum would count it
// once per map; the most complete single view is a lower bound that never counts a surface twice.
// The map's buffer is cleared for the next map.
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
layout(std430, binding = 1) buffer Tmp { highp uint tmp[]; };
layout(std430, binding = 2) buffer Geo { highp uint geo[]; };
uniform int u_values;         // 3 per geometry cell
void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_values)
        return;
    geo[i] = max(geo[i], tmp[i]);
    tmp[i] = 0u;
}
