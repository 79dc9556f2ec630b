// Cone tracing through the pre-integrated voxel map (thesis §3.3, Algorithm 1 with the errata of
// summary A.2.7 fixed; the loop is summary A.3). Voxel space [0,1]^3, premultiplied RGBA.
//   ISO_MIPS=1:  one texture with an isotropic mip chain (glGenerateMipmap), the cheapest level.
//   ISO_MIPS=0:  level 0 isotropic (u_vox0, thesis §4: anisotropic level 0 ripples) plus six
//                directional textures +X,-X,+Y,-Y,+Z,-Z holding levels 1.. (u_voxd0..5 level k = lod k+1).
//   AXIS_WEIGHT_SQ=0: thesis sample = sum |d_axis| T_face(axis)  (over-weights diagonals up to 1.73x)
//   AXIS_WEIGHT_SQ=1: weights d_axis^2 (sum 1)  -- not in the thesis, calibrated option.
//   OPACITY_CORRECTION=1: alpha' = 1 - (1 - alpha)^(step / voxel(lod)) -- not in the thesis.
//   CLIP_CONES=1: every cone stops at the volume border (thesis code: only apertures < 0.3; wide
//                 cones keep sampling clamped edge texels, the Fig. 18b banding) -- not in the thesis.
#ifndef CLIP_CONES
#define CLIP_CONES 0
#endif
uniform highp sampler3D u_vox0;
#if !ISO_MIPS
uniform highp sampler3D u_voxd0;
uniform highp sampler3D u_voxd1;
uniform highp sampler3D u_voxd2;
uniform highp sampler3D u_voxd3;
uniform highp sampler3D u_voxd4;
uniform highp sampler3D u_voxd5;
#endif
uniform float u_res_f;      // level-0 resolution
uniform float u_step_mul;   // step = max(diameter * u_step_mul, 1 voxel): 1 = text/Alg. 1, 0.5 = code
uniform float u_ao_lambda;  // AO distance falloff (thesis code: 725, d in voxel-space units)
// Footprint clamp (not in the thesis; gk_vct_options.footprint_clamp): a sample of diameter D is
// read at lod log2(D res), between a level whose texels are <= D and one whose texels are <= 2 D,
// and a trilinear fetch reads texels up to 1.5 texels from its centre: up to 3 D away. So a wide
// cone's coarse samples overlap the receiver's own surface once D > h / 3 (h = height above the
// receiver's tangent plane). The surface then lights itself (isotropic radiance) or shadows itself
// (its dark back), and since h starts at the apex offset, which is in voxels, this begins closer
// to the receiver on finer grids: the Cornell box's error rose with resolution. With c > 0 the
// sample diameter is capped at c h (default c = 1/3), the cone is narrower near its receiver and
// takes smaller steps there. 0: off (thesis).
uniform float u_footprint_clamp;

#if !ISO_MIPS
vec4 dir_sample(vec3 p, vec3 d, float lod)   // constant sampler indices only (GLSL ES rule)
{
#if AXIS_WEIGHT_SQ
    vec3 w = d * d;
#else
    vec3 w = abs(d);
#endif
    vec4 sx = d.x < 0.0 ? textureLod(u_voxd0, p, lod) : textureLod(u_voxd1, p, lod);
    vec4 sy = d.y < 0.0 ? textureLod(u_voxd2, p, lod) : textureLod(u_voxd3, p, lod);
    vec4 sz = d.z < 0.0 ? textureLod(u_voxd4, p, lod) : textureLod(u_voxd5, p, lod);
    return w.x * sx + w.y * sy + w.z * sz;
}
#endif

vec4 vox_sample(vec3 p, vec3 d, float lod)
{
#if ISO_MIPS
    return textureLod(u_vox0, p, lod);
#else
    if (lod <= 0.0) return textureLod(u_vox0, p, 0.0);
    if (lod < 1.0) return mix(textureLod(u_vox0, p, 0.0), dir_sample(p, d, 0.0), lod);
    return dir_sample(p, d, lod - 1.0);
#endif
}

// plane: the receiver's tangent plane (xyz normal, w offset) in voxel space, for the footprint clamp.
// Front-to-back accumulation C += (1 - A) C_s, A += (1 - A) a_s; AO ao += (1 - ao) a_s / (1 + d lambda).
// Returns the premultiplied radiance seen along the cone; ao = accumulated occlusion (0 = open).
vec4 trace_cone(vec3 apex, vec3 d, float aperture, float max_dist, vec4 plane, out float ao, out int steps)
{
    float vs = 1.0 / u_res_f, dst = 0.0, diam = 0.0, ao_acc = 0.0;
    vec4 acc = vec4(0.0);
    steps = 0;
    for (int it = 0; it < 4096; it++) {
        if (acc.a >= 1.0 || dst > max_dist) break;
        vec3 p = apex + d * dst;
        // thesis code: only cones narrower than 0.3 stop at the volume border
        if ((CLIP_CONES != 0 || aperture < 0.3) && (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0))))) break;
        float ds = diam;
        if (u_footprint_clamp > 0.0) ds = min(ds, u_footprint_clamp * max(dot(plane.xyz, p) + plane.w, 0.0));
        float lod = max(log2(ds * u_res_f), 0.0);
        vec4 s = vox_sample(p, d, lod);
        float step_len = max(ds * u_step_mul, vs);
#if OPACITY_CORRECTION
        float a_c = 1.0 - pow(max(1.0 - s.a, 0.0), step_len / (exp2(lod) * vs));
        s = s.a > 1e-6 ? s * (a_c / s.a) : vec4(0.0);
#endif
        acc += (1.0 - acc.a) * s;
        ao_acc += (1.0 - ao_acc) * s.a / (1.0 + dst * u_ao_lambda);
        dst += step_len;
        diam = dst * aperture;
        steps++;
    }
    ao = ao_acc;
    return acc;
}
