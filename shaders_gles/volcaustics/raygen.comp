// volcaustics pass 2, light-ray generation into the volume caustic buffer (research §6.3): one
// invocation per light-view texel. Where the light's nearest surface is specular, the light ray
// leaves it as the seed has it, p1 being where it leaves the specular object:
//   a mirror: one reflection (the seed's ring), p1 the reflection point;
//   glass: two refractions (the seed's Buddha, after [Hu07]'s image-space method): refracted into the
//     glass at the front surface p0 (pass 1b front), the ray's exit p1 is found by marching it
//     through the depth of the specular objects' back faces (pass 1b back: the first point no longer
//     in front of them, then bisection), refracted out with the back face's normal there; total
//     internal reflection ends the ray (no line). Fresnel transmittance (the exact dielectric
//     Fresnel, as the tracer's gk_fresnel_dielectric) at both surfaces and the glass's colour twice.
// Its end p2 is found by marching the ray through the light-view depth of the scene WITHOUT the
// specular objects (pass 1a, the seed's image-space search); a ray that leaves the light's view
// without a hit ends where it leaves the scene's box (the seed: "a large bounding sphere"; the box
// is tighter for rooms).
// Each texel's line carries the flux of its beam, Phi = I(w) dOmega_texel F T(s, p1): the spot's
// intensity in its direction, the texel's solid angle, the mirror's Schlick Fresnel of its F0 colour
// or the glass's two transmittances, and the medium's transmittance from the light to p1 (through
// p0). Outputs (rgba32f images, core in 3.1 for compute): p1 (w = 1 valid), p2, flux.
// RAYGEN_COUNT_FETCHES: the bench's counting variant (app/gi/volcaustics/vc_work.c): the light
// views' depth texels each invocation read (its own texel's, the march's and the glass exit's),
// added to RaygenFetches once. Never in the kiosk's frames.
// @variant -
// @variant RAYGEN_COUNT_FETCHES
precision highp float;
precision highp int;
layout(local_size_x = 8, local_size_y = 8) in;
#include "volcaustics/medium.glsl"
#ifdef RAYGEN_COUNT_FETCHES
layout(std430, binding = 6) buffer RaygenFetches { highp uint fetches; } raygen_counted;
highp uint g_depth_fetches = 0u;
#define RAYGEN_COUNT() g_depth_fetches++
#else
#define RAYGEN_COUNT()
#endif
uniform highp sampler2D u_depth_all;     // pass 1b depth
uniform highp sampler2D u_depth_nospec;  // pass 1a depth
uniform highp sampler2D u_nrm;           // pass 1b normal + specular flag
uniform highp sampler2D u_f0;            // pass 1b F0 colour (mirror) or colour + ior (glass)
uniform highp sampler2D u_depth_back;    // pass 1b back faces: depth
uniform highp sampler2D u_nrm_back;      // pass 1b back faces: normal
layout(rgba32f, binding = 0) writeonly uniform highp image2D u_p1;
layout(rgba32f, binding = 1) writeonly uniform highp image2D u_p2;
layout(rgba32f, binding = 2) writeonly uniform highp image2D u_flux;
uniform int u_res;
uniform mat4 u_light_vp;
uniform mat4 u_light_inv_vp;
uniform vec3 u_light_pos;
uniform vec3 u_light_fwd;       // the light view's axis (world)
uniform vec3 u_light_axis;      // the spot's axis (world)
uniform vec3 u_radiant;         // colour * intensity (cd)
uniform vec2 u_cone;            // cos(outer), cos(inner); spot only
uniform int u_spot;
uniform float u_texel_omega0;   // solid angle of a texel on the view axis, (2 tan(fov/2) / res)^2
uniform vec3 u_scene_min;
uniform vec3 u_scene_max;
uniform int u_steps;            // march steps for p2
uniform int u_glass_steps;      // march steps for a refracted ray's exit
uniform float u_spec_extent;    // the specular objects' bounding diameter (m): the longest path inside

vec3 world_of(vec2 uv, float depth)
{
    vec4 c = u_light_inv_vp * vec4(vec3(uv, depth) * 2.0 - 1.0, 1.0);
    return c.xyz / c.w;
}

// Exit distance of o + t d from the scene's box (o inside or on it).
float box_exit(vec3 o, vec3 d)
{
    vec3 inv = 1.0 / d;
    vec3 ta = (u_scene_min - o) * inv, tb = (u_scene_max - o) * inv;
    vec3 hi = max(ta, tb);
    return max(min(min(hi.x, hi.y), hi.z), 0.0);
}

// Is world point x behind the pass-1a depth (inside the light's view)? -1 outside the view.
float behind(vec3 x)
{
    vec4 c = u_light_vp * vec4(x, 1.0);
    if (c.w <= 0.0)
        return -1.0;
    vec3 ndc = c.xyz / c.w;
    if (any(greaterThan(abs(ndc), vec3(1.0))))
        return -1.0;
    RAYGEN_COUNT();
    float d = texture(u_depth_nospec, ndc.xy * 0.5 + 0.5).r;
    return (ndc.z * 0.5 + 0.5) > d + 1e-5 ? 1.0 : 0.0;
}

