// Shared declarations of the ispm passes (seed 000 §3.3; photon-mapping-000-004.md A.1.9–A.1.12,
// Appendix D). Buffer layouts are std430 and mirrored in app/gi/ispm/ispm_internal.h.
//
// Node   : one camera-frustum fragment of a per-pixel list (Algorithm 3.4's FragmentNode, 12 bytes,
//          plus 4): linear view depth, geometric normal as half-float spherical (θ, φ), next node
//          (-1 = end), and the surface's mirror reflectance (packUnorm4x8: rgb = specular albedo,
//          a = roughness; 0 on surfaces that are not mirrors), which the trace's further specular
//          bounces need (ispm_bounces > 1; the seed's single bounce reads only the first three),
//          then the surface's shape operator (shape.glsl: how the normal turns across the surface,
//          ispm_pack_shape), which those bounces need to reflect at the hit, not at the pixel centre.
// Pixel  : a list head plus the list's min/max depth (float bits; depth > 0 so uint order = float
//          order) and its length (the L8 test reads it).
// Photon : first hit on a specular RSM texel after reflection: origin (w = 1 valid, 0 absorbed),
//          direction (w = the photon's random-number key as a float, exact below 2^24: its RSM block or slot),
//          reflected power (w = light→reflector distance).
// Hit    : the photon's last hit (the second with the seed's one bounce): position (w = the specular
//          bounces on its path, 1 with the seed's, 0 = no hit; footprint.comp pairs only hits
//          with as many), receiver normal (w = splat radius h), power (w = total path length light→…→receiver).
struct Node { highp float depth; highp uint nrm; highp int next; highp uint spec; highp uint shape; };
struct Pixel { highp int head; highp uint zmin; highp uint zmax; highp uint count; };
struct Photon { highp vec4 org; highp vec4 dir; highp vec4 pow_d1; };
struct Hit { highp vec4 pos_valid; highp vec4 nrm_h; highp vec4 pow_dist; };

// Header of the photon buffer (ispm_internal.h ISPM_PH_*): filled by mask.comp, emit.comp and
// trace.comp, read back for the statistics.
#define ISPM_PHOTON_HEADER                                                                          \
    highp uint ph_count;        /* first hits written (slots used) */                               \
    highp uint ph_level;        /* mip level l of the specular mask the photons were taken at */    \
    highp uint ph_overflow;     /* photons dropped: the buffer was full */                          \
    highp uint ph_top;          /* M: specular RSM texels (top of the count pyramid) */             \
    highp uint ph_nonzero[16];  /* blocks holding a specular texel, per level */                    \
    highp uint ph_hits;         /* second hits the trace found */                                   \
    highp uint ph_reflected;    /* photons that survived Russian roulette and the lobe */           \
    highp uint ph_steps;        /* march steps + list nodes visited (the trace's work, L19) */     \
    highp uint ph_pad1;

// Normals as the seed stores them: spherical (θ, φ) in two halves.
highp uint ispm_encode_normal(highp vec3 n)
{
    return packHalf2x16(vec2(acos(clamp(n.z, -1.0, 1.0)), atan(n.y, n.x)));
}

highp vec3 ispm_decode_normal(highp uint h)
{
    highp vec2 s = unpackHalf2x16(h);
    return vec3(sin(s.x) * cos(s.y), sin(s.x) * sin(s.y), cos(s.x));
}

// A tangent frame (t, b) of the unit normal n, the same wherever n is the same: the frame the shape
// operator is stored in (shape.glsl).
void ispm_tangent_frame(highp vec3 n, out highp vec3 t, out highp vec3 b)
{
    t = normalize(abs(n.y) < 0.999 ? cross(vec3(0.0, 1.0, 0.0), n) : cross(vec3(1.0, 0.0, 0.0), n));
    b = cross(n, t);
}

// A shape operator in one uint, so that a peeled layer's spare channel holds it as a list node does:
// its symmetric part (a surface's shape operator is self-adjoint in an orthonormal frame; the mesh's
// interpolated normals nearly so) as three snorm8 entries over a shared power-of-two scale (top byte,
// biased by 128; 0 = flat). 1/127 of the largest entry is plenty for a first-order correction.
highp uint ispm_pack_shape(highp mat2 S)
{
    highp vec3 v = vec3(S[0][0], 0.5 * (S[0][1] + S[1][0]), S[1][1]);
    highp float m = max(abs(v.x), max(abs(v.y), abs(v.z)));
    if (!(m > 1e-20) || m > 1e20)
        return 0u;   // flat, or not a number
    highp int e = int(ceil(log2(m)));
    return (packSnorm4x8(vec4(v * exp2(float(-e)), 0.0)) & 0x00ffffffu) | (uint(e + 128) << 24);
}

