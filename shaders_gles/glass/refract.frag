// Transmissive surfaces (KHR_materials_transmission + KHR_materials_ior) in the real-time image:
// the opaque scene, lit and with its GI, is already in u_behind; a glass surface shows it refracted
// by a screen-space lookup. The view ray is bent by Snell's law at the surface (refract, eta =
// 1/ior, the normal facing the viewer) and followed as far as the opaque surface behind the pixel
// lies (its depth from the G-buffer); that point, projected back to the screen, is what the pixel
// shows, times (1 - F) (Schlick with F0 = ((ior-1)/(ior+1))^2) and the base colour tint. It is one
// refraction, not the two of a solid (the exit face is not known in screen space), and the
// reflected share F is left out (no environment to reflect): a plausible lens, not the reference's
// glass. Pixels whose lookup leaves the screen fall back to the unbent pixel behind.
// GLASS_COUNT_FETCHES: the bench's counting variant (#21, app/render/render_work.c), per fragment
// its depth read and, in front of the opaque scene, its two lookups of the image behind (with the
// atomics the depth test runs after the shader: hidden fragments count too); fragment-stage storage
// buffers capability-checked by the caller. Never in the kiosk's frames.
// @variant -
// @variant GLASS_COUNT_FETCHES
precision highp float;
#ifdef GLASS_COUNT_FETCHES
layout(std430, binding = 6) buffer GlassFetches { highp uint depth; highp uint behind; } glass_counted;
#endif
in vec3 v_world;
in vec3 v_normal;
in vec2 v_uv;
uniform highp sampler2D u_behind;   // lit opaque scene, RGBA16F, render size
uniform highp sampler2D u_depth;    // G-buffer depth of the opaque scene
uniform mat4 u_viewproj;
uniform mat4 u_inv_viewproj;
uniform vec3 u_eye;
uniform vec4 u_base_color;
uniform vec2 u_glass;               // ior, transmission
uniform vec2 u_size;                // render size in pixels
layout(location = 0) out vec4 o_color;

vec3 world_at(vec2 uv, float depth)
{
    vec4 p = u_inv_viewproj * vec4(vec3(uv, depth) * 2.0 - 1.0, 1.0);
    return p.xyz / p.w;
}

void main()
{
    vec2 uv = gl_FragCoord.xy / u_size;
    float behind_depth = texture(u_depth, uv).r;
#ifdef GLASS_COUNT_FETCHES
    atomicAdd(glass_counted.depth, 1u);
#endif
    if (gl_FragCoord.z >= behind_depth)
        discard; // the opaque scene is in front of this glass
#ifdef GLASS_COUNT_FETCHES
    atomicAdd(glass_counted.behind, 2u); // seen and unbent, below
#endif
    vec3 v = normalize(v_world - u_eye);
    vec3 n = normalize(v_normal);
    if (dot(n, v) > 0.0)
        n = -n;
    float ior = max(u_glass.x, 1.0);
    vec3 t = refract(v, n, 1.0 / ior);
    float along = length(world_at(uv, behind_depth) - v_world);
    vec4 clip = u_viewproj * vec4(v_world + t * along, 1.0);
    vec2 bent = clip.xy / clip.w * 0.5 + 0.5;
    if (clip.w <= 0.0 || any(lessThan(bent, vec2(0.0))) || any(greaterThan(bent, vec2(1.0))))
        bent = uv;
    float r0 = (ior - 1.0) / (ior + 1.0);
    float f = r0 * r0 + (1.0 - r0 * r0) * pow(1.0 - clamp(-dot(v, n), 0.0, 1.0), 5.0);
    vec3 seen = texture(u_behind, bent).rgb;
    vec3 unbent = texture(u_behind, uv).rgb;
    // The transmitted share passes through the glass; an only partly transmissive material keeps
    // the rest of the unbent background (its opaque part is not shaded here).
    vec3 c = u_glass.y * (1.0 - f) * u_base_color.rgb * seen + (1.0 - u_glass.y) * unbent;
    o_color = vec4(c, 1.0);
}
