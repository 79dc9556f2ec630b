// VPL generation (thesis §6.5 step 3): VPL i point-samples the RSM atlas at Halton position i
// (bases 2, 3); one output texel per VPL. Flux and area carry the Monte-Carlo weight
// u_weight = atlas texels / VPLs of this light. u_rotation ≠ 0 only for the F8 oracle (random
// pattern per frame, Cranley–Patterson rotation).
precision highp float;
precision highp int;
uniform highp sampler2D u_rsm_pos;
uniform highp sampler2D u_rsm_nrm;
uniform highp sampler2D u_rsm_flux;
uniform ivec2 u_atlas_size;
uniform int u_first;
uniform float u_weight;
uniform vec2 u_rotation;
layout(location = 0) out vec4 o_pos;
layout(location = 1) out vec4 o_nrm;
layout(location = 2) out vec4 o_flux;

float halton(int i, int base)
{
    float f = 1.0, r = 0.0;
    while (i > 0) {
        f /= float(base);
        r += f * float(i % base);
        i /= base;
    }
    return r;
}

void main()
{
    int i = int(gl_FragCoord.x) - u_first + 1;   // index 0 would be the corner (0, 0)
    vec2 h = fract(vec2(halton(i, 2), halton(i, 3)) + u_rotation);
    ivec2 px = min(ivec2(h * vec2(u_atlas_size)), u_atlas_size - 1);
    vec4 p = texelFetch(u_rsm_pos, px, 0);
    o_pos = vec4(p.xyz, p.w * u_weight);
    o_nrm = vec4(texelFetch(u_rsm_nrm, px, 0).xyz, 0.0);
    o_flux = vec4(texelFetch(u_rsm_flux, px, 0).rgb * u_weight, 1.0);
}
