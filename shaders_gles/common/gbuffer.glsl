// The G-buffer contract (app/gi/gi.h; written by gbuffer/gbuffer.frag), read the same way by direct
// light, vct and vpl. The C side binds it with gk_gbuffer_bind (app/gl/gbuffer_bind.h):
//   u_gb_depth      DEPTH_COMPONENT32F window depth: ndc = (uv, depth) * 2 - 1,
//                   world = u_inv_viewproj * ndc (highp: positions in metres and 32-bit depth)
//   u_gb_albedo     RGBA8: rgb = base colour, a = metallic
//   u_gb_normal     RGBA16F: xyz = world normal, w = roughness
//   u_gb_emission   RGBA16F: rgb = emitted radiance (nits), a > 0.5 = light proxy, else
//                   a = (1 - ao) / 2, ao the occlusionTexture's (gb_occlusion)
//   u_gb_specular   RGBA8: rgb = sqrt(c0) (dielectric F0 colour), a = KHR_materials_specular weight
//   u_inv_viewproj  inverse of the camera's projection * view
//   u_eye           camera position (world)
//   u_viewport      G-buffer size in pixels
// The albedo is 8-bit: mediump suffices and is the default; an includer that has always read it at
// highp (vct) defines GB_ALBEDO_PRECISION highp first (mediump may round k/255 to fp16).
#ifndef GB_ALBEDO_PRECISION
#define GB_ALBEDO_PRECISION mediump
#endif
#include "common/brdf.glsl"

uniform GB_ALBEDO_PRECISION sampler2D u_gb_albedo;
uniform highp sampler2D u_gb_normal;
uniform highp sampler2D u_gb_emission;
uniform highp sampler2D u_gb_depth;
uniform mediump sampler2D u_gb_specular;
uniform highp mat4 u_inv_viewproj;
uniform highp vec3 u_eye;
uniform highp vec2 u_viewport;

highp float gb_depth(ivec2 px) { return texelFetch(u_gb_depth, px, 0).r; }

// Window depth 1 (the clear value): nothing was drawn there.
bool gb_background(highp float depth) { return depth >= 1.0; }

// World position of window point uv (0..1) at window depth `depth`.
highp vec3 gb_world_at(highp vec2 uv, highp float depth)
{
    highp vec4 w = u_inv_viewproj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    return w.xyz / w.w;
}

// World position of pixel px (its centre) from the depth buffer.
highp vec3 gb_world_position(ivec2 px) { return gb_world_at((vec2(px) + 0.5) / u_viewport, gb_depth(px)); }

highp vec3 gb_normal(ivec2 px) { return normalize(texelFetch(u_gb_normal, px, 0).xyz); }
highp float gb_roughness(ivec2 px) { return texelFetch(u_gb_normal, px, 0).w; }
// rgb = base colour, a = metallic
GB_ALBEDO_PRECISION vec4 gb_albedo_metallic(ivec2 px) { return texelFetch(u_gb_albedo, px, 0); }
highp vec4 gb_emission(ivec2 px) { return texelFetch(u_gb_emission, px, 0); }
// glTF occlusionTexture's ambient occlusion at px (1: none), for ambient and indirect light only.
highp float gb_occlusion(ivec2 px)
{
    highp float a = gb_emission(px).a;
    return a > 0.5 ? 1.0 : 1.0 - 2.0 * a; // a light proxy has none
}

// The material at pixel px, as the BRDF takes it (common/brdf.glsl).
gk_brdf_material gb_material(ivec2 px)
{
    gk_brdf_material m;
    highp vec4 a = gb_albedo_metallic(px);
    highp vec4 sp = texelFetch(u_gb_specular, px, 0);
    m.base = a.rgb;
    m.metallic = a.a;
    m.roughness = texelFetch(u_gb_normal, px, 0).w;
    m.spec_weight = sp.a;
    m.c0 = sp.rgb * sp.rgb;
    return m;
}

struct gk_surface {
    highp vec3 p;       // world position
    highp vec3 n;       // unit normal facing the viewer
    highp vec3 v;       // unit direction to the eye
    gk_brdf_material m;
    bool unlit;         // background or light proxy
};

gk_surface gk_read_surface(ivec2 px)
{
    gk_surface s;
    highp float depth = gb_depth(px);
    s.p = gb_world_at((vec2(px) + 0.5) / u_viewport, depth);
    s.n = normalize(texelFetch(u_gb_normal, px, 0).xyz);
    s.v = normalize(u_eye - s.p);
    s.m = gb_material(px);
    s.unlit = gb_background(depth) || gb_emission(px).a > 0.5;
    return s;
}

// The geometric normal (the interpolated vertex normal, before the normal map), facing the viewer
// like gb_normal. A pass that reads it declares GB_GEOM_NORMAL before including this file and binds
// u_gb_geom_normal with gk_gbuffer_bind_geom_normal (the shading normal's texture when the driver
// has no 5th draw buffer). Used where the surface's own plane matters: the shadow receiver offset
// and receiver plane, vct's cone apex and clip plane.
#ifdef GB_GEOM_NORMAL
uniform highp sampler2D u_gb_geom_normal;
highp vec3 gb_geom_normal(ivec2 px) { return normalize(texelFetch(u_gb_geom_normal, px, 0).xyz); }
#endif
