// Maximum-depth mip chain of one VAL layer for the deep-umbra test (gather.frag, vpl_umbra=on; not
// in the thesis): r = the largest radial depth under the texel, g = 1 where the map has a gap there
// (a jump between neighbouring texels larger than their own surfaces' slopes explain: a silhouette
// or the sky's edge, which rays can pass through). Level 0 (z, slope) is written by the depth pass
// (val_depth.frag's second output); level 1 takes the gaps from the 4×4 texels of level 0 around
// its children, so jumps across children count too; coarser levels take the maxima of their 2×2
// children. The source level is the texture's base level while this draws (vpl_valmap.c), so
// texelFetch's lod 0 reads it and the level being written is never sampled.
precision highp float;
precision highp int;
uniform highp sampler2DArray u_zmax;
uniform int u_layer, u_level;
layout(location = 0) out vec4 o_zmax;

ivec3 at(ivec2 p, ivec2 size) { return ivec3(clamp(p, ivec2(0), size - 1), u_layer); }

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
    if (u_level == 1) {
        for (int j = -1; j < 3; j++)
            for (int i = -1; i < 3; i++) {
                vec2 a = texelFetch(u_zmax, at(c + ivec2(i, j), size), 0).rg;
                if (i >= 0 && i < 2 && j >= 0 && j < 2)
                    z = max(z, a.x);
                if (i < 2 && gap(a, texelFetch(u_zmax, at(c + ivec2(i + 1, j), size), 0).rg))
                    g = 1.0;
                if (j < 2 && gap(a, texelFetch(u_zmax, at(c + ivec2(i, j + 1), size), 0).rg))
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
    o_zmax = vec4(z, g, 0.0, 0.0);
}
