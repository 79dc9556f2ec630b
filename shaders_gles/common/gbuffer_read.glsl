// Reads the G-buffer written by gbuffer/gbuffer.frag and reconstructs the world position from
// depth (highp: positions in metres and 32-bit depth).
uniform mediump sampler2D u_gb_albedo;
uniform highp sampler2D u_gb_normal;
uniform highp sampler2D u_gb_emission;
uniform highp sampler2D u_gb_depth;
uniform highp mat4 u_inv_viewproj;
uniform highp vec3 u_eye;

struct gk_surface {
    highp vec3 p;       // world position
    highp vec3 n;       // unit normal facing the viewer
    highp vec3 v;       // unit direction to the eye
    highp vec3 base;
    highp float metallic;
    highp float roughness;
    bool unlit;         // background or light proxy
};

gk_surface gk_read_surface(ivec2 px, highp vec2 uv)
{
    gk_surface s;
    highp float depth = texelFetch(u_gb_depth, px, 0).r;
    highp vec4 ndc = vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    highp vec4 w = u_inv_viewproj * ndc;
    s.p = w.xyz / w.w;
    mediump vec4 a = texelFetch(u_gb_albedo, px, 0);
    highp vec4 nr = texelFetch(u_gb_normal, px, 0);
    s.n = normalize(nr.xyz);
    s.v = normalize(u_eye - s.p);
    s.base = a.rgb;
    s.metallic = a.a;
    s.roughness = nr.a;
    s.unlit = depth >= 1.0 || texelFetch(u_gb_emission, px, 0).a > 0.5;
    return s;
}
