// One LGV gathering iteration, eq. (6) (seed 002 §4.2 after Kaplanyan & Dachsbacher [17]; research
// B.2.5): every destination cell D gathers from its 6 axis neighbours S_i, through each of D's 5
// faces f_j a neighbour sees (not the shared one), the flux Phi = dw(S_i -> f_j) I_S(dir) G, dir from
// S_i's centre to the face's centre, dw = 0.4006696846 sr for the far face, 0.4234413544 sr for a
// side face; D takes (1/pi) Phi as a clamped cosine lobe along the face's normal. G, the fuzzy
// occlusion, is the transmittance of the face S_i and D share: 1 - its opacity (clamped to [0, 1]),
// the mean of the geometry volume's projected areas along the link's axis at the face's 4 corners
// (lgv_geometry.comp; u_occlusion = 0: G = 1, the leak the tests compare against). The iterations
// accumulate (LPV practice): acc += dst.
precision highp float;
precision highp int;
layout(local_size_x = 64) in;
#include "lgv/common.glsl"
layout(std430, binding = 5) readonly buffer Src { highp float src[]; };
layout(std430, binding = 6) buffer Acc { highp float acc[]; };
layout(std430, binding = 7) writeonly buffer Dst { highp float dst[]; };
layout(std430, binding = 4) readonly buffer Geo { highp uint geo[]; }; // 3 per corner: x, y, z
uniform ivec3 u_dims;
uniform int u_occlusion;
uniform float u_geo_fixed;    // fixed-point units per unit of opacity

// G between neighbours s and d, linked along axis a: the face they share lies at corner index
// max(s, d) along a and spans corners d .. d + 1 along the other two axes. A corner on the grid's
// bounds gathers surfels from half a cell along that axis (the other half lies outside the scene),
// so the face's opacity is the corners' projected area over the area they cover: a wall that fills
// a face at the floor is opaque there too (the plain mean of the 4 corners gave such faces 1/2).
highp float transmittance(ivec3 s, ivec3 d, int a)
{
    if (u_occlusion == 0)
        return 1.0;
    ivec3 gd = u_dims + 1;
    ivec3 c = d;
    c[a] = max(s[a], d[a]);
    int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
    highp float sum = 0.0, covered = 0.0;
    for (int k = 0; k < 4; k++) {
        ivec3 g = c;
        g[a1] += k & 1;
        g[a2] += k >> 1;
        highp float w1 = (g[a1] == 0 || g[a1] == u_dims[a1]) ? 0.5 : 1.0;
        highp float w2 = (g[a2] == 0 || g[a2] == u_dims[a2]) ? 0.5 : 1.0;
        sum += float(geo[3 * ((g.z * gd.y + g.y) * gd.x + g.x) + a]);
        covered += w1 * w2;
    }
    return 1.0 - clamp(sum / (covered * u_geo_fixed), 0.0, 1.0);
}

const ivec3 AXES[6] = ivec3[6](ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0), ivec3(0, 0, 1),
                               ivec3(0, 0, -1));
void main()
{
    int cell = int(gl_GlobalInvocationID.x);
    int n = u_dims.x * u_dims.y * u_dims.z;
    if (cell >= n)
        return;
    ivec3 d = ivec3(cell % u_dims.x, (cell / u_dims.x) % u_dims.y, cell / (u_dims.x * u_dims.y));
    vec4 out_c[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
    for (int i = 0; i < 6; i++) {
        ivec3 s = d - AXES[i]; // the neighbour that sends along +AXES[i]
        if (any(lessThan(s, ivec3(0))) || any(greaterThanEqual(s, u_dims)))
            continue;
        int sb = 12 * ((s.z * u_dims.y + s.y) * u_dims.x + s.x);
        vec4 cs[3] = vec4[3](vec4(src[sb], src[sb + 1], src[sb + 2], src[sb + 3]),
                             vec4(src[sb + 4], src[sb + 5], src[sb + 6], src[sb + 7]),
                             vec4(src[sb + 8], src[sb + 9], src[sb + 10], src[sb + 11]));
        highp float g = transmittance(s, d, i / 2);
        if (g <= 0.0)
            continue;
        vec3 delta = vec3(AXES[i]);
        for (int j = 0; j < 6; j++) {
            vec3 nu = vec3(AXES[j]);
            if (dot(nu, delta) < -0.5)
                continue; // the shared face
            bool far_face = dot(nu, delta) > 0.5;
            vec3 dir = normalize(delta + 0.5 * nu);
            float dw = far_face ? 0.4006696846 : 0.4234413544;
            vec4 y = lgv_sh(dir);
            vec4 lobe = vec4(0.886227, -1.023327 * nu.y, 1.023327 * nu.z, -1.023327 * nu.x);
            for (int ch = 0; ch < 3; ch++)
                out_c[ch] += (g * dw / 3.14159265) * max(dot(cs[ch], y), 0.0) * lobe;
        }
    }
    int b = 12 * cell;
    for (int ch = 0; ch < 3; ch++)
        for (int k = 0; k < 4; k++) {
            dst[b + 4 * ch + k] = out_c[ch][k];
            acc[b + 4 * ch + k] += out_c[ch][k];
        }
}
