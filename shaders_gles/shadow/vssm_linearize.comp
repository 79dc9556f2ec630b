// Prefilter pass 1 of VSSM / CSSM (app/render/shadow/shadow_prefilter.c): the shared depth map
// (DEPTH_COMPONENT32F window depth) converted to linear depth along the face axis, normalised to
// [0, 1] over [near, far]:  z = (lin - near) / (far - near).  Written into level 0 of an R32F
// array (u_zmin); with WITH_MAX also into u_zmax, the level 0 of the min-max pyramid (HSM).

// @variant WITH_MAX=1
precision highp float;
precision highp int;
layout(local_size_x = 8, local_size_y = 8) in;
uniform highp sampler2DArray u_depth;
layout(binding = 0, r32f) writeonly uniform highp image2DArray u_zmin;
#if defined(WITH_MAX)
layout(binding = 1, r32f) writeonly uniform highp image2DArray u_zmax;
#endif
uniform highp vec3 u_proj; // near, far, ortho (0/1)
uniform int u_size;

void main()
{
    ivec3 g = ivec3(gl_GlobalInvocationID);
    if (g.x >= u_size || g.y >= u_size)
        return;
    highp float w = texelFetch(u_depth, g, 0).r;
    highp float n = u_proj.x, f = u_proj.y;
    highp float lin = u_proj.z > 0.5 ? n + w * (f - n) : 2.0 * f * n / ((f + n) - (w * 2.0 - 1.0) * (f - n));
    highp float z = clamp((lin - n) / (f - n), 0.0, 1.0);
    imageStore(u_zmin, g, vec4(z));
#if defined(WITH_MAX)
    imageStore(u_zmax, g, vec4(z));
#endif
}
