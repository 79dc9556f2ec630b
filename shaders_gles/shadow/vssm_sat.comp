// Summed-area tables with EXACT modular integer sums (dong-001.md §1.3 [ours, verified]): values
// are fixed point (v * u_q, u_q = 2^bits - 1, bits = 32 - ceil(log2 of the largest kernel area)),
// and the running sums wrap modulo 2^32 (GLSL ES uint arithmetic). A box sum
//     S(x1,y1) - S(x0,y1) - S(x1,y0) + S(x0,y0)   (mod 2^32)
// is then exact whenever the true box sum fits in 32 bits, which the choice of bits guarantees.
// Built as in the verified probe: a row prefix pass, then a column prefix pass; one invocation
// per row (column) and layer.
//   SAT_BASIS 0: r32ui pair (z, z^2) of the normalised linear depth (VSSM moments; CSSM's <z>);
//                the column pass runs in place (r32ui images may be read-write in GLES 3.1).
//   SAT_BASIS 1: rgba32ui pair (cos(c_k z_c), sin(c_k z_c)), k = 1..4      (CSSM basis, SAT path)
//   SAT_BASIS 2: rgba32ui pair (z_c cos(c_k z_c), z_c sin(c_k z_c))         (CSM-Z basis)
//                z_c = u_range * z; values v in [-1, 1] stored as (v + 1) / 2 (the affine encoding
//                commutes with box filtering). rgba32ui images cannot be read-write, so the
//                column pass reads the row pass's output (bindings 0, 1) and writes bindings 2, 3.
// @variant SAT_ROWS=1 SAT_BASIS=0
// @variant SAT_COLS=1 SAT_BASIS=0
// @variant SAT_ROWS=1 SAT_BASIS=1
// @variant SAT_ROWS=1 SAT_BASIS=2
// @variant SAT_COLS=1 SAT_BASIS=1
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
uniform int u_size;
uniform highp float u_q;
uniform highp float u_range;
const highp vec4 CSSM_C = 3.14159265358979 * vec4(1.0, 3.0, 5.0, 7.0);

#if SAT_BASIS == 0
#if defined(SAT_ROWS)
layout(binding = 0, r32ui) writeonly uniform highp uimage2DArray u_out0;
layout(binding = 1, r32ui) writeonly uniform highp uimage2DArray u_out1;
#else
layout(binding = 0, r32ui) uniform highp uimage2DArray u_out0;
layout(binding = 1, r32ui) uniform highp uimage2DArray u_out1;
#endif
#else
#if defined(SAT_ROWS)
layout(binding = 0, rgba32ui) writeonly uniform highp uimage2DArray u_out0;
layout(binding = 1, rgba32ui) writeonly uniform highp uimage2DArray u_out1;
#else
layout(binding = 0, rgba32ui) readonly uniform highp uimage2DArray u_in0;
layout(binding = 1, rgba32ui) readonly uniform highp uimage2DArray u_in1;
layout(binding = 2, rgba32ui) writeonly uniform highp uimage2DArray u_out0;
layout(binding = 3, rgba32ui) writeonly uniform highp uimage2DArray u_out1;
#endif
#endif

#if defined(SAT_ROWS)
uniform highp sampler2DArray u_z; // normalised linear depth (vssm_linearize.comp)

highp uvec4 enc(highp vec4 v) { return uvec4((v * 0.5 + 0.5) * u_q + 0.5); }

void main()
{
    int row = int(gl_GlobalInvocationID.x), layer = int(gl_GlobalInvocationID.y);
    if (row >= u_size)
        return;
    highp uvec4 a0 = uvec4(0u), a1 = uvec4(0u);
    for (int x = 0; x < u_size; x++) {
        ivec3 p = ivec3(x, row, layer);
        highp float z = texelFetch(u_z, p, 0).r;
#if SAT_BASIS == 0
        a0.x += uint(z * u_q + 0.5);
        a1.x += uint(z * z * u_q + 0.5);
#else
        highp float zc = u_range * z;
        highp vec4 cs = cos(CSSM_C * zc), sn = sin(CSSM_C * zc);
#if SAT_BASIS == 1
        a0 += enc(cs);
        a1 += enc(sn);
#else
        a0 += enc(zc * cs);
        a1 += enc(zc * sn);
#endif
#endif
        imageStore(u_out0, p, a0);
        imageStore(u_out1, p, a1);
    }
}
#else
void main()
{
    int col = int(gl_GlobalInvocationID.x), layer = int(gl_GlobalInvocationID.y);
    if (col >= u_size)
        return;
    highp uvec4 a0 = uvec4(0u), a1 = uvec4(0u);
    for (int y = 0; y < u_size; y++) {
        ivec3 p = ivec3(col, y, layer);
#if SAT_BASIS == 0
        a0 += imageLoad(u_out0, p);
        a1 += imageLoad(u_out1, p);
#else
        a0 += imageLoad(u_in0, p);
        a1 += imageLoad(u_in1, p);
#endif
        imageStore(u_out0, p, a0);
        imageStore(u_out1, p, a1);
    }
}
#endif
