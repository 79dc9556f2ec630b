// volcaustics pass 1b (and, with VC_NO_SPECULAR, 1a): from the light, the nearest surface's normal
// (turned towards the light) with a = 1 on specular objects, and their F0 colour; the depth
// attachment holds its depth. Pass 1a keeps only the depth of the scene WITHOUT the specular
// objects (they discard), where the reflected rays look for their end point p2.
// Specular as the scene features define it (app/scene/features.c): metallic > 0.5, roughness < 0.2.
// Glass is not followed (one reflection only, as the seed's ring): it is an opaque surface here.
// @variant VC_NO_SPECULAR
// @variant VC_WITH_SPECULAR
precision highp float;
precision highp int;
in vec3 v_world;
in vec3 v_normal;
uniform vec4 u_base_color;
uniform vec2 u_metallic_roughness;
uniform vec4 u_specular;       // rgb ((ior-1)/(ior+1))^2 specularColorFactor, a specularFactor
uniform vec3 u_emissive;       // declared for draw_scene (gi.h)
uniform int u_mat_flags;
uniform mat4 u_model;          // declared for draw_scene (gi.h); used by lightview.vert
uniform vec3 u_light_pos;
layout(location = 0) out vec4 o_nrm;
layout(location = 1) out vec4 o_f0;

const int MAT_LIGHT_PROXY = 4;

void main()
{
    if ((u_mat_flags & MAT_LIGHT_PROXY) != 0)
        discard;
    float metallic = clamp(u_metallic_roughness.x, 0.0, 1.0), rough = clamp(u_metallic_roughness.y, 0.0, 1.0);
    bool specular = metallic > 0.5 && rough < 0.2;
#ifdef VC_NO_SPECULAR
    if (specular)
        discard;
#endif
    vec3 n = normalize(v_normal);
    if (dot(n, u_light_pos - v_world) < 0.0)
        n = -n;
    // F0 of glTF's fresnel_mix (brdf_spec.md): the metal's base colour, the dielectric's weighted c0
    vec3 f0 = mix(clamp(u_specular.a, 0.0, 1.0) * min(u_specular.rgb, vec3(1.0)), u_base_color.rgb, metallic);
    o_nrm = vec4(n * 0.5 + 0.5, specular ? 1.0 : 0.0);
    o_f0 = vec4(f0, 1.0);
}