highp mat2 ispm_unpack_shape(highp uint u)
{
    if (u == 0u)
        return mat2(0.0);
    highp vec3 v = unpackSnorm4x8(u).xyz * exp2(float(int(u >> 24) - 128));
    return mat2(v.x, v.y, v.y, v.z);
}

// The shading normal at a point dp (world) from a node's point, on the surface of the node's normal
// n and packed shape operator: n turned by the operator (clamped: it is a first-order model).
highp vec3 ispm_normal_at(highp vec3 n, highp uint shape, highp vec3 dp)
{
    highp vec3 t, b;
    ispm_tangent_frame(n, t, b);
    highp vec2 dn = ispm_unpack_shape(shape) * vec2(dot(dp, t), dot(dp, b));
    highp float len = length(dn);
    if (len > 0.5)
        dn *= 0.5 / len;
    return normalize(n + dn.x * t + dn.y * b);
}

// The seed's "pre-generated random numbers, the same every frame": a fixed hash (PCG) of a key,
// which is a random texture indexed by key without the texture.
highp uint ispm_hash(highp uint v)
{
    highp uint s = v * 747796405u + 2891336453u;
    highp uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (w >> 22u) ^ w;
}

highp float ispm_random(highp uint key, highp uint k)
{
    return float(ispm_hash(ispm_hash(key) ^ (k * 0x9E3779B9u)) >> 8u) * (1.0 / 16777216.0);
}

// The specular albedo s of a material and whether it reflects photons (a "specular" surface of the
// scene features, app/scene/features.c: metallic > 0.5, roughness < 0.2). fresnel_mix at normal
// incidence (app/core/brdf_spec.md, glTF Appendix B with KHR_materials_specular): the dielectric's
// F0 = specularFactor · min(c0, 1), the metal's the base colour. Shared by rsm.frag (the first
// bounce) and the lists (further bounces), so both bounce off the same mirror.
highp vec3 ispm_specular_albedo(highp vec3 base, highp float metallic, highp vec4 specular)
{
    return mix(clamp(specular.a, 0.0, 1.0) * min(specular.rgb, vec3(1.0)), base, metallic);
}

bool ispm_is_specular(highp float metallic, highp float rough)
{
    return metallic > 0.5 && rough < 0.2;
}

// A reflected direction about the mirror direction rm: the Phong lobe with the corrected sampling
// θ = arccos(ξ^{1/(α+1)}) (errata A.7 item 1) in the frame of Algorithm 3.3, Phong exponent from
// roughness (Blinn-Phong ↔ GGX: α = 2/r⁴ − 2); roughness ≤ 0.01 is a mirror. Random numbers k0, k0+1
// of key.
highp vec3 ispm_phong_lobe(highp vec3 rm, highp float rough, highp uint key, highp uint k0)
{
    if (rough <= 0.01)
        return rm;
    highp float alpha = min(2.0 / (rough * rough * rough * rough) - 2.0, 1.0e6);
    highp float cosT = pow(ispm_random(key, k0), 1.0 / (alpha + 1.0));
    highp float sinT = sqrt(max(0.0, 1.0 - cosT * cosT));
    highp float phi = 6.28318531 * ispm_random(key, k0 + 1u);
    highp vec3 ox, oy;
    if (abs(rm.y) > 1.0 - 1e-6) {           // Algorithm 3.3: Oz' parallel to Oy
        ox = vec3(1.0, 0.0, 0.0);
        oy = vec3(0.0, 0.0, -1.0);
    } else {
        ox = normalize(cross(vec3(0.0, 1.0, 0.0), rm));
        oy = cross(rm, ox);
    }
    return normalize(ox * (sinT * cos(phi)) + oy * (sinT * sin(phi)) + rm * cosT);
}

// Node.spec of a surface: its specular albedo and roughness packed, 0 when it is not a mirror.
highp uint ispm_node_spec(highp vec4 base_color, highp vec2 metallic_roughness, highp vec4 specular)
{
    highp float metallic = clamp(metallic_roughness.x, 0.0, 1.0), rough = clamp(metallic_roughness.y, 0.0, 1.0);
    if (!ispm_is_specular(metallic, rough))
        return 0u;
    return max(packUnorm4x8(vec4(ispm_specular_albedo(base_color.rgb, metallic, specular), rough)), 1u);
}
