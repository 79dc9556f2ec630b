// Shared declarations of the ispm passes (seed 000 §3.3; photon-mapping-000-004.md A.1.9–A.1.12,
// Appendix D). Buffer layouts are std430 and mirrored in app/gi/ispm/ispm_internal.h.
//
// Node   : one camera-frustum fragment of a per-pixel list (Algorithm 3.4's FragmentNode, 12 bytes):
//          linear view depth, geometric normal as half-float spherical (θ, φ), next node (-1 = end).
// Pixel  : a list head plus the list's min/max depth (float bits; depth > 0 so uint order = float
//          order) and its length (the L8 test reads it).
// Photon : first hit on a specular RSM texel after reflection: origin (w = 1 valid, 0 absorbed),
//          direction, reflected power (w = light→reflector distance).
// Hit    : the photon's second hit: position (w = 1 valid), receiver normal (w = splat radius h),
//          power (w = total path length light→reflector→receiver).
struct Node { highp float depth; highp uint nrm; highp int next; };
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
