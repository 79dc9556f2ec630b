// Maximum-depth mip chain of one VAL layer for the deep-umbra test (gather.frag, vpl_umbra=on; not
// in the thesis): r = the largest radial depth under the texel, g = 1 where the map has a gap there
// (a jump between neighbouring texels larger than their own surfaces' slopes explain: a silhouette
// or the sky's edge, which rays can pass through). Level 0 (z, slope) is written by the depth pass
// (val_depth.frag's second output); level 1 takes the gaps from the 4×4 texels of level 0 around
// its children, so jumps across children count too; coarser levels take the maxima of their 2×2
// children. The source level is the texture's base level while this draws (vpl_valmap.c), so
// texelFetch's lod 0 reads it and the level being written is never sampled.
// ZMAX_COUNT_FETCHES: the bench's counting variant (#21, app/gi/vpl/vpl_work.c), one atomic add per
// texel written of the distinct texels it read: at level 1 the 4x4 level-0 texels around its
// children that lie inside the disc (the gap tests' second reads repeat those), at coarser levels
// its 4 children. Fragment-stage storage buffers capability-checked by the caller; never in the
// kiosk's frames.
// @variant -
// @variant ZMAX_COUNT_FETCHES
precision highp float;
precision highp int;
#ifdef ZMAX_COUNT_FETCHES
layout(std430, binding = 6) buffer ZmaxFetches { highp uint texels; } zmax_counted;
#endif
uniform highp sampler2DArray u_zmax;
uniform int u_layer, u_level;
layout(location = 0) out vec4 o_zmax;

ivec3 at(ivec2 p, ivec2 size) { return ivec3(clamp(p, ivec2(0), size - 1), u_layer); }

// Level 0 at texel p (clamped). A texel the paraboloid disc's rim crosses reads as left out (depth
// 1, slope 1), not as a surface or the sky: outside the disc it is no direction at all, and inside
// it holds directions within half a texel's diagonal of the VAL's plane, where the map is wrong:
// triangles reaching over the horizon are rasterised with straight edges and their depth
// interpolated across a stretch the paraboloid bends (on light-leak rim texels held depths of 0.44
// and 0.57 between neighbours at 0.18). Read as they were, those texels made a gap in every kernel
// that reached the rim: on light-leak with vpl_umbra=plane, 83% of the leaked light that remained
// came from such kernels (mean chain level 3.9, a quarter of a 64² map). Light passing there leaves
// the VAL at cos θ ≤ √2·2/res (0.044 at 64²) of its normal.
bool on_rim(ivec2 p, ivec2 size)
{
    ivec3 t = at(p, size);
    vec2 s = (vec2(t.xy) + 0.5) / vec2(size) * 2.0 - 1.0;
    return length(s) + sqrt(2.0) / float(size.x) > 1.0;
}

vec2 level0(ivec2 p, ivec2 size)
{
    return on_rim(p, size) ? vec2(1.0) : texelFetch(u_zmax, at(p, size), 0).rg;
}

// Neighbours a and b (z, slope per texel): a step within 1.5× their slopes is one surface; fp16
// rounds z to 2^-11 relative. On light-leak 1.5 and 3 left the same residue (RMSE 0.0215; 3 moved
// cornell's error by 3e-6), 0.75 flagged surfaces seen obliquely (0.030).
bool gap(vec2 a, vec2 b)
{
    return abs(a.x - b.x) > 1.5 * (a.y + b.y) + ldexp(max(a.x, b.x), -9);
}

void main()
{
    ivec2 size = textureSize(u_zmax, 0).xy;
    ivec2 c = 2 * ivec2(gl_FragCoord.xy);
    float z = 0.0, g = 0.0;
#ifdef ZMAX_COUNT_FETCHES
    uint texels = u_level == 1 ? 0u : 4u;
#endif
    if (u_level == 1) {
        for (int j = -1; j < 3; j++)
            for (int i = -1; i < 3; i++) {
                vec2 a = level0(c + ivec2(i, j), size);
#ifdef ZMAX_COUNT_FETCHES
                texels += on_rim(c + ivec2(i, j), size) ? 0u : 1u;
#endif
                if (i >= 0 && i < 2 && j >= 0 && j < 2)
                    z = max(z, a.x);
                if (i < 2 && gap(a, level0(c + ivec2(i + 1, j), size)))
                    g = 1.0;
                if (j < 2 && gap(a, level0(c + ivec2(i, j + 1), size)))
                    g = 1.0;
            }
    } else {
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++) {
                vec2 a = texelFetch(u_zmax, at(c + ivec2(i, j), size), 0).rg;
                z = max(z, a.x);
                g = max(g, a.y);
            }
    }
#ifdef ZMAX_COUNT_FETCHES
    atomicAdd(zmax_counted.texels, texels);
#endif
    o_zmax = vec4(z, g, 0.0, 0.0);
}
