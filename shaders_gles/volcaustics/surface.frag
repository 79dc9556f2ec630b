// volcaustics surface caustics (surface.vert): a fragment of a ray's point sprite adds to the
// caustic irradiance E of the surface seen at this pixel (G-buffer depth and normal) the ray's flux
// times the normalised 2D Epanechnikov kernel K(d) = 2 / (pi h^2) (1 - d^2 / h^2), d the distance of
// the pixel's surface point from p2 (integral of K over the surface's plane: 1, so the flux is
// kept); nothing where the surface faces away from the arriving light or lies off the disk
// (another surface behind or in front of p2). Additive blending into RGBA32F (RGBA16F without
// EXT_float_blend); composite.frag turns E into radiance with the surface's diffuse albedo.
// SURFACE_COUNT_FRAGMENTS: the bench's counting variant (app/gi/volcaustics/vc_work.c), one atomic
// add per fragment of the sprites, discarded or not. Never in the kiosk's frames.
// @variant -
// @variant SURFACE_COUNT_FRAGMENTS
precision highp float;
precision highp int;
#ifdef SURFACE_COUNT_FRAGMENTS
layout(std430, binding = 6) buffer SurfaceFragments { highp uint fragments; } surface_counted;
#endif
flat in vec3 v_p2;
flat in vec3 v_from;
flat in vec3 v_flux;
flat in float v_h;
uniform highp sampler2D u_depth;     // the G-buffer depth
uniform highp sampler2D u_normal;    // the G-buffer normal (xyz world)
uniform mat4 u_inv_view_proj;
uniform vec2 u_size;
layout(location = 0) out vec4 o_irr;
void main()
{
#ifdef SURFACE_COUNT_FRAGMENTS
    atomicAdd(surface_counted.fragments, 1u);
#endif
    ivec2 px = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(u_depth, px, 0).r;
    if (depth >= 1.0 || v_h <= 0.0)
        discard;
    vec4 c = u_inv_view_proj * vec4(vec3(gl_FragCoord.xy / u_size, depth) * 2.0 - 1.0, 1.0);
    vec3 x = c.xyz / c.w;
    vec3 n = texelFetch(u_normal, px, 0).xyz;
    if (dot(n, v_from) <= 0.0)
        discard;
    vec3 d = x - v_p2;
    float r2 = dot(d, d) / (v_h * v_h);
    if (r2 >= 1.0 || abs(dot(d, n)) > 0.5 * v_h)
        discard;
    o_irr = vec4(v_flux * (2.0 / (3.14159265 * v_h * v_h) * (1.0 - r2)), 0.0);
}
