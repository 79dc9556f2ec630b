// Basis images of one VAL layer from its depth (thesis §6.3.2 / CSSM §5.3): CSSM writes
// cos/sin(c_k z) (RGBA8, stored 0.5 + 0.5·v, an affine code that commutes with box filtering) and
// z·cos/sin(c_k z) (RGBA16F); VSM writes the two moments (z, z²). Mipmapped afterwards.
// @variant CSSM=1
// @variant VIS_VSM=1
precision highp float;
precision highp int;
uniform highp sampler2DArray u_z;
uniform int u_layer;
#ifdef VIS_VSM
layout(location = 0) out vec4 o_moments;
#else
layout(location = 0) out vec4 o_cos;
layout(location = 1) out vec4 o_sin;
layout(location = 2) out vec4 o_zcos;
layout(location = 3) out vec4 o_zsin;
const vec4 C = 3.14159265 * vec4(1.0, 3.0, 5.0, 7.0);
#endif
void main()
{
    float z = texelFetch(u_z, ivec3(ivec2(gl_FragCoord.xy), u_layer), 0).r;
#ifdef VIS_VSM
    o_moments = vec4(z, z * z, 0.0, 0.0);
#else
    vec4 cz = cos(C * z), sz = sin(C * z);
    o_cos = 0.5 + 0.5 * cz;
    o_sin = 0.5 + 0.5 * sz;
    o_zcos = z * cz;
    o_zsin = z * sz;
#endif
}
