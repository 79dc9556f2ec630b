// Per-pixel linked lists (Algorithm 3.4; research Appendix D.1), tier A: every fragment in the
// camera frustum, depth test and culling off, appended with SSBO atomics. Needs fragment-stage
// storage blocks, which GLES 3.1 does not guarantee (ispm_lists.c probes for them). Nodes keep the
// geometric normal as authored (not face-forward): the trace's self-intersection rule needs it;
// and a mirror's reflectance and shape operator, for the trace's further bounces.
// A full pool drops the fragment and counts it (research L11).
precision highp float;
precision highp int;
#include "ispm/common.glsl"
#include "ispm/shape.glsl"
layout(std430, binding = 0) writeonly buffer Nodes { Node nodes[]; };
layout(std430, binding = 1) buffer Pixels { Pixel px[]; };
layout(std430, binding = 2) buffer Counter { uint ll_count; uint ll_capacity; uint ll_overflow; uint ll_pad; };
uniform int u_width;
uniform mat4 u_model;                 // the draw_scene contract (gi.h): used by ll_build.vert
uniform vec4 u_base_color;
uniform vec2 u_metallic_roughness;
uniform vec4 u_specular;                // the draw_scene contract (gi.h)
uniform vec3 u_emissive;
uniform int u_mat_flags;
in vec3 v_normal;
in vec3 v_world;
layout(location = 0) out vec4 o_unused;   // colour writes are masked; declared for completeness

const int MAT_LIGHT_PROXY = 4;

void main()
{
    vec3 n = normalize(v_normal);
    uint shape = ispm_shape_operator(v_world, n);   // derivatives: before any discard
    if ((u_mat_flags & MAT_LIGHT_PROXY) != 0)
        discard;   // the path tracer does not see light proxies; neither do photons
    ivec2 p = ivec2(gl_FragCoord.xy);
    int pix = p.y * u_width + p.x;
    float z = 1.0 / gl_FragCoord.w;   // linear view depth
    uint idx = atomicAdd(ll_count, 1u);
    if (idx >= ll_capacity) {
        atomicAdd(ll_overflow, 1u);
        discard;
    }
    nodes[idx].depth = z;
    nodes[idx].nrm = ispm_encode_normal(n);
    nodes[idx].shape = shape;
    nodes[idx].spec = ispm_node_spec(u_base_color, u_metallic_roughness, u_specular);
    nodes[idx].next = atomicExchange(px[pix].head, int(idx));
    uint zb = floatBitsToUint(z);
    atomicMin(px[pix].zmin, zb);
    atomicMax(px[pix].zmax, zb);
    atomicAdd(px[pix].count, 1u);
    o_unused = vec4(0.0);
}
