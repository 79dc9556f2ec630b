// The depth maps shared by the shadow methods (app/render/shadow/shadow_depth.c): a 2D array of
// DEPTH_COMPONENT32F layers, 1 for spot/disc/rect (perspective from the light centre along -Z)
// and directional (orthographic) lights, 6 for point/sphere/rect/disc lights (cube faces
// +u -u +v -v +dir -dir in the light's frame u_shadow_basis; layer 4 looks along the light's axis). Depth is sampled raw (no compare mode, NEAREST) and converted to
// linear depth along the face axis.
uniform highp sampler2DArray u_shadow_map;
uniform highp mat4 u_shadow_viewproj[6];
uniform highp mat4 u_shadow_inv_viewproj[6];
uniform highp vec3 u_shadow_pos;      // light centre; ortho: the map's eye point
uniform highp vec3 u_shadow_axis;     // map axis for 1-layer maps
uniform highp mat3 u_shadow_basis;    // columns: light u, v, dir (cube face axes)
uniform highp vec4 u_shadow_proj;     // near, far, ortho (0/1), layers (1/6)
uniform highp vec4 u_shadow_light;    // size_u, size_v (m; ortho: 2 tan(sun radius)), tan half fov (ortho: half extent m), map size

struct gk_shadow_coord {
    highp vec2 uv;
    highp float layer;
    highp float d;          // receiver linear depth along the face axis
    bool inside;            // within the map's frustum
};

highp vec3 gk_cube_axis(int f)
{
    return u_shadow_basis[f / 2] * ((f % 2 == 0) ? 1.0 : -1.0);
}

int gk_shadow_face(highp vec3 p)
{
    if (u_shadow_proj.w < 2.0)
        return 0;
    highp vec3 d = (p - u_shadow_pos) * u_shadow_basis; // light-frame coordinates
    highp vec3 ad = abs(d);
    if (ad.x >= ad.y && ad.x >= ad.z)
        return d.x >= 0.0 ? 0 : 1;
    if (ad.y >= ad.z)
        return d.y >= 0.0 ? 2 : 3;
    return d.z >= 0.0 ? 4 : 5;
}

highp float gk_shadow_linear(highp float window_depth)
{
    highp float n = u_shadow_proj.x, f = u_shadow_proj.y;
    if (u_shadow_proj.z > 0.5)
        return n + window_depth * (f - n);
    highp float z_ndc = window_depth * 2.0 - 1.0;
    return 2.0 * f * n / ((f + n) - z_ndc * (f - n));
}

// World size of one texel at linear depth d.
highp float gk_shadow_texel_world(highp float d)
{
    highp float extent = u_shadow_proj.z > 0.5 ? 2.0 * u_shadow_light.z : 2.0 * d * u_shadow_light.z;
    return extent / u_shadow_light.w;
}

gk_shadow_coord gk_shadow_project(highp vec3 p)
{
    gk_shadow_coord c;
    int f = gk_shadow_face(p);
    highp vec4 clip = u_shadow_viewproj[f] * vec4(p, 1.0);
    highp vec3 ndc = clip.xyz / clip.w;
    c.uv = ndc.xy * 0.5 + 0.5;
    c.layer = float(f);
    highp vec3 axis = u_shadow_proj.w > 1.5 ? gk_cube_axis(f) : u_shadow_axis;
    c.d = dot(p - u_shadow_pos, axis);
    c.inside = clip.w > 0.0 && all(greaterThanEqual(c.uv, vec2(0.0))) && all(lessThanEqual(c.uv, vec2(1.0))) &&
               c.d > u_shadow_proj.x && c.d < u_shadow_proj.y;
    return c;
}

// The bench's counting variant (#21, app/render/render_work.c): with SHADOW_COUNT_FETCHES the shadow
// lookups add up their fetches per pixel by the texture's format, each the roofline's kind of the
// same name -- unfiltered: the depth map, R32F (VSSM's min/max mips, CSSM's range), R32UI (the z
// SATs), RGBA32UI (CSSM_SAT's bases); filtered: RGBA16F (CSSM's mipmapped bases); a textureGather
// counts one -- and direct/light.frag adds them to a buffer once per pixel. Never in the kiosk's
// frames.
#ifdef SHADOW_COUNT_FETCHES
struct gk_shadow_counts {
    highp uint depth, r32f, r32ui, rgba32ui, rgba16f;
};
gk_shadow_counts gk_shadow_fetches = gk_shadow_counts(0u, 0u, 0u, 0u, 0u);
#define GK_SHADOW_COUNT(kind, n) gk_shadow_fetches.kind += uint(n)
#else
#define GK_SHADOW_COUNT(kind, n)
#endif

// Linear depth of the nearest occluder stored at uv (clamped to the map).
highp float gk_shadow_fetch(highp vec2 uv, highp float layer)
{
    GK_SHADOW_COUNT(depth, 1);
    return gk_shadow_linear(texture(u_shadow_map, vec3(clamp(uv, 0.0, 1.0), layer)).r);
}

// Receiver offset along the normal by 1.5 texels (normal-offset bias): removes acne on slopes
// without peter-panning contact shadows as a large constant bias would.
highp vec3 gk_shadow_offset(highp vec3 p, highp vec3 n)
{
    gk_shadow_coord c = gk_shadow_project(p);
    return p + n * (1.5 * gk_shadow_texel_world(max(c.d, u_shadow_proj.x)));
}

// Per-pixel hash in [0,1) (interleaved gradient noise): rotates sample grids so banding becomes
// fine noise.
highp float gk_shadow_noise()
{
    return fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
}

// Receiver-plane depth bias (Isidoro 2006): the receiver's linear depth at uv + offset, taking
// the receiver as its tangent plane, to first order: d + dot(gradient, offset). Without it a
// wide PCSS kernel on a surface inclined to the map (walls parallel to the light's axis) finds
// the receiver itself in front of its own depth and darkens it.
highp float gk_shadow_plane_depth(highp vec2 uv, int f, highp vec3 p, highp vec3 n, highp vec3 axis, highp float fallback)
{
    highp vec4 a = u_shadow_inv_viewproj[f] * vec4(uv * 2.0 - 1.0, -1.0, 1.0);
    highp vec4 b = u_shadow_inv_viewproj[f] * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
    highp vec3 p0 = a.xyz / a.w, p1 = b.xyz / b.w;
    highp float denom = dot(n, p1 - p0);
    if (abs(denom) < 1e-6)
        return fallback;
    highp vec3 x = p0 + (p1 - p0) * (dot(n, p - p0) / denom);
    return dot(x - u_shadow_pos, axis);
}

highp vec2 gk_shadow_receiver_gradient(gk_shadow_coord c, highp vec3 p, highp vec3 n)
{
    int f = int(c.layer);
    highp vec3 axis = u_shadow_proj.w > 1.5 ? gk_cube_axis(f) : u_shadow_axis;
    highp float e = 1.0 / u_shadow_light.w;
    highp float du = gk_shadow_plane_depth(c.uv + vec2(e, 0.0), f, p, n, axis, c.d) - c.d;
    highp float dv = gk_shadow_plane_depth(c.uv + vec2(0.0, e), f, p, n, axis, c.d) - c.d;
    // Near-grazing planes give huge slopes; they receive almost no light (cos ~ 0) anyway.
    return clamp(vec2(du, dv) / e, vec2(-100.0 * c.d), vec2(100.0 * c.d));
}
