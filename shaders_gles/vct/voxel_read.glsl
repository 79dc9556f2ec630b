// Reading one voxel of the voxelizer's scratch buffer ("voxel G-buffer", vct/common.glsl channels):
// the means over the fragments averaged into it. Needs `s[]` (the Scratch SSBO) declared before the
// include. Shared by the injection and the second-bounce pass, which must agree on what a voxel is.
vec4 vct_unpack8(uint v) { return vec4(float(v & 0xFFu), float((v >> 8) & 0xFFu), float((v >> 16) & 0xFFu), float(v >> 24)); }

// false for an empty voxel. nrm: the MEAN of the fragments' unit normals, not renormalised (see
// inject.comp); frac: the mean position inside the voxel, [0, 1)^3; emi: emission / u_emission_max.
bool vct_voxel_read(ivec3 c, out vec3 alb, out vec3 nrm, out vec3 frac, out vec3 emi)
{
    int i = vox_index(c), N = vox_count();
    emi = vec3(0.0);
#if AVERAGE_CAS
    uint a = s[CH_ALB * N + i];
    alb = vec3(0.0); nrm = vec3(0.0); frac = vec3(0.0);
    if ((a >> 24) == 0u) return false;
    alb = vct_unpack8(a & 0xFEFEFEFEu).rgb / 255.0;
    nrm = vct_unpack8(s[CH_NRM * N + i] & 0xFEFEFEFEu).rgb / 255.0 * 2.0 - 1.0;
    frac = vct_unpack8(s[CH_POS * N + i] & 0xFEFEFEFEu).rgb / 255.0;
#if EMISSIVE
    emi = vct_unpack8(s[CH_EMI * N + i] & 0xFEFEFEFEu).rgb / 255.0;
#endif
#else
    uint cnt = s[CH_COUNT * N + i] & ~SOLID_BIT;   // fragments only: a solid mark adds none
    alb = vec3(0.0); nrm = vec3(0.0); frac = vec3(0.0);
    if (cnt == 0u) return false;
    float inv = 1.0 / (255.0 * float(cnt));
    alb = vec3(float(s[(CH_ALB + 0) * N + i]), float(s[(CH_ALB + 1) * N + i]), float(s[(CH_ALB + 2) * N + i])) * inv;
    nrm = vec3(float(int(s[(CH_NRM + 0) * N + i])), float(int(s[(CH_NRM + 1) * N + i])), float(int(s[(CH_NRM + 2) * N + i]))) / (127.0 * float(cnt));
    frac = vec3(float(s[(CH_POS + 0) * N + i]), float(s[(CH_POS + 1) * N + i]), float(s[(CH_POS + 2) * N + i])) * inv;
#if EMISSIVE
    emi = vec3(float(s[(CH_EMI + 0) * N + i]), float(s[(CH_EMI + 1) * N + i]), float(s[(CH_EMI + 2) * N + i])) * inv;
#endif
#endif
    return true;
}

// Whether voxel c is opaque: it holds a fragment, or is marked solid behind a surface (vct_thick).
bool vct_voxel_occupied(ivec3 c)
{
#if AVERAGE_CAS
    return (s[CH_ALB * vox_count() + vox_index(c)] >> 24) != 0u;
#else
    return s[CH_COUNT * vox_count() + vox_index(c)] != 0u;
#endif
}