// Is world point x in front of the specular objects' back faces (inside or before them)? Outside the
// light's view: no.
bool before_back(vec3 x)
{
    vec4 c = u_light_vp * vec4(x, 1.0);
    if (c.w <= 0.0)
        return false;
    vec3 ndc = c.xyz / c.w;
    if (any(greaterThan(abs(ndc), vec3(1.0))))
        return false;
    RAYGEN_COUNT();
    return (ndc.z * 0.5 + 0.5) < texture(u_depth_back, ndc.xy * 0.5 + 0.5).r;
}

// The tracer's exact dielectric Fresnel reflectance (app/ref/materials.c), eta = eta_t / eta_i.
float fresnel_dielectric(float cos_i, float eta)
{
    float sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0)
        return 1.0;
    float cos_t = sqrt(1.0 - sin2_t);
    float rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    float rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

// Two refractions through the glass entered at p0 (normal n towards the light, wi the light's
// direction of travel): false on total internal reflection. Out: the exit p1, the direction after
// it and the transmitted share (Fresnel x colour, twice).
bool refract_through(vec3 p0, vec3 n, vec3 wi, float cos_i, vec4 optics, out vec3 p1, out vec3 dir, out vec3 share)
{
    float ior = 1.0 + 2.0 * optics.a;
    vec3 t = refract(wi, n, 1.0 / ior);
    float t_end = u_spec_extent, dt = t_end / float(u_glass_steps), a = 0.0, b = t_end;
    for (int i = 1; i <= u_glass_steps; i++) {
        if (!before_back(p0 + t * (dt * float(i)))) {
            a = dt * float(i - 1);
            b = dt * float(i);
            break;
        }
    }
    for (int k = 0; k < 10; k++) {
        float m = 0.5 * (a + b);
        if (before_back(p0 + t * m))
            a = m;
        else
            b = m;
    }
    p1 = p0 + t * b;
    vec4 c = u_light_vp * vec4(p1, 1.0);
    vec3 n1 = normalize(texture(u_nrm_back, c.xy / c.w * 0.5 + 0.5).xyz * 2.0 - 1.0);
    if (dot(n1, t) > 0.0)
        n1 = -n1;                   // facing the ray, inside the glass
    float cos1 = -dot(t, n1);
    dir = refract(t, n1, ior);
    if (dot(dir, dir) < 0.5)
        return false;               // total internal reflection
    share = optics.rgb * optics.rgb * (1.0 - fresnel_dielectric(cos_i, ior)) *
            (1.0 - fresnel_dielectric(cos1, 1.0 / ior));
    return true;
}

void raygen_texel()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (q.x >= u_res || q.y >= u_res)
        return;
    vec4 nf = texelFetch(u_nrm, q, 0);
    float depth = texelFetch(u_depth_all, q, 0).r;
    RAYGEN_COUNT();
    if (nf.a < 0.25 || depth >= 1.0) {   // a: 1 mirror, 0.5 glass, 0 other (lightview.frag)
        imageStore(u_p1, q, vec4(0.0));
        return;
    }
    vec2 uv = (vec2(q) + 0.5) / float(u_res);
    vec3 p1 = world_of(uv, depth);
    vec3 n = normalize(nf.xyz * 2.0 - 1.0);
    vec3 wi = normalize(p1 - u_light_pos);          // the light's direction of travel
    float cos_i = dot(-wi, n);
    if (cos_i <= 0.0) {
        imageStore(u_p1, q, vec4(0.0));
        return;
    }
    vec4 optics = texelFetch(u_f0, q, 0);
    vec3 p0 = p1, r, share;
    if (nf.a > 0.75) {
        r = reflect(wi, n);
        share = optics.rgb + (1.0 - optics.rgb) * pow(1.0 - cos_i, 5.0);   // Schlick, the mirror's F0
    } else if (!refract_through(p0, n, wi, cos_i, optics, p1, r, share)) {
        imageStore(u_p1, q, vec4(0.0));
        return;
    }
    // p2: march the ray to the box exit through pass 1a's depth, then bisect the step
    float t_end = box_exit(p1, r), t_prev = 0.0, t_hit = t_end;
    float dt = t_end / float(u_steps);
    for (int i = 1; i <= u_steps; i++) {
        float t = dt * float(i);
        if (behind(p1 + r * t) > 0.5) {
            float a = t_prev, b = t;
            for (int k = 0; k < 8; k++) {
                float m = 0.5 * (a + b);
                if (behind(p1 + r * m) > 0.5)
                    b = m;
                else
                    a = m;
            }
            t_hit = b;
            break;
        }
        t_prev = t;
    }
    vec3 p2 = p1 + r * t_hit;
    // the beam's flux
    float c_view = max(dot(wi, u_light_fwd), 1e-4);
    float omega = u_texel_omega0 * c_view * c_view * c_view;
    float spot = 1.0;
    if (u_spot == 1) {
        float t = clamp((dot(wi, u_light_axis) - u_cone.x) / max(u_cone.y - u_cone.x, 1e-4), 0.0, 1.0);
        spot = t * t;
    }
    vec3 flux = u_radiant * spot * omega * share * vc_transmittance(u_light_pos, p0) * vc_transmittance(p0, p1);
    imageStore(u_p1, q, vec4(p1, spot > 0.0 ? 1.0 : 0.0));
    imageStore(u_p2, q, vec4(p2, 0.0));
    imageStore(u_flux, q, vec4(flux, 0.0));
}

void main()
{
    raygen_texel();
#ifdef RAYGEN_COUNT_FETCHES
    atomicAdd(raygen_counted.fetches, g_depth_fetches);
#endif
}
