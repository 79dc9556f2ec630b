// volcaustics passes 1a and 1b (research dong-001.md §6.3), from the light:
//   VC_WITH_SPECULAR (1b, front): the nearest surface's normal (turned towards the light) with
//     a = 1 on a mirror, 0.5 on glass, 0 elsewhere, and its optics: a mirror's F0 colour (a = 1), or
//     glass's transmission colour with a = (ior - 1) / 2; the depth attachment holds its depth;
//   VC_BACK_FACES (1b, back): only the specular objects, drawn with the depth test reversed (the
//     farthest surface wins, vc_light.c): where a ray refracted into glass leaves it, and the normal
//     there (turned towards the light, like the front's);
//   VC_NO_SPECULAR (1a): only the depth of the scene WITHOUT the specular objects (they discard),
//     where the light rays leaving them look for their end point p2.
// Specular as the scene features define it (app/scene/features.c): a mirror is metallic > 0.5 with
// roughness < 0.2; glass is transmission > 0.5 with roughness < 0.2 (the tracer's smooth dielectric).
// LIGHTVIEW_COUNT_FRAGMENTS: the bench's counting variant (#21, app/gi/volcaustics/vc_work.c), one
// atomic add per fragment, before any discard (with the atomic the depth test runs after the
// shader: hidden fragments count too), in the bench's untimed frame only.
// @variant VC_NO_SPECULAR
// @variant VC_WITH_SPECULAR
// @variant VC_BACK_FACES
// @variant VC_NO_SPECULAR LIGHTVIEW_COUNT_FRAGMENTS
// @variant VC_WITH_SPECULAR LIGHTVIEW_COUNT_FRAGMENTS
// @variant VC_BACK_FACES LIGHTVIEW_COUNT_FRAGMENTS
precision highp float;
precision highp int;
#ifdef LIGHTVIEW_COUNT_FRAGMENTS
layout(std430, binding = 7) buffer LightViewFragments { highp uint fragments; } lightview_counted;
#endif
in vec3 v_world;
in vec3 v_normal;
uniform vec4 u_base_color;
uniform vec2 u_metallic_roughness;
uniform vec4 u_specular;       // rgb ((ior-1)/(ior+1))^2 specularColorFactor, a specularFactor
uniform vec3 u_emissive;       // declared for draw_scene (gi.h)
uniform int u_mat_flags;
uniform mat4 u_model;          // declared for draw_scene (gi.h); used by lightview.vert
uniform vec2 u_glass;          // KHR_materials_ior's ior, KHR_materials_transmission's factor (gi.h)
uniform vec3 u_light_pos;
layout(location = 0) out vec4 o_nrm;
layout(location = 1) out vec4 o_f0;

const int MAT_LIGHT_PROXY = 4;

void main()
{
#ifdef LIGHTVIEW_COUNT_FRAGMENTS
    atomicAdd(lightview_counted.fragments, 1u);
#endif
    if ((u_mat_flags & MAT_LIGHT_PROXY) != 0)
        discard;
    float metallic = clamp(u_metallic_roughness.x, 0.0, 1.0), rough = clamp(u_metallic_roughness.y, 0.0, 1.0);
    bool mirror = metallic > 0.5 && rough < 0.2;
    bool glass = !mirror && u_glass.y > 0.5 && rough < 0.2;
#ifdef VC_NO_SPECULAR
    if (mirror || glass)
        discard;
#endif
#ifdef VC_BACK_FACES
    if (!mirror && !glass)
        discard;
#endif
    vec3 n = normalize(v_normal);
    if (dot(n, u_light_pos - v_world) < 0.0)
        n = -n;
    // a mirror's F0 of glTF's fresnel_mix (brdf_spec.md): the metal's base colour, the dielectric's weighted c0
    vec3 f0 = mix(clamp(u_specular.a, 0.0, 1.0) * min(u_specular.rgb, vec3(1.0)), u_base_color.rgb, metallic);
    o_nrm = vec4(n * 0.5 + 0.5, mirror ? 1.0 : glass ? 0.5 : 0.0);
    // glass: the colour a refraction passes on (the tracer's base colour) and its ior in [1, 3]
    o_f0 = glass ? vec4(clamp(u_base_color.rgb, 0.0, 1.0), clamp((u_glass.x - 1.0) * 0.5, 0.0, 1.0)) : vec4(f0, 1.0);
}
