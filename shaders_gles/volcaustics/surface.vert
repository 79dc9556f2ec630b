// volcaustics surface caustics under (C) (research dong-001.md §6.1: C holds the surface caustics,
// the seed's [Wyman08b] caustic maps; here the same light rays as the volume caustic): every
// caustic-buffer texel's ray ends on a surface at p2 and deposits there the flux it still carries,
// Phi T(p1, p2). Drawn as glDrawArrays(GL_POINTS, 0, R^2) (gl_VertexID = texel), each a point sprite
// covering the disk of radius h around p2 that surface.frag fills with a normalised kernel. h
// follows the beam's footprint on the surface, |dp2/du x dp2/dv| for one texel step to each
// neighbour (k beams overlap: h = sqrt(k A / pi)), at least VC_SPLAT_MIN_PX pixels and at most
// u_h_max; a ray without valid neighbours gets the least radius.
precision highp float;
precision highp int;
#include "volcaustics/medium.glsl"
uniform highp sampler2D u_p1;
uniform highp sampler2D u_p2;
uniform highp sampler2D u_flux;
uniform int u_res;
uniform mat4 u_view_proj;
uniform float u_px_per_rad;    // pixels per unit of size at distance 1 (the projection's y scale x H / 2)
uniform float u_h_max;         // the largest kernel radius (m)
uniform float u_max_point;     // the driver's largest point size (pixels)
flat out vec3 v_p2;
flat out vec3 v_from;          // direction towards where the ray came from
flat out vec3 v_flux;          // the flux arriving at p2
flat out float v_h;
const float VC_SPLAT_OVERLAP = 16.0;  // k: beams a kernel spans (4, 9, 16: rel. RMSE 0.456, 0.431, 0.407 against the surface caustic on caustic-ring-fog; 16 also hides the dot grid)
const float VC_SPLAT_MIN_PX = 1.5;    // the least radius, in pixels at p2's distance

vec3 neighbour(ivec2 q, ivec2 step, vec3 p2, out bool ok)
{
    ivec2 a = q + step;
    if (a.x >= u_res || a.y >= u_res || texelFetch(u_p1, a, 0).w < 0.5) {
        a = q - step;
        if (a.x < 0 || a.y < 0 || texelFetch(u_p1, a, 0).w < 0.5) {
            ok = false;
            return vec3(0.0);
        }
    }
    ok = true;
    return texelFetch(u_p2, a, 0).xyz - p2;
}

void main()
{
    ivec2 q = ivec2(gl_VertexID % u_res, gl_VertexID / u_res);
    vec4 p1 = texelFetch(u_p1, q, 0);
    vec3 p2 = texelFetch(u_p2, q, 0).xyz;
    v_p2 = p2;
    v_from = normalize(p1.xyz - p2);
    v_flux = texelFetch(u_flux, q, 0).rgb * vc_transmittance(p1.xyz, p2);
    vec4 c = u_view_proj * vec4(p2, 1.0);
    if (p1.w < 0.5 || c.w <= 0.0 || max(v_flux.r, max(v_flux.g, v_flux.b)) <= 0.0) {
        v_h = 0.0;
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);   // outside the clip volume: no fragment
        gl_PointSize = 1.0;
        return;
    }
    float h_min = VC_SPLAT_MIN_PX * c.w / u_px_per_rad;
    bool okx, oky;
    vec3 du = neighbour(q, ivec2(1, 0), p2, okx), dv = neighbour(q, ivec2(0, 1), p2, oky);
    float h = h_min;
    if (okx && oky)
        h = clamp(sqrt(VC_SPLAT_OVERLAP * length(cross(du, dv)) / 3.14159265), h_min, max(u_h_max, h_min));
    v_h = h;
    gl_Position = c;
    gl_PointSize = min(2.0 * h * u_px_per_rad / c.w + 2.0, u_max_point);
}
