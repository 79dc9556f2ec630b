// Shared declarations of the lgv passes (seed 002, vct-003-grid-photon-002.md Part B). Layouts are
// std430 and mirrored in app/gi/lgv/lgv_internal.h.
//
// Distance cube-maps: 2D array textures of 6 layers per map (layer = 6 * map + face; maps: the
// lattice's, then the refractor maps, then the refractors' exit maps, lgv_maps.c), face f looks
// along axis f / 2 with sign + for even f; its image plane coordinates are (u, v) = (dot(d, U_f),
// dot(d, V_f)) / dot(d, W_f) in [-1, 1] (a 90-degree perspective), texel ((u, v) * 0.5 + 0.5) * res.
// The same mapping renders (cubemap.vert) and reads (lgv_texel), so no cube-map seam filtering is
// involved (research B.6). Per texel: distance from the map's centre (R32UI float bits; cleared to
// LGV_FAR: nothing), normal (RGBA8, n * 0.5 + 0.5) and base colour + material code (RGBA8):
//   code 0 diffuse; 1 mirror (metallic > 0.5, roughness < 0.2); 128 + 32 r + q glass of refractor
//   map r (0..3) and ior 1 + 0.05 q (q 0..31).
// The distance mips are min-reductions (mip_min.comp), never averages.
#define LGV_FAR 1.0e30

highp vec3 lgv_face_w(int f)
{
    int a = f / 2;
    float s = (f % 2 == 0) ? 1.0 : -1.0;
    return a == 0 ? vec3(s, 0.0, 0.0) : (a == 1 ? vec3(0.0, s, 0.0) : vec3(0.0, 0.0, s));
}
highp vec3 lgv_face_u(int f)
{
    int a = f / 2;
    return a == 0 ? vec3(0.0, 0.0, 1.0) : (a == 1 ? vec3(1.0, 0.0, 0.0) : vec3(1.0, 0.0, 0.0));
}
highp vec3 lgv_face_v(int f)
{
    int a = f / 2;
    return a == 0 ? vec3(0.0, 1.0, 0.0) : (a == 1 ? vec3(0.0, 0.0, 1.0) : vec3(0.0, 1.0, 0.0));
}

// Face and image-plane coordinates (in [-1, 1]) of direction d.
int lgv_face_of(highp vec3 d, out highp vec2 uv)
{
    highp vec3 a = abs(d);
    int f;
    if (a.x >= a.y && a.x >= a.z)
        f = d.x >= 0.0 ? 0 : 1;
    else if (a.y >= a.z)
        f = d.y >= 0.0 ? 2 : 3;
    else
        f = d.z >= 0.0 ? 4 : 5;
    highp float w = dot(d, lgv_face_w(f));
    uv = vec2(dot(d, lgv_face_u(f)), dot(d, lgv_face_v(f))) / w;
    return f;
}

// Real SH, 2 bands (research B.2.4; the same order and signs everywhere).
highp vec4 lgv_sh(highp vec3 w) { return vec4(0.282095, -0.488603 * w.y, 0.488603 * w.z, -0.488603 * w.x); }

// PCG hash (O'Neill's pcg32 output on a hashed state): reproducible per photon and frame.
highp uint lgv_pcg(highp uint v)
{
    highp uint state = v * 747796405u + 2891336453u;
    highp uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
