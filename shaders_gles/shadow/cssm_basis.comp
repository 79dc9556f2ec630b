// CSSM basis images for the mipmap prefilter (dong-001.md §3.1, §3.2, §3.4 pass L2): from the
// normalised linear depth z (vssm_linearize.comp), z_c = u_range * z (CSSM depth units: the
// Fourier series has period 2 in d - z, so depths are kept inside [0, u_range], u_range < 1), and
//   CSSM_PASS 0:  cos(c_k z_c), sin(c_k z_c), z_c cos(c_k z_c), z_c sin(c_k z_c)   (k = 1..4, c_k = pi (2k-1))
//   CSSM_PASS 1:  z_c (the "z/2" basis of Eq. 5.11, stored as z_c)
// into RGBA16F arrays (rgba16f is a GLES 3.1 image format; 4 image units per pass, the GLES 3.1
// minimum, hence two passes), then mipmapped by glGenerateMipmap. Values are computed in fp32;
// fp16 storage keeps ~2^-11 relative, enough after the 1/c_k weights (dong-001.md §7.4).
// @variant CSSM_PASS=0
// @variant CSSM_PASS=1
precision highp float;
precision highp int;
layout(local_size_x = 8, local_size_y = 8) in;
uniform highp sampler2DArray u_z;
uniform int u_size;
uniform highp float u_range;
const highp vec4 CSSM_C = 3.14159265358979 * vec4(1.0, 3.0, 5.0, 7.0);
#if CSSM_PASS == 0
layout(binding = 0, rgba16f) writeonly uniform highp image2DArray u_cos;
layout(binding = 1, rgba16f) writeonly uniform highp image2DArray u_sin;
layout(binding = 2, rgba16f) writeonly uniform highp image2DArray u_zcos;
layout(binding = 3, rgba16f) writeonly uniform highp image2DArray u_zsin;
#else
layout(binding = 0, rgba16f) writeonly uniform highp image2DArray u_zc;
#endif

void main()
{
    ivec3 g = ivec3(gl_GlobalInvocationID);
    if (g.x >= u_size || g.y >= u_size)
        return;
    highp float zc = u_range * texelFetch(u_z, g, 0).r;
#if CSSM_PASS == 0
    highp vec4 cs = cos(CSSM_C * zc), sn = sin(CSSM_C * zc);
    imageStore(u_cos, g, cs);
    imageStore(u_sin, g, sn);
    imageStore(u_zcos, g, zc * cs);
    imageStore(u_zsin, g, zc * sn);
#else
    imageStore(u_zc, g, vec4(zc, 0.0, 0.0, 1.0));
#endif
}
